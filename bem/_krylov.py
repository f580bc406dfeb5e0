"""The Krylov solves of one grid's active-set step (:mod:`bem._grid`): the primal solve on the
active set (GMRES on FFT products, right-preconditioned by the restricted inverse circulant, the
separation eliminated exactly), the free-panel (dual) solve where most panels are in contact,
and the retry of a solve that stagnated with a wider restart."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ._operator import CirculantOperator, gmres

if TYPE_CHECKING:
    from ._grid import _Grid

#: restart length of the second try of a Krylov solve that stagnated with `restart` (the
#: default 8 can stagnate for E_inf/E0 in the hundreds; 40 has not been seen to)
KRYLOV_RETRY_RESTART = 40
#: memory bound of that second try's Krylov basis (40 vectors of 2^21 panels)
KRYLOV_RETRY_BYTES = 41 * 8 * 2 ** 21
#: the Krylov solves keep their preconditioned vectors (one transform pair fewer per cycle)
#: while these take at most this memory: restart 8 on a set of up to 2^21 panels
KRYLOV_KEEP_BYTES = 8 * 8 * 2 ** 21

def _restricted_inverse(op: CirculantOperator, idx: np.ndarray):
    def apply(x):
        return op.apply_on(idx, x, inverse=True)

    return apply


def _linear_solve(grid: _Grid, idx, load, sep, x0, tol, restart, max_inner):
    """Solve on the active set; returns (sigma_full, s, iterations, relres, ok, C sigma on
    every panel).  The last product GMRES makes is with its answer, so that product over all
    panels is C sigma: kept, it gives the gaps without another transform."""
    op = grid.op
    held = [None]

    def product(values):
        held[0] = None  # memory: one whole product alive at a time
        held[0] = op.apply_on(idx, values, whole=True)
        return held[0][idx]

    n = grid.n
    na = idx.size
    pinv = _restricted_inverse(op, idx)
    per = grid.nodes  # the load is the mean over the period
    if load is not None:
        q = pinv(np.ones(na))
        beta = q.sum() / per
        # the load equation is scaled by scale/load so that the absolute Krylov tolerance
        # (tol times the scale of the heights) bounds its error relative to the load
        f = grid.scale / load

        def matvec(z):
            out = np.empty(na + 1)
            out[:na] = product(z[:na])
            out[:na] += z[na]
            out[na] = f * z[:na].sum() / per
            return out

        def precond(r):
            # block elimination of s with P = R C^+ R^T in place of C_AA^-1
            u = pinv(r[:na])
            t = (u.sum() / per - r[na] / f) / beta
            out = np.empty(na + 1)
            out[:na] = u - t * q
            out[na] = t
            return out

        b = np.append(grid.y[idx], f * load)
    else:
        matvec = product
        precond = pinv
        b = grid.y[idx] - sep
    # tol bounds every entry of the residual: gaps (k v) on A and the load equation
    z, its, relres, ok = gmres(matvec, precond, b, x0, tol * grid.scale, restart, max_inner,
                               keep=_keeps(restart, b.size))
    sigma = np.zeros(n)
    sigma[idx] = z[:na]
    s = z[na] if load is not None else sep
    return sigma, s, its, relres, ok, held[0]


def _dual_solve(grid: _Grid, free, load, x0, tol, restart, max_inner):
    """Load control with most panels in contact: the displacements u_F of the free panels.

    With u = y on the contact and u_F on the free set, sigma = C^+ u + load (C^+ maps onto
    zero-mean pressures, so the mean is the load) and the free panels carry no pressure:
    (C^+ u)_F = -load, a system of the size of the free set, preconditioned by R_F C R_F^T.
    The displacement is u less its mean, so the mean separation is s = mean(u) (the gap is then
    zero on the contact exactly).  The Krylov tolerance bounds the pressure left on the free
    panels, relative to the load (not below the rounding C^+ amplifies); it is set to zero there
    afterwards.
    Returns (sigma_full, s, iterations, residual over h k (scaled like the primal), ok).
    """
    op = grid.op
    m = free.size
    base = grid.y.copy()
    base[free] = 0.0
    g = op.pseudo_solve(base)[free]
    del base

    def matvec(z):
        return op.apply_on(free, z, inverse=True)

    def precond(r):
        return op.apply_on(free, r)

    b = -load - g
    # C^+ amplifies the rounding of u by up to max|1/symbol|: below that the residual cannot go
    floor = _dual_floor(grid)
    atol = max(tol * load, floor) * math.sqrt(m)
    z, its, res, ok = gmres(matvec, precond, b, x0, atol, restart, max_inner,
                            keep=_keeps(restart, m))
    u = grid.y.copy()
    u[free] = z
    del z
    sigma = op.pseudo_solve(u)
    sigma += load
    sigma[free] = 0.0
    s = float(u.mean())
    return sigma, s, its, res / load * grid.amp, ok, None


def _keeps(restart, size) -> bool:
    """Whether a Krylov solve keeps its preconditioned vectors (`gmres`'s ``keep``)."""
    return 8 * restart * size <= KRYLOV_KEEP_BYTES


def _dual_floor(grid: _Grid):
    """The pressure error (units of the pressure) below which the free-panel step cannot go:
    C^+ amplifies the rounding of u by up to max|1/symbol|."""
    return 16.0 * np.finfo(float).eps * grid.op.max_inverse * grid.amp


def _with_retry(solve, restart, size, widen=True):
    """``solve(restart)``, and once more with _retry_restart's wider restart if it did not
    converge: restarted GMRES can stagnate where the operator is far from normal (a stiff
    material, loss tangent ~ 10, near its memory length).  ``size``: the Krylov vectors'.
    GMRES updates its start in place, so the second try starts from the first one's iterate
    (whose residual is no larger than the start's)."""
    sigma, s, its, relres, ok, product = solve(restart)
    wide = _retry_restart(restart, size)
    if not ok and widen and wide > restart:
        del product  # memory
        sigma, s, more, relres, ok, product = solve(wide)
        its += more
    return sigma, s, its, relres, ok, product


def _retry_restart(restart, size):
    """The restart length of the second try of a stagnated Krylov solve: KRYLOV_RETRY_RESTART,
    or less where its basis (restart + 1 vectors of `size`) would pass KRYLOV_RETRY_BYTES."""
    fit = KRYLOV_RETRY_BYTES // (8 * max(size, 1)) - 1
    return max(restart, min(KRYLOV_RETRY_RESTART, fit))
