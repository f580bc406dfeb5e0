"""The BEM road's fronts: sweeps as tables and the SI fronts, thin loops and scalings around
`bem.solve` and `bem.solve_surface` through the shared `viscosine.table` and `viscosine.si`
(nothing here solves).
"""
from __future__ import annotations

import math
import warnings
from dataclasses import dataclass

from viscosine import si, table
from viscosine.checks import real, reals

from . import _solver, _surface_solver
from ._accepted import ACCEPTED, TERM_MIN, validate
from ._inputs import Prony, SampledProfile
from ._layer import Layer
from ._surface import sampled_surface

def sweep(*, load=None, penetration=None, speed, errors=False, **options):
    """Solve every (load or penetration, speed) pair: loads outer, speeds inner.

    Parameters
    ----------
    load, penetration : sequence of float
        Exactly one: the controls (outer loop).
    speed : sequence of float
        V τ_ref k (inner loop).
    errors : bool
        Add the columns ``error_<key>`` from each result's ``error_estimate`` (NaN where the
        solver has none).
    **options
        Passed to every `bem.solve` (profile, material, ratio, hk, nodes, …).

    Returns
    -------
    dict of ndarray
        The table of `viscosine.table.sweep` (inputs, ``success``, the scalars, NaN where
        null, separation, max_pressure, x_max_pressure, n_patches, ``message``) plus ``nodes``.
        Bad input raises ValueError before any point is solved; a failing point is a row with
        success False.
    """
    return table.sweep(_solver.solve, validate, load=load, penetration=penetration,
                        speed=speed, errors=errors, extra=("nodes",), **options)


def solve_si(*, nu, wavelength, speed, amplitude=None, heights=None, material=None, E0=None,
             Einf=None, tau=None, tau_creep=None, tau_relax=None, mean_pressure=None,
             penetration=None, thickness=None, foundation=None, **bem_options):
    """Solve a sliding contact from SI data: any material, the sinusoid or a sampled profile.

    Parameters
    ----------
    nu : float
        Poisson's ratio, −1 < ν ≤ 0.5.
    wavelength : float
        λ [m], the period of the profile.
    speed : float
        V ≥ 0 [m/s].
    amplitude : float, optional
        h [m] of the sinusoid h cos(2π x/λ) (the paper's indenter).
    heights : array_like, optional
        Instead of ``amplitude``: the heights y [m] of one period of any profile sampled at
        ``x_j = (j/M − 1/2) λ`` (M ≥ 8, `bem.SampledProfile` of k y); h = max y − mean y.
    material : viscosine.materials.Maxwell, optional
        A relaxation-form Prony series, moduli in Pa and times in s, or a series fitted to DMA
        data (`viscosine.materials.fit_prony`, in the data's modulus unit, which the data's
        header must name: it is turned into Pa).  Its reference units are its relaxed modulus
        E_r and 1 s: the dimensionless speed is V k × 1 s.  Not with E0, Einf, tau_*.
    E0, Einf : float, optional
        Instead of ``material``, the standard linear solid of eq. (2.3): relaxed and
        instantaneous moduli [Pa], Einf > E0.
    tau_creep, tau_relax : float, optional
        With E0, Einf, exactly one time of the solid [s]: its creep (retardation) time τ or its
        relaxation time τ_R = τ E0/Einf, converted exactly (τ = τ_R Einf/E0).  The
        dimensionless speed is V τ k.  A bare ``tau`` is refused (ValueError naming the two).
    mean_pressure, penetration : float
        Exactly one: p∞ [Pa] or Δ [m], 0 < Δ ≤ h.
    thickness : float, optional
        d [m]: a layer of this thickness on a rigid foundation in place of the half-space
        (`bem.Layer` with d/λ and Poisson's ratio ``nu``); needs ``foundation``.
    foundation : {"bonded", "frictionless"}, optional
        With ``thickness``: the layer's lower face on the foundation.
    **bem_options
        Options of `bem.solve` (nodes, rtol, max_nodes, tol, …); not ``layer`` (give
        ``thickness`` and ``foundation``).

    Returns
    -------
    viscosine.SIResult
        Lengths in m, stresses in Pa; ``solution`` is the `BemResult`.  ``full_contact_pressure``
        is p_FC(V) = (hk/2)|E*(kV)|/(1 − ν²) of the sinusoid (Appendix B, eq. B6, from the
        material's own complex compliance; on a layer divided by S(kd, ν), the factor of its
        mode 1; None for a sampled profile); the layer's ``approach`` and ``mean_displacement``
        are in ``solution.diagnostics["layer"]`` (over h); ``threshold_speed`` is
        None (the BEM has no closed form for it).  A DMA fit probed at frequencies k_n V
        outside its measured window (n = 1 … ⌈λ/2a⌉, the harmonics of the contact) raises a
        `UserWarning` (the modulus there is extrapolated).

    Raises
    ------
    ValueError
        An SI input that is invalid, or whose dimensionless group lies outside `bem.ACCEPTED`
        (named by the SI parameter it comes from).

    References
    ----------
    Menga, Putignano, Carbone & Demelio (2014): eq. (2.3) (the solid and its creep time),
    eqs (2.7)–(2.8) (the modulus at the sliding frequency), eq. (B6) (full contact).
    """
    if bem_options.get("layer") is not None:
        raise ValueError(f"layer={bem_options['layer']!r} is not allowed: solve_si takes the "
                         "layer in SI (thickness= [m] and foundation=; nu= is its ratio)")
    for name in ("profile", "ratio", "hk", "load"):
        if name in bem_options:
            raise ValueError(f"{name}={bem_options[name]!r} is not allowed: solve_si takes the "
                             "problem in SI (profile as heights= [m], the material as "
                             "material= or E0, Einf, tau_creep)")
    profile, amplitude = _si_profile(heights, amplitude, wavelength)
    model, sc, prony = _si_material(
        material, {"E0": E0, "Einf": Einf, "tau": tau, "tau_creep": tau_creep,
                   "tau_relax": tau_relax},
        {"nu": nu, "wavelength": wavelength, "amplitude": amplitude, "speed": speed,
         "mean_pressure": mean_pressure, "penetration": penetration})
    groups = _bem_groups(sc, profile, prony if model is not None else None)
    layer = _si_layer(thickness, foundation, nu, sc.wavelength)
    validate(**{k: v for k, v in bem_options.items()})
    sol = _solver.solve(**groups, **bem_options, layer=layer)
    pfc = (None if profile is not None
           else 0.5 * sc.hk / abs(complex(prony.jstar([1.0], sc.speed)[0])))
    if pfc is not None and layer is not None:
        pfc /= float(layer.factor([1.0])[0])
    if model is not None and sol.success and sc.speed > 0.0:
        # the contact's harmonics n = 1 … ⌈λ/2a⌉, at ω_n = n k V (rad/s)
        top = math.ceil(1.0 / max(float(sol.contact_fraction), 1e-300) - 1e-9)
        text = model.extrapolation_warning(sc.speed, sc.speed * max(1, top))
        if text is not None:
            warnings.warn(text, UserWarning, stacklevel=2)
    return si.result(sol, sc, full_contact_load=pfc, threshold_speed=None)


def _si_layer(thickness, foundation, nu, wavelength):
    """The `bem.Layer` of ``thickness`` d [m] over ``wavelength`` (None without a thickness)."""
    if thickness is None:
        if foundation is not None:
            raise ValueError(f"foundation={foundation!r} is not allowed without thickness=: it "
                             "is the lower face of a layer of thickness d [m]")
        return None
    d = real("thickness", thickness, "a finite layer thickness d > 0 [m]", lambda v: v > 0.0)
    if foundation is None:
        raise ValueError("foundation=None is not allowed with thickness=: 'bonded' or "
                         "'frictionless' (the layer's lower face on the rigid foundation)")
    return Layer(thickness_over_wavelength=d / wavelength, foundation=foundation, nu=nu)


def _bem_groups(sc, profile, prony):
    """The keyword arguments of `bem.solve` for the SI problem ``sc``, each checked against
    `bem.ACCEPTED`: the dimensionless groups, ``profile`` (when sampled) in place of hk, and
    ``prony`` (a Maxwell series' creep function) in place of the solid's ratio."""
    groups = si.groups(sc, validate, ACCEPTED, with_hk=("load",))
    if profile is not None:
        del groups["hk"]
        groups["profile"] = profile
    if prony is not None:
        groups["material"] = prony
    validate(**{k: v for k, v in groups.items() if k in ("material", "profile")})
    return groups


def _si_profile(heights, amplitude, wavelength):
    """(profile, amplitude [m]): the `SampledProfile` of k y from ``heights`` [m] and its
    amplitude, or (None, ``amplitude``) for the sinusoid."""
    if heights is None:
        return None, amplitude
    if amplitude is not None:
        raise ValueError(f"amplitude={amplitude!r} is not allowed with heights=: the "
                         "sampled profile fixes its amplitude (max y − mean y)")
    lam = real("wavelength", wavelength, "a finite length > 0", lambda v: v > 0.0, unit="m")
    k = 2.0 * math.pi / lam
    ky = reals("heights", heights, "a 1-D array of heights", unit="m") * k
    profile = SampledProfile(ky)
    return profile, profile.amplitude / k


def _si_material(material, sls, problem):
    """(model in Pa or None, scales, `Prony`) of the material: a Maxwell series ``material``
    (reference units its relaxed modulus and 1 s), else the standard linear solid of ``sls``
    (E0, Einf and one of its times, eq. 2.3).  ``problem``: the SI inputs the scales take
    besides (nu, wavelength, amplitude, speed, mean_pressure, penetration)."""
    if material is None:
        sc = si.scales(**sls, **problem)
        return None, sc, Prony.standard_linear_solid(sc.ratio)
    from viscosine.materials import Maxwell
    given = {k: v for k, v in sls.items() if v is not None}
    if given:
        name, value = next(iter(given.items()))
        raise ValueError(f"{name}={value!r} is not allowed with material=: the material "
                         "fixes the moduli and times")
    if not isinstance(material, Maxwell):
        raise ValueError(f"material={material!r} is not allowed: a "
                         "viscosine.materials.Maxwell (moduli in Pa, times in s, or a DMA "
                         "fit whose data name their modulus unit)")
    model = material.in_pascals()
    sc = si.material_scales(E_ref=model.E_r, tau_ref=1.0, **problem)
    # a fit's term below the floor (e.g. 1e-14 J(0+)) is dropped, not refused: a term of
    # weight w moves J* by at most w relative (viscosine.materials.Creep.without_negligible)
    creep, dropped = model.creep(E_ref=model.E_r, tau_ref=1.0).without_negligible(TERM_MIN)
    if dropped:
        warnings.warn(f"{len(dropped)} Prony term(s) below {TERM_MIN:g} J(0+) dropped (largest "
                      f"weight {dropped[0]:.2g}): J* moves by at most that fraction",
                      UserWarning, stacklevel=3)
    return model, sc, Prony(*creep)


def solve_surface_si(*, nu, length, speed, heights=None, surface=None, aspect=None,
                     material=None, E0=None, Einf=None, tau=None, tau_creep=None,
                     tau_relax=None, mean_pressure=None, penetration=None, direction=0.0,
                     thickness=None, foundation=None, **options):
    """Solve a rigid periodic surface's sliding contact from SI data (`bem.solve_surface`).

    Parameters
    ----------
    nu : float
        Poisson's ratio, −1 < ν ≤ 0.5.
    length : float
        Lx [m], the cell's side along x (k = 2π/Lx).
    speed : float
        V ≥ 0 [m/s].
    heights : array_like, optional
        The surface's heights z [m] on an (nx, ny) grid of one cell (rows along x; centres
        ``x_i = (i/nx − 1/2) Lx``, ``y_j = (j/ny − 1/2) Ly``), positive toward the body.
    surface : bem.Surface, optional
        Instead of ``heights``: a surface in the conventions' units (heights k z).
    aspect : float, optional
        Ly/Lx of ``heights`` (default ny/nx: square panels).
    material, E0, Einf, tau_creep, tau_relax
        As `bem.solve_si` (a bare ``tau`` refused): a `viscosine.materials.Maxwell` series, or
        the standard linear solid.
    mean_pressure, penetration : float
        Exactly one: p∞ [Pa] over the cell, or Δ [m], 0 < Δ ≤ h_ref.
    direction : float
        θ in degrees from +x.
    thickness, foundation
        A layer of thickness d [m] on a rigid foundation (as `bem.solve_si`).
    **options
        Options of `bem.solve_surface` (nodes, rtol, max_nodes, tol, …).

    Returns
    -------
    SurfaceSIResult
        The SI scalars beside the dimensionless ``solution`` (a `bem.SurfaceResult`).

    Raises
    ------
    ValueError
        An SI input that is invalid, named by its SI parameter.
    """
    for name in ("load", "ratio", "hk", "layer"):
        if name in options:
            raise ValueError(f"{name}={options[name]!r} is not allowed: solve_surface_si takes "
                             "the problem in SI")
    lx = real("length", length, "a finite cell side Lx > 0", lambda v: v > 0.0, unit="m")
    k = 2.0 * math.pi / lx
    if (heights is None) == (surface is None):
        raise ValueError(f"heights={heights!r} is not allowed: give exactly one of heights= [m] "
                         "and surface= (k z)")
    if heights is not None:
        z = reals("heights", heights, "a 2-D array of heights", unit="m")
        if z.ndim != 2:
            raise ValueError(f"heights=an array of shape {z.shape} is not allowed: a 2-D grid "
                             "of heights (rows along x, columns along y) [m]")
        surface = sampled_surface(z * k, z.shape[1] / z.shape[0] if aspect is None else aspect)
    amplitude = surface.amplitude / k
    model, sc, prony = _si_material(
        material, {"E0": E0, "Einf": Einf, "tau": tau, "tau_creep": tau_creep,
                   "tau_relax": tau_relax},
        {"nu": nu, "wavelength": lx, "amplitude": amplitude, "speed": speed,
         "mean_pressure": mean_pressure, "penetration": penetration})
    layer = _si_layer(thickness, foundation, nu, lx)
    control = {"load": sc.load} if sc.load is not None else {"penetration": sc.penetration}
    sol = _surface_solver.solve_surface(**control, speed=sc.speed, surface=surface,
                                        material=prony, direction=direction, layer=layer,
                                        **options)
    slips = (si.slip_warnings(sc, sol.load, sol.contact_fraction, prony.j_plus,
                              sol.full_contact) if sol.success else [])
    si.warn_slips(slips)
    return SurfaceSIResult.of(sol, sc, lx, slips)


@dataclass(frozen=True)
class SurfaceSIResult:
    """A surface solve in SI: lengths in m, stresses in Pa, speeds in m/s.

    Attributes
    ----------
    success, message : bool, str
        The dimensionless solution's.
    solution : bem.SurfaceResult
        The dimensionless answer (its ``error_estimate`` applies to the SI scalars alike).
    mu, mu_lateral, contact_fraction, n_patches : float, float, float, int
        Dimensionless already.
    mean_pressure, friction_stress, max_pressure : float
        p∞, τf = μ p∞ and the peak pressure [Pa].
    penetration, separation, length, amplitude : float
        Δ, s, Lx and h_ref [m].
    speed : float
        V [m/s].
    scales : dict
        The SI scales (`viscosine.si.SIScales.describe`: E_ref, E0/(1 − ν²) [Pa], k [1/m],
        τ_ref [s], both times of the solid and which was given, each key's ``units``) and the
        groups they gave (``load``, ``speed_group``).
    warnings : tuple of str
        The solution's warnings and the SI door's (a load that looks like a unit slip).

    The result protocol of every door: ``full_contact``, ``status``, ``nodes``,
    ``error_estimate``, ``tau_f`` (= ``friction_stress`` [Pa]) as on the dimensionless result.
    """

    success: bool
    message: str
    solution: object
    mu: float
    mu_lateral: float
    contact_fraction: float
    n_patches: int
    mean_pressure: float
    friction_stress: float
    max_pressure: float
    penetration: float
    separation: float
    length: float
    amplitude: float
    speed: float
    scales: dict
    warnings: tuple = ()

    @classmethod
    def of(cls, sol, sc, length, slips=()):
        e, h, k = sc.estar, sc.amplitude, sc.k
        scales = sc.describe()
        scales.update(load=sol.load, speed_group=sc.speed)
        scales["units"].update(load="-", speed_group="-")
        return cls(success=sol.success, message=sol.message, solution=sol, mu=sol.mu,
                   mu_lateral=sol.mu_lateral, contact_fraction=sol.contact_fraction,
                   n_patches=sol.n_patches, mean_pressure=sol.load * e,
                   friction_stress=sol.tau_f * e, max_pressure=sol.max_pressure * e,
                   penetration=sol.penetration * h, separation=sol.separation * h,
                   length=length, amplitude=h, speed=sc.speed / (sc.tau * k), scales=scales,
                   warnings=tuple(sol.warnings) + tuple(slips))

    # the result protocol of every door, from the dimensionless solution
    @property
    def full_contact(self) -> bool:
        return bool(self.solution.full_contact)

    @property
    def status(self) -> int:
        return int(self.solution.status)

    @property
    def nodes(self) -> int:
        return int(self.solution.nodes)

    @property
    def error_estimate(self):
        """The solution's estimate (dimensionless: it applies to the SI scalars alike)."""
        return self.solution.error_estimate

    @property
    def tau_f(self) -> float:
        """τf [Pa] (= ``friction_stress``)."""
        return self.friction_stress

    def scalars(self) -> dict:
        """The SI scalars (units: `viscosine.si.UNITS`)."""
        return {k: getattr(self, k) for k in (
            "mu", "mu_lateral", "contact_fraction", "n_patches", "mean_pressure",
            "friction_stress", "max_pressure", "penetration", "separation")}

    def as_dict(self) -> dict:
        """The dimensionless record with an ``si`` block (its scalars, the cell's length and
        amplitude and the speed, with ``units`` per key), ``si_scales`` (`scales`) and the
        warnings of both."""
        rec = self.solution.as_dict()
        rec["warnings"] = list(self.warnings)
        block = dict(self.scalars(), length=self.length, amplitude=self.amplitude,
                     speed=self.speed)
        block["units"] = {k: si.UNITS[k] for k in block}
        rec["si"] = block
        rec["si_scales"] = self.scales
        return rec
