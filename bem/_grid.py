"""One grid: primal-dual active set outside, preconditioned GMRES inside.

Discrete problem on N panels (units of :mod:`bem`: ``k y``, ``k v``, pressure in
``E_ref/(1 - nu^2)``)::

    gap_i = (C sigma)_i - y_i + s >= 0,   sigma_i >= 0,   sigma_i gap_i = 0,
    mean(sigma) = load            (load control; s unknown), or
    s given                       (penetration control; the load is an output).

Here ``y`` is the profile minus its mean, ``C`` the circulant of eq. (2.4)-(2.5)
and ``s`` the mean separation (the mean gap, because ``mean(C sigma) = 0``).

Outer iteration: primal-dual active set (a semi-smooth Newton method for the
complementarity conditions).  On the active set A the linear system is
``(C sigma)_A + s = y_A`` with ``sigma = 0`` off A (plus the load equation),
solved by GMRES on FFT products, right-preconditioned by the restriction of
the inverse circulant ``P = R C^+ R^T`` (symbol ``~ |n|/(2 J*(n))``) with an
exact block elimination of ``s``.  The operator is not symmetric (only its
symmetric part is positive definite), hence GMRES and not conjugate gradients
(:mod:`bem._krylov`, with the free-panel solve where most panels are in contact).
A grid starts from the solved coarser one (`_prolong`), else from the elastic contact.
Just below full contact a step solves for the gaps of the free panels instead
(:mod:`bem._gap`, under load and under penetration control).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import scipy.fft as sfft

from . import _kernels
from ._edges import _patches, _runs
from ._gap import _gap_solve, _gap_solve_sep, _gap_step_tol
from ._influence import collocation_shifts, influence_coefficients_nd
from ._inputs import Prony
from ._layer import symbol_correction
from ._krylov import _dual_floor, _dual_solve, _keeps, _linear_solve, _with_retry
from ._operator import CirculantOperator
from ._result import (CONVERGED, CYCLED, KRYLOV_FAILED, MESSAGES, OUTER_EXHAUSTED,
                      WINDOW_FAILED)


#: first grid of the refinement sequence (coarser grids only ever gave a start)
START_NODES = 512
#: grids from which a mostly-in-contact step solves on the free panels (_dual_solve): there the
#: memory matters, and the separation it gives differs from the primal step's by ~1e-11
#: relative (rounding amplified by C^+), far below the discretisation error at such N; on
#: smaller grids the primal step, whose gaps meet the Krylov tolerance exactly, is kept
DUAL_MIN_NODES = 2 ** 19
#: ... and where its rounding floor (_dual_floor) is at most this fraction of the load: the
#: standard linear solid with E_inf/E0 = 3 up to 2^21 panels; stiffer materials, whose floor
#: reaches 1e-7 of the load and lets pressures of that size sit on free panels, keep the primal
DUAL_MAX_FLOOR = 2e-8
#: ... and at most this fraction of the load's deficit below the full-contact load
#: (`_full_contact_deficit`), the scale of the pressures next to the gap: 1.6 % below p_FC
#: (E_inf/E0 = 3, 2^19 panels) the floor is 1.1e-7 of it and the answer is right; 1e-6 below it
#: is 1.8e-3 and ka was 6e-7 off, jumping from grid to grid (the primal step's: 1e-9).  The
#: band within 1e-3 below p_FC keeps the primal step
DUAL_MAX_DEFICIT_FLOOR = 1e-6
#: near full contact the Krylov tolerance is tol times this times the load's deficit over the
#: load, where that is smaller (`_near_full_tol`) ...
NEAR_FULL_TOL_SCALE = 100.0
#: ... but at least this many machine epsilons of the 2-norm of the heights (over their scale):
#: 1e-13 at 2^19 panels was reached, at 2^20 GMRES stagnated
NEAR_FULL_TOL_FLOOR = 8.0
#: a cold start's Krylov tolerance (as tol) until its active set settles: the decisions of
#: those steps need no more (the paper's point at 2^20: 1e-5, 1e-6, 1e-7 take 169, 143, 175
#: FFT pairs; a tolerance relative to each step's first residual let it grow without bound
#: where the first steps were far off)
COLD_KRYLOV_TOL = 1e-6
#: ... and a patch end that retreats by m >= 2 panels in such a step retreats by this times m
#: more: from too wide a set, each step removes about 0.4 of the excess (the pressure of the
#: wider set crosses zero that far inside), so the plain rule needs ~log2(N) steps (18 at 2^20)
RETREAT_FACTOR = 1.0
#: free-panel steps on one grid after which a set that still changes is decided by the primal
#: step (from a converged coarser grid it settles in 1 or 2; at E_inf/E0 = 3, V/V0 = 0.01,
#: 4e-5 below the full-contact load, it wandered 13 steps at 2^21 before a set repeated)
DUAL_MAX_STEPS = 3
#: the gap step (`_gap_solve`) where the load lies at most this fraction of itself below the
#: grid's full-contact load: the contact is the period less a narrow gap, and the gaps, solved
#: for directly, keep their own relative precision (as differences C sigma - y + s they carry
#: the residual's rounding, 1e-12 h at 2^24 panels, against gaps of 1e-12 h 1e-8 below p_FC)
GAP_STEP_DEFICIT = 1e-2
#: the gap step's Krylov restart (its basis is of the free panels' size only)
GAP_STEP_RESTART = 40
#: the modes of the heights at most this many machine epsilons of sum |y_i| are their rounding
#: (`_full_contact_pressure`)
PROFILE_ROUNDOFF = 1.0
#: pressure (over its maximum) and gap (over h) treated as zero by the active-set rule
ACTIVE_SET_ROUNDOFF = 2e-13
#: ... and once the sets have cycled: just inside the validity gate's 1e-12
CYCLE_ROUNDOFF = 9e-13


class _Grid:
    def __init__(self, profile, material: Prony, speed: float, nodes: int, layer=None):
        self.n = nodes
        self.h = 1.0 / nodes
        column = influence_coefficients_nd(material.j_plus, material.terms, speed, nodes)
        correction = None
        if layer is not None:  # the half-space's symbol plus the layer's alias sum
            lengths = [speed * tau_i / (2.0 * math.pi) for _, tau_i in material.terms]
            shifts = collocation_shifts(self.h, material.j_plus, material.terms, lengths)
            correction = symbol_correction(layer, material.j_plus, material.terms, speed, nodes,
                                           shifts)
        self.op = CirculantOperator(column, correction)
        self.material = material
        self.layer = layer      # a bem.Layer, or None (the half-space)
        y = profile.sample(nodes)
        self.y = y - y.mean()  # rounding only: samples have zero mean
        self.amp = float(profile.amplitude)
        self.nodes = nodes      # panels per period
        self.scale = self.amp   # of the heights and gaps (the Krylov and active-set allowances)
        self.s_offset = 0.0     # the mean separation is s_offset + s
        self.window = False

    @property
    def x(self):
        """Panel centres X_j = j/N - 1/2, made when asked (not kept: memory at large N)."""
        return np.arange(self.n) / self.n - 0.5


def _full_contact_deficit(grid: _Grid, load):
    """How far the load lies below the grid's full-contact load, p_FC - load (units of the
    pressure): the full-contact pressure C^+ y + load has its minimum at load - p_FC.  Near
    full contact the pressures next to the gap are of this order, not of the load's: the
    free-panel step's rounding floor must be small against them too (1e-6 below p_FC, it left
    ka 6e-7 off and jumping from grid to grid at 2^19 ... 2^21, where the primal step's
    converged like N^-2)."""
    return _full_contact_pressure(grid, load)[1]


def _full_contact_pressure(grid: _Grid, load):
    """(p_full, deficit): the full-contact pressure C^+ y + load on every panel and
    `_full_contact_deficit`'s p_FC - load (at least 0).

    On the line's grids the modes of y at its rounding (at most PROFILE_ROUNDOFF eps sum|y_i|)
    are dropped first: C^+ multiplies them by up to max|1/symbol| (E_inf/E0 times the mode
    number), and the sampled sinusoid's rounding made pressures of 3e-9 at 2^22 panels
    (E_inf/E0 = 30.8), half the deficit 1.3e-8 below p_FC: noisy edges, the gap widening from
    grid to grid."""
    if isinstance(grid, _Grid):
        f = sfft.rfft(grid.y)
        f[np.abs(f) <= PROFILE_ROUNDOFF * np.finfo(float).eps * float(np.abs(grid.y).sum())] \
            = 0.0
        pfull = grid.op._through(f, True)
        del f
    else:
        pfull = grid.op.pseudo_solve(grid.y)
    pfull += load
    return pfull, max(-float(pfull.min()), 0.0)


def _near_full_tol(grid: _Grid, load, deficit, tol):
    """The Krylov tolerance of a grid near full contact: ``tol`` times NEAR_FULL_TOL_SCALE
    times the deficit over the load where that is smaller, but not below NEAR_FULL_TOL_FLOOR
    machine epsilons of the heights' 2-norm (what a residual's rounding allows).  The gaps
    and the pressures next to a narrow gap scale with the deficit; a residual of tol = 1e-10 h
    left ka jumping by 1e-6 from grid to grid 1e-6 below p_FC (E_inf/E0 = 3, V/V0 = 1, N =
    2^16 ... 2^21), against 1e-8 at 2^19 with 1e-13."""
    if deficit is None or not deficit < load:
        return tol
    floor = NEAR_FULL_TOL_FLOOR * np.finfo(float).eps * float(np.linalg.norm(grid.y)) \
        / grid.scale
    return min(tol, max(floor, tol * NEAR_FULL_TOL_SCALE * deficit / load))


@dataclass
class _Mode:
    """How the active-set iteration on one grid steps now (`_solve_grid`, `_judge`)."""

    loose: bool  # a cold start's inexact steps (COLD_KRYLOV_TOL), until the set settles
    dual: bool   # the free-panel step (`_dual_solve`) where most panels are in contact
    pfull: np.ndarray | None = None  # the full-contact pressure: the gap step (`_gap_solve`)
    # (under penetration control, at zero load: `_gap_solve_sep`)
    roundoff: float = ACTIVE_SET_ROUNDOFF  # the active-set rule's allowance
    seen: dict = field(default_factory=dict)  # key of each active set -> its outer step
    retreat: bool = True  # the cold start's sped-up retreat of runs (`_speed_up_retreat`)
    why: list = field(default_factory=list)  # a gap step's reason for failing (`_gap_solve_sep`)


def _solve_grid(grid: _Grid, load, sep, active, sigma0, s0, tol, max_outer, restart,
                max_inner, cold=False, widen=True, retreat=True):
    """Primal-dual active-set iteration on one grid.  ``cold``: the start is far from the
    answer (no coarser grid gave it): the Krylov solves stop at COLD_KRYLOV_TOL and retreats are
    sped up (`_speed_up_retreat`) until the active set settles; then every step is solved to
    tol, and only such steps decide convergence (``retreat``: with the line's sped-up retreat of
    runs; a surface has no runs).  ``widen``: a stagnated Krylov solve is tried
    once more with a wider restart (`_with_retry`).  Each outer step is a linear solve on the
    active set (`_step`) and the active-set rule's verdict on it (`_judge`)."""
    n = grid.n
    inner = []
    status, message = OUTER_EXHAUSTED, "outer iterations exhausted"
    relres = 0.0
    sigma = sigma0  # the caller's start, not used after
    s = s0
    gap = None  # of the current sigma, once solved for
    new = np.empty(n, dtype=np.bool_)
    # the free-panel step on a large grid, unless its rounding floor is a visible part of the
    # load (stiff materials, whose 1/symbol grows like E_inf/E0 times the mode number) or of
    # the pressures next to a gap near full contact
    pfull, deficit = (None, None) if load is None or grid.window else \
        _full_contact_pressure(grid, load)
    tol = _near_full_tol(grid, load, deficit, tol)
    # just below full contact the gaps are solved for directly (`_gap_solve`; the line's
    # periodic grids: a surface's free set is no arc)
    near = isinstance(grid, _Grid) and deficit is not None and \
        deficit <= GAP_STEP_DEFICIT * load
    if load is None and sep and isinstance(grid, _Grid) and not grid.window:
        # penetration control: near full contact when the start's load (a coarser grid's)
        # lies within GAP_STEP_DEFICIT of the grid's full-contact load
        pfull, p_fc = _full_contact_pressure(grid, 0.0)
        p0 = float(sigma0.mean())
        near = p0 > 0.0 and p_fc - p0 <= GAP_STEP_DEFICIT * p0
    mode = _Mode(loose=cold and COLD_KRYLOV_TOL > tol,
                 dual=(load is not None and n >= DUAL_MIN_NODES and not grid.window
                       and not near
                       and _dual_floor(grid) <= DUAL_MAX_FLOOR * load
                       and _dual_floor(grid) <= DUAL_MAX_DEFICIT_FLOOR * deficit),
                 pfull=pfull if near else None, retreat=retreat)
    # this grid's full-contact load (`_estimate`: is the load clear of its error?)
    pfc = None if pfull is None or load is None else load - float(pfull.min())
    del pfull
    for it in range(1, max_outer + 1):
        if not active.any():
            active = grid.y >= grid.y.max()  # at least the highest point touches
        if active.all() and load is None and sep != 0.0:
            active = grid.y > sep  # full contact needs s = 0; restart from the overlap
        if active.all() and grid.window:
            status, message = WINDOW_FAILED, "the contact fills its window"
            break
        held, gap = [gap], None  # memory: _step lets go of the old gaps before its solve
        sigma, s, its, relres, ok, gap = _step(
            grid, active, sigma, s, held, load, sep, mode,
            COLD_KRYLOV_TOL if mode.loose else tol, restart, max_inner, widen)
        inner.append(its)
        if not ok:
            status = KRYLOV_FAILED
            message = mode.why[0] if mode.why else (
                f"Krylov solve did not reach tol (residual {relres / grid.amp:.3e} h"
                + (f" = {relres / grid.scale:.3e} of the window's drop)"
                   if grid.window else ")"))
            break
        key, verdict = _judge(mode, active, sigma, gap, new, grid, it)
        if verdict is not None:
            status, message = verdict
            break
        if key is None:
            continue  # the inexact steps have settled: this set again, solved to tol
        mode.seen[key] = it
        active = new.copy()
    if gap is None:  # stopped before a solve (a window that its contact fills)
        gap = np.zeros(n)
    return {"sigma": sigma, "s": s, "active": active.copy(), "gap": gap, "nit": len(inner),
            "inner": inner, "relres": relres, "status": status, "message": message,
            "exact_gaps": mode.pfull is not None, "pfc": pfc}


def _step(grid: _Grid, active, sigma, s, held, load, sep, mode, tol, restart, max_inner,
          widen):
    """One outer step's linear solve on the active set: full contact directly, the gap step
    (``mode.pfull``: just below full contact), the free-panel step (``mode.dual``, most panels
    in contact), else the primal one on the contact panels.
    ``held``: a list holding the gaps of ``sigma`` (or None), emptied here (memory).
    Returns (sigma, s, Krylov iterations, relres, ok, gaps of the new sigma)."""
    gap = held.pop()
    n = grid.n
    product = None
    if active.all():
        # full contact: C sigma = y - s on every panel; mean(C sigma) = 0 gives s
        s = float(grid.y.mean()) if load is not None else 0.0
        sigma = grid.op.pseudo_solve(grid.y) + (load if load is not None else 0.0)
        its, relres, ok = 0, 0.0, True
    elif mode.pfull is not None and 2 * int(np.count_nonzero(active)) > n:
        # just below full contact: the gaps of the free panels are the unknowns; they come
        # back exact (zero on the contact), not as C sigma - y + s
        free = np.flatnonzero(~active).astype(np.int32)
        # the previous step's gaps start it (the grid's first step: from zero)
        x0 = None if gap is None or not mode.seen else gap[free].copy()
        gap = None
        rtol = COLD_KRYLOV_TOL if mode.loose else _gap_step_tol(grid, free.size)
        if load is None:  # penetration control: the load from the previous step's on
            p0 = float(sigma.mean())
            return _with_retry(
                lambda r: _gap_solve_sep(grid, free, mode.pfull, p0, sep, x0, rtol, r,
                                         max_inner, _keeps(r, free.size),
                                         settle=not mode.loose, why=mode.why),
                max(restart, min(GAP_STEP_RESTART, free.size)), free.size, widen)
        return _with_retry(
            lambda r: _gap_solve(grid, free, mode.pfull, x0, rtol, r, max_inner,
                                 _keeps(r, free.size)),
            max(restart, min(GAP_STEP_RESTART, free.size)), free.size, widen)
    elif mode.dual and 2 * int(np.count_nonzero(active)) > n:
        # most panels in contact on a large grid: solve for the displacements of the few
        # free panels instead (memory and work scale with the free set, not the contact)
        free = np.flatnonzero(~active).astype(np.int32)  # N < 2^31; memory
        if gap is None:
            gap = grid.op.apply(sigma) - grid.y + s
        x0 = gap[free] + grid.y[free]
        gap = None  # memory
        sigma, s, its, relres, ok, product = _with_retry(
            lambda r: _dual_solve(grid, free, load, x0, tol, r, max_inner), restart,
            free.size, widen)
    else:
        idx = np.flatnonzero(active).astype(np.int32)  # N < 2^31; memory
        x0 = sigma[idx]
        if load is not None:
            x0 = np.append(x0, s)
        gap = None  # memory
        sigma, s, its, relres, ok, product = _with_retry(
            lambda r: _linear_solve(grid, idx, load, sep, x0, tol, r, max_inner), restart,
            idx.size, widen)
    if product is None:
        gap = grid.op.apply(sigma) - grid.y + s
    else:  # C sigma from the Krylov solve's last product: the same numbers
        gap = product
        gap -= grid.y
        gap += s
        del product
    return sigma, s, its, relres, ok, gap


def _judge(mode: _Mode, active, sigma, gap, new, grid: _Grid, it):
    """The active-set rule after outer step ``it``, the next set into ``new``.  Returns (key,
    verdict): verdict (status, message) when the iteration stops (converged, or cycled), else
    None, with key that of the next set, or None when a cold start's inexact steps have just
    settled (the same set is then solved again, to tol)."""
    key = _next_active_set(active, sigma, gap, new, mode.roundoff, _gap_scale(mode, gap, grid))
    if mode.loose and (key is None or key in mode.seen):
        # the inexact steps have settled (or cycle): from here every step is solved to tol
        mode.loose = False
        mode.seen.clear()
        if key is None:
            return None, None
    if mode.loose and mode.retreat and key is not None and _speed_up_retreat(active, new):
        key = np.packbits(new).tobytes()
    if mode.dual and key is not None and (key in mode.seen or it >= DUAL_MAX_STEPS):
        # the free-panel steps do not settle: their pressures carry the rounding that C^+
        # amplifies, and near full contact (gaps of 1e-6 h) edge panels whose pressure is
        # below that flip back and forth; the primal step decides them from here on
        mode.dual = False
        mode.seen.clear()
    if key in mode.seen and mode.roundoff < CYCLE_ROUNDOFF:
        # the sets repeat: the panels that flip may all sit within the validity gate's
        # round-off (a stiff edge: 1e-2 of max σ one way, 1e-12 h of gap the other); judge
        # them with that allowance from here on (a second cycle is final)
        mode.roundoff = CYCLE_ROUNDOFF
        mode.seen.clear()
        key = _next_active_set(active, sigma, gap, new, mode.roundoff,
                               _gap_scale(mode, gap, grid))
    if key is None:
        if grid.window and (active[0] or active[-1]):
            return None, (WINDOW_FAILED, "the contact reaches an end of its window")
        return None, (CONVERGED, MESSAGES[CONVERGED] if mode.roundoff < CYCLE_ROUNDOFF else
                      "converged (at the validity gate's round-off, after a cycle)")
    if key in mode.seen:
        return key, (CYCLED, f"active set cycles (outer step {it} repeats step "
                             f"{mode.seen[key]})")
    return key, None


def _gap_scale(mode: _Mode, gap, grid: _Grid):
    """The scale of the gaps' round-off for the active-set rule: h (the heights' scale), or
    after a gap step, whose gaps are exact to their own precision, the deepest gap (1e-8
    below p_FC it is 1e-13 h: an allowance of 2e-13 h would keep interpenetrating panels
    free)."""
    if mode.pfull is None:
        return grid.scale
    return min(grid.scale, max(float(np.max(gap)), 0.0))


def _speed_up_retreat(active, new):
    """In a cold start's inexact steps: each end of a run of contact panels that the rule
    (`new`) retreats by m >= 2 panels retreats by RETREAT_FACTOR m more, keeping at least half
    of the panels the rule keeps in the run (panels that leave inside a run, and runs that grow,
    are left alone).  The steps that follow, solved to tol, correct any overshoot.  Returns
    whether `new` changed."""
    n = active.size
    if active.all() or not active.any():
        return False
    changed = False
    for first, length in _runs(active):
        ids = (first + np.arange(length)) % n
        keep = np.flatnonzero(new[ids])
        if keep.size == 0:
            continue
        lo, hi = int(keep[0]), int(keep[-1])  # panels lo .. hi of the run stay at its ends
        more = [int(RETREAT_FACTOR * m) if m >= 2 else 0 for m in (lo, length - 1 - hi)]
        cap = (hi - lo + 1) // 2
        if sum(more) > cap:
            more = [m * cap // sum(more) for m in more]
        if more[0] or more[1]:
            new[ids[lo:lo + more[0]]] = False
            new[ids[hi + 1 - more[1]:hi + 1]] = False
            changed = True
    return changed


def _next_active_set(active, sigma, gap, new, roundoff, amp):
    """The active-set rule into `new`, with allowances of `roundoff` times max σ and h (well
    inside the validity gate's 1e-12 of each); None when nothing changes, else a key of the
    new set."""
    changed = _kernels.update_active_set(active, sigma, gap, new,
                                         roundoff * float(np.max(sigma)), roundoff * amp)
    return None if changed == 0 else np.packbits(new).tobytes()


def _prolong(prev: dict, prev_grid: _Grid, grid: _Grid):
    """Active set, pressure and separation on a finer grid from a solved coarser one."""
    x, xc = grid.x, prev_grid.x  # made once here (the grids do not keep them)
    if prev["active"].all():
        active = np.ones(grid.n, dtype=np.bool_)
    else:
        active = np.zeros(grid.n, dtype=np.bool_)
        patches = prev.get("patches")  # measured by _level_scalars when the grid converged
        if patches is None:
            patches = _patches(prev["sigma"], prev["gap"], prev["active"], xc, prev_grid.h)
        for p in patches:
            xr = (x - p.trailing_edge) % 1.0
            active |= xr < (p.leading_edge - p.trailing_edge)
    if prev_grid.window:
        xp, sp = xc, prev["sigma"]  # zero at both ends: np.interp holds it beyond
    else:
        xp = np.concatenate((xc - 1.0, xc, xc + 1.0))
        sp = np.tile(prev["sigma"], 3)
    del xc
    sigma = np.interp(x, xp, sp) * active
    return active, sigma, prev["s"] + (prev_grid.s_offset - grid.s_offset)


def _clip_shift(sig, load):
    """The shift t >= 0 with mean((sig - t)_+) = load, for sig the full-contact pressure (mean
    load): clipped at zero it carries more than the load, and its set of positive panels is too
    wide; lowered by t it carries the load.  Newton's method on mean((sig - t)_+), convex and
    decreasing in t, from t = 0: each step stays short of the root (the tangent lies below),
    until the excess is round-off or a step no longer moves t."""
    t = 0.0
    floor = 4.0 * np.finfo(float).eps * float(np.max(np.abs(sig)))
    for _ in range(60):
        pos = sig > t
        excess = float(np.mean(np.where(pos, sig - t, 0.0))) - load
        slope = float(np.mean(pos))
        if excess <= 1e-12 * load or slope == 0.0:
            break
        step = excess / slope
        t += step
        if step <= floor:
            break
    return t


def _solve_one(grid, load, sep, start, tol, max_outer, restart, max_inner, elastic=None,
               widen=True, carry=False, prolong=None):
    """Solve one grid, started from the finest coarser grid (``start``: a list holding it or
    None, emptied here; ``prolong``: how a coarser grid's answer starts this one, `_prolong`
    for the line's, else a surface's, whose active set has no runs to speed up), or else from the elastic contact of ``elastic = (profile, an
    elastic Prony)`` on the same grid, or else from scratch: under load control from the
    full-contact pressure clipped at zero, lowered first (`_clip_shift`) with ``carry`` (the
    first try of nested=False) so that it carries the load."""
    best = start.pop() if start else None
    n = grid.n
    full = sig = None
    line = prolong is None
    prolong = _prolong if line else prolong
    # no coarser grid of the sequence gives the start: the active set has far to go
    # (a surface's steps are all inexact until its set settles: from a coarser grid its
    # interpolated edges move at every step)
    cold = (best is None and n > START_NODES) or not line
    if grid.window:  # started from a coarser grid always
        active, sigma0, s0 = prolong(best[0], best[1], grid)
        return _solve_grid(grid, load, sep, active, sigma0, s0, tol, max_outer, restart,
                           max_inner)
    if sep == 0.0:
        # Delta = h: full contact, whose load is not unique; return the smallest
        # one (the full-contact threshold, the limit of Delta -> h from below)
        sig = grid.op.pseudo_solve(grid.y)
        full = sig - float(sig.min())
    elif load is not None and (best is None or best[0]["active"].all()):
        # (from a coarser grid in partial contact this test is skipped, a transform pair
        # saved: should this grid be in full contact, its active-set steps reach it)
        sig = grid.op.pseudo_solve(grid.y) + load
        if sig.min() >= 0.0:  # full contact: no active-set iteration needed
            full = sig
    if full is not None:
        s = float(grid.y.mean())
        return {"sigma": full, "s": s, "active": np.ones(n, np.bool_),
                "gap": grid.op.apply(full) - grid.y + s, "nit": 1, "inner": [0],
                "relres": 0.0, "status": CONVERGED, "message": MESSAGES[CONVERGED],
                "pfc": None if sep == 0.0 or grid.window else load - float(full.min())}
    if best is None and elastic is not None:
        # no coarser grid: start from the elastic contact on this grid (a symmetric
        # positive-definite problem, on which the active-set method converges from anywhere)
        eg = _Grid(elastic[0], elastic[1], 0.0, n, grid.layer)
        er = _solve_one(eg, load, sep, [None], tol, max(max_outer, 50), restart, max_inner)
        if er["status"] == CONVERGED:
            best = (er, eg)
    if best is None:
        if load is not None:
            # sig: the full-contact test's pressure above (made whenever no coarser grid starts)
            if carry:
                sig = sig - _clip_shift(sig, load)
            active = sig > 0.0
            sigma0 = np.where(active, sig, 0.0)
        else:
            active = grid.y > sep  # the rigid overlap
            sigma0 = np.zeros(n)
        s0 = 0.0 if sep is None else sep
    else:
        active, sigma0, s0 = prolong(best[0], best[1], grid)
        best = None
        if sep is not None:
            s0 = sep
    return _solve_grid(grid, load, sep, active, sigma0, s0, tol, max_outer, restart, max_inner,
                       cold, widen, retreat=line)

