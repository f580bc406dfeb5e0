"""The material readers and fits over the realistic test set, judged against the truth.

``python -m comparisons bench --materials-fits``: every case is data made from a known relaxation
series (`viscosine.materials.lognormal_series`, `isotherm_rows`, `time_rows`; with a checkout, also the measured DMA master curves
of ``tests/measured_curves.py``), read and fitted as a user's file would be, and judged against
the series and shift it came from.  Printed per case: accepted (or the refusal), the fit's
residuals, the truth's errors, seconds per fit (warm: after a first fit that imports scipy).

* raw isotherms (19 temperatures -30 ... 60 degC, 13 frequencies 0.1 ... 100 Hz, WLF 8.86/101.6
  at 20 degC, glassy/relaxed 1e3) with 0, 2 and 5 % scatter, three seeds each; with the entropic
  vertical factor (vertical shift "temperature" and "fitted"); 10 K apart (refused: the coldest
  pair overlaps too little);
* E(t) and J(t) (41 times over 5 decades) with 0 and 1 % scatter;
* the four Prony card forms written from a known series and read back;
* the measured DMA master curves of the fit's own test set, when ``tests/`` is there.

Returns 0 when every case that should be accepted is, every refusal that should happen does, and
the truth's errors are within the tests' tolerances; else 1.
"""
from __future__ import annotations

import math
import os
import sys
import tempfile
import time

import numpy as np

from viscosine import materials as vm

TRUTH = vm.lognormal_series(3.0, 1e3, centre=-5.0, width=3.0, decades=18.0)
SHIFT = vm.WLF(8.86, 101.6, 20.0)
FREQ = np.logspace(-1, 2, 13)


def _timed(f, *a, **k):
    t0 = time.perf_counter()
    out = f(*a, **k)
    return out, time.perf_counter() - t0


def isotherm_cases(folder):
    """(name, ok, line) per isotherm case."""
    out = []
    temps = np.arange(-30.0, 61.0, 5.0)
    cases = [(n, s, None, None) for n in (0.0, 0.02, 0.05) for s in (1, 2, 3)]
    cases += [(0.02, 1, 273.15, "temperature"), (0.02, 1, 273.15, "fitted")]
    for noise, seed, offset, vertical in cases:
        path = os.path.join(folder, "iso.csv")
        vm.write_sweeps(path, vm.isotherm_rows(TRUTH, SHIFT, temps, FREQ, noise=noise, seed=seed,
                                            kelvin_offset=offset))
        sp, sec = _timed(vm.superpose, vm.read_sweeps(path), 20.0, vertical=vertical)
        model, fsec = _timed(vm.fit_prony, sp.curve)
        got = np.array([s["log10_aT"] for s in sp.shifts])
        err = np.array([s["log10_aT_error"] for s in sp.shifts])
        miss = np.abs(got - SHIFT.log10_aT(temps))
        z = np.max(miss[err > 0] / err[err > 0])
        w = sp.wlf
        zc1, zc2 = abs(w.wlf.C1 - 8.86) / w.C1_error, abs(w.wlf.C2 - 101.6) / w.C2_error
        ok = bool(z <= 4.0 and zc1 <= 4.0 and zc2 <= 4.0 and (noise > 0 or miss.max() < 1e-3))
        f = model.fit
        name = f"isotherms {100 * noise:g} % seed {seed}" + (f", vertical {vertical}"
                                                              if vertical else "")
        out.append((name, ok, f"yes | shifts off by {miss.max():.4f} decade (worst "
                    f"{z:.2f} σ) | C1 {w.wlf.C1:.3f} ± {w.C1_error:.2g}, C2 {w.wlf.C2:.2f} ± "
                    f"{w.C2_error:.2g} (truth 8.86, 101.6) | WLF rms {w.rms:.3g} | fit E' "
                    f"{100 * f.storage_rms:.2f}/{100 * f.storage_max:.2f} %, E'' "
                    f"{100 * f.loss_rms:.2f}/{100 * f.loss_max:.2f} %, {f.terms} terms | "
                    f"{sec:.2f} s shifts, {fsec:.2f} s fit"))
    path = os.path.join(folder, "wide.csv")
    vm.write_sweeps(path, vm.isotherm_rows(TRUTH, SHIFT, np.arange(-30.0, 61.0, 10.0), FREQ))
    try:
        vm.superpose(vm.read_sweeps(path), 20.0)
        out.append(("isotherms 10 K apart", False, "accepted: should be refused"))
    except ValueError as exc:
        out.append(("isotherms 10 K apart", True, f"refused: {str(exc)[:110]}..."))
    return out


def time_cases(folder):
    out = []
    truth = vm.lognormal_series(2.0, 300.0, centre=0.0, width=1.5, decades=6.0, per_decade=2.0)
    t = np.logspace(-2, 3, 41)
    for kind, col in (("relaxation", "E [MPa]"), ("creep", "J [1/MPa]")):
        for noise in (0.0, 0.01):
            path = os.path.join(folder, "t.csv")
            rows = vm.time_rows(truth, t, kind=kind, noise=noise, seed=3)
            with open(path, "w", encoding="utf-8") as fh:
                fh.write(f"time [s],{col}\n" + "".join(f"{a!r},{b!r}\n" for a, b in rows))
            model, sec = _timed(vm.fit_time_data, vm.read_time_data(path))
            w = np.logspace(-2, 1, 20)
            off = float(np.max(np.abs(abs(model.modulus(w)) / abs(truth.modulus(w)) - 1)))
            ok = off <= 3 * noise + 2e-3
            out.append((f"{kind} data {100 * noise:g} %", ok,
                        f"yes | {model.fit.terms} terms, residual RMS/max {100 * model.fit.rms:.2f}/"
                        f"{100 * model.fit.max:.2f} % | |E*| off the truth {100 * off:.2f} % "
                        f"inside the window | {sec:.3f} s"))
    return out


def card_cases(folder):
    out = []
    known = vm.lognormal_series(3.0, 10.0, centre=-2.0, decades=8.0, per_decade=1.0)
    for form in vm.CARD_FORMS:
        path = os.path.join(folder, f"card.{form}")
        vm.write_card(path, known, form, nu=0.49)
        back, sec = _timed(vm.read_card, path)
        err = max([abs(back.E_r / known.E_r - 1)] +
                  [abs(a / b - 1) for a, b in zip(back.E, known.E)] +
                  [abs(a / b - 1) for a, b in zip(back.theta, known.theta)])
        out.append((f"{form} card", err <= 1e-14, f"yes | read back to {err:.1e} | "
                    f"{1e3 * sec:.2f} ms"))
    return out


def measured_curve_cases(folder):
    """Part of the fit's own test set (tests/measured_curves.py), when there."""
    here = os.path.dirname(os.path.abspath(__file__))
    tests = os.path.join(here, os.pardir, os.pardir, "tests")
    if not os.path.isfile(os.path.join(tests, "measured_curves.py")):
        return []
    sys.path.insert(0, tests)
    try:
        import measured_curves as mc
    finally:
        sys.path.pop(0)
    out = []
    truth = mc.rubber()
    for noise, bias in ((0.0, 0.0), (0.01, 0.03)):
        f, e1, e2 = mc.measure(truth, seed=1, noise=noise, bias=bias)
        curve = vm.MasterCurve(2 * math.pi * np.asarray(f), e1, e2)
        model, sec = _timed(vm.fit_prony, curve)
        r = model.fit
        w = curve.omega
        off1 = float(np.max(np.abs(model.modulus(w).real / truth.modulus(w).real - 1)))
        off2 = float(np.max(np.abs(model.modulus(w).imag / truth.modulus(w).imag - 1)))
        kk = r.kk_range
        out.append((f"measured DMA curve {100 * noise:g} % scatter, ±{100 * bias:g} % bias", True,
                    f"yes | {r.terms} terms | E' {100 * r.storage_rms:.2f}/"
                    f"{100 * r.storage_max:.2f} %, E'' {100 * r.loss_rms:.2f}/"
                    f"{100 * r.loss_max:.2f} % | KK {kk[0]:.3g}..{kk[1]:.3g} | off the truth "
                    f"E' {100 * off1:.1f} %, E'' {100 * off2:.1f} % | {sec:.2f} s"))
    return out


def run(out=sys.stdout):
    """The study (module docstring); 0 when every case holds."""
    with tempfile.TemporaryDirectory(prefix="viscosine-fits-") as folder:
        vm.fit_prony(vm.MasterCurve(np.logspace(-2, 2, 9), np.linspace(1, 2, 9),
                                    np.full(9, 0.1)))  # imports scipy: not counted below
        rows = []
        for part in (isotherm_cases, time_cases, card_cases, measured_curve_cases):
            for name, ok, line in part(folder):
                rows.append(ok)
                print(f"{'ok ' if ok else 'BAD'} {name:44s} | {line}", file=out, flush=True)
    bad = rows.count(False)
    print(f"\n{len(rows)} cases, {bad} not as expected", file=out)
    return 0 if bad == 0 else 1
