"""The gap step: near full contact, the gaps of the free panels as the unknowns.

Just below the full-contact load the contact is the whole period less a narrow gap.  With the
gaps g on the free panels F as unknowns (zero on the contact), C sigma = y - s + g gives
``sigma = p_full + C^+ g`` with ``p_full = C^+ y + load`` (the full-contact pressure) and
``s = mean(g)``; the free panels carry no pressure, ``(C^+ g)_F = -p_full_F``: a system of the
size of the free set whose right-hand side and unknowns keep their own relative precision
however shallow the gap.  Under load control the load is given (`_gap_solve`); under
penetration control s is, and the load is solved for with the gaps (`_gap_solve_sep`).  One
outer step of the active-set iteration of :mod:`bem._grid` (its ``_step``) calls these.
"""
from __future__ import annotations

import math

import numpy as np
import scipy.fft as sfft

from ._operator import gmres

#: the gap step's Krylov tolerance: the 2-norm of the pressure left on the free panels over
#: that of the full-contact pressure there (the deficit's scale; its gaps and edges move by
#: about as much, relative); a cold start's inexact steps stop at COLD_KRYLOV_TOL of it ...
GAP_STEP_TOL = 1e-10
#: ... and not below this many machine epsilons times the free panels times J0/J(0+): the
#: restricted C^+ is conditioned like its panels times the compliances' spread (E_inf/E0 =
#: 1000, V/V0 = 0.01, 1e-3 below p_FC, 22531 free panels at 2^20: stagnated at 3e-9)
GAP_STEP_FLOOR = 8.0
#: under penetration control the gap step's load is corrected (`_gap_solve_sep`) until the
#: correction is at most this fraction of the full-contact pressure's rms on the free panels
#: (what the gaps' solve is relative to), at most GAP_SEP_PASSES times a step
GAP_SEP_SETTLE = 1e-3
GAP_SEP_PASSES = 4
#: the gap step's Toeplitz block is applied on the free panels' span (2L-point transforms)
#: where that span L is at most this fraction of the period, else through the period's
GAP_LOCAL_SPAN = 0.25


def _gap_solve(grid, free, pfull, x0, rtol, restart, max_inner, keep):
    """Load control near full contact: the gaps g of the free panels, solved for directly.

    With the gap g on the free set F and zero on the contact, C sigma = y - s + g gives
    sigma = p_full + C^+ g (p_full = C^+ y + load, the full-contact pressure; C^+ maps onto
    zero-mean pressures) and s = mean(g); the free panels carry no pressure:
    (C^+ g)_F = -p_full_F, a system of the size of the free set, preconditioned by R_F C R_F^T
    (as `_dual_solve`, whose unknown is y + g).  The right-hand side is the full-contact
    pressure on the gap, of the order of the load's deficit below p_FC, and the unknowns are
    the gaps themselves: both keep their relative precision however small the gap (1e-13 h
    1e-8 below p_FC), where the primal step's gaps are differences of O(h) numbers.  The
    Krylov solve stops at ``rtol`` of ||p_full_F||; the pressure left on F is then set to
    zero.  The Toeplitz block is applied on the free panels' span when that is short
    (`_FreeSpan`), so a step costs O(L log L) plus one transform pair of the period.
    Returns (sigma_full, s, iterations, residual (scaled like the primal's), ok, gaps).
    """
    n = grid.n
    span = _FreeSpan(grid, free)
    b = -pfull[free]
    bnorm = float(np.linalg.norm(b))
    x = np.zeros(free.size) if x0 is None else np.asarray(x0, dtype=float)
    z, its, res, ok = gmres(span.inverse, span.forward, b, x, rtol * bnorm, restart,
                            max_inner, keep=keep)
    gap = np.zeros(n)
    gap[free] = z
    sigma = grid.op.pseudo_solve(gap)
    sigma += pfull
    sigma[free] = 0.0
    s = float(gap.sum()) / n  # mean(C sigma) = 0 = mean(y): the mean gap
    scale = max(float(np.max(pfull)), 1e-300)
    return sigma, s, its, res / scale * grid.amp, ok, gap


def _gap_solve_sep(grid, free, pfull0, p0, sep, x0, rtol, restart, max_inner, keep,
                   settle=True, why=None):
    """Penetration control near full contact: the gaps g of the free panels and the load p.

    As `_gap_solve` with p_full = pfull0 + p (``pfull0`` = C^+ y, the full-contact pressure
    at zero load), the load now unknown and the mean separation given: s = mean(g) (``sep``).
    The system is linear in p: g = g_0 + (p - p_0) q with A g_0 = -(pfull0 + p_0)_F and
    A q = -1 (A = R_F C^+ R_F^T), so p = p_0 + (N s - sum g_0)/sum q.  Starting from the
    previous step's load ``p0`` (a coarser grid's on the first), the correction is small and
    the gaps keep their own precision (near full contact the load hangs on s like
    p_FC - p ~ sqrt(s): the primal step's residual of 1e-10 h left the load 4e-10 off, 1e-8 h
    below full contact); the gaps are solved again at the corrected load until the correction
    is at most GAP_SEP_SETTLE of the rms full-contact pressure on the free panels.
    ``settle``: a load that has not settled in GAP_SEP_PASSES passes fails the step (ok False);
    a cold start's inexact steps pass False (the steps solved to tol decide convergence).
    ``why``: a list that gets the reason of a failure other than the gaps' Krylov solve's.
    Returns (sigma_full, s, iterations, residual ||A g + (pfull0 + p)_F|| at the returned
    load and gaps (scaled like the primal's), ok, gaps)."""
    n, m = grid.n, free.size
    if why is not None:
        why.clear()
    span = _FreeSpan(grid, free)
    q, total, qres, qok = gmres(span.inverse, span.forward, -np.ones(m), np.zeros(m),
                                rtol * math.sqrt(m), restart, max_inner, keep=keep)
    qsum = float(q.sum())
    x = np.zeros(m) if x0 is None else np.asarray(x0, dtype=float)
    p, settled, ok, dp = p0, False, qok and qsum < 0.0, 0.0
    base = pfull0[free]
    for _ in range(GAP_SEP_PASSES if ok else 0):
        b = -(base + p)
        bnorm = float(np.linalg.norm(b))
        x, its, _, ok = gmres(span.inverse, span.forward, b, x, rtol * bnorm, restart,
                              max_inner, keep=keep)
        total += its
        if not ok:
            break
        dp = (n * sep - float(x.sum())) / qsum
        x += dp * q  # the gaps at the corrected load (the system is linear in p)
        p += dp
        if abs(dp) <= GAP_SEP_SETTLE * bnorm / math.sqrt(m):
            settled = True
            break
    scale = max(float(np.max(pfull0)) + p, 1e-300)
    # the residual of the gaps returned, at the load returned (after the last correction)
    res = float(np.linalg.norm(span.inverse(x) + base + p)) if qok and qsum < 0.0 else 0.0
    if not qok:
        _say(why, f"the gap step's response to the load (A q = -1 on {m} free panels) did "
                  f"not reach tol (residual {qres / math.sqrt(m):.3e} of its right-hand side)")
    elif not qsum < 0.0:
        _say(why, f"the gap step's response to the load does not close the gaps (mean "
                  f"{qsum / m:.3e} >= 0 per unit load: no load gives the separation asked; "
                  f"the free panels' system is that rounding's, {m} panels)")
    elif ok and not settled and settle:
        ok = False
        _say(why, f"the gap step's load did not settle in {GAP_SEP_PASSES} pass(es) (last "
                  f"correction {abs(dp) / max(abs(p), 1e-300):.3e} of the load, residual "
                  f"{res / scale:.3e} h)")
    gap = np.zeros(n)
    gap[free] = x
    sigma = grid.op.pseudo_solve(gap)
    sigma += pfull0
    sigma += p
    sigma[free] = 0.0
    return sigma, sep, total, res / scale * grid.amp, ok, gap


def _say(why, text):
    if why is not None:
        why.append(text)


def _gap_step_tol(grid, free_panels):
    """The gap step's Krylov tolerance (relative to the full-contact pressure on the free
    panels): GAP_STEP_TOL, or the rounding floor GAP_STEP_FLOOR eps m J0/J(0+) of m free
    panels where that is larger."""
    spread = grid.material.J0 / grid.material.j_plus
    return max(GAP_STEP_TOL, GAP_STEP_FLOOR * np.finfo(float).eps * free_panels * spread)


class _FreeSpan:
    """R_F C^+ R_F^T and R_F C R_F^T for the gap step (`_gap_solve`): on the shortest arc of
    panels holding the free set F, through the Toeplitz block of that arc (exact, by its
    circulant embedding on a fast transform length) where the arc is at most GAP_LOCAL_SPAN of
    the period, else through the period."""

    def __init__(self, grid, free):
        n = grid.n
        self.op, self.free = grid.op, free
        self.local = False
        if free.size == 0:
            return
        steps = np.diff(np.append(free, free[0] + n))  # to the next free panel
        far = int(np.argmax(steps))
        start = int(free[(far + 1) % free.size])
        length = n - int(steps[far]) + 1  # the arc from start over every free panel
        if length > GAP_LOCAL_SPAN * n:
            return
        self.local = True
        self.idx = (free - start) % n
        size = sfft.next_fast_len(2 * length, real=True)
        self.size = size
        offsets = np.arange(size)
        offsets[size - length + 1:] -= size  # the embedding's column: offsets 0 .. L-1, -(L-1) .. -1
        offsets[length:size - length + 1] = 0  # not reached from inside the arc
        keep = np.ones(size, dtype=bool)
        keep[length:size - length + 1] = False
        self.symbols = []
        for inverse in (True, False):
            f = grid.op.symbol.copy()
            if inverse:
                f[0] = 0.0
                f[1:] = 1.0 / f[1:]
            col = sfft.irfft(f, n)
            del f
            emb = np.where(keep, col[offsets % n], 0.0)
            del col
            self.symbols.append(sfft.rfft(emb))
        self.plus, self.plain = self.symbols

    def _local(self, symbol, values):
        z = np.zeros(self.size)
        z[self.idx] = values
        return sfft.irfft(sfft.rfft(z) * symbol, self.size)[self.idx]

    def inverse(self, z):
        """(C^+ z~)_F for z~ equal to z on F and zero elsewhere."""
        if self.local:
            return self._local(self.plus, z)
        return self.op.apply_on(self.free, z, inverse=True)

    def forward(self, r):
        """(C r~)_F: the preconditioner."""
        if self.local:
            return self._local(self.plain, r)
        return self.op.apply_on(self.free, r)
