"""The BEM road's fronts: sweeps as tables and the SI front, thin loops and scalings around
`bem.solve` through the shared `viscosine._table` and `viscosine._si` (nothing here solves).
"""
from __future__ import annotations

from viscosine import _si, _table

from . import _solver
from ._accepted import ACCEPTED, validate
from ._inputs import Prony

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
        The table of `viscosine._table.sweep` (inputs, ``success``, the scalars, NaN where
        null, separation, max_pressure, x_max_pressure, n_patches, ``message``) plus ``nodes``.
        Bad input raises ValueError before any point is solved; a failing point is a row with
        success False.
    """
    return _table.sweep(_solver.solve, validate, load=load, penetration=penetration,
                        speed=speed, errors=errors, extra=("nodes",), **options)


def solve_si(*, E0, Einf, tau, nu, wavelength, amplitude, speed, mean_pressure=None,
             penetration=None, **bem_options):
    """Solve the paper's problem (a sinusoid on the standard linear solid) from SI data.

    Parameters
    ----------
    E0, Einf, tau, nu, wavelength, amplitude, speed, mean_pressure, penetration
        As in `analytic.solve_si`: moduli [Pa] (Einf > E0), the creep time of eq. (2.3) [s],
        Poisson's ratio, λ and h [m], V [m/s] and exactly one of p∞ [Pa] and Δ [m].
    **bem_options
        Options of `bem.solve` (nodes, rtol, max_nodes, tol, …).

    Returns
    -------
    viscosine.SIResult
        Lengths in m, stresses in Pa; ``solution`` is the `BemResult`.  ``full_contact_pressure``
        is p_FC(V) = (hk/2)|E*(kV)|/(1 − ν²) of the sinusoid (Appendix B, eq. B6, from the
        material's own complex compliance); ``threshold_speed`` is None (the BEM has no closed
        form for it).

    Raises
    ------
    ValueError
        An SI input that is invalid, or whose dimensionless group lies outside `bem.ACCEPTED`
        (named by the SI parameter it comes from).
    """
    for name in ("profile", "material", "ratio", "hk", "load"):
        if name in bem_options:
            raise ValueError(f"{name}={bem_options[name]!r} is not allowed: solve_si takes the "
                             "problem in SI (use bem.solve for other profiles and materials)")
    sc = _si.scales(E0=E0, Einf=Einf, tau=tau, nu=nu, wavelength=wavelength,
                    amplitude=amplitude, speed=speed, mean_pressure=mean_pressure,
                    penetration=penetration)
    groups = _si.groups(sc, validate, ACCEPTED, with_hk=("load",))
    validate(**{k: v for k, v in bem_options.items()})
    sol = _solver.solve(**groups, **bem_options)
    material = Prony.standard_linear_solid(sc.ratio)
    pfc = 0.5 * sc.hk / abs(complex(material.jstar([1.0], sc.speed)[0]))
    return _si.result(sol, sc, full_contact_load=pfc, threshold_speed=None)
