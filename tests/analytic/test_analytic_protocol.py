"""The result protocol of the semi-analytic road: scalars, JSON record, fields, peak, patches,
sweep and the SI front."""
import json
import math

import numpy as np
import pytest

import analytic
import viscosine
from analytic import westergaard
from conftest import ROUNDOFF
from viscosine import Fields, SIResult

EIGHT = ["full_contact", "contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu"]
RECORD = {"solver", "version", "control", "load_asked", "penetration_asked", "load", "speed",
          "ratio", "hk", *EIGHT, "separation", "success", "message", "warnings", "max_pressure",
          "x_max_pressure", "n_patches", "patches", "diagnostics", "error_estimate"}
PATCH = {"trailing_edge", "leading_edge", "width", "load", "centroid", "summit", "ka", "ke",
         "ke_hat"}


@pytest.mark.parametrize("kw", [dict(load=0.3, speed=1.0), dict(penetration=0.8, speed=0.1),
                                dict(load=2.0, speed=1.0), dict(load=0.2, speed=0.0)])
def test_scalars_and_record(kw):
    sol = analytic.solve(**kw)
    sc = sol.scalars()
    assert list(sc) == EIGHT
    assert all(v is None or type(v) in (bool, float) for v in sc.values())
    rec = sol.as_dict()
    assert set(rec) == RECORD
    assert json.loads(json.dumps(rec, allow_nan=False)) == rec
    assert rec["solver"] == "analytic" and rec["version"] == viscosine.__version__
    control = "load" if "load" in kw else "penetration"
    assert rec["control"] == control and rec[f"{control}_asked"] == kw[control]
    assert rec["error_estimate"] is None and rec["success"] is True
    assert set(rec["diagnostics"]) == {"nit", "nfev", "residuals"}
    assert rec["diagnostics"]["residuals"] == sol.residuals
    assert rec["n_patches"] == 1 and set(rec["patches"][0]) == PATCH
    for k in EIGHT:
        assert rec[k] == sc[k]


def test_default_fields_grid():
    f = analytic.solve(load=0.3, speed=1.0).fields()
    assert isinstance(f, Fields) and f.units == "conventions"
    assert np.array_equal(f.x_over_lambda, np.arange(1024) / 1024 - 0.5)
    with pytest.raises(ValueError, match="x_over_lambda"):
        analytic.solve(load=0.3, speed=1.0).fields([0.0, math.nan])


@pytest.mark.parametrize("load,speed,ratio", [(0.3, 1.0, 3.0), (0.05, 0.01, 3.0), (0.9, 30.0, 3.0),
                                              (1e-8, 1.0, 10.0), (0.4, 1e-3, 1000.0)])
def test_peak_pressure_is_the_maximum_of_the_field(load, speed, ratio):
    sol = analytic.solve(load=load, speed=speed, ratio=ratio)
    p = sol.patches[0]
    X = np.linspace(p.trailing_edge, p.leading_edge, 2001)
    field = sol.fields(X).pressure
    assert field.max() <= sol.max_pressure * (1 + ROUNDOFF)
    assert field.max() >= sol.max_pressure * (1 - 1e-5)      # grid of 2000 points
    h = 1e-4 * p.width
    near = sol.fields(sol.x_max_pressure + np.array([-h, h])).pressure
    assert np.all(near <= sol.max_pressure * (1 + ROUNDOFF))


def test_peak_pressure_in_the_limits():
    sol = analytic.solve(load=0.2, speed=0.0)
    assert sol.max_pressure == pytest.approx(westergaard.pressure(0.0, 0.2, 1.0), rel=ROUNDOFF)
    assert sol.x_max_pressure == 0.0
    for speed in (1e-12, 1e12):
        m = 1.0 if speed < 1 else 3.0
        sol = analytic.solve(load=0.2 * m, speed=speed)
        assert sol.max_pressure == pytest.approx(westergaard.pressure(0.0, 0.2 * m, 1.0, m), rel=1e-9)
        assert abs(sol.x_max_pressure) < 1e-8
    full = analytic.solve(load=2.0, speed=1.0)
    mag, delta = analytic.modulus(1.0, 3.0)
    assert full.max_pressure == 2.0 + 0.5 * mag and full.x_max_pressure == delta / (2 * math.pi)


@pytest.mark.parametrize("kw", [dict(load=0.3, speed=1.0), dict(load=1.2, speed=3.0),
                                dict(load=2.0, speed=1.0)])
def test_patch_matches_the_scalars(kw):
    sol = analytic.solve(**kw)
    (p,) = sol.patches
    assert p.leading_edge > p.trailing_edge and p.load == sol.load and p.summit == 0.0
    assert p.ka == sol.ka and p.ke == sol.ke and p.ke_hat == sol.ke_hat
    assert p.ka == pytest.approx(math.pi * p.width, rel=ROUNDOFF)
    assert p.ke_hat == pytest.approx(2 * math.pi * (p.centroid - p.summit), rel=ROUNDOFF)
    if sol.full_contact:
        assert (p.trailing_edge, p.leading_edge, p.width, p.ke) == (-0.5, 0.5, 1.0, None)
    else:
        centre = 0.5 * (p.trailing_edge + p.leading_edge)
        assert p.ke == pytest.approx(2 * math.pi * (centre - p.summit), rel=ROUNDOFF)


def test_sweep_is_a_table_loads_outer_speeds_inner():
    t = analytic.sweep(load=[0.2, 0.8], speed=[0.1, 1.0, 10.0])
    assert list(t["load"]) == [0.2] * 3 + [0.8] * 3
    assert list(t["speed"]) == [0.1, 1.0, 10.0] * 2
    assert t["success"].all() and list(t["n_patches"]) == [1] * 6
    for i in range(6):
        sol = analytic.solve(load=t["load"][i], speed=t["speed"][i])
        for key in ("ka", "ke_hat", "penetration", "tau_f", "mu", "max_pressure"):
            assert t[key][i] == getattr(sol, key)
        assert t["full_contact"][i] == sol.full_contact
    assert np.isnan(t["ke"][5]) == analytic.solve(load=0.8, speed=10.0).full_contact
    tp = analytic.sweep(penetration=[0.5, 1.0], speed=[1.0], ratio=10.0, hk=0.5)
    assert tp["success"].all() and list(tp["penetration_asked"]) == [0.5, 1.0]


def test_sweep_refuses_bad_input_before_solving():
    with pytest.raises(ValueError, match="^speed="):
        analytic.sweep(load=[0.3], speed=[1.0, 1e300])
    with pytest.raises(ValueError, match="^ratio="):
        analytic.sweep(load=[0.3], speed=[1.0], ratio=1.0)


BASE = dict(E0=5e6, Einf=15e6, tau_creep=2e-3, nu=0.45, wavelength=1e-3, amplitude=1.5e-4, speed=0.05)


def test_solve_si_returns_an_si_result_with_the_transition():
    r = analytic.solve_si(**BASE, mean_pressure=1e6)
    assert isinstance(r, SIResult) and r.success and isinstance(r.solution, analytic.Solution)
    k = 2 * math.pi / BASE["wavelength"]
    estar = BASE["E0"] / (1 - BASE["nu"] ** 2)
    w = BASE["speed"] * BASE["tau_creep"] * k
    hk = BASE["amplitude"] * k
    assert r.full_contact_pressure == pytest.approx(analytic.transition_load(w, 3.0, hk) * estar,
                                                    rel=ROUNDOFF)
    vth = analytic.threshold_speed(1e6 / estar, 3.0, hk) / (BASE["tau_creep"] * k)
    assert r.threshold_speed == pytest.approx(vth, rel=ROUNDOFF) or r.threshold_speed == vth
    assert r.max_pressure == pytest.approx(r.solution.max_pressure * estar, rel=ROUNDOFF)
    f = r.fields()
    assert f.units == "SI" and f.x_over_lambda.size == 1024


@pytest.mark.parametrize("kw,name", [
    (dict(mean_pressure=1e-40), "mean_pressure"),     # load below the accepted range
    (dict(mean_pressure=1e6, amplitude=1e4), "amplitude"),   # hk above it
    (dict(mean_pressure=1e6, speed=1e40), "speed"),
    (dict(mean_pressure=1e6, Einf=5e6 * (1 + 1e9)), "Einf"),
])
def test_solve_si_names_the_si_input_behind_an_out_of_range_group(kw, name):
    args = {**BASE, **kw}
    with pytest.raises(ValueError, match=f"^{name}=.* is not allowed: one giving .*: it gives"):
        analytic.solve_si(**args)
