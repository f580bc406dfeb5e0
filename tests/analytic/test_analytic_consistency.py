"""Consistency of every solved point (the conditions any correct solution meets) over a grid and over
the whole parameter range, and penetration control as the inverse of load control."""
import math

import numpy as np
import pytest

import analytic
from conftest import QUADRATURE, ROUNDOFF

SPEEDS = np.logspace(-2, 2, 20)


def _check_point(sol):
    assert sol.success, sol.message
    if sol.full_contact:
        return
    for key, val in sol.residuals.items():
        assert val < QUADRATURE, (key, val)
    c = sol.check()
    assert c["min_pressure"] >= -1e-9
    assert c["min_gap"] >= -1e-9
    assert c["mean_pressure_error"] < QUADRATURE
    assert c["mean_displacement"] < QUADRATURE
    assert c["separation_error"] < QUADRATURE
    assert c["pressure_at_edges"] < QUADRATURE
    assert c["gap_at_edges"] < QUADRATURE
    assert c["friction_error"] < QUADRATURE


@pytest.mark.parametrize("ratio", [3.0, 10.0])
def test_grid_10_loads_20_speeds(ratio):
    """10 loads (1e-3 … 1.2 × (p̃FC)∞) × 20 speeds (1e-2 … 1e2): closure residuals < 1e-10,
    σ ≥ −1e-9 p∞λ/(2a) in the contact, gap ≥ −1e-9 h outside, |mean σ − p∞| < 1e-10 p∞, v
    continuous at ±a, mean v = 0, mean gap = s, τ̃f equal to the quadrature of σ ∂v/∂x."""
    hk = 1.0
    loads = np.logspace(-3, math.log10(1.2), 10) * 0.5 * ratio * hk
    nfull = 0
    for load in loads:
        for speed in SPEEDS:
            sol = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
            nfull += sol.full_contact
            _check_point(sol)
    assert 0 < nfull < loads.size * SPEEDS.size  # the grid crosses the transition


@pytest.mark.parametrize("ratio", [1.01, 1000.0])
@pytest.mark.parametrize("hk", [0.05, 4.0])
def test_whole_range(ratio, hk):
    """Speeds 1e-4 … 1e4, loads from 1e-3 of p̃FC to beyond it, extreme ratios and hk."""
    for speed in (1e-4, 1e-2, 1.0, 1e2, 1e4):
        pfc = analytic.transition_load(speed, ratio, hk)
        for f in (1e-3, 0.3, 0.999, 1.5):
            sol = analytic.solve(load=f * pfc, speed=speed, ratio=ratio, hk=hk)
            assert sol.full_contact == (f >= 1.0)
            _check_point(sol)


@pytest.mark.parametrize("speed", [0.01, 0.5, 2.0, 100.0])
def test_penetration_control_inverts_load_control(speed):
    for pen in (0.05, 0.5, 0.9, 0.999):
        sp = analytic.solve(penetration=pen, speed=speed)
        assert sp.success and sp.penetration == pytest.approx(pen, rel=ROUNDOFF)
        sl = analytic.solve(load=sp.load, speed=speed)
        assert sl.ka == pytest.approx(sp.ka, rel=ROUNDOFF)
        assert sl.ke == pytest.approx(sp.ke, rel=1e-11)
        assert sl.penetration == pytest.approx(pen, rel=ROUNDOFF)
        assert sl.mu == pytest.approx(sp.mu, rel=1e-11)


def test_penetration_one_is_the_transition_load():
    for speed in (0.1, 3.0):
        sol = analytic.solve(penetration=1.0, speed=speed)
        assert sol.full_contact
        assert sol.load == pytest.approx(analytic.transition_load(speed), rel=ROUNDOFF)


def test_fixed_penetration_gives_the_same_profile_at_both_speed_limits():
    """Figure 3b: at fixed Δ the elastic limits E0 and E∞ give the same displacement field."""
    X = np.linspace(-0.5, 0.5, 401)
    lo = analytic.solve(penetration=0.8, speed=1e-12).fields(X)
    hi = analytic.solve(penetration=0.8, speed=1e12).fields(X)
    assert np.max(np.abs(lo.displacement - hi.displacement)) < 1e-9


def test_paper_statements_on_eccentricities():
    """e < ê in partial contact (figure 11), both positive (toward the leading edge); the contact
    shrinks with speed at fixed load (figure 5) and has its minimum near V0 at fixed Δ (figure 7)."""
    for speed in (0.1, 1.0, 10.0):
        sol = analytic.solve(load=0.3, speed=speed)
        assert 0 < sol.ke < sol.ke_hat
    kas = [analytic.solve(load=0.3, speed=s).ka for s in np.logspace(-2, 2, 9)]
    assert np.all(np.diff(kas) < 0)
    speeds = np.logspace(-2, 2, 41)
    kas = [analytic.solve(penetration=0.8, speed=s).ka for s in speeds]
    assert 0.3 < speeds[int(np.argmin(kas))] < 3.0
