"""`fourier_solve`, the Fourier reference's front: the inputs checked, the resolution of the
memory layers and of a layer's thickness judged, full contact answered in closed form, and the
levels solved from a Westergaard start."""
from __future__ import annotations

import math
import time

import numpy as np

from viscosine.checks import bad, integer, is_integer, real

from .._layer import check_layer, describe, layer_factor
from ._closed_form import full_contact
from ._levels import _level
from ._material import material
from ._result import _failed, _full_result, _on_layer, _partial_result

_TWO_PI = 2.0 * math.pi

#: default levels (points per period) and shifts per level
NODES = (1024, 2048, 4096, 8192)
SHIFTS = 16
#: the largest grid: the restricted matrix of a near-full contact is then ~0.5 GB in LU form
MAX_NODES = 8192
MIN_NODES = 64
#: points per shortest memory layer below which a grid does not resolve it (measured: the
#: standard linear solid with E∞/E0 = 100 meets the estimates at 3.9 points, not at 1.3)
MIN_LAYER_POINTS = 4.0
#: points of the finest grid per thickness d of a layer below which d is not resolved
#: (`thickness_resolution`).  Measured against the BEM (rtol 1e-7 or 1e-8) over k d = 0.005 …
#: 0.5, both foundations, V/V0 = 0.1, 1, 10, contacts of 4 % to 68 % of the period (414
#: solves): with the default levels the true errors exceeded the estimates in 2 of 18 solves
#: under 32 points per d (1.2 and 1.3 times, at 13 and 26 points), in none of 72 from 32 on;
#: three levels (8 or 16 shifts) exceeded them in 5 of 126 under 32, 2 of 198 from 32 on (up to
#: 2.3 times both)
MIN_THICKNESS_POINTS = 32.0
#: the grid from which the first level is started
_START_NODES = 256


def _check_nodes(nodes):
    seq = [nodes] if is_integer(nodes) else nodes
    allowed = (f"an even number of points per period in [{MIN_NODES}, {MAX_NODES}], or an "
               "increasing sequence of them (three or more for Richardson's extrapolation)")
    try:
        seq = list(seq)
    except TypeError:
        raise bad("nodes", nodes, allowed) from None
    if not seq or not all(is_integer(v) and MIN_NODES <= v <= MAX_NODES and v % 2 == 0
                          for v in seq):
        raise bad("nodes", nodes, allowed)
    if any(b <= a for a, b in zip(seq[:-1], seq[1:])):
        raise bad("nodes", nodes, allowed)
    return tuple(int(v) for v in seq)


def _westergaard_start(control, value, hk, e1):
    """Patches [(x_t, x_l)] of Westergaard's solution with the modulus |E*(1)| (a start only)."""
    if control == "load":
        s = min(value / (0.5 * hk * abs(e1)), 0.999)
    else:
        s = value                       # invert Δ/h = s(1 − ln s) by fixed point
        for _ in range(60):
            s = min(value / (1.0 - math.log(max(s, 1e-300))), 0.999)
    half = 2.0 * math.asin(math.sqrt(s)) / _TWO_PI
    return [(-half, half)]


def memory_resolution(speed, nodes, **material_kw):
    """Shortest memory layer of the material and whether `nodes` points per period resolve it.

    Behind the leading edge the pressure relaxes over L = w θ/(2π) wavelengths for each
    relaxation time θ of the series (θ = τ E0/E∞ for the standard linear solid).  A grid with
    fewer than `MIN_LAYER_POINTS` points across the shortest such layer leaves a sawtooth in the
    pressure there, misses part of the dissipation (the modes beyond N/2 with Im J* ∝ n w) and
    moves the contact edges by a fraction of L; the measured errors then exceed the estimates.

    Parameters
    ----------
    speed : float
        w = V τ_ref k ≥ 0.
    nodes : int
        Points per period of the finest grid.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    length, resolved : float, bool
        The shortest layer w θ_min/(2π) (x/λ; inf without memory or at rest) and whether
        ``length * nodes >= MIN_LAYER_POINTS``.
    """
    w = real("speed", speed, "a finite speed w = V τ_ref k ≥ 0", lambda v: v >= 0.0)
    thetas = material(**material_kw).relaxation_times()
    if w == 0.0 or not thetas:
        return math.inf, True
    length = w * min(thetas) / _TWO_PI
    return length, length * nodes >= MIN_LAYER_POINTS


def thickness_resolution(thickness, nodes):
    """The thickness d/λ of a layer and whether `nodes` points per period resolve it.

    d is a length of the solution: the layer's kernel differs from the half-space's by a part
    that is smooth over d only (S − 1 decays like e^{−2|n|kd}), so the pressure of a thin
    layer's contact changes its form over d at the edges (from the half-space's square root
    to the thin layer's own), and the edge fit, whose expansion about an edge converges
    within about 2d, is narrowed to d/2 (`_FIT_LAYER`) once the grid has the points.  A grid
    with fewer than `MIN_THICKNESS_POINTS` points across d is not trusted (measured against
    the BEM: see the constant).

    Parameters
    ----------
    thickness : float
        k d > 0.
    nodes : int
        Points per period of the finest grid.

    Returns
    -------
    length, resolved : float, bool
        d/λ and whether ``length * nodes >= MIN_THICKNESS_POINTS``.
    """
    kd = real("thickness", thickness, "a finite thickness k d > 0", lambda v: v > 0.0,
              kind=True)
    length = kd / _TWO_PI
    return length, length * nodes >= MIN_THICKNESS_POINTS


def fourier_solve(*, load=None, penetration=None, speed, ratio=None, creep=None,
                  relaxation=None, hk=1.0, nodes=NODES, shifts=SHIFTS, require_resolved=True,
                  layer=None):
    """Steady sliding of the sinusoid over any Prony-series material, by Fourier collocation.

    Parameters
    ----------
    load : float, optional
        Mean pressure p̃ = p∞(1 − ν²)/E_ref > 0 (load control).
    penetration : float, optional
        Δ/h in (0, 1] (penetration control; the load is an output; at 1 the smallest load of
        full contact).  Give exactly one of the two.
    speed : float
        w = V τ_ref k ≥ 0 (V/V0 for the standard linear solid; 0 is the relaxed elastic solid).
    ratio, creep, relaxation
        The material, at most one (default ratio 3): see `material`.
    hk : float
        Amplitude h k > 0 of k y = hk cos(2πX).
    nodes : int or sequence of int
        Points per period of the levels (even, 64 … 8192, increasing); default
        (1024, 2048, 4096, 8192).
    shifts : int
        Grids per level, shifted by 1/shifts of a spacing and averaged (1 … 64); default 16.
    require_resolved : bool
        True (default): a point whose shortest memory layer (`memory_resolution`) or whose
        layer thickness (`thickness_resolution`) the finest grid does not resolve is not
        solved and the result is not a success.  False solves it anyway, with a warning: its
        errors may then exceed the estimates.  Full contact (closed form) is exempt.
    layer : mapping, optional
        A layer of thickness d on a rigid foundation in place of the half-space:
        ``{"thickness": k d (finite, > 0), "foundation": "bonded" (u_x = u_z = 0 at the
        bottom) or "frictionless" (u_z = 0 and no shear there), "nu": ν in (−1, 0.5]}``.
        Mode n of the operator is the half-space's times S(|n| k d, ν) (`layer_factor`); the
        scalars keep their meaning and the result adds ``layer``, ``mean_displacement`` and
        ``approach``.  None (default): the half-space, answered exactly as without it.

    Returns
    -------
    FourierResult
        ``success`` False, with the reason in ``message``, when the memory or the layer is not
        resolved, a grid did not converge or the grids disagree on the contact (a point within
        a grid spacing of a transition); never raises for valid input.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: ..."`` for the first bad input.

    References
    ----------
    Eqs (2.2)–(2.5), (3.1) and Appendix B of Menga, Putignano, Carbone & Demelio, Proc. R.
    Soc. A 470, 20140392, 2014; the layer: Menga, Afferrante & Carbone, J. Mech. Phys. Solids
    95 (2016) 517–529.
    """
    t0 = time.perf_counter()
    if (load is None) == (penetration is None):
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
    if load is not None:
        control = "load"
        value = real("load", load, "a finite mean pressure p̃ > 0", lambda v: v > 0.0)
    else:
        control = "penetration"
        value = real("penetration", penetration, "a finite penetration Δ/h in (0, 1]",
                      lambda v: 0.0 < v <= 1.0)
    w = real("speed", speed, "a finite speed w = V τ_ref k ≥ 0", lambda v: v >= 0.0)
    hk = real("hk", hk, "a finite amplitude hk > 0", lambda v: v > 0.0)
    mat = material(ratio=ratio, creep=creep, relaxation=relaxation)
    levels_n = _check_nodes(nodes)
    shifts = integer("shifts", shifts, "an integer number of shifted grids per level in [1, 64]",
                     lambda v: 1 <= v <= 64)
    if not isinstance(require_resolved, bool):
        raise bad("require_resolved", require_resolved, "True or False")
    lay = check_layer(layer)
    kw = _material_kw(mat)
    fc = full_contact(w, hk=hk, layer=lay, **kw)
    common = {"control": control, "asked": value, "speed": w, "hk": hk,
              "material": mat.as_dict(), "nodes": levels_n, "shifts": shifts}
    if lay is not None:
        common["layer"] = describe(lay)
    if control == "load" and value >= fc["load_threshold"]:
        return _on_layer(_full_result(value, fc, common, t0), lay, mat)
    if control == "penetration" and value == 1.0:
        return _on_layer(_full_result(fc["load_threshold"], fc, common, t0), lay, mat)
    warnings = []
    length, resolved = memory_resolution(w, levels_n[-1], **kw)
    unresolved = []
    if not resolved:
        unresolved.append(f"the shortest memory layer, w θ_min/(2π) = {length:.3g} λ, spans "
                          f"{length * levels_n[-1]:.3g} points of the finest grid "
                          f"({levels_n[-1]}), under the {MIN_LAYER_POINTS} that resolve it")
    factor = thickness = None
    if lay is not None:
        d, resolved = thickness_resolution(lay["thickness"], levels_n[-1])
        if not resolved:
            unresolved.append(f"the layer's thickness, d = {d:.3g} λ, spans "
                              f"{d * levels_n[-1]:.3g} points of the finest grid "
                              f"({levels_n[-1]}), under the {MIN_THICKNESS_POINTS} that "
                              "resolve it")
        thickness = d
        top = max(levels_n[-1], _START_NODES) // 2
        factor = layer_factor(np.arange(top + 1) * lay["thickness"], lay["nu"],
                              lay["foundation"])
    for text in unresolved:
        if require_resolved:
            return _on_layer(_failed(common, text + "; not solved (require_resolved=False "
                                     "solves it, with errors that may exceed the estimates)",
                                     [], t0), lay, mat)
        warnings.append(text + ": errors may exceed the estimates")
    # the start: Westergaard's contact with mode 1's modulus (the layer's, |E*(1)|/S(kd))
    e1 = fc["modulus"] if lay is None else fc["modulus"] / fc["layer_factor"]
    patches = _westergaard_start(control, value, hk, e1)
    target = value if control == "load" else hk * (1.0 - value)   # the load, or s in 1/k
    if levels_n[0] > _START_NODES:
        start = _level(_START_NODES, 1, mat, w, hk, control, target, patches, factor,
                       thickness)
        if start["patches"]:
            patches = start["patches"]
    levels = []
    for n in levels_n:
        lv = _level(n, shifts, mat, w, hk, control, target, patches, factor, thickness)
        levels.append(lv)
        if lv["message"]:
            return _on_layer(_failed(common, lv["message"], levels, t0), lay, mat)
        patches = [(p[0], p[1]) for p in lv["avg_patches"]]
    return _on_layer(_partial_result(levels, common, warnings, t0), lay, mat)


def _material_kw(mat):
    key = "creep" if mat.form == "creep" else "relaxation"
    return {key: (mat.base, mat.amps, mat.times)}
