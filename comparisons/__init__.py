"""The comparison layer: the only package that imports both roads.

`python -m comparisons point|sweep|report|crosscheck|bench|suite|verify|mastercurve` (see
`cli/`): the cross-validation report, convergence studies, benchmarks (`bench/`), the certified
benchmark suite, the verification of another code's results and a third code driven as a peer
(`peers/`).
Operating points cross between the roads as plain dimensionless numbers (units, signs and keys of
`docs/conventions.md`), never as shared objects: the `operating_point.OperatingPoint` stays on
this side, and `roads` hands each road its own keywords.

Where each job lives (a module imports only its own line and the lines below it):

- ``cli/``, ``__main__``: the command line, one module per subcommand (``cli.SUBCOMMANDS``);
  options in, exit status out; no logic of its own beyond the options.
- ``verify/``, ``suite`` (with ``suite_cases``, ``suite_compute``, ``suite_surfaces``,
  ``suite_inputs``, ``suite_export``), ``report`` (with ``report_doc``, ``report_layers``,
  ``report_numbers``, ``report_specs``, ``report_runs``, ``report_surfaces``), ``crosscheck``,
  ``mastercurve``, ``points`` (with ``sweep_outputs``, a sweep's table and picture): the jobs a
  user runs.
- ``plots/``: every figure, and the only importer of matplotlib.
- ``runner``, ``_materials``, ``_material_options``, ``gate``, ``store``, ``_cluster``: an
  operating point from the options to a checked record, its material (and the flags that read
  it), its last line of defence, its stored result, and where it runs.
- ``roads``, ``peers/``: the adapter to ``bem`` and ``analytic``, the only module that calls
  them, and the third codes run as witnesses.
- ``operating_point``: the one frozen operating point every door builds (its defaults, the
  refusal of options that do not apply, SI input made dimensionless, the table from each
  parameter to its option and keyword); it calls no road.
- ``convergence`` (order, Richardson, certified digits), ``fields`` (patches and sampled
  fields), ``_io`` (the atomic UTF-8 writer and the readers), ``_errors`` (what a command
  reports), ``_html``, ``progress`` (the throttled progress line): shared by all of the above.

Beside these, ``bench/`` holds the benchmarks that print figures: it times the roads themselves
and may use any job; only the command line's ``bench`` imports it.

References
----------
N. Menga, C. Putignano, G. Carbone and G. P. Demelio, The sliding contact of a rigid wavy surface
with a viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014), doi:10.1098/rspa.2014.0392.
"""
