"""Helpers on sampled fields the comparison layer shares (verify's reading of another code's
fields, the Tamaas peer's measuring of its own).  The roads keep their own: bem and analytic
share nothing but `viscosine`.
"""
from __future__ import annotations

import numpy as np


def true_runs(mask) -> list:
    """The maximal runs of True in a periodic boolean array, as ``[(first index, length), ...]``.

    A run may wrap past the end of the array (its first index is then near the end); the whole
    array True is one run ``(0, n)``, none True is ``[]``.  Runs are listed from the one after
    the first False entry, in order around the period.
    """
    mask = np.asarray(mask, dtype=bool)
    n = mask.size
    if mask.all():
        return [(0, n)]
    if not mask.any():
        return []
    start = int(np.argmin(mask))  # the first False entry: no run wraps past it
    d = np.diff(np.concatenate(([0], np.roll(mask, -start).astype(np.int8), [0])))
    firsts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    return [((int(f) + start) % n, int(e - f)) for f, e in zip(firsts, ends)]
