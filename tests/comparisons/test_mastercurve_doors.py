"""``mastercurve``'s doors: one temperature without a shift (the material as given, a_T = 1) and
the standard linear solid as ``--E0 --Einf --tau-creep | --tau-relax`` (as ``point --units SI``
takes it), judged against the semi-analytic road in SI; what does not fit is refused before any
work, one line, status 2."""
import csv
import json
import math

import pytest

import analytic
from comparisons import cli, mastercurve

#: a standard linear solid and a sinusoid in SI (E∞/E0 = 3, hk = 2π/10)
SLS = {"E0": 1e6, "Einf": 3e6, "tau_creep": 1e-3}
GEOMETRY = ["--load", "1e5", "--wavelength", "0.01", "--amplitude", "0.001", "--nu", "0.5"]
SPEEDS = (0.02, 0.2)
#: the honesty studies' bound on a true error, in units of the record's own estimate
ESTIMATE_FACTOR = 3.0


def _run(capsys, *argv):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _points(folder):
    with open(folder / "points.csv", encoding="utf-8") as fh:
        return list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))


def test_the_standard_linear_solid_at_one_temperature_is_the_semi_analytic_answer(capsys,
                                                                                  tmp_path):
    """--E0 --Einf --tau-creep, no shift: each μ within its own estimate (× 3) of
    analytic.solve_si on the same SI problem; --tau-relax τ E0/E∞ gives the same curve."""
    rows = {}
    for name, time in (("creep", ["--tau-creep", "1e-3"]),
                       ("relax", ["--tau-relax", repr(1e-3 * 1e6 / 3e6)])):
        out = tmp_path / name
        rc, _, err = _run(capsys, "mastercurve", "--E0", "1e6", "--Einf", "3e6", *time,
                          "--temperatures", "23", "--speeds", *SPEEDS, *GEOMETRY,
                          "--rtol", "1e-4", "--out", out)
        assert rc == 0, err
        rows[name] = _points(out)
        doc = json.loads((out / "mastercurve.json").read_text(encoding="utf-8"))
        assert doc["parameters"]["shift"] == {"kind": "none", "T_ref": 23.0}
    for row, speed in zip(rows["creep"], SPEEDS, strict=True):
        assert row["success"] == "1" and float(row["temperature"]) == 23.0
        assert float(row["log10_aT"]) == 0.0 and float(row["reduced_speed"]) == speed
        ref = analytic.solve_si(mean_pressure=1e5, speed=speed, wavelength=0.01, amplitude=0.001,
                                nu=0.5, **SLS)
        mu, est = float(row["mu"]), float(row["mu_error"])
        assert est <= 1e-4 and abs(mu / ref.friction_coefficient - 1) <= ESTIMATE_FACTOR * est
    for a, b in zip(rows["creep"], rows["relax"], strict=True):
        assert float(a["mu"]) == pytest.approx(float(b["mu"]), rel=1e-9)


def test_the_model_is_the_papers_solid():
    """E(t) = E0 + (E∞ − E0) e^(−t/θ) with θ = τ E0/E∞ (eq. 2.3's creep time τ)."""
    m = mastercurve.standard_linear_solid(2e6, 8e6, tau_creep=0.4)
    assert (m.E_r, m.E, m.theta) == (2e6, (6e6,), (pytest.approx(0.1, rel=1e-15),))
    assert mastercurve.standard_linear_solid(2e6, 8e6, tau_relax=0.1).theta == (0.1,)
    shift = mastercurve.NoShift(20.0)
    assert shift.log10_aT(20.0) == 0.0
    with pytest.raises(ValueError, match="T=40.0 is not allowed: without a shift"):
        shift.log10_aT(40.0)


SLS_ARGS = ["--E0", "1e6", "--Einf", "3e6", "--tau-creep", "1e-3"]


@pytest.mark.parametrize("argv, message", [
    (SLS_ARGS + ["--temperatures", "20", "40"],
     "--temperatures 20 40 is not allowed without --wlf or --shift-table"),
    (["--temperatures", "20"], "the material is missing: --material FILE, or --E0"),
    (["--material", "x.csv", "--E0", "1e6", "--temperatures", "20"],
     "--E0 is not allowed with --material"),
    (["--E0", "1e6", "--tau-creep", "1", "--temperatures", "20"], "--Einf is missing"),
    (["--E0", "1e6", "--Einf", "1e6", "--tau-creep", "1", "--temperatures", "20"],
     "--Einf 1000000.0 is not allowed: a finite modulus > --E0 1e+06 [Pa]"),
    (["--E0", "1e6", "--Einf", "3e6", "--temperatures", "20"],
     "--tau-creep or --tau-relax (exactly one) is required"),
    (SLS_ARGS + ["--tau-relax", "1", "--temperatures", "20"],
     "--tau-relax is not allowed with --tau-creep"),
    (SLS_ARGS + ["--max-residual", "0.1", "--temperatures", "20"],
     "--max-residual is not allowed here: it applies to a DMA curve (--material FILE with "
     "E', E'')"),
    (SLS_ARGS + ["--loss-weight", "0", "--temperatures", "20"],
     "--loss-weight is not allowed here: it applies to a DMA curve"),
    (["--E0", "1e6", "--Einf", "3e6", "--tau", "1", "--temperatures", "20"], "which time?"),
])
def test_what_does_not_fit_is_refused_before_any_work(capsys, tmp_path, argv, message):
    out = tmp_path / "out"
    rc, stdout, err = _run(capsys, "mastercurve", *argv, "--speeds", "0.1", *GEOMETRY,
                           "--out", out)
    assert rc == 2 and stdout == "" and len(err.splitlines()) == 1, err
    assert message in err and len(err.rstrip("\n")) <= 160, err
    assert not out.exists()


def test_the_surviving_shift_options_still_shift(capsys, tmp_path):
    """With --wlf the SLS's times move by a_T: at T the point (V, T) is (a_T V, T_ref), so its
    speed group is a_T times that of T_ref (the solve itself is the other tests')."""
    plan, params = mastercurve.prepare(
        mastercurve.standard_linear_solid(**SLS), shift=__import__("viscosine").materials.WLF(
            8.86, 101.6, 20.0), temperatures=[20.0, 40.0], speeds=[0.1], mean_pressure=1e5,
        wavelength=0.01, amplitude=0.001, nu=0.5, nodes=256)
    (t0, v0, la0, s0), (t1, v1, la1, s1) = plan
    assert la0 == 0.0 and la1 == pytest.approx(-8.86 * 20 / (101.6 + 20), rel=1e-14)
    assert s1["speed"] == s0["speed"]  # the group is V k x 1 s; the material's times moved
    tau0 = s0["material"]["log10_aT"], s1["material"]["log10_aT"]
    assert tau0 == (0.0, la1) and math.isfinite(la1)
