"""The SI front both roads share: inputs in SI turned into the dimensionless groups, and a
dimensionless result turned back into SI.  Nothing here solves anything.

Natural units: lengths 1/k = λ/(2π) (or h), stresses E0/(1 − ν²), times τ (the creep time of the
standard linear solid, J(t) = 1/E0 − (1/E1) e^{−t/τ}; a relaxation time τ_R of the same solid is
τ E0/E∞).  The solid's time is given by name, ``tau_creep`` or ``tau_relax`` (`creep_time`); a
bare ``tau`` is refused, since the two differ by the factor E∞/E0 and a swap shifts every
speed by it.  For any other material (`material_scales`) the reference modulus E_ref is its
relaxed modulus and the reference time τ_ref is 1 s, so the speed group is V k × 1 s.
"""
from __future__ import annotations

import math
import warnings as _warnings
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from . import protocol
from .checks import allowed_part, bad, real
from .fields import Fields


@dataclass(frozen=True)
class SIScales:
    """The SI problem in dimensionless groups, and the scales that take results back."""

    ratio: float | None  # E∞/E0 of the standard linear solid (None: another material)
    hk: float           # h k
    speed: float        # V/V0 = V τ k
    load: float | None  # p̃∞, or None under penetration control
    penetration: float | None  # Δ/h, or None under load control
    k: float            # wavenumber [1/m]
    estar: float        # E0/(1 − ν²) [Pa]
    wavelength: float   # λ [m]
    amplitude: float    # h [m]
    tau: float          # the reference time τ_ref [s]: the creep time τ of the solid, else 1 s
    given: dict         # the SI inputs each group comes from, as passed (for refusals)
    time_given: str | None = None  # "tau_creep" or "tau_relax" (the solid), None otherwise
    nu: float | None = None        # Poisson's ratio

    @property
    def E_ref(self) -> float:
        """The reference modulus [Pa]: E0 of the solid, a material's relaxed modulus."""
        return self.estar * (1.0 - self.nu ** 2) if self.nu is not None else math.nan

    def describe(self) -> dict:
        """The scales as a self-explaining JSON object: each value, its ``units`` (key → unit)
        and, for the standard linear solid, both times (``tau_creep`` and ``tau_relax`` =
        τ E0/E∞) and which was given (``time_given``)."""
        out = {"E_ref": self.E_ref, "plane_strain_modulus": self.estar, "nu": self.nu,
               "wavelength": self.wavelength, "k": self.k, "amplitude": self.amplitude,
               "tau_ref": self.tau}
        units = dict(UNITS)
        if self.ratio is not None:
            out.update(ratio=self.ratio, tau_creep=self.tau, tau_relax=self.tau / self.ratio,
                       time_given=self.time_given)
            out["tau_ref_is"] = "tau_creep, the creep (retardation) time of eq. (2.3)"
        else:
            out["tau_ref_is"] = "1 s, the time unit of the material's series"
        out["load_is"] = "p_inf (1 - nu^2)/E_ref"
        out["speed_is"] = "V tau_ref k, k = 2 pi/wavelength"
        out["units"] = {k: units[k] for k in out if k in units}
        return out


#: the unit of every SI key a record or a result carries ("-": a pure number)
UNITS = {"E_ref": "Pa", "E0": "Pa", "Einf": "Pa", "plane_strain_modulus": "Pa", "nu": "-",
         "wavelength": "m", "length": "m", "k": "1/m", "amplitude": "m", "tau_ref": "s",
         "tau_creep": "s", "tau_relax": "s", "ratio": "-", "contact_halfwidth": "m",
         "eccentricity": "m", "pressure_eccentricity": "m", "penetration": "m",
         "mean_separation": "m", "separation": "m", "mean_pressure": "Pa",
         "friction_stress": "Pa", "friction_coefficient": "-", "mu": "-", "mu_lateral": "-",
         "max_pressure": "Pa", "x_max_pressure": "m", "full_contact_pressure": "Pa",
         "threshold_speed": "m/s", "speed": "m/s", "contact_fraction": "-", "n_patches": "-",
         "speed_group": "-", "load": "-", "thickness": "m", "approach": "m"}


#: why a bare ``tau`` is refused, and the two names to choose from (every SI door says it)
TIME_NAMES = ("tau_creep (the creep, retardation, time of eq. 2.3) or tau_relax (the "
              "relaxation time, tau_creep E0/Einf) [s]")


def creep_time(*, E0, Einf, tau=None, tau_creep=None, tau_relax=None) -> float:
    """The creep (retardation) time τ of the standard linear solid, from the one time given.

    ``tau_relax`` is the relaxation time τ_R, the time over which the stress relaxes under a
    step of strain, τ_R = τ E0/E∞, so τ = τ_R E∞/E0.  A bare ``tau`` is refused: which of the
    two it means cannot be told.  E0 < E∞ are taken as already checked.

    Raises
    ------
    ValueError
        ``tau`` given, not exactly one of ``tau_creep`` and ``tau_relax``, or a time that is
        not finite and > 0.
    """
    if tau is not None:
        raise ValueError(f"tau={tau!r} is not allowed: which time? give {TIME_NAMES}")
    given = {k: v for k, v in (("tau_creep", tau_creep), ("tau_relax", tau_relax))
             if v is not None}
    if not given:  # the one form of a parameter not given, as at the command line
        raise ValueError(f"tau_creep is missing: give exactly one time of the standard linear "
                         f"solid, {TIME_NAMES}")
    if len(given) != 1:
        shown = ", ".join(f"{k}={v!r}" for k, v in given.items())
        raise ValueError(f"{shown} is not allowed: give exactly one time of the standard linear "
                         f"solid, {TIME_NAMES}")
    (name, value), = given.items()
    if name == "tau_relax":
        t = real(name, value, "a finite relaxation time > 0", lambda v: v > 0.0, unit="s")
        return t * (Einf / E0)
    return real(name, value, "a finite creep (retardation) time > 0", lambda v: v > 0.0, unit="s")


def _modulus(E0):
    return real("E0", E0, "a finite modulus > 0", lambda v: v > 0.0, unit="Pa")


def _poisson(nu):
    return real("nu", nu, "a Poisson ratio in (-1, 0.5]", lambda v: -1.0 < v <= 0.5, unit="-")


def _amplitude(h):
    return real("amplitude", h, "a finite length > 0", lambda v: v > 0.0, unit="m")


def field_scales(*, E0, nu, amplitude):
    """(E0 [Pa], ν, h [m]) checked as `scales` checks them: what converts SI fields (pressure
    over E0/(1 − ν²), lengths over h) when nothing else of the problem is given."""
    return _modulus(E0), _poisson(nu), _amplitude(amplitude)


def scales(*, E0, Einf, tau=None, nu, wavelength, amplitude, speed, mean_pressure=None,
           penetration=None, tau_creep=None, tau_relax=None) -> SIScales:
    """Validate SI inputs (ValueError naming the parameter, its value and what is allowed).

    The solid's time is exactly one of ``tau_creep`` and ``tau_relax`` (`creep_time`; a bare
    ``tau`` is refused); the speed group is V τ k with τ the creep time.
    """
    E0 = _modulus(E0)
    Einf = real("Einf", Einf, f"a finite modulus > E0 = {E0!r}", lambda v: v > E0, unit="Pa")
    tau = creep_time(E0=E0, Einf=Einf, tau=tau, tau_creep=tau_creep, tau_relax=tau_relax)
    sc = _scales(E0, tau, nu, wavelength, amplitude, speed, mean_pressure, penetration,
                 ratio=Einf / E0, given_ratio=Einf)
    return _replace(sc, time_given="tau_relax" if tau_relax is not None else "tau_creep")


def material_scales(*, E_ref, tau_ref=1.0, nu, wavelength, amplitude, speed, mean_pressure=None,
                    penetration=None) -> SIScales:
    """SI inputs for any material, in units of its relaxed modulus ``E_ref`` [Pa] and
    ``tau_ref`` [s] (1 s: the speed group is then V k × 1 s); ``ratio`` is None.

    ``amplitude`` is h = max(y) − mean(y) of the profile [m].  Raises as `scales`.
    """
    E_ref = real("E_ref", E_ref, "a finite relaxed modulus > 0", lambda v: v > 0.0, unit="Pa")
    tau_ref = real("tau_ref", tau_ref, "a finite time > 0", lambda v: v > 0.0, unit="s")
    return _scales(E_ref, tau_ref, nu, wavelength, amplitude, speed, mean_pressure, penetration,
                   ratio=None, given_ratio=None)


def _scales(E0, tau, nu, wavelength, amplitude, speed, mean_pressure, penetration, *, ratio,
            given_ratio) -> SIScales:
    nu, h = _poisson(nu), _amplitude(amplitude)
    lam = real("wavelength", wavelength, "a finite length > 0", lambda v: v > 0.0, unit="m")
    V = real("speed", speed, "a finite speed >= 0", lambda v: v >= 0.0, unit="m/s")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError(f"mean_pressure={mean_pressure!r}, penetration={penetration!r} is not "
                         "allowed: give exactly one of mean_pressure [Pa] and penetration [m]")
    k = 2.0 * math.pi / lam
    estar = E0 / (1.0 - nu * nu)
    load = pen = None
    if mean_pressure is not None:
        load = real("mean_pressure", mean_pressure, "a finite pressure > 0", lambda v: v > 0.0,
                    unit="Pa") / estar
    else:
        pen = real("penetration", penetration, f"a finite depth in (0, amplitude = {h!r}]",
                   lambda v: 0.0 < v <= h, unit="m") / h
    given = {"load": mean_pressure, "penetration": penetration, "speed": speed,
             "ratio": given_ratio, "hk": amplitude}
    return SIScales(ratio, h * k, V * tau * k, load, pen, k, estar, lam, h, tau, given, nu=nu)


def _replace(sc, **kw):
    return replace(sc, **kw)


def slip_warnings(sc, load, contact_fraction, j_plus, full_contact=False) -> list:
    """`viscosine.protocol.unit_slips` of a result, worded in the units the point was given in.

    ``sc``: the `SIScales` of an SI point, or their description (`SIScales.describe`: the
    ``si`` of a command-line point), and the slip is named in the SI inputs (the mean pressure
    and the modulus it is measured against, and the likely slip); None: a dimensionless point,
    the conventions' wording (`viscosine.protocol.slip_warnings`).
    """
    if sc is None:
        return protocol.slip_warnings(load, contact_fraction, j_plus, full_contact)
    found = protocol.unit_slips(load, contact_fraction, j_plus, full_contact)
    if isinstance(sc, SIScales):
        estar, e, solid = sc.estar, sc.E_ref, sc.ratio is not None
    else:  # the description: its plane-strain modulus, E_ref, and a ratio for the solid only
        estar, e, solid = sc["plane_strain_modulus"], sc["E_ref"], sc.get("ratio") is not None
    p = load * estar
    what = "E0" if solid else "E_ref (the relaxed modulus)"
    out = []
    if "strain" in found:
        out.append(f"a mean pressure of {p:.3g} Pa with {what} = {e:.3g} Pa is "
                   f"{found['strain']:.2g} × the instantaneous plane-strain modulus: far outside "
                   "linear theory; the modulus in MPa given as Pa, or the pressure in the wrong unit?")
    if "sliver" in found:
        guess = "MPa given as Pa?" if p < 1e3 else "a pressure in the wrong unit?"
        out.append(f"a mean pressure of {p:.3g} Pa with {what} = {e:.3g} Pa leaves a vanishing "
                   f"sliver of contact (contact fraction {found['sliver']:.2g} < "
                   f"{protocol.SLIVER:g}): {guess}")
    return out


def warn_slips(texts):
    """Raise each of ``texts`` as a `viscosine.ViscosineWarning` (what the record carries)."""
    from . import ViscosineWarning
    for t in texts:
        _warnings.warn(t, ViscosineWarning, stacklevel=3)


# the SI input behind each dimensionless group, to name it when the group is out of range
_SOURCE = {"load": ("mean_pressure", "p∞(1 − ν²)/E0"), "penetration": ("penetration", "Δ/h"),
           "speed": ("speed", "V τ 2π/λ"), "ratio": ("Einf", "Einf/E0"),
           "hk": ("amplitude", "amplitude·2π/wavelength")}


def groups(sc: SIScales, validate, accepted, with_hk=()) -> dict:
    """The dimensionless keyword arguments of a road's ``solve`` for the SI problem `sc`, each
    checked by that road's ``validate`` against its ``accepted`` ranges.

    A group outside them is refused naming the SI input it comes from.  ``with_hk`` names the
    groups whose range the road states relative to hk (validated together with it).
    """
    out = {"speed": sc.speed, "hk": sc.hk}
    if sc.ratio is not None:  # the standard linear solid; any other material is the road's own
        out["ratio"] = sc.ratio
    if sc.load is not None:
        out["load"] = sc.load
    else:
        out["penetration"] = sc.penetration
    for name, value in out.items():
        try:
            validate(**{name: value}, **({"hk": sc.hk} if name in with_hk else {}))
        except ValueError:
            si_name, formula = _SOURCE[name]
            if sc.ratio is None:  # a material in units of its relaxed modulus and tau_ref
                formula = formula.replace("E0", "E_ref").replace("V τ", "V τ_ref")
            text = accepted[name][2]
            short = allowed_part(text)
            why = text[len(short) + 2:] if len(text) > len(short) else ""
            raise bad(si_name, sc.given[name], f"one giving {value:.3g} as {short}: it gives "
                      f"{formula} = {value!r}" + (f"; {why}" if why else "")) from None
    return out


@dataclass(frozen=True)
class SIResult:
    """One operating point in SI units (lengths m, stresses Pa, speeds m/s).

    ``solution`` is the dimensionless result behind it (either road's result object);
    ``error_estimate`` is its estimate (dimensionless: absolute for the contact fraction, ka,
    ke, kê; relative for Δ/h, τf, μ), or None.
    """

    success: bool
    message: str
    full_contact: bool
    contact_halfwidth: float | None   # a [m] (λ/2 in full contact); None with several patches
    eccentricity: float | None        # e [m], toward the leading edge; None in full contact
    pressure_eccentricity: float | None  # ê [m]
    penetration: float                # Δ [m]
    mean_separation: float            # s [m]
    mean_pressure: float              # p∞ [Pa]
    friction_stress: float            # τf [Pa], positive when it resists the motion
    friction_coefficient: float       # μ
    max_pressure: float               # [Pa]
    x_max_pressure: float             # [m]
    full_contact_pressure: float | None  # p_FC(V) [Pa], None where the road cannot say
    threshold_speed: float | None     # V_th [m/s] for this p∞ (0: never full; inf: always)
    wavelength: float                 # λ [m]
    amplitude: float                  # h [m]
    plane_strain_modulus: float       # E0/(1 − ν²) [Pa]
    error_estimate: Any
    solution: Any
    warnings: tuple = ()              # the solution's and the SI door's (a unit slip)
    scales: Any = None                # the SIScales behind it

    # the result protocol of every door (dimensionless already, or the solution's)
    @property
    def mu(self) -> float:
        """μ, the friction coefficient (= ``friction_coefficient``)."""
        return self.friction_coefficient

    @property
    def tau_f(self) -> float:
        """τf [Pa] (= ``friction_stress``)."""
        return self.friction_stress

    @property
    def contact_fraction(self) -> float:
        """2a/λ (1 in full contact)."""
        return float(self.solution.contact_fraction)

    @property
    def n_patches(self) -> int:
        return int(self.solution.n_patches)

    @property
    def status(self) -> int:
        return int(getattr(self.solution, "status", 0 if self.success else 1))

    @property
    def nodes(self):
        """The BEM's panels per period (None on the semi-analytic road)."""
        return getattr(self.solution, "nodes", None)

    def scalars(self) -> dict:
        """The SI scalars, keyed as `as_dict`'s ``si`` block (units in ``UNITS``)."""
        return {k: getattr(self, k) for k in _SI_KEYS}

    def as_dict(self) -> dict:
        """The dimensionless record with an ``si`` block of these scalars, ``si_scales`` (the
        scales, both times of the solid and which was given) and each block's ``units``."""
        rec = self.solution.as_dict()
        rec["warnings"] = list(self.warnings)
        rec["si"] = protocol.plain(dict(self.scalars(), units={k: UNITS[k] for k in _SI_KEYS}))
        if self.scales is not None:
            rec["si_scales"] = protocol.plain(self.scales.describe())
        return rec

    def fields(self, x=None) -> Fields:
        """σ [Pa], v [m] (into the body, from the deformed mean line) and gap [m] at x [m]
        (default: the solution's own points)."""
        X = None if x is None else np.asarray(x, dtype=float) / self.wavelength
        f = self.solution.fields(X)
        return Fields(f.x_over_lambda, f.pressure * self.plane_strain_modulus,
                      f.displacement * self.amplitude, f.gap * self.amplitude, units="SI",
                      edges=f.edges)


#: the SI scalars of a line result, in the order of its record's ``si`` block
_SI_KEYS = ("full_contact", "contact_halfwidth", "eccentricity", "pressure_eccentricity",
            "penetration", "mean_separation", "mean_pressure", "friction_stress",
            "friction_coefficient", "max_pressure", "x_max_pressure", "full_contact_pressure",
            "threshold_speed", "wavelength", "amplitude", "plane_strain_modulus")
UNITS["full_contact"] = "-"


def result(sol, sc: SIScales, *, full_contact_load=None, threshold_speed=None) -> SIResult:
    """Build the SI result from a dimensionless one (the result protocol of both roads).

    ``full_contact_load`` is p̃FC(V) and ``threshold_speed`` V_th/V0, when the road knows them.
    A load that looks like a unit slip (`slip_warnings`) is added to the result's
    ``warnings`` and raised as a `viscosine.ViscosineWarning`.
    """
    k = sc.k
    # a record's scalars (no contact fraction) carry their own warnings already
    slips = (slip_warnings(sc, float(sol.load), float(sol.contact_fraction),
                           protocol.instantaneous_compliance(sol), bool(sol.full_contact))
             if sol.success and getattr(sol, "contact_fraction", None) is not None else [])
    warn_slips(slips)

    def length(v):
        return None if v is None else float(v) / k

    return SIResult(
        success=bool(sol.success), message=str(sol.message), full_contact=bool(sol.full_contact),
        contact_halfwidth=length(sol.ka), eccentricity=length(sol.ke),
        pressure_eccentricity=length(sol.ke_hat),
        penetration=float(sol.penetration) * sc.amplitude,
        mean_separation=float(sol.separation) * sc.amplitude,
        mean_pressure=float(sol.load) * sc.estar,
        friction_stress=float(sol.tau_f) * sc.estar,
        friction_coefficient=float(sol.mu),
        max_pressure=float(sol.max_pressure) * sc.estar,
        x_max_pressure=float(sol.x_max_pressure) * sc.wavelength,
        full_contact_pressure=None if full_contact_load is None else full_contact_load * sc.estar,
        threshold_speed=None if threshold_speed is None else threshold_speed / (sc.tau * k),
        wavelength=sc.wavelength, amplitude=sc.amplitude, plane_strain_modulus=sc.estar,
        error_estimate=getattr(sol, "error_estimate", None), solution=sol,
        warnings=tuple(getattr(sol, "warnings", ())) + tuple(slips), scales=sc)
