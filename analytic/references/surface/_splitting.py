"""The contact problem on one grid: Douglas–Rachford splitting of the monotone affine operator
and the normal cone of the admissible pressures, accelerated by Anderson's mixing with the
safeguard of Zhang, O'Donoghue & Boyd (see the package docstring)."""
from __future__ import annotations

import math

import numpy as np

#: Anderson's memory: 8 differences (measured on the bi-sinusoid at 256²: 5 → 111, 10 → 95
#: evaluations of the map; each kept difference costs two passes over the grid)
_MEMORY = 8
#: iterations of the map before a level is declared not converged
_MAX_ITERATIONS = 20000
#: the safeguard's bound on a mixed step's residual: D ‖g_0‖ (k + 1)^−(1+ε)
_SAFE_D, _SAFE_EPS = 1e6, 1e-6


def _project(y, load, t):
    """max(y − t, 0) with t the root of mean(max(y − t, 0)) = load, from the guess t.

    f(t) = mean(max(y − t, 0)) − load is convex, decreasing and piecewise linear: Newton's
    method from the left of the root stays there and ends on its linear piece exactly; from
    the right its first step lands on the left.
    """
    n = y.size
    for _ in range(200):
        above = y > t
        count = int(np.count_nonzero(above))
        if count == 0:          # nothing above t: the step that puts the peak alone in contact
            t = float(y.max()) - load * n
            continue
        excess = float(np.sum(y[above] - t)) / n - load
        step = excess * n / count
        t_new = t + step
        if abs(step) <= 4e-16 * max(abs(t), abs(load)) or t_new == t:
            t = t_new
            break
        t = t_new
    return np.maximum(y - t, 0.0), t


def _norm(v):
    """‖v‖₂ by einsum (BLAS's threaded dot costs more than it saves on two shared cores)."""
    return math.sqrt(float(np.einsum("i,i->", v, v)))


def _anderson(T, y0, tol_of, memory=_MEMORY, max_iterations=_MAX_ITERATIONS):
    """A fixed point of T by Anderson's mixing (type II) with the safeguard of Zhang et al.

    ``T(y)`` returns (T y, aux); ``tol_of(aux)`` the bound on ‖T y − y‖∞ that stops.  Returns
    (y, aux, evaluations, mixed steps kept, converged).

    The differences are kept as rows and their Gram matrix updated by one row per step; the
    sums are NumPy's (einsum, not BLAS: reproducible, and no threads fighting for the cores).
    """
    shape = y0.shape
    n = y0.size
    dy = np.zeros((memory, n))
    dg = np.zeros((memory, n))
    gram = np.zeros((memory, memory))
    ty, aux = T(y0)
    evals = 1
    y = y0.ravel().copy()
    g = ty.ravel() - y
    g0 = _norm(g)
    kept, count, head = 0, 0, 0
    while evals < max_iterations:
        if float(np.max(np.abs(g))) <= tol_of(aux):
            return y.reshape(shape), aux, evals, kept, True
        k = min(count, memory)
        if k:
            b = np.einsum("ij,j->i", dg[:k], g)
            gm = gram[:k, :k]
            ridge = 1e-12 * max(np.trace(gm) / k, 1e-300)
            try:
                gam = np.linalg.solve(gm + ridge * np.eye(k), b)
            except np.linalg.LinAlgError:
                gam = np.zeros(k)
            cand = y + g - np.einsum("i,ij->j", gam, dy[:k]) - np.einsum("i,ij->j", gam,
                                                                           dg[:k])
            tc, auxc = T(cand.reshape(shape))
            evals += 1
            gc = tc.ravel() - cand
            if _norm(gc) <= _SAFE_D * g0 * (kept + 1) ** (-1.0 - _SAFE_EPS):
                kept += 1
            else:                               # the plain step T y instead
                cand = y + g
                tc, auxc = T(cand.reshape(shape))
                evals += 1
                gc = tc.ravel() - cand
        else:
            cand = y + g
            tc, auxc = T(cand.reshape(shape))
            evals += 1
            gc = tc.ravel() - cand
        dy[head] = cand - y
        dg[head] = gc - g
        k = min(count + 1, memory)
        row = np.einsum("ij,j->i", dg[:k], dg[head])
        gram[head, :k] = row
        gram[:k, head] = row
        head = (head + 1) % memory
        count += 1
        y, g, aux = cand, gc, auxc
    return y.reshape(shape), aux, evals, kept, False


def _solve_level(grid, zt, control, value, start, tol):
    """The contact on one grid: σ, k u, k s, evaluations, mixed steps kept, converged.

    zt: k z̃ on the grid; value: p̃ (load) or k s (penetration); start: (σ, gap, s) of a
    coarser grid interpolated here, or None.
    """
    gamma = 1.0 / math.sqrt(grid.scales[0] * grid.scales[1])
    resolvent = 1.0 / (1.0 + gamma * grid.symbol)
    zh = gamma * grid.rfft(zt)
    npts = grid.nx * grid.ny
    if control == "penetration":
        zh[0, 0] -= gamma * value * npts      # the constant s of A(σ) = Cσ − z̃ + s
    state = {"t": 0.0}

    def T(y):
        if control == "load":
            sigma, state["t"] = _project(y, value, state["t"])
        else:
            sigma = np.maximum(y, 0.0)
        r = grid.irfft(resolvent * (grid.rfft(2.0 * sigma - y) + zh))
        return y + r - sigma, sigma

    if start is None:
        y0 = np.full((grid.nx, grid.ny), value if control == "load" else 0.0)
        if control == "penetration":
            y0 = gamma * np.maximum(zt - value, 0.0)   # the rigid overlap, pressed
    else:
        s0, g0, sep0 = start
        if control == "load":
            y0 = s0 - gamma * (g0 - sep0)
            state["t"] = gamma * sep0
        else:
            y0 = s0 - gamma * g0
    y, sigma, evals, kept, ok = _anderson(T, y0, lambda sig: tol * max(float(sig.max()),
                                                                          1e-300))
    if control == "load":
        sigma, t = _project(y, value, state["t"])
        s = t / gamma
    else:
        sigma = np.maximum(y, 0.0)
        s = value
    return sigma, grid.apply(sigma), s, evals, kept, ok
