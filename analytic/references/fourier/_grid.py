"""One grid of the Fourier reference: the collocation operator (a circulant of the mode
symbols) and the primal-dual active-set solve of the contact on N shifted points, with the
restricted solves (Levinson's recursion for one patch, dense LU otherwise)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import linalg

_TWO_PI = 2.0 * math.pi

#: an active-set step drops σ_j < −_TOL·max σ and adds gap_j < −_TOL·hk: the error of the
#: restricted solve (its residual is held below 1e-12) must not make the iteration cycle at a
#: point that sits on an edge
_TOL = 1e-11
_MAX_ACTIVE_SET = 100


def _runs(active):
    """(start, length) of the circular runs of True, in order of start."""
    n = active.size
    if active.all():
        return [(0, n)]
    if not active.any():
        return []
    a = active.astype(np.int8)
    up = np.flatnonzero(np.diff(np.concatenate([a[-1:], a])) == 1)
    down = np.flatnonzero(np.diff(np.concatenate([a[-1:], a])) == -1)
    out = []
    for s0 in up:
        later = down[down > s0]
        end = later[0] if later.size else down[0] + n
        out.append((int(s0), int(end - s0)))
    return out


def _circulant_product(colhat, x, n):
    return np.fft.irfft(np.fft.rfft(x, axis=0) * (colhat if x.ndim == 1 else colhat[:, None]),
                        n, axis=0)


def _toeplitz_product(c, r, z):
    """T z for the Toeplitz T with first column c and first row r (FFT, any number of columns)."""
    L = c.size
    m = 1 << int(math.ceil(math.log2(2 * L)))
    gen = np.zeros(m)
    gen[:L] = c
    gen[m - L + 1:] = r[1:][::-1]
    padded = np.concatenate([z, np.zeros((m - L,) + z.shape[1:])])
    return _circulant_product(np.fft.rfft(gen), padded, m)[:L]


def _restricted_solve(col, runs, idx, rhs):
    """Solve C_AA z = rhs on the active points idx (rhs of shape (|A|, k)).

    One patch: C_AA is Toeplitz (Levinson, O(|A|²)), with refinement steps by FFT products
    until the residual meets its bound; otherwise (or if it is not met) dense LU.
    """
    n = col.size
    if len(runs) == 1:
        s0, L = runs[0]
        order = (s0 + np.arange(L)) % n     # the run in order along x
        loc = np.empty(n, dtype=np.intp)
        loc[idx] = np.arange(idx.size)
        b = rhs[loc[order]]
        c = col[:L]
        r = col[(-np.arange(L)) % n]
        # Levinson's recursion leaves residuals of ~1e-13 here (LU ~1e-15): a refinement step
        # only where they exceed 1e-12, far below the discretisation errors
        bound = 1e-12 * max(np.max(np.abs(b)), 1e-300)
        try:
            z = linalg.solve_toeplitz((c, r), b, check_finite=False)
            for _ in range(3):
                res = b - _toeplitz_product(c, r, z)
                if np.max(np.abs(res)) <= bound:
                    out = np.empty_like(z)
                    out[loc[order]] = z
                    return out
                z = z + linalg.solve_toeplitz((c, r), res, check_finite=False)
        except linalg.LinAlgError:  # a singular leading minor: LU pivots past it
            pass
    dense = np.empty((idx.size, idx.size))
    for i0 in range(0, idx.size, 1024):  # row blocks: no |A|² index array at once
        rows = idx[i0:i0 + 1024]
        dense[i0:i0 + rows.size] = col[(rows[:, None] - idx[None, :]) % n]
    return linalg.solve(dense, rhs, check_finite=False)


@dataclass
class _Grid:
    n: int
    phi: float
    x: np.ndarray
    sigma: np.ndarray
    gap: np.ndarray
    s: float
    active: np.ndarray
    nit: int
    converged: bool
    complementarity: float


def _solve_grid(n, phi, mat, w, hk, control, value, patches, factor=None):
    """Active-set solve on one shifted grid, started from the patches [(x_t, x_l), ...].

    ``factor``: the layer factor S of the modes 0 … N/2 (None: the half-space)."""
    x = -0.5 + (np.arange(n) + phi) / n
    y = hk * np.cos(_TWO_PI * x)
    modes = np.arange(n // 2 + 1, dtype=float)
    sym = np.zeros(modes.size, dtype=complex)
    sym[1:] = (2.0 / modes[1:]) * mat.jstar(modes[1:], w)
    if factor is not None:
        sym[1:] *= factor[1:]
    # C has no mode 0 (v from its mean line), so it is singular and its restriction to a
    # near-full contact nearly so.  The solves use C' = C + c0·mean, mode 0 given the symbol
    # c0 = 2 Re J*(1) (times S(kd) on a layer) of the scale of mode 1: C'σ = Cσ + c0 mean(σ),
    # which only moves s.
    c0 = float(sym[1].real)
    sym[0] = c0
    col = np.fft.irfft(sym, n)        # C'[i, j] = col[(i − j) mod n]; Nyquist: its real part
    colhat = np.fft.rfft(col)
    active = np.zeros(n, dtype=bool)
    for xt, xl in patches:
        # positions of the points relative to the trailing edge, unwrapped into [0, 1)
        active |= np.mod(x - xt, 1.0) <= (xl - xt)
    if control == "penetration" and not np.any(y > value):
        # no point of this grid reaches the body: no contact to solve for
        zero = np.zeros(n)
        return _Grid(n, phi, x, zero, value - y, value, zero.astype(bool), 0, True, 0.0)
    if not active.any():
        active[np.argmax(y)] = True
    seen = set()
    converged = False
    sigma = np.zeros(n)
    for it in range(1, _MAX_ACTIVE_SET + 1):
        idx = np.flatnonzero(active)
        runs = _runs(active)
        z = _restricted_solve(col, runs, idx, np.stack([y[idx], np.ones(idx.size)], axis=1))
        # on the contact C'σ + t = y with t = s − c0 mean(σ), so σ = z1 − t z2
        m1, m2 = z[:, 0].sum() / n, z[:, 1].sum() / n
        if control == "load":
            t = (m1 - value) / m2
            s = t + c0 * value
        else:
            s = value
            t = (s - c0 * m1) / (1.0 - c0 * m2)
        sa = z[:, 0] - t * z[:, 1]
        sigma = np.zeros(n)
        sigma[idx] = sa
        gap = _circulant_product(colhat, sigma, n) - y + t
        gap[idx] = 0.0
        new = active.copy()
        new[idx[sa < -_TOL * max(sa.max(), 0.0)]] = False
        new[~active & (gap < -_TOL * hk)] = True
        if np.array_equal(new, active):
            converged = True
            break
        key = new.tobytes()
        if key in seen:
            break
        seen.add(key)
        active = new
    scale = max(sigma.max(), 1e-300)
    compl = max(float(-sigma.min()) / scale, float(-gap.min()) / hk, 0.0)
    return _Grid(n, phi, x, sigma, gap, s, active, it, converged, compl)
