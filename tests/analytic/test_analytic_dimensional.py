"""The SI front: unit invariance and agreement with the dimensionless solver."""
import math

import numpy as np
import pytest

import analytic
from analytic import solve_si
from viscosine import Fields, SIResult
from conftest import ROUNDOFF

BASE = dict(E0=5e6, Einf=15e6, tau_creep=2e-3, nu=0.45, wavelength=1e-3, amplitude=1.5e-4, speed=0.05)


def _scaled(L, S, T):
    """The same physical problem in units where length ×L, stress ×S, time ×T."""
    b = BASE
    return dict(E0=b["E0"] * S, Einf=b["Einf"] * S, tau_creep=b["tau_creep"] * T, nu=b["nu"],
                wavelength=b["wavelength"] * L, amplitude=b["amplitude"] * L,
                speed=b["speed"] * L / T)


@pytest.mark.parametrize("control", ["load", "penetration"])
def test_unit_invariance(control):
    ref = solve_si(**BASE, **({"mean_pressure": 1e6} if control == "load" else {"penetration": 1e-4}))
    x = np.linspace(-5e-4, 5e-4, 11)
    f0 = ref.fields(x)
    assert isinstance(ref, SIResult) and isinstance(f0, Fields) and f0.units == "SI"
    sig0, v0 = f0.pressure, f0.displacement
    for L, S, T in [(1e3, 1e-6, 1.0), (1e-2, 7.0, 3e3), (2.0, 1.0, 1e-4)]:
        kw = _scaled(L, S, T)
        r = solve_si(**kw, **({"mean_pressure": 1e6 * S} if control == "load" else {"penetration": 1e-4 * L}))
        assert r.contact_halfwidth == pytest.approx(ref.contact_halfwidth * L, rel=ROUNDOFF)
        assert r.eccentricity == pytest.approx(ref.eccentricity * L, rel=1e-11)
        assert r.pressure_eccentricity == pytest.approx(ref.pressure_eccentricity * L, rel=1e-11)
        assert r.penetration == pytest.approx(ref.penetration * L, rel=ROUNDOFF)
        assert r.mean_separation == pytest.approx(ref.mean_separation * L, rel=ROUNDOFF)
        assert r.mean_pressure == pytest.approx(ref.mean_pressure * S, rel=ROUNDOFF)
        assert r.friction_stress == pytest.approx(ref.friction_stress * S, rel=1e-11)
        assert r.friction_coefficient == pytest.approx(ref.friction_coefficient, rel=1e-11)
        assert r.threshold_speed == pytest.approx(ref.threshold_speed * L / T, rel=ROUNDOFF) or \
            (r.threshold_speed == ref.threshold_speed == 0.0)
        f = r.fields(x * L)
        sig, v = f.pressure, f.displacement
        assert np.allclose(f.x_over_lambda, f0.x_over_lambda, rtol=ROUNDOFF, atol=ROUNDOFF)
        assert np.allclose(sig, sig0 * S, rtol=1e-11, atol=1e-11 * np.abs(sig0).max() * S)
        assert np.allclose(v, v0 * L, rtol=1e-11, atol=1e-11 * np.abs(v0).max() * L)


def test_si_matches_the_dimensionless_groups():
    r = solve_si(**BASE, mean_pressure=1e6)
    k = 2 * math.pi / BASE["wavelength"]
    estar = BASE["E0"] / (1 - BASE["nu"] ** 2)
    sol = analytic.solve(load=1e6 / estar, speed=BASE["speed"] * BASE["tau_creep"] * k, ratio=3.0, hk=BASE["amplitude"] * k)
    assert r.contact_halfwidth * k == pytest.approx(sol.ka, rel=ROUNDOFF)
    assert r.friction_coefficient == pytest.approx(sol.mu, rel=ROUNDOFF)


@pytest.mark.parametrize("kw,name", [
    (dict(E0=-1.0), "E0"), (dict(E0=float("nan")), "E0"), (dict(Einf=4e6), "Einf"),
    (dict(tau_creep=0.0), "tau_creep"), (dict(nu=0.6), "nu"), (dict(nu=-1.0), "nu"),
    (dict(wavelength=0.0), "wavelength"), (dict(amplitude=float("inf")), "amplitude"),
    (dict(speed=-1.0), "speed"),
])
def test_si_bad_input(kw, name):
    args = {**BASE, **kw}
    with pytest.raises(ValueError, match=name):
        solve_si(**args, mean_pressure=1e6)


def test_si_penetration_beyond_amplitude():
    with pytest.raises(ValueError, match="penetration"):
        solve_si(**BASE, penetration=2 * BASE["amplitude"])
    with pytest.raises(ValueError, match="exactly one"):
        solve_si(**BASE)
