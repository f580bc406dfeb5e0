"""The odd inputs, one by one: each is either solved correctly or refused up front with the
supported range (never a traceback, never a non-finite or physically invalid number)."""
import json
import math

import numpy as np
import pytest

import analytic
from analytic import hunter, westergaard
from analytic._accepted import LOAD_MAX, LOAD_MIN, RATIO_MAX, SPEED_MAX
from conftest import QUADRATURE, ROUNDOFF
from test_analytic_properties import _appendix_b, _assert_consistent, _assert_valid


def test_light_load_has_a_positive_penetration_and_friction():
    """p̃∞ = 1e-20 (ka ≈ 1.6e-10): Δ/h ≈ 3.3e-19 > 0, μ > 0, every check at round-off; the
    half-width is Westergaard's with E∞ (the memory length Vτ ≫ a)."""
    sol = analytic.solve(load=1e-20, speed=1.0)
    _assert_valid(sol)
    _assert_consistent(sol)
    assert 0.0 < sol.penetration < 1e-18 and sol.separation == 1.0
    assert sol.ka == pytest.approx(westergaard.half_angle(1e-20, 1.0, 3.0), rel=1e-9)


@pytest.mark.parametrize("Pbar", [1e-12, 1e-24, 1e-36])
def test_vanishing_load_friction_is_hunters(Pbar):
    """At fixed a/(Vτ) = 1 and vanishing load the eccentricities, the load factor and μ are
    Hunter's to first order in the load, i.e. to round-off here: the friction is computed as a
    sum of positive terms (its former closed form lost ~1e-16/p̃∞ of its digits)."""
    h = hunter.solve(1.0, 3.0)
    load = 0.5 * Pbar
    w = 2.0 * math.sqrt(Pbar / h.load_factor)
    for _ in range(60):  # fixed point on V so that ka/(V/V0) = 1
        w = analytic.solve(load=load, speed=w).ka
    sol = analytic.solve(load=load, speed=w)
    A = sol.ka
    assert A / w == pytest.approx(1.0, rel=1e-12)
    assert sol.ke / A == pytest.approx(h.e_over_a, rel=1e-9)
    assert sol.ke_hat / A == pytest.approx(h.e_hat_over_a, rel=1e-9)
    assert Pbar / math.sin(A / 2) ** 2 == pytest.approx(h.load_factor, rel=1e-9)
    assert sol.mu == pytest.approx(A * h.e_hat_over_a, rel=1e-9)  # μ = ê/R, kR = 1/(hk)


@pytest.mark.parametrize("speed", [0.0, 1e-3, 1.0, 30.0])
@pytest.mark.parametrize("ratio", [math.nextafter(1.0, 2.0), 1.5, 3.0, RATIO_MAX])
def test_just_below_the_transition_penetration_stays_at_most_one(speed, ratio):
    """Just below p̃FC, Δ/h once came out as 1.0000000000000002: now s/h is computed without
    cancellation (Westergaard's series), so s ≥ 0 and Δ/h = 1 − s ≤ 1."""
    pfc = 0.5 if speed == 0.0 else analytic.transition_load(speed, ratio)
    for k in (4, 7, 10, 12, 14, 15, 16):
        sol = analytic.solve(load=pfc * (1.0 - 10.0 ** -k), speed=speed, ratio=ratio)
        _assert_valid(sol)
        assert sol.penetration <= 1.0 and sol.separation >= 0.0
        if not sol.full_contact:
            c = sol.check()
            assert c["separation_error"] < QUADRATURE * max(sol.separation, 1e-300) + 1e-15


@pytest.mark.parametrize("load", [1e16, LOAD_MAX])
def test_heavy_load_friction_is_appendix_b(load):
    """p̃∞ = 1e16 once gave μ = 0: μ = τ̃f/p̃∞ with τ̃f of Appendix B, positive."""
    amp, phase, tau = _appendix_b(1.0, 3.0, 1.0)
    sol = analytic.solve(load=load, speed=1.0)
    _assert_valid(sol)
    assert sol.mu > 0.0 and sol.mu == pytest.approx(tau / load, rel=ROUNDOFF)


def test_full_contact_keys_are_exact():
    """Full contact: ka = π, Δ/h = 1, s = 0, contact fraction 1 by construction."""
    for load in (0.5 * 3.0 * (1 + 1e-15), 0.7, 2.0, 1e10):
        for speed in (0.0, 1e-6, 1.0, 1e6):
            sol = analytic.solve(load=load, speed=speed)
            if not sol.full_contact:
                continue
            rec = sol.as_dict()
            assert rec["ka"] == math.pi and rec["penetration"] == 1.0
            assert rec["contact_fraction"] == 1.0 and rec["separation"] == 0.0
            assert rec["patches"][0]["width"] == 1.0


def test_ratio_one_ulp_above_one():
    """E∞/E0 = 1 + 2⁻⁵²: the viscoelastic quantities are first order in ρ − 1, and computed so:
    scaled by ρ − 1 they agree with ρ = 1 + 2⁻⁴⁰ to O(2⁻⁴⁰)."""
    lo, hi = math.nextafter(1.0, 2.0), 1.0 + 2.0 ** -40
    a = analytic.solve(load=0.3, speed=1.0, ratio=lo)
    b = analytic.solve(load=0.3, speed=1.0, ratio=hi)
    _assert_valid(a)
    _assert_consistent(a)
    for key in ("ke", "ke_hat", "mu"):
        assert getattr(a, key) / (lo - 1.0) == pytest.approx(getattr(b, key) / (hi - 1.0), rel=1e-10)
    full = analytic.solve(load=0.6, speed=1.0, ratio=lo)
    amp, phase, tau = _appendix_b(1.0, lo, 1.0)
    assert full.full_contact and full.ke_hat == pytest.approx(phase, rel=ROUNDOFF)


@pytest.mark.parametrize("kw,name,allowed", [
    (dict(load=1e-320), "load", "in [1e-40, 1e+40]"),
    (dict(load=1e41), "load", "in [1e-40, 1e+40]"),
    (dict(ratio=1e308), "ratio", "≤ 1e+08"),
    (dict(ratio=1 + 1e-16), "ratio", "E∞/E0 > 1"),  # 1 + 1e-16 is 1.0 in double precision
    (dict(hk=1e308), "hk", "in [1e-06, 1e+06]"),
    (dict(hk=1e-300), "hk", "in [1e-06, 1e+06]"),
    (dict(speed=1e308), "speed", "in [1e-30, 1e+30]"),
    (dict(speed=1e-300), "speed", "in [1e-30, 1e+30]"),
    (dict(penetration=1e-300), "penetration", "in [1e-40, 1]"),
])
def test_odd_inputs_are_refused_with_the_range(kw, name, allowed):
    args = dict(load=0.3, speed=1.0, ratio=3.0, hk=1.0)
    if "penetration" in kw:
        args.pop("load")
    args.update(kw)
    with pytest.raises(ValueError) as exc:
        analytic.solve(**args)
    msg = str(exc.value)
    assert msg.startswith(f"{name}={float(kw[name])!r} is not allowed") and allowed in msg


def test_accepted_is_data_with_reasons():
    assert set(analytic.ACCEPTED) == {"load", "penetration", "speed", "ratio", "hk"}
    for name, (low, high, text) in analytic.ACCEPTED.items():
        assert 0.0 <= low < high and isinstance(text, str) and len(text) > 40, name
    assert analytic.ACCEPTED["load"][:2] == (LOAD_MIN, LOAD_MAX)
    assert analytic.ACCEPTED["speed"][1] == SPEED_MAX
    assert analytic.validate(load=1, speed=0, ratio=2, hk=1) == dict(load=1.0, speed=0.0,
                                                                     ratio=2.0, hk=1.0)


def test_failed_solution_is_json_ready_and_has_no_fields():
    """A failure (forced here through the private constructor) carries NaN scalars as null."""
    from analytic.solver import _failed
    inputs = {"control": "load", "asked": 0.3, "speed": 1.0, "ratio": 3.0, "hk": 1.0}
    sol = _failed(inputs, "numerical failure: test")
    rec = sol.as_dict()
    json.dumps(rec, allow_nan=False)
    assert rec["success"] is False and rec["ka"] is None and rec["patches"] == []
    with pytest.raises(RuntimeError):
        sol.fields()
    assert np.isnan(sol.max_pressure)
