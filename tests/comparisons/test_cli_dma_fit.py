"""The DMA fit on the command line: ``--loss-weight`` and ``--nu`` reach the fit and the reader
(point, sweep, mastercurve), are refused where no DMA curve is fitted, and every command that
fits a curve writes its figure ``<stem>_fit.png`` (point and sweep beside the command,
mastercurve into --out).  Every run has its own folder as the current one."""
import json
import pathlib

import numpy as np
import pytest

from comparisons import cli
from viscosine.materials import (WLF, Maxwell, fit_prony, isotherm_rows, lognormal_series,
                                 read_dma, time_rows, write_card)

from conftest import ROUNDOFF

#: a relaxation spectrum on the fit's grid (the fit is exact) and its curve, window 1e-2 … 1e3
SPECTRUM = Maxwell(1.0, tuple([10.0 / 13] * 13), tuple(np.logspace(-4.0, 2.0, 13).tolist()))
OMEGA = np.logspace(-2.0, 3.0, 41)
NU = 0.4
POINT = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "1024"]
SWEEP = ["sweep", "--solver", "bem", "--load", "0.3", "--speed", "1", "2", "--nodes", "1024"]
MC = ["mastercurve", "--temperatures", "20", "--speeds", "1e-3", "--load", "1e5",
      "--wavelength", "1e-3", "--amplitude", "1e-4", "--nu", "0.5", "--nodes", "1024"]
FIT_ONLY = "--loss-weight is not allowed here: it applies to a DMA curve (--material FILE with E', E'')"


def _curve(path, header, factor=1.0, loss_factor=1.0):
    """The curve written to ``path``; its name as typed (relative to the current folder)."""
    e = SPECTRUM.modulus(OMEGA)
    path.write_text(header + "\n" + "".join(
        f"{float(w)!r},{float(s) * factor!r},{float(lo) * factor * loss_factor!r}\n"
        for w, s, lo in zip(OMEGA, e.real, e.imag)))
    return pathlib.Path(path.name)


@pytest.fixture
def here(tmp_path, monkeypatch):
    """A fresh current folder (the figures of point and sweep are written there)."""
    monkeypatch.chdir(tmp_path)
    return tmp_path


@pytest.fixture
def tensile(here):
    return _curve(here / "tensile.csv", "frequency [rad/s],storage [MPa],loss [MPa]")


@pytest.fixture
def shear(here):
    """The same material as G', G'' (E = 2 (1 + ν) G with ν = NU)."""
    return _curve(here / "shear.csv", "frequency [rad/s],G' [MPa],G'' [MPa]",
                  1.0 / (2.0 * (1.0 + NU)))


@pytest.fixture
def inconsistent(here):
    """E'' twice what E' implies: no series meets both, so the weight moves the fit."""
    return _curve(here / "inconsistent.csv", "frequency [rad/s],storage [MPa],loss [MPa]",
                  loss_factor=2.0)


def _run(capsys, *argv):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _records(capsys, *argv):
    rc, out, err = _run(capsys, *argv)
    assert rc == 0, err
    return [json.loads(line) for line in out.splitlines()], err


def _refused(capsys, *argv):
    rc, out, err = _run(capsys, *argv)
    assert rc == 2 and out == "", err
    lines = err.strip().splitlines()
    assert len(lines) == 1 and len(lines[0]) <= 200, err
    return lines[0]


# ------------------------------------------------------------------------------ --loss-weight
@pytest.mark.parametrize("weight", [0.0, 100.0])
def test_loss_weight_is_the_fit_of_that_weight(inconsistent, weight, capsys):
    (rec,), _ = _records(capsys, *POINT, "--material", inconsistent, "--loss-weight", weight)
    fit = rec["material"]["fit"]
    want = fit_prony(read_dma(inconsistent), loss_weight=weight).fit
    assert fit["loss_weight"] == weight
    assert (fit["storage_rms"], fit["loss_rms"]) == (want.storage_rms, want.loss_rms)
    equal = fit_prony(read_dma(inconsistent)).fit
    # the weight moves the fit: E' alone is met better, E'' followed better
    if weight == 0.0:
        assert fit["storage_rms"] < 0.5 * equal.storage_rms
    else:
        assert fit["loss_rms"] < 0.5 * equal.loss_rms


def test_sweep_and_mastercurve_take_the_loss_weight(inconsistent, here, capsys):
    recs, _ = _records(capsys, *SWEEP, "--material", inconsistent, "--loss-weight", "0")
    assert [r["material"]["fit"]["loss_weight"] for r in recs] == [0.0, 0.0]
    rc, _, err = _run(capsys, *MC, "--material", inconsistent, "--loss-weight", "0",
                      "--out", here / "mc")
    assert rc == 0, err
    doc = json.loads((here / "mc" / "mastercurve.json").read_text())
    assert doc["parameters"]["material"]["fit"]["loss_weight"] == 0.0


@pytest.mark.parametrize("argv", [
    POINT + ["--loss-weight", "0"],
    SWEEP + ["--loss-weight", "0"],
    MC + ["--E0", "1e6", "--Einf", "3e6", "--tau-creep", "1", "--loss-weight", "0"],
], ids=["point", "sweep", "mastercurve"])
def test_loss_weight_without_a_dma_curve_is_refused(argv, here, capsys):
    assert _refused(capsys, *argv).endswith(FIT_ONLY)
    assert not list(here.iterdir())


def test_loss_weight_with_a_series_file_is_refused(here, capsys):
    (here / "relax.txt").write_text("E_r 1\n2 0.5\n")
    series = "relax.txt"
    line = _refused(capsys, *POINT, "--material", series, "--loss-weight", "0")
    assert line.endswith("--loss-weight 0.0: not for a relaxation series (it applies to a DMA "
                         "curve or raw isotherms)")
    assert "--max-residual 0.1: not for a relaxation series" in _refused(
        capsys, *POINT, "--material", series, "--max-residual", "0.1")


def test_a_bad_loss_weight_is_named(tensile, capsys):
    line = _refused(capsys, *POINT, "--material", tensile, "--loss-weight", "-1")
    assert "--loss-weight -1.0: must be a weight >= 0" in line


# ------------------------------------------------------------------------------ --nu and G', G''
def test_a_shear_curve_with_nu_is_its_tensile_twin(tensile, shear, here, capsys):
    (e,), _ = _records(capsys, *POINT, "--material", tensile)
    (g,), _ = _records(capsys, *POINT, "--material", shear, "--nu", NU)
    assert g["material"]["shear_nu"] == NU and "shear_nu" not in e["material"]
    for k in ("mu", "penetration", "contact_fraction", "ka"):
        assert g[k] == pytest.approx(e[k], rel=1e-9, abs=ROUNDOFF), k
    # --units SI: the problem's --nu converts the curve too
    si = ["--units", "SI", "--wavelength", "1e-3", "--amplitude", "1e-4", "--nu", NU]
    (e_si,), _ = _records(capsys, *POINT[:3], "--speed", "1e-3", "--nodes", "1024", "--load",
                          "1e5", *si, "--material", tensile)
    (g_si,), _ = _records(capsys, *POINT[:3], "--speed", "1e-3", "--nodes", "1024", "--load",
                          "1e5", *si, "--material", shear)
    assert g_si["mu"] == pytest.approx(e_si["mu"], rel=1e-9)
    # the master curve reads it with its own --nu
    mc = [a if a != "0.5" else str(NU) for a in MC]
    for name, f in (("e", tensile), ("g", shear)):
        rc, _, err = _run(capsys, *mc, "--material", f, "--out", here / name)
        assert rc == 0, err
    mu = [json.loads((here / n / "mastercurve.json").read_text())["points"][0]["mu"]
          for n in ("e", "g")]
    assert mu[1] == pytest.approx(mu[0], rel=1e-9)


def test_nu_is_asked_for_a_shear_curve_and_refused_where_unused(tensile, shear, capsys):
    assert "it holds shear moduli G', G'': give --nu" in _refused(
        capsys, *POINT, "--material", shear)
    assert "--nu 0.7: must be a Poisson ratio" in _refused(
        capsys, *POINT, "--material", shear, "--nu", "0.7")
    assert "--nu 0.4 is not allowed here: without --units SI, only for a layer" in _refused(
        capsys, *POINT, "--material", tensile, "--nu", "0.4")
    assert "--nu is not allowed without --units SI" in _refused(capsys, *POINT, "--nu", "0.4")


# ------------------------------------------------------------------------------ shear data
#: the truth of the shear data below (tensile, MPa, s) and its Poisson ratio: G = E/(2 (1 + ν))
TRUTH = lognormal_series(1.0, 100.0, centre=-1.0, decades=6.0, per_decade=2.0)
TO_G = 1.0 / (2.0 * (1.0 + NU))
SHEAR_TRUTH = Maxwell(TRUTH.E_r * TO_G, tuple(e * TO_G for e in TRUTH.E), TRUTH.theta)
ISO_WLF = WLF(8.86, 101.6, 20.0)
SI = ["--units", "SI", "--load", "3e5", "--speed", "1.6e-4", "--wavelength", "1e-3",
      "--amplitude", "1e-4", "--nu", NU]


def _shear_files(here):
    """The truth as a relaxation series (MPa) and as each kind of shear data (MPa), the way a
    lab or an FE program writes it: G(t), isotherms of G', G'', an LS-DYNA card (its BULK
    fixes ν = NU), a pyvisco table of G_0, G_i; the isotherms also as E', E'' (their twin)."""
    for name, unit in (("truth.txt", 1.0), ("truth_pa.txt", 1e6)):  # MPa; Pa (for SI)
        (here / name).write_text(f"E_r {TRUTH.E_r * unit!r}\n" + "".join(
            f"{e * unit!r} {t!r}\n" for e, t in zip(TRUTH.E, TRUTH.theta)))
    rows = time_rows(SHEAR_TRUTH, np.logspace(-5.0, 3.0, 41))
    (here / "gt.csv").write_text("time [s],G [MPa]\n" + "".join(f"{t!r},{g!r}\n"
                                                              for t, g in rows))
    for name, model, head in (("giso.csv", SHEAR_TRUTH, "G' [MPa],G'' [MPa]"),
                              ("eiso.csv", TRUTH, "storage [MPa],loss [MPa]")):
        rows = isotherm_rows(model, ISO_WLF, np.arange(-10.0, 61.0, 10.0),
                             np.logspace(-1.0, 2.0, 13))
        (here / name).write_text(f"temperature [degC],frequency [Hz],{head}\n" + "".join(
            ",".join(repr(v) for v in r) + "\n" for r in rows))
    write_card(here / "g.lsdyna", TRUTH, "lsdyna", nu=NU)
    g0 = SHEAR_TRUTH.glassy
    (here / "g.pyvisco").write_text("i,tau_i,alpha_i,G_0,G_i\n-,s,-,MPa,MPa\n" + "".join(
        f"{k + 1},{t!r},{g / g0!r},{g0!r},{g!r}\n"
        for k, (g, t) in enumerate(zip(SHEAR_TRUTH.E, SHEAR_TRUTH.theta))))


@pytest.fixture
def shear_data(here):
    _shear_files(here)
    return here


@pytest.mark.parametrize("name", ["gt.csv", "g.lsdyna", "g.pyvisco"])
def test_shear_data_with_nu_give_the_truth_they_were_built_from(shear_data, name, capsys):
    """G(t) (fitted exactly: the truth's times lie on the fit's grid) and the two shear cards,
    turned into E = 2 (1 + ν) G by --nu, give the point of the tensile truth."""
    (want,), _ = _records(capsys, *POINT, "--material", "truth.txt")
    (got,), _ = _records(capsys, *POINT, "--material", name, "--nu", NU)
    assert got["material"]["shear_nu"] == pytest.approx(NU, abs=1e-12)
    # the groups are in E_ref: a fitted G(t) has E_ref = its fitted E_r, which only the factor
    # 2 (1 + ν) makes the truth's (else the factor cancels from every group); a card's unit
    assert got["material"]["E_ref"] == pytest.approx(
        TRUTH.E_r if name == "gt.csv" else 1.0, rel=1e-9)
    for key in ("mu", "penetration", "contact_fraction"):
        assert got[key] == pytest.approx(want[key], rel=1e-9), key


def test_lsdyna_takes_its_nu_from_bulk_and_refuses_another(shear_data, capsys):
    (rec,), _ = _records(capsys, *POINT, "--material", "g.lsdyna")
    assert rec["material"]["shear_nu"] == pytest.approx(NU, abs=1e-12)
    line = _refused(capsys, *POINT, "--material", "g.lsdyna", "--nu", "0.3")
    assert "--nu 0.3 contradicts the LS-DYNA card's ν = 0.4 (from BULK" in line


def test_an_lsdyna_card_in_si_has_one_nu_for_e_and_the_plane_strain_modulus(here, capsys):
    """A card whose BULK fixes ν0 = 0.4995: --nu 0.5 (within `NU_AGREE`, so taken) gives the
    point of --nu 0.4995, both E = 2 (1 + ν0) G and E* = E/(1 - ν0²) with ν0, echoed as the
    problem's ν (mixing them would move E* by 7e-4)."""
    from viscosine.materials._cards import NU_AGREE
    nu0 = 0.4995
    in_pa = Maxwell(TRUTH.E_r * 1e6, tuple(e * 1e6 for e in TRUTH.E), TRUTH.theta)
    write_card(here / "near.lsdyna", in_pa, "lsdyna", nu=nu0, unit="Pa")
    si = [a for a in SI if a not in ("--nu", NU)]
    recs, warned = [], []
    for nu in ("0.5", repr(nu0)):
        (rec,), err = _records(capsys, "point", *si, "--solver", "bem", "--nodes", "1024",
                               "--nu", nu, "--material", "near.lsdyna")
        recs.append(rec)
        warned.append(err)
    assert warned[0] == warned[1] and "linear theory" not in warned[0]  # a modulus in Pa
    assert abs(0.5 - nu0) <= NU_AGREE
    for rec in recs:
        assert rec["material"]["shear_nu"] == pytest.approx(nu0, abs=1e-12)
        assert rec["si_scales"]["nu"] == rec["material"]["shear_nu"]
    assert recs[0]["si_scales"] == recs[1]["si_scales"]
    assert recs[0]["mu"] == recs[1]["mu"] and recs[0]["load"] == recs[1]["load"]
    # mastercurve: the same one ν
    mc = [a for a in MC if a not in ("--nu", "0.5")]
    docs = []
    for nu in ("0.5", repr(nu0)):
        rc, _, err = _run(capsys, *mc, "--nu", nu, "--material", "near.lsdyna", "--out",
                          here / f"mc{nu}")
        assert rc == 0, err
        docs.append(json.loads((here / f"mc{nu}" / "mastercurve.json").read_text()))
    assert [d["parameters"]["nu"] for d in docs] == [recs[0]["si_scales"]["nu"]] * 2
    assert docs[0]["points"][0]["mu"] == docs[1]["points"][0]["mu"]


def test_shear_isotherms_with_nu_are_their_tensile_twin_and_near_the_truth(shear_data, capsys):
    """Isotherms of G', G'' with --nu: the point of the same isotherms written as E', E''
    (one factor on every isotherm: the same shifts, the same fit), and within the fit's
    residual of the truth (SI: both in MPa, so the fitted E_r does not enter the groups)."""
    at = ["--temperature", "20"]
    (g,), _ = _records(capsys, *POINT, *at, "--material", "giso.csv", "--nu", NU)
    (e,), _ = _records(capsys, *POINT, *at, "--material", "eiso.csv")
    assert g["material"]["shear_nu"] == NU and "shear_nu" not in e["material"]
    assert g["material"]["superposition"]["wlf"]["C1"] == pytest.approx(
        e["material"]["superposition"]["wlf"]["C1"], rel=1e-9)
    for key in ("mu", "penetration"):
        assert g[key] == pytest.approx(e[key], rel=1e-9), key
    (gs,), _ = _records(capsys, "point", *SI, "--solver", "bem", "--nodes", "1024", *at,
                        "--material", "giso.csv")
    (ts,), _ = _records(capsys, "point", *SI, "--solver", "bem", "--nodes", "1024",
                        "--material", "truth_pa.txt")
    assert gs["mu"] == pytest.approx(ts["mu"], rel=2e-3)


@pytest.mark.parametrize("name,holds", [("gt.csv", "a shear modulus G(t)"),
                                        ("giso.csv", "shear isotherms G', G''"),
                                        ("g.pyvisco", "shear moduli G_0, G_i")])
def test_shear_data_without_nu_ask_for_it(shear_data, name, holds, capsys):
    argv = POINT + (["--temperature", "20"] if name == "giso.csv" else [])
    line = _refused(capsys, *argv, "--material", name)
    assert line.endswith(f"--material {name}: it holds {holds}: give --nu, a Poisson ratio in "
                         "(-1, 0.5] (E = 2 (1 + ν) G)") and len(line) <= 160, line
    assert _refused(capsys, *argv, "--material", name, "--nu", "0.7").endswith(
        "--nu 0.7: must be a Poisson ratio in (-1, 0.5]")


def test_mastercurve_takes_shear_data_with_its_nu(shear_data, here, capsys):
    """mastercurve's --nu (required: the problem's) converts the G(t) table too."""
    mc = [a for a in MC if a not in ("--nu", "0.5")] + ["--nu", NU]
    for name in ("gt.csv", "truth_pa.txt"):       # MPa in its header; a series in Pa
        rc, _, err = _run(capsys, *mc, "--material", name, "--out", here / name[:-4])
        assert rc == 0, err
    got, want = (json.loads((here / n / "mastercurve.json").read_text())
                 for n in ("gt", "truth_pa"))
    assert got["parameters"]["material"]["shear_nu"] == NU
    assert got["points"][0]["mu"] == pytest.approx(want["points"][0]["mu"], rel=1e-9)


# ------------------------------------------------------------------------------ keyword <-> flag
def _parser_of(command):
    sub = next(a for a in cli.build_parser()._actions if a.dest == "command")
    return {o: a.dest for a in sub.choices[command]._actions for o in a.option_strings}


def test_every_keyword_of_the_materials_api_has_its_flag_and_back():
    """`_materials.FLAGS` lists every keyword of every reader and fit a --material file goes
    through (read from their signatures), each with the flag that gives it on point, sweep
    and mastercurve (the flag's value lands in that keyword) or a reason for none; and every
    flag that `dma_fit_options` declares is one of those keywords."""
    import argparse
    import inspect

    from comparisons import _materials
    from comparisons.cli._common import dma_fit_options
    from viscosine import materials as vm
    for func, table in _materials.FLAGS.items():
        params = list(inspect.signature(getattr(vm, func)).parameters)[1:]
        assert set(params) == set(table), func
        for keyword, flag in table.items():
            if flag is None:
                assert _materials.NO_FLAG[keyword], keyword
                continue
            for command in ("point", "sweep", "mastercurve"):
                # mastercurve's temperatures are --temperatures: its isotherms' own is
                # --reference-temperature
                f = ("--reference-temperature" if (command, flag) == ("mastercurve",
                                                                      "--temperature")
                     else flag)
                dests = _parser_of(command)
                assert f in dests, (command, f)
                want = "reference_temperature" if f == "--reference-temperature" else (
                    "temperature" if f == "--temperature" else keyword)
                assert dests[f] == want, (command, f)
    declared = argparse.ArgumentParser()
    dma_fit_options(declared)
    flags = {o: a.dest for a in declared._actions for o in a.option_strings}
    flags.pop("-h"), flags.pop("--help")
    assert flags == {f: k for k, f in _materials.FLAG_OF.items()
                     if f not in ("--nu", "--temperature")}


def test_each_new_flag_is_the_python_keyword(shear_data, tensile, here, capsys):
    """--extend, --material-kind, --frequency-unit, --vertical-shift, --shift-method give the
    fits the Python API makes with the same keywords."""
    from viscosine.materials import read_sweeps, superpose
    (rec,), _ = _records(capsys, *POINT, "--material", tensile, "--extend", "2")
    want = fit_prony(read_dma(tensile), extend=2.0).fit
    assert rec["material"]["fit"]["candidates"] == want.candidates
    assert rec["material"]["read_options"] == {"extend": 2.0}
    # a curve whose header names no unit: Hz multiplies every frequency by 2 pi
    bare = _curve(here / "bare.csv", "f,storage,loss")
    (hz,), _ = _records(capsys, *POINT, "--material", bare, "--frequency-unit", "Hz")
    assert hz["material"]["measured_window"] == pytest.approx(
        [2 * np.pi * OMEGA[0], 2 * np.pi * OMEGA[-1]], rel=ROUNDOFF)
    # storage/loss say no kind: G with --nu is the shear twin of the tensile curve
    neutral = _curve(here / "neutral.csv", "frequency [rad/s],storage [MPa],loss [MPa]",
                     1.0 / (2.0 * (1.0 + NU)))
    (g,), _ = _records(capsys, *POINT, "--material", neutral, "--material-kind", "G",
                       "--nu", NU)
    (e,), _ = _records(capsys, *POINT, "--material", tensile)
    assert g["mu"] == pytest.approx(e["mu"], rel=1e-9) and g["material"]["shear_nu"] == NU
    # E_ref is the fitted E_r: the same as the tensile twin's only with the factor 2 (1 + ν)
    assert g["material"]["E_ref"] == pytest.approx(e["material"]["E_ref"], rel=1e-9)
    # --per-decade and --extend reach the time-domain fit too
    (gt,), _ = _records(capsys, *POINT, "--material", "gt.csv", "--nu", NU, "--per-decade",
                        "3", "--extend", "0.5")
    from viscosine.materials import fit_time_data, read_time_data
    want = fit_time_data(read_time_data("gt.csv").tensile(NU), per_decade=3.0, extend=0.5).fit
    assert (gt["material"]["fit"]["per_decade"], gt["material"]["fit"]["candidates"]) == (
        3.0, want.candidates)
    (iso,), _ = _records(capsys, *POINT, "--temperature", "20", "--material", "eiso.csv",
                         "--vertical-shift", "none", "--shift-method", "tan_delta")
    sp = superpose(read_sweeps("eiso.csv"), 20.0, method="tan_delta")
    got = iso["material"]["superposition"]
    assert (got["method"], got["vertical"]) == ("tan_delta", None)
    assert got["wlf"]["C1"] == sp.wlf.wlf.C1


@pytest.mark.parametrize("argv,said", [
    (["--material", "truth.txt", "--extend", "2"], "--extend 2.0: not for a relaxation series "
     "(it applies to a DMA curve, raw isotherms or an E(t)/J(t) table)"),
    (["--material", "gt.csv", "--nu", NU, "--shift-method", "tan_delta"], "--shift-method "
     "tan_delta: not for an E(t) or J(t) table (it applies to raw isotherms)"),
    (["--material", "giso.csv", "--nu", NU, "--temperature", "20", "--material-kind", "E"],
     "--material-kind E: not for raw isotherms (it applies to a DMA curve)"),
    (["--material", "gt.csv", "--nu", NU, "--extend", "7"],
     "--extend 7.0: must be decades in [0, 5]"),
    (["--extend", "1"], "--extend is not allowed here: it applies to a --material file"),
    (["--material", "tensile.csv", "--extend", "9"], "--extend 9.0: must be decades in [0, 5]"),
    (["--material", "tensile.csv", "--nu", NU, "--material-kind", "E"],
     "--nu 0.4: not with --material-kind E (ν converts shear moduli only)"),
    (["--material", "tensile.csv", "--material-kind", "G"], "--nu is missing: --material-kind "
     "G needs it, a Poisson ratio in (-1, 0.5] (E = 2 (1 + ν) G)"),
], ids=["series", "time", "isotherms", "range", "no-material", "dma-range", "nu-with-E",
        "G-without-nu"])
def test_the_new_flags_are_refused_where_they_do_not_apply(shear_data, tensile, argv, said,
                                                           capsys):
    """One form (``--flag value: ...``), whichever reader or fit refuses."""
    line = _refused(capsys, *POINT, *argv)
    assert said in line and len(line) <= 160, line


# ------------------------------------------------------------------------------ the fit figure
def test_point_and_sweep_write_the_fit_figure_beside_the_command(tensile, here, capsys):
    for argv, command in ((POINT, "point"), (SWEEP, "sweep")):
        figure = here / "tensile_fit.png"
        if figure.exists():
            figure.unlink()
        _, err = _records(capsys, *argv, "--material", tensile)
        assert figure.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
        said = [ln for ln in err.splitlines() if ln.startswith(f"{command}: DMA fit of ")]
        assert len(said) == 1 and said[0].endswith("wrote ./tensile_fit.png"), err
    # a series file: nothing fitted, no figure
    series = here / "relax.txt"
    series.write_text("E_r 1\n2 0.5\n")
    _, err = _records(capsys, *SWEEP, "--material", series)
    assert "DMA fit" not in err and not list(here.glob("relax*.png"))


def test_mastercurve_writes_the_fit_figure_into_out(tensile, here, capsys):
    rc, _, err = _run(capsys, *MC, "--material", tensile, "--out", here / "mc")
    assert rc == 0, err
    assert (here / "mc" / "tensile_fit.png").read_bytes()[:4] == b"\x89PNG"
    assert not list(here.glob("*.png"))          # nothing beside the command
    assert f"mastercurve: DMA fit of {here / tensile}" in err
