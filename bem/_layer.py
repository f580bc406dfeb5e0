"""Surface compliance of a layer of thickness d on a rigid foundation, one Fourier mode at a time.

A layer of thickness d (plane strain, Poisson ratio nu) carries a normal pressure
``p(x) = p^ exp(ikx)`` and no shear on its top face; its bottom face is either bonded to a
rigid foundation (``u_x = u_z = 0``) or lies on it without friction (``u_z = 0``, no shear).
The normal displacement of the top face is the half-space's times the layer factor S::

    v^ = S(t, nu) 2 (1 - nu^2) / (E |k|) p^,   t = |k| d,   S -> 1 as t -> inf

(pressure positive in compression, displacement positive into the body).  In steady
sliding only E depends on the frequency, so mode n of the BEM operator becomes
``(2/|n|) S(|n| k d) J*(n)`` (in the units of :mod:`bem`).  Its n = 0 value is finite for a
layer: ``k v^_0 = (k d) uniform_compliance(nu, foundation) J0 sigma^_0`` with the relaxed
compliance ``J0 = J(t -> inf)``, the mean pressure being static in the frame of the indenter.

Units: t = |k| d and S are dimensionless; `uniform_compliance` is in ``(1 - nu^2)/E`` per
unit thickness.

The closed forms (derived in ``docs/layers.md``), with ``q = exp(-2t)`` and
``kappa = 3 - 4 nu``::

    bonded        S = [kappa (1 - q^2) - 4 t q] / [kappa (1 + q^2) + (1 + kappa^2 + 4 t^2) q]
    frictionless  S = (1 - q)^2 / [(1 - q^2) + 4 t q]          (independent of nu)

Evaluation: ``1 - q`` is ``-expm1(-2t)`` and every sum has terms of one sign but the bonded
numerator, which cancels for small t (to O(t^3) at nu = 1/2).  Below ``_T_SERIES`` it is
written as ``2 (1 - 2 nu)(1 - q^2) + 2 q (sinh 2t - 2t)``, with ``sinh u - u`` by its Taylor
series (`_sinh_minus`); from there on it cancels by at most a factor 3.5.  Beyond ``_T_ONE``
S is 1 (exactly, as the formulas round there too); ``t = inf`` is the half-space.  Measured
against a 60-digit reference (``tests/test_layer_factor.py``) the relative error is at most
3 ulp for t from 1e-8 to 50 and nu in (-1, 1/2].

References
----------
The half-space compliance of eq. (2.2) of the paper, mode by mode; the layer geometry of
Menga, Afferrante & Carbone, J. Mech. Phys. Solids 95 (2016) 517-529 (its confined layer is
the bonded case here).
"""
from __future__ import annotations

import numpy as np

from viscosine._checks import bad, real, reals

#: the lower boundaries a layer may have
FOUNDATIONS = ("bonded", "frictionless")
#: the meanings of the uniform mode (see `uniform_compliance`)
LATERAL = ("free", "held")
#: below this t the bonded numerator is summed from its series (see the module docstring)
_T_SERIES = 1.0
#: Taylor terms of sinh u - u kept below u = 2 _T_SERIES: the first omitted one,
#: u^27/27!, is below 1e-20 of the sum at u = 2
_SINH_TERMS = 12
#: from here on S is 1 exactly: the formulas round to 1 from t = 22.55 (``docs/layers.md``)
_T_ONE = 25.0


def _sinh_minus(u: np.ndarray) -> np.ndarray:
    """``sinh(u) - u`` without cancellation for ``0 <= u <= 2``: Taylor series, Horner in u^2."""
    u2 = u * u
    acc = np.ones_like(u)
    for j in range(_SINH_TERMS - 1, 0, -1):  # term j+1 over term j is u^2/((2j+2)(2j+3))
        acc = 1.0 + acc * u2 / ((2 * j + 2) * (2 * j + 3))
    return u * u2 / 6.0 * acc


def _bonded(t: np.ndarray, nu: float) -> np.ndarray:
    q = np.exp(-2.0 * t)
    one_minus_q2 = -np.expm1(-2.0 * t) * (1.0 + q)
    kappa = 3.0 - 4.0 * nu
    num = np.empty_like(t)
    small = t < _T_SERIES
    ts = t[small]
    num[small] = (2.0 * (1.0 - 2.0 * nu) * one_minus_q2[small]
                  + 2.0 * q[small] * _sinh_minus(2.0 * ts))
    big = ~small
    num[big] = kappa * one_minus_q2[big] - 4.0 * t[big] * q[big]  # cancels <= 3.5x (t = 1)
    den = kappa * (1.0 + q * q) + (1.0 + kappa * kappa + 4.0 * t * t) * q
    return num / den


def _frictionless(t: np.ndarray) -> np.ndarray:
    q = np.exp(-2.0 * t)
    a = -np.expm1(-2.0 * t)  # 1 - q
    den = a * (1.0 + q) + 4.0 * t * q
    out = np.zeros_like(t)  # S(0) = 0
    pos = t > 0.0
    out[pos] = a[pos] * (a[pos] / den[pos])  # a^2 would underflow first
    return out


def _check_nu(nu) -> float:
    return real("nu", nu, "a Poisson ratio in (-1, 0.5]", lambda v: -1.0 < v <= 0.5, kind=True)


def _check_foundation(foundation) -> str:
    if not isinstance(foundation, str) or foundation not in FOUNDATIONS:
        raise bad("foundation", foundation,
                  "'bonded' (u_x = u_z = 0 at the bottom) or 'frictionless' (u_z = 0 and no shear "
                  "at the bottom)")
    return foundation


def _check_t(t) -> np.ndarray:
    allowed = "a dimensionless thickness |k| d >= 0 (inf for the half-space)"
    arr = reals("t", t, allowed)
    wrong = np.isnan(arr) | (arr < 0.0)
    if wrong.any():
        where = np.flatnonzero(wrong.ravel())[0]
        value = arr.ravel()[where]
        tail = f" (element {where} of the array)" if arr.ndim else ""
        raise bad("t", float(value), allowed + "; NaN and negative values are refused" + tail)
    return arr


def layer_factor(t, nu, foundation):
    """Layer factor S: the surface compliance of one mode over the half-space's.

    Parameters
    ----------
    t : float or array_like
        ``|k| d``, wavenumber times layer thickness (dimensionless), ``>= 0``; ``inf`` is the
        half-space (S = 1).
    nu : float
        Poisson ratio, ``-1 < nu <= 0.5``.
    foundation : {"bonded", "frictionless"}
        The lower boundary: bonded to the rigid foundation, or lying on it without friction.

    Returns
    -------
    float or ndarray
        S, of the shape of ``t`` (a float for a scalar).  ``0 <= S < 1`` for finite t; S = 0
        at t = 0.

    Raises
    ------
    ValueError
        Naming the parameter: t negative or NaN, nu outside (-1, 0.5], an unknown foundation.

    References
    ----------
    ``docs/layers.md`` (derivation, limits); eq. (2.2) of the paper for the half-space.
    """
    arr = _check_t(t)
    nu = _check_nu(nu)
    foundation = _check_foundation(foundation)
    out = np.ones_like(arr)
    finite = arr < _T_ONE
    if finite.any():
        tf = arr[finite]
        out[finite] = _bonded(tf, nu) if foundation == "bonded" else _frictionless(tf)
    return float(out) if out.ndim == 0 else out


def uniform_compliance(nu, foundation, lateral="free"):
    """The n = 0 mode: the layer's compression under a uniform pressure.

    ``v^_0 = C d (1 - nu^2)/E p^_0``, i.e. ``k v^_0 = C (k d) J sigma^_0`` in the units of
    :mod:`bem`.  C is the value at t = 0 of ``2 S(t)/t`` when that limit is the physics:

    - bonded: ``C = (1 - 2 nu)/(1 - nu)^2``, uniaxial strain (the foundation holds the
      bottom; 0 for an incompressible layer); ``lateral`` does not matter.
    - frictionless, ``lateral="free"``: ``C = 1``, plane-strain compression free to spread
      (the mean lateral stress is zero: a long layer with free ends, the limit of the modes).
    - frictionless, ``lateral="held"``: ``C = (1 - 2 nu)/(1 - nu)^2``, as bonded (u_x strictly
      periodic, so no mean lateral strain: the ends are held).  The modes do not tend to this.

    Parameters
    ----------
    nu : float
        Poisson ratio, ``-1 < nu <= 0.5``.
    foundation : {"bonded", "frictionless"}
    lateral : {"free", "held"}
        What holds the layer's ends; only the frictionless foundation depends on it.

    Returns
    -------
    float
        C, in ``(1 - nu^2)/E`` per unit thickness.

    References
    ----------
    ``docs/layers.md``, "The uniform mode".
    """
    nu = _check_nu(nu)
    foundation = _check_foundation(foundation)
    if not isinstance(lateral, str) or lateral not in LATERAL:
        raise bad("lateral", lateral,
                  "'free' (the layer's ends free: no mean lateral stress) or 'held' (no mean "
                  "lateral strain)")
    if foundation == "frictionless" and lateral == "free":
        return 1.0
    return (1.0 - 2.0 * nu) / ((1.0 - nu) * (1.0 - nu))
