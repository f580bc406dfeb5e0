"""Convergence in one place: the observed order of a mesh study and the Richardson step.

Every study of the project (the report's, `verify`'s, the suite's certification, the BEM
benchmark) fits its order and extrapolates with these two functions; each keeps its own rule
for which meshes and errors enter (its floor), and says so where it calls them.

The certified study of the benchmark suite (`study`, with its constants), which `verify` runs
too, and the rule of certified digits (`digits`, `half_unit`, `rounded`) live here beside them:
one order fit, one Richardson step, one digits rule.
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


def richardson(coarse, fine, order, ratio=2.0):
    """The Richardson value of two meshes (``fine`` on a mesh ``ratio`` times finer) whose error
    goes like ``N^-order``: ``fine + (fine - coarse)/(ratio^order - 1)`` (NaN without an order).
    A float for scalars; for arrays (fields on one grid) an array, point by point."""
    if not math.isfinite(order):
        value = np.full(np.shape(fine), np.nan)
    else:
        value = fine + (fine - coarse) / (ratio ** order - 1.0)
    return float(value) if np.ndim(value) == 0 else value


# ------------------------------------------------------------------------------ certified digits
MAX_DIGITS = 12      # a hard cap; RELATIVE_FLOOR is what binds
RELATIVE_FLOOR = 1e-10  # half a unit of the last certified digit is never below 1e-10 |value|:
                        # ten times the round-off level, which differs between machines, so a
                        # certified digit survives recomputation anywhere


def digits(value, error) -> int:
    """Certified significant digits of ``value`` given an absolute error bound ``error``.

    The largest d in 0..MAX_DIGITS with ``error < ½ · 10^(floor(log10|value|) − d + 1)`` and
    that half unit at least RELATIVE_FLOOR · |value|; 0 for a zero or non-finite value or a
    non-finite error.
    """
    if value is None or error is None or not math.isfinite(value) or not math.isfinite(error) \
            or value == 0.0:
        return 0
    e10 = math.floor(math.log10(abs(value)))
    for d in range(MAX_DIGITS, 0, -1):
        hu = 0.5 * 10.0 ** (e10 - d + 1)
        if error < hu and hu >= RELATIVE_FLOOR * abs(value):
            return d
    return 0


def half_unit(value, ndigits) -> float:
    """Half a unit of the last of ``ndigits`` significant digits of ``value`` (inf for 0 digits)."""
    if ndigits <= 0 or value == 0.0:
        return math.inf
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - ndigits + 1)


def rounded(value, ndigits) -> str:
    """``value`` written with ``ndigits`` significant digits ("" when none is certified)."""
    if value is None or ndigits <= 0 or not math.isfinite(value):
        return ""
    e10 = math.floor(math.log10(abs(value))) if value != 0.0 else 0
    if -5 <= e10 < 6:
        return f"{value:.{max(ndigits - 1 - e10, 0)}f}"
    return f"{value:.{ndigits - 1}e}"


# ------------------------------------------------------------------------------ the certified study
LAST = 4             # differences of the finest meshes that make the convergence study
ROUNDOFF = 1e-11     # relative size of a difference that is round-off, not discretisation
MIN_ORDER = 0.5      # below this observed order nothing is certified (not converging) ...
#: ... unless every value of the study lies within this × |q| of the others and they move both
#: ways: the sub-panel edge fits settle and then scatter without an order.  A one-way drift is
#: not scatter (measured: prony4-partial's ka rises by ~5e-9 per doubling over N = 2^14 ... 2^20,
#: a spread of 2.1e-8, with differences that do not shrink)
SCATTER_FLOOR = 1e-8
MAX_ORDER = 4.0


def study(nodes, values, last=LAST):
    """Convergence study of one scalar over meshes doubling in N: the certification rule of the
    benchmark suite (`comparisons.suite`, its docstring: 'How a value is certified'), also
    `verify`'s.

    The order is `observed_order` of the differences (floored at ROUNDOFF |q|), the value
    `richardson`'s step from the two finest meshes.

    Parameters
    ----------
    nodes : sequence of int
        The meshes, each twice the previous one.
    values : sequence of float
        The scalar on each mesh (NaN where the solve failed).
    last : int
        Number of finest differences used (``last + 1`` meshes).

    Returns
    -------
    dict
        ``order`` (observed, NaN in the round-off regime or when undetermined), ``richardson``,
        ``estimate`` (error estimate E, inf when not converging), ``finest`` and ``regime``
        ("asymptotic", "round-off", "scatter", "not converging" or "too few meshes").
    """
    N = np.asarray(nodes, float)
    q = np.asarray(values, float)
    out = {"order": float("nan"), "richardson": float("nan"), "estimate": float("inf"),
           "finest": float(q[-1]) if q.size else float("nan"), "regime": "too few meshes"}
    if q.size < last + 1 or not np.all(np.isfinite(q[-(last + 1):])):
        return out
    q = q[-(last + 1):]
    N = N[-(last + 1):]
    d = np.abs(np.diff(q))
    floor = ROUNDOFF * float(np.max(np.abs(q)))
    if np.all(d[-2:] <= floor):
        out.update(order=float("nan"), richardson=float(q[-1]), estimate=max(floor, float(d[-1])),
                   regime="round-off")
        return out
    dd = np.maximum(d, floor)
    p = observed_order(N[1:], dd)
    out["order"] = p
    if not p >= MIN_ORDER:
        spread = float(np.max(q) - np.min(q))
        steps = np.sign(np.diff(q)[d > floor])
        # a drift (every step one way) is not scatter, however small: it may go on
        if spread <= SCATTER_FLOOR * float(np.max(np.abs(q))) and \
                np.any(steps > 0) and np.any(steps < 0):
            out.update(richardson=float(q[-1]), estimate=max(floor, spread), regime="scatter")
        else:
            out["regime"] = "not converging"
        return out
    pu = min(p, MAX_ORDER)
    r = 2.0 ** pu - 1.0
    steps = np.arange(-(d.size - 1), 1, dtype=float)  # 0 at the finest difference
    envelope = float(np.max(dd * 2.0 ** (pu * steps)))
    out.update(richardson=richardson(q[-2], q[-1], pu), estimate=envelope / r,
               regime="asymptotic")
    return out
