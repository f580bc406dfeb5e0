"""Steady viscoelastic sliding of a rigid periodic surface (three-dimensional contact).

The surface z = h(x, y), periodic on the cell Lx x Ly, slides at speed V in the direction
theta over a viscoelastic half-space (or a layer on a rigid foundation).  In the frame of the
surface the steady displacement of the mode of wave vector q is that of the line contact's mode
loaded at the frequency q.V (``docs/surfaces.md``): the operator is diagonal on the cell's
modes (`bem._surface_operator`), and the contact problem is the line contact's, on a grid of
nx x ny panels flattened into one vector, solved by the same primal-dual active set with
preconditioned GMRES (`bem._grid`).

Every result carries an estimate of its discretisation error from the grids it solved (each
twice as fine as the one before along both sides), and by default the grid is refined until
that estimate meets ``rtol``.
"""
from __future__ import annotations

import math
import os
import time

import numpy as np

import viscosine
from viscosine.checks import bad, positive_int, real

from ._accepted import ACCEPTED, validate
from ._estimate import ESTIMATE_SAFETY, _first_order_bound, _halvings
from ._grid import _clip_shift, _solve_one
from ._study import _meshes
from ._inputs import Prony
from ._layer import Layer, mean_displacement
from ._result import CONVERGED, MESSAGES, STATUS_INVALID, STATUS_TARGET
from ._surface import Surface, bisinusoid
from ._surface_operator import SpectralOperator, surface_symbol
from ._surface_measure import measure
from ._surface_result import SurfaceResult, pressure_moments

#: default accuracy target of the adaptive surface mesh (viscosine.SURFACE_RTOL, the one value
#: the command line reads too): the estimated errors of μ and Δ/h_ref (relative) and of the
#: contact fraction (absolute, though its estimate is reported relative); docs/surfaces.md says
#: why
SURFACE_RTOL = viscosine.SURFACE_RTOL
#: the coarsest grid's panels along x (at least; more where the surface's modes need them)
SURFACE_START = 32
#: bytes per panel of a surface solve (symbol, fields, transforms, the Krylov basis on the
#: active set): measured peaks in python -m comparisons bench --surfaces
SURFACE_BYTES_PER_PANEL = 150
#: gaps (over h_ref) and pressures (over the maximum) the validity gate counts as zero
ROUNDOFF = 1e-12
#: contact panels below which a grid's answer is no answer (a contact inside a panel or two
#: has no shape: its area, friction and penetration are the grid's, not the surface's)
MIN_CONTACT_PANELS = 16


def _memory() -> int:
    try:
        return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):
        return 0


def max_surface_panels() -> int:
    """The most panels (nx ny) a surface solve may take: half the machine's memory at
    SURFACE_BYTES_PER_PANEL."""
    return int(_memory() / 2 // SURFACE_BYTES_PER_PANEL)


class _SurfaceGrid:
    """One (nx, ny) grid: the interface `bem._grid` asks of a grid, on flattened fields."""

    window = False

    def __init__(self, surface: Surface, material: Prony, speed, direction, nx, ny, layer):
        self.shape = (nx, ny)
        self.n = nx * ny
        self.nodes = self.n  # the load is the mean over all panels
        sym = surface_symbol(nx, ny, surface.aspect, material.j_plus, material.terms, speed,
                             direction, layer)
        self.op = SpectralOperator(sym, self.shape)
        z = surface.sample(nx, ny).reshape(-1)
        self.y = z - z.mean()
        self.amp = float(surface.amplitude)
        self.scale = self.amp
        self.s_offset = 0.0
        self.layer = layer
        self.aspect = surface.aspect


def _interp_periodic(c: np.ndarray, n_out: int, axis: int) -> np.ndarray:
    """Linear interpolation of cell-centred periodic samples onto n_out centres along axis."""
    n_in = c.shape[axis]
    t = (np.arange(n_out) + 0.5) * n_in / n_out - 0.5  # target centres in source index units
    i0 = np.floor(t).astype(np.int64)
    f = t - i0
    a = np.take(c, i0 % n_in, axis=axis)
    b = np.take(c, (i0 + 1) % n_in, axis=axis)
    shape = [1, 1]
    shape[axis] = n_out
    f = f.reshape(shape)
    return (1.0 - f) * a + f * b


def _prolong(prev: dict, prev_grid: _SurfaceGrid, grid: _SurfaceGrid):
    """Active set, pressure and separation on a finer grid from a solved coarser one: the
    pressure interpolated (bilinear, periodic), the active set where it is positive."""
    sig = prev["sigma"].reshape(prev_grid.shape)
    sig = _interp_periodic(_interp_periodic(sig, grid.shape[0], 0), grid.shape[1], 1)
    sig = sig.reshape(-1)
    if prev["active"].all():
        active = np.ones(grid.n, dtype=np.bool_)
    else:
        active = sig > 0.0
    return active, np.where(active, sig, 0.0), prev["s"]


def _ny_for(nx: int, aspect: float) -> int:
    return max(4, 2 * int(round(nx * aspect / 2.0)))


def _shapes(surface: Surface, nodes, max_panels) -> list:
    """The grids to solve, coarse to fine: (nx, ny) with ny = nx Ly/Lx (even), every grid
    twice the one before along both sides."""
    mx, my = surface.min_nodes()
    nx0 = SURFACE_START
    while nx0 < mx or _ny_for(nx0, surface.aspect) < my:
        nx0 *= 2
    if nodes is not None:
        # the estimate's grids N/8, N/4, N/2 below N, where the surface's modes fit on them
        out = []
        for k in (3, 2, 1, 0):
            nx = nodes // 2 ** k
            if nodes % 2 ** k == 0 and nx >= mx and _ny_for(nx, surface.aspect) >= my \
                    and nx >= 8:
                out.append((nx, _ny_for(nx, surface.aspect)))
        return out
    out = []
    nx = nx0
    while nx * _ny_for(nx, surface.aspect) <= max_panels:
        out.append((nx, _ny_for(nx, surface.aspect)))
        nx *= 2
    return out


#: the estimate's scalars: relative ones (over |q_N|), and the lateral coefficient over |μ| (it
#: can vanish)
RELATIVE = ("penetration", "tau_f", "mu", "max_pressure", "contact_fraction")
ABSOLUTE = ("mu_lateral",)


def _estimate(run: list):
    """The error estimate from the last converged grids (fine to coarse, each twice the next
    along both sides): `bem._estimate._first_order_bound` times ESTIMATE_SAFETY, relative for
    RELATIVE (the contact fraction's too), the lateral coefficient over |μ|.  Returns
    (estimate, reason): reason says why there is none yet."""
    if len(run) < 3:
        return None, "fewer than three converged grids"
    # the number of patches is not asked to stay put (on the line it is): a rough surface's
    # smallest patches appear and merge as the grid refines, while the area, the friction and
    # the penetration converge; the result says when it changed (`_build`)
    est = {}
    for k in RELATIVE + ABSOLUTE:
        vals = [sc[k] for sc in run]
        e = ESTIMATE_SAFETY * _first_order_bound(vals)
        if k == "penetration":
            e += ESTIMATE_SAFETY * ROUNDOFF
        scale = abs(vals[0]) if k in RELATIVE else abs(run[0]["mu"])  # mu_lateral: over |μ|
        est[k] = e / scale if scale > 0 else (0.0 if e == 0 else math.inf)
    return est, None


def _met(est, rtol, fraction) -> bool:
    """Whether the estimate meets rtol: μ and Δ/h_ref relative, the contact fraction absolute
    (its relative estimate times ``fraction``, the grid's; docs/surfaces.md says why)."""
    return est is not None and est["mu"] <= rtol and est["penetration"] <= rtol and \
        est["contact_fraction"] * abs(fraction) <= rtol


# --------------------------------------------------------------------------------------------
# The front door
# --------------------------------------------------------------------------------------------
def solve_surface(*, load=None, penetration=None, speed, surface=None, direction=0.0,
                  material=None, ratio=None, hk=None, layer=None, nodes=None, rtol=None,
                  max_nodes=None, tol=1e-10, max_outer=50, restart=8, max_inner=300,
                  progress=None) -> SurfaceResult:
    """Steady sliding of a rigid periodic surface over a viscoelastic half-space (3D contact).

    The mode of wave vector q of the surface displacement is the line contact's mode loaded at
    the frequency q·V: ``k u_q = (2/|q|) J*(q·e) S(|q| k d) σ_q`` with J*(n) the line contact's
    compliance of the mode n at the speed w (eq. 2.5 of Menga et al.
    (2014) in Fourier space, extended to the plane; ``docs/surfaces.md``).  Solved on grids of
    nx x ny panels, each twice as fine as the one before, by the line contact's active set.

    Parameters
    ----------
    load : float, optional
        p̃∞ = p∞ (1 − ν²)/E_ref, p∞ the mean pressure over the cell (load control).
    penetration : float, optional
        Δ/h_ref in (0, 1] (penetration control; the load is an output).  Exactly one of the two.
    speed : float
        V τ_ref k, k = 2π/Lx (V/V0 for the standard linear solid).
    surface : bem.Surface, optional
        The rigid surface (`bem.bisinusoid`, `bem.self_affine`, `bem.sampled_surface`,
        `bem.read_surface`); default the bi-sinusoid ``bisinusoid(hk)``.
    direction : float
        θ in degrees from +x, counter-clockwise.
    material : bem.Prony, optional
        Default the standard linear solid with ``ratio`` (default 3).
    ratio, hk : float, optional
        E∞/E0 of the default material; h k of the default bi-sinusoid (default 1).
    layer : bem.Layer, optional
        A layer on a rigid foundation (its thickness over Lx) instead of the half-space.
    nodes : int, optional
        A fixed grid of ``nodes`` panels along x (ny = nodes Ly/Lx); its halvings N/2, N/4, N/8
        are solved too and give the estimate.  Default: adaptive.
    rtol : float, optional
        Adaptive mesh: the target of the estimated errors of μ and Δ/h_ref (relative) and the
        contact fraction (absolute: its relative estimate times the fraction); default 1e-3
        (`SURFACE_RTOL`).
    max_nodes : int, optional
        Adaptive mesh: the most panels along x of the finest grid; default and bound: the
        largest grid of at most `max_surface_panels()` panels.
    tol, max_outer, restart, max_inner
        As `bem.solve`.
    progress : callable, optional
        Called with a one-line string after each grid (the command line prints it on
        standard error).

    Returns
    -------
    SurfaceResult

    References
    ----------
    Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): eqs. (2.3)-(2.5).
    """
    prob = _surface_problem(load=load, penetration=penetration, speed=speed, surface=surface,
                            direction=direction, material=material, ratio=ratio, hk=hk,
                            layer=layer, nodes=nodes, rtol=rtol, max_nodes=max_nodes, tol=tol,
                            max_outer=max_outer, restart=restart, max_inner=max_inner)
    return _refine(prob, progress)


def solve_surface_meshes(*, nodes, load=None, penetration=None, speed, surface=None,
                         direction=0.0, material=None, ratio=None, hk=None, layer=None,
                         tol=1e-10, max_outer=50, restart=8, max_inner=300, progress=None):
    """A grid study: `solve_surface` on each fixed grid of ``nodes``, the grids solved once.

    Fixed grids solved one by one solve their coarser grids again each time (a study of
    64 ... 1024 panels along x costs about 1.8 solves of its finest grid, with its halvings);
    here they are one sequence from the coarsest grid's N/8 up, every grid started from the one
    half as fine (about 1.3).  Each result is what ``solve_surface(nodes=N, ...)`` answers, its
    estimate from the grids N/8 ... N; only the start of N/8 differs (``solve_surface`` starts
    it afresh, from the full-contact pressure clipped to carry the load, the study from N/16),
    so the answers agree to the Krylov tolerance ``tol``, not bit for bit (the coarsest grid's
    are the same bits).  A grid that failed does not stop the study: the next starts afresh,
    and an estimate rests only on grids that halve in turn.

    Parameters
    ----------
    nodes : sequence of int
        The grids (panels along x), distinct, each the finest divided by a power of two; in any
        order, answered coarse to fine.
    load, penetration, speed, surface, direction, material, ratio, hk, layer, tol, max_outer, restart, max_inner, progress
        As for `solve_surface`.

    Returns
    -------
    iterator of SurfaceResult
        One per grid, coarse to fine, each yielded as soon as it is solved; ``list(...)`` for
        all.  The inputs are checked before the first.
    """
    meshes = _meshes(nodes)
    kw = dict(load=load, penetration=penetration, speed=speed, surface=surface,
              direction=direction, material=material, ratio=ratio, hk=hk, layer=layer,
              rtol=None, max_nodes=None, tol=tol, max_outer=max_outer, restart=restart,
              max_inner=max_inner)
    low = _surface_problem(nodes=meshes[0], **kw)["shapes"][0][0]  # the coarsest's first grid
    p = _surface_problem(nodes=meshes[-1], **kw)
    aspect = p["surface"].aspect
    p["shapes"] = [(n, _ny_for(n, aspect)) for n in _doublings(low, meshes[-1])]
    return _study(p, meshes, progress)


def _doublings(low, top) -> list:
    """low, 2 low, ... up to top (top = low 2^k)."""
    out = [low]
    while out[-1] < top:
        out.append(out[-1] * 2)
    return out


def _study(p: dict, meshes: list, progress):
    for state in _grids(p, progress, study=True):
        nx = state[2][1].shape[0]  # the grid just solved
        if nx in meshes:
            yield _build(dict(p, nodes=nx), *state)


def validate_surface(*, load=None, penetration=None, speed, surface=None, direction=0.0,
                     material=None, ratio=None, hk=None, layer=None, nodes=None, rtol=None,
                     max_nodes=None):
    """Check the inputs of `solve_surface` without solving: ValueError naming the first bad
    one, its value and what is allowed (the memory a fixed grid asks included)."""
    _surface_problem(load=load, penetration=penetration, speed=speed, surface=surface,
                     direction=direction, material=material, ratio=ratio, hk=hk, layer=layer,
                     nodes=nodes, rtol=rtol, max_nodes=max_nodes, tol=1e-10, max_outer=50,
                     restart=8, max_inner=300)


def _surface_problem(*, load, penetration, speed, surface, direction, material, ratio, hk,
                     layer, nodes, rtol, max_nodes, tol, max_outer, restart, max_inner):
    if (load is None) == (penetration is None):
        raise bad("load", load, "exactly one of load and penetration "
                  f"(got load={load!r}, penetration={penetration!r})")
    if speed is None:
        raise bad("speed", speed, ACCEPTED["speed"][2])
    if surface is not None and hk is not None:
        raise bad("hk", hk, "nothing with surface= (hk is the default bi-sinusoid's amplitude)")
    if surface is None:
        surface = bisinusoid(1.0 if hk is None else hk)
    if not isinstance(surface, Surface):
        raise bad("surface", surface, "a bem.Surface (bem.bisinusoid, bem.self_affine, "
                  "bem.sampled_surface or bem.read_surface)")
    amp = surface.amplitude
    # the line's ranges, with h_ref k in place of hk (the load over the amplitude, the speed,
    # the material, the layer)
    validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=amp,
             material=material, layer=layer)
    theta = real("direction", direction, "a finite direction in degrees", kind=True)
    if material is None:
        material = Prony.standard_linear_solid(3.0 if ratio is None else ratio)
    cap = max_panels = max_surface_panels()
    if nodes is not None:
        nodes = positive_int("nodes", nodes, 8)
        for name, v in (("rtol", rtol), ("max_nodes", max_nodes)):
            if v is not None:
                raise bad(name, v, f"nothing with nodes={nodes}: {name} steers the adaptive mesh")
        mx, my = surface.min_nodes()
        if nodes < mx or _ny_for(nodes, surface.aspect) < my:
            raise bad("nodes", nodes, f"at least {max(mx, 8)} panels along x (the surface's "
                      f"finest mode, {surface.band[0]} x {surface.band[1]}, must lie below the "
                      "grid's Nyquist mode)")
        need = nodes * _ny_for(nodes, surface.aspect)
        if need > cap:
            raise bad("nodes", nodes, f"at most {cap} panels, half this machine's memory "
                      f"({_memory() / 2 / 2**30:.1f} GiB; {nodes} x "
                      f"{_ny_for(nodes, surface.aspect)} panels take about "
                      f"{need * SURFACE_BYTES_PER_PANEL / 2**30:.1f} GiB)")
    else:
        rtol = SURFACE_RTOL if rtol is None else real(
            "rtol", rtol, "a finite accuracy target in [1e-8, 1e-1]", lambda v: 1e-8 <= v <= 0.1,
            kind=True)
        if max_nodes is not None:
            max_nodes = positive_int("max_nodes", max_nodes, 8)
            ny = _ny_for(max_nodes, surface.aspect)
            if max_nodes * ny > cap:
                raise bad("max_nodes", max_nodes, f"a finest grid that fits in memory: "
                          f"{max_nodes} x {ny} panels take about "
                          f"{max_nodes * ny * SURFACE_BYTES_PER_PANEL / 2**30:.1f} GiB, and half "
                          f"of this machine's memory is {_memory() / 2 / 2**30:.1f} GiB")
            max_panels = max_nodes * ny
    sep = None if penetration is None else amp * (1.0 - float(penetration))
    shapes = _shapes(surface, nodes, max_panels)
    if not shapes:
        raise bad("max_nodes", max_nodes, "room for the coarsest grid the surface needs "
                  f"({surface.min_nodes()} panels)")
    return {"surface": surface, "material": material, "speed": float(speed),
            "direction": math.radians(theta), "degrees": theta, "layer": layer,
            "load": None if load is None else float(load), "sep": sep,
            "penetration": None if penetration is None else float(penetration),
            "nodes": nodes, "rtol": rtol, "shapes": shapes,
            "tol": real("tol", tol, "a finite tolerance in (0, 0.01]", lambda v: 0.0 < v <= 1e-2),
            "max_outer": positive_int("max_outer", max_outer, 1),
            "restart": positive_int("restart", restart, 1),
            "max_inner": positive_int("max_inner", max_inner, 1)}


def _refine(p: dict, progress) -> SurfaceResult:
    """Solve the grids in turn (each started from the one before), measure each, estimate."""
    for state in _grids(p, progress):
        pass
    return _build(p, *state)


def _grids(p: dict, progress, study=False):
    """The grids of ``p["shapes"]`` in turn, each started from the last converged one; yields
    (levels, converged, last, est, reason) after each grid.  Stops where the adaptive target
    is met and, unless ``study``, after two grids in a row that failed."""
    levels, converged = [], []
    best = last = None
    est, reason = None, "fewer than three converged grids"
    failed = 0
    t0 = time.perf_counter()
    for nx, ny in p["shapes"]:
        grid = _SurfaceGrid(p["surface"], p["material"], p["speed"], p["direction"], nx, ny,
                            p["layer"])
        start = [best] if best is not None else [None]
        res = _solve_one(grid, p["load"], p["sep"], start, p["tol"], p["max_outer"],
                         p["restart"], p["max_inner"], carry=best is None, prolong=_prolong)
        levels.append((nx, ny, res["nit"], res["status"], grid.op.transforms / 2.0))
        last = (res, grid)
        if res["status"] == CONVERGED:
            failed = 0
            sc = measure(res, grid, p["surface"], p["direction"], p["load"])
            levels[-1] = levels[-1][:4] + (grid.op.transforms / 2.0,)
            converged.append((nx, sc))
            best = (res, grid)
            est, reason = _estimate([sc for _, sc in _halvings(converged)])
            if progress is not None:
                text = (f"surface grid {nx} x {ny}: {res['nit']} active-set steps, "
                        f"mu = {sc['mu']:.6g}, contact {sc['contact_fraction']:.4f}")
                if est is not None:
                    text += f", estimate mu {est['mu']:.1e}"
                progress(text + f" ({time.perf_counter() - t0:.1f} s)")
            yield levels, converged, last, est, reason
            if p["nodes"] is None and _met(est, p["rtol"], sc["contact_fraction"]):
                break
        else:
            failed += 1
            best = None  # a grid that failed does not start the next
            if progress is not None:
                progress(f"surface grid {nx} x {ny}: {res['message']}")
            yield levels, converged, last, est, reason
            if failed >= 2 and not study:
                break


def _build(p, levels, converged, last, est, reason) -> SurfaceResult:
    res, grid = last
    nx, ny = grid.shape
    ok_grid = res["status"] == CONVERGED
    if ok_grid:
        sc = converged[-1][1]
    else:
        sc = measure(res, grid, p["surface"], p["direction"], p["load"])
    sigma, active = res["sigma"], res["active"]
    amp = grid.amp
    load = sc["load"]
    gap = res["gap"]
    disp = (gap + grid.y - res["s"]) / amp  # u = gap + z - s (k units), over k h_ref
    resid = _residuals(sigma, gap, active, amp, load, res, sc)
    status, message = res["status"], res["message"]
    warnings = []
    if ok_grid:
        problems = _gate(sc, resid, load)
        panels = int(np.count_nonzero(active))
        if not sc["full_contact"] and panels < MIN_CONTACT_PANELS:
            problems.append(f"the grid is too coarse for the contact: it holds {panels} contact "
                            f"panel{'s' if panels != 1 else ''} of {nx} x {ny} (at least "
                            f"{MIN_CONTACT_PANELS} are needed; refine the grid, or leave it "
                            "adaptive)")
        if problems:
            status = STATUS_INVALID
            message = f"{MESSAGES[STATUS_INVALID]}: " + "; ".join(problems)
    if status == CONVERGED and p["nodes"] is None and \
            not _met(est, p["rtol"], sc["contact_fraction"]):
        status = STATUS_TARGET
        if est is None:
            message = f"{MESSAGES[STATUS_TARGET]} ({reason}; finest grid {nx} x {ny})"
        else:
            message = (f"{MESSAGES[STATUS_TARGET]}: estimated errors mu {est['mu']:.2e}, "
                       f"penetration {est['penetration']:.2e}, contact fraction "
                       f"{est['contact_fraction'] * abs(sc['contact_fraction']):.2e} "
                       f"(absolute) > rtol {p['rtol']:g} at {nx} x {ny}")
    if status == CONVERGED and est is None:
        warnings.append(f"no error estimate: {reason}")
    counts = [sc["n_patches"] for _, sc in reversed(_halvings(converged))] if converged else []
    if status == CONVERGED and len(set(counts)) > 1:
        warnings.append("the number of contact patches changes with the grid (" +
                        ", ".join(str(c) for c in counts) + ", coarse to fine)")
    diagnostics = {"memory_lengths": [p["speed"] * t / (2.0 * math.pi) for _, t in
                                      p["material"].terms]}
    if p["layer"] is not None:
        lay = p["layer"]
        v0 = mean_displacement(lay, p["material"].J0, load) / amp
        diagnostics["layer"] = dict(lay.describe(), mean_displacement=v0,
                                    approach=sc["penetration"] + v0)
        if status == CONVERGED and (sc["penetration"] + v0) * amp >= lay.thickness:
            status = STATUS_INVALID
            message = (f"{MESSAGES[STATUS_INVALID]}: the approach {sc['penetration'] + v0:.4g} "
                       f"h_ref reaches the foundation (k d = {lay.thickness:g})")
    mat = p["material"]
    return SurfaceResult(
        success=status == CONVERGED, status=status,
        message=message if status != CONVERGED else (
            MESSAGES[CONVERGED] + ("" if not warnings else "; " + "; ".join(warnings))),
        nit=res["nit"], nodes=nx, shape=(nx, ny),
        control="load" if p["load"] is not None else "penetration",
        asked=p["load"] if p["load"] is not None else p["penetration"],
        load=load, speed=p["speed"], direction=p["degrees"],
        full_contact=sc["full_contact"], contact_fraction=sc["contact_fraction"],
        penetration=sc["penetration"], separation=sc["separation"], tau_f=sc["tau_f"],
        mu=sc["mu"], mu_lateral=sc["mu_lateral"], n_patches=sc["n_patches"],
        patches=sc["patches"], max_pressure=sc["max_pressure"],
        at_max_pressure=sc["at_max_pressure"],
        pressure_moments=pressure_moments(sigma, active),
        error_estimate=est, residuals=resid, levels=tuple(levels), diagnostics=diagnostics,
        surface=p["surface"].describe(),
        material={"J0": mat.J0, "J": list(mat.J), "tau": list(mat.tau), "ratio": mat.ratio},
        warnings=tuple(warnings),
        pressure=sigma.reshape(nx, ny), displacement=disp.reshape(nx, ny),
        gap=(np.where(active, 0.0, gap) / amp).reshape(nx, ny))


def _residuals(sigma, gap, active, amp, load, res, sc) -> dict:
    smax = float(np.max(sigma)) if sigma.size else 0.0
    g = gap / amp
    return {"complementarity": float(np.max(np.abs(sigma * g))),
            "contact_gap": float(np.max(np.abs(g[active]))) if active.any() else 0.0,
            # off the contact (on it the gap is the linear solve's residual: contact_gap)
            "interpenetration": max(0.0, -float(np.min(g[~active]))) if not active.all() else 0.0,
            "negative_pressure": max(0.0, -float(np.min(sigma))) / smax if smax > 0 else 0.0,
            "load_balance": abs(float(sigma.mean()) - load) / load if load > 0 else 0.0,
            "krylov": float(res["relres"]) / amp,
            "friction_mismatch": (abs(sc["tau_f"] - sc["tau_direct"]) / abs(sc["tau_f"])
                                  if sc["tau_f"] != 0 else abs(sc["tau_direct"]))}


def _gate(sc, resid, load) -> list:
    """What makes a converged grid's answer unphysical (empty when it passes)."""
    out = []
    for k in ("contact_fraction", "penetration", "tau_f", "mu", "mu_lateral", "max_pressure"):
        if not math.isfinite(sc[k]):
            out.append(f"{k} is not finite")
    if not 0.0 < sc["penetration"] <= 1.0 + ROUNDOFF:
        out.append(f"penetration {sc['penetration']:.3e} outside (0, 1]")
    if sc["mu"] < -ROUNDOFF:
        out.append(f"mu {sc['mu']:.3e} < 0")
    if resid["negative_pressure"] > ROUNDOFF:
        out.append(f"negative pressure {resid['negative_pressure']:.1e} of the maximum")
    if resid["interpenetration"] > ROUNDOFF:
        out.append(f"interpenetration {resid['interpenetration']:.1e} h_ref")
    if resid["load_balance"] > 1e-9:
        out.append(f"load balance {resid['load_balance']:.1e}")
    return out
