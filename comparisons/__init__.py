"""The comparison layer: the only package that imports both roads.

`python -m comparisons point|sweep|report|bench` (see `cli.py`); cross-validation report,
convergence studies and benchmarks.  Operating points cross between the roads as plain
dimensionless numbers (`conventions.md`), never as shared objects.
"""
