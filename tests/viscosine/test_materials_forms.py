"""The new material files through `--material` (raw isotherms, E(t)/J(t), FE cards), the measured
window a series file carries, the record's provenance, and refusals in the user's own numbers."""
import json

import numpy as np
import pytest

from comparisons import _materials
from comparisons.cli import main
from viscosine import materials as vm
from viscosine.materials._synthetic import isotherm_rows, lognormal_series, time_rows

TRUTH = lognormal_series(3.0, 1e3, centre=-5.0, width=3.0, decades=18.0)
SHIFT = vm.WLF(8.86, 101.6, 20.0)
TEMPS = np.arange(-30.0, 61.0, 5.0)


@pytest.fixture(scope="module")
def sweeps(tmp_path_factory):
    path = tmp_path_factory.mktemp("sweeps") / "isotherms.csv"
    vm.write_sweeps(path, isotherm_rows(TRUTH, SHIFT, TEMPS, np.logspace(-1, 2, 13)))
    return str(path)


def test_forms_are_told_apart(sweeps, tmp_path):
    assert vm.material_form(sweeps) == "sweeps"
    t = tmp_path / "relax.csv"
    t.write_text("time [s],E [MPa]\n" + "".join(f"{a!r},{b!r}\n" for a, b in time_rows(
        TRUTH, np.logspace(-3, 2, 20))), encoding="utf-8")
    assert vm.material_form(t) == "time"
    c = tmp_path / "card.inp"
    vm.write_card(c, lognormal_series(3.0, 10.0, decades=4.0, per_decade=1.0), "abaqus")
    assert vm.material_form(c) == "card"


def test_isotherms_as_a_material(sweeps):
    m = _materials.read(sweeps, temperature=40.0)
    info = m.info
    assert info["form"] == "sweeps" and info["temperature"] == 40.0 and info["shift"] is None
    sp = info["superposition"]
    assert sp["reference_temperature"] == 40.0
    shifts = {s["temperature"]: s["log10_aT"] for s in sp["shifts"]}
    for T, la in shifts.items():   # exact data: the true shifts relative to 40
        assert la == pytest.approx(SHIFT.log10_aT(T) - SHIFT.log10_aT(40.0), abs=2e-3)
    assert len(info["sha256"]) == 64 and info["fit"]["kk_range"] is not None
    assert info["measured_window"] == pytest.approx(list(m.window))
    # the material at 40 is the truth moved to 40: |E*| at the sliding frequency
    w = np.logspace(-1, 3, 5)
    truth40 = TRUTH.at_temperature(SHIFT, 40.0)
    assert np.max(np.abs(abs(m.model.modulus(w)) / abs(truth40.modulus(w)) - 1)) < 0.02
    # the record's material reads the same again (a worker without the parsed file)
    again = _materials.reread(json.loads(json.dumps(info)))
    assert again.prony == m.prony


def test_isotherms_with_their_fitted_wlf(sweeps):
    base = _materials.read(sweeps)
    assert base.info["temperature"] == 15.0          # the isotherm nearest the middle
    shift, info = _materials.fitted_shift(base)
    # the truth's WLF referred to 15: C2' = C2 + 15 - 20, C1' = C1 C2/C2'
    assert shift.C2 == pytest.approx(96.6, rel=2e-3)
    assert shift.C1 == pytest.approx(8.86 * 101.6 / 96.6, rel=2e-3)
    at = _materials.at_temperature(base, shift, info, 50.0)
    assert at.window == pytest.approx(tuple(w / shift.a_T(50.0) for w in base.window))
    again = _materials.reread(json.loads(json.dumps(at.info)))
    assert again.prony == at.prony


def test_window_header_travels_and_flags(tmp_path):
    model = TRUTH
    path = tmp_path / "series.txt"
    vm.write_series(path, model, window=(1e-2, 1e4))
    assert vm.read_window(path) == (1e-2, 1e4)
    assert vm.read_relaxation(path) == model           # the comment is skipped
    m = _materials.read(str(path))
    assert m.window == (1e-2, 1e4)
    text = _materials.extrapolation(m, 1e-4, 0.5)        # harmonics 1, 2 at 1e-4, 2e-4
    assert text is not None and "2 decade(s) below" in text
    assert _materials.extrapolation(m, 1.0, 0.5) is None
    creep = tmp_path / "creep.txt"
    vm.write_series(creep, model, form="creep", window=(1e-2, 1e4))
    mc = _materials.read(str(creep))
    assert mc.window == (1e-2, 1e4) and "3 decade(s) above" in _materials.extrapolation(
        mc, 1e7, 1.0)
    moved = _materials.at_temperature(mc, SHIFT, {"kind": "WLF"}, 60.0)
    assert moved.window == pytest.approx((1e-2 / SHIFT.a_T(60.0), 1e4 / SHIFT.a_T(60.0)))


def test_refusal_in_the_users_numbers(tmp_path, capsys):
    stiff = lognormal_series(2.0, 1e9, centre=-3.0, decades=13.0)
    path = tmp_path / "stiff.txt"
    vm.write_series(path, stiff)
    assert main(["point", "--solver", "bem", "--load", "0.1", "--speed", "1", "--material",
                 str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert "(E_r + sum E_i)/E_r = 2e+09/2 = 1e+09 is above 1e+08" in err
    assert "J0" not in err and len(err.splitlines()) == 1
    # 27 terms at 2.3e7 are accepted
    ok = lognormal_series(2.0, 2.3e7, centre=-3.0, decades=13.0)
    vm.write_series(path, ok)
    m = _materials.read(str(path))
    assert m.info["terms"] == 27


def test_point_on_isotherms_from_the_command_line(sweeps, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)              # point writes the fit figure beside the command
    assert main(["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "4096",
                 "--material", sweeps, "--temperature", "30"]) == 0
    rec = json.loads(capsys.readouterr().out)
    mat = rec["material"]
    assert mat["form"] == "sweeps" and mat["temperature"] == 30.0
    assert mat["superposition"]["wlf"]["holds"] == [-30.0, 60.0]
    assert mat["fit"]["max_residual"] < 0.01 and mat["sha256"]
    assert (tmp_path / "isotherms_fit.png").is_file()


def test_mastercurve_on_isotherms(sweeps, tmp_path):
    """mastercurve on raw isotherms: the master curve at --reference-temperature, moved by the
    WLF fitted to them; the shift figure; --wlf and a reference for another form refused."""
    import subprocess
    import sys
    out = tmp_path / "mc"
    base = [sys.executable, "-m", "comparisons", "mastercurve", "--material", sweeps,
            "--speeds", "1e-3", "--load", "1e5", "--wavelength", "1e-3", "--amplitude", "1e-4",
            "--nu", "0.5", "--nodes", "1024"]
    proc = subprocess.run(base + ["--temperatures", "0", "40", "--reference-temperature", "20",
                                  "--out", str(out)], capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert "WLF: C1 = 8.86" in proc.stderr and (out / "shifts.png").stat().st_size > 10_000
    run = json.loads((out / "mastercurve.json").read_text())
    sp = run["parameters"]["material"]["superposition"]
    assert sp["reference_temperature"] == 20.0
    assert run["parameters"]["shift"]["kind"] == "WLF fitted to the isotherms"
    got = [p["log10_aT"] for p in run["points"]]
    assert got == pytest.approx([SHIFT.log10_aT(0.0), SHIFT.log10_aT(40.0)], abs=2e-3)
    bad = subprocess.run(base + ["--temperatures", "0", "--wlf", "8.86", "101.6", "20", "--out",
                                 str(tmp_path / "x")], capture_output=True, text=True,
                         cwd=tmp_path)
    assert bad.returncode == 2 and "--wlf is not allowed with raw isotherms" in bad.stderr


def test_python_route_flags_the_window_of_a_series_file(tmp_path):
    """A series written with its window, read in Python (read_series) and solved with
    bem.solve_si: the probed frequencies below the window raise the warning, with its decades;
    in the window, none."""
    import warnings

    import bem
    model = vm.Maxwell(1e6, (2e6,), (1.0 / 3.0,))
    path = tmp_path / "series.txt"
    vm.write_series(path, model, window=(10.0, 1e4))
    back = vm.read_series(path)
    assert back == model and back.fit.window == (10.0, 1e4)
    assert _materials.from_model(back).window == (10.0, 1e4)
    kw = dict(nu=0.5, wavelength=1e-3, amplitude=1e-4, mean_pressure=2e5, nodes=1024)
    with warnings.catch_warnings(record=True) as caught:   # kV = 6.3 rad/s: 0.2 decade below
        warnings.simplefilter("always")
        bem.solve_si(material=back, speed=1e-3, **kw)
    texts = [str(w.message) for w in caught if issubclass(w.category, UserWarning)]
    assert any("decade(s) below the measured window" in t for t in texts), texts
    with warnings.catch_warnings(record=True) as caught:   # kV = 630 rad/s: inside
        warnings.simplefilter("always")
        bem.solve_si(material=back, speed=0.1, **kw)
    assert not any("measured window" in str(w.message) for w in caught)
