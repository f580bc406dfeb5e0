"""viscosine.materials: the exact interconversion of the two Prony forms, the DMA reader and its
refusals, the Prony fit, the time–temperature shifts, and the fit figure."""
from __future__ import annotations

import math
import pathlib
import re

import numpy as np
import pytest

from viscosine import materials
from viscosine.materials import (Creep, MasterCurve, Maxwell, ShiftTable, WLF, fit_prony,
                                 read_dma, read_shift_table)

from conftest import ROUNDOFF

ROOT = pathlib.Path(__file__).resolve().parents[2]
SBR = ROOT / "comparisons" / "data" / "suite" / "materials" / "dma-sbr.csv"
EPS = np.finfo(float).eps


def _random_series(seed):
    """8–64 terms log-spaced (with jitter) over 2–20 decades, E_glassy/E_r up to ~1e4."""
    rng = np.random.default_rng(seed)
    n = int(rng.integers(8, 65))
    decades = rng.uniform(2.0, 20.0)
    step = decades / (n - 1)
    # realistic series are log-spaced: jitter each time by at most a third of the spacing
    log_t = np.linspace(-decades / 2, decades / 2, n) + rng.uniform(-step / 3, step / 3, n)
    theta = 10.0 ** (log_t + rng.uniform(-3.0, 3.0))
    E = 10.0 ** rng.uniform(-3.0, 0.0, n)
    E_r = 10.0 ** rng.uniform(-4.0, -1.0) * E.sum()
    return Maxwell(E_r, rng.permutation(E), rng.permutation(theta))


def _all_frequencies(m, extra=3.0, num=4000):
    th = np.array(m.theta)
    return np.logspace(-math.log10(th.max()) - extra, -math.log10(th.min()) + extra, num)


def _exact_compliance(m, c, w):
    """J* of a creep series with J(0+) = 1/E_glassy taken from the Maxwell side (no
    cancellation): the conversion's own accuracy."""
    out = np.full(w.shape, 1.0 / m.glassy, dtype=complex)
    for j, t in zip(c.J, c.tau):
        out += j / (1.0 + 1j * w * t)
    return out


# ----------------------------------------------------------------- exact: the standard linear solid
@pytest.mark.parametrize("E0, Einf, tau", [(1.0, 3.0, 1.0), (2.0, 6.0, 1.5), (3e6, 3e9, 2e-4)])
def test_standard_linear_solid_both_ways(E0, Einf, tau):
    """E_r = E0, E_1 = E∞ − E0, θ = τ E0/E∞  <->  J0 = 1/E0, J_1 = 1/E0 − 1/E∞, creep time τ."""
    m = Maxwell(E0, (Einf - E0,), (tau * E0 / Einf,))
    c = m.creep()
    assert isinstance(c, Creep) and len(c.J) == 1
    assert c.J0 == 1.0 / E0
    assert c.J[0] == pytest.approx(1.0 / E0 - 1.0 / Einf, rel=8 * EPS)
    assert c.tau[0] == pytest.approx(tau, rel=8 * EPS)
    # the inverse reads J(0+) = J0 - J_1: a cancellation of eps E∞/E0, whatever the method
    back = Maxwell.from_creep(1.0 / E0, (1.0 / E0 - 1.0 / Einf,), (tau,))
    assert back.E_r == pytest.approx(E0, rel=2 * EPS)
    assert back.E[0] == pytest.approx(Einf - E0, rel=8 * EPS * Einf / E0)
    assert back.theta[0] == pytest.approx(tau * E0 / Einf, rel=8 * EPS * Einf / E0)


def test_creep_units_for_the_bem_road():
    """creep(E_ref, tau_ref) gives the nondimensional series: the paper's SLS with ratio 3."""
    m = Maxwell(5e6, (10e6,), (0.2 / 3.0,))            # E0 = 5 MPa, E∞ = 15 MPa, τ = 0.2 s
    c = m.creep(E_ref=5e6, tau_ref=0.2)
    assert c.J0 == pytest.approx(1.0, rel=2 * EPS)
    assert c.J[0] == pytest.approx(2.0 / 3.0, rel=8 * EPS)
    assert c.tau[0] == pytest.approx(1.0, rel=8 * EPS)
    J0, J, tau = c                                      # unpacks for bem.Prony(*c)
    assert (J0, J, tau) == tuple(c)


# ----------------------------------------------------------------- identity: random series
@pytest.mark.parametrize("seed", range(40))
def test_random_series_round_trip(seed):
    """E*(ω) J*(ω) = 1 at frequencies spanning every time, for 8–64 terms over up to 20
    decades; the retardation times interlace the relaxation times; and back again."""
    m = _random_series(seed)
    c = m.creep()
    n = len(m.E)
    assert len(c.J) == n and all(j > 0.0 for j in c.J)
    w = _all_frequencies(m)
    e = m.modulus(w)
    # the conversion itself: J(0+) = 1/E_glassy
    assert np.max(np.abs(e * _exact_compliance(m, c, w) - 1.0)) < ROUNDOFF
    # as the BEM road sees it, J(0+) = J0 - sum J_k: the representation's own cancellation,
    # a few eps times E_glassy/E_r, adds to it
    ratio = m.glassy / m.E_r
    assert np.max(np.abs(e * c.compliance(w) - 1.0)) < ROUNDOFF + 8 * EPS * ratio
    assert c.J0 - math.fsum(c.J) == pytest.approx(1.0 / m.glassy, rel=8 * EPS * ratio)
    # interlacing: tau_1 > theta_1 > tau_2 > theta_2 > ... (both descending)
    taus, thetas = sorted(c.tau, reverse=True), sorted(m.theta, reverse=True)
    merged = [v for pair in zip(taus, thetas) for v in pair]
    assert all(a > b for a, b in zip(merged, merged[1:]))
    # and back: times to round-off, amplitudes to the representation's cancellation
    back = Maxwell.from_creep(*c)
    np.testing.assert_allclose(back.theta, np.sort(m.theta), rtol=1e-14 + 16 * EPS * ratio)
    order = np.argsort(m.theta)
    err = np.max(np.abs(np.array(back.E) - np.array(m.E)[order])) / m.glassy
    assert err < 64 * EPS * ratio
    assert back.E_r == pytest.approx(m.E_r, rel=4 * EPS)


def test_sixty_four_terms_over_twenty_decades():
    """The widest case asked for: 64 terms, one every 20/63 decade, E∞/E_r = 1e3."""
    theta = np.logspace(-10.0, 10.0, 64)
    E = np.full(64, 999.0 / 64)
    m = Maxwell(1.0, E, theta)
    c = m.creep()
    w = np.logspace(-13.0, 13.0, 8000)
    assert np.max(np.abs(m.modulus(w) * _exact_compliance(m, c, w) - 1.0)) < ROUNDOFF
    assert np.max(np.abs(m.modulus(w) * c.compliance(w) - 1.0)) < ROUNDOFF


def test_a_negligible_term_keeps_its_relative_accuracy():
    """A term 1e-13 of the glassy modulus puts a zero within ~1e-13 of its pole: the distance
    to the pole is solved for, so the residue stays right and the product stays 1."""
    m = Maxwell(1.0, (1e-10, 500.0, 499.0), (1.0, 1e-3, 1e3))
    c = m.creep()
    w = np.logspace(-6.0, 6.0, 3001)
    assert np.max(np.abs(m.modulus(w) * _exact_compliance(m, c, w) - 1.0)) < ROUNDOFF
    back = Maxwell.from_creep(*c)
    assert back.E[1] == pytest.approx(1e-10, rel=1e-6)


def test_dropping_a_negligible_term_moves_the_compliance_by_at_most_its_weight():
    """`Creep.without_negligible`: the terms below floor J(0+) go (J0 kept), their weights are
    returned, and J*(w) moves by at most the weight relative to |J*|, at every frequency."""
    c = Creep(1.0, (0.5, 3e-3, 1e-2), (1.0, 1e-2, 1e2))
    jp = c.J0 - math.fsum(c.J)
    kept, weights = c.without_negligible(3e-2)
    assert kept == Creep(1.0, (0.5,), (1.0,))
    assert weights == pytest.approx((1e-2 / jp, 3e-3 / jp), rel=ROUNDOFF)
    w = np.logspace(-6.0, 6.0, 2001)
    moved = np.abs(kept.compliance(w) / c.compliance(w) - 1.0)
    assert moved.max() <= sum(weights) * (1.0 + 1e-12)
    assert moved.max() > 0.5 * max(weights)             # the bound is reached, not loose
    assert c.without_negligible(1e-12) == (c, ())       # nothing below: the same series


def test_merged_dropped_and_elastic():
    m = Maxwell(2.0, (1.0, 0.0, 0.5, 0.5), (1.0, 7.0, 3.0, 3.0))  # zero term, a repeated time
    c = m.creep()
    assert len(c.J) == 2
    w = np.logspace(-3, 3, 301)
    assert np.max(np.abs(m.modulus(w) * _exact_compliance(m, c, w) - 1.0)) < ROUNDOFF
    assert Maxwell(4.0).creep() == Creep(0.25, (), ())
    assert Maxwell.from_creep(0.25, (), ()) == Maxwell(4.0)


def test_modulus_signs_limits_and_extremes():
    m = _random_series(3)
    w = np.concatenate([[0.0], np.logspace(-30, 300, 400)])
    e = m.modulus(w)
    assert np.all(np.isfinite(e))
    assert np.all(e.imag >= 0.0) and np.all(np.diff(e.real) >= 0.0)
    assert e[0] == m.E_r
    assert e[-1].real == pytest.approx(m.glassy, rel=ROUNDOFF)
    np.testing.assert_allclose(m.compliance(w[1:50]) * e[1:50], 1.0, rtol=ROUNDOFF)
    # relaxation modulus: E(0+) glassy, E(∞) relaxed
    assert m.relaxation(0.0) == pytest.approx(m.glassy, rel=ROUNDOFF)
    assert m.relaxation(1e300) == m.E_r


def test_forty_term_conversion_round_trips():
    """40 terms over 20 decades (its cost, about 3 ms, is a benchmark figure, not a test)."""
    m = Maxwell(1.0, np.linspace(10.0, 100.0, 40), np.logspace(-10, 10, 40))
    c = m.creep()
    w = np.logspace(-12, 12, 97)
    np.testing.assert_allclose(m.modulus(w) * c.compliance(w), 1.0, rtol=1e-12)


@pytest.mark.parametrize("make, pattern", [
    (lambda: Maxwell(0.0), r"E_r=0\.0 is not allowed: .*E_r > 0"),
    (lambda: Maxwell(float("nan")), r"E_r=nan"),
    (lambda: Maxwell(True), r"E_r=True"),
    (lambda: Maxwell(1.0, (-1.0,), (1.0,)), r"E=\(-1\.0,\) is not allowed: .*E_i >= 0"),
    (lambda: Maxwell(1.0, (1.0,), (0.0,)), r"theta=\(0\.0,\) is not allowed: .*theta_i > 0"),
    (lambda: Maxwell(1.0, (1.0,), (float("inf"),)), r"theta=\(inf,\)"),
    (lambda: Maxwell(1.0, (1.0, 2.0), (1.0,)), r"one amplitude per relaxation time"),
    (lambda: Maxwell.from_creep(1.0, (0.6, 0.4), (1.0, 2.0)), r"J0=1\.0 .*J\(0\+\)"),
    (lambda: Maxwell.from_creep(0.0, (), ()), r"J0=0\.0"),
    (lambda: Maxwell.from_creep(1.0, (0.5,), (-1.0,)), r"tau=\(-1\.0,\)"),
    (lambda: Maxwell(1.0).creep(E_ref=0.0), r"E_ref=0\.0"),
])
def test_not_a_series_is_refused(make, pattern):
    with pytest.raises(ValueError, match=pattern):
        make()


# ----------------------------------------------------------------- the DMA reader
def test_read_the_suite_curve():
    c = read_dma(SBR, frequency_unit="Hz")
    assert c.omega.size == 109                              # 12 decades, 9 per decade
    assert c.window == pytest.approx((2e-4 * math.pi, 2e8 * math.pi), rel=1e-12)
    assert 3.0 < c.storage[0] < 4.0 and 2000.0 < c.storage[-1] < 3007.0   # MPa
    assert 0.8 < c.tan_delta.max() < 1.2
    assert c.source == str(SBR)
    assert np.array_equal(read_dma(SBR).omega, c.omega)     # the header says [Hz]
    with pytest.raises(ValueError, match=r"frequency_unit='rad/s' is not allowed: the unit of "
                                         r"the file's frequency column \('Hz' in "):
        read_dma(SBR, frequency_unit="rad/s")


def test_frequency_unit_without_a_header_unit(tmp_path):
    path = tmp_path / "c.csv"
    path.write_text(_curve_text(GOOD))
    assert np.array_equal(read_dma(path).omega, [r[0] for r in GOOD])        # rad/s
    np.testing.assert_allclose(read_dma(path, frequency_unit="Hz").omega,
                               [2 * math.pi * r[0] for r in GOOD], rtol=1e-15)


def test_shear_moduli_are_turned_into_tensile(tmp_path):
    c = read_dma(SBR, frequency_unit="Hz")
    nu = 0.49
    g = tmp_path / "g.csv"
    g.write_text("# shear\nloss, Frequency [Hz], temperature, storage\n" + "".join(
        f"{float(l) / (2 * (1 + nu))!r}, {float(w) / (2 * math.pi)!r}, 20, "
        f"{float(s) / (2 * (1 + nu))!r}\n"
        for w, s, l in zip(c.omega, c.storage, c.loss)))
    e = read_dma(g, kind="G", nu=nu, frequency_unit="Hz")
    np.testing.assert_allclose(e.storage, c.storage, rtol=1e-14)
    np.testing.assert_allclose(e.loss, c.loss, rtol=1e-14)


def _curve_text(rows, header="frequency,storage,loss"):
    return "# test curve\n" + header + "\n" + "".join(",".join(map(str, r)) + "\n" for r in rows)


GOOD = [(1e-2 * 10 ** (k / 2), 1.0 + k, 0.8 + 0.2 * k) for k in range(8)]


def _with(j, row):
    rows = list(GOOD)
    rows[j] = row
    return rows


@pytest.mark.parametrize("content, pattern", [
    (_curve_text(_with(3, (GOOD[3][0], -1.0, GOOD[3][2]))), r"storage modulus > 0 .*\(line 6\)"),
    (_curve_text(_with(3, (GOOD[3][0], GOOD[3][1], "nan"))), r"finite numbers \(line 6: loss"),
    (_curve_text(_with(2, (GOOD[2][0], GOOD[2][1], 0.0))), r"loss modulus > 0.*\(line 5\)"),
    (_curve_text(GOOD[:4]), r"at least 5 points \(got 4 distinct frequencies\)"),
    (_curve_text(GOOD[:4] + [GOOD[3]]), r"at least 5 points \(got 4 distinct frequencies\)"),
    ("", r"header line naming the columns frequency, storage, loss.*empty"),
    ("# only a comment\n", r"empty or only comments"),
    (_curve_text(GOOD, header="frequency,storage"), r"line 2 has no column 'loss'"),
    (_curve_text(GOOD, header="frequency,storage,loss,loss"), r"more than one column 'loss'"),
    (_curve_text(GOOD).replace("\n0.1,", "\n0.1,7,"), r"3 fields on every line.*line 5 has 4"),
    (_curve_text(GOOD).replace("\n0.1,", "\n0.1x,"), r"line 5: frequency '0\.1x' is not a number"),
])
def test_bad_dma_files_are_refused(tmp_path, content, pattern):
    path = tmp_path / "curve.csv"
    path.write_text(content)
    with pytest.raises(ValueError, match=pattern) as info:
        read_dma(path)
    message = str(info.value)
    assert message.startswith(f"dma={str(path)!r} is not allowed: ")
    assert "\n" not in message


def test_what_is_data_is_read_not_refused(tmp_path):
    """Rows out of order, a frequency measured twice, a storage modulus that falls, a loss too
    small for the rise of E' (not Kramers-Kronig consistent): data, read and reported."""
    path = tmp_path / "curve.csv"
    rows = _with(4, (GOOD[2][0], GOOD[4][1], GOOD[4][2]))           # out of order
    path.write_text(_curve_text(rows))
    c = read_dma(path)
    assert np.all(np.diff(c.omega) > 0) and "sorted" in " ".join(c.notes)
    rows = _with(4, (GOOD[3][0] * (1 + 4e-15), GOOD[3][1] * 1.05, GOOD[3][2] * 1.05))
    path.write_text(_curve_text(rows))
    c = read_dma(path)                                             # a duplicate: merged
    assert c.omega.size == 7 and c.points == 8 and len(c.merged) == 1
    assert c.storage[3] == pytest.approx(GOOD[3][1] * math.sqrt(1.05), rel=1e-12)
    assert c.merged[0][1:] == (2, pytest.approx(0.05, rel=1e-9), pytest.approx(0.05, rel=1e-9))
    path.write_text(_curve_text(_with(5, (GOOD[5][0], 2.5, GOOD[5][2]))))
    c = read_dma(path)                                             # E' falls: counted
    assert c.drops == (1, pytest.approx(1 - 2.5 / GOOD[4][1], rel=1e-12))
    path.write_text(_curve_text([(w, s, 1e-3 * l) for w, s, l in GOOD]))
    m = fit_prony(read_dma(path))                                  # E'' far too small for E'
    assert m.fit.kk_range[1] < 0.01                                # measured/implied E''
    assert m.fit.max_residual > 0.5 and any("Kramers" in w for w in m.fit.warnings)


def test_swapped_columns_are_read_and_flagged(tmp_path):
    """Storage and loss exchanged: the loss peak makes a storage modulus that falls, and E''
    is thousands of times what E' implies: the report says both."""
    text = SBR.read_text().replace("storage [MPa],loss [MPa]", "loss [MPa],storage [MPa]")
    path = tmp_path / "swapped.csv"
    path.write_text(text)
    m = fit_prony(read_dma(path, frequency_unit="Hz"))
    assert m.fit.drops[0] > 10 and m.fit.kk_range[1] > 100
    assert any("columns exchanged" in w for w in m.fit.warnings)
    assert any("Kramers-Kronig" in w for w in m.fit.warnings)


def test_binary_and_foreign_files_are_refused(tmp_path):
    b = tmp_path / "b.csv"
    b.write_bytes(b"frequency,storage,loss\n\x00\x01")
    with pytest.raises(ValueError, match=r"binary"):
        read_dma(b)
    latin = tmp_path / "l.csv"
    latin.write_bytes("# modul \xe9\nfrequency,storage,loss\n".encode("latin-1"))
    with pytest.raises(ValueError, match=r"not UTF-8"):
        read_dma(latin)
    with pytest.raises(ValueError, match=r"readable file"):
        read_dma(tmp_path / "missing.csv")


@pytest.mark.parametrize("kw, pattern", [
    (dict(kind="G"), r"nu=None is not allowed: a Poisson ratio"),
    (dict(kind="G", nu=0.6), r"nu=0\.6 is not allowed: a Poisson ratio in \(-1, 0\.5\]"),
    (dict(kind="E", nu=0.5), r"nu=0\.5 is not allowed: None with kind='E'"),
    (dict(kind="K"), r"kind='K' is not allowed"),
    (dict(frequency_unit="1/s"), r"frequency_unit='1/s' is not allowed"),
])
def test_bad_reader_options(kw, pattern):
    with pytest.raises(ValueError, match=pattern):
        read_dma(SBR, **kw)


def test_master_curve_checks_itself():
    w, s, l = (np.array(v, dtype=float) for v in zip(*GOOD))
    c = MasterCurve(w, s, l)
    assert not c.omega.flags.writeable
    with pytest.raises(ValueError, match=r"as many values"):
        MasterCurve(w, s[:-1], l)
    # any order: sorted (row j of the input is named in a refusal)
    c2 = MasterCurve(w[::-1], s[::-1], l[::-1])
    assert np.array_equal(c2.omega, c.omega) and np.array_equal(c2.loss, c.loss)
    with pytest.raises(ValueError, match=r"^omega\[2\]=.* storage modulus > 0"):
        MasterCurve(w, np.where(np.arange(w.size) == 2, -1.0, s), l)
    # a storage modulus that falls is scatter, counted
    s2 = s.copy()
    s2[4] = s2[3] * 0.995
    assert MasterCurve(w, s2, l).drops == (1, pytest.approx(0.005, rel=1e-9))


# ----------------------------------------------------------------- the Prony fit
def test_fit_reproduces_the_suite_curve():
    c = read_dma(SBR, frequency_unit="Hz")
    m = fit_prony(c)
    r = m.fit
    assert r.storage_max < 0.02 and r.loss_max < 0.02 and r.tan_delta_max < 0.02
    assert r.storage_rms <= r.storage_max and r.loss_rms <= r.loss_max
    assert r.terms == len(m.E) <= r.candidates and all(e > 0.0 for e in m.E)
    assert m.measured_window == c.window
    # the report is what the data say
    e = m.modulus(c.omega)
    assert np.max(np.abs(e.real / c.storage - 1.0)) == pytest.approx(r.storage_max, rel=1e-12)
    # and the fitted series converts exactly (E∞/E_r ~ 900 here)
    cr = m.creep()
    w = _all_frequencies(m)
    assert np.max(np.abs(m.modulus(w) * cr.compliance(w) - 1.0)) < ROUNDOFF
    # deterministic
    again = fit_prony(read_dma(SBR, frequency_unit="Hz"))
    assert again == m and again.fit == r


def test_fit_recovers_a_series_on_its_grid():
    """Data made by a series whose times are candidates of the fit are fitted to round-off."""
    w = np.logspace(-2, 4, 61)
    theta = np.logspace(-5.0, 3.0, 17)                   # 2 per decade, 1/w_max/10 .. 10/w_min
    true = Maxwell(2.0, 10.0 ** np.linspace(0, 3, 17), theta)
    e = true.modulus(w)
    m = fit_prony(MasterCurve(w, e.real, e.imag), per_decade=2)
    assert m.fit.max_residual < 1e-8


def test_a_bound_the_fit_misses_is_refused_in_the_users_units():
    c = read_dma(SBR, frequency_unit="Hz")
    m = fit_prony(c, per_decade=1)                   # one per decade: a ripple of ~8 % on E''
    assert 0.05 < m.fit.max_residual < 0.1 and m.fit.bound is None   # no bound: reported
    with pytest.raises(ValueError, match=r"max_residual=0\.05 is not allowed: .*misses E'?'? at "
                                         r"[0-9.e+]+ Hz by [-+][0-9.]+ % \(datum [0-9.]+, fit "
                                         r"[0-9.]+ MPa\); measured E''/E'' implied by E' is 1"):
        fit_prony(c, per_decade=1, max_residual=0.05)
    assert fit_prony(c, per_decade=1, max_residual=0.1).fit.bound == 0.1


def test_a_fluid_gets_a_floor_and_a_warning():
    """A single Maxwell element (no relaxed modulus): the fit floors E_r, says so, and still
    reproduces the data in the window."""
    w = np.logspace(-3, 3, 31)
    x = w * 1.0
    curve = MasterCurve(w, 100.0 * x * x / (1 + x * x), 100.0 * x / (1 + x * x))
    m = fit_prony(curve, extend=0.0)
    assert m.fit.relaxed_floor == m.E_r > 0.0 and m.E_r <= curve.storage.min()
    assert any("no relaxed modulus" in t for t in m.fit.warnings)
    assert m.fit.storage_max < 0.01 and m.fit.loss_max < 0.01


def test_extrapolation_warning():
    m = fit_prony(read_dma(SBR))
    w0, w1 = m.measured_window
    assert m.extrapolation_warning(w0, w1) is None
    assert m.extrapolation_warning(math.sqrt(w0 * w1)) is None
    low = m.extrapolation_warning(w0 / 100.0, w1)
    assert re.search(r"2 decade\(s\) below the measured window", low)
    both = m.extrapolation_warning(w0 / 10.0, w1 * 1000.0)
    assert "1 decade(s) below" in both and "3 decade(s) above" in both and "\n" not in both
    assert Maxwell(1.0, (1.0,), (1.0,)).extrapolation_warning(1e-9, 1e9) is None
    with pytest.raises(ValueError, match=r"omega_hi=1\.0 is not allowed"):
        m.extrapolation_warning(2.0, 1.0)


@pytest.mark.parametrize("kw, pattern", [
    (dict(per_decade=0.1), r"per_decade=0\.1"),
    (dict(extend=-1.0), r"extend=-1\.0"),
    (dict(max_residual=0.0), r"max_residual=0\.0"),
])
def test_bad_fit_options(kw, pattern):
    with pytest.raises(ValueError, match=pattern):
        fit_prony(read_dma(SBR), **kw)
    with pytest.raises(ValueError, match=r"curve=.* a MasterCurve"):
        fit_prony("dma-sbr.csv")


# ----------------------------------------------------------------- shifts
def test_wlf():
    s = WLF(17.44, 51.6, 20.0)
    assert s.log10_aT(20.0) == 0.0
    assert s.log10_aT(30.0) == pytest.approx(-17.44 * 10 / 61.6, rel=ROUNDOFF)
    assert s.a_T(10.0) > 1.0 > s.a_T(40.0)                # faster when hot
    np.testing.assert_allclose(s.log10_aT(np.array([20.0, 30.0])), [0.0, s.log10_aT(30.0)])
    for T in (20.0 - 51.6, -40.0, float("nan")):
        with pytest.raises(ValueError, match=r"T=.* above the WLF pole T_ref - C2"):
            s.log10_aT(T)
    with pytest.raises(ValueError, match=r"C2=-1\.0"):
        WLF(17.44, -1.0, 20.0)


def test_shift_table_and_its_reader(tmp_path):
    t = ShiftTable((-20.0, 0.0, 20.0, 60.0), (6.0, 3.0, 0.0, -3.0))
    assert t.log10_aT(10.0) == pytest.approx(1.5, rel=ROUNDOFF)
    assert t.log10_aT(60.0) == -3.0
    assert t.a_T(40.0) == pytest.approx(10 ** -1.5, rel=ROUNDOFF)
    for T in (-20.5, 61.0):
        with pytest.raises(ValueError, match=r"inside the shift table \[-20\.0, 60\.0\]"):
            t.log10_aT(T)
    with pytest.raises(ValueError, match=r"log_aT=.* strictly decreasing"):
        ShiftTable((0.0, 10.0, 20.0), (1.0, 2.0, 0.0))
    with pytest.raises(ValueError, match=r"T=.* strictly increasing"):
        ShiftTable((0.0, 0.0, 20.0), (1.0, 0.5, 0.0))
    path = tmp_path / "shift.csv"
    path.write_text("# measured at 4 temperatures, degC\nTemperature [degC], log_aT\n"
                    "-20, 6\n0, 3\n20, 0\n60, -3\n")
    assert read_shift_table(path) == t
    path.write_text("temperature,log_aT\n0,3\n-20,6\n20,0\n")
    with pytest.raises(ValueError, match=r"shift_table=.* increasing temperatures \(line 3"):
        read_shift_table(path)
    path.write_text("temperature,log_aT\n0,3\n20,4\n")
    with pytest.raises(ValueError, match=r"strictly decreasing with T \(line 3"):
        read_shift_table(path)
    path.write_text("temperature,shift\n0,3\n20,4\n")
    with pytest.raises(ValueError, match=r"no column 'log_aT'"):
        read_shift_table(path)


@pytest.mark.parametrize("shift", [WLF(17.44, 51.6, 20.0),
                                   ShiftTable((-20.0, 20.0, 60.0), (6.0, 0.0, -3.0))],
                         ids=["wlf", "table"])
def test_at_temperature_scales_every_time(shift):
    m = fit_prony(read_dma(SBR, frequency_unit="Hz"))
    T = 35.0
    hot = m.at_temperature(shift, T)
    a = shift.a_T(T)
    assert hot.temperature == T and hot.E == m.E and hot.E_r == m.E_r
    np.testing.assert_allclose(hot.theta, np.array(m.theta) * a, rtol=ROUNDOFF)
    w = np.logspace(-2, 6, 50)
    np.testing.assert_allclose(hot.modulus(w), m.modulus(w * a), rtol=ROUNDOFF)
    assert hot.measured_window == pytest.approx((m.fit.window[0] / a, m.fit.window[1] / a))
    assert hot.fit.loss_max == m.fit.loss_max
    # from 35 to 0 is from the reference to 0
    cold = hot.at_temperature(shift, 0.0)
    np.testing.assert_allclose(cold.theta, m.at_temperature(shift, 0.0).theta, rtol=1e-12)


# ----------------------------------------------------------------- relaxation files, forms, units
def test_relaxation_file_reads_the_series_and_converts_to_the_creep_file(tmp_path):
    """A relaxation-series file is the Maxwell form of a material; its creep form is the
    creep-series file of the same material (both written in one set of units)."""
    m = Maxwell(1.0, (1.9117622793709936, 0.42157105396233896),
                (0.04275180120485259, 7.017248198795148))
    path = tmp_path / "relax.txt"
    path.write_text("# relaxation form, moduli in E_ref, relaxation times in tau_ref\n"
                    f"E_r {m.E_r!r}\n" + "".join(f"{e!r}, {t!r}  # term\n"
                                                 for e, t in zip(m.E, m.theta)))
    got = materials.read_relaxation(path)
    assert got == m and got.fit is None
    assert materials.material_form(path) == "relaxation"
    c = got.creep()
    assert c.J0 == 1.0 and len(c.J) == 2
    (tmp_path / "elastic.txt").write_text("Er 2.5\n")
    assert materials.read_relaxation(tmp_path / "elastic.txt") == Maxwell(2.5)


@pytest.mark.parametrize("content, pattern", [
    ("J0 1.0\n0.5 1.0\n", r"first line 'E_r <value>'.*line 1: 'J0 1.0'"),
    ("E_r -1\n", r"relaxed modulus E_r > 0 \(line 1"),
    ("E_r 1\n-2 0.5\n", r"amplitudes E_i >= 0 \(line 2: -2\.0\)"),
    ("E_r 1\n2 0\n", r"relaxation times theta_i > 0 \(line 2"),
    ("E_r 1\n2 nan\n", r"finite numbers \(line 2"),
    ("E_r 1\n2 0.5 7\n", r"exactly two numbers .*line 2 has 3"),
    ("E_r 1\n2 x\n", r"numeric fields \(line 2: 'x'"),
    ("# nothing\n", r"empty or only comments"),
])
def test_bad_relaxation_files_are_refused(tmp_path, content, pattern):
    path = tmp_path / "r.txt"
    path.write_text(content)
    with pytest.raises(ValueError, match=pattern) as info:
        materials.read_relaxation(path)
    assert str(info.value).startswith(f"relaxation={str(path)!r} is not allowed: ")
    assert "\n" not in str(info.value)


def test_material_form_tells_the_three_forms_apart(tmp_path):
    assert materials.material_form(SBR) == "dma"
    (tmp_path / "c.txt").write_text("# creep\nj0 1\n0.5 1\n")
    assert materials.material_form(tmp_path / "c.txt") == "creep"
    for content, shown in [("x_over_lambda,ky\n-0.5,1\n", "x_over_lambda ky"),
                           ("frequency,storage\n1,2\n", "frequency storage"),
                           ("1.0\n0.5\n", "1.0")]:
        (tmp_path / "x.txt").write_text(content)
        with pytest.raises(ValueError, match=r"material=.* is not allowed: .*: a creep series "
                                             r"\(first line 'J0 <value>'\), a relaxation "
                                             r"series .* or a DMA master curve .*line 1 "
                                             f"begins '{re.escape(shown)}'"):
            materials.material_form(tmp_path / "x.txt")
    (tmp_path / "b.txt").write_bytes(b"J0 1\x00")
    with pytest.raises(ValueError, match=r"binary"):
        materials.material_form(tmp_path / "b.txt")


def test_the_modulus_unit_is_read_and_turned_into_pascals(tmp_path):
    c = read_dma(SBR)
    assert c.modulus_unit == "MPa"
    m = fit_prony(c)
    assert m.fit.modulus_unit == "MPa"
    pa = m.in_pascals()
    assert pa.E_r == m.E_r * 1e6 and pa.E == tuple(e * 1e6 for e in m.E)
    assert pa.theta == m.theta and pa.fit.modulus_unit == "Pa" and pa.in_pascals() == pa
    assert pa.fit.max_residual == m.fit.max_residual
    hand = Maxwell(1e6, (2e6,), (1e-3,))
    assert hand.in_pascals() is hand                      # by hand: Pa by convention
    # a header without a unit: turning it into pascals would be a guess
    path = tmp_path / "c.csv"
    path.write_text(_curve_text(GOOD))
    assert read_dma(path).modulus_unit is None
    w, s_, l_ = (np.array(v, dtype=float) for v in zip(*GOOD))
    fit = fit_prony(MasterCurve(w, s_, l_), max_residual=1.0)
    with pytest.raises(ValueError, match=r"modulus_unit=None is not allowed: a modulus unit"):
        fit.in_pascals()
    # storage and loss in two known units: the loss is converted to the storage's unit
    path.write_text(_curve_text(GOOD, header="frequency,storage [MPa],loss [kPa]"))
    c = read_dma(path)
    assert c.modulus_unit == "MPa" and "loss converted from kPa to MPa" in c.notes
    np.testing.assert_allclose(c.loss, [r[2] * 1e-3 for r in GOOD], rtol=1e-15)
    # in two units of which one is unknown: a silent factor, refused
    path.write_text(_curve_text(GOOD, header="frequency,storage [MPa],loss [bar]"))
    with pytest.raises(ValueError, match=r"storage and loss in one unit .*'MPa' and 'bar'"):
        read_dma(path)


# ----------------------------------------------------------------- the fit figure; independence
def test_fit_figure_writes_a_png(tmp_path):
    from comparisons.plots import materials as _material_plots
    c = read_dma(SBR, frequency_unit="Hz")
    m = fit_prony(c)
    out = _material_plots.dma_fit_figure(tmp_path / "fit.png", c, m)
    data = pathlib.Path(out).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    ax = _material_plots.plot_dma_fit(c, m)
    assert "dma-sbr.csv" in ax.get_title() and "terms" in ax.get_title()
    import matplotlib.pyplot as plt
    plt.close(ax.figure)


def test_materials_imports_neither_road_nor_matplotlib():
    text = "".join(p.read_text() for p in pathlib.Path(materials.__file__).parent.glob("*.py"))
    assert not re.search(r"^\s*(from|import)\s+(bem|analytic|comparisons|matplotlib)\b",
                         text, re.M)
