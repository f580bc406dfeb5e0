"""The contact edges read from fields: verify's own fit (no solver's code).

Near an edge σ ∝ d^½ and gap ∝ d^(3/2) with analytic corrections, so σ² (inside) and
gap^(2/3) (outside) are analytic with a simple zero at the edge; a grid adds a tail that decays
away from it (~h/d for a panel solver), which a plain polynomial mistakes for a shift.  The
method, in words, is in `comparisons.verify._scalars`.
"""
from __future__ import annotations

import math

import numpy as np

#: degree of the polynomial part of every edge fit
EDGE_DEGREE = 3
#: passes of the fixed point in the tail's distances (measured to contract by 0.1-0.3 a pass);
#: a side that has not settled to 1e-10 h after them gives no zero
EDGE_PASSES = 40
#: a side whose zero moves by at most this many spacings between its two windows holds the model
#: to the fit's resolution (~1e-4 h on exact samples; viscosine's BEM's edge fit uses the same
#: bound, so its fields give back its own edges)
EDGE_STILL = 2e-3
#: with no side that still, a side counts in the plain fits only if both its windows place a
#: zero and the zeros agree to this many spacings (the resolution POSITION_PANELS claims): a side
#: that fails it has another scale in its window (a relaxation layer next to the edge), which
#: bends a plain fit by up to half a spacing (measured: the leading edge from the Fourier
#: collocation's fields at sls-partial-v0.1, N = 1024, 0.54 h with the pressure's side, 0.003 h
#: without it; on exact samples and viscosine's BEM's fields of the 13 partial-contact SLS suite
#: cases at N = 512 … 4096 no edge gets worse by more than 0.002 h for it)
EDGE_HOLDS = 0.1


def _edge_windows(m):
    """(first, narrow last, plain last) point indices of the edge fits on a grid of m points."""
    first = max(1, int(round(math.sqrt(m) / 16.0)))
    return (first, max(first + EDGE_DEGREE + 4, int(round(math.sqrt(m) / 4.0))),
            max(first + 6, int(round(math.sqrt(m) / 2.0))))


def _nearest_real_root(coef, near):
    """The real root of the polynomial Σ coef_k t^k nearest ``near`` (None without one)."""
    roots = np.polynomial.polynomial.polyroots(coef)
    real = roots.real[np.abs(roots.imag) < 1e-9]
    return float(real[np.argmin(np.abs(real - near))]) if real.size else None


def _plain_roots(sides, h, m):
    """The plain fit's root of each side (None where it has none in [−h, 2h]): the
    least-squares cubic over the points ~√m/16 … ~√m/2 from the edge (from the edge point on,
    quadratic, where fewer remain), its root nearest the edge."""
    first, _, last = _edge_windows(m)
    roots = []
    for vals, sign, shift in sides:
        top = min(last, vals.size - 1)
        lo = first if top - first >= 5 else 0
        root = None
        if top - lo >= 3:
            k = np.arange(lo, top + 1)
            pos = sign * (k + shift) * h
            scale = float(np.max(np.abs(pos)))
            coef = np.polynomial.polynomial.polyfit(pos / scale, vals[k],
                                                    3 if top - lo >= 5 else 2)
            root = _nearest_real_root(coef, 0.0)
            root = root * scale if root is not None and -h <= root * scale <= 2.0 * h else None
        roots.append(root)
    return roots


def _tail_zero(vals, sign, shift, lo, hi, start, h):
    """The zero near ``start`` of the least-squares cubic + b h/|d| through vals[k] at the
    offsets sign (k + shift) h, k = lo … hi (d = offset − zero, the zero iterated to a fixed
    point); None with too few points, a zero outside [−h/2, 3h/2] or no fixed point."""
    hi = min(hi, vals.size - 1)
    if hi - lo < EDGE_DEGREE + 4:
        return None
    k = np.arange(lo, hi + 1)
    pos = sign * (k + shift) * h
    scale = hi * h
    poly = np.vander(pos / scale, EDGE_DEGREE + 1, increasing=True)
    zero = start
    for _ in range(EDGE_PASSES):
        design = np.column_stack((poly, h / np.abs(pos - zero)))
        coef = np.linalg.lstsq(design, vals[k], rcond=None)[0]
        root = _nearest_real_root(coef[:-1], zero / scale)
        if root is None or not -0.5 * h <= root * scale <= 1.5 * h:
            return None
        moved, zero = abs(root * scale - zero), root * scale
        if moved <= 1e-10 * h:
            return zero
    return None


def edge_offset(inside_sq, outside_23, h, m):
    """How far a contact edge lies beyond the last contact point (x/λ, toward the free side).

    Parameters
    ----------
    inside_sq : ndarray
        σ² at the contact points counted inward from the edge (index 0 the last contact point,
        at offset 0; index k at −k h).
    outside_23 : ndarray
        gap^(2/3) at the free points counted outward (index k at offset (k + 1) h); may be empty.
    h : float
        The spacing (x/λ).
    m : int
        Points per period (the fit windows grow like √m).

    Returns
    -------
    float
        The offset, in [−h/2, 3h/2].  Each side is fitted by a cubic plus a tail b h/d over the
        points ~√m/16 … ~√m/4 from the edge (its narrow window; a side cut short by the next
        edge: the first half of its points) and over twice as many (its wide window).  The
        narrow zeros of the sides whose two zeros agree to EDGE_STILL h are averaged.  Else
        the plain fits (`_plain_roots`) of the sides whose two zeros agree to EDGE_HOLDS h are
        averaged; with none (or no root), those of every side; with none of them either, σ²
        extrapolated linearly from the last two contact points (at most h), else h/2.  A mean
        of plain roots is clipped to [−h/2, 3h/2].
    """
    sides = ((inside_sq, -1.0, 0.0), (outside_23, 1.0, 1.0))
    plain = _plain_roots(sides, h, m)
    found = [r for r in plain if r is not None]
    if found:
        start = min(max(sum(found) / len(found), -0.5 * h), 1.5 * h)
    elif inside_sq.size >= 2 and inside_sq[1] > inside_sq[0]:
        start = min(h, h * inside_sq[0] / (inside_sq[1] - inside_sq[0]))
    else:
        start = 0.5 * h
    first, narrow, _ = _edge_windows(m)
    moves = []  # per side: (how far its zero moves between the windows, its narrow zero)
    for vals, sign, shift in sides:
        top = min(narrow, (vals.size - 1) // 2)
        near = _tail_zero(vals, sign, shift, first, top, start, h)
        wide = _tail_zero(vals, sign, shift, first, 2 * top, start, h)
        moves.append((math.inf, None) if near is None or wide is None else
                     (abs(near - wide), near))
    still = [z for d, z in moves if d <= EDGE_STILL * h]
    if still:
        return sum(still) / len(still)
    held = [r for r, (d, _) in zip(plain, moves) if r is not None and d <= EDGE_HOLDS * h]
    if held:
        return min(max(sum(held) / len(held), -0.5 * h), 1.5 * h)
    return start
