"""The comparison layer: the only package that imports both roads.

`python -m comparisons point|sweep|report|crosscheck|bench|suite|verify|mastercurve` (see
`cli/`): the cross-validation report, convergence studies, benchmarks (`bench/`), the certified
benchmark suite, the verification of another code's results and a third code driven as a peer
(`peers/`).
Operating points cross between the roads as plain dimensionless numbers (units, signs and keys of
`docs/conventions.md`), never as shared objects.

References
----------
N. Menga, C. Putignano, G. Carbone and G. P. Demelio, The sliding contact of a rigid wavy surface
with a viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014), doi:10.1098/rspa.2014.0392.
"""
