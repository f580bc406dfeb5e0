"""One grid of a level (full contact in closed form, else the splitting started from the
coarser grid) and Richardson's extrapolation over the levels with its observed order."""
from __future__ import annotations

import math

import numpy as np
from scipy import ndimage
from scipy.optimize import brentq

from ._measure import _level_scalars, _lowest
from ._splitting import _solve_level


def _prolong(field_, nx, ny):
    """A coarse grid's field at the panel centres of nx × ny (periodic bilinear)."""
    cx, cy = field_.shape
    ii = np.arange(nx) * (cx / nx)
    jj = np.arange(ny) * (cy / ny)
    coords = np.meshgrid(ii, jj, indexing="ij")
    return ndimage.map_coordinates(field_, coords, order=1, mode="grid-wrap")


def _solve_grid(grid, zk, control, value, asked, start, tol, h_ref):
    """One grid: a dict of σ, gap, u (k units), s, scalars and the iteration's counts, or
    the message of a failure (str).  start: the coarser grid's (σ, gap, s) or None."""
    nx, ny = grid.nx, grid.ny
    zt = zk - zk.mean()
    # the pressure of full contact, σ̂_q = ẑ_q/Ĉ(q) (q ≠ 0): gap = 0 everywhere
    zh = grid.rfft(zt)
    osc_h = np.zeros_like(zh)
    nz = grid.symbol != 0.0
    osc_h[nz] = zh[nz] / grid.symbol[nz]
    osc = grid.irfft(osc_h)
    evals = kept = 0
    full = True
    if control == "load" and value + osc.min() >= 0.0:
        sigma, s, u = value + osc, 0.0, zt.copy()
    elif control == "penetration" and asked == 1.0:
        sigma, s, u = osc - _lowest(osc), 0.0, zt.copy()
    else:
        full = False
        if start is not None:
            start = (_prolong(start[0], nx, ny), _prolong(start[1], nx, ny), start[2])
        sigma, u, s, evals, kept, converged = _solve_level(grid, zt, control, value, start,
                                                           tol)
        if not converged:
            return (f"the iteration did not converge on the {nx} × {ny} grid ({evals} "
                    "evaluations of its map)")
    if not sigma.max() > 0.0:
        return f"no contact on the {nx} × {ny} grid (the surface does not reach s)"
    gap = s - zt + u
    return {"sigma": sigma, "gap": gap, "u": u, "s": s, "evaluations": evals, "mixed": kept,
            "scalars": _level_scalars(grid, sigma, gap, s, zk, h_ref, full)}


def _order(n1, n2, n3, d1, d2):
    """The order p with d1/d2 = (n1^−p − n2^−p)/(n2^−p − n3^−p) (NaN if none in [0.1, 10])."""
    ratio = d1 / d2
    if not ratio > 1.0:
        return math.nan
    f = lambda p: (n1 ** -p - n2 ** -p) / (n2 ** -p - n3 ** -p) - ratio
    try:
        return brentq(f, 0.1, 10.0, xtol=1e-12)
    except ValueError:
        return math.nan


def richardson(nodes, values):
    """Richardson's extrapolation from the last three grids, with its observed order.

    Parameters
    ----------
    nodes : sequence of int
        Panels along x of the grids, increasing.
    values : sequence of float
        One scalar on each grid.

    Returns
    -------
    value, estimate, order, extrapolated : float, float, float, bool
        With the differences d1, d2 of the last three grids of one sign and shrinking, the
        order p they show (`_order`; for grids doubling, log2(d1/d2)) in [0.5, 8] gives the
        finest grid's error c N3^−p = d2 N3^−p/(N2^−p − N3^−p), which is the estimate.  The
        extrapolated value (finest + that correction) is returned only when four grids or more
        show orders within 0.5 of each other over their last two triples; its estimate is then
        the larger of the correction and the change from the extrapolation one grid coarser.
        Otherwise (errors that change sign as an edge moves across the points, or a pre-
        asymptotic start) the finest value is returned with the larger of |d2| and
        |d1| (N2/N3) (what a first-order error of d1 leaves on the finest grid) as its
        estimate.  Two grids: the finest value and |d2|; one: NaN.
    """
    q = [float(v) for v in values]
    ns = [float(v) for v in nodes]
    if len(q) < 2:
        return q[-1], math.nan, math.nan, False
    d2 = q[-1] - q[-2]
    if len(q) < 3:
        return q[-1], abs(d2), math.nan, False
    plain_estimate = max(abs(d2), abs(q[-2] - q[-3]) * ns[-2] / ns[-1])
    if not all(math.isfinite(v) for v in q[-3:]):
        return q[-1], math.nan, math.nan, False
    if q[-1] == q[-2] == q[-3]:
        return q[-1], 0.0, math.nan, False

    def triple(k):
        n1, n2, n3 = ns[k - 3:k]
        a, b = q[k - 2] - q[k - 3], q[k - 1] - q[k - 2]
        if b == 0.0:
            return math.nan, math.nan
        p = _order(n1, n2, n3, a, b)
        if not 0.5 <= p <= 8.0:
            return p, math.nan
        return p, b * n3 ** -p / (n2 ** -p - n3 ** -p)

    order, corr = triple(len(q))
    if not math.isfinite(corr):
        return q[-1], plain_estimate, order, False
    if len(q) >= 4:
        order0, corr0 = triple(len(q) - 1)
        if math.isfinite(corr0) and abs(order - order0) <= 0.5:
            value = q[-1] + corr
            return value, max(abs(corr), abs(value - (q[-2] + corr0))), order, True
    return q[-1], abs(corr), order, False
