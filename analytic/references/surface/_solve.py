"""`solve`, the surface reference's front: the inputs checked, each level solved on two grids
shifted by half a panel and averaged, the levels combined by Richardson's extrapolation, the
layer's uniform mode added."""
from __future__ import annotations

import math
import time

import numpy as np

from viscosine.checks import bad, check_reals

from .._layer import uniform_compliance
from ._inputs import (ACCEPTED, TOL, _TESTS, _check_layer, _check_nodes, _material,
                      _shortest_relaxation)
from ._levels import _solve_grid, richardson
from ._operator import _Grid
from ._result import SurfaceSolution
from ._surface import _Surface

_TWO_PI = 2.0 * math.pi

#: a contact patch with fewer points than this on the finest grid is warned of
_MIN_PATCH_POINTS = 16
#: scalars combined over the grids: relative estimates (the contact fraction's too, as the
#: output contract and the surface BEM give it), then absolute ones (the lateral force can
#: vanish)
_RELATIVE = ("load", "penetration", "tau_f", "mu", "max_pressure", "contact_fraction")
_ABSOLUTE = ("mu_lateral",)
#: diagnostics averaged over a level's grids like the scalars
_DIAGNOSTIC = ("mu_direct", "mu_lateral_direct", "contact_fraction_nodal")
#: every level is solved on two grids, the surface moved by these fractions of a panel along
#: both axes, and averaged
SHIFTS = (0.0, 0.5)
#: added to every estimate (relative or absolute, as the estimate): what the grid differences
#: cannot see, the rounding of the iteration's stop
_FLOOR = 1e-13


def solve(*, load=None, penetration=None, speed, heights, aspect=1.0, direction=0.0,
          ratio=None, material=None, nodes=None, tol=TOL, layer=None):
    """Steady sliding of a rigid periodic surface over a viscoelastic half-space.

    Parameters
    ----------
    load : float, optional
        Mean pressure over the cell p̃ = p∞(1 − ν²)/E0 > 0 (load control).
    penetration : float, optional
        Δ/h_ref in (0, 1] (penetration control; the load is an output; at 1 the smallest
        load of full contact).  Give exactly one of the two.
    speed : float
        w = V τ k ≥ 0 (V/V0; 0 is the relaxed elastic solid, J0).
    heights : callable, array or dict
        The surface as k·z (positive toward the body): a callable f(x, y) of positions over
        Lx (arrays of one shape, y in [−aspect/2, aspect/2)); a 2-D array of point values at
        the panel centres x_i = i/nx − ½, y_j = (j/ny − ½)·aspect (its trigonometric
        interpolant is solved on grids of multiples of nx); or harmonics ``{(m, n): c}``,
        k·z = Σ Re[c e^{2πi(m x + n y/aspect)}] (the bi-sinusoid hk[cos kx + cos ky] is
        ``{(1, 0): hk, (0, 1): hk}`` with aspect 1).
    aspect : float
        Ly/Lx in [1/64, 64] (default 1).
    direction : float
        θ, degrees from +x counter-clockwise (default 0).
    ratio : float, optional
        E∞/E0 of the standard linear solid (default 3).
    material : (J0, J, tau), optional
        A creep series instead of ``ratio``: J0 and J_i in (1 − ν²)/E0, τ_i in τ.
    nodes : int or sequence of int, optional
        Panels along x of the grids (ny = nx·aspect rounded to even, or in the array's
        proportion): one N solves N/4, N/2 and N; default (64, 128, 256), for an array
        (nx, 2nx, 4nx) up to `MAX_NODES`.
    tol : float
        Stop when the iteration's residual ‖T y − y‖∞ is below tol·max σ (default 1e-10).
    layer : mapping, optional
        A layer of thickness d on a rigid foundation in place of the half-space (None, the
        default: the half-space, solved exactly as without this argument):
        ``{"thickness": k d}`` (k = 2π/Lx) or ``{"thickness_over_wavelength": d/Lx}``, with
        ``"foundation"`` (``"bonded"`` or ``"frictionless"``) and ``"nu"`` (in (−1, 0.5]),
        as `analytic.references.fourier_solve` takes it.  Mode q of the operator is the
        half-space's times the layer factor S(|q| k d, ν) of `analytic.references._layer`
        (Navier's equations, one mode at a time); the scalars keep their meaning (Δ from the
        mean plane of the deformed surface) and the result adds ``layer``,
        ``mean_displacement`` v̄0/h_ref (the layer's uniform compression, k v̄0 = C (k d) J0 p̃,
        J0 the relaxed compliance, C of `uniform_compliance` of `analytic.references._layer`)
        and ``approach`` Δ/h_ref + v̄0/h_ref, as the BEM's ``diagnostics["layer"]``.  An
        approach that reaches the foundation (approach · k h_ref ≥ k d) is not a success;
        under penetration control Δ/h_ref ≥ k d/(k h_ref) is refused.

    Returns
    -------
    SurfaceSolution

    Raises
    ------
    ValueError
        ``"name=value is not allowed: …"`` for any input outside what is accepted.

    References
    ----------
    Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014), eq. (2.5) (the
    operator, here per mode of the surface) and eq. (3.1) (the friction).
    """
    t0 = time.perf_counter()
    if load is not None and penetration is not None:
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
    if load is None and penetration is None:
        raise ValueError("load=None, penetration=None is not allowed: give exactly one of "
                         "load and penetration")
    vals = check_reals(ACCEPTED, (("load", load), ("penetration", penetration),
                                  ("speed", speed), ("direction", direction),
                                  ("aspect", aspect), ("tol", tol)), _TESTS)
    mat = _material(ratio, material)
    lay = _check_layer(layer)
    surf = _Surface(heights, vals["aspect"])
    levels = _check_nodes(nodes, surf)
    w, theta, tol = vals["speed"], vals["direction"], vals["tol"]
    control = "load" if load is not None else "penetration"
    asked = vals[control]

    fine_samples = surf.sample(*surf.grid_for(levels[-1]))
    h_ref = surf.extent(fine_samples)
    if not h_ref > 0.0:
        raise bad("heights", heights, surf.what + " (max z − mean z is not > 0)")
    if lay is not None and control == "penetration" and asked * h_ref >= lay["thickness"]:
        # the approach is at least Δ (C ≥ 0): the crest would reach the foundation
        raise bad("penetration", penetration, f"a penetration Δ/h_ref below k d/(k h_ref) = "
                  f"{lay['thickness'] / h_ref:.6g} on this layer (the approach Δ/h_ref + "
                  "v̄0/h_ref, at least Δ/h_ref, must not reach the foundation)")
    value = asked if control == "load" else h_ref * (1.0 - asked)
    warnings = []
    rows, failure = [], None
    starts = [None] * len(SHIFTS)
    for n in levels:
        t1 = time.perf_counter()
        nx, ny = surf.grid_for(n)
        grid = _Grid(nx, ny, vals["aspect"], theta, w, mat, lay)
        pair = []
        for k, shift in enumerate(SHIFTS):
            zk = fine_samples if (n, shift) == (levels[-1], 0.0) else surf.sample(nx, ny, shift)
            got = _solve_grid(grid, zk, control, value, asked, starts[k], tol, h_ref)
            if isinstance(got, str):
                failure = got
                break
            pair.append(got)
            starts[k] = (got["sigma"], got["gap"], got["s"])
        if failure is not None:
            break
        scalars = {key: 0.5 * (pair[0]["scalars"][key] + pair[1]["scalars"][key])
                   for key in _RELATIVE + _ABSOLUTE + _DIAGNOSTIC}
        for key in ("n_patches", "full_contact", "smallest_patch_points"):
            scalars[key] = pair[0]["scalars"][key]
        scalars["complementarity"] = max(p["scalars"]["complementarity"] for p in pair)
        rows.append({"nodes": nx, "ny": ny, "scalars": scalars,
                     "shifted": [p["scalars"] for p in pair],
                     "evaluations": sum(p["evaluations"] for p in pair),
                     "mixed": sum(p["mixed"] for p in pair),
                     "seconds": time.perf_counter() - t1})
    elapsed = time.perf_counter() - t0
    material_out = {"J0": mat[0], "J": list(mat[1]), "tau": list(mat[2])}
    if failure is None:
        last = pair[0]
        x = np.arange(nx) / nx - 0.5
        y = (np.arange(ny) / ny - 0.5) * vals["aspect"]
    common = dict(control=control, asked=asked, speed=w, direction=theta,
                  aspect=vals["aspect"], material=material_out, h_ref=h_ref,
                  grids=tuple((r["nodes"], r["ny"]) for r in rows), levels=tuple(rows),
                  nodes=rows[-1]["nodes"] if rows else 0, elapsed=elapsed)
    if lay is not None:
        common["layer"] = {"thickness": lay["thickness"],
                           "thickness_over_wavelength": lay["thickness"] / _TWO_PI,
                           "foundation": lay["foundation"], "nu": lay["nu"],
                           "uniform_compliance": uniform_compliance(lay["nu"],
                                                                    lay["foundation"])}
    if failure is not None:
        nan = math.nan
        empty = np.zeros((0, 0))
        return SurfaceSolution(success=False, status=1, message=failure, load=nan,
                               full_contact=False, contact_fraction=nan, penetration=nan,
                               separation=nan, tau_f=nan, mu=nan, mu_lateral=nan,
                               n_patches=0, max_pressure=nan, error_estimate={},
                               observed_order={}, extrapolated={}, diagnostics={},
                               warnings=tuple(warnings), x=np.zeros(0), y=np.zeros(0),
                               pressure=empty, gap=empty, displacement=empty, **common)
    common.update(x=x, y=y, pressure=last["sigma"], gap=last["gap"] / h_ref,
                  displacement=last["u"] / h_ref)

    ns = [r["nodes"] for r in rows]
    out, est, order, extra = {}, {}, {}, {}
    for key in _RELATIVE + _ABSOLUTE:
        v, e, p, x_ = richardson(ns, [r["scalars"][key] for r in rows])
        a_, b_ = (g[key] for g in rows[-1]["shifted"])
        # one grid's error oscillates with where the edges fall between the points: the
        # finest level's two grids sample it at two phases, so their spread joins the estimate
        e = max(e, abs(a_ - b_)) if math.isfinite(e) else abs(a_ - b_)
        if key in _RELATIVE:
            e = e / abs(v) if v != 0.0 else math.inf
        e = e + _FLOOR
        out[key], est[key], order[key], extra[key] = v, e, p, x_
    est["n_patches"] = None
    fine = rows[-1]["scalars"]
    if len({r["scalars"]["n_patches"] for r in rows}) > 1:
        warnings.append("the grids disagree on the number of patches: "
                        + ", ".join(str(r["scalars"]["n_patches"]) for r in rows))
    if not fine["full_contact"] and fine["smallest_patch_points"] < _MIN_PATCH_POINTS:
        warnings.append(f"a contact patch of {fine['smallest_patch_points']} points on the "
                        "finest grid: its edges are not resolved")
    memory = w * _shortest_relaxation(mat) / _TWO_PI
    if 0.0 < memory * nx < 4.0:
        warnings.append(f"the shortest memory length w θ/(2π) = {memory:.3g} Lx has fewer "
                        f"than 4 panels on the finest grid ({nx} along x)")
    if control == "penetration" and asked == 1.0:
        message = "the threshold of full contact (Δ/h_ref = 1), in closed form on each grid"
    elif fine["full_contact"]:
        message = "full contact, in closed form on each grid (σ̂_q = ẑ_q/Ĉ(q))"
    else:
        message = ("converged on grids " + ", ".join(f"{a} × {b}" for a, b in common["grids"])
                   + f" ({sum(r['evaluations'] for r in rows)} evaluations of the map)")
    finite = all(math.isfinite(out[k]) for k in ("load", "penetration", "mu", "mu_lateral",
                                                  "contact_fraction", "max_pressure"))
    success = finite and out["load"] > 0.0
    if not success:
        message = "non-finite or non-positive scalars; not a solution"
    diagnostics = {k: fine[k] for k in ("mu_direct", "mu_lateral_direct",
                                         "contact_fraction_nodal", "complementarity")}
    if lay is not None:
        load_out = out["load"] if control == "penetration" else asked
        # the uniform mode: k v̄0 = C (k d) J0 p̃ (static: the relaxed J0), over k h_ref
        mean = common["layer"]["uniform_compliance"] * lay["thickness"] * mat[0] * load_out \
            / h_ref
        approach = out["penetration"] + mean
        est["mean_displacement"] = est["load"]      # v̄0 ∝ p̃
        est["approach"] = ((est["penetration"] * abs(out["penetration"])
                            + est["load"] * abs(mean)) / abs(approach)
                           if approach != 0.0 else math.inf)
        common.update(mean_displacement=mean, approach=approach)
        diagnostics["layer"] = dict(common["layer"], mean_displacement=mean, approach=approach)
        if success and approach * h_ref >= lay["thickness"]:
            success = False
            message = (f"the crest's approach {approach:.6g} h_ref reaches the foundation at "
                       f"d = {lay['thickness'] / h_ref:.6g} h_ref (k d = "
                       f"{lay['thickness']:.6g}, k h_ref = {h_ref:.6g}): not a solution of "
                       "small strains")
        if lay["thickness"] * nx / _TWO_PI < 4.0:
            warnings.append(f"the layer's thickness d = {lay['thickness'] / _TWO_PI:.3g} Lx "
                            f"spans fewer than 4 panels on the finest grid ({nx} along x)")
    return SurfaceSolution(success=success, status=0 if success else 1, message=message,
                           load=out["load"] if control == "penetration" else asked,
                           full_contact=fine["full_contact"],
                           contact_fraction=out["contact_fraction"],
                           penetration=out["penetration"], separation=1.0 - out["penetration"],
                           tau_f=out["tau_f"], mu=out["mu"], mu_lateral=out["mu_lateral"],
                           n_patches=fine["n_patches"], max_pressure=out["max_pressure"],
                           error_estimate=est, observed_order=order, extrapolated=extra,
                           diagnostics=diagnostics, warnings=tuple(warnings), **common)
