"""Full contact (Appendix B) and the transition.

Appendix B is re-implemented here from the paper's own formulas — M(k, ω) = −2(1 − ν²)/(E(ω)|k|),
E(ω)⁻¹ = iωJ(ω) with J(ω) = ∫ J(t) e^{−iωt} dt, σ_max = h|M⁻¹|, φ = arg M⁻¹ (the printed arg|M⁻¹|
is a typo), F_T = π h² Im M⁻¹ per wavelength — with J(ω) integrated numerically, and compared with
the solver's closed forms.
"""
import math

import numpy as np
import pytest
from scipy.integrate import quad

import analytic
from analytic.full_contact import modulus
from conftest import QUADRATURE, ROUNDOFF

RHO, HK = 3.0, 1.0


def appendix_b(speed, ratio, hk):
    """Amplitude (over E0/(1−ν²)), |phase| and |F_T|/λ (over E0/(1−ν²)) from (B2)–(B8).

    Units: k = 1, τ = 1, E0 = 1, 1 − ν² = 1.  J(ω) = ∫_0^∞ J(t) e^{−iωt} dt for the SLS is done
    with the J(∞) part analytically (1/(iω E0)) and the decaying part by QUADPACK's Fourier rule.
    """
    E0, Einf = 1.0, ratio
    E1inv = 1.0 / E0 - 1.0 / Einf
    omega = speed  # ω = kV, k = 1, τ = 1
    re = quad(lambda t: -E1inv * math.exp(-t), 0, np.inf, weight="cos", wvar=omega)[0]
    im = -quad(lambda t: -E1inv * math.exp(-t), 0, np.inf, weight="sin", wvar=omega)[0]
    J = 1.0 / (1j * omega * E0) + complex(re, im)
    E = 1.0 / (1j * omega * J)
    Minv = -E * 1.0 / 2.0               # M⁻¹ = −E|k|/(2(1 − ν²))
    h = hk
    sigma_max = h * abs(Minv)
    phase = abs(math.atan2(Minv.imag, -Minv.real))  # arg of −M⁻¹ (tensile → compressive)
    FT_per_lambda = math.pi * h * h * abs(Minv.imag) / (2 * math.pi)
    return sigma_max, phase, FT_per_lambda


@pytest.mark.parametrize("speed", [1e-3, 0.1, 1.0, 3.0, 10.0, 1e3])
def test_full_contact_against_appendix_b(speed):
    load = 2.0 * analytic.transition_load(speed, RHO, HK)
    sol = analytic.solve(load=load, speed=speed, ratio=RHO, hk=HK)
    assert sol.full_contact and sol.ka == math.pi and sol.ke is None and sol.penetration == 1.0
    amp, phase, ft = appendix_b(speed, RHO, HK)
    assert sol.ke_hat == pytest.approx(phase, rel=ROUNDOFF, abs=1e-15)
    assert sol.tau_f == pytest.approx(ft, rel=ROUNDOFF)
    assert sol.mu == pytest.approx(ft / load, rel=ROUNDOFF)
    f = sol.fields(np.linspace(-0.5, 0.5, 4001))
    assert 0.5 * (f.pressure.max() - f.pressure.min()) == pytest.approx(amp, rel=1e-6)
    assert f.x_over_lambda[np.argmax(f.pressure)] * 2 * math.pi == pytest.approx(phase, abs=2e-3)


def test_friction_is_load_independent_in_full_contact():
    """(B8): τf does not depend on the load, so μ falls as 1/p∞ (figure 12)."""
    speed = 1.0
    pfc = analytic.transition_load(speed, RHO, HK)
    taus = [analytic.solve(load=f * pfc, speed=speed, ratio=RHO, hk=HK).tau_f for f in (1.0, 1.5, 3.0)]
    assert np.ptp(taus) < ROUNDOFF * taus[0]


def test_transition_load_limits_and_threshold_speed_inverse():
    assert analytic.transition_load(1e-12, RHO, HK) == pytest.approx(0.5, rel=ROUNDOFF)
    assert analytic.transition_load(1e12, RHO, HK) == pytest.approx(1.5, rel=ROUNDOFF)
    for load in (0.6, 1.0, 1.4):
        v = analytic.threshold_speed(load, RHO, HK)
        assert analytic.transition_load(v, RHO, HK) == pytest.approx(load, rel=ROUNDOFF)
    assert analytic.threshold_speed(0.4, RHO, HK) == 0.0
    assert analytic.threshold_speed(1.6, RHO, HK) == math.inf
    # |E(kV)| from Appendix B equals the full-contact load
    for speed in (0.1, 1.0, 10.0):
        amp, _, _ = appendix_b(speed, RHO, HK)
        assert analytic.transition_load(speed, RHO, HK) == pytest.approx(amp, rel=1e-10)


@pytest.mark.parametrize("speed", [0.3, 1.0, 5.0])
def test_partial_contact_joins_full_contact_at_the_transition(speed):
    """Just below p̃FC: ka → π, ke and kê → the loss angle, τf → Appendix B (continuity)."""
    pfc = analytic.transition_load(speed, RHO, HK)
    mag, delta = modulus(speed, RHO)
    above = analytic.solve(load=pfc * (1 + 1e-12), speed=speed, ratio=RHO, hk=HK)
    assert above.full_contact
    gaps = []
    for eps in (1e-4, 1e-8, 1e-12):
        below = analytic.solve(load=pfc * (1 - eps), speed=speed, ratio=RHO, hk=HK)
        assert below.success and not below.full_contact
        gaps.append(math.pi - below.ka)
        assert below.ke == pytest.approx(delta, abs=3 * eps ** 0.5)
        assert below.ke_hat == pytest.approx(delta, abs=10 * eps)
        assert below.tau_f == pytest.approx(above.tau_f, rel=10 * eps + 1e-13)
        assert below.penetration == pytest.approx(1.0, abs=10 * eps)
    # the root is not lost as ka → π: π − ka ∝ sqrt(p̃FC − p̃∞) down to a deficit of 1e-12
    # (next-order term O(deficit) ≈ 0.6 % at 1e-4; round-off in ka is ~1e-16/deficit relative)
    assert gaps[0] / gaps[1] == pytest.approx(100.0, rel=1e-2)
    assert gaps[1] / gaps[2] == pytest.approx(100.0, rel=1e-3)


def test_threshold_speed_separates_full_and_partial_contact():
    load = 1.0
    vth = analytic.threshold_speed(load, RHO, HK)
    assert analytic.solve(load=load, speed=vth * (1 - 1e-9), ratio=RHO, hk=HK).full_contact
    sol = analytic.solve(load=load, speed=vth * (1 + 1e-6), ratio=RHO, hk=HK)
    assert not sol.full_contact and sol.ka > math.pi - 1e-2
