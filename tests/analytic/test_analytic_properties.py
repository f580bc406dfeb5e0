"""Property-based tests over the whole accepted input space of the semi-analytic road.

Every point of `analytic.ACCEPTED` (log-uniform draws, bounds included) must give a finite,
physically valid answer that passes its own consistency checks, and the known limits where they
apply; every point outside must end in a ValueError naming the parameter.  Hypothesis runs
derandomized with bounded example counts, so the suite is deterministic.
"""
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

import analytic
from analytic import westergaard
from analytic._accepted import (HK_MAX, HK_MIN, LOAD_MAX, LOAD_MIN, PENETRATION_MIN, RATIO_MAX,
                                SPEED_MAX, SPEED_MIN)
from conftest import LIMIT, QUADRATURE, ROUNDOFF


def _settings(n):
    return settings(max_examples=n, derandomize=True, deadline=None, database=None,
                    suppress_health_check=[HealthCheck.too_slow])


def _log_uniform(lo, hi):
    """Log-uniform floats in [lo, hi], the bounds themselves included."""
    inner = st.floats(math.log10(lo), math.log10(hi)).map(lambda e: min(max(10.0 ** e, lo), hi))
    return st.one_of(st.sampled_from([lo, hi]), inner, inner, inner)


LOADS = _log_uniform(LOAD_MIN, LOAD_MAX)
PENETRATIONS = _log_uniform(PENETRATION_MIN, 1.0)
SPEEDS = st.one_of(st.just(0.0), _log_uniform(SPEED_MIN, SPEED_MAX))
HKS = _log_uniform(HK_MIN, HK_MAX)
# ratio − 1 log-uniform from one ulp of 1 to RATIO_MAX − 1
RATIOS = st.one_of(st.sampled_from([math.nextafter(1.0, 2.0), RATIO_MAX]),
                   _log_uniform(2.3e-16, RATIO_MAX - 1.0).map(lambda d: min(1.0 + d, RATIO_MAX)))
CONTROLS = st.one_of(st.builds(lambda v: {"load": v}, LOADS),
                     st.builds(lambda v: {"penetration": v}, PENETRATIONS))


def _assert_valid(sol):
    """The constraints every answer satisfies, and a JSON record without NaN."""
    assert sol.success, sol.message
    for key in ("load", "contact_fraction", "ka", "ke_hat", "penetration", "separation",
                "tau_f", "mu", "max_pressure", "x_max_pressure"):
        assert math.isfinite(getattr(sol, key)), key
    assert 0.0 < sol.ka <= math.pi
    assert 0.0 < sol.penetration <= 1.0 and sol.separation >= 0.0
    assert sol.tau_f >= 0.0 and sol.mu >= 0.0
    assert (sol.mu > 0.0) == (sol.speed > 0.0)
    assert sol.load > 0.0 and sol.max_pressure >= sol.load
    assert -0.5 <= sol.x_max_pressure < 0.5
    if sol.full_contact:
        assert sol.ka == math.pi and sol.penetration == 1.0 and sol.separation == 0.0
        assert sol.ke is None and sol.contact_fraction == 1.0
    else:
        assert sol.ka < math.pi and math.isfinite(sol.ke) and sol.ke >= 0.0
        # the peak sits inside the contact
        p = sol.patches[0]
        assert p.trailing_edge <= sol.x_max_pressure <= p.leading_edge
    rec = sol.as_dict()
    json.dumps(rec, allow_nan=False)
    assert rec["patches"][0]["load"] == sol.load and sol.n_patches == 1


def _rho_floor(sol, tol):
    """``tol``, or the round-off of a difference of terms ρ times larger (50 ρ ε) where that
    is larger: the (2.14) check and the penetration target (analytic/solver.py, _RHO_BOUND)."""
    return max(tol, 50.0 * 2.220446049250313e-16 * sol.ratio)


def _assert_consistent(sol):
    c = sol.check()
    assert c["min_pressure"] >= -1e-9, c
    assert c["min_gap"] >= -1e-9, c
    for key in ("mean_pressure_error", "mean_displacement", "separation_error",
                "pressure_at_edges", "gap_at_edges", "friction_error"):
        assert c[key] < QUADRATURE, (key, c)
    for key, val in sol.residuals.items():
        tol = _rho_floor(sol, QUADRATURE) if key in ("closure_2_14", "target") else QUADRATURE
        assert val < tol, (key, val)


@pytest.mark.slow  # about 20 s (the cheap half below runs by default)
@_settings(60)
@given(control=CONTROLS, speed=SPEEDS, ratio=RATIOS, hk=HKS)
def test_every_accepted_point_is_a_consistent_answer(control, speed, ratio, hk):
    sol = analytic.solve(**control, speed=speed, ratio=ratio, hk=hk)
    _assert_valid(sol)
    _assert_consistent(sol)
    if "penetration" in control:
        assert sol.penetration == pytest.approx(control["penetration"],
                                                rel=_rho_floor(sol, 1e-11))


@_settings(300)
@given(control=CONTROLS, speed=SPEEDS, ratio=RATIOS, hk=HKS)
def test_every_accepted_point_is_a_valid_answer(control, speed, ratio, hk):
    """The cheap half of the test above, on five times as many points."""
    _assert_valid(analytic.solve(**control, speed=speed, ratio=ratio, hk=hk))


@_settings(150)
@given(load=LOADS, factor=st.floats(1e-6, 10.0).map(lambda e: 1.0 + e), speed=SPEEDS,
       ratio=RATIOS, hk=HKS)
def test_penetration_and_half_width_grow_with_the_load(load, factor, speed, ratio, hk):
    assume(load * factor <= LOAD_MAX)
    a = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
    b = analytic.solve(load=load * factor, speed=speed, ratio=ratio, hk=hk)
    assert a.success and b.success
    assert a.ka <= b.ka and a.penetration <= b.penetration
    assert a.full_contact <= b.full_contact


@_settings(150)
@given(load=LOADS, speed=st.one_of(_log_uniform(SPEED_MIN, 1e-12), _log_uniform(1e8, SPEED_MAX)),
       ratio=RATIOS, hk=HKS)
def test_westergaard_at_extreme_speeds(load, speed, ratio, hk):
    """E0 when the memory lengths (V/V0 and V/V0 over ρ) are far below the contact and the
    gap; E∞ at V/V0 ≥ 1e8 and V/V0 ≥ 1e4 ρ (the relaxation time is τ/ρ), where the deviation is
    O((ka V0/V)²)."""
    m = 1.0 if speed < 1.0 else ratio
    assume(m == 1.0 or speed >= 1e4 * ratio)
    sol = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
    assert sol.success
    if load >= westergaard.full_contact_load(hk, m) * (1.0 + 1e-12):
        assert sol.full_contact
        return
    if sol.full_contact:  # within rounding of the transition
        assert load >= westergaard.full_contact_load(hk, m) * (1.0 - 1e-9)
        return
    ka_w = westergaard.half_angle(load, hk, m)
    if m == 1.0:
        # first order in V/V0: ka = ka_W − (1 − 1/ρ)(V/V0)/2; needs the layer ≪ contact and gap
        scale = speed / min(ka_w, math.pi - ka_w)
        assume(scale < 1e-9)
        tol = scale + LIMIT
    else:
        tol = _rho_floor(sol, LIMIT)  # Δ/h: a difference of terms ρ times larger
    assert sol.ka == pytest.approx(ka_w, rel=tol)
    assert sol.penetration == pytest.approx(westergaard.penetration(load, hk, m), rel=tol)


def _appendix_b(speed, ratio, hk):
    """Pressure amplitude, phase and τ̃f of Appendix B from the complex modulus
    E/E0 = (1 + iw)/(1 + iw/ρ) = (1 + w²/ρ + i w(ρ − 1)/ρ)/(1 + w²/ρ²), w = V/V0, written out
    independently of `analytic.full_contact` (ρ − 1 exact: no cancellation as ρ → 1)."""
    w = speed
    den = 1.0 + (w / ratio) ** 2
    re, im = (1.0 + w * (w / ratio)) / den, w * ((ratio - 1.0) / ratio) / den
    return 0.5 * hk * math.hypot(re, im), math.atan2(im, re), 0.25 * hk * hk * im


@_settings(150)
@given(factor=_log_uniform(1.0 + 1e-9, 1e6), speed=SPEEDS, ratio=RATIOS, hk=HKS)
def test_full_contact_is_appendix_b(factor, speed, ratio, hk):
    amp, phase, tau = _appendix_b(speed, ratio, hk)
    load = amp * factor
    assume(LOAD_MIN <= load <= LOAD_MAX)
    sol = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
    _assert_valid(sol)
    assert sol.full_contact
    assert sol.ke_hat == pytest.approx(phase, rel=ROUNDOFF, abs=1e-300)
    assert sol.tau_f == pytest.approx(tau, rel=ROUNDOFF, abs=1e-300)
    assert sol.mu == pytest.approx(tau / load, rel=ROUNDOFF, abs=1e-300)
    assert sol.max_pressure == pytest.approx(load + amp, rel=ROUNDOFF)
    f = sol.fields(np.linspace(-0.5, 0.5, 257))
    assert f.pressure.min() >= 0.0 and np.all(f.gap == 0.0)
    assert sol.check()["min_pressure"] >= 0.0


@_settings(60)
@given(pen=_log_uniform(PENETRATION_MIN, 1.0 - 1e-9), speed=SPEEDS, ratio=RATIOS, hk=HKS)
def test_penetration_control_inverts_load_control(pen, speed, ratio, hk):
    sp = analytic.solve(penetration=pen, speed=speed, ratio=ratio, hk=hk)
    assert sp.success and sp.penetration == pytest.approx(pen, rel=1e-11)
    assume(LOAD_MIN <= sp.load <= LOAD_MAX)
    sl = analytic.solve(load=sp.load, speed=speed, ratio=ratio, hk=hk)
    assert sl.ka == pytest.approx(sp.ka, rel=1e-11)
    assert sl.penetration == pytest.approx(pen, rel=1e-11)


# ----------------------------------------------------------------------------- bad input
GOOD = dict(load=0.3, speed=1.0, ratio=3.0, hk=1.0)
OUTSIDE = {
    "load": st.one_of(st.floats(-1e300, 0.0), st.floats(0.0, LOAD_MIN, exclude_max=True),
                      st.floats(LOAD_MAX, 1e308, exclude_min=True)),
    "penetration": st.one_of(st.floats(-1e300, PENETRATION_MIN, exclude_max=True),
                             st.floats(1.0, 1e308, exclude_min=True)),
    "speed": st.one_of(st.floats(-1e308, 0.0, exclude_max=True),
                       st.floats(0.0, SPEED_MIN, exclude_min=True, exclude_max=True),
                       st.floats(SPEED_MAX, 1e308, exclude_min=True)),
    "ratio": st.one_of(st.floats(-1e308, 1.0), st.floats(RATIO_MAX, 1e308, exclude_min=True)),
    "hk": st.one_of(st.floats(-1e308, HK_MIN, exclude_max=True),
                    st.floats(HK_MAX, 1e308, exclude_min=True)),
}
NOT_NUMBERS = st.sampled_from([math.nan, math.inf, -math.inf, "0.3", None, True, [0.3], 1j])


@_settings(200)
@given(name=st.sampled_from(sorted(OUTSIDE)), data=st.data())
def test_inputs_outside_the_accepted_range_are_refused(name, data):
    value = data.draw(st.one_of(OUTSIDE[name], NOT_NUMBERS))
    assume(not (value is None and name in ("load", "penetration")))
    kw = dict(GOOD)
    if name == "penetration":
        kw.pop("load")
    kw[name] = value
    with pytest.raises(ValueError) as exc:
        analytic.solve(**kw)
    msg = str(exc.value)
    assert msg.startswith(f"{name}=") and "is not allowed" in msg
    if value is not None:  # to validate, None means "not given"
        with pytest.raises(ValueError, match=f"^{name}="):
            analytic.validate(**{name: value})
