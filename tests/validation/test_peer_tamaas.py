"""Tamaas as a third code (comparisons.peers.tamaas): limits, exact full contact, dt order, and
the Richardson-extrapolated friction against the semi-analytic road.

Tolerances are discretisation errors measured with this adapter and Tamaas 2.9.0 (each written
next to its measurement); the full-contact test is exact (Tamaas's backward Euler has a closed
form for a single Fourier mode).  Runtime: about half a minute on two loaded cores.
"""
from __future__ import annotations

import cmath
import json
import math
import sys

import numpy as np
import pytest

tamaas = pytest.importorskip("tamaas", minversion="2.9")  # the test extra installs it

import analytic  # noqa: E402
from comparisons.peers import tamaas as peer  # noqa: E402
from viscosine import Fields  # noqa: E402

from conftest import ROUNDOFF  # noqa: E402


def westergaard(load, hk, modulus):
    """Elastic periodic contact (eq. 3.1, Appendix A): ka and Δ/h for E = modulus·E0."""
    s = load / (modulus * hk / 2.0)
    return 2.0 * math.asin(math.sqrt(s)), s * (1.0 - math.log(s))


def westergaard_pressure(x, load, hk, modulus):
    """σ(1 − ν²)/E0 of Westergaard's solution at x/λ (crest at 0)."""
    ka, _ = westergaard(load, hk, modulus)
    th = 2.0 * math.pi * np.asarray(x)
    r2 = math.sin(0.5 * ka) ** 2 - np.sin(0.5 * th) ** 2
    return modulus * hk * np.cos(0.5 * th) * np.sqrt(np.maximum(r2, 0.0))


# ----------------------------------------------------------------------------- limits
N_LIMIT = 256


@pytest.fixture(scope="module", params=[("relaxed", 1e-8, 1.0), ("glassy", 1e8, 3.0)],
                ids=lambda p: p[0])
def limit(request):
    name, speed, modulus = request.param
    return peer.solve(load=0.15, speed=speed, ratio=3.0, hk=1.0, nodes=N_LIMIT), modulus


def test_limits_are_westergaard(limit):
    """V/V0 = 1e-8 and 1e8: Westergaard with E0 and with E∞ = 3 E0.

    Measured at N = 256 (p̃∞ = 0.05–0.3): contact width within 0.11 cell of Westergaard's
    (edges from gap^(2/3)), Δ/h within 6.1e-5 relative; ke, kê and μ are the O(V/V0) or
    O(V0/V) viscoelastic corrections (measured at most 6.6e-9, bounded by 10·1e-8).
    """
    r, modulus = limit
    assert r.success, r.message
    ka, pen = westergaard(0.15, 1.0, modulus)
    assert not r.full_contact and r.n_patches == 1
    assert abs(r.ka - ka) <= math.pi * 0.25 / N_LIMIT          # a quarter cell of width
    assert abs(r.penetration / pen - 1.0) <= 2e-4
    assert abs(r.contact_fraction - ka / math.pi) <= 0.25 / N_LIMIT
    for key in ("ke", "ke_hat", "mu"):
        assert abs(getattr(r, key)) <= 1e-7, key
    # relaxed: steady at once (dt = T/N ≫ τ); glassy: the transient is O(T/τ) ~ 1e-8
    assert r.diagnostics["periods"] == 2


def test_limit_fields(limit):
    """The pressure field is Westergaard's; constraints hold; crest frame and signs.

    Measured at N = 256: largest nodal pressure error 1.3 % (relaxed) and 2.0 % (glassy) of
    the peak, at the node next to an edge (σ ~ √distance is resolved to O(√Δx) there); 2.3e-5
    and 8.6e-5 over the middle half of the contact.  Complementarity and the contact
    displacement hold to 2e-10 (Tamaas's tolerance 1e-10).
    """
    r, modulus = limit
    f = r.fields()
    assert isinstance(f, Fields) and f.x_over_lambda.size == N_LIMIT
    assert f.x_over_lambda[0] == -0.5 and f.x_over_lambda[N_LIMIT // 2] == 0.0
    exact = westergaard_pressure(f.x_over_lambda, 0.15, 1.0, modulus)
    peak = exact.max()
    assert np.max(np.abs(f.pressure - exact)) <= 0.04 * peak
    a = r.ka / (2.0 * math.pi)
    core = np.abs(f.x_over_lambda) <= 0.5 * a
    assert np.max(np.abs(f.pressure - exact)[core]) <= 2e-4 * peak
    assert abs(np.mean(f.pressure) - 0.15) <= ROUNDOFF              # the load, Tamaas's target
    assert abs(np.mean(f.displacement)) <= ROUNDOFF                  # from the deformed mean line
    assert np.all(f.pressure >= 0.0) and np.all(f.gap >= 0.0)
    assert np.all(f.gap[f.pressure > 0.0] == 0.0)
    # in contact the surface follows the indenter: v/h = cos(kx) − s/h
    inside = f.pressure > 0.0
    np.testing.assert_allclose(f.displacement[inside],
                               np.cos(2 * np.pi * f.x_over_lambda[inside]) - r.separation,
                               atol=1e-9)
    assert r.diagnostics["complementarity"] <= 1e-8
    assert abs(r.x_max_pressure) <= 1.0 / N_LIMIT


# ----------------------------------------------------------------------------- exact
@pytest.mark.parametrize("speed", [0.3, 1.0, 3.0])
@pytest.mark.parametrize("cells", [1.0, 0.5])
def test_full_contact_is_backward_euler_exactly(speed, cells):
    """In full contact the pressure is one Fourier mode, and Tamaas's backward Euler with
    relaxation time τ/ratio and branch modulus (ratio − 1)G∞ has the closed form
    E/E0 = 1 + (ρ − 1) r(z − 1)/(z − r), r = τ_R/(τ_R + dt), z = exp(i kV dt).  μ and kê must
    equal it to the solver and steadiness tolerances (measured: 4e-11 relative at V/V0 = 3);
    it tends to Appendix B as dt → 0.  A creep time passed as a relaxation time, G∞ ≠ 1 or a
    sign slip in τf or kê would show here at the percent level."""
    load, ratio, hk, n = 1.6, 3.0, 1.0, 64     # above (p̃FC)∞ = 1.5: full at any speed
    t_cell = 2.0 * math.pi / (speed * n)
    r = peer.solve(load=load, speed=speed, ratio=ratio, hk=hk, nodes=n, dt=cells * t_cell)
    assert r.success, r.message
    assert r.dt == pytest.approx(cells * t_cell, rel=ROUNDOFF)
    tr = 1.0 / ratio
    q = tr / (tr + r.dt)
    z = cmath.exp(1j * speed * r.dt)
    e = 1.0 + (ratio - 1.0) * q * (z - 1.0) / (z - q)
    delta = cmath.phase(e)
    assert r.full_contact and r.ka == math.pi and r.ke is None
    assert r.contact_fraction == 1.0 and r.penetration == pytest.approx(1.0, abs=1e-12)
    assert r.mu == pytest.approx(hk * hk * abs(e) * math.sin(delta) / (4.0 * load), rel=1e-9)
    assert r.ke_hat == pytest.approx(delta, rel=1e-9)
    # the first-order error against Appendix B (the semi-analytic road): one-signed, halving
    # with dt (measured 1.1 %, 3.0 %, 4.8 % at one cell per step and V/V0 = 0.3, 1, 3)
    a = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
    assert 0.0 < 1.0 - r.mu / a.mu <= 0.06 * cells


# ----------------------------------------------------------------------------- dt order
N_STUDY = 256


@pytest.fixture(scope="module")
def peak_study():
    speed, _ = peer.friction_peak(load=0.15, ratio=3.0, hk=1.0)
    t_cell = 2.0 * math.pi / (speed * N_STUDY)
    study = peer.dt_study(load=0.15, speed=speed, ratio=3.0, hk=1.0, nodes=N_STUDY,
                          dts=[4 * t_cell, 2 * t_cell, t_cell])
    return speed, study


def test_friction_peak_on_the_analytic_road(peak_study):
    speed, _ = peak_study
    assert 0.9 < speed < 1.2   # measured 1.0585 at p̃∞ = 0.15, E∞/E0 = 3, hk = 1
    mu = analytic.solve(load=0.15, speed=speed).mu
    for f in (0.9, 1.1):
        assert analytic.solve(load=0.15, speed=f * speed).mu < mu


def test_dt_order_is_first(peak_study):
    """Backward Euler: first order in dt.  Measured at N = 256 and 512 with 4, 2, 1 cell
    crossings per step: orders 0.97–1.04 for μ at V/V0 = 0.35, 1.06, 3.2."""
    _, st = peak_study
    assert st["success"]
    mus = [r["mu"] for r in st["rows"]]
    assert mus[0] < mus[1] < mus[2]              # μ rises as dt falls (the lag shrinks)
    assert 0.9 <= st["order"]["mu"] <= 1.1
    assert 0.8 <= st["order"]["penetration"] <= 1.2  # measured 0.90 at the peak, N = 256


def test_richardson_mu_matches_the_analytic_road(peak_study):
    """Richardson μ (two finest steps, first order) at the friction peak against the
    semi-analytic road.  Measured at N = 256: −0.042 % (−0.002 % at N = 512); the estimated
    dt error 6.5e-5 is the smaller part, the rest is the grid (N/2 moves it by 5.5e-5)."""
    speed, st = peak_study
    a = analytic.solve(load=0.15, speed=speed, ratio=3.0, hk=1.0)
    assert abs(st["richardson"]["mu"] / a.mu - 1.0) <= 1e-3
    # the coarse steps alone are off by 1.7–6.7 %: the extrapolation is what agrees
    assert abs(st["rows"][0]["mu"] / a.mu - 1.0) > 0.01
    assert abs(st["richardson"]["penetration"] / a.penetration - 1.0) <= 5e-4  # measured 1.1e-4
    assert abs(st["richardson"]["ke_hat"] - a.ke_hat) <= 1e-3                 # measured 1e-4


# ----------------------------------------------------------------------------- invariance
def test_poisson_ratio_drops_out(monkeypatch):
    """ν only scales Tamaas's E* = 2G∞/(1 − ν) with G∞ = 1: every output is unchanged (measured
    to 4e-16; bounded by Tamaas's tolerance 1e-10, in case its iterations take another path)."""
    ref = peer.solve(load=0.15, speed=1.0, nodes=64)
    nu = 0.3
    from comparisons.peers import _tamaas_solve as model  # where Tamaas's model is set up
    monkeypatch.setattr(model, "_NU", nu)
    monkeypatch.setattr(model, "_E_TAMAAS", 2.0 * (1.0 + nu))
    monkeypatch.setattr(model, "_ESTAR0", 2.0 * (1.0 + nu) / (1.0 - nu * nu))
    r = peer.solve(load=0.15, speed=1.0, nodes=64)
    for key, value in ref.scalars().items():
        assert getattr(r, key) == pytest.approx(value, rel=1e-10, abs=ROUNDOFF), key


def test_amplitude_scaling():
    """The problem is linear in h at fixed p̃∞/hk: ka, Δ/h, kê and v/h are unchanged, σ and μ
    scale with hk (measured to 9e-16; bounded by Tamaas's tolerance 1e-10)."""
    a = peer.solve(load=0.15, speed=1.0, hk=1.0, nodes=64)
    b = peer.solve(load=0.015, speed=1.0, hk=0.1, nodes=64)
    for key in ("ka", "ke", "ke_hat", "penetration", "contact_fraction"):
        assert getattr(b, key) == pytest.approx(getattr(a, key), rel=1e-10), key
    assert b.mu == pytest.approx(0.1 * a.mu, rel=1e-10)
    np.testing.assert_allclose(b.fields().pressure, 0.1 * a.fields().pressure,
                               atol=1e-10 * a.max_pressure)
    np.testing.assert_allclose(b.fields().displacement, a.fields().displacement, atol=1e-10)


# ----------------------------------------------------------------------------- protocol
def test_result_protocol_and_json():
    r = peer.solve(load=0.15, speed=1.0, nodes=64)
    assert r.success and r.status == 0
    sc = r.scalars()
    assert set(sc) == set(peer.SCALAR_KEYS)
    assert all(type(v) in (bool, float) for v in sc.values())
    rec = json.loads(json.dumps(r.as_dict(), allow_nan=False))
    assert rec["solver"] == "tamaas" and rec["mu"] == sc["mu"] and rec["n_patches"] == 1
    d = rec["diagnostics"]
    assert d["steps"] == d["periods"] * 64 and d["dt_over_period"] == pytest.approx(1 / 64)
    assert d["dt_over_tau"] == pytest.approx(2 * math.pi / 64)
    p = r.patches[0]
    assert p.trailing_edge < 0.0 < p.leading_edge and p.ka == r.ka and p.ke == r.ke
    f = r.fields([0.0, 0.5 / 64])
    assert f.pressure[1] == pytest.approx(0.5 * (r.fields().pressure[32] + r.fields().pressure[33]))


def test_dt_is_snapped_and_said():
    t_cell = 2 * math.pi / (1.0 * 64)
    r = peer.solve(load=0.15, speed=1.0, nodes=64, dt=2.7 * t_cell)  # nearest divisor (log): 2
    assert r.dt == pytest.approx(2 * t_cell) and r.diagnostics["cells_per_step"] == 2
    assert any("snapped" in w for w in r.warnings)
    r = peer.solve(load=0.15, speed=1.0, nodes=64, dt=0.3 * t_cell)  # 1/3 cell per step
    assert r.diagnostics["steps_per_cell"] == 3
    with pytest.raises(ValueError, match="distinct after snapping"):
        peer.dt_study(load=0.15, speed=1.0, nodes=64, dts=[1.0 * t_cell, 1.1 * t_cell])


def test_unsteady_run_is_not_an_answer():
    r = peer.solve(load=0.15, speed=30.0, nodes=32, max_periods=2)
    assert not r.success and r.status == 1
    assert "not steady" in r.message and "max_periods" in r.message


def test_log_level_is_restored():
    before = tamaas.get_log_level()
    peer.solve(load=0.15, speed=1.0, nodes=32)
    assert tamaas.get_log_level() == before


@pytest.mark.parametrize("kwargs, name", [
    ({"load": -1.0}, "load"), ({"load": "x"}, "load"), ({"load": True}, "load"),
    ({"speed": 0.0}, "speed"), ({"speed": math.inf}, "speed"), ({"ratio": 1.0}, "ratio"),
    ({"hk": 0.0}, "hk"), ({"nodes": 17}, "nodes"), ({"nodes": 8}, "nodes"),
    ({"nodes": 64.0}, "nodes"), ({"dt": 0.0}, "dt"), ({"dt": math.nan}, "dt"),
    ({"tolerance": 1.0}, "tolerance"), ({"max_periods": 1}, "max_periods"),
])
def test_bad_input_names_parameter_value_and_range(kwargs, name):
    args = {"load": 0.15, "speed": 1.0, "nodes": 32, **kwargs}
    with pytest.raises(ValueError) as err:
        peer.solve(**args)
    msg = str(err.value)
    assert msg.startswith(f"{name}={kwargs[name]!r} is not allowed: ")
    assert msg == f"{name}={kwargs[name]!r} is not allowed: {peer.ACCEPTED[name][2]}"


def test_missing_tamaas_says_how_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "tamaas", None)  # import tamaas now raises ImportError
    with pytest.raises(ImportError, match=r"pip install 'viscosine\[peers\]'"):
        peer.solve(load=0.15, speed=1.0, nodes=32)
    with pytest.raises(ValueError):  # bad input is still refused first
        peer.solve(load=-1.0, speed=1.0, nodes=32)


def test_table_and_figure(tmp_path):
    """The report's table and figure on a small grid (one speed, two steps)."""
    data = peer.third_code_table(speeds=[1.0], nodes=64, cells_per_step=(2, 1))
    assert json.loads(json.dumps(data, allow_nan=False))["summary"][0]["speed"] == 1.0
    s = data["summary"][0]
    assert s["order"] is None and s["mu_error"] is None and len(s["mu_per_dt"]) == 2
    assert abs(s["relative_difference"]) < 0.01   # measured −0.34 % at N = 64
    text = peer.format_table(data)
    assert "| 1 | 64 |" in text and "p̃∞ = 0.15" in text
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from comparisons.plots.peers import plot_dt_convergence
    fig, ax = plt.subplots()
    assert plot_dt_convergence(ax, data) is ax
    fig.savefig(tmp_path / "dt.png")
    plt.close(fig)
    assert (tmp_path / "dt.png").stat().st_size > 0
