"""The scalars of one solved grid: the friction as the dissipation of the modes, the load, Δ/h,
and the contact edges located below the grid by a least-squares fit of the gap to the form each
edge imposes (the creep operator's recovery at the trailing edge)."""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar
from scipy.special import dawsn

from ._grid import _runs

_TWO_PI = 2.0 * math.pi

#: powers of d in the gap fit near an edge; its window is _FIT_WINDOW of the shorter of the
#: contact and the gap region (the expansion about one edge converges up to the other edges;
#: measured on the exact gap: edges to ~1e-9 λ at a quarter), and no fewer points than
#: _FIT_MIN_POINTS (the fit averages the O(h²) errors of the gap over them)
_FIT_POWERS = (1.5, 2.5, 3.5, 4.5, 5.5, 6.5)
_FIT_WINDOW = 0.25
_FIT_MIN_POINTS = 24
#: on a layer the fit window is also at most this many thicknesses d: the layer's kernel
#: differs from the half-space's by a part analytic in a strip of half-width 2d only (S − 1
#: ~ e^{−2|n|kd}), which bounds the expansion about an edge as the other edges do; a quarter
#: of that radius, as _FIT_WINDOW (measured: at k d = 0.2 the uncapped window, ~1.2 d, left
#: errors of 1e-6 in ka that did not fall with N and exceeded the estimates 2-4 times)
_FIT_LAYER = 0.5


def _wrap(x):
    """x/λ into [−½, ½)."""
    return (x + 0.5) % 1.0 - 0.5


def _recovery(powers, z):
    """R_p(z) = Φ_p(z)/z^p with Φ_p(z) = ∫_0^z e^{−(z−u)} u^p du, for each p of ``powers`` (a
    1-D array of half-integers) and z ≥ 0 of any shape: an array of shape powers.shape + z.shape.

    Series z Σ_k (−z)^k / ((p+1)…(p+1+k)) below z = max p + 8 (it loses at most ~3 digits
    there); above, the upward recurrence R_p = 1 − (p/z) R_{p−1} from R_{−1/2} = 2√z F(√z)
    (F Dawson's integral), stable once z exceeds p.  R_p(0) = 0, R_p(∞) = 1.  Every power (and
    every Prony term's z) in one array operation: the edge fit calls this for each trial edge.
    """
    z = np.asarray(z, dtype=float)
    q = np.asarray(powers, dtype=float).reshape((-1,) + (1,) * z.ndim)
    out = np.empty(q.shape[:1] + z.shape)
    big = z > q.max() + 8.0
    if np.any(big):
        zb = z[big]
        r = 2.0 * np.sqrt(zb) * dawsn(np.sqrt(zb))
        p = -0.5
        table = {}
        while p < q.max():
            p += 1.0
            r = 1.0 - (p / zb) * r
            table[p] = r
        for k, qk in enumerate(q.ravel()):
            out[k][big] = table[float(qk)]
    small = ~big
    if np.any(small):
        zs = z[small]
        qs = q.reshape(-1, 1)
        # the alternating terms fall below 1e-17 of the sum within 3 max z + 40 of them (z < 15)
        nterms = int(3.0 * zs.max()) + 40
        term = np.broadcast_to(1.0 / (qs + 1.0), (qs.size, zs.size)).copy()
        total = term.copy()
        for j in range(1, nterms):
            term *= -zs / (qs + 1.0 + j)
            total += term
        out[:, small] = zs * total
    return out


def _edge_basis(d, powers, trailing, creep):
    """Columns of the gap model at distances d ≥ 0 from an edge.

    Leading edge: d^p, p = 3/2, 5/2, … (the memory there reaches only ahead of the contact and
    adds half-integer powers).  Trailing edge: the creep operator applied to (−x)_+^p,

        ψ_p(d) = J(0+) d^p + Σ_i J_i L_i^p Φ_p(d/L_i),   L_i = w τ_i/(2π) in x/λ,

    the recovery of the surface behind the contact, which on a length L_i turns J(0+) d^p into
    J0 d^p and which no power series in d reproduces on a window wider than L_i.
    """
    cols = d[:, None] ** powers[None, :]
    if not trailing or not creep[1]:
        return cols
    jplus, terms = creep
    weights = np.array([j_i for j_i, _ in terms])
    lengths = np.array([length for _, length in terms])
    # a term of zero length has recovered at once: J_i joins J(0+)
    factor = np.full((powers.size, d.size), jplus + weights[lengths == 0.0].sum())
    live = lengths != 0.0
    if np.any(live):
        r = _recovery(powers, d[None, :] / lengths[live][:, None])  # (power, term, point)
        factor += np.einsum("t,ptm->pm", weights[live], r)
    return cols * factor.T


def _fit_edge(xs, g, lo, hi, side, trailing, creep, nbasis):
    """The edge x_e in [lo, hi] whose gap model (`_edge_basis`) fits g best.

    Variable projection: the coefficients by linear least squares for each x_e, x_e by Brent's
    method on the misfit (columns scaled to unit maximum).
    """
    powers = np.asarray(_FIT_POWERS[:nbasis])

    def misfit(xe):
        d = np.maximum(side * (xs - xe), 0.0)
        a = _edge_basis(d, powers, trailing, creep)
        a = a / np.maximum(np.max(np.abs(a), axis=0), 1e-300)
        coef, *_ = np.linalg.lstsq(a, g, rcond=None)
        return float(np.sum((a @ coef - g) ** 2))

    res = minimize_scalar(misfit, bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-15, "maxiter": 500})
    return float(res.x)


def _edges(grid, s0, length, gap_before, gap_after, creep, reach=None):
    """Trailing and leading edges (unwrapped x/λ) of the run of `length` points from s0.

    gap_before/gap_after: the gap points between this run and its neighbours (the run's own
    other end for a single patch).  The fit window is a quarter of the shorter of the contact
    and the gap region (the distance to the nearest other edge, which bounds the expansion),
    and no more than ``reach`` points on a layer (its expansion converges within about 2d
    there, `_FIT_LAYER`), at least _FIT_MIN_POINTS points, skipping the first gap point (the
    discretisation error is largest there).  Returns (x_t, x_l, fitted).
    """
    n = grid.n
    h = 1.0 / n
    x0 = grid.x[s0]
    x_last = x0 + (length - 1) * h      # last contact point, unwrapped
    fitted = True
    out = []
    for side, room in ((-1, gap_before), (+1, gap_after)):
        k = _FIT_WINDOW * min(length, room)
        if reach is not None:
            k = min(k, reach)
        k = max(_FIT_MIN_POINTS, int(round(k)))
        k = min(k, (room - 1) // 2)
        m = np.arange(2, k + 2)
        if side > 0:
            xs, g = x_last + m * h, grid.gap[(s0 + length - 1 + m) % n]
            lo, hi = x_last - h, x_last + 2 * h
        else:
            xs, g = x0 - m * h, grid.gap[(s0 - m) % n]
            lo, hi = x0 - 2 * h, x0 + h
        if k >= 8:
            nb = len(_FIT_POWERS) if k >= 24 else 4
            out.append(_fit_edge(xs, g, lo, hi, side, side < 0, creep, nb))
            continue
        # too few gap points for the fit: the zero of gap^(2/3), linear through two points
        fitted = False
        first = x_last + h if side > 0 else x0 - h
        idx = (s0 + length - 1 + np.array([1, 2])) % n if side > 0 else (s0 - np.array([1, 2])) % n
        gi = np.maximum(grid.gap[idx], 0.0) ** (2.0 / 3.0)
        den = gi[1] - gi[0]
        out.append(first - side * h * gi[0] / den if den > 0.0 else first - side * 0.5 * h)
    return out[0], out[1], fitted


def _grid_scalars(grid, mat, w, hk, creep, factor=None, reach=None):
    """The scalars of one grid, and its patches [(x_t, x_l, load, centroid)].

    ``factor``: the layer factor of the modes 0 … N/2 and ``reach`` the widest edge fit in
    points (None, None: the half-space)."""
    n = grid.n
    sig = grid.sigma
    shat = np.fft.rfft(sig) / n
    modes = np.arange(shat.size, dtype=float)
    weight = np.ones(modes.size)
    weight[0] = 0.0
    if n % 2 == 0:
        weight[-1] = 0.0   # the Nyquist mode is real in C: it dissipates nothing
    if factor is not None:
        weight = weight * factor   # a mode's displacement, so its dissipation, carries S
    tau = float(np.sum(weight * 4.0 * mat.jstar(modes, w).imag * np.abs(shat) ** 2))
    load = float(np.mean(sig))
    out = {"load": load, "penetration": 1.0 - grid.s / hk, "tau_f": tau,
           "mu": tau / load if load > 0.0 else math.nan}
    runs = _runs(grid.active)
    patches = []
    fitted = True
    if len(runs) == 1 and runs[0][1] == n:
        s1 = np.sum(sig * np.exp(-1j * _TWO_PI * grid.x)) / n  # σ̂_1 with its true phase
        out.update(full_contact=True, contact_fraction=1.0, ka=math.pi, ke=None,
                   ke_hat=-math.atan2(s1.imag, s1.real))
        return out, [(-0.5, 0.5, load, _wrap(out["ke_hat"] / _TWO_PI))], True
    for i, (s0, length) in enumerate(runs):
        prev_end = runs[i - 1][0] + runs[i - 1][1]
        nxt = runs[(i + 1) % len(runs)][0]
        before = (s0 - prev_end) % n
        after = (nxt - (s0 + length)) % n
        xt, xl, ok = _edges(grid, s0, length, before, after, creep, reach)
        fitted &= ok
        pts = (s0 + np.arange(length)) % n
        xr = grid.x[s0] + np.arange(length) / n
        share = float(np.sum(sig[pts])) / n
        # a patch that carries nothing (a point held at σ = 0 by the tolerance): its centre
        centroid = (float(np.sum(xr * sig[pts]) / np.sum(sig[pts])) if share > 0.0
                    else 0.5 * (xt + xl))
        shift = _wrap(0.5 * (xt + xl)) - 0.5 * (xt + xl)  # wrap by the centre, keep the pair
        patches.append((xt + shift, xl + shift, share, centroid + shift))
    patches.sort(key=lambda p: p[3])
    out["full_contact"] = False
    out["contact_fraction"] = float(sum(p[1] - p[0] for p in patches))
    if len(patches) == 1:
        xt, xl, _, cen = patches[0]
        out.update(ka=math.pi * (xl - xt), ke=_TWO_PI * 0.5 * (xt + xl), ke_hat=_TWO_PI * cen)
    else:
        out.update(ka=None, ke=None, ke_hat=None)
    return out, patches, fitted
