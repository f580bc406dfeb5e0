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
"""
from __future__ import annotations

import math
import numbers

import numpy as np

from . import _kernels
from ._influence import influence_coefficients_nd
from ._accepted import validate
from ._assemble import _patches, build_result
from ._inputs import Prony, Sinusoid, _Profile, _bad
from ._operator import CirculantOperator, gmres
from ._result import BemResult


# --------------------------------------------------------------------------
# One grid
# --------------------------------------------------------------------------
class _Grid:
    def __init__(self, profile, material: Prony, speed: float, nodes: int):
        self.n = nodes
        self.h = 1.0 / nodes
        self.x = np.arange(nodes) / nodes - 0.5
        self.op = CirculantOperator(
            influence_coefficients_nd(material.j_plus, material.terms, speed, nodes))
        y = profile.sample(nodes)
        self.y = y - y.mean()  # rounding only: samples have zero mean
        self.slope = profile.slope(nodes)
        self.amp = float(profile.amplitude)


def _restricted_inverse(op: CirculantOperator, idx: np.ndarray):
    n = op.n

    def apply(x):
        e = np.zeros(n)
        e[idx] = x
        return op.pseudo_solve(e)[idx]

    return apply


def _linear_solve(grid: _Grid, idx, load, sep, x0, tol, restart, max_inner):
    """Solve on the active set; returns (sigma_full, s, iterations, relres, ok)."""
    op = grid.op
    n = grid.n
    na = idx.size
    pinv = _restricted_inverse(op, idx)
    if load is not None:
        q = pinv(np.ones(na))
        beta = q.sum() / n

        def matvec(z):
            e = np.zeros(n)
            e[idx] = z[:na]
            out = np.empty(na + 1)
            out[:na] = op.apply(e)[idx] + z[na]
            out[na] = z[:na].sum() / n
            return out

        def precond(r):
            # block elimination of s with P = R C^+ R^T in place of C_AA^-1
            u = pinv(r[:na])
            t = (u.sum() / n - r[na]) / beta
            out = np.empty(na + 1)
            out[:na] = u - t * q
            out[na] = t
            return out

        b = np.append(grid.y[idx], load)
    else:
        def matvec(z):
            e = np.zeros(n)
            e[idx] = z
            return op.apply(e)[idx]

        precond = pinv
        b = grid.y[idx] - sep
    # tol bounds every entry of the residual: gaps (k v) on A and the load equation
    z, its, relres, ok = gmres(matvec, precond, b, x0, tol * grid.amp, restart, max_inner)
    sigma = np.zeros(n)
    sigma[idx] = z[:na]
    s = z[na] if load is not None else sep
    return sigma, s, its, relres, ok


def _solve_grid(grid: _Grid, load, sep, active, sigma0, s0, tol, max_outer, restart,
                max_inner):
    """Primal-dual active-set iteration on one grid."""
    n = grid.n
    seen = {}
    inner = []
    status, message = 1, "outer iterations exhausted"
    relres = 0.0
    sigma = sigma0.copy()
    s = s0
    gap = np.zeros(n)
    new = np.empty(n, dtype=np.bool_)
    for it in range(1, max_outer + 1):
        if not active.any():
            active = grid.y >= grid.y.max()  # at least the highest point touches
        if active.all() and load is None and sep != 0.0:
            active = grid.y > sep  # full contact needs s = 0; restart from the overlap
        if active.all():
            # full contact: C sigma = y - s on every panel; mean(C sigma) = 0 gives s
            s = float(grid.y.mean()) if load is not None else 0.0
            sigma = grid.op.pseudo_solve(grid.y) + (load if load is not None else 0.0)
            inner.append(0)
            relres = 0.0
            ok = True
        else:
            idx = np.flatnonzero(active)
            x0 = sigma[idx]
            if load is not None:
                x0 = np.append(x0, s)
            sigma, s, its, relres, ok = _linear_solve(grid, idx, load, sep, x0, tol,
                                                      restart, max_inner)
            inner.append(its)
        gap = grid.op.apply(sigma) - grid.y + s
        if not ok:
            status = 2
            message = f"Krylov solve did not reach tol (residual {relres / grid.amp:.3e} h)"
            break
        changed = _kernels.update_active_set(active, sigma, gap, new)
        if changed == 0:
            status, message = 0, "converged"
            break
        key = np.packbits(new).tobytes()
        if key in seen:
            status, message = 3, f"active set cycles (outer step {it} repeats step {seen[key]})"
            break
        seen[key] = it
        active = new.copy()
    return {"sigma": sigma, "s": s, "active": active.copy(), "gap": gap, "nit": len(inner),
            "inner": inner, "relres": relres, "status": status, "message": message}


def _prolong(prev: dict, prev_grid: _Grid, grid: _Grid):
    """Active set, pressure and separation on a finer grid from a solved coarser one."""
    if prev["active"].all():
        active = np.ones(grid.n, dtype=np.bool_)
    else:
        active = np.zeros(grid.n, dtype=np.bool_)
        for p in _patches(prev["sigma"], prev["gap"], prev["active"], prev_grid.x,
                               prev_grid.h):
            xr = (grid.x - p.trailing_edge) % 1.0
            active |= xr < (p.leading_edge - p.trailing_edge)
    xp = np.concatenate((prev_grid.x - 1.0, prev_grid.x, prev_grid.x + 1.0))
    sp = np.tile(prev["sigma"], 3)
    sigma = np.interp(grid.x, xp, sp) * active
    return active, sigma, prev["s"]


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


def solve(*, load=None, penetration=None, speed, profile=None, material=None, ratio=None,
          hk=None, nodes=4096, tol=1e-10, max_outer=50, nested=True, coarsest=256,
          level_ratio=4, restart=40, max_inner=600) -> BemResult:
    """Steady sliding of a rigid periodic indenter on a viscoelastic half-plane (eq. 2.4-2.5).

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
    nodes : int
        Panels per period, ``N >= 8``.
    tol : float
        Bound on the 2-norm of the residual of each Krylov solve, relative to the
        amplitude h k (so on every gap on the contact, in units of h, and on the
        load equation); default 1e-10.
    max_outer : int
        Active-set iterations per grid.
    nested : bool
        Solve on grids N/level_ratio^l first (down to ``coarsest`` panels).
    restart, max_inner : int
        GMRES restart length and iteration cap per linear solve.

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
    validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk,
             profile=profile, material=material, nodes=nodes)
    if profile is None:
        profile = Sinusoid(1.0 if hk is None else hk)
    elif hk is not None:
        raise _bad("hk", hk, f"no hk with profile={profile!r}: the profile fixes the amplitude")
    if material is None:
        material = Prony.standard_linear_solid(3.0 if ratio is None else ratio)
    elif ratio is not None:
        raise _bad("ratio", ratio, "no ratio with material=...: the Prony series fixes the moduli")
    if not isinstance(profile, _Profile):
        raise _bad("profile", profile, "a bem.Sinusoid, bem.Harmonics or bem.SampledProfile")
    if not isinstance(material, Prony):
        raise _bad("material", material, "a bem.Prony creep function")
    speed = _check_real("speed", speed, "a finite speed >= 0", lambda v: v >= 0.0)
    nodes = _check_positive_int("nodes", nodes, 8)
    if (load is None) == (penetration is None):
        raise _bad("load", load, "exactly one of load and penetration "
                   f"(got load={load!r}, penetration={penetration!r})")
    if load is not None:
        load = _check_real("load", load, "a finite mean pressure > 0", lambda v: v > 0.0)
    if penetration is not None:
        penetration = _check_real("penetration", penetration, "Delta/h in (0, 1]",
                                  lambda v: 0.0 < v <= 1.0)
    tol = _check_real("tol", tol, "a finite tolerance in (0, 0.01]", lambda v: 0.0 < v <= 1e-2)
    max_outer = _check_positive_int("max_outer", max_outer, 1)
    coarsest = _check_positive_int("coarsest", coarsest, 8)
    level_ratio = _check_positive_int("level_ratio", level_ratio, 2)
    restart = _check_positive_int("restart", restart, 1)
    max_inner = _check_positive_int("max_inner", max_inner, 1)

    amp = float(profile.amplitude)
    control, asked = ("load", load) if load is not None else ("penetration", penetration)
    sep = None if penetration is None else amp * (1.0 - penetration)

    fine = _Grid(profile, material, speed, nodes)
    full_start = None
    if sep == 0.0:
        # Delta = h: full contact, whose load is not unique; return the smallest
        # one (the full-contact threshold, the limit of Delta -> h from below)
        sig = fine.op.pseudo_solve(fine.y)
        full_start = sig - float(sig.min())
    elif load is not None:
        sig = fine.op.pseudo_solve(fine.y) + load
        if sig.min() >= 0.0:  # full contact: no active-set iteration needed
            full_start = sig
    if full_start is not None:
        res = {"sigma": full_start, "s": float(fine.y.mean()), "active": np.ones(nodes, np.bool_),
               "gap": fine.op.apply(full_start) - fine.y + float(fine.y.mean()), "nit": 1,
               "inner": [0], "relres": 0.0, "status": 0, "message": "converged"}
        return build_result(res, fine, profile, material, speed, amp, load,
                            [(nodes, 1, (0,))], asked=asked, control=control)

    sizes = [nodes]
    while nested and sizes[-1] // level_ratio >= coarsest:
        sizes.append(sizes[-1] // level_ratio)
    sizes.reverse()

    history = []
    prev = prev_grid = None
    for level, n in enumerate(sizes):
        final = level == len(sizes) - 1
        grid = fine if final else _Grid(profile, material, speed, n)
        # coarse grids only supply a starting active set: 1e-8 is plenty there
        level_tol = tol if final else max(tol, 1e-8)
        if prev is None:
            if load is not None:
                sig = grid.op.pseudo_solve(grid.y) + load
                active = sig > 0.0
                sigma0 = np.where(active, sig, 0.0)
            else:
                active = grid.y > sep  # the rigid overlap
                sigma0 = np.zeros(n)
            s0 = 0.0 if sep is None else sep
        else:
            # an unconverged coarse grid only gives a worse start
            active, sigma0, s0 = _prolong(prev, prev_grid, grid)
            if sep is not None:
                s0 = sep
        res = _solve_grid(grid, load, sep, active, sigma0, s0, level_tol, max_outer,
                          restart, max_inner)
        history.append((n, res["nit"], tuple(res["inner"])))
        prev, prev_grid = res, grid

    return build_result(prev, prev_grid, profile, material, speed, amp, load, history,
                        asked=asked, control=control)
