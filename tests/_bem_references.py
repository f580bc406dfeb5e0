"""Independent references for the BEM tests (closed forms; nothing from bem/).

Fourier reference of the influence coefficients
------------------------------------------------
For N panels, C_m = (1/N) sum_k Chat_k exp(2 pi i k m / N) with the aliased sum
Chat_k = sum_p s(k + pN),  s(n) = (2/|n|) J*(n) sinc(pi n/N),
J*(n) = J(0+) + sum_i J_i / (1 - i n W_i),  W_i = w tau_i.
With n = k + pN, sinc(pi n/N) = (-1)^p sin(pi k/N) N/(pi n), so
Chat_k = (2 N sin(pi k/N)/pi) [J(0+) A_k + sum_i J_i B_k(W_i)],
A_k = sum_p (-1)^p/(n|n|),  B_k(W) = sum_p (-1)^p/(n|n|(1 - i n W)).
Alternating Hurwitz sums eta_s(x) = sum_{p>=0} (-1)^p/(p + x)^s close them:
A_k = (eta_2(x) + eta_2(1-x))/N^2, x = k/N, and
* W <= 1: 1/(n^2(1 - i n W)) = 1/n^2 + iW/n + (iW)^2/(1 - i n W) gives
  B_k = A_k + (iW/N) {[eta_1(x) - eta_1(1-x)] - [eta_1(z) - eta_1(1-z)]},
  z = (k + i/W)/N (digamma of complex argument);
* W > 1: 1/(n^2(1 - i n W)) = i/(n^3 W) + 1/(n^4 W^2) - 1/(n^4 W^2 (1 - i n W)) gives
  B_k = (i/W)(eta_3(x) - eta_3(1-x))/N^3 + (eta_4(x) + eta_4(1-x))/(W^2 N^4)
        - W^-2 sum_p (-1)^p sgn(n)/(n^4 (1 - i n W))   (last sum direct, ~|p|^-5).
Each form avoids the cancellation the other suffers from.
"""
from __future__ import annotations

import numpy as np
from scipy import special


def _eta1(x):
    """sum_{p>=0} (-1)^p/(p+x) (x may be complex)."""
    return 0.5 * (special.psi((x + 1.0) / 2.0) - special.psi(x / 2.0))


def _eta_s(s, x):
    """sum_{p>=0} (-1)^p/(p+x)^s for real x > 0, s >= 2 (Hurwitz zeta)."""
    return 2.0 ** (-s) * (special.zeta(s, x / 2.0) - special.zeta(s, (x + 1.0) / 2.0))


def aliased_symbol(nodes, j_plus, terms, speed, direct_terms=40):
    """Chat_k, k = 0..N-1 (closed forms above); Chat_0 = 0."""
    n_ = nodes
    k = np.arange(1, n_)
    x = k / n_
    a_k = (_eta_s(2, x) + _eta_s(2, 1.0 - x)) / n_**2
    bracket = j_plus * a_k.astype(complex)
    for j_i, tau_i in terms:
        w_i = speed * tau_i
        if w_i == 0.0:
            bracket += j_i * a_k
            continue
        if w_i <= 1.0:
            z = (k + 1j / w_i) / n_
            b_k = a_k + (1j * w_i / n_) * ((_eta1(x) - _eta1(1.0 - x))
                                           - (_eta1(z) - _eta1(1.0 - z)))
        else:
            b_k = (1j / w_i) * (_eta_s(3, x) - _eta_s(3, 1.0 - x)) / n_**3 \
                + (_eta_s(4, x) + _eta_s(4, 1.0 - x)) / (w_i**2 * n_**4)
            rem = np.zeros(k.size, complex)
            for p in range(-direct_terms, direct_terms + 1):
                nn = (k + p * n_).astype(float)
                rem += (-1.0) ** p * np.sign(nn) / (nn**4 * (1.0 - 1j * nn * w_i))
            b_k = b_k - rem / w_i**2
        bracket += j_i * b_k
    out = np.zeros(n_, complex)
    out[1:] = (2.0 * n_ * np.sin(np.pi * x) / np.pi) * bracket
    return out


def fourier_coefficients(nodes, j_plus, terms, speed):
    """C_m from the aliased Fourier symbol (inverse DFT)."""
    chat = aliased_symbol(nodes, j_plus, terms, speed)
    c = np.fft.ifft(chat)
    return c.real, np.max(np.abs(c.imag))


def brute_symbol(nodes, k, j_plus, terms, speed, pmax=200000):
    """Chat_k by direct summation over |p| <= pmax with pairwise averaging of
    the alternating partial sums (an independent check of the closed forms)."""
    p = np.arange(-pmax, pmax + 1)
    n = (k + p * nodes).astype(float)
    jstar = j_plus + sum(j_i / (1.0 - 1j * n * speed * tau_i) for j_i, tau_i in terms)
    s = (2.0 / np.abs(n)) * jstar * np.sinc(n / nodes)
    # symmetric partial sums S_P = sum_{|p|<=P}; average consecutive ones
    order = np.argsort(np.abs(p), kind="stable")
    center = s[p == 0][0]
    pos = s[p > 0]
    neg = s[p < 0][::-1]
    partial = center + np.cumsum(pos + neg)
    for _ in range(6):
        partial = 0.5 * (partial[1:] + partial[:-1])
    return partial[-1]


# --------------------------------------------------------------------------
# Westergaard (1939) for a rigid sinusoid on an elastic half-plane
# --------------------------------------------------------------------------
def westergaard(load, hk, modulus):
    """Closed form for mean pressure ``load`` (E0* units), modulus E/E0.

    p* = E* k h / 2, load/p* = sin^2(pi a/lambda), peak pressure 2 pbar/sin(pi a/lambda),
    Delta/h = (pbar/p*)(1 - ln(pbar/p*)).

    Returns dict with ka, penetration, peak, and pressure(x_over_lambda).
    """
    pstar = modulus * hk / 2.0
    r = load / pstar
    psi = np.arcsin(np.sqrt(r))
    out = {
        "ka": 2.0 * psi,
        "penetration": r * (1.0 - np.log(r)),
        "peak": 2.0 * load / np.sin(psi),
    }

    def pressure(x):
        s2 = np.sin(psi) ** 2 - np.sin(np.pi * np.asarray(x)) ** 2
        return np.where(s2 > 0, (2.0 * load / np.sin(psi) ** 2) * np.cos(np.pi * np.asarray(x))
                        * np.sqrt(np.clip(s2, 0.0, None)), 0.0)

    out["pressure"] = pressure
    return out


# --------------------------------------------------------------------------
# Full contact (Appendix B, in the sign conventions of conventions.md)
# --------------------------------------------------------------------------
def jstar(n, j_plus, terms, speed):
    """J*(-k_n V) in units of 1/E_ref for mode n (complex)."""
    return j_plus + sum(j_i / (1.0 - 1j * n * speed * tau_i) for j_i, tau_i in terms)


def full_contact(amplitudes, phases, load, j_plus, terms, speed):
    """Full-contact solution for k y = sum_n a_n cos(2 pi n X + phi_n).

    In full contact v = y - s with s = 0 and each harmonic is independent:
    sigma_hat_n = n a_n e^{i phi_n} / (4 J*(n)),
    sigma(X) = load + sum_n 2 Re(sigma_hat_n e^{2 pi i n X}),
    tau_f = -(1/2pi) int sigma d(ky)/dX dX = sum_n n^2 a_n^2 Im J*(n) / (4 |J*(n)|^2)
    (positive when it resists the motion; the paper's (B8) is minus this).
    Returns dict: pressure(x), tau_f, mu, phase_lead_1 (for a sinusoid k e_hat = arg J*(1)).
    """
    amps = np.asarray(amplitudes, float)
    phs = np.asarray(phases, float)
    ns = np.arange(1, amps.size + 1)
    js = np.array([jstar(n, j_plus, terms, speed) for n in ns])
    shat = ns * amps * np.exp(1j * phs) / (4.0 * js)

    def pressure(x):
        x = np.asarray(x, float)
        return load + sum(2.0 * np.real(sh * np.exp(2j * np.pi * n * x)) for n, sh in zip(ns, shat))

    tau_f = float(np.sum(ns**2 * amps**2 * js.imag / (4.0 * np.abs(js) ** 2)))
    return {"pressure": pressure, "tau_f": tau_f, "mu": tau_f / load,
            "sigma_hat": shat, "jstar": js}
