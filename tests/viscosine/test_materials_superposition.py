"""Raw isotherms -> shifts, WLF and a master curve, judged against the truth they were made from.

The test set: a known relaxation series (glassy/relaxed 1e3 over 18 decades) measured at 19
temperatures, 0.1 ... 100 Hz, shifted by known WLF constants, with 0 or 2 % multiplicative
scatter (seeded).  Tolerances: without scatter the shifts are the interpolation's (1e-3
decade); with scatter each recovered shift must lie within 4 of its own reported standard
errors of the truth, and C1, C2 within 4 of theirs.
"""
import math

import numpy as np
import pytest

from viscosine.materials import WLF, fit_prony
from viscosine.materials._superposition import _arrhenius, fit_wlf, superpose
from viscosine.materials._sweeps import Sweeps, read_sweeps, write_sweeps
from viscosine.materials._synthetic import isotherm_rows, lognormal_series

TRUTH = lognormal_series(3.0, 1e3, centre=-5.0, width=3.0, decades=18.0)
SHIFT = WLF(8.86, 101.6, 20.0)
TEMPS = np.arange(-30.0, 61.0, 5.0)
FREQ = np.logspace(-1, 2, 13)


def _sweeps(tmp_path, noise, kelvin_offset=None, seed=1):
    path = tmp_path / "sweeps.csv"
    write_sweeps(path, isotherm_rows(TRUTH, SHIFT, TEMPS, FREQ, noise=noise, seed=seed,
                                     kelvin_offset=kelvin_offset))
    return read_sweeps(path)


def _shifts(sp):
    return (np.array([s["log10_aT"] for s in sp.shifts]),
            np.array([s["log10_aT_error"] for s in sp.shifts]))


@pytest.mark.parametrize("method", ["moduli", "tan_delta"])
def test_exact_isotherms_give_the_true_shifts(tmp_path, method):
    sp = superpose(_sweeps(tmp_path, 0.0), 20.0, method=method)
    got, _ = _shifts(sp)
    assert np.max(np.abs(got - SHIFT.log10_aT(TEMPS))) < 1e-3
    assert sp.wlf.wlf.C1 == pytest.approx(8.86, rel=1e-3)
    assert sp.wlf.wlf.C2 == pytest.approx(101.6, rel=1e-3)
    assert sp.wlf.holds == (-30.0, 60.0) and sp.arrhenius is None
    # the master curve is the truth's, at the reduced frequencies
    mod = TRUTH.modulus(sp.curve.omega)
    assert np.max(np.abs(sp.curve.storage / mod.real - 1)) < 1e-2


@pytest.mark.parametrize("seed", [1, 2])
def test_scattered_isotherms_within_their_own_errors(tmp_path, seed):
    sp = superpose(_sweeps(tmp_path, 0.02, seed=seed), 20.0)
    got, err = _shifts(sp)
    true = SHIFT.log10_aT(TEMPS)
    assert np.all(np.abs(got - true) <= 4 * err + 1e-9), np.abs(got - true) / np.maximum(err, 1e-9)
    assert np.max(np.abs(got - true)) < 0.3       # 2 % scatter: a few tenths of a decade at most
    w = sp.wlf
    assert abs(w.wlf.C1 - 8.86) <= 4 * w.C1_error and abs(w.wlf.C2 - 101.6) <= 4 * w.C2_error
    assert w.C1_error < 0.5 and w.C2_error < 3.0
    assert w.holds == (-30.0, 60.0)
    # the fitted series meets the data to about their scatter
    model = fit_prony(sp.curve)
    assert model.fit.storage_rms < 0.05 and model.fit.loss_rms < 0.05


@pytest.mark.parametrize("vertical", ["temperature", "fitted"])
def test_vertical_shift(tmp_path, vertical):
    """Data with the entropic factor T/T0: 'temperature' removes it exactly, 'fitted' finds it."""
    sw = _sweeps(tmp_path, 0.0, kelvin_offset=273.15)
    sp = superpose(sw, 20.0, vertical=vertical)
    got, _ = _shifts(sp)
    true_b = np.log10(293.15 / (TEMPS + 273.15))
    got_b = np.array([s["log10_bT"] for s in sp.shifts])
    assert np.max(np.abs(got - SHIFT.log10_aT(TEMPS))) < (1e-3 if vertical == "temperature"
                                                          else 5e-3)
    assert np.max(np.abs(got_b - true_b)) < (1e-12 if vertical == "temperature" else 2e-3)
    # without the vertical shift the moduli disagree and the shifts are biased
    biased, _ = _shifts(superpose(sw, 20.0))
    assert np.max(np.abs(biased - SHIFT.log10_aT(TEMPS))) > 0.1


def test_wlf_range_and_arrhenius_below():
    """Shifts that follow WLF from -10 degC up and an Arrhenius line (100 kJ/mol) below: the
    range is found, C1 and C2 come from the WLF points alone, the activation energy is
    recovered."""
    t = np.arange(-40.0, 41.0, 5.0)
    tk, t_g, ea = t + 273.15, -10.0, 100e3
    y = SHIFT.log10_aT(t)
    below = t < t_g
    y[below] = SHIFT.log10_aT(t_g) + ea / (8.314462618 * math.log(10)) * (
        1 / tk[below] - 1 / (t_g + 273.15))
    w = fit_wlf(t, y, np.full(t.size, 0.01), 20.0)
    assert w.holds == (-10.0, 40.0)
    assert w.wlf.C1 == pytest.approx(8.86, rel=1e-8) and w.wlf.C2 == pytest.approx(101.6, rel=1e-8)
    arr = _arrhenius(Sweeps((), temperature_unit="degC"), t, y, w)
    assert arr.range == (-40.0, -15.0)
    assert arr.activation_energy == pytest.approx(ea, rel=1e-9)


def test_refusals(tmp_path):
    sw = _sweeps(tmp_path, 0.0)
    with pytest.raises(ValueError, match="reference_temperature=70.0"):
        superpose(sw, 70.0)
    with pytest.raises(ValueError, match="vertical='fitted'"):
        superpose(sw, 20.0, method="tan_delta", vertical="fitted")
    with pytest.raises(ValueError, match="temperature_unit=None"):
        p = tmp_path / "nounit.csv"
        p.write_text("temperature,frequency,storage,loss\n" + "".join(
            f"{T},{f},{1 + f + T / 100},{0.1 + f / 10}\n" for T in (0, 10, 20) for f in (1, 2, 3, 4)),
            encoding="utf-8")
        superpose(read_sweeps(p), 10.0, vertical="temperature")
    # 10 degrees apart the two coldest isotherms share less than the least overlap allowed at
    # the true shift (2.8 decades of a 3-decade sweep): refused, not placed at the edge
    wide = tmp_path / "wide.csv"
    write_sweeps(wide, isotherm_rows(TRUTH, SHIFT, np.arange(-30.0, 61.0, 10.0), FREQ))
    with pytest.raises(ValueError, match="-30 and -20 overlay best where they share only 0.2"):
        superpose(read_sweeps(wide), 20.0)
    bad = tmp_path / "two.csv"
    bad.write_text("temperature,frequency,storage,loss\n0,1,2,0.1\n0,2,3,0.1\n0,3,4,0.1\n"
                   "10,1,2,0.1\n10,2,3,0.1\n10,3,4,0.1\n", encoding="utf-8")
    with pytest.raises(ValueError, match="at least 3 temperatures"):
        read_sweeps(bad)
