"""Contact solver: primal-dual active set outside, preconditioned GMRES inside.

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
symmetric part is positive definite), hence GMRES and not conjugate gradients.

Nested iteration: the problem is solved on grids N/4^l, ..., N/4, N; the
sub-panel contact edges of one grid give the active set on the next, so that
the finest grid usually needs two or three outer steps.

Contact window (light loads, adaptive mesh, load control, the sinusoid): once a periodic grid
has located a single patch narrower than 1/64 of the period, the refinement goes on in a
window of about six patch widths around it, a block of panels of a periodic grid too fine to be
made (up to 2^50 panels per period).  The operator there is the Toeplitz block of the periodic
one, with the same exact coefficients (``influence_coefficients_nd(..., span)``), and the
pressure is zero outside; heights and the separation are measured from the crest, so that gaps
of the size of Delta keep their digits.  A window whose contact reaches its ends, or that does
not meet the target, gives no answer: the periodic grids go on.
"""
from __future__ import annotations

import math
import numbers
import warnings

import numpy as np

from viscosine import DEFAULT_RTOL, ViscosineWarning

from . import _assemble, _kernels
from ._influence import influence_coefficients_nd
from ._accepted import MAX_NODES, validate
from ._assemble import (ROUNDOFF, _full_patch, _patches, _runs,
                        _window_friction, build_result, edge_lag_reach, edge_lags)
from ._inputs import Prony, Sinusoid, _bad
from ._operator import CirculantOperator, WindowOperator, gmres
from ._result import (CONVERGED, CYCLED, KRYLOV_FAILED, OUTER_EXHAUSTED, STATUS_TARGET,
                      BemResult)


#: status of a contact-window grid whose contact reaches the window's ends (never returned:
#: the adaptive mesh then answers from its periodic grids)
WINDOW_FAILED = 6


# --------------------------------------------------------------------------
# One grid
# --------------------------------------------------------------------------
class _Grid:
    def __init__(self, profile, material: Prony, speed: float, nodes: int):
        self.n = nodes
        self.h = 1.0 / nodes
        self.op = CirculantOperator(
            influence_coefficients_nd(material.j_plus, material.terms, speed, nodes))
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


class _WindowGrid:
    """A contact window: panels ``first .. first + count - 1`` of a grid of ``nodes`` panels per
    period that is never made (light loads: a contact of a few panels of the largest periodic
    grid spans thousands of these).  The operator is the Toeplitz block of the periodic one
    (exact coefficients, :class:`WindowOperator`); the pressure is zero off the window, whose
    ends must stay free.  Heights are measured from the crest, ``k y - h k = -2 h k sin^2(pi
    X)``, and the separation likewise (``s = h k + s_window``), so that gaps and Delta, whose
    size is that of the window's drop, not of h, keep their digits.  The sinusoid only.
    """

    window = True

    def __init__(self, profile, material: Prony, speed: float, nodes: int, first: int,
                 count: int):
        self.n = count
        self.nodes = nodes
        self.first = first
        self.profile, self.material, self.speed = profile, material, speed
        self.h = 1.0 / nodes
        #: the operator's pieces, kept for the friction (elastic, unshifted memory columns)
        self.columns = {}
        self.op = WindowOperator(influence_coefficients_nd(
            material.j_plus, material.terms, speed, nodes, (-count, 2 * count + 1),
            self.columns), _window_preconditioner(material, speed, count, nodes))
        #: the grid whose panels decide the friction's form (the window's first: one form for
        #: all the grids whose differences make the estimate)
        self.form_nodes = nodes
        self.amp = float(profile.amplitude)
        self.y = -2.0 * self.amp * np.sin(np.pi * self.x) ** 2
        self.s_offset = self.amp
        self.scale = float(-self.y.min())

    @property
    def x(self):
        """Panel centres X = (first + j)/nodes - 1/2 (exact: integers below 2^53)."""
        return (self.first + np.arange(self.n)) / self.nodes - 0.5

    def extended(self, margin: int) -> "_WindowGrid":
        """The same grid's window with `margin` more panels at each end (the gaps just beyond
        the window, where no pressure is, for the validity gate and the fields)."""
        return _WindowGrid(self.profile, self.material, self.speed, self.nodes,
                           self.first - margin, self.n + 2 * margin)


def _window_preconditioner(material: Prony, speed: float, count: int, nodes: int):
    """Symbol of the preconditioner of a window of `count` panels: the periodic operator of
    period Lambda = 2 count/nodes (twice the window) on 2 count panels, ``Lambda (2/k) J*(k /
    Lambda) sinc(pi k/(2 count))`` for mode k (the symbol of the periodic operator, lengths
    scaled by Lambda).  It has the window's singularity and memory on scales below the window;
    what differs (a constant, which the separation takes, and smooth low-rank parts) costs
    GMRES a few steps.  The truncated kernel's own circulant, by contrast, carries the jump of a
    long memory at its wrap: for E_inf/E0 = 1000 its inverse left GMRES stagnating.  Mode 0
    takes mode 1's value (any nonzero value serves)."""
    period = 2.0 * count / nodes
    k = np.arange(count + 1, dtype=float)
    k[0] = 1.0
    return period * (2.0 / k) * material.jstar(k / period, speed) * np.sinc(k / (2.0 * count))


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
    z, its, relres, ok = gmres(matvec, precond, b, x0, tol * grid.scale, restart, max_inner)
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
    z, its, res, ok = gmres(matvec, precond, b, x0, atol, restart, max_inner)
    u = grid.y.copy()
    u[free] = z
    del z
    sigma = op.pseudo_solve(u)
    sigma += load
    sigma[free] = 0.0
    s = float(u.mean())
    return sigma, s, its, res / load * grid.amp, ok, None


def _dual_floor(grid: _Grid):
    """The pressure error (units of the pressure) below which the free-panel step cannot go:
    C^+ amplifies the rounding of u by up to max|1/symbol|."""
    return 16.0 * np.finfo(float).eps * grid.op.max_inverse * grid.amp


def _solve_grid(grid: _Grid, load, sep, active, sigma0, s0, tol, max_outer, restart,
                max_inner, cold=False, widen=True):
    """Primal-dual active-set iteration on one grid.  ``cold``: the start is far from the
    answer (no coarser grid gave it): the Krylov solves stop at COLD_KRYLOV_TOL and retreats are
    sped up (`_speed_up_retreat`) until the active set settles; then every step is solved to
    tol, and only such steps decide convergence.  ``widen``: a stagnated Krylov solve is tried
    once more with a wider restart (`_with_retry`)."""
    n = grid.n
    seen = {}
    inner = []
    status, message = OUTER_EXHAUSTED, "outer iterations exhausted"
    relres = 0.0
    sigma = sigma0  # the caller's start, not used after
    s = s0
    gap = None  # of the current sigma, once solved for
    new = np.empty(n, dtype=np.bool_)
    roundoff = ACTIVE_SET_ROUNDOFF
    # the free-panel step on a large grid, unless its rounding floor is a visible part of the
    # load (stiff materials, whose 1/symbol grows like E_inf/E0 times the mode number)
    dual = (load is not None and n >= DUAL_MIN_NODES and not grid.window
            and _dual_floor(grid) <= DUAL_MAX_FLOOR * load)
    loose = cold and COLD_KRYLOV_TOL > tol
    for it in range(1, max_outer + 1):
        step_tol = COLD_KRYLOV_TOL if loose else tol
        if not active.any():
            active = grid.y >= grid.y.max()  # at least the highest point touches
        if active.all() and load is None and sep != 0.0:
            active = grid.y > sep  # full contact needs s = 0; restart from the overlap
        if active.all() and grid.window:
            status, message = WINDOW_FAILED, "the contact fills its window"
            break
        if active.all():
            # full contact: C sigma = y - s on every panel; mean(C sigma) = 0 gives s
            s = float(grid.y.mean()) if load is not None else 0.0
            sigma = grid.op.pseudo_solve(grid.y) + (load if load is not None else 0.0)
            inner.append(0)
            relres = 0.0
            ok = True
            product = None
        elif dual and 2 * int(np.count_nonzero(active)) > n:
            # most panels in contact on a large grid: solve for the displacements of the few
            # free panels instead (memory and work scale with the free set, not the contact)
            free = np.flatnonzero(~active).astype(np.int32)  # N < 2^31; memory
            if gap is None:
                gap = grid.op.apply(sigma) - grid.y + s
            x0 = gap[free] + grid.y[free]
            gap = None  # memory
            sigma, s, its, relres, ok, product = _with_retry(
                lambda r: _dual_solve(grid, free, load, x0, step_tol, r, max_inner), restart,
                free.size, widen)
            inner.append(its)
        else:
            idx = np.flatnonzero(active).astype(np.int32)  # N < 2^31; memory
            x0 = sigma[idx]
            if load is not None:
                x0 = np.append(x0, s)
            gap = None  # memory
            sigma, s, its, relres, ok, product = _with_retry(
                lambda r: _linear_solve(grid, idx, load, sep, x0, step_tol, r, max_inner), restart,
                idx.size, widen)
            inner.append(its)
        if product is None:
            gap = grid.op.apply(sigma) - grid.y + s
        else:  # C sigma from the Krylov solve's last product: the same numbers
            gap = product
            gap -= grid.y
            gap += s
            del product
        if not ok:
            status = KRYLOV_FAILED
            message = (f"Krylov solve did not reach tol (residual {relres / grid.amp:.3e} h"
                       + (f" = {relres / grid.scale:.3e} of the window's drop)"
                          if grid.window else ")"))
            break
        key = _next_active_set(active, sigma, gap, new, roundoff, grid.scale)
        if loose and (key is None or key in seen):
            # the inexact steps have settled (or cycle): from here every step is solved to tol
            loose = False
            seen.clear()
            if key is None:
                continue
        if loose and key is not None and _speed_up_retreat(active, new):
            key = np.packbits(new).tobytes()
        if dual and key is not None and (key in seen or it >= DUAL_MAX_STEPS):
            # the free-panel steps do not settle: their pressures carry the rounding that C^+
            # amplifies, and near full contact (gaps of 1e-6 h) edge panels whose pressure is
            # below that flip back and forth; the primal step decides them from here on
            dual = False
            seen.clear()
        if key in seen and roundoff < CYCLE_ROUNDOFF:
            # the sets repeat: the panels that flip may all sit within the validity gate's
            # round-off (a stiff edge: 1e-2 of max σ one way, 1e-12 h of gap the other); judge
            # them with that allowance from here on (a second cycle is final)
            roundoff = CYCLE_ROUNDOFF
            seen.clear()
            key = _next_active_set(active, sigma, gap, new, roundoff, grid.scale)
        if key is None:
            status, message = CONVERGED, ("converged" if roundoff < CYCLE_ROUNDOFF else
                                  "converged (at the validity gate's round-off, after a cycle)")
            if grid.window and (active[0] or active[-1]):
                status, message = WINDOW_FAILED, "the contact reaches an end of its window"
            break
        if key in seen:
            status, message = CYCLED, f"active set cycles (outer step {it} repeats step {seen[key]})"
            break
        seen[key] = it
        active = new.copy()
    if gap is None:  # stopped before a solve (a window that its contact fills)
        gap = np.zeros(n)
    return {"sigma": sigma, "s": s, "active": active.copy(), "gap": gap, "nit": len(inner),
            "inner": inner, "relres": relres, "status": status, "message": message}


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


# --------------------------------------------------------------------------
# Public entry
# --------------------------------------------------------------------------
def _check_positive_int(name, value, minimum):
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise _bad(name, value, f"an integer >= {minimum}")
    if value < minimum:
        raise _bad(name, value, f"an integer >= {minimum}")
    return int(value)


def _check_real(name, value, allowed, test):
    if isinstance(value, bool):
        raise _bad(name, value, allowed)
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise _bad(name, value, allowed) from None
    if not math.isfinite(v) or not test(v):
        raise _bad(name, value, allowed)
    return v


#: first grid of the refinement sequence (coarser grids only ever gave a start)
START_NODES = 512
#: the default cap of the adaptive mesh: the memory cap bem.MAX_NODES (2^24 where memory
#: allows, about 2.5 GB and a minute for that grid)
ADAPTIVE_MAX_NODES = MAX_NODES
#: active-set steps on a grid started from a converged coarser one (it usually needs 1 to 5)
MAX_OUTER_AFTER_CONVERGED = 15
#: the largest grid on which a failed solve is retried from the elastic contact
MAX_NODES_RETRY = 2 ** 21
#: up to this grid the retry gets all max_outer active-set steps (from the elastic contact
#: it may need 15-20), above it MAX_OUTER_AFTER_CONVERGED
MAX_NODES_FULL_RETRY = 2 ** 18
#: consecutive failed grids, none converged yet, after which the adaptive mesh gives up
MAX_FAILED_FROM_SCRATCH = 5
#: grids from which a mostly-in-contact step solves on the free panels (_dual_solve): there the
#: memory matters, and the separation it gives differs from the primal step's by ~1e-11
#: relative (rounding amplified by C^+), far below the discretisation error at such N; on
#: smaller grids the primal step, whose gaps meet the Krylov tolerance exactly, is kept
DUAL_MIN_NODES = 2 ** 19
#: ... and where its rounding floor (_dual_floor) is at most this fraction of the load: the
#: standard linear solid with E_inf/E0 = 3 up to 2^21 panels; stiffer materials, whose floor
#: reaches 1e-7 of the load and lets pressures of that size sit on free panels, keep the primal
DUAL_MAX_FLOOR = 2e-8
#: a cold start's Krylov tolerance (as tol) until its active set settles: the decisions of
#: those steps need no more (the paper's point at 2^20: 1e-5, 1e-6, 1e-7 take 169, 143, 175
#: FFT pairs; a tolerance relative to each step's first residual let it grow without bound
#: where the first steps were far off)
COLD_KRYLOV_TOL = 1e-6
#: ... and a patch end that retreats by m >= 2 panels in such a step retreats by this times m
#: more: from too wide a set, each step removes about 0.4 of the excess (the pressure of the
#: wider set crosses zero that far inside), so the plain rule needs ~log2(N) steps (18 at 2^20)
RETREAT_FACTOR = 1.0
#: nested=False tries the full-contact start with at most these active-set steps and Krylov
#: iterations per step, and no wider second try (the paper's point takes 9 steps of at most 7
#: at 2^20; E_inf/E0 = 1000 at V/V0 = 0.01 stagnated at 300 per step for 50 steps) before the
#: elastic start
COLD_DIRECT_STEPS = 20
COLD_DIRECT_INNER = 40
#: free-panel steps on one grid after which a set that still changes is decided by the primal
#: step (from a converged coarser grid it settles in 1 or 2; at E_inf/E0 = 3, V/V0 = 0.01,
#: 4e-5 below the full-contact load, it wandered 13 steps at 2^21 before a set repeated)
DUAL_MAX_STEPS = 3
#: restart length of the second try of a Krylov solve that stagnated with `restart` (the
#: default 8 can stagnate for E_inf/E0 in the hundreds; 40 has not been seen to)
KRYLOV_RETRY_RESTART = 40
#: memory bound of that second try's Krylov basis (40 vectors of 2^21 panels)
KRYLOV_RETRY_BYTES = 41 * 8 * 2 ** 21
#: pressure (over its maximum) and gap (over h) treated as zero by the active-set rule
ACTIVE_SET_ROUNDOFF = 2e-13
#: ... and once the sets have cycled: just inside the validity gate's 1e-12
CYCLE_ROUNDOFF = 9e-13
#: a single patch of at most this fraction of the period hands over to a contact window (its
#: grid is then at least 2^21/(6/64) = 2.2e7 panels per period, finer than the periodic cap;
#: and a stiff material's pressure relaxation layer, which the periodic grids resolve last, gets
#: tens of panels)
WINDOW_MAX_FRACTION = 1.0 / 64.0
#: panels of the first window level, and the most a window gets
WINDOW_START_PANELS = 1024
WINDOW_MAX_PANELS = 2 ** 21
#: the window spans at most this many (at least half as many) patch widths
WINDOW_SPAN = 6.0
#: the finest virtual grid of a window (positions j/nodes exact; panel values finite up to 2^52)
WINDOW_MAX_NODES = 2 ** 50
#: the error estimate is this factor times the first-order bound of the last differences
ESTIMATE_SAFETY = 1.5
#: a patch narrower than this many panels on the coarsest grid of an estimate is not resolved
MIN_PATCH_PANELS = 8
#: a Prony term's memory length w tau_i/(2 pi) (in wavelengths) is resolved from this many panels
MIN_MEMORY_PANELS = 4.0
#: what the edge fits' memory-lag correction (`edge_lags`) may leave of a term's first-order
#: edge shift, in the estimate's bound
LAG_RESIDUAL = 0.1
#: keys of the error estimate: relative for these, absolute for the others
RELATIVE_KEYS = ("penetration", "tau_f", "mu")
ESTIMATE_KEYS = ("contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu")


def solve(*, load=None, penetration=None, speed, profile=None, material=None, ratio=None,
          hk=None, nodes=None, rtol=None, max_nodes=None, tol=1e-10, max_outer=50,
          restart=8, max_inner=300, nested=True) -> BemResult:
    """Steady sliding of a rigid periodic indenter on a viscoelastic half-plane (eq. 2.4-2.5).

    The problem is solved on a sequence of grids N = 512, 1024, 2048, ... (each started from
    the contact of the previous one).  The differences between the scalars of the last three
    grids give an a-posteriori estimate of each scalar's discretisation error (see
    `error_estimate` of the result).  With ``nodes=None`` (the default) the sequence stops at
    the first grid whose estimate meets ``rtol``; with ``nodes`` it stops at that grid.

    Parameters
    ----------
    load : float, optional
        Mean pressure ``p (1 - nu^2)/E_ref > 0`` (load control).
    penetration : float, optional
        ``Delta/h`` in (0, 1] (penetration control; the load is an output).  At 1
        the contact is full and the load is not unique: the smallest one (the
        full-contact threshold) is returned.  Give exactly one of the two.
    speed : float
        ``w = V tau_ref k >= 0`` (``V/V0`` of the paper for the standard linear solid).
    profile : Sinusoid, Harmonics or SampledProfile, optional
        The indenter, ``k y`` over one period, crest of the sinusoid at X = 0; default
        ``Sinusoid(hk)``.
    material : Prony, optional
        Creep function (compliances in ``1/E_ref``, times in ``tau_ref``); default the
        standard linear solid with ``ratio``.
    ratio : float, optional
        ``E_inf/E0`` of the default standard linear solid (default 3); not with ``material``.
    hk : float, optional
        Amplitude of the default sinusoid (default 1); not with ``profile``.
    nodes : int, optional
        Panels per period (a power of two is not required): a fixed mesh.  Default: adaptive
        (whose ``result.nodes`` is, after a contact window, the panels per period of the
        window's grid, which may exceed ``max_nodes``; ``result.diagnostics["window"]`` then
        describes the window).
    rtol : float, optional
        Adaptive mesh only: the target of the estimated errors, relative for Delta/h and mu,
        absolute for ka and ke (the contact fraction times pi with several patches).
        Default 1e-6.
    max_nodes : int, optional
        Adaptive mesh only: the largest periodic grid (a power of two, up to
        ``bem.MAX_NODES``); default ``bem.MAX_NODES`` (2^24, or less where memory is smaller).
        A contact window has its own bound, 2^21 panels in the window.
        When the target is not met there, the result is not a success and says which
        estimate was reached.
    tol : float
        Bound on the 2-norm of the residual of each Krylov solve, relative to the
        amplitude h k (so on every gap on the contact, in units of h, and on the
        load equation); default 1e-10.
    max_outer : int
        Active-set iterations per grid.
    restart, max_inner : int
        GMRES restart length and iteration cap per linear solve.  A solve that stagnates is
        tried once more with a restart length of 40 (less where its basis would pass 690 MB).
    nested : bool
        With ``nodes``: solve the coarser grids first (their contact starts the next grid, and
        the last three give the error estimate).  False solves ``nodes`` alone, from the
        full-contact pressure clipped at zero (should that fail, once more from the relaxed
        elastic contact, then from the elastic contact with the first harmonic's compliance
        |J*|), with no estimate.  The adaptive
        mesh is always nested.

    Returns
    -------
    BemResult

    Raises
    ------
    ValueError
        On bad input, naming the parameter, its value and what is allowed.

    References
    ----------
    Eq. (2.2)-(2.5) (operator), (3.1) (friction), Appendix B (full contact).
    """
    if (load is None) == (penetration is None):
        raise _bad("load", load, "exactly one of load and penetration "
                   f"(got load={load!r}, penetration={penetration!r})")
    validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk,
             profile=profile, material=material, nodes=nodes, rtol=rtol, max_nodes=max_nodes)
    # validate has refused everything outside bem.ACCEPTED (and conflicting options)
    if profile is None:
        profile = Sinusoid(1.0 if hk is None else hk)
    if material is None:
        material = Prony.standard_linear_solid(3.0 if ratio is None else ratio)
    speed = float(speed)
    load = None if load is None else float(load)
    penetration = None if penetration is None else float(penetration)
    if nodes is not None:
        nodes = _check_positive_int("nodes", nodes, 8)
        for name, v in (("rtol", rtol), ("max_nodes", max_nodes)):
            if v is not None:
                raise _bad(name, v, f"nothing with nodes={nodes}: {name} steers the adaptive "
                           "mesh (nodes=None)")
    else:
        if nested is not True:
            raise _bad("nested", nested, "True without nodes (the adaptive mesh is nested)")
        rtol = DEFAULT_RTOL if rtol is None else float(rtol)
        max_nodes = ADAPTIVE_MAX_NODES if max_nodes is None else max(int(max_nodes), START_NODES)
    tol = _check_real("tol", tol, "a finite tolerance in (0, 0.01]", lambda v: 0.0 < v <= 1e-2)
    max_outer = _check_positive_int("max_outer", max_outer, 1)
    restart = _check_positive_int("restart", restart, 1)
    max_inner = _check_positive_int("max_inner", max_inner, 1)

    amp = float(profile.amplitude)
    control, asked = ("load", load) if load is not None else ("penetration", penetration)
    sep = None if penetration is None else amp * (1.0 - penetration)
    if nodes is not None:  # the fixed grid and the halvings below it down to START_NODES
        low = max(8, min(START_NODES // 2, nodes // 4))  # at least N/4 for an estimate
        sizes = [nodes]
        while nested and sizes[-1] % 2 == 0 and sizes[-1] // 2 >= low:
            sizes.append(sizes[-1] // 2)
        sizes.reverse()
    else:
        sizes = []
        n = START_NODES
        while n <= max_nodes:
            sizes.append(n)
            n *= 2
    levels = []      # one entry per grid: (nodes, nit, inner iterations, status)
    scalars = []     # (nodes, dict of scalars) of the converged grids, coarse to fine
    best = None      # (res, grid) of the finest converged grid
    estimate = None
    reason = None
    note = None      # what the estimate carries for unresolved memory lengths
    reached = None
    failed = 0
    good = None      # (res, grid) of the finest converged grid
    window = None    # what the contact window gave, once tried
    harmonic = (profile, Prony(abs(complex(material.jstar([1.0], speed)[0]))))
    for n in sizes:
        grid = _Grid(profile, material, speed, n)
        steps = max_outer if good is None else min(max_outer, MAX_OUTER_AFTER_CONVERGED)
        elastic = (profile, Prony(material.J0))
        # the coarser grid is handed over in a list that _solve_one empties, so that it is
        # freed once it has given its start (memory at large N)
        start, best, last, res = [best], None, None, None
        if nodes is not None:
            good = None  # a fixed mesh answers on its own grid or not at all
        # nested=False: first from the full-contact pressure clipped at zero, with few Krylov
        # steps each (where the operator is far from normal, a stiff material at low speed,
        # they stagnate from there); then, as any grid that fails, from the elastic contact
        direct = not nested and START_NODES < n <= MAX_NODES_RETRY
        if direct:
            res = _solve_one(grid, load, sep, start, tol, min(steps, COLD_DIRECT_STEPS),
                             restart, min(max_inner, COLD_DIRECT_INNER), widen=False)
        else:
            res = _solve_one(grid, load, sep, start, tol, steps, restart, max_inner,
                             elastic=elastic)
        if res["status"] != CONVERGED and (levels[:-1] or direct) and n <= MAX_NODES_RETRY:
            # the coarser contact can be a poor start where the finer grid first resolves a
            # memory length; try once more from the elastic contact on this grid (not on the
            # largest grids, where a failing retry costs minutes)
            retry = _solve_one(grid, load, sep, [None], tol,
                               max_outer if n <= MAX_NODES_FULL_RETRY else steps, restart,
                               max_inner, elastic=elastic)
            if retry["status"] == CONVERGED or good is None:
                res = retry
        if res["status"] != CONVERGED and not levels and harmonic != elastic:
            # the first grid failed from the relaxed contact: try from the elastic contact with
            # the compliance |J*| of the first harmonic at this speed, near the glassy one at
            # high speed (from the relaxed contact a stiff material at high speed shrinks its
            # contact by one panel per active-set step and runs out of steps on every grid).
            # Only there: on a finer grid the coarser contact is the better start
            retry = _solve_one(grid, load, sep, [None], tol, max_outer, restart, max_inner,
                               elastic=harmonic)
            if retry["status"] == CONVERGED:
                res = retry
        levels.append((n, res["nit"], tuple(res["inner"]), res["status"]))
        last = (res, grid)
        # an unconverged grid still gives the next one a better start than none
        best = (res, grid)
        if res["status"] != CONVERGED:
            failed += 1
            if nodes is None and failed >= (2 if scalars else MAX_FAILED_FROM_SCRATCH):
                # two finer grids in a row failed after a converged one (or the first few
                # grids all failed): refining further only costs more, each failed grid
                # running all its active-set steps
                reason = (f"the solve did not converge on N={levels[-failed][0]} … N={n} "
                          f"({res['message']})")
                break
            continue
        failed = 0
        good = (res, grid)
        scalars.append((n, _level_scalars(res, grid, profile, material, speed, amp)))
        estimate, reason, note = _estimate(scalars, material, speed)
        if nodes is None and reason is None and _met(estimate, scalars[-1][1], rtol):
            reached = n
            break
        if nodes is None and window is None and _window_wanted(load, profile, scalars[-1][1]):
            window = _window_refine(res, grid, profile, material, speed, load, rtol, tol,
                                    max_outer, restart, max_inner)
            if window["reached"]:
                wres, wgrid = window["res"], window["grid"]
                answer = build_result(wres, wgrid, profile, material, speed, amp, load,
                                      levels + window["levels"], asked=asked, control=control,
                                      error_estimate=window["estimate"], rtol=rtol,
                                      extra_diagnostics={"window": window["summary"]})
                if answer.success:
                    return _announced(answer)
                window["summary"]["outcome"] = answer.message
            # the window gave no answer: the periodic grids go on as without it
            window["res"] = window["grid"] = None  # memory
    res, grid = last
    if nodes is None and reached is None and good is not None:
        # the finest converged grid, flagged: its estimate did not meet the target
        res, grid = good
        res = dict(res)
        res["status"] = STATUS_TARGET
        shown = "no estimate" if estimate is None else "estimated errors " + ", ".join(
            f"{k}={v:.2e}" for k, v in estimate.items() if v is not None)
        stop = "max_nodes" if levels[-1][0] == max_nodes else f"refinement stopped at N={levels[-1][0]}"
        res["message"] = (f"accuracy target rtol={rtol:g} not reached (finest converged grid "
                          f"N={grid.n}, {stop}): {reason + '; ' if reason else ''}{shown}")
    if nodes is not None and reason is not None:
        estimate = None  # the grids below a fixed one do not resolve the contact: no estimate
    shown_note = "; ".join(t for t in (reason, note) if t)
    extra = {"estimate_note": shown_note} if shown_note else {}
    if window is not None:
        extra["window"] = window["summary"]
    return _announced(build_result(res, grid, profile, material, speed, amp, load, levels,
                                   asked=asked, control=control, error_estimate=estimate,
                                   rtol=rtol if nodes is None else None,
                                   extra_diagnostics=extra or None))


def _announced(result):
    """The result, its warnings raised as `viscosine.ViscosineWarning` (a Python caller sees
    what the command line prints; they stay in ``result.warnings``)."""
    for text in result.warnings:
        warnings.warn(text, ViscosineWarning, stacklevel=3)
    return result


def _window_wanted(load, profile, values):
    """Whether a converged periodic grid hands over to a contact window: load control, the
    sinusoid, one patch of at most WINDOW_MAX_FRACTION of the period, located to within a few
    panels (at least MIN_PATCH_PANELS of them)."""
    return (load is not None and isinstance(profile, Sinusoid) and values["npatch"] == 1
            and values["contact_fraction"] <= WINDOW_MAX_FRACTION
            and values["min_panels"] >= MIN_PATCH_PANELS)


def _window_refine(res, pgrid, profile, material, speed, load, rtol, tol, max_outer,
                   restart, max_inner):
    """Refine a contact window until its estimate meets rtol (light loads).

    The window is centred on the patch of the periodic grid ``pgrid`` and spans
    WINDOW_SPAN (at least half that) times its width: panels ``first .. first + n - 1`` of a
    virtual grid of ``nodes = 2^k`` panels per period, with n = WINDOW_START_PANELS, 2n, ...
    up to WINDOW_MAX_PANELS (the same interval on every level, ``nodes`` doubling with n).
    Each level starts from the one before (the first from ``pgrid``); the estimate is that of
    the periodic grids (:func:`_estimate`) on the window's levels.  Returns a dict: ``reached``
    (the target met on a converged window whose contact keeps off its ends), ``res``, ``grid``,
    ``estimate``, ``levels`` (nodes per period, active-set steps, inner iterations, status)
    and ``summary`` (for the diagnostics).
    """
    patch = res["patches"][0]
    width = patch.width
    centre = 0.5 * (patch.trailing_edge + patch.leading_edge)
    n = WINDOW_START_PANELS
    nodes = 1 << max(0, math.ceil(math.log2(n / (WINDOW_SPAN * width))))
    first = int(round((centre + 0.5) * nodes - 0.5 * n))
    start = (res, pgrid)
    scalars, levels = [], []
    out = {"reached": False, "res": None, "grid": None, "estimate": None, "levels": levels}
    note = "not converged"
    grid = None
    finest = nodes * (WINDOW_MAX_PANELS // n)
    if finest > WINDOW_MAX_NODES or \
            ESTIMATE_SAFETY * _unresolved_memory(material, speed, finest,
                                                WINDOW_MAX_PANELS) > rtol:
        # the edge shift of the memory lengths the finest window grid leaves unresolved is
        # above the target on its own (a speed near 0): the periodic grids go on
        n = 2 * WINDOW_MAX_PANELS
        note = "not tried: a memory length stays unresolved on the finest window grid"
    while n <= WINDOW_MAX_PANELS and nodes <= WINDOW_MAX_NODES:
        grid = _WindowGrid(profile, material, speed, nodes, first, n)
        grid.coarse = pgrid
        if levels:
            grid.form_nodes = levels[0][0]  # one friction form per window
        wres = _solve_one(grid, load, None, [start], tol, max_outer, restart, max_inner)
        levels.append((nodes, wres["nit"], tuple(wres["inner"]), wres["status"]))
        if wres["status"] != CONVERGED:
            note = wres["message"]
            break
        values = _level_scalars(wres, grid, profile, material, speed, grid.amp)
        if values["npatch"] != 1:
            note = f"{values['npatch']} patches in the window"
            break
        scalars.append((nodes, values))
        estimate, reason, _ = _estimate(scalars, material, speed)
        out.update(res=wres, grid=grid, estimate=estimate)
        note = reason or "estimate above rtol"
        if reason is None and _met(estimate, values, rtol):
            out["reached"] = True
            note = "target met"
            break
        start = (wres, grid)
        n, nodes, first = 2 * n, 2 * nodes, 2 * first
    ends = grid.x[[0, -1]] if grid is not None else (None, None)
    out["summary"] = {"from_x_over_lambda": None if grid is None else float(ends[0]),
                      "to_x_over_lambda": None if grid is None else float(ends[1]),
                      "panels": 0 if grid is None else grid.n, "coarse_nodes": pgrid.n,
                      "outcome": note, "levels": [list(lv) for lv in levels]}
    return out


def _solve_one(grid, load, sep, start, tol, max_outer, restart, max_inner, elastic=None,
               widen=True):
    """Solve one grid, started from the finest coarser grid (``start``: a list holding it or
    None, emptied here), or else from the elastic contact of ``elastic = (profile, an
    elastic Prony)`` on the same grid, or else from scratch."""
    best = start.pop() if start else None
    n = grid.n
    full = None
    # no coarser grid of the sequence gives the start: the active set has far to go
    cold = best is None and n > START_NODES
    if grid.window:  # started from a coarser grid always
        active, sigma0, s0 = _prolong(best[0], best[1], grid)
        return _solve_grid(grid, load, sep, active, sigma0, s0, tol, max_outer, restart,
                           max_inner)
    if sep == 0.0:
        # Delta = h: full contact, whose load is not unique; return the smallest
        # one (the full-contact threshold, the limit of Delta -> h from below)
        sig = grid.op.pseudo_solve(grid.y)
        full = sig - float(sig.min())
    elif load is not None:
        sig = grid.op.pseudo_solve(grid.y) + load
        if sig.min() >= 0.0:  # full contact: no active-set iteration needed
            full = sig
    if full is not None:
        s = float(grid.y.mean())
        return {"sigma": full, "s": s, "active": np.ones(n, np.bool_),
                "gap": grid.op.apply(full) - grid.y + s, "nit": 1, "inner": [0],
                "relres": 0.0, "status": CONVERGED, "message": "converged"}
    if best is None and elastic is not None:
        # no coarser grid: start from the elastic contact on this grid (a symmetric
        # positive-definite problem, on which the active-set method converges from anywhere)
        eg = _Grid(elastic[0], elastic[1], 0.0, n)
        er = _solve_one(eg, load, sep, [None], tol, max(max_outer, 50), restart, max_inner)
        if er["status"] == CONVERGED:
            best = (er, eg)
    if best is None:
        if load is not None:
            sig = grid.op.pseudo_solve(grid.y) + load
            active = sig > 0.0
            sigma0 = np.where(active, sig, 0.0)
        else:
            active = grid.y > sep  # the rigid overlap
            sigma0 = np.zeros(n)
        s0 = 0.0 if sep is None else sep
    else:
        active, sigma0, s0 = _prolong(best[0], best[1], grid)
        best = None
        if sep is not None:
            s0 = sep
    return _solve_grid(grid, load, sep, active, sigma0, s0, tol, max_outer, restart, max_inner,
                       cold, widen)


def _level_scalars(res, grid, profile, material, speed, amp):
    """The scalars of one converged grid (for the estimate): plain floats, None where null."""
    sigma = res["sigma"]
    active = res["active"]
    if grid.window:
        tau_f = _window_friction(sigma, grid, material, speed)
        mean_p = float(sigma.sum()) / grid.nodes
        res["friction"] = (tau_f, None)  # build_result's, should this grid be the answer
    else:
        res["friction"] = _assemble._friction(sigma, grid.y, material, speed)
        tau_f = res["friction"][0]
        mean_p = float(sigma.mean())
    out = {"penetration": (amp - grid.s_offset - float(res["s"])) / amp, "tau_f": tau_f,
           "mu": tau_f / mean_p if mean_p > 0 else math.nan,
           # the gaps' round-off that the validity gate allows, over h (ROUNDOFF of the scale)
           "gap_roundoff": ROUNDOFF * (grid.scale / amp),
           "panels": grid.n}
    if active.all():
        p = _full_patch(sigma, grid.y, profile, mean_p)
        out.update(contact_fraction=1.0, ka=math.pi, ke=None, ke_hat=p.ke_hat, npatch=1,
                   min_panels=grid.n)
        return out
    patches = _patches(sigma, res["gap"], active, grid.x, grid.h, profile, grid.y, grid.window,
                       edge_lags(material, speed, grid.h, grid.n))
    res["patches"] = patches  # the next grid's start needs their edges too
    frac = float(sum(p.width for p in patches))
    out.update(contact_fraction=frac, npatch=len(patches),
               min_panels=min(p.panels for p in patches))
    if len(patches) == 1:
        p = patches[0]
        out.update(ka=p.ka, ke=p.ke, ke_hat=p.ke_hat)
    else:
        out.update(ka=None, ke=None, ke_hat=None)
    return out


def _unresolved_memory(material, speed, nodes, panels=None):
    """Bound on the contact-edge error of the Prony terms whose memory length
    ``L_i = w tau_i/(2 pi)`` (wavelengths) spans fewer than MIN_MEMORY_PANELS panels of `nodes`
    (``panels``: the panels the edge fits see, when not a period's, as for `edge_lags`).

    A grid that does not resolve ``L_i`` misses the inner layer of the term at the contact
    edges, whose effect on the edges is first order in ``L_i``: ``pi L_i J_i/(J_i + J_loc)`` on
    ka and ke, with ``J_loc = J(0+) + sum of J_j over the terms of shorter memory`` (what acts at
    once on the scale ``L_i``).  For the standard linear solid this is ``(1 - 1/rho) w/2``, the
    first-order retreat of the trailing edge at low speed.  The edge fits correct it for the
    terms far below the fitted distances (`edge_lags`): their part of the bound is
    LAG_RESIDUAL of it (measured on the standard linear solid against the semi-analytic road,
    N = 512 ... 65536, E_inf/E0 = 3 and 1000: at most 0.083 of the first-order shift is left,
    against all of it without the correction).  The others (up to MIN_MEMORY_PANELS panels)
    keep it whole.  The bound is carried by the estimate; it is not a reason to refine.
    """
    h = 1.0 / nodes
    corrected = edge_lag_reach(h, nodes if panels is None else panels)
    bound = 0.0
    j_loc = material.j_plus
    for j, t in sorted(material.terms, key=lambda jt: jt[1]):
        length = speed * t / (2.0 * math.pi)
        if j > 0.0 and length < MIN_MEMORY_PANELS * h:
            share = LAG_RESIDUAL if length <= corrected else 1.0
            bound += share * math.pi * length * j / (j + j_loc)
        j_loc += j
    return bound


def _estimate(scalars, material, speed):
    """A-posteriori error estimate from the last converged grids N/8 (when there), N/4, N/2, N.

    Each scalar q is assumed to converge at least at first order in 1/N, so the error of q_N is
    bounded by |q_N - q_N/2| and, against accidentally small differences (the edges' position in
    their panels makes the errors oscillate: two grids can agree by chance), by
    |q_N - q_N/2^j|/2^(j-1) and |q_N/2^(j-1) - q_N/2^j|/2^(j-1) for j = 2, 3; the estimate is
    ESTIMATE_SAFETY times the largest (relative to |q_N| for Delta/h, tau_f and mu).  Delta/h
    adds ESTIMATE_SAFETY times the validity gate's round-off of a gap (1e-12 h), below which no
    separation is certified (measured: 2.6e-13 h at Delta/h = 4.6e-4, where the grids agreed
    to 7e-14 h).  Returns
    (estimate, reason, note): reason is None when the grids resolve the contact, else why the
    estimate is not trusted yet; note says what the estimate includes for the memory lengths
    the grids do not resolve (None when they resolve them all, or when every grid of the run is
    in full contact: no edges, no inner layers).
    """
    if len(scalars) < 3:
        return None, "fewer than three converged grids", None
    run = [scalars[-1]]
    for n, sc in reversed(scalars[:-1]):
        if len(run) == 4 or n * 2 != run[-1][0]:
            break
        run.append((n, sc))
    if len(run) < 3:
        return None, "no three consecutive converged grids", None
    counts = {sc["npatch"] for _, sc in run}
    if len(counts) > 1:
        return None, ("the number of contact patches changes with N (" +
                      ", ".join(str(sc["npatch"]) for _, sc in reversed(run)) + ")"), None
    est = {}
    for k in ESTIMATE_KEYS:
        vals = [sc[k] for _, sc in run]  # fine to coarse
        if any(v is None for v in vals):
            est[k] = None
            continue
        cands = [abs(vals[0] - vals[1])]
        for j in range(2, len(vals)):
            w = 0.5 ** (j - 1)
            cands += [w * abs(vals[0] - vals[j]), w * abs(vals[j - 1] - vals[j])]
        e = ESTIMATE_SAFETY * max(cands)
        if k == "penetration":
            # the validity gate counts gaps within ROUNDOFF of their scale (h; a window's drop)
            # as zero: the separation is not certified below that, whatever the grids agree to
            # (it shows where Delta/h is small)
            e += ESTIMATE_SAFETY * max(sc["gap_roundoff"] for _, sc in run)
        if k in RELATIVE_KEYS:
            scale = abs(vals[0])
            e = e / scale if scale > 0 else (0.0 if e == 0 else math.inf)
        est[k] = e
    reason = None
    n0, a = run[min(2, len(run) - 1)]  # N/4: the coarsest grid every estimate uses
    if a["min_panels"] < MIN_PATCH_PANELS:
        reason = f"a contact patch spans {a['min_panels']} panels at N={n0} " \
                 f"(at least {MIN_PATCH_PANELS} are needed)"
    # full contact has no edges, hence no inner layers: a single harmonic per mode, which the
    # exact panel coefficients give to O(1/N^2) whatever the memory lengths (Appendix B)
    full = all(sc["contact_fraction"] == 1.0 for _, sc in run)
    shift = 0.0 if full else _unresolved_memory(material, speed, n0, a.get("panels"))
    note = None
    if shift > 0.0:
        for k in est:
            if est[k] is not None:
                est[k] += ESTIMATE_SAFETY * shift
        note = (f"a memory length w tau_i/(2 pi) spans fewer than {MIN_MEMORY_PANELS:g} "
                f"panels at N={n0}: its edge shift, up to {shift:.1e}, is in the estimate")
    return est, reason, note


def _met(estimate, values, rtol):
    """Whether the estimate meets rtol on mu, Delta/h (relative) and ka, ke (absolute; the
    contact fraction times pi where several patches leave ka and ke undefined)."""
    keys = ["mu", "penetration"]
    keys += ["ka", "ke"] if values["npatch"] == 1 else ["contact_fraction"]
    for k in keys:
        e = estimate.get(k)
        if e is None:
            if k == "ke" and values["ke"] is None:  # full contact: no ke
                continue
            return False
        if k == "contact_fraction":
            e = math.pi * e
        if not e <= rtol:
            return False
    return True
