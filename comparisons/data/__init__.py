"""Data shipped with :mod:`comparisons` (a package only so that the files are installed with it)."""
