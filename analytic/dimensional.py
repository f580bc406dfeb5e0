"""A thin SI front: dimensional inputs in, the same results in SI out.

Nothing here solves anything: inputs are turned into the dimensionless groups of
`conventions.md`, `solver.solve` does the work, and the outputs are
scaled back.  Natural units: lengths 1/k = λ/(2π), stresses E0/(1 − ν²), times τ.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from . import solver
from .full_contact import threshold_speed, transition_load


def _positive(name, value, unit):
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r}: must be a real number > 0 [{unit}]") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name} = {value!r}: must be finite and > 0 [{unit}]")
    return v


@dataclass(frozen=True)
class SIResult:
    """One operating point in SI units (lengths m, stresses Pa, speeds m/s)."""

    full_contact: bool
    contact_halfwidth: float          # a [m] (λ/2 in full contact)
    eccentricity: float | None        # e [m], toward the leading edge; None in full contact
    pressure_eccentricity: float      # ê [m]
    penetration: float                # Δ [m]
    mean_separation: float            # s [m]
    mean_pressure: float              # p∞ [Pa]
    friction_stress: float            # τf [Pa], positive when it resists the motion
    friction_coefficient: float       # μ
    full_contact_pressure: float      # p_FC(V) [Pa]
    threshold_speed: float            # V_th [m/s] for this p∞ (0: never full contact; inf: always)
    wavelength: float                 # λ [m]
    amplitude: float                  # h [m]
    plane_strain_modulus: float       # E0/(1 − ν²) [Pa]
    solution: solver.Solution         # the dimensionless solution behind it

    def fields(self, x):
        """σ [Pa], v [m] (into the body, from the deformed mean line) and gap [m] at x [m]."""
        f = self.solution.fields(np.asarray(x, dtype=float) / self.wavelength)
        return (f.pressure * self.plane_strain_modulus, f.displacement * self.amplitude,
                f.gap * self.amplitude)


def solve_si(*, E0, Einf, tau, nu, wavelength, amplitude, speed, mean_pressure=None,
             penetration=None):
    """Solve the paper's problem from SI data.

    Parameters
    ----------
    E0, Einf : float
        Relaxed and instantaneous Young's moduli [Pa], Einf > E0 (eq. 2.3: 1/E∞ = 1/E0 − 1/E1).
    tau : float
        Creep (retardation) time of eq. (2.3) [s].  For a relaxation time τ_R of the same solid,
        τ = τ_R E∞/E0 (paper-notes 11).
    nu : float
        Poisson's ratio, −1 < ν ≤ 0.5.
    wavelength, amplitude : float
        λ and h of the rigid sinusoid h cos(2π(x − Vt)/λ) [m].
    speed : float
        Sliding speed V ≥ 0 [m/s].
    mean_pressure : float, optional
        p∞ [Pa] (load control).
    penetration : float, optional
        Δ [m], 0 < Δ ≤ h (penetration control).  Give exactly one of the two.

    Returns
    -------
    SIResult
    """
    E0 = _positive("E0", E0, "Pa")
    Einf = _positive("Einf", Einf, "Pa")
    if not Einf > E0:
        raise ValueError(f"Einf = {Einf!r}: must be > E0 = {E0!r} [Pa]")
    tau = _positive("tau", tau, "s")
    try:
        nu = float(nu)
    except (TypeError, ValueError):
        raise ValueError(f"nu = {nu!r}: must be a real number in (-1, 0.5]") from None
    if not (math.isfinite(nu) and -1.0 < nu <= 0.5):
        raise ValueError(f"nu = {nu!r}: must be in (-1, 0.5]")
    lam = _positive("wavelength", wavelength, "m")
    h = _positive("amplitude", amplitude, "m")
    try:
        V = float(speed)
    except (TypeError, ValueError):
        raise ValueError(f"speed = {speed!r}: must be a real number ≥ 0 [m/s]") from None
    if not (math.isfinite(V) and V >= 0.0):
        raise ValueError(f"speed = {speed!r}: must be finite and ≥ 0 [m/s]")
    if (mean_pressure is None) == (penetration is None):
        raise ValueError("give exactly one of mean_pressure [Pa] and penetration [m]")
    k = 2.0 * math.pi / lam
    estar = E0 / (1.0 - nu * nu)
    ratio, hk, w = Einf / E0, h * k, V * tau * k
    if mean_pressure is not None:
        p = _positive("mean_pressure", mean_pressure, "Pa")
        sol = solver.solve(load=p / estar, speed=w, ratio=ratio, hk=hk)
    else:
        d = _positive("penetration", penetration, "m")
        if d > h:
            raise ValueError(f"penetration = {penetration!r}: must be in (0, amplitude = {h!r}] [m]")
        sol = solver.solve(penetration=d / h, speed=w, ratio=ratio, hk=hk)
    if not sol.success:
        raise RuntimeError(f"the semi-analytic solver did not converge: {sol.message}; "
                           f"residuals {sol.residuals}")
    vth = threshold_speed(sol.load, ratio, hk)
    return SIResult(
        full_contact=sol.full_contact,
        contact_halfwidth=sol.ka / k,
        eccentricity=None if sol.ke is None else sol.ke / k,
        pressure_eccentricity=sol.ke_hat / k,
        penetration=sol.penetration * h,
        mean_separation=sol.separation * h,
        mean_pressure=sol.load * estar,
        friction_stress=sol.tau_f * estar,
        friction_coefficient=sol.mu,
        full_contact_pressure=transition_load(w, ratio, hk) * estar,
        threshold_speed=vth / (tau * k),
        wavelength=lam,
        amplitude=h,
        plane_strain_modulus=estar,
        solution=sol,
    )
