"""`python -m comparisons verify`: another code's results in, a verdict and a report out.

    python -m comparisons verify (--case NAME | (--load P | --penetration D) --speed S
                                  [--ratio R] [--hk H] [--profile F] [--prony F])
                                 (--fields F.csv|F.npz [...] | --scalars F.jsonl |
                                  --callable MODULE:FUNCTION [--nodes N ...] |
                                  --peer tamaas [--nodes N ...] [--dt-cells C ... | --dt T])
                                 [--rtol R] [--tol NAME=VALUE ...] [--units SI --E0 ... ]
                                 [--out DIR] [--label TEXT] [--no-figures]

One module per step, each documenting its part of the method (`docs/cli.md` for the user):

- ``_inputs``: reading the JSON lines of scalars and the callable (the fields CSV:
  `comparisons.fields.read_fields_csv`); bad input;
- ``_point``: the operating point (a suite case, a dict or the options), checked;
- ``_scalars`` and ``_edges``: scalars and contact patches from fields, and verify's own fit of
  the contact edges;
- ``_reference``: the reference (the semi-analytic road where it applies, else the BEM);
- ``_results``: the results of the solver under test (fields, scalars, a callable, a peer);
- ``_quantities``: what is compared and how each difference is measured;
- ``_tolerances``, ``_compare``, ``_diagnose``, ``_study``: the tolerance of each quantity and
  why, the verdict with its floors, the slips the inputs look like, the convergence study;
- ``_report``: report.md, report.html, verdict.json and the figures
  (`comparisons.plots.verify` draws them);
- ``_api``: `assert_agrees`; ``_command``: the command (`run`);
- on a surface case of the suite (a rigid periodic surface, 2-D fields): ``_surface_fields``
  (the ``.npz`` of the conventions, a callable's output, the scalars derived from them),
  ``_surface_reference`` (the case's certified values and fields, what is compared, the
  tolerances from the surface BEM's error on the same grid), ``_surface_judge`` (the verdict,
  the convergence study, the slips) and ``_surface_report``.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (eq. 3.1 for the
friction; the problem and the semi-analytic road).
"""
from __future__ import annotations

from ._api import assert_agrees
from ._command import DEFAULT_NODES, DEFAULT_PEER_NODES, MESSAGE_LIMIT, run
from ._compare import POSITION_PANELS, derivation_floor, evaluate, position_floor
from ._diagnose import MIRRORED, SLIP_GAIN, diagnose
from ._edges import EDGE_DEGREE, EDGE_HOLDS, EDGE_PASSES, EDGE_STILL, edge_offset
from ._inputs import SCALARS_ALLOWED, load_callable, read_scalars_jsonl
from ._point import check_point, point_from_case
from ._quantities import ABS, ALL_KEYS, COMPARED_KEYS, LABELS, NORM_KEYS, REL, norms
from ._reference import REFERENCE_MIN_NODES, Reference, reference_for
from ._report import SCALARS_FROM_FIELDS, markdown, write_report
from ._results import (DEFAULT_DT_CELLS, Result, SurfaceOutput, peer_tamaas,
                       results_from_fields, to_conventions, viscosine_bem)
from ._scalars import CONTACT, scalars_from_fields
from ._study import ORDER_FLOOR, convergence, fit_order
from ._surface_reference import SURFACE_DEFAULT_NODES, SURFACE_KEYS
from ._tolerances import (DEFAULT_RTOL, FIELD_LAW, GRID_FACTOR, GRID_MAX_NODES,
                          MEASURED_FIELD_CONSTANTS, field_constants, field_tolerance,
                          grid_errors, grid_size, tolerances)

__all__ = [
    "ABS", "ALL_KEYS", "COMPARED_KEYS", "CONTACT", "DEFAULT_DT_CELLS", "DEFAULT_NODES",
    "DEFAULT_PEER_NODES", "DEFAULT_RTOL", "EDGE_DEGREE", "EDGE_HOLDS", "EDGE_PASSES",
    "EDGE_STILL", "FIELD_LAW", "GRID_FACTOR", "GRID_MAX_NODES", "LABELS",
    "MEASURED_FIELD_CONSTANTS", "MESSAGE_LIMIT", "MIRRORED", "NORM_KEYS", "ORDER_FLOOR",
    "POSITION_PANELS", "REFERENCE_MIN_NODES", "REL", "SCALARS_ALLOWED", "SCALARS_FROM_FIELDS",
    "SLIP_GAIN", "SURFACE_DEFAULT_NODES", "SURFACE_KEYS", "Reference", "Result",
    "SurfaceOutput", "assert_agrees", "check_point", "convergence",
    "derivation_floor", "diagnose", "edge_offset", "evaluate", "field_constants",
    "field_tolerance", "fit_order", "grid_errors", "grid_size", "load_callable", "markdown",
    "norms", "peer_tamaas", "point_from_case", "position_floor", "read_scalars_jsonl",
    "reference_for", "results_from_fields", "run", "scalars_from_fields", "to_conventions",
    "tolerances", "viscosine_bem", "write_report",
]
