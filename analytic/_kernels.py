"""Compiled quadrature loops of the semi-analytic road (numba, cache=True, IEEE arithmetic).

Every integral here is ∫_0^T f(t) dt with t the distance from a contact or gap edge, where f
behaves like t^{±1/2}·(analytic) at t = 0 and may carry a boundary layer of width ℓ ≪ T (the
memory weights e^{−βt} and e^{−t/w}).  The graded rule used throughout:

* first panel [0, h0] mapped by t = u², which turns t^{±1/2} into an analytic integrand;
* following panels [h0 2^{j−1}, h0 2^j] up to T: each sees the edge at a distance of at least
  its own width, so 20-point Gauss–Legendre converges like 5.8^{−40} there;
* h0 = ¼ × the smallest feature scale near the edge (layer width, distance to the next
  singular point of the analytic continuation).

Notation as in `_closure.py`: contact |θ| < A, gap A < θ < 2π − A, G = π − A; tL, tR are the
distances from the trailing (−A) and leading (+A) edges of the contact; uL, uR from the contact
edges A and 2π − A bounding the gap.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

_X, _W = np.polynomial.legendre.leggauss(20)
X01 = 0.5 * (_X + 1.0)
W01 = 0.5 * _W
NG = 20
# φ(y) = y sqrt(1 + y²) − asinh(y) = 2 Σ_n C(−1/2, n) y^{2n+3}/(2n+3) for y < 1/2
PHI_C = np.array([2.0 * math.comb(2 * n, n) * (-0.25) ** n / (2 * n + 3) for n in range(30)])


@njit(cache=True)
def panel_count(T, h0):
    """Panels of the graded rule on [0, T] with first panel h0 ≤ T."""
    if h0 >= T:
        return 1
    return int(math.ceil(math.log2(T / h0))) + 1


@njit(cache=True)
def node(T, h0, npan, p, i):
    """Node t and weight of the i-th Gauss point of panel p of the graded rule on [0, T]."""
    if p == 0:
        su = math.sqrt(min(h0, T))
        u = su * X01[i]
        return u * u, su * W01[i] * 2.0 * u
    lo = min(h0 * 2.0 ** (p - 1), T)
    hi = T if p == npan - 1 else min(h0 * 2.0 ** p, T)
    return lo + (hi - lo) * X01[i], (hi - lo) * W01[i]


@njit(cache=True)
def graded_nodes(L, hl, hr):
    """Nodes of the two-sided graded rule on [0, L]: distances from both ends, and weights."""
    half = 0.5 * L
    hl = min(hl, half)
    hr = min(hr, half)
    nl = panel_count(half, hl)
    nr = panel_count(half, hr)
    n = (nl + nr) * NG
    from_left = np.empty(n)
    from_right = np.empty(n)
    weight = np.empty(n)
    k = 0
    for p in range(nl):
        for i in range(NG):
            s, wt = node(half, hl, nl, p, i)
            from_left[k] = s
            from_right[k] = L - s
            weight[k] = wt
            k += 1
    for p in range(nr):
        for i in range(NG):
            s, wt = node(half, hr, nr, p, i)
            from_left[k] = L - s
            from_right[k] = s
            weight[k] = wt
            k += 1
    return from_left, from_right, weight


@njit(cache=True)
def phi(y):
    """y sqrt(1 + y²) − asinh(y) without cancellation (y ≥ 0)."""
    if y < 0.5:
        y2 = y * y
        acc = 0.0
        for n in range(PHI_C.size - 1, -1, -1):
            acc = acc * y2 + PHI_C[n]
        return acc * y2 * y
    return y * math.sqrt(1.0 + y * y) - math.asinh(y)


@njit(cache=True)
def contact_density(tL, tR, G, Hc, Hs, kappa):
    """P = Hc P_W + κ P_K + Hs P_W' at distances tL, tR from the trailing and leading edges."""
    r2 = math.sin(0.5 * tL) * math.sin(0.5 * tR)
    r = math.sqrt(r2)
    c2 = math.sin(0.5 * (G + min(tL, tR)))   # cos(θ/2) = sin((π − |θ|)/2)
    s2 = math.sin(0.25 * (tL - tR))          # sin(θ/2), θ = (tL − tR)/2
    return (2.0 * Hc * c2 * r2 + kappa * c2 - Hs * s2 * (c2 * c2 + r2)) / r


@njit(cache=True)
def gap_density(uL, uR, sA, Hc, Hs, kappa):
    """R_q = Hc D + κ Q_K + Hs D' at distances uL, uR from the gap ends A and 2π − A."""
    R = math.sqrt(math.sin(0.5 * uL) * math.sin(0.5 * uR))
    c2 = math.sin(0.25 * (uR - uL))          # cos(θ/2), odd about θ = π
    y = R / sA
    return 2.0 * sA * sA * Hc * phi(y) - 2.0 * kappa * math.asinh(y) + 2.0 * Hs * c2 * R


@njit(cache=True)
def closure_integrals(A, G, w, rho):
    """I_W, I_K, I_WK = I_W − sin²(A/2) I_K, I_W0, D_J, J_K of `_closure.py`.

    The contact integrals carry the weight e^{−β(θ+A)}; I_WK and I_W0 = ∫ P_W (e^{−β(θ+A)} −
    e^{−βA}) are integrated against the weight minus its value at the centre, so that neither
    suffers the cancellation of the difference written out.
    """
    beta = rho / w
    sA = math.sin(0.5 * A)
    sA2 = sA * sA
    # contact, mirror pair ±θ summed; t = distance to the nearer edge, |θ| = A − t
    h0 = 0.25 * min(1.0 / beta, 2.0 * A, 2.0 * G)
    npan = panel_count(A, h0)
    IW = 0.0
    IK = 0.0
    IWK = 0.0
    IW0 = 0.0
    ebA = math.exp(-beta * A)
    for p in range(npan):
        for i in range(NG):
            t, wt = node(A, h0, npan, p, i)
            far = math.sin(A - 0.5 * t) if A <= G else math.sin(G + 0.5 * t)
            r2 = math.sin(0.5 * t) * far
            r = math.sqrt(r2)
            c2 = math.sin(0.5 * (G + t))
            even = math.exp(-beta * t) + math.exp(-beta * (2.0 * A - t))
            x = beta * (A - t)
            if x < 1.0:  # even − 2e^{−βA} = 4 e^{−βA} sinh²(β|θ|/2), without cancellation
                even0 = 4.0 * ebA * math.sinh(0.5 * x) ** 2
            else:
                even0 = (math.exp(-0.5 * beta * t) - math.exp(-0.5 * beta * (2.0 * A - t))) ** 2
            IW += wt * even * 2.0 * c2 * r
            IK += wt * even * c2 / r
            IWK += wt * even0 * c2 * (2.0 * r2 - sA2) / r
            IW0 += wt * even0 * 2.0 * c2 * r
    # gap, pair (θ, 2π − θ): cos(θ/2) is odd about π, weight e^{−u/w} − e^{−(2G−u)/w}
    h0 = 0.25 * min(w, 2.0 * A, 2.0 * G)
    npan = panel_count(G, h0)
    DJ = 0.0
    JK = 0.0
    for p in range(npan):
        for i in range(NG):
            u, wt = node(G, h0, npan, p, i)
            far = math.sin(A + 0.5 * u) if A <= G else math.sin(G - 0.5 * u)
            R = math.sqrt(math.sin(0.5 * u) * far)
            c2 = math.sin(0.5 * (G - u))
            odd = -math.exp(-u / w) * math.expm1(-2.0 * (G - u) / w)
            DJ += wt * odd * 2.0 * c2 * R
            JK += wt * odd * c2 / R
    return IW, IK, IWK, IW0, DJ, JK


@njit(cache=True)
def contact_pressure(theta, A, G, beta, Hc, Hs, kappa):
    """Σ(θ) = β ∫_θ^A P(φ) e^{−β(φ−θ)} dφ at one point −A ≤ θ ≤ A (inverse of eq. 2.8)."""
    tL0 = min(max(theta + A, 0.0), 2.0 * A)   # distance of θ from the trailing edge
    ell = min(max(A - theta, 0.0), 2.0 * A)
    if ell <= 0.0:
        return 0.0
    feat = min(1.0 / beta, 2.0 * G, 2.0 * A)
    # refined toward θ (memory layer, the trailing edge at distance tL0) and toward A
    s, sR, wq = graded_nodes(ell, 0.25 * (min(feat, tL0) if tL0 > 0.0 else feat), 0.25 * feat)
    acc = 0.0
    for j in range(s.size):
        acc += wq[j] * contact_density(tL0 + s[j], sR[j], G, Hc, Hs, kappa) * math.exp(-beta * s[j])
    return beta * acc


@njit(cache=True)
def gap_function(theta, A, G, w, Hc, Hs, kappa):
    """u(θ) = gap/h = (1/w) ∫_θ^{2π−A} R_q(ξ) e^{−(ξ−θ)/w} dξ at one point A ≤ θ ≤ 2π − A."""
    uL0 = min(max(theta - A, 0.0), 2.0 * G)   # distance of θ from the contact edge A
    ell = 2.0 * G - uL0
    if ell <= 0.0:
        return 0.0
    sA = math.sin(0.5 * A)
    feat = min(w, 2.0 * A, 2.0 * G)
    s, sR, wq = graded_nodes(ell, 0.25 * (min(feat, uL0) if uL0 > 0.0 else feat), 0.25 * feat)
    acc = 0.0
    for j in range(s.size):
        acc += wq[j] * gap_density(uL0 + s[j], sR[j], sA, Hc, Hs, kappa) * math.exp(-s[j] / w)
    return acc / w


@njit(cache=True)
def contact_pressure_many(theta, A, G, beta, Hc, Hs, kappa, out):
    for j in range(theta.size):
        out[j] = contact_pressure(theta[j], A, G, beta, Hc, Hs, kappa)


@njit(cache=True)
def gap_function_many(theta, A, G, w, Hc, Hs, kappa, out):
    for j in range(theta.size):
        out[j] = gap_function(theta[j], A, G, w, Hc, Hs, kappa)


@njit(cache=True)
def paper_closures(A, G, w, rho, ke, Hc, Hs, kappa):
    """Residuals of (2.14) and of (2.15) in its corrected form (DERIVATION.md §4), relative to the
    sum of the absolute values of their terms.

    (2.14): ∫ p exp(−(E∞/E0) x/(Vτ)) dx = 0 over the contact, with the full singular P;
    (2.15): (1/(Vτ)) ∫_a^{λ−a} q_A e^{−(x−a)/(Vτ)} dx = h cos(ka + ke) − h cos(ka − ke) e^{−(λ−2a)/(Vτ)},
    with q_A = Hc Q_W + κ Q_K + Hs Q_W' the Appendix-A displacement from the indenter's mean line.
    Both use two-sided rules over the whole contact and the whole gap (no mirror pairing).
    """
    beta = rho / w
    sA = math.sin(0.5 * A)
    # (2.14) over the whole contact, tL from the trailing edge
    tL, tR, wq = graded_nodes(2.0 * A, 0.25 * min(1.0 / beta, 2.0 * G, 2.0 * A),
                              0.25 * min(2.0 * G, 2.0 * A))
    s_val = 0.0
    s_abs = 0.0
    for j in range(tL.size):
        P = contact_density(tL[j], tR[j], G, Hc, Hs, kappa)
        f = wq[j] * math.exp(-beta * tL[j])
        s_val += f * P
        s_abs += f * abs(P)
    r214 = abs(s_val) / s_abs
    # (2.15) over the whole gap, uL from the contact edge A
    uL, uR, wq = graded_nodes(2.0 * G, 0.25 * min(w, 2.0 * A, 2.0 * G), 0.25 * min(2.0 * A, 2.0 * G))
    q_val = 0.0
    q_abs = 0.0
    for j in range(uL.size):
        R = math.sqrt(math.sin(0.5 * uL[j]) * math.sin(0.5 * uR[j]))
        c2 = math.sin(0.25 * (uR[j] - uL[j]))
        th = A + uL[j]
        QW = math.cos(th) + 2.0 * sA * sA * phi(R / sA)
        QWp = -math.sin(th) + 2.0 * c2 * R
        QK = -2.0 * math.asinh(R / sA)
        qA = Hc * QW + kappa * QK + Hs * QWp
        f = wq[j] * math.exp(-uL[j] / w) / w
        q_val += f * qA
        q_abs += f * abs(qA)
    EL = math.exp(-2.0 * G / w)
    rhs1 = math.cos(A + ke)
    rhs2 = math.cos(A - ke) * EL
    r215 = abs(q_val - rhs1 + rhs2) / (q_abs + abs(rhs1) + abs(rhs2))
    return r214, r215
