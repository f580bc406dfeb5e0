"""The report's section "A layer of finite thickness" (`comparisons.report.layers_section`, its
numbers in `comparisons.report_numbers`, its figures in `comparisons.plots.layers`).

Checked: its half-space curve is the report's own runs; a layer thick enough for S = 1 on every
mode is the half-space bit for bit along the section's own route (spec → runner → roads → bem);
a frictionless layer's answer does not depend on ν; the closed-form full-contact load against the
BEM at Δ/h = 1 within the BEM's own mesh-difference estimate; the rule that says where full
contact leaves the crest above the foundation against the BEM's verdict; and, on the quick
report's runs, the physics the section reads from its curves.
"""
import dataclasses
import math

import numpy as np
import pytest

import bem
from comparisons import report, runner
from comparisons import report_numbers as rn
from comparisons.store import Store
from comparisons.store import key as store_key

SCALARS = ("load", "penetration", "contact_fraction", "ka", "ke", "ke_hat", "tau_f", "mu")


@pytest.mark.parametrize("quick", [True, False], ids=["quick", "full"])
def test_the_half_space_curve_is_the_reports_own_runs(quick):
    """The section's half-space specs at the figures' speeds are figure 12's specs (one store
    entry each), its speeds hold the figures' as the same floats, and the report runs each spec
    once."""
    cfg = report.config(quick, workers=1)
    assert set(cfg.speeds_bem.tolist()) <= set(cfg.layer_speeds.tolist())
    half = {store_key(s) for s, _ in rn.layer_runs(cfg.nodes, cfg.layer_speeds)
            if "layer" not in s and s["load"] == rn.LAYER_LOAD}
    assert {store_key(rn.bem_spec(rn.LAYER_LOAD, s, cfg.nodes)) for s in cfg.speeds_bem} <= half
    assert len(half) == len(cfg.layer_speeds)
    keys = [store_key(s) for s, _ in report.bem_runs(cfg)]
    assert len(keys) == len(set(keys))
    assert set(keys) >= {store_key(s) for s, _ in rn.layer_runs(cfg.nodes, cfg.layer_speeds)}


@pytest.mark.parametrize("foundation", ["bonded", "frictionless"])
def test_a_thick_layer_is_the_half_space_along_the_sections_route(foundation):
    """d/λ = 4 (kd = 25.1): S = 1 exactly on every mode (docs/layers.md §3), so every scalar of
    the run is the half-space's, bit for bit, through the same spec, runner and adapter."""
    for speed in (0.1, 1.0):
        got = runner.run(rn.layer_spec(rn.LAYER_LOAD, speed, 1024, 4.0, foundation))
        ref = runner.run(rn.bem_spec(rn.LAYER_LOAD, speed, 1024))
        assert got["ok"] and ref["ok"], (got["error"], ref["error"])
        assert {k: got["record"][k] for k in SCALARS} == {k: ref["record"][k] for k in SCALARS}
        assert got["record"]["error_estimate"] == ref["record"]["error_estimate"]
        assert rn.layer_of(got["record"])["thickness_over_wavelength"] == 4.0


def test_a_frictionless_layers_answer_does_not_depend_on_nu():
    """S_F and the free-ended uniform compression (C = 1 in (1 − ν²)d/E) are independent of ν,
    and the load is p(1 − ν²)/E0: the section may run its frictionless layers at ν = ½."""
    spec = rn.layer_spec(rn.LAYER_LOAD, 1.0, 1024, 0.2, "frictionless")
    recs = []
    for nu in (0.5, 0.3, -0.5):
        s = {**spec, "layer": {**spec["layer"], "nu": nu}}
        out = runner.run(s)
        assert out["ok"], out["error"]
        recs.append(out["record"])
    for rec in recs[1:]:
        assert {k: rec[k] for k in SCALARS} == {k: recs[0][k] for k in SCALARS}
        assert rn.layer_of(rec)["approach"] == rn.layer_of(recs[0])["approach"]


@pytest.mark.parametrize("foundation, d", [("bonded", 0.02), ("bonded", 0.05), ("bonded", 0.2),
                                           ("bonded", 1.0), ("frictionless", 0.02),
                                           ("frictionless", 0.2)])
def test_closed_form_full_contact_load_against_the_bem(foundation, d):
    """p̃FC(V) of `roads.full_contact_load` (Appendix B, mode 1 over S(kd)) against the BEM's
    load at Δ/h = 1, the section's marker: within the BEM's estimate, the difference of its
    loads on N and N/2 panels (measured at N = 2048: 5e-7 relative against an estimate of
    1.5e-6 from d/λ = 0.05 up, the half-space's own collocation error; 1.0e-6 at d/λ = 0.02,
    V/V0 = 100, where mode 1's aliases, of relative size 1/(S N³), add to it).  The closed form is
    the half-space's over the BEM's own S(kd) of mode 1, to round-off."""
    layer = bem.Layer(thickness_over_wavelength=d, foundation=foundation, nu=rn.LAYER_NU)
    s1 = float(layer.factor([1])[0])
    for speed in rn.LAYER_FC_SPEEDS:
        closed = rn.roads.full_contact_load(speed, rn.RATIO, rn.HK,
                                            rn.layer_description(d, foundation))
        half = rn.roads.transition_load(speed, rn.RATIO, rn.HK)
        assert closed * s1 == pytest.approx(half, rel=1e-12)
        loads = {}
        for n in (1024, 2048):
            out = runner.run(rn.layer_spec(None, speed, n, d, foundation, penetration=1.0,
                                           hk=rn.LAYER_FC_HK))
            assert out["ok"] and out["record"]["full_contact"], out["error"]
            loads[n] = out["record"]["load"] * rn.HK / rn.LAYER_FC_HK
        estimate = abs(loads[2048] - loads[1024])
        assert abs(loads[2048] - closed) <= estimate, (speed, loads, closed)
        assert abs(loads[2048] / closed - 1.0) < 3e-6


@pytest.mark.parametrize("foundation, d, speed", [
    ("bonded", 0.1, 1.0), ("bonded", 0.2, 1.0), ("bonded", 0.5, 100.0),
    ("frictionless", 1.0, 0.01), ("frictionless", 1.0, 1.0), ("frictionless", 1.0, 100.0),
    ("frictionless", 0.5, 0.01), ("frictionless", 0.5, 1.0), ("frictionless", 0.2, 0.01)])
def test_where_full_contact_clears_the_foundation_is_the_bems_verdict(foundation, d, speed):
    """`full_contact_clears` (approach·h = h + C kd p̃FC/k < d, with p̃FC the closed form) says
    where the BEM accepts full contact at the report's hk = 1: the bonded incompressible layer
    refused up front below d = h (its approach is Δ/h = 1), the frictionless one after the solve
    (its uniform compression adds kd p̃FC; d/λ = 0.5 at V/V0 = 1 misses by 2 %)."""
    closed = rn.roads.full_contact_load(speed, rn.RATIO, rn.HK,
                                        rn.layer_description(d, foundation))
    out = runner.run(rn.layer_spec(None, speed, 1024, d, foundation, penetration=1.0))
    assert out["ok"] == rn.full_contact_clears(d, foundation, closed), out["error"]
    if out["ok"]:
        lay = rn.layer_of(out["record"])
        assert lay["uniform_compliance"] == rn.uniform_compliance(foundation)
        assert lay["approach"] * rn.HK < lay["thickness"]
        assert out["record"]["load"] == pytest.approx(closed, rel=1e-5)
    else:
        assert "foundation" in out["error"]


@pytest.fixture(scope="module")
def quick_section(tmp_path_factory, quick_report):
    """The section's runs of the quick report (N = 1024, 17 speeds): the report's own store,
    shared with test_report.py (tests/conftest.py), and the section written from them."""
    reported, proc = quick_report
    assert proc.returncode == 0, proc.stderr
    out = tmp_path_factory.mktemp("layers")
    cfg = report.config(True, workers=1)
    store = Store(str(reported / "results"))
    doc, timings = report.Doc(), {}
    report.layers_section(doc, str(out), store, cfg, timings)
    return out, cfg, store, doc, timings


def test_the_section_writes_its_figures_tables_and_times(quick_section):
    out, cfg, store, doc, timings = quick_section
    md = doc.markdown()
    for name in ("layers_mu", "layers_contact", "layers_full_contact"):
        assert (out / f"{name}.png").stat().st_size > 10_000
        assert f"({name}.png)" in md
    assert md.count("\n|---") == 2 and "—" not in md.split("| half-space | BEM |")[1].split("\n")[0]
    assert set(timings) == {"layer section: runs (sum over processes)",
                            "layer section: figures and tables"}
    assert all(store.get(s)["ok"] for s, _ in rn.layer_runs(cfg.nodes, cfg.layer_speeds))


def test_the_physics_the_section_reads_from_its_curves(quick_section):
    """What the section says, on the quick report's runs (estimated errors ≤ 1.5e-2 in μ, 1e-2 in
    2a/λ; every margin below is larger).

    A layer is stiffer than the half-space on every mode (0 < S < 1, S increasing in kd) and
    the bonded one stiffer than the frictionless one (S_B < S_F): under the same load a stiffer
    surface makes a narrower contact, at every speed.  The friction peak, lower and at a lower
    speed on a thinner layer, and the thinnest bonded layer's larger μ at low speeds and
    smaller at high ones are measured (a factor 1.33 and 0.15 at V/V0 = 0.01 and 100)."""
    _, cfg, store, _, _ = quick_section
    sweeps = rn.layer_sweeps(store, cfg)
    curves = sweeps["curves"]
    for f, cs in curves.items():
        assert all(not c["failed"] for c in cs)
        ordered = sorted(cs, key=lambda c: math.inf if c["d_over_lambda"] is None
                         else c["d_over_lambda"])
        width = np.array([c["contact_fraction"] for c in ordered])
        assert np.all(np.diff(width, axis=0) > 0.0), f  # thinner: narrower, at every speed
        peaks = np.array([c["peak"] for c in ordered])
        assert np.all(np.diff(peaks[:, 1]) > 0.0) and np.all(np.diff(peaks[:, 0]) > 0.0), peaks
    by = {(f, c["d_over_lambda"]): c for f, cs in curves.items() for c in cs}
    for d in (0.2, 0.5, 1.0):
        assert np.all(np.array(by["bonded", d]["contact_fraction"])
                      < np.array(by["frictionless", d]["contact_fraction"]))
    find = rn.layer_findings(sweeps, rn.layer_full_contact(store, cfg))
    thin = find["thinnest"]["bonded"]
    assert thin["d_over_lambda"] == 0.05
    assert thin["mu_ratio_low"] > 1.2 and thin["mu_ratio_high"] < 0.2
    assert 0.1 < thin["crossing"] < 0.4
    # p̃FC ∝ 1/S: (kd)^-3 for the squeezed film, (kd)^-1 for the frictionless layer (between
    # d/λ = 0.02 and 0.05 the next terms of S take 0.15 and 0.001 off the exponents)
    assert 2.7 < find["exponent"]["bonded"] < 3.0
    assert find["exponent"]["frictionless"] == pytest.approx(1.0, abs=0.01)
    assert find["speed_spread"]["bonded"] < 1e-5 and find["speed_spread"]["frictionless"] < 1e-5


def test_the_half_space_of_the_section_meets_the_semi_analytic_road(quick_section):
    """The section's half-space BEM curve (the report's runs) against figure 12's semi-analytic
    curve: within the BEM's estimate at every speed, and its interpolated friction peak near the
    semi-analytic road's (4 speeds per decade: 5e-3 in μ, 3e-3 in V/V0 measured)."""
    _, cfg, store, _, _ = quick_section
    sweeps = rn.layer_sweeps(store, cfg)
    half = next(c for c in sweeps["curves"]["bonded"] if c["d_over_lambda"] is None)
    for s, mu, err in zip(half["speed"], half["mu"], half["mu_error"]):
        assert abs(mu / rn.semi_analytic(rn.LAYER_LOAD, s).mu - 1.0) <= err
    (v, mu), (va, mua) = half["peak"], sweeps["analytic"]["peak"]
    assert abs(mu / mua - 1.0) < 1e-2 and abs(v / va - 1.0) < 1e-2


def test_the_layer_figures_draw_the_numbers_given():
    """The figure functions draw what they are given: one line per layer and the half-space's
    line and circles per panel, and p̃FC split where the crest would reach the foundation."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from comparisons.plots import layers
    curve = {"speed": [0.1, 1.0, 10.0], "mu": [0.1, 0.3, 0.1],
             "contact_fraction": [0.5, 0.4, 0.3]}
    data = {"load": 0.3, "nu": 0.5,
            "curves": {f: [{**curve, "d_over_lambda": d} for d in (0.1, None)]
                       for f in layers.FOUNDATIONS},
            "analytic": {"speed": [0.1, 10.0], "mu": [0.1, 0.1], "contact_fraction": [0.5, 0.3]}}
    fig = layers.plot_friction(plt.figure(), data)
    assert [len(ax.lines) for ax in fig.axes] == [3, 3]
    assert all(ax.get_xscale() == "log" for ax in fig.axes)
    plt.close(fig)
    marker = {"d_over_lambda": 0.1, "closed_form": 2.0, "bem": 2.0, "bem_hk1": None}
    fc = {"d_over_lambda": [0.05, 0.1, 0.2],
          "curves": {f: [{"speed": 1.0, "load": [4.0, 2.0, 1.0], "clears": [False, True, True],
                          "half_space": 0.67, "markers": [marker]}]
                     for f in layers.FOUNDATIONS}}
    fig = layers.plot_full_contact(plt.figure(), fc)
    solid = fig.axes[0].lines[0].get_ydata()
    assert np.isnan(solid[0]) and list(solid[1:]) == [2.0, 1.0]
    plt.close(fig)
