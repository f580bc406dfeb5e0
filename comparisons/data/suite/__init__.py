"""The benchmark suite's data: ``suite.json``, ``materials/``, ``profiles/``, ``fields/``
(read by :mod:`comparisons.suite`)."""
