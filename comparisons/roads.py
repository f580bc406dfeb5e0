"""The adapter to the two roads: the one module of the comparison layer that calls them.

The roads are :mod:`bem` (the boundary-element method) and :mod:`analytic` (the semi-analytic
solution of the paper and, in `analytic.fourier_solve`, an independent dense Fourier
collocation).  Every other module of `comparisons` reaches them through the functions here, so
that the call shape of each road (its keywords, tolerances and input objects) lives in one place:

- the front door (`comparisons.runner`): `validate_analytic`, `validate_bem` (each road's own
  accepted ranges), `accepted` and `si_groups` (SI inputs checked by the road), and the record
  adapters `analytic_record` and `bem_record` (road → JSON record, fields and the constraint
  figures the last line of defence, `comparisons.gate`, checks: a `Solved`).  They pass the
  user's values as given, so that the road's own refusal names them as typed;
- operating points as plain dicts of numbers (the suite, verify, the report, the cross-check,
  the peers): `analytic_solution`, `fourier_solution`, `bem_solution` (values as floats; a
  point's ``layer`` is a plain description, turned into each road's own by `layer` and the
  reference's mapping), `transition_load`, `threshold_speed`, `full_contact_load`;
- the BEM's inputs: `read_profile`, `read_prony` (the BEM's readers: the one definition of each
  file format), `sinusoid`, `standard_linear_solid`, `prony`;
- `source_hash`: the two roads' source, on which a certified result depends.

Each road is imported inside the functions that use it: importing this module loads neither (the
records of the analytic road never load the BEM; `comparisons._materials` and
`comparisons.mastercurve` load no road at import).  The calls look ``bem.solve`` and
``analytic.solve`` up on their modules when made, so that a test replacing them is seen.

The benchmarks (the package `comparisons.bench`) time the roads' own calls and call them
directly.
"""
from __future__ import annotations

import hashlib
import math
from pathlib import Path
from typing import NamedTuple

import numpy as np

from viscosine import Fields

from . import operating_point as op

#: Krylov tolerance of the suite's BEM solves (relative to h k): below the discretisation error
#: at the finest mesh, so that the convergence study sees the mesh and not the linear solver
#: (the default 1e-10 leaves Δ/h changes of ~1e-11 at N = 2^18)
BEM_TOL = 1e-12


def _road(solver):
    import importlib
    return importlib.import_module(solver)


# ------------------------------------------------------------------------------ the front door
class Solved(NamedTuple):
    """What an adapter returns: the road's JSON record, its fields, its constraint figures."""

    record: dict
    fields: Fields | None
    constraints: dict | None  # min_pressure (over a pressure scale), min_gap (over h), mean_pressure_error


def _controls(spec):
    """The control of a spec, its value as given (unlike `point_controls`: no conversion)."""
    if spec.get("load") is not None:
        return {"load": spec["load"]}
    return {"penetration": spec.get("penetration")}


def _bem_kwargs(spec, problem):
    """bem.solve's keywords for a spec and its parsed ``problem`` ``(profile, material)``:
    None for the sinusoid of the spec's ``hk`` and the standard linear solid of its ``ratio``."""
    profile, material = problem
    kw = dict(_controls(spec), speed=spec["speed"])
    if profile is not None:
        kw["profile"] = profile
    else:
        kw["hk"] = spec["hk"]
    return _material_and_mesh(kw, spec, material)


def _material_and_mesh(kw, spec, material):
    """``kw`` with the material (``material``, else the standard linear solid of the spec's
    ``ratio``), the mesh options the spec sets and its layer: what bem.solve and
    bem.solve_surface take alike."""
    if material is not None:
        kw["material"] = material
    else:
        kw["ratio"] = spec["ratio"]
    for name in ("nodes", "rtol", "max_nodes"):
        if spec.get(name) is not None:
            kw[name] = spec[name]
    if spec.get("layer") is not None:
        kw["layer"] = layer(spec["layer"])
    return kw


def layer(description):
    """The BEM's layer (``bem.Layer``) of a plain description: ``foundation``, ``nu`` and one of
    ``thickness_over_wavelength`` (d/λ) and ``thickness`` (k d), as given (the Layer refuses,
    naming the parameter)."""
    import bem
    return bem.Layer(**{k: description.get(k) for k in ("thickness", "thickness_over_wavelength",
                                                        "foundation", "nu")})


def _analytic_layer(description):
    """The Fourier reference's layer mapping (k d, foundation, ν) of a plain description."""
    if description is None:
        return None
    kd = description.get("thickness")
    if kd is None:
        kd = 2.0 * math.pi * float(description["thickness_over_wavelength"])
    return {"thickness": float(kd), "foundation": description["foundation"],
            "nu": float(description["nu"])}


def validate_analytic(spec):
    """``analytic.validate`` on a spec (ValueError naming the first input it refuses)."""
    import analytic
    analytic.validate(**_controls(spec), speed=spec["speed"], ratio=spec["ratio"], hk=spec["hk"])


def validate_bem(spec, problem):
    """``bem.validate`` on a spec and its ``problem`` (see `bem_record`); a spec's ``layer``
    is checked there too (its thickness, foundation and ν, the mesh it allows, the depth a
    penetration reaches)."""
    import bem
    bem.validate(**_bem_kwargs(spec, problem))


def term_floor() -> float:
    """The smallest non-zero creep term over J(0+) the BEM takes (``bem.TERM_MIN``): a fitted
    series' smaller terms are dropped before it (`comparisons._materials.bem_series`)."""
    import bem
    return bem.TERM_MIN


def accepted(solver):
    """The road's table of accepted inputs, name → (low, high, what is allowed and why)."""
    return _road(solver).ACCEPTED


def si_groups(solver, scales):
    """The dimensionless groups of the SI problem ``scales`` (`viscosine.si.groups`), each
    checked by the road's own ``validate`` (ValueError naming the SI input)."""
    from viscosine import si
    return si.groups(scales, _road(solver).validate, accepted(solver),
                      with_hk=("load",) if solver == "bem" else ())


def analytic_record(spec, points, deep):
    """Adapter of the semi-analytic road (``analytic.solve`` → record, fields, constraints).

    ``points``: the fields on that many points of a uniform grid, or None (no fields);
    ``deep``: the constraint figures from the graded quadrature of the fields (a few ms).
    """
    import analytic
    from viscosine import protocol
    sol = analytic.solve(**_controls(spec), speed=spec["speed"], ratio=spec["ratio"], hk=spec["hk"])
    rec = _worded(sol.as_dict(), spec, sol.warnings, protocol.instantaneous_compliance(sol))
    if not sol.success:
        return Solved(rec, None, None)
    f = None
    if points is not None:
        f = sol.fields(np.arange(points) / points - 0.5)
    c = None
    if deep:  # graded quadrature of the fields: exact constraints, a few ms
        chk = sol.check()
        c = {"min_pressure": chk.get("min_pressure", chk.get("min_pressure_over_load")),
             "min_gap": chk["min_gap"], "mean_pressure_error": chk["mean_pressure_error"]}
    return Solved(rec, f, c)


def bem_record(spec, problem, want_fields):
    """Adapter of the BEM road (``bem.solve`` → record, fields, constraints).

    ``problem``: ``(profile, material)``, the parsed profile and creep series of the spec, None
    for the sinusoid of its ``hk`` and the standard linear solid of its ``ratio``.  The
    constraint figures come with every converged result (the panel values are at hand).
    """
    import bem
    from viscosine import protocol
    res = bem.solve(**_bem_kwargs(spec, problem))
    rec = _worded(res.as_dict(), spec, res.warnings, protocol.instantaneous_compliance(res))
    rec.setdefault("iterations", int(res.nit))
    rec["profile_file"] = spec.get("profile")
    rec["prony_file"] = spec.get("prony")
    if not res.success:
        return Solved(rec, None, None)
    f = res.fields()
    # the panel values are at hand: the constraints cost nothing on this road.  The mean σ is
    # the fields' own quadrature: after a contact window the grid is not uniform (fine window
    # panels, coarse periodic ones), and each panel weighs its width
    smax = float(np.max(f.pressure)) if f.pressure.size else 0.0
    load = rec.get("load") or float(res.load)
    c = {"min_pressure": float(np.min(f.pressure)) / smax if smax > 0 else 0.0,
         "min_gap": float(np.min(f.gap)),
         "mean_pressure_error": abs(f.mean("pressure") / load - 1.0)}
    return Solved(rec, f if want_fields else None, c)


def _worded(rec, spec, own, j_plus):
    """A record whose ``warnings`` are the road's own (``own``, the result's) and then its unit
    slips in the units the point was given in (`viscosine.si.slip_warnings`: in SI, naming the
    pressure in Pa and the modulus, under ``--units SI``, the spec's ``si``; in the conventions'
    groups otherwise), line and surface alike.  ``j_plus``: J(0+) over the reference compliance."""
    from viscosine import si
    if rec.get("success"):
        rec["warnings"] = list(own) + si.slip_warnings(
            spec.get("si"), rec["load"], rec["contact_fraction"], j_plus,
            bool(rec["full_contact"]))
    return rec


# ------------------------------------------------------------------------------ surfaces
def surface(description, parsed=None):
    """The BEM's surface (``bem.Surface``) of a spec's plain ``surface`` description: a
    bi-sinusoid, a self-affine surface (its seed fixes it), or a file's (``parsed`` when read
    already).  The constructors check the values, naming the parameter."""
    import bem
    kind = description["kind"]
    aspect = description.get("aspect")
    aspect = 1.0 if aspect is None else aspect
    if kind == "bisinusoid":
        return bem.bisinusoid(op.hk_of(description), description.get("hk_y"), aspect)
    if kind == "self_affine":
        kw = {k: description[k] for k in ("hurst", "rolloff", "short_cutoff", "long_cutoff",
                                          "rms_slope", "rms_height", "seed")
              if description.get(k) is not None}
        return bem.self_affine(**kw, aspect=aspect)
    return parsed if parsed is not None else bem.read_surface(description["path"])


def read_surface(path, units="conventions", length=None):
    """A file of heights on a grid, read by the BEM's own reader (``bem.read_surface``): k z,
    or metres (``units="SI"``) over the cell's side ``length`` Lx [m]."""
    import bem
    return bem.read_surface(path, units=units, length=length)


def _surface_kwargs(spec, material, parsed):
    """bem.solve_surface's keywords for a surface spec (``material``: None for the standard
    linear solid of its ``ratio``; ``parsed``: a surface file's Surface, when read)."""
    kw = dict(_controls(spec), speed=spec["speed"], direction=spec["direction"],
              surface=surface(spec["surface"], parsed))
    return _material_and_mesh(kw, spec, material)


def validate_surface(spec, material, parsed):
    """``bem.validate_surface`` on a surface spec (ValueError naming the first bad input)."""
    import bem
    bem.validate_surface(**_surface_kwargs(spec, material, parsed))


def surface_record(spec, material, parsed, want_fields):
    """Adapter of the surface BEM (``bem.solve_surface`` → record, fields, constraints); the
    constraint figures from the panel values (σ ≥ 0 over max σ, gap ≥ 0 over h_ref, mean σ
    against the load), as on the line."""
    import bem
    res = bem.solve_surface(**_surface_kwargs(spec, material, parsed))
    j_plus = material.j_plus if material is not None else 1.0 / spec["ratio"]
    rec = _worded(res.as_dict(), spec, res.warnings, j_plus)
    if not res.success:
        return Solved(rec, None, None)
    smax = float(np.max(res.pressure))
    c = {"min_pressure": float(np.min(res.pressure)) / smax if smax > 0 else 0.0,
         "min_gap": float(np.min(res.gap)),
         "mean_pressure_error": abs(float(np.mean(res.pressure)) / res.load - 1.0)}
    return Solved(rec, res.fields() if want_fields else None, c)


def persson(load, speed, spectrum, ratio):
    """Persson's theory (``analytic.references.persson``) on a self-affine spectrum (``hurst``,
    ``rolloff``, ``short_cutoff``, ``rms_slope`` of a surface description): (μ, contact
    fraction); RuntimeError when its quadrature did not meet its own bound."""
    from analytic.references import persson as theory
    kw = {k: spectrum[k] for k in ("hurst", "rolloff", "short_cutoff", "long_cutoff",
                                   "rms_slope", "rms_height") if spectrum.get(k) is not None}
    res = theory.solve(load=load, speed=speed, ratio=ratio, **kw)
    if not res.success:
        raise RuntimeError(f"Persson's theory at load={load}, speed={speed}: {res.message}")
    return res.mu, res.contact_fraction


# ------------------------------------------------------------------------------ operating points
def point_controls(point):
    """``{"load": p̃∞}`` or ``{"penetration": Δ/h}`` of an operating point dict, as a float."""
    if point.get("load") is not None:
        return {"load": float(point["load"])}
    return {"penetration": float(point["penetration"])}


def analytic_solution(point):
    """The semi-analytic solution (``analytic.solve``) at an operating point dict: ``load`` or
    ``penetration``, ``speed``, ``ratio`` (default 3), ``hk`` (default 1)."""
    import analytic
    return analytic.solve(**point_controls(point), speed=float(point["speed"]),
                          ratio=op.ratio_of(point), hk=op.hk_of(point))


def fourier_solution(point, material):
    """The Fourier reference at an operating point on the sinusoid (load or penetration control)
    for the creep series ``material`` (a :class:`bem.Prony`, the BEM's own input, so that both
    roads solve the same material).

    ``require_resolved=False``: broad spectra have memory layers far below any grid, which the
    reference's estimates and refusals judge, not a blanket refusal.  A point's ``layer`` (a
    plain description, see `layer`) puts the same layer under both codes.
    """
    import analytic
    kw = {} if point.get("layer") is None else {"layer": _analytic_layer(point["layer"])}
    return analytic.fourier_solve(**point_controls(point), speed=float(point["speed"]),
                                  creep=(float(material.J0), tuple(float(j) for j in material.J),
                                         tuple(float(t) for t in material.tau)),
                                  hk=op.hk_of(point), require_resolved=False, **kw)


def _case_bem_kwargs(point, problem) -> dict:
    """The keywords of the line BEM at a suite case's point dict but the mesh: ``problem`` is
    ``(profile, material)``, the BEM's objects; the point's ``layer`` (a plain description, see
    `layer`), if any, under the profile; Krylov tolerance `BEM_TOL`."""
    profile, material = problem
    kw = {} if point.get("layer") is None else {"layer": layer(point["layer"])}
    return dict(profile=profile, material=material, speed=float(point["speed"]), tol=BEM_TOL,
                **point_controls(point), **kw)


def bem_solution(point, nodes, problem):
    """The BEM solution at an operating point dict on ``nodes`` panels (`_case_bem_kwargs`)."""
    import bem
    return bem.solve(nodes=int(nodes), **_case_bem_kwargs(point, problem))


def bem_meshes(point, nodes, problem):
    """`bem_solution` on each mesh of ``nodes`` (``bem.solve_meshes``: the grids solved once, as
    one nested sequence): an iterator of the results, coarse to fine, each as its grid is
    solved."""
    import bem
    return bem.solve_meshes(nodes=[int(n) for n in nodes], **_case_bem_kwargs(point, problem))


def full_contact_load(speed, ratio, hk, layer_description=None):
    """p̃FC(V) of the sinusoid on the standard linear solid ``ratio``, on the half-space or on a
    layer (a plain description, see `layer`): the closed form ``analytic.full_contact``
    (Appendix B; on a layer mode 1 carries the factor S(kd))."""
    from analytic.references.fourier import full_contact
    kw = {} if layer_description is None else {"layer": _analytic_layer(layer_description)}
    return float(full_contact(float(speed), hk=float(hk), ratio=float(ratio),
                                       **kw)["load_threshold"])


def transition_load(speed, ratio, hk):
    """p̃FC(V), the smallest load of full contact (``analytic.transition_load``)."""
    import analytic
    return analytic.transition_load(speed, ratio, hk)


def threshold_speed(load, ratio, hk):
    """The speed at which ``load`` reaches full contact (``analytic.threshold_speed``)."""
    import analytic
    return analytic.threshold_speed(load, ratio, hk)


# ------------------------------------------------------------------------------ the BEM's inputs
def read_profile(path):
    """A periodic profile file, read by the BEM's own reader (``bem.read_profile``)."""
    import bem
    return bem.read_profile(path)


def read_prony(path):
    """A Prony-series creep function file, read by the BEM's own reader (``bem.read_prony``)."""
    import bem
    return bem.read_prony(path)


def sinusoid(hk):
    """The sinusoidal indenter of amplitude times wavenumber ``hk`` (``bem.Sinusoid``)."""
    import bem
    return bem.Sinusoid(hk)


def standard_linear_solid(ratio):
    """The standard linear solid E∞/E0 = ``ratio`` as the BEM's creep series."""
    import bem
    return bem.Prony.standard_linear_solid(ratio)


def prony(J0, J, tau):
    """A creep series J(t) = J0 − Σ J_i exp(−t/τ_i) as the BEM's material (``bem.Prony``)."""
    import bem
    return bem.Prony(J0, J, tau)


# ------------------------------------------------------------------------------ their source
def source_hash() -> str:
    """Hash of the two roads' source files: a resumed check never reuses another code's results."""
    import analytic
    import bem
    h = hashlib.sha256()
    for pkg in (analytic, bem):
        root = Path(pkg.__file__).parent
        for f in sorted(root.rglob("*.py")):  # subpackages too: analytic.references
            h.update(f.relative_to(root).as_posix().encode())
            h.update(f.read_bytes())
    return h.hexdigest()


# ------------------------------------------------------------------------------ surface cases
def _surface_point_kwargs(point):
    """The keywords a surface operating point dict (``surface``: a plain description,
    ``direction``, ``load`` or ``penetration``, ``speed``, ``ratio``; ``layer`` optional) gives
    both surface solvers, as floats."""
    return dict(point_controls(point), speed=float(point["speed"]),
                direction=op.direction_of(point))


def _case_surface_kwargs(point) -> dict:
    """The keywords of the surface BEM at a surface operating point dict but the grid: Krylov
    tolerance `BEM_TOL`; the point's ``layer`` (a plain description, see `layer`), if any,
    under it."""
    kw = {} if point.get("layer") is None else {"layer": layer(point["layer"])}
    return dict(_surface_point_kwargs(point), surface=surface(point["surface"]),
                ratio=op.ratio_of(point), tol=BEM_TOL, **kw)


def surface_solution(point, nodes):
    """The surface BEM (``bem.solve_surface``) at a surface operating point dict on a fixed grid
    of ``nodes`` panels along x (its halvings solved too: its own estimate)."""
    import bem
    return bem.solve_surface(nodes=int(nodes), **_case_surface_kwargs(point))


def surface_meshes(point, nodes):
    """`surface_solution` on each grid of ``nodes`` (``bem.solve_surface_meshes``: the grids
    solved once): an iterator of the results, coarse to fine, each as its grid is solved."""
    import bem
    return bem.solve_surface_meshes(nodes=[int(n) for n in nodes], **_case_surface_kwargs(point))


def surface_harmonics(description):
    """The surface of a plain description as harmonics ``{(m, n): c}``, k z = Σ Re[c e^{2πi(m x +
    n y/aspect)}] (the surface reference's form), and its aspect: the BEM's band-limited surface
    (its seeded synthesis for a self-affine one) handed over as numbers."""
    s = surface(description)
    # the BEM keeps one mode of each conjugate pair, heights Σ Re(2 c e^{...})
    return {(int(m), int(n)): 2.0 * complex(c) for (m, n), c in zip(s.modes, s.coefficients)}, \
        float(s.aspect)


def surface_reference_solution(point, nodes):
    """The independent surface reference (``analytic.references.surface.solve``: Douglas–Rachford
    splitting, its own measurements and Richardson estimate) at a surface operating point dict
    on the grids ``nodes`` (panels along x); the point's ``layer`` (a plain description, see
    `layer`), if any, under it as the reference's own mapping (k d, foundation, ν: mode q's
    symbol times its own layer factor S(|q| k d, ν), ``analytic.references._layer``)."""
    from analytic.references import surface as surface_reference
    kw = {} if point.get("layer") is None else {"layer": _analytic_layer(point["layer"])}
    heights, aspect = surface_harmonics(point["surface"])
    return surface_reference.solve(**_surface_point_kwargs(point), heights=heights,
                                   aspect=aspect, ratio=op.ratio_of(point),
                                   nodes=tuple(int(n) for n in nodes), **kw)


def bisinusoid_full_contact(speed, direction, ratio, hk, hk_y):
    """Full contact of the bi-sinusoid k z = hk cos kx + hk_y cos ky (square cell) on the
    standard linear solid ``ratio``, from the line's Appendix B (``analytic.references
    .fourier.full_contact``): each family of ridges is the line's sinusoid sliding at the speed
    component across it, w cos θ and w sin θ (``docs/surfaces.md`` §2.2, §2.3).

    Returns ``{"tau_f", "lateral", "load_threshold"}``: the friction stress along V and the
    lateral force per unit area (both independent of the load in full contact) and p̃_FC, the
    sum of the two families' thresholds."""
    from analytic.references.fourier import full_contact
    th = math.radians(float(direction))
    c, s = math.cos(th), math.sin(th)
    tau, lat, fc = 0.0, 0.0, 0.0
    # the ridges along y (mode (1, 0)) pull along −x, those along x (mode (0, 1)) along −y, each
    # with the line's friction at its signed speed; projected on ê and ê⊥ = (−sin θ, cos θ)
    for amp, comp, along, across in ((hk, c, c, -s), (hk_y, s, s, c)):
        if amp <= 0.0:
            continue
        fam = full_contact(abs(float(speed) * comp), hk=float(amp), ratio=float(ratio))
        t = math.copysign(float(fam["tau_f"]), comp) if comp != 0.0 else 0.0
        tau += along * t
        lat -= across * t
        fc += float(fam["load_threshold"])
    return {"tau_f": tau, "lateral": lat, "load_threshold": fc}


def surface_on_grid(description, nx, ny):
    """The surface of a plain description at the panel centres of an nx × ny grid (x_i = i/nx
    − ½, y_j = (j/ny − ½) Ly/Lx): ``heights`` k z (mean 0), the exact ``slope_x``, ``slope_y``
    (dz/dx, dz/dy), ``amplitude`` k h_ref and ``aspect``; ValueError naming ``nodes`` when
    the grid cannot hold the surface's finest mode."""
    s = surface(description)
    gx, gy = s.gradient(nx, ny)
    return {"heights": s.sample(nx, ny), "slope_x": gx, "slope_y": gy,
            "amplitude": float(s.amplitude), "aspect": float(s.aspect)}
