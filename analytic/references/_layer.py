"""The surface compliance of a layer on a rigid foundation, one Fourier mode at a time, solved
numerically from Navier's equations (the references' own; nothing from `bem`).

A layer 0 ≤ z ≤ d (z into the body; plane strain; shear modulus μ, Poisson ratio ν) carries on
its top face the pressure p̂ e^{ikx} and no shear; its bottom face is

- ``"bonded"``: u_x = u_z = 0 at z = d (the confined layer of Menga, Afferrante & Carbone, J.
  Mech. Phys. Solids 95 (2016) 517–529);
- ``"frictionless"``: u_z = 0 and σ_xz = 0 at z = d (it slides on the foundation).

Its top displacement is the half-space's (eq. 2.2 of Menga, Putignano, Carbone & Demelio, Proc.
R. Soc. A 470, 20140392, 2014, one mode) times the layer factor S(t, ν), t = |k| d:
v̂ = S · 2(1 − ν²)/(E|k|) · p̂.  In steady sliding only E depends on the frequency, so mode n of
the reference's operator becomes (2/|n|) S(|n| k d, ν) J*(n).

One mode (k = 1, μ = 1, p̂ = 1; ζ = |k| z, 0 ≤ ζ ≤ t).  With u_x = i U e^{ikx}, u_z = W e^{ikx},
σ_xz = i X e^{ikx}, σ_zz = Z e^{ikx}, Hooke's law (plane strain) and equilibrium are the
first-order system y' = M y, y = (U, W, X, Z):

    U' = X − W,   W' = a U + b Z,   X' = c U − a Z,   Z' = X,
    a = ν/(1 − ν),  b = (1 − 2ν)/(2(1 − ν)),  c = 2/(1 − ν)        (all finite on (−1, ½]).

The top face gives X(0) = 0, Z(0) = −1; the bottom gives U(t) = W(t) = 0 (bonded) or
W(t) = X(t) = 0 (frictionless).  The half-space (t → ∞) has W(0) = 1 − ν, so S = W(0)/(1 − ν).
M has the double eigenvalues ∓1 with the Jordan chains (derived by hand, checked in the tests)

    (M + I) v = 0, (M + I) v' = v:   v = (−1, 1, 2, −2),  v' = (2(1 − ν), 1 − 2ν, −2, 0),
    (M − I) w = 0, (M − I) w' = w:   w = (1, 1, 2, 2),    w' = (2(1 − ν), −(1 − 2ν), 2, 0).

S is found from one 4 × 4 linear system per mode, two ways (`_thick`, `_thin`):

- t ≥ `T_SWITCH`:

      y = A e^{−ζ} v + B e^{−ζ}(v' + ζ v) + C e^{−(t−ζ)} w + D e^{−(t−ζ)}(w' − (t − ζ) w),

  functions that decay away from the face they belong to, so every entry is at most max(1, t)
  e^{−t} off its own face and nothing overflows; the four boundary conditions fix A … D.  As
  t → 0 the four functions merge (at t = 1e-3, ν = ½ this loses 2e-7 of S);
- t < `T_SWITCH`: y(t) = Φ(t) y(0), Φ = exp(M t) by its Taylor series (the coefficients
  M^j/j! in exact rational arithmetic from ν, rounded once), and the unknowns are the four
  components of y(0): the thin layer's small S is then a solved unknown, not a difference.

Each keeps S to a few ulp on its side of `T_SWITCH` (measured against the closed forms in 50
digits; see ``tests/validation/test_fourier_layer.py``).  From `T_HALF_SPACE` on S is 1 exactly: the first
reflection between the faces gives 1 − S ≈ P(t) e^{−2t} with P quadratic (each face's second
function carries one factor t), measured from the solve as (4/κ) t² (bonded, κ = 3 − 4ν ≥ 1)
and 4t (frictionless) to leading order, so 1 − S < 2⁻⁵⁴ (S rounds to 1) from t ≈ 22.6 at
worst; the bound is 25 (1 − S < 6e-19 there).

The uniform mode n = 0 (`uniform_compliance`) is the layer's compression under the mean
pressure, finite unlike the half-space's.

This module never imports `bem` (the two roads are independent).
"""
from __future__ import annotations

import math
from collections.abc import Mapping
from fractions import Fraction
from functools import lru_cache

import numpy as np

from viscosine.checks import bad, real, reals

#: the lower boundaries a layer may have
FOUNDATIONS = ("bonded", "frictionless")
#: what holds the ends of a layer on a frictionless foundation (see `uniform_compliance`)
LATERAL = ("free", "held")
#: below this t the state is carried from the top face by exp(M t) (`_thin`), from it on the
#: decaying basis is used (`_thick`): each is within 5 ulp of S on its side (measured; the
#: decaying basis loses 4e-13 of S by t = 0.1 at ν = ½, the series needs more terms above 1)
T_SWITCH = 1.0
#: Taylor terms of exp(M t) for t < T_SWITCH: the first omitted, M^24/24!, has entries below
#: 1e-22 (measured at ν = ½, the largest, 0.3 and −1 + 1e-6), negligible at t <= 1 where Φ
#: is of order one and, for small t, below the leading power of every entry by t^21 or more
_TAYLOR_TERMS = 24
#: from here on S = 1 exactly (S rounds to 1 from t ≈ 22.6, see the module docstring)
T_HALF_SPACE = 25.0
#: the keys of the layer mapping of `fourier_solve` and `full_contact`
KEYS = ("thickness", "foundation", "nu")


def _check_nu(nu, name="nu") -> float:
    return real(name, nu, "a Poisson ratio in (-1, 0.5]", lambda v: -1.0 < v <= 0.5, kind=True)


def _check_foundation(foundation, name="foundation") -> str:
    if not isinstance(foundation, str) or foundation not in FOUNDATIONS:
        raise bad(name, foundation, "'bonded' (u_x = u_z = 0 at the bottom face) or "
                  "'frictionless' (u_z = 0 and no shear at the bottom face)")
    return foundation


def _check_t(t) -> np.ndarray:
    allowed = "a dimensionless thickness t = |k| d >= 0 (inf for the half-space)"
    arr = reals("t", t, allowed)
    wrong = np.isnan(arr) | (arr < 0.0)
    if wrong.any():
        where = int(np.flatnonzero(wrong.ravel())[0])
        tail = f" (element {where} of the array)" if arr.ndim else ""
        raise bad("t", float(arr.ravel()[where]), allowed + "; NaN and negative values are "
                  "refused" + tail)
    return arr


# --------------------------------------------------------------------------------------------
# One mode of Navier's equations
# --------------------------------------------------------------------------------------------
def _rows(foundation):
    """The components of y that vanish at the bottom face."""
    return (0, 1) if foundation == "bonded" else (1, 2)


@lru_cache(maxsize=64)
def _taylor(nu: float) -> np.ndarray:
    """M^j/j!, j = 0 … _TAYLOR_TERMS − 1, exact in rationals from the float ν, then rounded:
    a coefficient that vanishes for this ν is 0, not a rounding (the thin layer's S is the
    leading surviving power of t, e.g. t³ for the incompressible bonded layer)."""
    v = Fraction(nu)
    a, b, c = v / (1 - v), (1 - 2 * v) / (2 * (1 - v)), 2 / (1 - v)
    zero, one = Fraction(0), Fraction(1)
    m = [[zero, -one, one, zero], [a, zero, zero, b], [c, zero, zero, -a],
         [zero, zero, one, zero]]
    p = [[one if i == j else zero for j in range(4)] for i in range(4)]
    out = [p]
    for j in range(1, _TAYLOR_TERMS):
        p = [[sum(p[i][k] * m[k][l] for k in range(4)) / j for l in range(4)] for i in range(4)]
        out.append(p)
    return np.array([[[float(x) for x in row] for row in q] for q in out])


def _thin(t: np.ndarray, nu: float, foundation: str) -> np.ndarray:
    """S for 0 < t < T_SWITCH: the unknowns are y(0); rows X(0) = 0, Z(0) = −1 and the two
    bottom conditions on y(t) = exp(M t) y(0)."""
    coef = _taylor(float(nu))
    phi = np.broadcast_to(coef[-1], (t.size, 4, 4)).copy()
    for j in range(_TAYLOR_TERMS - 2, -1, -1):  # Horner in t
        phi = phi * t[:, None, None] + coef[j]
    system = np.zeros((t.size, 4, 4))
    system[:, 0, 2] = 1.0          # X(0) = 0
    system[:, 1, 3] = 1.0          # Z(0) = −1
    r1, r2 = _rows(foundation)
    system[:, 2] = phi[:, r1]
    system[:, 3] = phi[:, r2]
    rhs = np.zeros((t.size, 4, 1))
    rhs[:, 1, 0] = -1.0
    y0 = np.linalg.solve(system, rhs)[:, :, 0]
    return y0[:, 1] / (1.0 - nu)


def _basis(zeta: np.ndarray, t: np.ndarray, nu: float) -> np.ndarray:
    """y of the four decaying functions at depth ζ (shape (m, 4 components, 4 functions))."""
    v = np.array([-1.0, 1.0, 2.0, -2.0])
    v1 = np.array([2.0 * (1.0 - nu), 1.0 - 2.0 * nu, -2.0, 0.0])
    w = np.array([1.0, 1.0, 2.0, 2.0])
    w1 = np.array([2.0 * (1.0 - nu), -(1.0 - 2.0 * nu), 2.0, 0.0])
    down = np.exp(-zeta)[:, None]          # from the top face
    up = np.exp(zeta - t)[:, None]         # from the bottom face
    z, r = zeta[:, None], (t - zeta)[:, None]
    return np.stack([down * v, down * (v1 + z * v), up * w, up * (w1 - r * w)], axis=-1)


def _thick(t: np.ndarray, nu: float, foundation: str) -> np.ndarray:
    """S for t >= T_SWITCH: the amplitudes of the four decaying functions are the unknowns."""
    top = _basis(np.zeros_like(t), t, nu)
    bottom = _basis(t, t, nu)
    r1, r2 = _rows(foundation)
    system = np.stack([top[:, 2], top[:, 3], bottom[:, r1], bottom[:, r2]], axis=1)
    rhs = np.zeros((t.size, 4, 1))
    rhs[:, 1, 0] = -1.0
    amp = np.linalg.solve(system, rhs)[:, :, 0]
    return np.einsum("mk,mk->m", top[:, 1], amp) / (1.0 - nu)


def layer_factor(t, nu, foundation):
    """The layer factor S(t, ν): a mode's surface compliance over the half-space's.

    Solved from Navier's equations as one 4 × 4 linear system per mode (module docstring),
    vectorised over t.

    Parameters
    ----------
    t : float or array_like
        |k| d, wavenumber times thickness (dimensionless), ``>= 0``; ``inf`` is the half-space.
    nu : float
        Poisson ratio, ``-1 < nu <= 0.5``.
    foundation : {"bonded", "frictionless"}
        The bottom face: bonded to the rigid foundation, or on it without friction.

    Returns
    -------
    float or ndarray
        S, of the shape of ``t`` (a float for a scalar): 0 at t = 0, in (0, 1] for finite t > 0,
        1 exactly from `T_HALF_SPACE` on.

    Raises
    ------
    ValueError
        Naming the parameter: t negative or NaN, ν outside (−1, 0.5], an unknown foundation.

    References
    ----------
    Eq. (2.2) of Menga, Putignano, Carbone & Demelio (2014), mode by mode; the layer of Menga,
    Afferrante & Carbone (2016).
    """
    arr = _check_t(t)
    nu = _check_nu(nu)
    foundation = _check_foundation(foundation)
    flat = arr.ravel()
    out = np.ones_like(flat)
    out[flat == 0.0] = 0.0                       # no layer: no displacement
    thin = (flat > 0.0) & (flat < T_SWITCH)
    thick = (flat >= T_SWITCH) & (flat < T_HALF_SPACE)
    if thin.any():
        out[thin] = _thin(flat[thin], nu, foundation)
    if thick.any():
        out[thick] = _thick(flat[thick], nu, foundation)
    out = out.reshape(arr.shape)
    return float(out) if out.ndim == 0 else out


# --------------------------------------------------------------------------------------------
# The uniform mode
# --------------------------------------------------------------------------------------------
def uniform_compliance(nu, foundation, lateral="free"):
    """C of the uniform mode: v̂_0 = C (1 − ν²) d/E · p̂_0, i.e. k v̂_0 = C (k d) J σ̂_0 in the
    units of `analytic.references.fourier` (J in (1 − ν²)/E_ref).

    Under a uniform pressure the layer is in a homogeneous state (σ_zz = −p̂_0, σ_xz = 0,
    x-independent strains: a z-dependent ε_xx would need shear).  Plane-strain Hooke's law,
    2μ ε_zz = (1 − ν)σ_zz − νσ_xx and 2μ ε_xx = (1 − ν)σ_xx − νσ_zz, needs one lateral
    condition:

    - ε_xx = 0 (uniaxial strain): σ_xx = ν/(1 − ν) σ_zz and v̂_0 = d (1 + ν)(1 − 2ν)/((1 − ν)E)
      p̂_0, C = (1 − 2ν)/(1 − ν)², zero for ν = ½.  The bonded layer: u_x = 0 on its bottom
      face, and a homogeneous ε_xx is then 0 everywhere.  ``lateral`` does not matter;
    - σ_xx = 0 (free to spread): v̂_0 = d (1 − ν²)/E p̂_0, C = 1.  The frictionless foundation
      with ``lateral="free"``: with no shear on either face, equilibrium keeps the resultant
      N = ∫σ_xx dz the same at every x (and the modes n ≠ 0 carry none, ik N̂_n = 0), so a layer
      whose ends are free has N = 0.  This is the limit of the modes, 2S_F/t → 1 as t → 0;
    - the frictionless foundation with ``lateral="held"``: ends held so that the mean lateral
      strain is zero (u_x strictly periodic): the uniaxial strain, C = (1 − 2ν)/(1 − ν)².

    Parameters
    ----------
    nu : float
        Poisson ratio in (−1, 0.5].
    foundation : {"bonded", "frictionless"}
    lateral : {"free", "held"}
        What holds the ends of a layer on a frictionless foundation (default ``"free"``).

    Returns
    -------
    float
        C, in (1 − ν²)/E per unit thickness.
    """
    nu = _check_nu(nu)
    foundation = _check_foundation(foundation)
    if not isinstance(lateral, str) or lateral not in LATERAL:
        raise bad("lateral", lateral, "'free' (the layer's ends free: no resultant lateral "
                  "stress) or 'held' (no mean lateral strain)")
    if foundation == "frictionless" and lateral == "free":
        return 1.0
    # ε_zz/σ_zz with ε_xx = 0, in (1 − ν²)/E = (1 − ν)/(2μ): [(1 − ν) − ν²/(1 − ν)]/(1 − ν)
    return ((1.0 - nu) - nu * nu / (1.0 - nu)) / (1.0 - nu)


# --------------------------------------------------------------------------------------------
# The layer argument of the reference
# --------------------------------------------------------------------------------------------
def check_layer(layer):
    """The ``layer`` argument of `fourier_solve` / `full_contact` as a plain dict, or None.

    ``layer`` is None (the half-space) or a mapping with exactly the keys ``"thickness"`` (k d,
    finite > 0), ``"foundation"`` (``"bonded"`` or ``"frictionless"``) and ``"nu"`` (in
    (−1, 0.5]).  The first bad entry is refused as ``layer['key']=value is not allowed: ...``;
    so is a layer so thin that S(k d) of mode 1 underflows (e.g. k d below 1e-102 bonded at
    ν = ½, where S = (2/3)(k d)³), whose full-contact load would be infinite.
    """
    if layer is None:
        return None
    if not isinstance(layer, Mapping):
        raise bad("layer", layer, "None (the half-space) or a mapping {'thickness': k d > 0, "
                  "'foundation': 'bonded' or 'frictionless', 'nu': a Poisson ratio in "
                  "(-1, 0.5]}")
    keys = set(layer)
    if keys != set(KEYS):
        missing = [k for k in KEYS if k not in keys]
        extra = sorted(map(repr, keys - set(KEYS)))
        why = "; ".join(x for x in (f"missing {', '.join(missing)}" if missing else "",
                                    f"unknown {', '.join(extra)}" if extra else "") if x)
        raise bad("layer", dict(layer), f"a mapping with exactly the keys thickness (k d), "
                  f"foundation and nu ({why})")
    allowed = "a finite thickness k d > 0 (k = 2π/λ; layer=None for the half-space)"
    kd = real("layer['thickness']", layer["thickness"], allowed, lambda v: v > 0.0, kind=True)
    foundation = _check_foundation(layer["foundation"], "layer['foundation']")
    nu = _check_nu(layer["nu"], "layer['nu']")
    s1 = layer_factor(kd, nu, foundation)
    if s1 < np.finfo(float).tiny:  # mode 1 would have no compliance: p̃FC = ∞
        raise bad("layer['thickness']", kd, f"{allowed}, whose layer factor S(k d) of mode 1 is "
                  f"a normal number (here S = {s1:.3g}: the layer is rigid in double precision)")
    return {"thickness": kd, "foundation": foundation, "nu": nu}


def describe(layer: dict) -> dict:
    """The layer as the result reports it: its entries, d/λ, C of the uniform mode
    (``lateral="free"``) and the factor S(k d) of mode 1."""
    kd = layer["thickness"]
    return {"thickness": kd, "thickness_over_wavelength": kd / (2.0 * math.pi),
            "foundation": layer["foundation"], "nu": layer["nu"],
            "uniform_compliance": uniform_compliance(layer["nu"], layer["foundation"]),
            "factor_mode_1": layer_factor(kd, layer["nu"], layer["foundation"])}
