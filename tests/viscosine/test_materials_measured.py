"""Measured master curves: realistic curves built from a known Prony material (lab layouts,
overlapping temperature sweeps with their own bias, scatter, duplicate frequencies, E'' not
consistent with E', a fluid tail) are read with no options and fitted; each fit is judged
against the material it was built from, not against the data.

Tolerances: every sweep carries a multiplicative bias b, uniform in [-BIAS, BIAS], which no fit
can remove where one sweep alone covers a stretch of frequency, and point scatter NOISE (normal)
which a smooth fit averages over a few points; the fitted modulus may therefore be off the truth
by up to BIAS + 3 NOISE (`TRUTH`).  The scatter estimate must see the injected scatter, within
the factor the sweep biases add (`scatter_is_seen`).
"""
import json
import math
import subprocess
import sys

import numpy as np
import pytest

import measured_curves as mc
from viscosine.materials import MasterCurve, fit_prony, read_dma

NOISE, BIAS = 0.01, 0.03
TRUTH = BIAS + 3 * NOISE


def _truth_error(truth, curve, model, scale=1.0):
    w = np.logspace(math.log10(curve.window[0]), math.log10(curve.window[1]), 300)
    t, m = truth.modulus(w) * scale, model.modulus(w)
    return (float(np.max(np.abs(m.real / t.real - 1.0))),
            float(np.max(np.abs(m.imag / t.imag - 1.0))))


def scatter_is_seen(report):
    return all(NOISE / 2 < s < NOISE + BIAS for s in report.scatter)


@pytest.fixture(scope="module")
def rubber():
    return mc.rubber()


@pytest.mark.parametrize("layout, order", [("lab", "decreasing"), ("tab", "shuffled"),
                                           ("plain", "increasing")])
def test_lab_layouts_are_read_and_fitted_to_the_truth(tmp_path, rubber, layout, order):
    f, e1, e2 = mc.measure(rubber, noise=NOISE, bias=BIAS, seed=5, duplicates=3)
    path = mc.write(tmp_path / f"{layout}.csv", f, e1, e2, layout=layout, order=order)
    c = read_dma(path)
    assert c.units == ("Hz", "MPa") and c.points == f.size and len(c.merged) == 3
    assert c.window[0] == pytest.approx(2 * np.pi * f.min(), rel=1e-6)
    m = fit_prony(c)
    r = m.fit
    assert max(_truth_error(rubber, c, m)) < TRUTH
    assert scatter_is_seen(r)
    assert 0.9 < r.kk_range[0] <= r.kk_range[1] < 1.1       # consistent data: no KK warning
    assert not any("Kramers" in w for w in r.warnings)
    assert r.merged == 3 and any("merged" in w for w in r.warnings)
    assert r.drops[0] > 0 and r.chosen_by == "held-out"
    if layout == "lab":
        assert "units row (line 2)" in c.notes and any("tan delta" in n and "agrees" in n
                                                       for n in c.notes)


def test_shear_moduli_in_kpa_with_a_units_row(tmp_path, rubber):
    f, e1, e2 = mc.measure(rubber, noise=NOISE, bias=BIAS, seed=6)
    path = mc.write(tmp_path / "g.txt", f, e1, e2, layout="shear-kpa")
    with pytest.raises(ValueError, match=r"nu=None is not allowed: .*shear moduli"):
        read_dma(path)
    c = read_dma(path, nu=0.5)
    assert c.units == ("rad/s", "kPa")
    m = fit_prony(c)
    assert max(_truth_error(rubber, c, m, scale=1e3)) < TRUTH


def test_duplicates_two_sets_at_one_frequency_are_merged_not_blamed_on_tan_delta(rubber):
    f, e1, e2 = mc.measure(rubber, noise=0.0, bias=0.0, seed=7, duplicates=4,
                           duplicate_spread=0.05)
    c = MasterCurve(2 * np.pi * f, e1, e2)
    assert len(c.merged) == 4
    for freq, n, s1, s2 in c.merged:
        assert n == 2 and s1 == pytest.approx(0.05, rel=1e-9) and s2 == pytest.approx(0.05,
                                                                                       rel=1e-9)
    m = fit_prony(c)
    # the merged points sit sqrt(1.05) above the truth: the fit follows within 2.5 %
    assert max(_truth_error(rubber, c, m)) < 0.025


def test_inconsistent_loss_is_measured_per_decade_and_weighted(rubber):
    f, e1, e2 = mc.measure(rubber, noise=NOISE, bias=BIAS, seed=4,
                           loss_factor=mc.transition_and_tail)
    c = MasterCurve(2 * np.pi * f, e1, e2, frequency_unit="Hz", modulus_unit="MPa")
    fits = {lw: fit_prony(c, loss_weight=lw) for lw in (0.0, 1.0, 100.0)}
    r = fits[1.0].fit
    assert any("Kramers" in w for w in r.warnings)
    # the KK figure finds the factor injected: per decade, within 15 % (scatter, bias)
    fdata = c.omega / (2 * np.pi)
    for decade, ratio in r.kk:
        inside = (fdata >= 10 ** decade) & (fdata < 10 ** (decade + 1))
        expected = float(np.median(mc.transition_and_tail(fdata[inside])))
        assert ratio == pytest.approx(expected, rel=0.15), decade
    # the weight moves the fit between E' and E'': E' alone recovers the material's E'
    assert _truth_error(rubber, c, fits[0.0])[0] < TRUTH
    rms = {lw: (m.fit.storage_rms, m.fit.loss_rms) for lw, m in fits.items()}
    assert rms[0.0][0] < rms[1.0][0] < rms[100.0][0]
    assert rms[0.0][1] > rms[1.0][1] > rms[100.0][1]
    assert fits[100.0].fit.loss_weight == 100.0


def test_a_fluid_tail_is_floored_and_fitted_in_the_window():
    truth = mc.rubber(E_r=1e-6, centre=-4.0, width=2.5, span=(-11.0, 4.0))
    f, e1, e2 = mc.measure(truth, noise=NOISE, bias=BIAS, seed=3, decades=(-5.0, 5.0))
    c = MasterCurve(2 * np.pi * f, e1, e2, frequency_unit="Hz", modulus_unit="MPa")
    m = fit_prony(c)
    assert m.fit.relaxed_floor is not None and 0.0 < m.E_r <= c.storage.min()
    assert any("no relaxed modulus" in w for w in m.fit.warnings)
    assert max(_truth_error(truth, c, m)) < TRUTH


def test_per_decade_stays_an_override_and_the_choice_is_reported(rubber):
    f, e1, e2 = mc.measure(rubber, noise=NOISE, bias=BIAS, seed=8)
    c = MasterCurve(2 * np.pi * f, e1, e2)
    auto = fit_prony(c)
    tried = dict(auto.fit.held_out)
    assert set(tried) == {1.0, 1.5, 2.0, 3.0, 4.0, 6.0}
    assert tried[auto.fit.per_decade] <= 1.05 * min(tried.values()) or \
        tried[auto.fit.per_decade] <= 1e-3
    given = fit_prony(c, per_decade=3)
    assert given.fit.per_decade == 3 and given.fit.chosen_by == "given" and not given.fit.held_out


def test_a_measured_curve_through_the_command_line(tmp_path, rubber):
    f, e1, e2 = mc.measure(rubber, noise=NOISE, bias=BIAS, seed=5, duplicates=3)
    path = mc.write(tmp_path / "sbr-lab.csv", f, e1, e2, layout="lab", order="decreasing")
    proc = subprocess.run([sys.executable, "-m", "comparisons", "point", "--solver", "bem",
                           "--load", "0.3", "--speed", "1", "--nodes", "1024", "--material",
                           str(path)], cwd=tmp_path, capture_output=True, text=True,
                          timeout=300)
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    fit = rec["material"]["fit"]
    assert fit["merged"] == 3 and fit["frequency_unit"] == "Hz" and fit["decades"]
    assert fit["per_decade_chosen_by"] == "held-out" and fit["bound"] is None
    png = tmp_path / "sbr-lab_fit.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "DMA fit of" in proc.stderr and "wrote ./sbr-lab_fit.png" in proc.stderr
