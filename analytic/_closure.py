"""The closure of the partial-contact problem for a given contact half-angle A = ka.

Notation (all dimensionless, see `analytic/DERIVATION.md` for the derivation):

* θ = k x measured from the centre of the contact, contact on |θ| < A, gap on A < θ < 2π − A;
  G = π − A (kept separately so that nothing near the transition is computed as π − A);
* w = V τ k = V/V0, ρ = E∞/E0, β = ρ/w = 1/ε (ε is the pressure memory length in θ);
* pressures P = 2p/(E* k h) and Σ = 2σ/(E* k h) with E* = E0/(1 − ν²); P̄ = mean of P = 2p̃∞/(hk);
* after Hunter's transformation (eqs 2.7–2.8) the pressure in the contact is
  P = Hc·P_W + κ·P_K + Hs·P_W', with P_W = 2 cos(θ/2) r, P_K = cos(θ/2)/r,
  r = sqrt(sin((A+θ)/2) sin((A−θ)/2)), Hc = C + wS, Hs = S − wC, C = cos ke, S = sin ke.

The two closure equations (2.14) and (2.15), once the integrals of the derivative terms are
done by parts, reduce to

  (2.14)  [C(1−ρ) + S(w + ρ/w)]·I_W + κ·I_K = 0,
  (2.15)  S(w + 1/w)·D_J − κ·J_K = 0,

with four positive integrals I_W, I_K (contact, weight e^{−β(θ+A)}) and D_J, J_K (gap, weight
e^{−(θ−A)/w}).  Both are linear and homogeneous in (κ, C, S) for fixed A, so ke and κ follow in
closed form from them and the load P̄ = κ + Hc sin²(A/2) is an explicit function of A.  Load or
penetration control is then a one-dimensional root search in A (see `solver.py`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ._kernels import closure_integrals


@dataclass(frozen=True)
class Integrals:
    """The contact and gap integrals of the reduced closure for one (A, w, ρ)."""

    IW: float   # ∫ P_W e^{−β(θ+A)} dθ over the contact
    IK: float   # ∫ P_K e^{−β(θ+A)} dθ over the contact
    IWK: float  # ∫ (P_W − sin²(A/2) P_K) e^{−β(θ+A)} dθ (< 0), evaluated without cancellation
    IW0: float  # ∫ P_W (e^{−β(θ+A)} − e^{−βA}) dθ (≥ 0), evaluated without cancellation
    DJ: float   # ∫ 2 cos(θ/2) R e^{−(θ−A)/w} dθ over the gap
    JK: float   # ∫ cos(θ/2)/R e^{−(θ−A)/w} dθ over the gap


def integrals(A, G, w, rho):
    """Evaluate the closure integrals (see module docstring) for 0 < A < π, 0 < w < ∞."""
    return Integrals(*closure_integrals(A, G, w, rho))


@dataclass(frozen=True)
class State:
    """Everything the closure fixes for one contact half-angle A (partial contact)."""

    A: float
    G: float
    w: float
    rho: float
    ke: float
    kappa: float   # amplitude of the flat-punch (crack-row) part P_K
    Hc: float
    Hs: float
    Pbar: float    # mean of P: 2 p̃∞/(hk)
    sep: float     # mean separation s/h
    pen: float     # Δ/h = 1 − s/h
    ke_hat: float
    tau_hat: float  # τ̃f /(hk)²
    ints: Integrals


def log_sin_half(A, G):
    """log sin(A/2), accurate near A = π."""
    if A > 0.5 * math.pi:
        c = math.sin(0.5 * G)  # cos(A/2)
        return 0.5 * math.log1p(-c * c)
    return math.log(math.sin(0.5 * A))


def westergaard_separation(c):
    """c + (1 − c) ln(1 − c) = Σ_{n≥2} cⁿ/(n(n − 1)) for 0 ≤ c ≤ ½, without cancellation.

    With c = cos²(A/2) this is 1 − sin²(A/2)(1 − ln sin²(A/2)): Westergaard's s/h at half-angle A
    (it vanishes like c²/2 at the transition, where the closed form cancels to nothing).
    """
    acc = 0.0
    term = c
    for n in range(2, 200):
        term *= c
        add = term / (n * (n - 1))
        acc += add
        if add <= 1e-17 * acc:
            break
    return acc


def state(A, G, w, rho):
    """Solve the reduced closure at half-angle A (0 < A < π) for speed w > 0 and ratio ρ > 1."""
    I = integrals(A, G, w, rho)
    sA = math.sin(0.5 * A)
    cA = math.sin(0.5 * G)
    sA2, cA2 = sA * sA, cA * cA
    L2 = 2.0 * log_sin_half(A, G)  # ln sin²(A/2) < 0
    # tan ke from eliminating κ between the two closures; every term is positive
    if w <= 1.0:
        num = (rho - 1.0) * w * I.IW * I.JK
        den = (w * w + rho) * I.IW * I.JK + (1.0 + w * w) * I.DJ * I.IK
    else:  # same ratio divided by w², to stay finite at any w
        num = (rho - 1.0) / w * I.IW * I.JK
        den = (1.0 + rho / (w * w)) * I.IW * I.JK + (1.0 / (w * w) + 1.0) * I.DJ * I.IK
    ke = math.atan2(num, den)
    C, S = math.cos(ke), math.sin(ke)
    kappa = S * (w + 1.0 / w) * I.DJ / I.JK
    Hc = C + w * S
    Hs = S - w * C
    Pbar = kappa + Hc * sA2
    # s/h = Hc cA² + 2P̄ ln sA = Hc Wc − κ|ln sA²|, Wc = cA² + sA² ln sA² (Westergaard's s/h).
    # Each of s/h and Δ/h = 1 − s/h is computed where it is the small one, so that neither is
    # the rounding remainder of 1 minus the other and Δ/h ≤ 1 holds exactly when s ≥ 0.
    if sA2 <= 0.5:
        # Δ/h = Hc·sA²(1 − ln sA²) + κ|ln sA²| + 2 sin²(ke/2) − w S
        pen = Hc * sA2 * (1.0 - L2) - kappa * L2 + 2.0 * math.sin(0.5 * ke) ** 2 - w * S
        sep = 1.0 - pen
    else:
        sep = Hc * westergaard_separation(cA2) + kappa * L2
        pen = 1.0 - sep
    eps = w / rho
    # pressure centroid from the crest: kê = ke − ε − Hs sA²/P̄, rewritten with (2.14); I_WK < 0
    ke_hat = ke - eps * kappa * I.IWK / (I.IW * Pbar)
    tau_hat = _friction(I, A, sA2, cA2, C, S, kappa, w, rho)
    return State(A, G, w, rho, ke, kappa, Hc, Hs, Pbar, sep, pen, ke_hat, tau_hat, I)


def _friction(I, A, sA2, cA2, C, S, kappa, w, rho):
    """τ̃f/(hk)² as a sum of positive terms (DERIVATION.md §5).

    The closed form (hk)²/4 · Im[((1 + iw) sA²(1 + cA²) + 2κ cA² e^{ike}) / (1 + iε)] is the
    difference of two terms that agree to O(A²) at small contacts (μ lost all its digits at
    p̃∞ = 1e-14).  With a = ∫P_W cos θ = π sA²(1 + cA²), b = ∫P_K cos θ = 2π cA² it reads
    4π τ̂ (1 + ε²) = ε D + κ b S, D = (ρ − 1) a − κ b C; eliminating κ with (2.14) and the
    moments of P_W, P_K gives D I_K = (ρ − 1)(a I_K − b I_W + S² b I_W) + C S (w + ρ/w) b I_W with
    a I_K − b I_W = 2π² sA⁴ e^{−βA} + π sA² I_W0 − π (2 − sA²) I_WK, every term ≥ 0.
    """
    pi = math.pi
    beta = rho / w
    eps = w / rho
    a = pi * sA2 * (1.0 + cA2)
    b = 2.0 * pi * cA2
    aIK_bIW = (2.0 * pi * pi * sA2 * sA2 * math.exp(-beta * A) + pi * sA2 * I.IW0
               - pi * (2.0 - sA2) * I.IWK)
    D = ((rho - 1.0) * (aIK_bIW + S * S * b * I.IW) + C * S * (w + 1.0 / eps) * b * I.IW) / I.IK
    if eps <= 1.0:
        return (eps * D + kappa * b * S) / (4.0 * pi * (1.0 + eps * eps))
    return (D + kappa * b * S / eps) / (4.0 * pi * (eps + 1.0 / eps))
