"""Convergence in one place: the observed order of a mesh study and the Richardson step.

Every study of the project (the report's, `verify`'s, the suite's certification, the BEM
benchmark) fits its order and extrapolates with these two functions; each keeps its own rule
for which meshes and errors enter (its floor), and says so where it calls them.
"""
from __future__ import annotations

import math

import numpy as np


def observed_order(nodes, errors, floor=0.0) -> float:
    """Order p of ``err ∝ N^-p``: the least-squares slope of log err against log N over the
    finite errors above ``floor`` (NaN when fewer than two remain).  Single steps scatter with
    where a contact edge falls inside its panel; a fit over several doublings is what means
    something."""
    n = np.asarray(nodes, float)
    e = np.asarray([np.nan if v is None else v for v in errors], float)
    ok = np.isfinite(e) & (e > floor)
    if ok.sum() < 2:
        return float("nan")
    return float(-np.polyfit(np.log(n[ok]), np.log(e[ok]), 1)[0])


def richardson(coarse, fine, order, ratio=2.0) -> float:
    """The Richardson value of two meshes (``fine`` on a mesh ``ratio`` times finer) whose error
    goes like ``N^-order``: ``fine + (fine - coarse)/(ratio^order - 1)`` (NaN without an order)."""
    if not math.isfinite(order):
        return float("nan")
    return float(fine + (fine - coarse) / (ratio ** order - 1.0))
