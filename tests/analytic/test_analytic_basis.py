"""Identity tests of the semi-analytic road's building blocks against independent quadrature.

The elastic arc solution (DERIVATION.md §3) and the four closure integrals (§4) are checked with
QUADPACK (scipy.integrate.quad), which shares nothing with the graded Gauss rules of the solver.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

from analytic import _kernels as K
from analytic._closure import integrals, state
from conftest import QUADRATURE, ROUNDOFF

A = 2.1
SA = math.sin(A / 2)


def r(t):
    return math.sqrt(max(math.sin((A + t) / 2) * math.sin((A - t) / 2), 0.0))


def P_W(t):
    return 2 * math.cos(t / 2) * r(t)


def P_K(t):
    return math.cos(t / 2) / r(t) if r(t) > 0 else 0.0


def P_Wprime(t):
    return -math.sin(t / 2) * (SA ** 2 + math.cos(t)) / r(t) if r(t) > 0 else 0.0


def log_kernel(P, th):
    """(1/π) ∫ −log|2 sin((θ−φ)/2)| P(φ) dφ over the arc, by QUADPACK."""
    f = lambda p: -math.log(abs(2 * math.sin((th - p) / 2))) * P(p) / math.pi
    pts = [th] if -A < th < A else None
    return quad(f, -A, A, points=pts, limit=500, epsabs=1e-14, epsrel=1e-13)[0]


def D(t):
    s2 = math.sin(t / 2)
    return 2 * (s2 * math.sqrt(s2 ** 2 - SA ** 2) - SA ** 2 * math.acosh(s2 / SA))


INSIDE = [-1.9, -0.7, 0.0, 0.4, 1.3, 2.0]
OUTSIDE = [2.3, 2.9, math.pi, 3.7, 4.1]


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_westergaard_part_of_the_arc_solution():
    """K[P_W] = cos θ + c_W on the arc and cos θ + c_W + D(θ) on the gap, mean(P_W) = sin²(A/2)."""
    vals = [log_kernel(P_W, t) - math.cos(t) for t in INSIDE]
    assert np.ptp(vals) < 1e-11
    cW = vals[0]
    for t in OUTSIDE:
        assert log_kernel(P_W, t) == pytest.approx(math.cos(t) + cW + D(t), abs=1e-11)
    assert quad(P_W, -A, A)[0] / (2 * math.pi) == pytest.approx(SA ** 2, rel=1e-13)
    # zero mean of the displacement fixes c_W: −(1/2π) ∫_gap D = −(cos²(A/2) + 2 sin²(A/2) log sin(A/2))
    assert cW == pytest.approx(-(math.cos(A / 2) ** 2 + 2 * SA ** 2 * math.log(SA)), abs=1e-11)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_flat_punch_part_of_the_arc_solution():
    """K[P_K] = −2 log sin(A/2) on the arc, minus 2 arccosh(sin(θ/2)/sin(A/2)) on the gap."""
    cK = -2 * math.log(SA)
    for t in INSIDE:
        assert log_kernel(P_K, t) == pytest.approx(cK, abs=1e-10)
    for t in OUTSIDE:
        assert log_kernel(P_K, t) == pytest.approx(cK - 2 * math.acosh(math.sin(t / 2) / SA), abs=1e-10)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_antisymmetric_part_is_minus_the_derivative_of_westergaard():
    """K[−P_W'] = sin θ on the arc: (A2) is −P_W' once the appendix's tensile sign is flipped."""
    for t in INSIDE:
        assert -log_kernel(P_Wprime, t) == pytest.approx(math.sin(t), abs=1e-10)


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")  # the reference's own
@pytest.mark.parametrize("A_,w", [(0.3, 0.5), (1.2, 1.0), (2.5, 3.0), (2.9, 0.2), (1.0, 20.0)])
def test_closure_integrals_against_quadpack(A_, w):
    """The graded Gauss rules of the solver against QUADPACK with algebraic end weights."""
    rho = 3.0
    G = math.pi - A_
    beta = rho / w
    I = integrals(A_, G, w, rho)
    sA2 = math.sin(A_ / 2) ** 2
    # contact, t = θ + A ∈ (0, 2A): r² = sin(t/2) sin(A − t/2)
    c2 = lambda t: math.cos((t - A_) / 2)
    rr = lambda t: math.sqrt(math.sin(t / 2) * math.sin(A_ - t / 2))
    # √(t(2A − t))/r without 0/0 at the ends (QAWS evaluates there): x/sin(x/2) = 2/sinc(x/2π)
    smooth = lambda t: 2.0 / math.sqrt(np.sinc(t / (2 * math.pi)) * np.sinc((2 * A_ - t) / (2 * math.pi)))
    opts = dict(weight="alg", wvar=(-0.5, -0.5), epsabs=0.0, epsrel=1e-13, limit=400)
    IW = quad(lambda t: 2 * c2(t) * rr(t) * math.exp(-beta * t), 0, 2 * A_, epsabs=0.0, epsrel=1e-13, limit=400)[0]
    IK = quad(lambda t: c2(t) * smooth(t) * math.exp(-beta * t), 0, 2 * A_, **opts)[0]
    assert I.IW == pytest.approx(IW, rel=QUADRATURE)
    assert I.IK == pytest.approx(IK, rel=QUADRATURE)
    assert I.IWK == pytest.approx(IW - sA2 * IK, rel=1e-8, abs=1e-12 * IW)
    IW0 = quad(lambda t: 2 * c2(t) * rr(t) * (math.exp(-beta * t) - math.exp(-beta * A_)), 0, 2 * A_,
               epsabs=0.0, epsrel=1e-13, limit=400)[0]
    assert I.IW0 == pytest.approx(IW0, rel=1e-8, abs=1e-12 * IW)
    # gap, u = θ − A ∈ (0, 2G): R² = sin(u/2) sin(A + u/2)
    cg = lambda u: math.cos((u + A_) / 2)
    RR = lambda u: math.sqrt(math.sin(u / 2) * math.sin(A_ + u / 2))
    smoothg = lambda u: 2.0 / math.sqrt(np.sinc(u / (2 * math.pi)) * np.sinc((2 * G - u) / (2 * math.pi)))
    DJ = quad(lambda u: 2 * cg(u) * RR(u) * math.exp(-u / w), 0, 2 * G, epsabs=1e-15, epsrel=1e-13, limit=400)[0]
    JK = quad(lambda u: cg(u) * smoothg(u) * math.exp(-u / w), 0, 2 * G, **opts)[0]
    assert I.DJ == pytest.approx(DJ, rel=1e-9)
    assert I.JK == pytest.approx(JK, rel=QUADRATURE)


def test_phi_series_and_direct_forms_agree():
    y = np.linspace(0.3, 0.7, 41)
    direct = y * np.sqrt(1 + y * y) - np.arcsinh(y)
    got = np.array([K.phi(v) for v in y])
    assert np.allclose(got, direct, rtol=1e-14, atol=0)
    # small y: leading term (2/3) y³ − y⁵/5
    for v in [1e-3, 1e-6]:
        assert K.phi(v) == pytest.approx(2 / 3 * v ** 3 - v ** 5 / 5, rel=ROUNDOFF)


@pytest.mark.parametrize("A_", [0.2, 1.0, 2.0, 3.0])
@pytest.mark.parametrize("w", [1e-3, 0.3, 3.0, 1e3])
@pytest.mark.parametrize("rho", [1.5, 3.0, 100.0])
def test_friction_as_positive_terms_equals_the_closed_form(A_, w, rho):
    """Where the closed form (hk)²/4 · Im[((1 + iw) sA²(1 + cA²) + 2κ cA² e^{ike})/(1 + iε)] has
    no cancellation (contacts of order one), the sum-of-positive-terms form equals it."""
    st = state(A_, math.pi - A_, w, rho)
    sA2, cA2 = math.sin(A_ / 2) ** 2, math.cos(A_ / 2) ** 2
    E = ((1 + 1j * w) * sA2 * (1 + cA2) + 2 * st.kappa * cA2 * np.exp(1j * st.ke)) / (1 + 1j * w / rho)
    assert st.tau_hat == pytest.approx(0.25 * E.imag, rel=1e-12)


def test_closure_reduction_solves_the_unreduced_equations():
    """ke and κ from the reduced closure satisfy (2.14)–(2.15) written with the full integrands."""
    for A_, w in [(0.5, 0.1), (1.5, 1.0), (2.8, 7.0)]:
        st = state(A_, math.pi - A_, w, 3.0)
        r214, r215 = K.paper_closures(st.A, st.G, st.w, st.rho, st.ke, st.Hc, st.Hs, st.kappa)
        assert r214 < QUADRATURE and r215 < QUADRATURE
