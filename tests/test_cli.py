"""The command line end to end (conventions.md): point, sweep, fields CSV, failure reporting."""
import csv
import json
import subprocess
import sys

import numpy as np
import pytest

import analytic
from comparisons import cli

KEYS = {"solver", "load", "speed", "ratio", "hk", "full_contact", "contact_fraction", "ka", "ke",
        "ke_hat", "penetration", "tau_f", "mu"}


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True,
                          text=True, cwd=cwd)


def test_point_prints_one_json_object_with_every_key(tmp_path):
    csv_path = tmp_path / "f.csv"
    proc = _cli("point", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                "--fields", str(csv_path), "--nodes", "256")
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.strip().splitlines()
    assert len(lines) == 1
    rec = json.loads(lines[0])
    assert KEYS <= set(rec)
    ref = analytic.solve(load=0.3, speed=1.0)
    assert rec["ka"] == ref.ka and rec["mu"] == ref.mu and rec["full_contact"] is False
    with open(csv_path) as fh:
        rows = list(csv.reader(fh))
    assert rows[0] == ["x_over_lambda", "pressure", "displacement", "gap"]
    data = np.array(rows[1:], dtype=float)
    assert data.shape == (256, 4)
    assert data[0, 0] == -0.5 and data[128, 0] == 0.0
    assert np.all(data[:, 1] >= 0) and np.all(data[:, 3] >= 0)
    assert abs(data[:, 1].mean() - 0.3) < 5e-3  # midpoint rule of a √-edged field


def test_point_with_penetration_reports_the_load():
    proc = _cli("point", "--solver", "analytic", "--penetration", "0.8", "--speed", "1")
    rec = json.loads(proc.stdout)
    assert rec["penetration"] == pytest.approx(0.8, rel=1e-13)
    assert rec["load"] == pytest.approx(analytic.solve(penetration=0.8, speed=1.0).load, rel=1e-15)


def test_full_contact_ke_is_null():
    rec = json.loads(_cli("point", "--solver", "analytic", "--load", "1.6", "--speed", "1").stdout)
    assert rec["full_contact"] is True and rec["ke"] is None and rec["ka"] == pytest.approx(np.pi)


@pytest.mark.parametrize("workers", ["1", "2"])
def test_sweep_order_loads_outer_speeds_inner(workers):
    proc = _cli("sweep", "--solver", "analytic", "--load", "0.2", "0.8", "--speed", "0.1", "1", "10",
                "--workers", workers)
    assert proc.returncode == 0, proc.stderr
    recs = [json.loads(line) for line in proc.stdout.strip().splitlines()]
    assert [(r["load"], r["speed"]) for r in recs] == [(l, s) for l in (0.2, 0.8) for s in (0.1, 1.0, 10.0)]
    for r in recs:
        assert r == analytic.solve(load=r["load"], speed=r["speed"]).as_dict()


def test_unconverged_point_is_reported_not_printed(monkeypatch, capsys):
    """A failed solve goes to stderr with its residuals, exit status 1, nothing on stdout."""
    real = analytic.solve

    def failing(*a, **k):
        sol = real(*a, **k)
        return type(sol)(**{**sol.__dict__, "success": False, "status": 1,
                            "message": "root search did not converge"})
    monkeypatch.setattr(analytic, "solve", failing)
    rc = cli.main(["point", "--solver", "analytic", "--load", "0.3", "--speed", "1"])
    out = capsys.readouterr()
    assert rc == 1 and out.out == ""
    assert "not converged" in out.err and "residuals" in out.err
    rc = cli.main(["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1", "2"])
    out = capsys.readouterr()
    assert rc == 1 and out.out == "" and out.err.count("not converged") == 2
