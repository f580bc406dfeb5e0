"""Levels of the Fourier reference: one N solved on shifted grids and averaged (the trapezoidal
rule over the shift), and Richardson's extrapolation over the levels with its observed order."""
from __future__ import annotations

import math

from ._grid import _solve_grid
from ._measure import _FIT_LAYER, _grid_scalars

_TWO_PI = 2.0 * math.pi

#: scalars averaged and extrapolated; the first four have relative error estimates
_RELATIVE = ("penetration", "tau_f", "mu", "contact_fraction")
_ABSOLUTE = ("ka", "ke", "ke_hat")
_KEYS = ("load",) + _RELATIVE + _ABSOLUTE
#: added to every estimate (in the scalar's own units, before the relative ones are divided by
#: the value): what the level and shift differences cannot see.  The edge fit has a model
#: error that does not shrink with h (its window is a fixed fraction of the contact): measured
#: on the exact gap of the semi-analytic solution, up to 2e-9 λ per edge, so 4e-9 in the
#: contact fraction and ~1e-8 in ka and ke; the others, rounding of their scale
_FLOOR = {"load": 1e-13, "penetration": 1e-13, "tau_f": 1e-13, "mu": 1e-13,
          "contact_fraction": 4e-9, "ka": 1e-8, "ke": 1e-8, "ke_hat": 1e-12}


def _level(n, shifts, mat, w, hk, control, value, patches, factor=None, thickness=None):
    """One level: the same N on `shifts` shifted grids, averaged (trapezoidal rule in φ).

    ``factor``: the layer factor S of the modes 0, 1, … (at least N/2 + 1 of them) and
    ``thickness`` d/λ of the layer (None, None: the half-space)."""
    reach = None
    if factor is not None:
        factor = factor[:n // 2 + 1]
        reach = _FIT_LAYER * thickness * n
    rows, pats, grids = [], [], []
    fitted = True
    jplus, terms = mat.creep_terms()
    creep = (jplus, tuple((j, w * t / _TWO_PI) for j, t in terms))  # lengths L_i in x/λ
    for k in range(shifts):
        grid = _solve_grid(n, k / shifts, mat, w, hk, control, value, patches, factor)
        grids.append(grid)
        if not grid.converged:
            break
        sc, pt, ok = _grid_scalars(grid, mat, w, hk, creep, factor, reach)
        fitted &= ok
        rows.append(sc)
        pats.append(pt)
        if pt:
            patches = [(p[0], p[1]) for p in pt]   # starts the next shift
    out = {"nodes": n, "nit": sum(g.nit for g in grids),
           "converged": all(g.converged for g in grids),
           "complementarity": max(g.complementarity for g in grids),
           "fitted": fitted, "grid": grids[0], "patches": patches, "message": ""}
    if not out["converged"]:
        out["message"] = (f"the active set did not converge on a grid of {n} points (shift "
                          f"{grids[-1].phi:g}) after {grids[-1].nit} steps")
        return out
    counts = {len(p) for p in pats}
    full = {r["full_contact"] for r in rows}
    if counts == {0}:
        out["message"] = f"no contact on the grids of {n} points (penetration below their reach)"
        return out
    if len(counts) > 1 or len(full) > 1:
        out["message"] = (f"the shifted grids of {n} points disagree on the contact "
                          f"({sorted(counts)} patches, full contact {sorted(full)}): a contact "
                          "or a gap narrower than a few spacings, or a point within a spacing "
                          "of a change in the number of patches")
        return out
    avg, half = {}, {}
    for key in _KEYS:
        vals = [r[key] for r in rows]
        if any(v is None for v in vals):
            avg[key] = half[key] = None
            continue
        avg[key] = math.fsum(vals) / len(vals)
        even = vals[::2]
        half[key] = math.fsum(even) / len(even)
    avg["full_contact"] = rows[0]["full_contact"]
    # patches averaged over the shifts (they are sorted by centroid on every grid)
    npat = len(pats[0])
    out["avg_patches"] = [tuple(math.fsum(p[i][j] for p in pats) / len(pats) for j in range(4))
                          for i in range(npat)]
    out["scalars"], out["half"] = avg, half
    return out


def richardson(nodes, values):
    """Richardson's extrapolation of a sequence of levels, with its observed order.

    Parameters
    ----------
    nodes : sequence of int
        Points per period, increasing.
    values : sequence of float
        The scalar on each level.

    Returns
    -------
    value, estimate, order, extrapolated : float, float, float, bool
        ``order`` is the order p = log(d₁/d₂)/log(N₃/N₂) shown by the last three levels (d₁,
        d₂ their differences; NaN when undefined).  The extrapolation q₃ + d₂/((N₃/N₂)^p − 1)
        is returned only when it is trustworthy: four levels or more, the last three
        differences of one sign and shrinking, and the orders of the last two triples within
        0.5 of each other, in [0.5, 8].  Its estimate is then the larger of the correction and
        the change from the extrapolation one level coarser.  Otherwise the finest value is
        returned, ``extrapolated`` False, with the larger of the last difference and the one
        before it over (N₃/N₂)² as its estimate.
    """
    q = [float(v) for v in values]
    ns = [float(v) for v in nodes]
    if len(q) < 2:
        return q[-1], math.nan, math.nan, False
    d2 = q[-1] - q[-2]
    if len(q) < 3:
        return q[-1], abs(d2), math.nan, False

    def triple(a, b, c, nb, nc):
        e1, e2 = b - a, c - b
        if e1 == 0.0 or e2 == 0.0:
            return math.nan, math.nan
        p = math.log(abs(e1 / e2)) / math.log(nc / nb)
        if e1 / e2 <= 1.0:
            return p, math.nan
        return p, c + e2 / ((nc / nb) ** p - 1.0)

    order, value = triple(*q[-3:], *ns[-2:])
    # without a trustworthy order: the last difference, or the one before it over
    # (N₃/N₂)² (the error it implies for the finest level at second order) if larger,
    # which covers a last difference that is small by chance (errors that oscillate)
    plain = max(abs(d2), abs(q[-2] - q[-3]) / (ns[-1] / ns[-2]) ** 2)
    if len(q) < 4 or not math.isfinite(value):
        return q[-1], plain, order, False
    order0, value0 = triple(*q[-4:-1], *ns[-3:-1])
    if not (math.isfinite(value0) and 0.5 <= order <= 8.0 and 0.5 <= order0 <= 8.0
            and abs(order - order0) <= 0.5):
        return q[-1], plain, order, False
    return value, max(abs(value - q[-1]), abs(value - value0)), order, True
