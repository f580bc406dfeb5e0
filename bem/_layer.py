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

`Layer` is the input of ``bem.solve(layer=...)``; `symbol_correction` turns the half-space's
discrete symbol into the layer's (its alias sum, with `continuum_symbol`), `mean_displacement`
gives the uniform mode (``docs/layers.md`` §7).

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
against a 60-digit reference (``tests/validation/test_layer_factor.py``) the relative error is at most
3 ulp for t from 1e-8 to 50 and nu in (-1, 1/2].

References
----------
The half-space compliance of eq. (2.2) of the paper, mode by mode; the layer geometry of
Menga, Afferrante & Carbone, J. Mech. Phys. Solids 95 (2016) 517-529 (its confined layer is
the bonded case here).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from viscosine.checks import bad, real, reals

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


# --------------------------------------------------------------------------
# The layer of a solve: its input, its operator, its uniform mode
# --------------------------------------------------------------------------
#: the thinnest layer a solve takes, kd: the operator sums the modes |m| < _T_ONE/kd (2.5e5
#: here) and the mesh must resolve d (`MIN_LAYER_PANELS` panels at N/4: N >= 1e6 here)
THICKNESS_MIN = 1e-4
#: round-off of the lowest mode of the half-space's symbol relative to it, per panel: its
#: real-space column sums N coefficients (measured 2.2e-18 N at N = 2^10 ... 2^20); five times
#: that.  A layer's lowest mode, S(kd) times the half-space's, is made as the half-space's plus a
#: correction of order one (`symbol_correction`), so it carries this round-off over S(kd)
SYMBOL_ROUNDOFF_PER_PANEL = 1e-17
#: the relative round-off a layer's lowest mode may carry: a hundredth of the default rtol
SYMBOL_ROUNDOFF_BUDGET = 1e-8
#: the adaptive mesh trusts its estimate only once d spans this many panels on the coarsest
#: grid of the estimate (N/4): d is a length of the solution (the pressure varies over d at
#: the contact edges of a thin layer), which the grids must see before their differences do
MIN_LAYER_PANELS = 4.0


def _same_thickness(kd, d_over_lambda) -> bool:
    """Whether k d and d/lambda, both given, are one thickness (as a Layer keeps them both:
    `dataclasses.replace` passes both back)."""
    try:
        return math.isclose(float(kd), 2.0 * math.pi * float(d_over_lambda), rel_tol=1e-15)
    except (TypeError, ValueError):
        return False


@dataclass(frozen=True)
class Layer:
    """A layer of thickness d on a rigid foundation, under the profile (`bem.solve(layer=...)`).

    Give one of ``thickness`` (k d, k = 2 pi/lambda) and ``thickness_over_wavelength``
    (d/lambda); both are kept, the other made from the given one (both may be given when they
    are the same thickness, as `dataclasses.replace` gives them).

    Parameters
    ----------
    thickness : float, optional
        k d, in ``[THICKNESS_MIN, inf)`` (finite; ``layer=None`` is the half-space).  From
        k d = 25 on the layer factor of every mode is 1 exactly: the half-space's answer.
    thickness_over_wavelength : float, optional
        d/lambda (k d / 2 pi).
    foundation : {"bonded", "frictionless"}
        The lower boundary: bonded (u_x = u_z = 0), or lying without friction (u_z = 0).
    nu : float
        Poisson ratio in (-1, 0.5], constant in time (only E depends on the frequency).

    Raises
    ------
    ValueError
        Naming the parameter: a thickness not finite or below THICKNESS_MIN (or both, or
        neither, given), an unknown foundation, nu outside (-1, 0.5].
    """

    thickness: float | None = None
    foundation: str | None = None
    nu: float | None = None
    thickness_over_wavelength: float | None = None

    def __post_init__(self):
        two_pi = 2.0 * math.pi
        allowed = (f"a finite thickness k d >= {THICKNESS_MIN:g} (k = 2 pi/lambda; "
                   "layer=None for the half-space)")
        both = self.thickness is not None and self.thickness_over_wavelength is not None
        if both and not _same_thickness(self.thickness, self.thickness_over_wavelength):
            both = False  # two different layers: refused below
        elif both:
            object.__setattr__(self, "thickness_over_wavelength", None)  # as dataclasses.replace
        if not both and (self.thickness is None) == (self.thickness_over_wavelength is None):
            raise bad("thickness", self.thickness, "exactly one of thickness (k d) and "
                      "thickness_over_wavelength (d/lambda) (got thickness="
                      f"{self.thickness!r}, thickness_over_wavelength="
                      f"{self.thickness_over_wavelength!r})")
        if self.thickness is not None:
            kd = real("thickness", self.thickness, allowed, lambda v: v >= THICKNESS_MIN,
                      kind=True)
        else:
            dl = real("thickness_over_wavelength", self.thickness_over_wavelength,
                      f"a finite d/lambda >= {THICKNESS_MIN / two_pi:g}",
                      lambda v: v * two_pi >= THICKNESS_MIN, kind=True)
            kd = two_pi * dl
        object.__setattr__(self, "foundation", _check_foundation(self.foundation))
        object.__setattr__(self, "nu", _check_nu(self.nu))
        object.__setattr__(self, "thickness", kd)
        object.__setattr__(self, "thickness_over_wavelength", kd / two_pi)

    @property
    def uniform(self) -> float:
        """C of `uniform_compliance` (``lateral="free"``: the limit of the modes)."""
        return uniform_compliance(self.nu, self.foundation)

    @property
    def finest_nodes(self) -> int:
        """The most panels per period a solve on this layer may use (`finest_nodes`)."""
        return finest_nodes(self)

    def factor(self, modes) -> np.ndarray:
        """S(|n| k d) of the modes n (an array; 1 exactly from |n| k d = 25 on)."""
        return layer_factor(np.abs(np.asarray(modes, dtype=float)) * self.thickness, self.nu,
                            self.foundation)

    def describe(self) -> dict:
        """The layer as plain numbers (for the result's diagnostics)."""
        return {"thickness": self.thickness,
                "thickness_over_wavelength": self.thickness_over_wavelength,
                "foundation": self.foundation, "nu": self.nu, "uniform_compliance": self.uniform}


def continuum_symbol(modes, j_plus, terms, speed, nodes, shifts) -> np.ndarray:
    """The continuum symbol of the modes m != 0 of the panel operator, with the panel factor:
    ``(2/|m|) sinc(pi m/N) [J(0+) + sum_i J_i exp(-2 pi i m delta_i)/(1 - i m w tau_i)]``.

    The discrete symbol (``rfft`` of the column of `_influence.influence_coefficients_nd`) is
    its alias sum over ``m = n + p N``; ``delta_i`` (wavelengths) is term i's collocation shift
    (`_influence.collocation_shifts`: its memory part is sampled at ``X - delta_i``).  A term
    with no memory (speed 0) acts at once: its factor is then 1.
    """
    m = np.asarray(modes, dtype=float)
    js = np.full(m.shape, j_plus, dtype=complex)
    for (j_i, tau_i), delta in zip(terms, shifts):
        if j_i == 0.0:
            continue
        phase = np.exp(-2j * math.pi * m * delta) if delta > 0.0 else 1.0
        js += j_i * phase / (1.0 - 1j * m * speed * tau_i)
    return (2.0 / np.abs(m)) * np.sinc(m / nodes) * js


def symbol_correction(layer: Layer, j_plus, terms, speed, nodes, shifts):
    """What the layer adds to the half-space's discrete symbol (``rfft`` modes 0 .. N/2):
    ``sum_p (S(|n + p N| k d) - 1) chat(n + p N)`` with `continuum_symbol` chat, over the modes
    ``|n + p N| k d < 25`` (beyond, S = 1 exactly).  None when no mode sees the layer (k d >= 25:
    the operator is the half-space's, bit for bit).

    Mode n of the continuum operator with a layer is the half-space's times S (``docs/layers.md``
    §1); the discrete symbol of panel collocation is the alias sum of the continuum one, so
    the half-space's (made in real space) plus this sum is the layer's.
    """
    top = int(math.ceil(_T_ONE / layer.thickness))  # |m| < top may have S < 1
    m = np.arange(-top, top + 1, dtype=np.int64)
    m = m[(m != 0) & (np.abs(m) * layer.thickness < _T_ONE)]
    if m.size == 0:
        return None
    bins = m % nodes
    keep = bins <= nodes // 2
    m, bins = m[keep], bins[keep]
    weight = layer.factor(m) - 1.0
    out = np.zeros(nodes // 2 + 1, dtype=complex)
    np.add.at(out, bins, weight * continuum_symbol(m, j_plus, terms, speed, nodes, shifts))
    return out


def finest_nodes(layer: Layer) -> int:
    """The most panels on which the layer's lowest mode keeps its relative round-off,
    ``SYMBOL_ROUNDOFF_PER_PANEL N / S(kd)``, within SYMBOL_ROUNDOFF_BUDGET: a thin layer (S(kd)
    small: (2/3)(kd)^3 for a bonded incompressible one) allows fewer, and one too thin for any
    grid is refused rather than answered from a lowest mode that is round-off."""
    s = float(layer.factor([1.0])[0])
    return int(SYMBOL_ROUNDOFF_BUDGET * s / SYMBOL_ROUNDOFF_PER_PANEL)


def mean_displacement(layer: Layer, j0: float, load: float) -> float:
    """k v^_0: the layer's uniform compression under the mean pressure (units of :mod:`bem`),
    ``C (k d) J0 sigma^_0`` with the relaxed compliance J0 (the mean pressure is static in the
    frame of the indenter) and C of `uniform_compliance` (``lateral="free"``)."""
    return layer.uniform * layer.thickness * j0 * load
