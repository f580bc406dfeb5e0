"""``sweep --csv FILE --plot FILE``: the table holds exactly the printed records (one row each,
its header naming every unit), in the conventions' groups or in SI; an interrupted sweep keeps
the rows and the curve of its finished points; outputs that could not be written are refused
before any work.  The semi-analytic road keeps these fast (about a second of solving)."""
import csv
import json
import math

import pytest

from comparisons import cli, runner

SLS_SI = ["--units", "SI", "--nu", "0.5", "--wavelength", "0.01", "--amplitude", "0.001",
          "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "1e-3"]
#: the first bytes of each figure format --plot writes
MAGIC = {".png": b"\x89PNG", ".pdf": b"%PDF", ".svg": b"<?xml"}


def _run(capsys, *argv):
    rc = cli.main(list(argv))
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _table(path):
    with open(path, encoding="utf-8", newline="") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


def _cell(text):
    return None if text == "" else (text if text == "analytic" else float(text))


@pytest.mark.parametrize("ext", sorted(MAGIC))
def test_the_table_is_the_printed_records_and_the_picture_is_written(capsys, tmp_path, ext):
    table, picture = tmp_path / "mu.csv", tmp_path / f"mu{ext}"
    rc, out, err = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.1", "0.3",
                        "--speed", "0.1:10:3", "--csv", str(table), "--plot", str(picture))
    assert rc == 0, err
    records = [json.loads(line) for line in out.splitlines()]
    header, rows = _table(table)
    assert header[:3] == ["load [p∞(1-ν²)/E0]", "speed [V/V0]", "mu [-]"]
    assert "penetration [Δ/h]" in header and "mu_error [-]" in header
    assert len(rows) == len(records) == 6
    for rec, row in zip(records, rows):
        cells = dict(zip(header, map(_cell, row)))
        name = {h.split(" [")[0]: h for h in header}
        for key in ("load", "speed", "mu", "tau_f", "penetration", "ka", "ke", "ke_hat",
                    "contact_fraction", "ratio", "hk"):
            assert cells[name[key]] == rec[key], key  # the same double, through repr
        assert cells["full_contact [-]"] == int(rec["full_contact"])
        assert cells["mu_error [-]"] is None  # the semi-analytic road gives no estimate
    assert picture.read_bytes()[:len(MAGIC[ext])] == MAGIC[ext]


def test_si_columns_are_the_records_si_block(capsys, tmp_path):
    table = tmp_path / "si.csv"
    rc, out, err = _run(capsys, "sweep", "--solver", "analytic", *SLS_SI, "--load", "1e5",
                        "--speed", "0.05", "0.5", "--csv", str(table), "--plot",
                        str(tmp_path / "si.png"))
    assert rc == 0, err
    records = [json.loads(line) for line in out.splitlines()]
    header, rows = _table(table)
    assert header[:4] == ["speed [m/s]", "mean_pressure [Pa]", "mu [-]", "friction_stress [Pa]"]
    for rec, row in zip(records, rows, strict=True):
        cells = dict(zip(header, map(_cell, row)))
        assert cells["speed [m/s]"] == rec["si"]["speed"]
        assert cells["mean_pressure [Pa]"] == rec["si"]["mean_pressure"]
        assert cells["contact_halfwidth [m]"] == rec["si"]["contact_halfwidth"]
        # what the SI columns mean: V = (V/V0)/(τ k), τf = μ p∞
        k = 2 * math.pi / 0.01
        assert cells["speed [m/s]"] == pytest.approx(rec["speed"] / (1e-3 * k), rel=1e-14)
        assert cells["friction_stress [Pa]"] == pytest.approx(cells["mu [-]"] * 1e5, rel=1e-12)
    assert [c["speed [m/s]"] for c in (dict(zip(header, map(_cell, r))) for r in rows)] == \
        pytest.approx([0.05, 0.5], rel=1e-14)


def test_an_interrupted_sweep_keeps_its_finished_rows_and_curve(capsys, tmp_path, monkeypatch):
    """The third point is interrupted (Ctrl-C): the two finished rows are in the table, whole,
    and the picture shows them."""
    solved = []
    real = runner.run

    def interrupted(spec, *a, **k):
        if len(solved) == 2:
            raise KeyboardInterrupt
        solved.append(spec["speed"])
        return real(spec, *a, **k)
    monkeypatch.setattr(runner, "run", interrupted)
    table, picture = tmp_path / "mu.csv", tmp_path / "mu.png"
    rc, out, err = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.3",
                        "--speed", "0.1", "1", "10", "--csv", str(table), "--plot", str(picture))
    assert rc == 130 and "interrupted" in err
    header, rows = _table(table)
    assert len(out.splitlines()) == len(rows) == 2
    assert [float(r[1]) for r in rows] == solved == [0.1, 1.0]
    assert picture.read_bytes()[:4] == MAGIC[".png"]


@pytest.mark.parametrize("option, name, message", [
    ("--plot", "mu.jpg", "--plot {}: must end in .png, .pdf, .svg"),
    ("--plot", "afile/mu.png", "--plot {}: "),     # a path through a file
    ("--csv", "afile/mu.csv", "--csv {}: "),
])
def test_an_output_that_cannot_be_written_is_refused_before_any_work(capsys, tmp_path, option,
                                                                    name, message):
    (tmp_path / "afile").write_text("")
    path = tmp_path / name
    rc, out, err = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                        option, str(path))
    assert rc == 2 and out == "" and len(err.splitlines()) == 1
    assert message.format(path) in err, err
    assert [p.name for p in tmp_path.iterdir()] == ["afile"]


@pytest.mark.parametrize("option, name", [("--plot", "new/mu.png"), ("--csv", "new/mu.csv")])
def test_a_missing_output_folder_is_made(capsys, tmp_path, option, name):
    # one rule for every command's outputs: missing folders on the way are created
    path = tmp_path / name
    rc, out, err = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                        option, str(path))
    assert rc == 0, err
    assert path.stat().st_size > 0
