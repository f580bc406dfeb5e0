"""Materials on the command line and the SI fronts, end to end: the time each speed is measured
in, creep and relaxation files of one material giving one point, DMA curves (fit, SHA-256,
residual, extrapolation warnings), temperature shifts, SI inputs, the friction master curve, and
one-line refusals (exit status 2) of every kind of bad material input.

Meshes are fixed and small (N = 1024 … 2048): each claim here is an identity between two solves
of the same discretised problem, so it holds to round-off at any N."""
import hashlib
import json
import math
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import analytic
import bem
from comparisons import cli, mastercurve
from viscosine.materials import Maxwell, WLF, fit_prony, read_dma

from conftest import ROUNDOFF

ROOT = pathlib.Path(__file__).resolve().parents[2]
SUITE = ROOT / "comparisons" / "data" / "suite" / "materials"
SBR = SUITE / "dma-sbr.csv"
PRONY2 = SUITE / "prony2.txt"
BEM = ["point", "--solver", "bem", "--load", "0.3", "--nodes", "2048"]
#: relative on these, absolute (they are angles of order 1, or fractions) on the others
RELATIVE = ("mu", "tau_f", "penetration", "load", "max_pressure")
ABSOLUTE = ("contact_fraction", "ka", "ke", "ke_hat")

#: a smooth relaxation spectrum whose times lie on the fit's grid (the fit is exact), and its
#: DMA curve over five decades: window 1e-2 … 1e3 rad/s
SPECTRUM = Maxwell(1.0, tuple([10.0 / 13] * 13), tuple(np.logspace(-4.0, 2.0, 13).tolist()))
OMEGA = np.logspace(-2.0, 3.0, 41)


def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "comparisons", *map(str, args)],
                          capture_output=True, text=True, cwd=cwd)


def _run(capsys, *argv):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _point(capsys, *argv):
    rc, out, err = _run(capsys, *argv)
    assert rc == 0, err
    return json.loads(out), err


def _same_point(a, b, tol=ROUNDOFF):
    for k in RELATIVE:
        assert a[k] == pytest.approx(b[k], rel=tol, abs=0.0), k
    for k in ABSOLUTE:
        assert a[k] == pytest.approx(b[k], rel=0.0, abs=tol), k


def _write_relaxation(path, m):
    path.write_text("# generalised Maxwell: E(t) = E_r + sum E_i exp(-t/theta_i)\n"
                    f"E_r {m.E_r!r}\n" + "".join(f"{e!r} {t!r}\n" for e, t in zip(m.E, m.theta)))
    return path


def _spectrum_curve(header="frequency [rad/s],storage [MPa],loss [MPa]"):
    e = SPECTRUM.modulus(OMEGA)
    return ("# synthetic: the modulus of SPECTRUM\n" + header + "\n" + "".join(
        f"{w!r},{s!r},{l!r}\n" for w, s, l in zip(OMEGA.tolist(), e.real.tolist(),
                                                   e.imag.tolist())))


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    """Each test runs in its own folder: point and sweep write a DMA fit's figure beside the
    command (never into the repository)."""
    monkeypatch.chdir(tmp_path)


@pytest.fixture
def dma(tmp_path):
    """The DMA curve of SPECTRUM (moduli in MPa, angular frequencies)."""
    path = tmp_path / "dma.csv"
    path.write_text(_spectrum_curve())
    return path


# ------------------------------------------------------------------------------ name the time
def test_relaxation_and_creep_files_of_one_material_give_one_point(tmp_path):
    """End to end: the creep file (--prony, --material) and its exact relaxation twin."""
    p = bem.read_prony(PRONY2)
    relax = _write_relaxation(tmp_path / "relax.txt", Maxwell.from_creep(p.J0, p.J, p.tau))
    recs = {}
    for name, option, path in (("prony", "--prony", PRONY2), ("creep", "--material", PRONY2),
                               ("relaxation", "--material", relax)):
        proc = _cli(*BEM, "--speed", "1", option, path, cwd=tmp_path)
        assert proc.returncode == 0, proc.stderr
        recs[name] = json.loads(proc.stdout)
    assert recs["prony"]["mu"] == recs["creep"]["mu"]     # the same file, the same series
    _same_point(recs["relaxation"], recs["creep"])
    rel = recs["relaxation"]["material"]
    assert rel["form"] == "relaxation" and rel["terms"] == 2
    assert rel["sha256"] == hashlib.sha256(relax.read_bytes()).hexdigest()
    assert "relaxation times" in recs["relaxation"]["time_unit"]
    assert "creep (retardation) times" in recs["creep"]["time_unit"]
    assert recs["prony"]["material"]["form"] == "creep"


def test_a_relaxation_time_is_not_a_creep_time(tmp_path, capsys):
    """The paper's solid written with its relaxation time τ/3 is the solid; written with τ as a
    relaxation time it is the solid at three times the speed (τ_creep = τ_relax E∞/E0)."""
    sls = _point(capsys, *BEM, "--speed", "1")[0]
    assert "creep (retardation) time" in sls["time_unit"]
    assert sls["material"]["form"] == "standard_linear_solid" and sls["material"]["ratio"] == 3
    right = _write_relaxation(tmp_path / "right.txt", Maxwell(1.0, (2.0,), (1.0 / 3.0,)))
    _same_point(_point(capsys, *BEM, "--speed", "1", "--material", right)[0], sls)
    wrong = _write_relaxation(tmp_path / "wrong.txt", Maxwell(1.0, (2.0,), (1.0,)))
    _same_point(_point(capsys, *BEM, "--speed", "1", "--material", wrong)[0],
                _point(capsys, *BEM, "--speed", "3")[0])
    a = _point(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")[0]
    assert a["time_unit"] == sls["time_unit"]


def test_help_says_which_time_the_speed_is_measured_in(capsys):
    for name in ("point", "sweep"):
        assert cli.main([name, "--help"]) == 0
        text = " ".join(capsys.readouterr().out.split())
        assert "creep time" in text and "relaxation" in text and "--material FILE" in text
        assert "--tau-creep" in text and "--tau-relax" in text
    assert cli.main(["mastercurve", "--help"]) == 0
    assert "[m/s]" in capsys.readouterr().out


# ------------------------------------------------------------------------------ DMA
def test_dma_point_records_the_file_its_sha256_and_the_fit(tmp_path):
    proc = _cli("point", "--solver", "bem", "--load", "0.1", "--speed", "1", "--nodes", "1024",
                "--material", SBR, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    m = rec["material"]
    assert m["form"] == "dma" and m["path"] == str(SBR)
    assert m["sha256"] == hashlib.sha256(SBR.read_bytes()).hexdigest()
    fit = fit_prony(read_dma(SBR))
    assert m["terms"] == len(fit.E) and m["E_ref"] == fit.E_r and m["tau_ref"] == 1.0
    assert m["fit"]["max_residual"] == fit.fit.max_residual < 0.02
    assert m["fit"]["bound"] is None                      # no bound unless --max-residual
    assert m["fit"]["modulus_unit"] == "MPa" and "[MPa]" in m["E_ref_is"]
    assert "1 s" in rec["time_unit"] and rec["success"] is True
    assert "extrapolation" not in proc.stderr             # ω = 1 … 10 rad/s: measured


def test_extrapolation_is_warned_outside_the_window_and_not_inside(dma, capsys):
    base = ["point", "--solver", "bem", "--load", "0.3", "--nodes", "1024", "--material", dma]
    inside, err = _point(capsys, *base, "--speed", "1")
    assert inside["material"]["fit"]["max_residual"] < 1e-6   # the spectrum is on the grid
    assert inside["material"]["fit"]["window"] == [OMEGA[0], OMEGA[-1]]
    assert not any("extrapolation" in w for w in inside["warnings"])
    assert not [ln for ln in err.splitlines() if "warning: extrapolation" in ln]
    for speed, side in (("1e-4", "below"), ("1000", "above")):
        rec, err = _point(capsys, *base, "--speed", speed)
        warned = [w for w in rec["warnings"] if w.startswith("extrapolation:")]
        assert len(warned) == 1 and f"decade(s) {side} the measured window" in warned[0]
        lines = [ln for ln in err.splitlines() if "warning: extrapolation" in ln]
        assert len(lines) == 1 and lines[0].startswith("point: warning: extrapolation:")
    # the harmonics of the contact count: at 200 the first is inside, the fifth is not
    rec, _ = _point(capsys, *base, "--speed", "200")
    top = math.ceil(1.0 / rec["contact_fraction"])
    assert top >= 5 and any("above the measured window" in w for w in rec["warnings"])


# ------------------------------------------------------------------------------ temperature
def test_a_point_at_T_is_the_reference_point_at_the_speed_times_aT(dma, tmp_path, capsys):
    base = ["point", "--solver", "bem", "--load", "0.3", "--nodes", "1024", "--material", dma]
    wlf = WLF(8.86, 101.6, 20.0)
    table = tmp_path / "shift.csv"
    table.write_text("temperature [degC],log_aT\n-10,3\n20,0\n80,-2.5\n")
    for T, shift, a in ((60.0, ["--wlf", "8.86", "101.6", "20"], wlf.a_T(60.0)),
                        (0.0, ["--shift-table", table], 10.0 ** 2.0)):
        hot, _ = _point(capsys, *base, "--speed", "0.5", "--temperature", T, *shift)
        ref, _ = _point(capsys, *base, "--speed", repr(0.5 * a))
        _same_point(hot, ref)
        assert hot["speed"] == 0.5 and hot["material"]["temperature"] == T
        assert hot["material"]["log10_aT"] == pytest.approx(math.log10(a), rel=ROUNDOFF)
        assert hot["material"]["fit"]["window"] == pytest.approx([OMEGA[0] / a, OMEGA[-1] / a],
                                                                 rel=ROUNDOFF)
    at_ref, _ = _point(capsys, *base, "--speed", "0.5", "--temperature", "20", "--wlf", "8.86",
                       "101.6", "20")
    assert at_ref["mu"] == _point(capsys, *base, "--speed", "0.5")[0]["mu"]
    # a creep series shifts as well (every time times a_T)
    creep, _ = _point(capsys, *BEM, "--speed", "0.5", "--material", PRONY2, "--temperature",
                      "60", "--wlf", "8.86", "101.6", "20")
    _same_point(creep, _point(capsys, *BEM, "--speed", repr(0.5 * wlf.a_T(60.0)), "--material",
                              PRONY2)[0])


def test_sweep_takes_the_material_and_the_temperature(dma, capsys):
    rc, out, err = _run(capsys, "sweep", "--solver", "bem", "--load", "0.3", "--speed", "0.5",
                        "5", "--nodes", "1024", "--material", dma, "--temperature", "60",
                        "--wlf", "8.86", "101.6", "20")
    assert rc == 0, err
    recs = [json.loads(line) for line in out.splitlines()]
    assert [r["speed"] for r in recs] == [0.5, 5.0]
    assert all(r["material"]["temperature"] == 60.0 and r["material"]["form"] == "dma"
               for r in recs)


# ------------------------------------------------------------------------------ SI
SI = ["--units", "SI", "--nu", "0.5", "--wavelength", "1e-3", "--amplitude", "1e-4"]


def test_si_point_is_the_si_front(capsys):
    sls = dict(E0=1e6, Einf=3e6, nu=0.5, wavelength=1e-3, amplitude=1e-4, speed=0.05,
               mean_pressure=2e4)
    rec, _ = _point(capsys, "point", "--solver", "bem", "--load", "2e4", "--speed", "0.05",
                    "--nodes", "1024", *SI, "--E0", "1e6", "--Einf", "3e6", "--tau-relax",
                    repr(0.01 / 3))
    ref = bem.solve_si(**sls, tau_creep=0.01, nodes=1024)
    assert rec["si"]["friction_coefficient"] == pytest.approx(ref.friction_coefficient,
                                                              rel=ROUNDOFF)
    assert rec["si"]["contact_halfwidth"] == pytest.approx(ref.contact_halfwidth, rel=ROUNDOFF)
    assert rec["si"]["mean_pressure"] == pytest.approx(2e4, rel=1e-9)  # achieved, to the
    # solver's load-balance tolerance
    assert rec["si"]["speed"] == pytest.approx(0.05, rel=ROUNDOFF)
    assert rec["si_scales"]["tau_ref"] == pytest.approx(0.01, rel=ROUNDOFF)
    a, _ = _point(capsys, "point", "--solver", "analytic", "--load", "2e4", "--speed", "0.05",
                  *SI, "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01")
    assert a["si"]["friction_coefficient"] == analytic.solve_si(**sls, tau_creep=0.01).friction_coefficient
    # a DMA curve in SI: moduli from the header's MPa, times in s
    rec, _ = _point(capsys, "point", "--solver", "bem", "--load", "2e5", "--speed", "0.01",
                    "--nodes", "1024", *SI, "--material", SBR)
    ref = bem.solve_si(material=fit_prony(read_dma(SBR)), nu=0.5, wavelength=1e-3,
                       amplitude=1e-4, speed=0.01, mean_pressure=2e5, nodes=1024)
    assert rec["si"]["friction_coefficient"] == pytest.approx(ref.friction_coefficient,
                                                              rel=ROUNDOFF)
    assert rec["material"]["units"] == "SI" and rec["material"]["E_ref"] == pytest.approx(
        fit_prony(read_dma(SBR)).E_r * 1e6, rel=ROUNDOFF)


def test_solve_si_takes_any_material_any_time_and_a_profile_in_metres():
    base = dict(nu=0.5, wavelength=1e-3, speed=0.05, mean_pressure=2e4, nodes=1024)
    ref = bem.solve_si(E0=1e6, Einf=3e6, tau_creep=0.01, amplitude=1e-4, **base)
    same = [bem.solve_si(E0=1e6, Einf=3e6, tau_creep=0.01, amplitude=1e-4, **base),
            bem.solve_si(E0=1e6, Einf=3e6, tau_relax=0.01 / 3, amplitude=1e-4, **base),
            bem.solve_si(material=Maxwell(1e6, (2e6,), (0.01 / 3,)), amplitude=1e-4, **base),
            bem.solve_si(E0=1e6, Einf=3e6, tau_creep=0.01, **base, heights=1e-4 * np.cos(
                2 * np.pi * (np.arange(64) / 64 - 0.5)))]
    for r in same:  # a relaxation time, a Maxwell series, a sampled cosine: round-off apart
        _same_point(r.solution.as_dict(), ref.solution.as_dict())
    assert same[3].full_contact_pressure is None and ref.full_contact_pressure > 0
    assert analytic.solve_si(E0=1e6, Einf=3e6, tau_relax=0.01 / 3, amplitude=1e-4,
                             **{k: v for k, v in base.items() if k != "nodes"}).success
    for kw, pattern in [
        (dict(E0=1e6, Einf=3e6, tau_creep=0.01, tau_relax=0.003), r"exactly one time"),
        (dict(E0=1e6, Einf=3e6), r"^tau_creep is missing: give exactly one time"),
        (dict(E0=1e6, Einf=3e6, tau_relax=-1.0), r"^tau_relax=-1\.0 is not allowed"),
        (dict(material=SPECTRUM, E0=1e6), r"^E0=.* is not allowed with material="),
        (dict(material="dma.csv"), r"^material='dma\.csv' is not allowed"),
        (dict(material=fit_prony(read_dma(SBR)).__class__(1.0, fit=None), tau=1.0),
         r"^tau=1\.0 is not allowed with material="),
    ]:
        with pytest.raises(ValueError, match=pattern):
            bem.solve_si(amplitude=1e-4, **base, **kw)
    with pytest.raises(ValueError, match=r"^amplitude=0\.0001 is not allowed with heights="):
        bem.solve_si(E0=1e6, Einf=3e6, tau_creep=0.01, amplitude=1e-4, heights=np.ones(8), **base)
    with pytest.warns(UserWarning, match=r"decade\(s\) below the measured window"):
        bem.solve_si(material=fit_prony(read_dma(SBR)), amplitude=1e-4,
                     **dict(base, speed=1e-9, mean_pressure=2e5))


# ------------------------------------------------------------------------------ master curve
MC = ["mastercurve", "--wlf", "8.86", "101.6", "20", "--load", "2e5", "--wavelength", "1e-3",
      "--amplitude", "1e-4", "--nu", "0.5", "--nodes", "1024"]


def test_mastercurve_end_to_end_writes_each_point_and_resumes(dma, tmp_path):
    out = tmp_path / "mc"
    args = [*MC, "--material", dma, "--temperatures", "20", "60", "--speeds", "1e-4:1e-2:2",
            "--out", out]
    proc = _cli(*args, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout == ""
    # a run this short prints its summary only (the progress line is throttled), after the
    # DMA fit's line (its figure into --out)
    lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("mastercurve: ")]
    fit = [ln for ln in lines if ln.startswith("mastercurve: DMA fit of ")]
    progress = [ln for ln in lines if ln not in fit]
    assert len(progress) == 1 and progress[0].startswith("mastercurve: 4/4 points in ")
    assert len(fit) == 1 and fit[0].endswith(f"wrote {out / 'dma_fit.png'}")
    assert sorted(p.name for p in out.iterdir()) == ["dma_fit.png", "mastercurve.json",
                                                     "mastercurve.png", "points.csv"]
    doc = json.loads((out / "mastercurve.json").read_text())
    assert doc["parameters"]["material"]["sha256"] == hashlib.sha256(dma.read_bytes()).hexdigest()
    pts = doc["points"]
    assert [(p["temperature"], p["speed"]) for p in pts] == [(20, 1e-4), (20, 1e-2), (60, 1e-4),
                                                            (60, 1e-2)]
    assert all(p["success"] and 0.0 < p["mu"] < 1.0 for p in pts)
    a = WLF(8.86, 101.6, 20.0).a_T(60.0)
    assert pts[2]["reduced_speed"] == pytest.approx(1e-4 * a, rel=ROUNDOFF)
    assert (out / "mastercurve.png").read_bytes()[:4] == b"\x89PNG"
    lines = (out / "points.csv").read_text().splitlines()
    assert lines[1].startswith("# parameters: ") and len(lines) == 4 + 4
    # an interrupted run: the last point lost mid-line; the same command solves only it
    (out / "points.csv").write_text("\n".join(lines[:-1]) + "\n" + lines[-1][:20])
    again = _cli(*args, cwd=tmp_path)
    assert again.returncode == 0, again.stderr
    assert "4/4 points (3 from points.csv) in " in again.stderr
    redo = json.loads((out / "mastercurve.json").read_text())["points"]
    assert [p["mu"] for p in redo] == [p["mu"] for p in pts]
    # other parameters in the same folder: refused, nothing overwritten
    other = _cli(*[a if a != "2e5" else "3e5" for a in map(str, args)], cwd=tmp_path)
    assert other.returncode == 2 and len(other.stderr.strip().splitlines()) == 1
    assert "other parameters" in other.stderr


# ------------------------------------------------------------------------------ negligible terms
def test_a_fit_with_a_negligible_term_is_solved_and_the_record_lists_it(dma, tmp_path, capsys):
    """The failure first: the exact creep form of the loss-weighted fit of SPECTRUM holds a term
    below the BEM's floor 1e-12 J(0+), which bem refuses; mastercurve solves it with the term
    dropped and says so in the record (count, largest weight)."""
    model = fit_prony(read_dma(dma), loss_weight=2.0)
    creep = model.creep(E_ref=model.E_r)
    jp = creep.J0 - math.fsum(creep.J)
    assert min(creep.J) < 1e-12 * jp
    with pytest.raises(ValueError, match=r"is below 1e-12 J\(0\+\)"):
        bem.validate(material=bem.Prony(*creep))
    out = tmp_path / "mc"
    rc, _, err = _run(capsys, *MC, "--material", dma, "--temperatures", "20", "--speeds",
                      "1e-3", "--loss-weight", "2", "--out", out)
    assert rc == 0, err
    doc = json.loads((out / "mastercurve.json").read_text())
    dropped = doc["parameters"]["material"]["dropped_terms"]
    small = [j / jp for j in creep.J if j < 1e-12 * jp]
    assert dropped["count"] == len(small)
    assert dropped["largest_weight"] == pytest.approx(max(small), rel=1e-9)  # in Pa: new digits
    assert doc["points"][0]["success"]


def test_a_dropped_term_moves_mu_within_its_weight(tmp_path, capsys):
    """The standard linear solid of E∞/E0 = 3 (creep time 1) plus a relaxation term of 3e-13:
    the BEM drops its creep term (weight ~1e-13) and agrees with the semi-analytic road on the
    solid, which is the full series to within that weight, within its own estimate + w."""
    path = _write_relaxation(tmp_path / "sls_tiny.txt",
                             Maxwell(1.0, (2.0, 3e-13), (1.0 / 3.0, 1e-2)))
    b, _ = _point(capsys, "point", "--solver", "bem", "--load", "0.3", "--speed", "1",
                  "--rtol", "1e-5", "--material", path)
    a, _ = _point(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")
    w = b["material"]["dropped_terms"]["largest_weight"]
    assert b["material"]["dropped_terms"]["count"] == 1 and 0.0 < w < 1e-12
    for key in ("mu", "penetration"):
        err = abs(b[key] / a[key] - 1.0)
        assert err <= b["error_estimate"][key] + w, (key, err, b["error_estimate"][key])


@pytest.mark.parametrize("option", ["--material", "--prony"])
def test_a_creep_file_with_a_negligible_term_is_solved_without_it(option, tmp_path, capsys):
    """A creep file with a term of 3e-13 J(0+), as --material or through --prony (the BEM's own
    reader): dropped where the series is handed to the BEM, as a fitted series' (it was refused
    in 400 characters naming --material): the record lists it and the point is the one of the
    file without it."""
    full = tmp_path / "creep_tiny.txt"
    full.write_text("J0 1\n0.5 1\n1.5e-13 0.1\n")
    bare = tmp_path / "creep.txt"
    bare.write_text("J0 1\n0.5 1\n")
    argv = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "1024"]
    b, _ = _point(capsys, *argv, option, full)
    a, _ = _point(capsys, *argv, option, bare)
    dropped = b["material"]["dropped_terms"]
    assert dropped["count"] == 1 and dropped["floor"] == bem.TERM_MIN
    assert dropped["largest_weight"] == pytest.approx(1.5e-13 / 0.5, rel=1e-9)
    assert "dropped_terms" not in a["material"]
    if option == "--material":
        assert b["material"]["terms"] == 2
    _same_point(b, a)


def test_solve_si_drops_a_negligible_term_with_a_warning():
    """bem.solve_si: the solid of E∞/E0 = 3 plus a relaxation term 3e-13 E0 solves (the creep
    term, ~1e-13 J(0+), dropped with a warning) to the point of the solid within its weight."""
    base = dict(nu=0.5, wavelength=1e-3, speed=0.05, mean_pressure=2e4, nodes=1024,
                amplitude=1e-4)
    ref = bem.solve_si(material=Maxwell(1e6, (2e6,), (0.01 / 3,)), **base)
    with pytest.warns(UserWarning, match=r"1 Prony term\(s\) below 1e-12 J\(0\+\) dropped"):
        got = bem.solve_si(material=Maxwell(1e6, (2e6, 3e-7), (0.01 / 3, 1e-4)), **base)
    _same_point(got.solution.as_dict(), ref.solution.as_dict(), tol=1e-12)


def test_mastercurve_api_collapses_onto_the_reduced_speed(dma):
    """μ(V, T) = μ(a_T V, T_ref): the Python API, through bem.solve (runner.run)."""
    wlf = WLF(8.86, 101.6, 20.0)
    a = wlf.a_T(60.0)
    seen = []
    table = mastercurve.friction_master_curve(
        str(dma), shift=wlf, temperatures=[60.0, 20.0], speeds=[1e-4, 1e-4 * a],
        mean_pressure=2e5, wavelength=1e-3, amplitude=1e-4, nu=0.5, nodes=1024,
        on_point=lambda row, i, n, reused: seen.append((i, n, reused)))
    assert seen == [(0, 4, False), (1, 4, False), (2, 4, False), (3, 4, False)]
    assert table.success.all() and table.speed.tolist() == [1e-4, 1e-4 * a] * 2
    # (60, 1e-4) and (20, 1e-4 a_T) are one point
    assert table.mu[0] == pytest.approx(table.mu[3], rel=ROUNDOFF)
    assert table.parameters["material"]["form"] == "dma"
    # a Maxwell object in Pa and s is accepted as well
    pa = Maxwell(1e6, tuple(e * 1e6 for e in SPECTRUM.E), SPECTRUM.theta)
    t2 = mastercurve.friction_master_curve(pa, shift=wlf, temperatures=[20.0], speeds=[1e-4],
                                           mean_pressure=2e5, wavelength=1e-3, amplitude=1e-4,
                                           nu=0.5, nodes=1024)
    # the fit recovers SPECTRUM (its times are on the fit's grid) to its residual, < 1e-6 of
    # the moduli, not to round-off: the two series are the same material to about 1e-9 in μ
    assert t2.mu[0] == pytest.approx(table.mu[2], rel=1e-9)


# ------------------------------------------------------------------------------ bad input
GOOD = [(1e-2 * 10 ** (k / 2), 1.0 + k, 0.8 + 0.2 * k) for k in range(8)]


def _curve(rows, header="frequency,storage [MPa],loss [MPa]"):
    return header + "\n" + "".join(",".join(map(str, r)) + "\n" for r in rows)


def _with(j, row):
    rows = list(GOOD)
    rows[j] = row
    return rows


POINT = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "1024"]
SHIFT = ["--wlf", "8.86", "101.6", "20"]
# (argv with {file} for a file holding `content`, {dma}, {sbr}, {prony}, {table}, {tmp};
# content; fragment)
BAD = [
    # DMA curves no linear viscoelastic solid gives
    (POINT + ["--material", "{file}"], _curve(_with(3, (GOOD[3][0], -1.0, GOOD[3][2]))),
     "a storage modulus > 0 (storage -1.0) (line 5)"),
    (POINT + ["--material", "{file}"], _curve(_with(2, (GOOD[2][0], GOOD[2][1], 0.0))),
     "a loss modulus > 0"),
    (POINT + ["--material", "{file}"], _curve(_with(3, (GOOD[3][0], "nan", GOOD[3][2]))),
     "finite numbers (line 5: storage"),
    (POINT + ["--material", "{file}"], _curve(GOOD, "frequency,storage [MPa],loss [bar]"),
     "storage and loss in one unit"),
    # relaxation and creep series
    (POINT + ["--material", "{file}"], "E_r -1\n", "relaxed modulus E_r > 0"),
    (POINT + ["--material", "{file}"], "E_r 1\n-2 0.5\n", "amplitudes E_i >= 0"),
    (POINT + ["--material", "{file}"], "E_r 1\n2 0\n", "relaxation times theta_i > 0"),
    (POINT + ["--material", "{file}"], "J0 1\n1.5 1\n", "J(0+)"),
    (POINT + ["--prony", "{file}"], "E_r 1\n2 0.5\n", "this is a relaxation series"),
    # not one of the forms
    (POINT + ["--material", "{file}"], "1\n0.7\n0\n-0.7\n-1\n-0.7\n0\n0.7\n",
     "a creep or relaxation series, Prony card, E(t)/J(t) or DMA curve"),
    (POINT + ["--material", "{file}"], "", "empty or only comments"),
    (POINT + ["--material", "{tmp}"], "", "a folder"),
    # the fit, the shift
    (POINT + ["--material", "{sbr}", "--max-residual", "1e-4"], "",
     "--max-residual 0.0001: must be a bound the fit meets (its largest residual is "),
    (POINT + ["--material", "{prony}", "--max-residual", "0.1"], "",
     "--max-residual 0.1: not for a creep series (it applies to a DMA curve or raw isotherms)"),
    (POINT + ["--material", "{dma}", "--temperature", "100", "--shift-table", "{table}"], "",
     "--temperature 100.0: must be a temperature inside the shift table [-10.0, 80.0]"),
    (POINT + ["--material", "{dma}", "--temperature", "-90", *SHIFT], "",
     "above the WLF pole"),
    (POINT + ["--material", "{dma}", "--temperature", "60"], "", "without --wlf"),
    (POINT + ["--material", "{dma}", *SHIFT], "", "--wlf is not allowed without --temperature"),
    (POINT + ["--temperature", "60", *SHIFT], "", "--temperature is not allowed here"),
    (POINT + ["--prony", "{prony}", "--material", "{prony}"], "", "--material is not allowed"),
    (POINT + ["--material", "{prony}", "--ratio", "2"], "", "--ratio is not allowed"),
    (POINT + ["--material", "{dma}", "--wlf", "8", "-1", "20", "--temperature", "30"], "",
     "--wlf 8.0 -1.0 20.0 is not allowed: C2=-1.0"),
    (["point", "--solver", "analytic", "--load", "0.3", "--speed", "1", "--material", "{prony}"],
     "", "--material is not allowed here: a BEM option"),
    # SI
    (POINT[:-2] + ["--units", "SI", "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01", "--nu",
                   "0.5", "--wavelength", "1e-3"], "", "--amplitude is missing"),
    (POINT + ["--units", "SI", "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01",
              "--tau-relax", "0.003", "--nu", "0.5", "--wavelength", "1e-3",
              "--amplitude", "1e-4"], "", "--tau-relax 0.003 is not allowed with --tau-creep"),
    (POINT + ["--units", "SI", "--E0", "-1e6", "--Einf", "3e6", "--tau-creep", "0.01", "--nu", "0.5",
              "--wavelength", "1e-3", "--amplitude", "1e-4"], "", "--E0 -1000000.0: must be"),
    (POINT + ["--units", "SI", "--material", "{dma}", "--nu", "0.5", "--wavelength", "1e-3",
              "--amplitude", "1e-4", "--load", "-3"], "", "--load given twice"),
    (POINT[:5] + ["--speed", "1e40", "--units", "SI", "--material", "{dma}", "--nu", "0.5",
                  "--wavelength", "1e-3", "--amplitude", "1e-4"], "",
     "--speed 1e+40: must be one giving 6.28e+43 as V τ_ref k"),
    (POINT + ["--units", "SI", "--material", "{dma}", "--E0", "1e6", "--nu", "0.5",
              "--wavelength", "1e-3", "--amplitude", "1e-4"], "", "--E0 is not allowed with "
                                                                  "--material"),
    (POINT + ["--units", "SI", "--hk", "1"], "", "--hk is not allowed with --units SI"),
    (POINT + ["--nu", "0.5"], "", "--nu is not allowed without --units SI"),
    # the master curve
    (MC + ["--material", "{dma}", "--temperatures", "20", "-90", "--speeds", "1", "--out",
           "{tmp}"], "", "--temperatures -90.0: must be a finite temperature above the WLF pole"),
    (MC[:1] + ["--shift-table", "{table}"] + MC[5:] + ["--material", "{dma}",
                                                       "--temperatures", "100", "--speeds", "1",
                                                       "--out", "{tmp}"],
     "", "inside the shift table [-10.0, 80.0]"),
    (MC + ["--material", "{dma}", "--temperatures", "20", "--speeds", "-1", "--out", "{tmp}"],
     "", "--speeds -1.0 is not allowed: a finite sliding speed > 0 [m/s]"),
    (MC + ["--material", "{file}", "--temperatures", "20", "--speeds", "1", "--out", "{tmp}"],
     _spectrum_curve("frequency,storage,loss"), "must be a modulus unit the DMA header names"),
    (MC + ["--material", "{dma}", "--temperatures", "20", "--speeds", "1", "--out",
           "{file}/x"], "", "is a file, not a folder"),
]


@pytest.mark.parametrize("argv, content, fragment", BAD,
                         ids=[f"{i}-{f[:40]}" for i, (_, _, f) in enumerate(BAD)])
def test_bad_material_input_is_one_line_and_status_2(argv, content, fragment, dma, tmp_path,
                                                    capsys):
    (tmp_path / "bad.txt").write_text(content)
    (tmp_path / "shift.csv").write_text("temperature,log_aT\n-10,3\n20,0\n80,-2.5\n")
    names = {"file": tmp_path / "bad.txt", "dma": dma, "prony": PRONY2, "tmp": tmp_path,
             "table": tmp_path / "shift.csv", "sbr": SBR}
    rc, out, err = _run(capsys, *[a.format(**names) for a in argv])
    assert rc == 2, err
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith("python -m comparisons ")
    assert fragment in lines[0], lines[0]
    assert not (tmp_path / "mastercurve").exists() and not (tmp_path / "points.csv").exists()


def test_bad_input_end_to_end_is_one_line_and_status_2(tmp_path):
    (tmp_path / "dma.csv").write_text(_curve(_with(4, (GOOD[4][0], -1.0, GOOD[4][2]))))
    proc = _cli(*POINT, "--material", tmp_path / "dma.csv", cwd=tmp_path)
    assert proc.returncode == 2 and proc.stdout == ""
    assert len(proc.stderr.strip().splitlines()) == 1 and "storage modulus > 0" in proc.stderr
    assert "Traceback" not in proc.stderr


def test_the_material_module_imports_no_road_at_import():
    """comparisons._materials reaches bem only inside its functions (the record machinery of
    the analytic road must not load the BEM)."""
    code = ("import sys, comparisons._materials, comparisons.mastercurve; "
            "print('bem' in sys.modules, 'analytic' in sys.modules)")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                          cwd=ROOT)
    assert proc.stdout.split() == ["False", "False"], proc.stderr
