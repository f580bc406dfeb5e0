"""The Fourier reference's material: a Prony series in creep or relaxation form, validated, and
its complex compliance J*(n) and modulus E*(n) at the mode frequencies n w (the transform
convention and the sign of i are in the package docstring)."""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq

from viscosine.checks import bad, real, series


@dataclass(frozen=True)
class Material:
    """A Prony series in one of its two forms, as plain numbers (made by `material`).

    Attributes
    ----------
    form : str
        ``"creep"`` (base J0, amplitudes J_i, times τ_i) or ``"relaxation"`` (base E_r,
        amplitudes E_i, times θ_i).
    base : float
    amps, times : tuple of float
    """

    form: str            # "creep" or "relaxation"
    base: float          # J0 or E_r
    amps: tuple          # J_i or E_i
    times: tuple         # τ_i or θ_i

    def jstar(self, n, w):
        """J*(n) at speed w (array n)."""
        n = np.asarray(n, dtype=float)
        if self.form == "creep":
            out = np.full(n.shape, self.base - math.fsum(self.amps), dtype=complex)
            for a, t in zip(self.amps, self.times):
                out += a / (1.0 - 1j * (n * (w * t)))
            return out
        return 1.0 / self.estar(n, w)

    def estar(self, n, w):
        """E*(n) at speed w (array n)."""
        n = np.asarray(n, dtype=float)
        if self.form == "relaxation":
            out = np.full(n.shape, self.base, dtype=complex)
            for a, t in zip(self.amps, self.times):
                x = n * (w * t)
                out += a * (-1j * x) / (1.0 - 1j * x)
            return out
        return 1.0 / self.jstar(n, w)

    def as_dict(self):
        return {"form": self.form, "base": self.base, "amplitudes": list(self.amps),
                "times": list(self.times)}

    def creep_terms(self):
        """(J(0+), ((J_i, τ_i), ...)): the creep form (for a relaxation series, J(s) = 1/E(s)
        by partial fractions at the zeros of E(s), s the Laplace variable)."""
        if self.form == "creep":
            return self.base - math.fsum(self.amps), _merged(self.amps, self.times)
        terms = _merged(self.amps, self.times)
        e_inf = self.base + math.fsum(a for a, _ in terms)
        e_of = lambda s: e_inf - math.fsum(a / (1.0 + s * t) for a, t in terms)
        de = lambda s: math.fsum(a * t / (1.0 + s * t) ** 2 for a, t in terms)
        # E(s) increases between its poles −1/θ_i from −∞ to +∞, and from −∞ to E_r > 0 on
        # (−1/θ_max, 0): one zero s_j = −1/τ_j in each of those intervals
        poles = sorted(-1.0 / t for _, t in terms)
        out = []
        for lo, hi in zip(poles, poles[1:] + [0.0]):
            s = _zero_between(e_of, lo, hi, rising=True)
            out.append((-1.0 / s / de(s), -1.0 / s))   # J_j = τ_j / E'(s_j)
        return 1.0 / e_inf, tuple(out)

    def relaxation_times(self):
        """θ_k of the relaxation form (given, or −1/s at the zeros of J(s))."""
        if self.form == "relaxation":
            return tuple(sorted(t for _, t in _merged(self.amps, self.times)))
        jplus, terms = self.creep_terms()
        j_of = lambda s: jplus + math.fsum(a / (1.0 + s * t) for a, t in terms)
        # J(s) decreases between its poles −1/τ_i from +∞ to −∞, and from J(0+) > 0 to −∞ left of
        # the leftmost one: one zero in each of those intervals
        poles = sorted(-1.0 / t for _, t in terms)
        out = []
        for lo, hi in zip([None] + poles[:-1], poles):
            out.append(-1.0 / _zero_between(j_of, lo, hi, rising=False))
        return tuple(sorted(out))


def _merged(amps, times):
    """((a, t), ...) with equal times summed and zero amplitudes dropped (sorted by t)."""
    acc = {}
    for a, t in zip(amps, times):
        if a > 0.0:
            acc[t] = acc.get(t, 0.0) + a
    return tuple((a, t) for t, a in sorted(acc.items()))


def _zero_between(f, lo, hi, rising):
    """The zero of f, monotone between its poles lo < hi (lo None: −∞), by Brent's method."""
    sign = 1.0 if rising else -1.0
    if lo is None:          # step out to the left until f has the sign it has at −∞
        lo = 2.0 * hi
        while sign * f(lo) >= 0.0:
            lo *= 2.0
        a = lo
    else:
        d = 0.5 * (hi - lo)
        while sign * f(lo + d) >= 0.0 and lo + d != lo:
            d *= 0.5
        a = lo + d
    d = 0.5 * (hi - a)
    while sign * f(hi - d) <= 0.0 and hi - d != hi:
        d *= 0.5
    return brentq(f, a, hi - d, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500)


def material(*, ratio=None, creep=None, relaxation=None):
    """The material of `fourier_solve`, validated (exactly one form; none: ratio 3).

    Parameters
    ----------
    ratio : float, optional
        E∞/E0 ≥ 1 of the standard linear solid (creep form J0 = 1, J_1 = 1 − 1/ratio, τ_1 = 1,
        units E0 and τ).
    creep : (J0, J_i, tau_i), optional
        Creep form J(t) = J0 − Σ J_i e^{−t/τ_i}: J0 and J_i in (1 − ν²)/E_ref, J_i ≥ 0,
        τ_i > 0 in τ_ref, J(0+) = J0 − Σ J_i > 0.
    relaxation : (E_r, E_i, theta_i), optional
        Relaxation form E(t) = E_r + Σ E_i e^{−t/θ_i}: E_r > 0 and E_i ≥ 0 in
        E_ref/(1 − ν²), θ_i > 0 in τ_ref.

    Returns
    -------
    Material
    """
    given = {k: v for k, v in (("ratio", ratio), ("creep", creep), ("relaxation", relaxation))
             if v is not None}
    if len(given) > 1:
        name = list(given)[1]
        raise bad(name, given[name], f"one material only (got {' and '.join(given)}): "
                  "ratio, creep or relaxation")
    if ratio is None and creep is None and relaxation is None:
        ratio = 3.0
    if ratio is not None:
        r = real("ratio", ratio, "a finite E∞/E0 ≥ 1 (1 is elastic)", lambda v: v >= 1.0)
        return Material("creep", 1.0, ((r - 1.0) / r,), (1.0,))
    form, value = ("creep", creep) if creep is not None else ("relaxation", relaxation)
    what = ("a triple (J0, J_i, tau_i) of J(t) = J0 − Σ J_i exp(−t/τ_i)" if form == "creep" else
            "a triple (E_r, E_i, theta_i) of E(t) = E_r + Σ E_i exp(−t/θ_i)")
    try:
        base, amps, times = value
    except (TypeError, ValueError):
        raise bad(form, value, what) from None
    try:  # a bad part is refused as the whole triple, named by its form
        base = real(form, base, "", lambda v: v > 0.0)
    except ValueError:
        raise bad(form, value, what + " with a finite base value > 0") from None
    try:
        amps = series(form, amps, "", lambda v: v >= 0.0)
        times = series(form, times, "", lambda v: v > 0.0)
    except ValueError:
        raise bad(form, value, what + " with finite amplitudes ≥ 0 and times > 0") from None
    if len(amps) != len(times):
        raise bad(form, value, f"{what} with one time per amplitude (got {len(amps)} "
                  f"amplitudes and {len(times)} times)")
    if form == "creep" and not base - math.fsum(amps) > 0.0:
        raise bad(form, value, f"{what} with J(0+) = J0 − Σ J_i > 0 (got "
                  f"{base - math.fsum(amps)!r})")
    return Material(form, base, amps, times)


def complex_compliance(modes, speed, **material_kw):
    """J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i) (or 1/E*(n) for a relaxation series).

    Parameters
    ----------
    modes : array_like
        Mode numbers n (X-frequencies).
    speed : float
        w = V τ_ref k ≥ 0.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    ndarray of complex, in (1 − ν²)/E_ref.
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    return material(**material_kw).jstar(modes, w)


def complex_modulus(modes, speed, **material_kw):
    """E*(n) = E_r + Σ E_i (−i n w θ_i)/(1 − i n w θ_i) (or 1/J*(n) for a creep series).

    Same parameters as `complex_compliance`; returns E_ref/(1 − ν²) units.
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    return material(**material_kw).estar(modes, w)
