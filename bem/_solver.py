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
from ._inputs import Prony, Sinusoid, _Profile, _bad
from ._operator import CirculantOperator, gmres
from ._result import BemResult, Patch


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


# --------------------------------------------------------------------------
# Contact patches and sub-panel edges
# --------------------------------------------------------------------------
def _runs(active: np.ndarray) -> list[tuple[int, int]]:
    """Cyclic runs of active panels as (first index, length)."""
    n = active.size
    if active.all():
        return [(0, n)]
    if not active.any():
        return []
    start = int(np.flatnonzero(~active)[0])  # rotate so that index `start` is free
    rolled = np.roll(active, -start)
    d = np.diff(np.concatenate(([0], rolled.astype(np.int8), [0])))
    firsts = np.flatnonzero(d == 1)
    lasts = np.flatnonzero(d == -1)
    return [((int(f) + start) % n, int(l - f)) for f, l in zip(firsts, lasts)]


def _root_near_zero(pos, vals, deg):
    """Real root nearest 0 of the least-squares polynomial of degree deg through (pos, vals)."""
    scale = float(np.max(np.abs(pos)))
    c = np.polynomial.polynomial.polyfit(pos / scale, vals, deg)
    roots = np.polynomial.polynomial.polyroots(c)
    roots = roots[np.abs(roots.imag) < 1e-9].real * scale
    if roots.size == 0:
        return None
    return float(roots[np.argmin(np.abs(roots))])


def _edge_offset(inside_sq, outside_23, h, nodes):
    """Offset of a contact edge beyond the centre of the last contact panel.

    inside_sq[m] = sigma^2 at the m-th contact panel counted inward from the edge
    (m = 0 is the last one, at offset -m h); outside_23[m] = gap^(2/3) at the m-th
    free panel outward (offset (m + 1) h).  Near an edge sigma ~ d^(1/2) and
    gap ~ d^(3/2) with analytic corrections, so sigma^2 and gap^(2/3) are analytic
    with a simple zero at the edge.  The panels right at the edge carry an O(1)
    relative discretisation error that does not shrink with h, so each is fitted
    by a cubic over panels at distances sqrt(N)/16 .. sqrt(N)/2 (growing with N,
    shrinking in wavelengths), and the two zeros are averaged.  Measured on
    Westergaard's solution the error then falls like N^-1.6 (see the tests).
    Short patches or gaps fall back to fewer points, and finally to extrapolating
    sigma^2 linearly from the last two contact panels.
    """
    m1 = max(1, int(round(math.sqrt(nodes) / 16.0)))
    m2 = max(m1 + 6, int(round(math.sqrt(nodes) / 2.0)))
    est = []
    for vals, sign, shift in ((inside_sq, -1.0, 0.0), (outside_23, 1.0, 1.0)):
        avail = vals.size
        lo, hi = m1, min(m2, avail - 1)
        if hi - lo < 5:
            lo, hi = 0, min(m2, avail - 1)
        if hi - lo < 3:
            continue
        m = np.arange(lo, hi + 1)
        deg = 3 if hi - lo >= 5 else 2
        root = _root_near_zero(sign * (m + shift) * h, vals[m], deg)
        if root is not None and -h <= root <= 2.0 * h:
            est.append(root)
    if est:
        return min(max(sum(est) / len(est), -0.5 * h), 1.5 * h)
    if inside_sq.size >= 2 and inside_sq[1] > inside_sq[0]:
        return min(h, h * inside_sq[0] / (inside_sq[1] - inside_sq[0]))
    return 0.5 * h


def _patch_edges(sigma, gap, first, length, free_after, free_before, x, h):
    """(trailing, leading) edges of one patch, unwrapped so that leading > trailing."""
    n = sigma.size
    last = first + length - 1
    half = (length - 1) // 2 + 1
    ins_lead = sigma[(last - np.arange(half)) % n] ** 2
    ins_trail = sigma[(first + np.arange(half)) % n] ** 2
    out_lead = np.abs(gap[(last + 1 + np.arange(max(free_after // 2, 0))) % n]) ** (2.0 / 3.0)
    out_trail = np.abs(gap[(first - 1 - np.arange(max(free_before // 2, 0))) % n]) ** (2.0 / 3.0)
    x_first = x[first]
    x_last = x_first + (length - 1) * h
    lead = x_last + _edge_offset(ins_lead, out_lead, h, n)
    trail = x_first - _edge_offset(ins_trail, out_trail, h, n)
    return trail, lead


def _patches(sigma, gap, active, x, h):
    out = []
    n = sigma.size
    runs = _runs(active)
    for i, (first, length) in enumerate(runs):
        nxt_first = runs[(i + 1) % len(runs)][0]
        prv_first, prv_len = runs[i - 1]
        free_after = (nxt_first - (first + length)) % n
        free_before = (first - (prv_first + prv_len)) % n
        if len(runs) == 1:
            free_after = free_before = n - length
        trail, lead = _patch_edges(sigma, gap, first, length, free_after, free_before, x, h)
        shift = -math.floor(0.5 * (trail + lead) + 0.5)  # centre into [-1/2, 1/2)
        trail += shift
        lead += shift
        ids = (first + np.arange(length)) % n
        xs = x[first] + shift + h * np.arange(length)  # unwrapped centres
        if xs.mean() - 0.5 * (trail + lead) > 0.5:
            xs -= 1.0
        elif xs.mean() - 0.5 * (trail + lead) < -0.5:
            xs += 1.0
        w = sigma[ids]
        load = float(w.sum()) / n
        centroid = float(np.dot(w, xs) / w.sum()) if w.sum() > 0 else 0.5 * (trail + lead)
        out.append(Patch(trailing_edge=trail, leading_edge=lead,
                         ka=math.pi * (lead - trail), ke=math.pi * (trail + lead),
                         ke_hat=2.0 * math.pi * centroid, load=load, panels=int(length)))
    return out


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
# Friction (mean frictional stress, positive when it resists the motion)
# --------------------------------------------------------------------------
def _friction(sigma, y, material: Prony, speed: float):
    """(dissipation estimate, direct estimate) of tau_f (1 - nu^2)/E_ref.

    tau_f = (1/lambda) int sigma dv/dx dx in the paper (eq. 3.1), negative when it
    resists; reported with the opposite sign (conventions.md).  With
    sigma = sum_n sigma_n e^{2 pi i n X} and v_n = (2/|n|) J*(n) sigma_n,
    -(1/lambda) int sigma v' dx = sum_{n>0} 4 Im J*(n) |sigma_n|^2 (the energy
    dissipated per unit sliding distance), insensitive to phase errors.
    Collocation makes the panel values exceed the point values: a mode n of
    piecewise-constant pressure displaces the collocation points by its symbol
    times sinc(pi n/N), so the solve returns sigma(X_j)/sinc mode by mode (in
    real space sigma_j = sigma - h^2 sigma''/24 + ..., the opposite of a panel
    average); hence sigma_n = DFT_n * sinc(pi n/N).  The direct estimate
    -(1/2 pi) int sigma d(ky)/dX dX = sum_{n>0} 2 n Im(conj(sigma_n) y_n) uses the
    profile instead of v (equal on the contact).
    """
    n = sigma.size
    sh = np.fft.rfft(sigma) / n
    yh = np.fft.rfft(y) / n
    modes = np.arange(sh.size, dtype=float)
    sh = sh * np.sinc(modes / n)
    weight = np.ones_like(modes)
    weight[0] = 0.0
    if n % 2 == 0:
        weight[-1] = 0.5  # Nyquist: +N/2 and -N/2 share one discrete mode
    jim = material.jstar(modes, speed).imag
    diss = float(np.sum(weight * 4.0 * jim * np.abs(sh) ** 2))
    direct = float(np.sum(weight * 2.0 * modes * np.imag(np.conj(sh) * yh)))
    return diss, direct


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
        return _build_result(res, fine, profile, material, speed, amp, load,
                             [(nodes, 1, (0,))])

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

    return _build_result(prev, prev_grid, profile, material, speed, amp, load, history)


def _build_result(res, grid: _Grid, profile, material, speed, amp, load, history):
    sigma = res["sigma"]
    active = res["active"]
    s = float(res["s"])
    gap = res["gap"]
    n = grid.n
    out = np.empty(4)
    _kernels.contact_residuals(active, sigma, gap, out)
    mean_p = float(sigma.mean())
    target = load if load is not None else mean_p
    smax = float(sigma.max()) if sigma.size else 0.0
    tau_f, tau_direct = _friction(sigma, grid.y, material, speed)
    residuals = {
        "complementarity": float(out[0]) / amp,
        "contact_gap": float(out[1]) / amp,
        "interpenetration": float(out[2]) / amp,
        "negative_pressure": float(out[3]) / smax if smax > 0 else float(out[3]),
        "load_balance": abs(mean_p - target) / target if target > 0 else abs(mean_p),
        "krylov": float(res["relres"]) / amp,
        "friction_mismatch": abs(tau_direct - tau_f) / abs(tau_f) if tau_f != 0 else 0.0,
    }
    # panels across the thinnest pressure memory layer w τ_R (only reported, not a residual
    # that gates success): below one panel the edges carry an error of the order of the layer
    tau_r = material.relaxation_times
    layer = speed * min(tau_r) * n / (2.0 * math.pi) if (tau_r and speed > 0.0) else math.inf
    full = bool(active.all())
    if full:
        ka, ke, frac, patches = math.pi, None, 1.0, ()
        yh = np.fft.rfft(grid.y)
        sh = np.fft.rfft(sigma)
        nstar = int(np.argmax(np.abs(yh[1:]))) + 1
        ke_hat = float(np.angle(yh[nstar] / sh[nstar])) / nstar
    else:
        patches = tuple(_patches(sigma, gap, active, grid.x, grid.h))
        main = max(patches, key=lambda p: p.load)
        ka, ke, ke_hat = main.ka, main.ke, main.ke_hat
        frac = float(sum(p.leading_edge - p.trailing_edge for p in patches))
    disp = grid.op.apply(sigma) / amp
    gap_out = np.where(active, 0.0, gap) / amp
    status = int(res["status"])
    success = status == 0
    message = res["message"]
    if not success:
        message = (f"not converged: {message}; residuals "
                   + ", ".join(f"{k}={v:.3e}" for k, v in residuals.items()))
    elif layer < 1.0 and not full:
        message += (f"; the pressure memory layer spans {layer:.2g} panel: contact edges carry an "
                    "error of the order of the layer (refine N to resolve it)")
    return BemResult(
        success=success, status=status, message=message, nit=int(res["nit"]),
        inner_iterations=tuple(res["inner"]), residuals=residuals, nodes=n, speed=speed,
        material=material, profile=profile, load=mean_p, full_contact=full,
        contact_fraction=frac, ka=ka, ke=ke, ke_hat=ke_hat,
        penetration=(amp - s) / amp, tau_f=tau_f, mu=tau_f / mean_p if mean_p > 0 else float("nan"),
        separation=s / amp, x_over_lambda=grid.x, pressure=sigma, displacement=disp,
        gap=gap_out, patches=patches, levels=tuple(history), memory_layer_panels=layer)
