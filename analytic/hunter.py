"""Hunter's (1961) rigid cylinder sliding (rolling, frictionless) on a standard linear solid.

The second oracle: an isolated contact of half-width a under a cylinder of radius R, on the same
material (J(t) = 1/E0 − (1/E1) e^{−t/τ}, ρ = E∞/E0), at speed V.  With the relaxation length
ℓ = Vτ, z = a/ℓ and E* = E0/(1 − ν²), Hunter's transformation (q = v − ℓ v',
p = σ − (ℓ/ρ) σ') turns it into an elastic half-space problem on |x| < a whose solution is

    p(x) = (E*/2R) [sqrt(a² − x²) − (e − ℓ) x / sqrt(a² − x²)] + (W − W_H)/(π sqrt(a² − x²)),

with x measured from the centre of the contact, e the offset of that centre from the cylinder's
lowest point (toward the leading edge) and W_H = π E* a²/(4R) the Hertz load of width a.  The
two closure conditions, σ(−a) = 0 (∫ p e^{−ρx/ℓ} dx = 0) and the continuity of v at the
leading edge (∫_a^∞ [q' − q'_contact] e^{−(x−a)/ℓ} dx = 0), give with b = ρz

    e/a = (1 − 1/ρ)(1/z) · I1(b) K0(z) / [I1(b) K0(z) + I0(b) K1(z)],
    W/W_H = Λ = 1 + 2 (e/a) K1(z)/K0(z),
    ê/a   = e/a − 1/(ρz) − (e/a − 1/z)/Λ        (pressure centroid from the lowest point),
    μ     = ê/R                                  (rolling-resistance coefficient).

z → ∞ is Hertz with E0, z → 0 Hertz with E∞ (Λ → ρ).  The periodic problem of the paper tends
to this solution at vanishing load when a/(Vτ) is held fixed (so that the relaxation length is
also small compared with λ), with R = 1/(h k²): ka → 0, V/V0 = ka/z.

The same closure, written for the periodic contact, is derived in `analytic/DERIVATION.md`; here
the half-space functions (√(x² − a²), 1/√(x² − a²), x/√(x² − a²) outside, and the Laplace
transforms that make them Bessel functions) are used directly.

References: S. C. Hunter, The rolling contact of a rigid cylinder with a viscoelastic half space,
J. Appl. Mech. 28, 611–617 (1961); the periodic problem is that of Menga, Putignano, Carbone &
Demelio, Proc. R. Soc. A 470, 20140392, 2014.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import integrate, optimize, special


@dataclass(frozen=True)
class Hunter:
    """Hunter's solution at z = a/(Vτ) and ρ = E∞/E0 (lengths over a)."""

    z: float
    ratio: float
    e_over_a: float
    e_hat_over_a: float
    load_factor: float  # Λ = W/W_H(a)


def solve(z, ratio):
    """Hunter's closed form at z = a/(Vτ) > 0 for ratio E∞/E0 > 1."""
    if not (math.isfinite(z) and z > 0.0):
        raise ValueError(f"z = {z!r}: must be finite and > 0 (a/(Vτ))")
    if not (math.isfinite(ratio) and ratio > 1.0):
        raise ValueError(f"ratio = {ratio!r}: must be finite and > 1")
    b = ratio * z
    # exponentially scaled Bessel functions: the e^{b} and e^{−z} factors cancel in the ratios
    i0, i1 = special.i0e(b), special.i1e(b)
    k0, k1 = special.k0e(z), special.k1e(z)
    e_a = ((ratio - 1.0) / ratio) / z * i1 * k0 / (i1 * k0 + i0 * k1)
    lam = 1.0 + 2.0 * e_a * k1 / k0
    eh_a = e_a - 1.0 / (ratio * z) - (e_a - 1.0 / z) / lam
    return Hunter(z, ratio, e_a, eh_a, lam)


def pressure(x_over_a, z, ratio):
    """σ(x)/(E* a/R) at points x/a of the contact (x from the contact centre).

    Σ(x) = (1/c) ∫_x^a p(ξ) e^{−(ξ−x)/c} dξ with c = ℓ/ρ (inverse of Hunter's transformation);
    integrated with QUADPACK's algebraic-weight rule for the 1/√(a − ξ) edge.
    """
    h = solve(z, ratio)
    c = 1.0 / (ratio * z)  # c/a
    coef_odd = h.e_over_a - 1.0 / z
    coef_k = (h.load_factor - 1.0) / 4.0  # (W − W_H)/(π E* a²/R) = Λ/4 − 1/4

    def p_times_root(xi):  # p(ξ)·√(1 − ξ²), in units of E* a/R, without the edge singularity
        return 0.5 * (1.0 - xi * xi) - 0.5 * coef_odd * xi + coef_k

    out = []
    for x in np.atleast_1d(np.asarray(x_over_a, dtype=float)):
        if x >= 1.0:
            out.append(0.0)
            continue
        # QUADPACK weight (ξ − x)^α (1 − ξ)^{-1/2}: α = −1/2 absorbs the other edge at x = −1
        if x <= -1.0:
            x, alpha = -1.0, -0.5
            f = lambda xi: p_times_root(xi) * math.exp(-(xi + 1.0) / c)
        else:
            alpha = 0.0
            f = lambda xi, x=x: p_times_root(xi) / math.sqrt(1.0 + xi) * math.exp(-(xi - x) / c)
        val = integrate.quad(f, x, 1.0, weight="alg", wvar=(alpha, -0.5),
                             epsabs=1e-15, epsrel=1e-11, limit=200)[0]
        out.append(val / c)
    return np.array(out)


def halfwidth(load, speed, ratio):
    """a/R for given W/(E* R) and ℓ/R = Vτ/R: solves (a/R)² Λ(a/ℓ) = 4W/(π E* R)."""
    a0sq = 4.0 * load / math.pi

    def f(log_a):
        a = math.exp(log_a)
        return math.log(a * a * solve(a / speed, ratio).load_factor / a0sq)

    lo = 0.5 * math.log(a0sq / ratio) - 1.0
    hi = 0.5 * math.log(a0sq) + 1.0
    return math.exp(optimize.brentq(f, lo, hi, xtol=1e-15, rtol=4 * np.finfo(float).eps))
