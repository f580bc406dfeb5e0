"""A thin SI front: dimensional inputs in, the same results in SI out.

Nothing here solves anything: `viscosine.si.scales` turns the SI inputs into the dimensionless
groups (load p̃∞ = p∞(1 − ν²)/E0, speed V τ k, ratio E∞/E0, hk), `solver.solve` does the work
and `viscosine.si.result` scales the outputs back.  Natural units: lengths 1/k = λ/(2π),
stresses E0/(1 − ν²), times τ.
"""
from __future__ import annotations

from viscosine import si

from . import solver
from ._accepted import ACCEPTED
from .full_contact import threshold_speed, transition_load

def solve_si(*, E0, Einf, tau=None, nu, wavelength, amplitude, speed, mean_pressure=None,
             penetration=None, tau_creep=None, tau_relax=None):
    """Solve the paper's problem from SI data.

    Parameters
    ----------
    E0, Einf : float
        Relaxed and instantaneous Young's moduli [Pa], Einf > E0 (eq. 2.3: 1/E∞ = 1/E0 − 1/E1).
    tau_creep, tau_relax : float
        Exactly one time of the solid [s]: its creep (retardation) time τ of eq. (2.3), or its
        relaxation time τ_R = τ E0/E∞, converted exactly to τ = τ_R E∞/E0.  A bare ``tau`` is
        refused (ValueError naming the two).  The speed group is V τ k with the creep time.
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
    viscosine.SIResult
        Lengths in m, stresses in Pa, speeds in m/s; ``fields(x)`` (x in m) gives a
        `viscosine.Fields` with ``units="SI"``; ``solution`` is the dimensionless `Solution`.
        ``success`` is False (with the message) when the solve failed.

    Raises
    ------
    ValueError
        An SI input that is invalid or whose dimensionless group lies outside
        `analytic.ACCEPTED` (named by the SI parameter it comes from).
    """
    sc = si.scales(E0=E0, Einf=Einf, tau=tau, tau_creep=tau_creep, tau_relax=tau_relax, nu=nu,
                    wavelength=wavelength, amplitude=amplitude, speed=speed,
                    mean_pressure=mean_pressure, penetration=penetration)
    groups = si.groups(sc, solver.validate, ACCEPTED)
    sol = solver.solve(**groups)
    vth = threshold_speed(sol.load, sc.ratio, sc.hk) if sol.success else None
    return si.result(sol, sc, full_contact_load=transition_load(sc.speed, sc.ratio, sc.hk),
                      threshold_speed=vth)

