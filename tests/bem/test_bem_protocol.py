"""The BEM road's public shape: the result protocol (shared with the semi-analytic road), its
accepted inputs, the validity gate, sweep and solve_si, and its input files.

Small meshes (N ≤ 1024) throughout; Hypothesis derandomized with a bounded example count.
"""
import json
import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import analytic
import bem
from bem import _assemble
from bem._accepted import (HK_MAX, HK_MIN, LOAD_OVER_AMPLITUDE, PENETRATION_MIN, RATIO_EPS,
                           RATIO_MAX, SPEED_MAX, SPEED_MIN)
from viscosine import Fields
from viscosine.protocol import SCALAR_KEYS

N = 512
TWO_HARMONICS = bem.Harmonics([1.0, 0.0, 0.0, 0.6], [0.0, 0.0, 0.0, 0.0])


# ------------------------------------------------------------------------------ protocol
def test_record_has_the_analytic_keys_and_round_trips():
    r = bem.solve(load=0.3, speed=1.0, nodes=N)
    a = analytic.solve(load=0.3, speed=1.0)
    rec = r.as_dict()
    back = json.loads(json.dumps(rec, allow_nan=False))
    assert back == rec
    common = set(a.as_dict())
    assert common <= set(rec) and set(rec) - common <= {"nodes", "rtol"}
    assert "rtol" not in rec  # the mesh was fixed
    assert rec["solver"] == "bem" and rec["control"] == "load" and rec["load_asked"] == 0.3
    assert rec["penetration_asked"] is None and rec["ratio"] == 3.0 and rec["hk"] == 1.0
    assert set(r.scalars()) == set(SCALAR_KEYS)
    assert rec["n_patches"] == 1 and set(rec["patches"][0]) == set(a.as_dict()["patches"][0]) | {"panels"}
    assert rec["patches"][0]["summit"] == 0.0
    d = rec["diagnostics"]
    assert {"nit", "inner_iterations", "residuals", "levels", "memory_layer_panels"} <= set(d)
    assert set(rec["error_estimate"]) == {"contact_fraction", "ka", "ke", "ke_hat",
                                          "penetration", "tau_f", "mu"}
    assert all(v > 0 for v in rec["error_estimate"].values()) and isinstance(rec["warnings"], list)
    # the two roads agree on what the keys mean (a coarse mesh: a loose bound)
    assert abs(r.ka - a.ka) < 2e-2 and abs(r.ke - a.ke) < 2e-2 and abs(r.mu / a.mu - 1) < 2e-2


def test_ratio_as_given_and_none_for_prony_and_profiles():
    r = bem.solve(load=0.3, speed=1.0, ratio=3.0, nodes=64)
    assert r.as_dict()["ratio"] == 3.0  # not 3.000000000000001 recomputed from the compliances
    p = bem.solve(load=0.3, speed=1.0, material=bem.Prony(1.0, (0.5,), (1.0,)),
                  profile=TWO_HARMONICS, nodes=64)
    assert p.as_dict()["ratio"] is None and p.as_dict()["hk"] is None


def test_penetration_control_record():
    r = bem.solve(penetration=0.5, speed=1.0, nodes=N)
    rec = r.as_dict()
    assert rec["control"] == "penetration" and rec["penetration_asked"] == 0.5
    assert rec["load_asked"] is None and rec["load"] == pytest.approx(float(r.pressure.mean()))


def test_full_contact_has_one_patch_spanning_the_period():
    r = bem.solve(load=2.0, speed=1.0, nodes=N)
    assert r.full_contact and r.penetration == 1.0 and r.separation == 0.0
    (p,) = r.patches
    assert (p.trailing_edge, p.leading_edge, p.width, p.ka, p.ke) == (-0.5, 0.5, 1.0, math.pi, None)
    assert p.ke_hat == r.ke_hat and p.load == r.load and r.ka == math.pi
    a = analytic.solve(load=2.0, speed=1.0)
    assert r.ke_hat == pytest.approx(a.ke_hat, abs=1e-6)  # collocation error of N = 512


def test_fields_are_viscosine_fields():
    r = bem.solve(load=0.3, speed=1.0, nodes=N)
    f = r.fields()
    assert isinstance(f, Fields) and f.x_over_lambda.size == N
    assert np.array_equal(f.pressure, r.pressure) and np.array_equal(f.gap, r.gap)
    # elsewhere: periodic linear interpolation, σ ≥ 0 and gap ≥ 0 kept
    x = np.array([-0.5, 0.001, 0.7, 3.25])
    g = r.fields(x)
    assert np.array_equal(g.x_over_lambda, x)
    assert g.pressure[0] == r.pressure[0] and g.gap[2] == pytest.approx(r.fields([-0.3]).gap[0])
    assert np.all(g.pressure >= 0) and np.all(g.gap >= 0)
    assert r.max_pressure == r.pressure.max()
    assert r.x_max_pressure == r.x_over_lambda[np.argmax(r.pressure)]
    with pytest.raises(ValueError, match="x_over_lambda"):
        r.fields([[0.0]])


def test_two_patches():
    """k y = 0.3 cos 2πX + cos 4πX: summits at X = 0 (1.3) and X = ½ (0.7), one patch each."""
    r = bem.solve(load=0.2, speed=0.5, profile=bem.Harmonics([0.3, 1.0], [0.0, 0.0]), nodes=1024)
    assert r.success and r.n_patches == 2 and not r.full_contact
    assert r.ka is None and r.ke is None and r.ke_hat is None
    rec = r.as_dict()
    assert rec["ka"] is None and rec["n_patches"] == 2 and len(rec["patches"]) == 2
    assert sum(p.load for p in r.patches) == pytest.approx(r.load, rel=1e-12)
    assert r.contact_fraction == pytest.approx(sum(p.width for p in r.patches), rel=1e-14)
    summits = sorted(abs(p.summit) for p in r.patches)
    assert summits == pytest.approx([0.0, 0.5], abs=1e-12)
    for p in r.patches:
        assert p.ke == pytest.approx(math.pi * (p.trailing_edge + p.leading_edge)
                                     - 2 * math.pi * p.summit, abs=1e-15)


# ------------------------------------------------------------------------------ odd inputs
ODD = [
    (dict(load=1e-320), "load=1e-320"),
    (dict(load=1e308), "load=1e+308"),
    (dict(load=1e-9), "load=1e-09"),
    (dict(load=0.3, ratio=1e308), "ratio=1e+308"),
    (dict(load=0.3, ratio=1 + 1e-16), "ratio=1.0"),
    (dict(load=0.3, ratio=1 + 1e-13), "ratio="),
    (dict(load=0.3, ratio=1e9), "ratio=1000000000.0"),
    (dict(load=0.3, hk=1e308), "hk=1e+308"),
    (dict(load=0.3, speed=1e308), "speed=1e+308"),
    (dict(load=0.3, speed=1e-40), "speed=1e-40"),
    (dict(penetration=1e-12), "penetration=1e-12"),
    (dict(load=0.3, nodes=2 ** 40), "nodes=1099511627776"),
    (dict(load=0.3, nodes=4), "nodes=4"),
    (dict(load=0.3, material=bem.Prony(1.0, (0.5,), (1e-320,))), "material="),
    (dict(load=0.3, material=bem.Prony(1.0, (0.5,), (1e300,))), "material="),
    (dict(load=0.3, material=bem.Prony(1.0, (1e-14,), (1.0,))), "material="),
    (dict(load=0.3, material=bem.Prony(1.0, (1.0 - 1e-9,), (1.0,))), "material="),
    (dict(load=0.3, material=bem.Prony(1e-300, (5e-301,), (1.0,))), "material="),
    (dict(load=0.3, profile=bem.Harmonics([1e-9], [0.0])), "profile="),
]


@pytest.mark.parametrize("kw, name", ODD)
def test_odd_inputs_are_refused_naming_the_parameter(kw, name):
    kw = {"speed": 1.0, **kw}
    with pytest.raises(ValueError, match="is not allowed") as info:
        bem.solve(nodes=kw.pop("nodes", 64), **kw)
    assert str(info.value).startswith(name)


def test_validate_and_accepted():
    assert set(bem.ACCEPTED) >= {"load", "penetration", "speed", "ratio", "hk", "nodes",
                                 "rtol", "max_nodes", "material", "profile"}
    assert all(isinstance(v[2], str) and v[2] for v in bem.ACCEPTED.values())
    assert bem.MAX_NODES & (bem.MAX_NODES - 1) == 0 and 2 ** 16 <= bem.MAX_NODES <= 2 ** 24
    assert bem.ACCEPTED["nodes"][1] == bem.MAX_NODES
    assert bem.validate(load=1e-8, speed=0.0, nodes=8) == {"load": 1e-8, "speed": 0.0, "nodes": 8}
    for kw, name in [(dict(rtol=1e-12), "rtol="), (dict(rtol=0.1), "rtol="),
                     (dict(max_nodes=3000), "max_nodes=3000"),
                     (dict(max_nodes=2 * bem.MAX_NODES), "max_nodes="),
                     (dict(load=1e-3, hk=1e6), "load=0.001"),  # p̃∞/hk below the range
                     (dict(hk=1.0, profile=TWO_HARMONICS), "hk="),
                     (dict(ratio=3.0, material=bem.Prony(1.0)), "ratio=")]:
        with pytest.raises(ValueError, match="is not allowed") as info:
            bem.validate(**kw)
        assert str(info.value).startswith(name), info.value
    # the elastic Prony series (no term) is accepted; a viscoelastic one needs E∞/E0 > 1 + ε
    bem.validate(material=bem.Prony(2.0))
    bem.validate(ratio=1 + 2 * RATIO_EPS)


@pytest.mark.parametrize("kw", [dict(penetration=PENETRATION_MIN),
                                dict(load=0.3, speed=SPEED_MIN), dict(load=0.3, speed=SPEED_MAX),
                                dict(load=0.3, ratio=RATIO_MAX, speed=1e-3),
                                dict(load=HK_MIN * 0.3, hk=HK_MIN), dict(load=HK_MAX * 0.3, hk=HK_MAX),
                                dict(load=LOAD_OVER_AMPLITUDE[1]),
                                dict(load=0.3, material=bem.Prony(1.0, (0.5, 0.4), (1e-6, 1e6)))])
def test_extremes_inside_are_solved(kw):
    r = bem.solve(speed=kw.pop("speed", 1.0), nodes=1024, **kw)
    assert r.success, r.message
    assert json.loads(json.dumps(r.as_dict(), allow_nan=False))["success"]


def test_every_status_has_its_meaning():
    """bem.MESSAGES names every status a result can carry; success is status 0 alone."""
    assert sorted(bem.MESSAGES) == list(range(6)) and bem.MESSAGES[0] == "converged"
    ok = bem.solve(load=0.3, speed=1.0, nodes=256)
    capped = bem.solve(load=0.3, speed=0.1, max_nodes=1024)
    exhausted = bem.solve(load=0.3, speed=1.0, nodes=1024, max_outer=1)
    for r, status in ((ok, 0), (capped, 5), (exhausted, 1)):
        assert r.status == status and r.success == (status == 0), r.message
        assert r.status in bem.MESSAGES


# ------------------------------------------------------------------------------ validity gate
def test_broken_state_is_not_a_success(monkeypatch):
    real = _assemble._friction
    monkeypatch.setattr(_assemble, "_friction", lambda *a: (-abs(real(*a)[0]) - 1.0, 0.0))
    r = bem.solve(load=0.3, speed=1.0, nodes=64)
    assert not r.success and r.status == _assemble.STATUS_INVALID
    assert bem.MESSAGES[r.status] == "converged, but the answer failed the validity gate"
    assert "tau_f" in r.message and "invalid result" in r.message
    assert r.as_dict()["success"] is False and r.as_dict()["patches"] == []
    monkeypatch.setattr(_assemble, "_friction", lambda *a: (math.nan, 0.0))
    r = bem.solve(load=0.3, speed=1.0, nodes=64)
    assert not r.success and "not finite" in r.message
    assert json.dumps(r.as_dict(), allow_nan=False)


def test_gate_catches_load_and_sign_violations():
    class G:  # a two-panel-free state with a negative pressure and a wrong load
        n, h = 16, 1 / 16
        nodes, window, s_offset, scale = 16, False, 0.0, 1.0  # a periodic grid (h k = 1)
        layer = None  # on the half-space
        x = np.arange(16) / 16 - 0.5
        y = np.cos(2 * np.pi * x)

        class op:
            @staticmethod
            def apply(s):
                return np.zeros_like(s)

    sigma = np.where(np.abs(G.x) < 0.2, 1.0, 0.0)
    sigma[8] = -0.5
    active = sigma != 0
    res = {"sigma": sigma, "s": 0.3, "active": active, "gap": np.where(active, 0.0, 0.1),
           "nit": 1, "inner": [1], "relres": 0.0, "status": 0, "message": "converged"}
    r = _assemble.build_result(res, G, bem.Sinusoid(1.0), bem.Prony(1.0), 0.0, 1.0, 0.3,
                               [(16, 1, (1,))], asked=0.3, control="load")
    assert not r.success and "negative pressure" in r.message and "asked for" in r.message


def test_error_estimate_and_rtol_are_carried(monkeypatch):
    real = _assemble.build_result
    est = {"contact_fraction": 1e-5, "ka": 2e-5, "ke": None, "ke_hat": 1e-5, "penetration": 1e-6,
           "tau_f": 1e-4, "mu": 1e-4}

    def spy(*a, **kw):
        return real(*a, **dict(kw, error_estimate=est, rtol=1e-6, extra_diagnostics={"x": 1}))

    import bem._solver as solver
    monkeypatch.setattr(solver, "build_result", spy)
    r = bem.solve(load=0.3, speed=1.0, nodes=64)
    rec = r.as_dict()
    assert rec["error_estimate"] == est and rec["rtol"] == 1e-6 and rec["diagnostics"]["x"] == 1
    t = bem.sweep(load=[0.3], speed=[1.0], nodes=64, errors=True)
    assert t["error_ka"][0] == 2e-5 and math.isnan(t["error_ke"][0])


# ------------------------------------------------------------------------------ sweep, SI
def test_sweep_equals_individual_solves():
    loads, speeds = [0.2, 1.2], [0.0, 1.0]
    t = bem.sweep(load=loads, speed=speeds, nodes=256)
    i = 0
    for p in loads:
        for v in speeds:
            r = bem.solve(load=p, speed=v, nodes=256)
            assert t["success"][i] == r.success and t["nodes"][i] == 256
            for k in ("ka", "penetration", "tau_f", "mu", "contact_fraction", "max_pressure"):
                assert t[k][i] == getattr(r, k), k
            i += 1
    with pytest.raises(ValueError, match="speed=1e\\+308"):
        bem.sweep(load=loads, speed=[1.0, 1e308], nodes=256)


def test_solve_si_is_invariant_under_a_change_of_units():
    base = dict(E0=1e6, Einf=3e6, tau_creep=0.01, nu=0.5, wavelength=1e-3, amplitude=1e-4,
                speed=0.05, mean_pressure=2e4)
    a = bem.solve_si(**base, nodes=512)
    # lengths ×10, moduli ×7, times ×3: the same dimensionless problem
    b = bem.solve_si(E0=7e6, Einf=21e6, tau_creep=0.03, nu=0.5, wavelength=1e-2, amplitude=1e-3,
                     speed=0.05 * 10 / 3, mean_pressure=7 * 2e4, nodes=512)
    assert a.success and b.success
    for k in SCALAR_KEYS:
        va, vb = a.solution.scalars()[k], b.solution.scalars()[k]
        assert va == pytest.approx(vb, rel=1e-9, abs=1e-12), k
    assert b.contact_halfwidth == pytest.approx(10 * a.contact_halfwidth, rel=1e-9)
    assert b.friction_stress == pytest.approx(7 * a.friction_stress, rel=1e-9)
    assert a.threshold_speed is None
    pfc = analytic.solve_si(**base).full_contact_pressure
    assert a.full_contact_pressure == pytest.approx(pfc, rel=1e-12)
    f = a.fields([0.0, 2.5e-4])
    assert f.units == "SI" and f.pressure[0] > 0
    with pytest.raises(ValueError, match="^speed=1e\\+300"):
        bem.solve_si(**dict(base, speed=1e300), nodes=512)


# ------------------------------------------------------------------------------ files
@pytest.mark.parametrize("reader, content, word", [
    (reader, content, word) for reader in (bem.read_profile, bem.read_prony)
    for content, word in [(b"", "empty"), (b"# only a comment\n", "empty"),
                          (b"J0 1\x00\x01\n", "binary"), (b"J0 \xff\xfe1\n", "UTF-8")]]
    + [(bem.read_prony, b"J0 nan\n", "finite"), (bem.read_prony, b"J0 1\n0.5 inf\n", "finite"),
       (bem.read_profile, b"1\n2\n3\n4\n5\n6\n7\n-inf\n", "finite")])
def test_files_refused_naming_the_file(tmp_path, reader, content, word):
    path = tmp_path / "input.txt"
    path.write_bytes(content)
    with pytest.raises(ValueError, match=word) as info:
        reader(path)
    assert "input.txt" in str(info.value)


def test_utf8_files_are_read(tmp_path):
    path = tmp_path / "prony.txt"
    path.write_text("# matériau: E∞/E0 = 3\nJ0 1.0\n0.6666666666666666 1.0\n", encoding="utf-8")
    assert bem.read_prony(path) == bem.Prony(1.0, (0.6666666666666666,), (1.0,))
    prof = tmp_path / "profile.csv"
    prof.write_text("x_over_lambda,ky  # hauteur\n" + "".join(
        f"{j / 16 - 0.5!r},{math.cos(2 * math.pi * (j / 16 - 0.5))!r}\n" for j in range(16)),
        encoding="utf-8")
    assert bem.read_profile(prof).heights.size == 16
    prof.write_text("x_over_lambda,ky\n" + "".join(
        f"{j / 16 - 0.5!r},nan\n" for j in range(16)), encoding="utf-8")
    with pytest.raises(ValueError, match="profile=.*profile.csv.*finite"):
        bem.read_profile(prof)


# ------------------------------------------------------------------------------ properties
def _log_uniform(lo, hi):
    inner = st.floats(math.log10(lo), math.log10(hi)).map(lambda e: min(max(10.0 ** e, lo), hi))
    return st.one_of(st.sampled_from([lo, hi]), inner, inner)


@settings(max_examples=40, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(over=_log_uniform(*LOAD_OVER_AMPLITUDE), pen=_log_uniform(PENETRATION_MIN, 1.0),
       by_load=st.booleans(), speed=st.one_of(st.just(0.0), _log_uniform(SPEED_MIN, SPEED_MAX)),
       ratio=_log_uniform(1 + 2 * RATIO_EPS, RATIO_MAX), hk=_log_uniform(HK_MIN, HK_MAX))
def test_accepted_inputs_give_an_answer_or_a_clean_failure(over, pen, by_load, speed, ratio, hk):
    control = {"load": over * hk} if by_load else {"penetration": pen}
    try:
        r = bem.solve(**control, speed=speed, ratio=ratio, hk=hk, nodes=N)
    except ValueError as exc:  # only a refusal naming a parameter
        assert "is not allowed" in str(exc)
        return
    rec = json.loads(json.dumps(r.as_dict(), allow_nan=False))
    if not r.success:
        assert r.message and rec["success"] is False
        return
    several = r.n_patches > 1  # then ka is None (no single patch describes the contact)
    assert 0.0 < r.penetration <= 1.0 and r.mu >= 0.0
    assert (r.ka is None) if several else 0.0 < r.ka <= math.pi
    assert 0.0 < r.contact_fraction <= 1.0 and np.all(r.pressure >= 0) and np.all(r.gap >= 0)
    assert abs(r.load / control["load"] - 1) <= 1e-8 if by_load else r.penetration == pytest.approx(pen, rel=1e-6)
