"""Full contact (Appendix B) and the transition to partial contact, in closed form.

Units: see `analytic/__init__.py`.  w = V/V0 = V τ k, ρ = E∞/E0.

In full contact the pressure is sinusoidal (eq. B6).  For the standard linear solid the complex
modulus at the sliding frequency ω = kV, in the convention where the pressure *leads* the
profile, is

    E(ω)/E0 = (1 + i w)/(1 + i w/ρ),    |E|/E0 = sqrt((1 + w²)/(1 + w²/ρ²)),
    δ = arg E = atan(w) − atan(w/ρ)        (loss angle),

so that, in the crest frame,

    σ(x)(1 − ν²)/E0 = p̃∞ + (hk/2)(|E|/E0) cos(kx − δ),
    τ̃f = τf (1 − ν²)/E0 = (hk)²/4 · (|E|/E0) sin δ   (eq. B8 per unit length, resisting > 0),
    kê = δ  (pressure maximum, and centroid over the wavelength centred on it).

The paper's (B7) writes arg|M⁻¹|, a typo for arg M⁻¹; its (B6) omits the mean pressure; its (B8)
is a force per wavelength, negative when it resists.  Full contact holds while σ ≥ 0, i.e. for
p̃∞ ≥ p̃FC(V) = (hk/2)|E(kV)|/E0 (the paper's threshold relation |E(kVth)|/E0 = 2p̃∞/(hk)).
docs/conventions.md, 'Reading the paper', lists these readings with the others.

References: Appendix B (eqs B1–B8) and the transition of §3 of Menga, Putignano, Carbone &
Demelio, Proc. R. Soc. A 470, 20140392, 2014.
"""
from __future__ import annotations

import math


def modulus(w, rho):
    """|E(kV)|/E0 and the loss angle δ (rad) of the standard linear solid at speed w = V/V0."""
    if w <= 1.0:
        mag = math.sqrt((1.0 + w * w) / (1.0 + (w / rho) ** 2))
    else:  # divide through by w² to stay finite at any speed
        mag = rho * math.sqrt((1.0 / (w * w) + 1.0) / ((rho / w) ** 2 + 1.0))
    # atan(w) − atan(w/ρ) as a single atan, accurate at both ends; (ρ − 1)/ρ rather than
    # 1 − 1/ρ, which keeps only ~1e-16/(ρ − 1) of its digits as ρ → 1
    delta = math.atan2(w * ((rho - 1.0) / rho), 1.0 + w * w / rho)
    return mag, delta


def transition_load(speed, ratio=3.0, hk=1.0):
    """p̃FC(V): the smallest load that keeps full contact at speed V/V0 (figure 8)."""
    mag, _ = modulus(speed, ratio)
    return 0.5 * hk * mag


def threshold_speed(load, ratio=3.0, hk=1.0):
    """Vth/V0: full contact below it, partial above (|E(kVth)|/E0 = 2p̃∞/(hk)).

    Returns 0.0 when the load is below (p̃FC)0 = hk/2 (partial contact at every speed) and
    inf when it is at or above (p̃FC)∞ = ρ hk/2 (full contact at every speed).
    """
    m = 2.0 * load / hk
    if m <= 1.0:
        return 0.0
    if m >= ratio:
        return math.inf
    # (1 + w²)/(1 + w²/ρ²) = m²  ⇒  w² = (m² − 1)/(1 − m²/ρ²)
    return math.sqrt((m - 1.0) * (m + 1.0) / ((1.0 - m / ratio) * (1.0 + m / ratio)))


def friction_stress(speed, ratio=3.0, hk=1.0):
    """τ̃f in full contact (independent of the load, eq. B8)."""
    mag, delta = modulus(speed, ratio)
    return 0.25 * hk * hk * mag * math.sin(delta)
