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
    IWK: float  # ∫ (P_W − sin²(A/2) P_K) e^{−β(θ+A)} dθ, evaluated without cancellation
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


def state(A, G, w, rho):
    """Solve the reduced closure at half-angle A (0 < A < π) for speed w > 0 and ratio ρ > 1."""
    I = integrals(A, G, w, rho)
    sA = math.sin(0.5 * A)
    cA = math.sin(0.5 * G)
    sA2, cA2 = sA * sA, cA * cA
    lsA = log_sin_half(A, G)
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
    # s/h = Hc cos²(A/2) + 2 P̄ log sin(A/2); 1 − Hc cA² rewritten to avoid cancellation
    pen = sA2 + (2.0 * math.sin(0.5 * ke) ** 2 - w * S) * cA2 - 2.0 * Pbar * lsA
    sep = 1.0 - pen
    eps = w / rho
    # pressure centroid from the crest: kê = ke − ε − Hs sA²/P̄, rewritten with (2.14)
    ke_hat = ke - eps * kappa * I.IWK / (I.IW * Pbar)
    # friction: (hk)²/4 · Im[((1 + iw) sA²(1 + cA²) + 2κ cA² e^{ike}) / (1 + iε)], whose
    # numerator Im[(X + iY)(1 − iε)] = Y − εX is written out so that w − ε appears explicitly
    Y_eps_X = w * (1.0 - 1.0 / rho) * sA2 * (1.0 + cA2) + 2.0 * kappa * cA2 * (S - eps * C)
    tau_hat = (0.25 * Y_eps_X / (1.0 + eps * eps) if eps <= 1.0
               else 0.25 * (Y_eps_X / eps) / (eps + 1.0 / eps))
    return State(A, G, w, rho, ke, kappa, Hc, Hs, Pbar, sep, pen, ke_hat, tau_hat, I)
