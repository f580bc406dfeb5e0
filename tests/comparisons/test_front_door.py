"""Through the front door: the command line on the points a contact window answers, whose fields
are on a non-uniform grid (fine window panels, coarse periodic ones), and the `viscosine.Fields`
quadrature that makes them usable.

The command line runs in a subprocess, as a user runs it; its JSON is judged against the
semi-analytic road within the record's own error estimate (× 3, the honesty studies' bound).
"""
import csv
import json
import math
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

import analytic
import bem
from comparisons import fields, runner, suite
from comparisons import operating_point as op
from conftest import ROUNDOFF
from viscosine import Fields

DATA = Path(suite.__file__).resolve().parent / "data" / "suite"
#: the honesty studies' bound on a true error, in units of the record's own estimate
ESTIMATE_FACTOR = 3.0
#: scalars judged: (key, relative?), as `error_estimate` measures them (conventions)
JUDGED = (("mu", True), ("tau_f", True), ("penetration", True), ("contact_fraction", True),
          ("ka", False), ("ke", False), ("ke_hat", False))


def _cli(*args, cwd=None):
    proc = subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True,
                          text=True, cwd=cwd)
    assert "Traceback" not in proc.stderr
    return proc


def _within_estimate(rec, ref):
    """Every judged scalar of the record within ESTIMATE_FACTOR × its estimate of the reference."""
    est = rec["error_estimate"]
    assert est is not None, rec["message"]
    for key, rel in JUDGED:
        a, b, e = rec[key], getattr(ref, key), est.get(key)
        assert a is not None and b is not None and e is not None, key
        err = abs(a - b) / abs(b) if rel else abs(a - b)
        assert err <= ESTIMATE_FACTOR * e, (key, a, b, err, e)


# ------------------------------------------------------------------------------ window points
@pytest.mark.parametrize("load, speed, ratio", [
    (1e-6, 1.0, 3.0), pytest.param(1e-5, 0.01, 300.0, marks=pytest.mark.slow)],  # stiff: 12 s
                         ids=["light", "stiff"])
def test_a_window_point_is_answered_by_point_and_its_fields_carry_the_load(tmp_path, load,
                                                                           speed, ratio):
    path = tmp_path / "f.csv"
    proc = _cli("point", "--solver", "bem", "--load", repr(load), "--speed", repr(speed),
                "--ratio", repr(ratio), "--fields", str(path))
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["success"] and rec["diagnostics"]["window"]["outcome"] == "target met"
    _within_estimate(rec, analytic.solve(load=load, speed=speed, ratio=ratio))
    # the CSV states its grid; a plain CSV reader and the weights of its width column give back
    # the load (the gate's figure: the mean over the period, not the mean of the rows)
    lines = path.read_text().splitlines()
    assert runner.GRID_NON_UNIFORM in [ln[2:] for ln in lines if ln.startswith("#")]
    with open(path) as fh:
        rows = list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))
    p = np.array([float(r["pressure"]) for r in rows])
    w = np.array([float(r["width"]) for r in rows])
    assert abs(math.fsum(w) - 1.0) <= ROUNDOFF
    assert abs(math.fsum(w * p) / rec["load"] - 1.0) <= 1e-9
    assert abs(p.mean() / rec["load"] - 1.0) > 1.0  # why a plain mean of the rows is wrong
    f = Fields.from_columns(fields.read_fields_csv(path))
    assert not f.uniform and f.x_over_lambda.size == len(rows)
    assert abs(f.mean("pressure") / rec["load"] - 1.0) <= 1e-9
    assert abs(f.mean("displacement")) <= 1e-9  # v from the mean line of the deformed surface
    assert abs(f.mean("gap") - rec["separation"]) <= 1e-9  # the mean gap is s/h
    g = fields.read_fields_csv(path)  # verify's reader takes the same file
    assert np.array_equal(g["width"], f.widths)


def test_a_sweep_of_window_points_prints_every_answer():
    loads = (1e-6, 1e-8)
    proc = _cli("sweep", "--solver", "bem", "--load", *map(repr, loads), "--speed", "1")
    assert proc.returncode == 0, proc.stderr
    recs = [json.loads(ln) for ln in proc.stdout.splitlines()]
    assert [r["load_asked"] for r in recs] == list(loads)
    for rec, load in zip(recs, loads):
        assert rec["diagnostics"]["window"]["outcome"] == "target met"
        _within_estimate(rec, analytic.solve(load=load, speed=1.0))


# ------------------------------------------------------------------------------ input files
def _certified(case, rec, keys=("mu", "penetration", "tau_f")):
    """The record against a suite case's certified values: within their certified error plus
    ESTIMATE_FACTOR × the record's estimate (both are relative for these keys)."""
    for k in keys:
        c = case["certified"]["scalars"][k]
        err = abs(rec[k] - c["value"]) / abs(c["value"])
        assert err <= c["error"] / abs(c["value"]) + ESTIMATE_FACTOR * rec["error_estimate"][k], \
            (case["name"], k, rec[k], c["value"])


def test_a_prony_file_point_end_to_end():
    case = suite.get_case("prony2-partial")
    prony = DATA / case["point"]["prony"]
    proc = _cli("point", "--solver", "bem", "--prony", str(prony), "--load", "0.3",
                "--speed", "1")
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["ratio"] is None and rec["prony_file"]["path"] == str(prony)
    _certified(case, rec)


def test_a_prony_file_window_point_is_the_solver_s_own_answer():
    prony = DATA / "materials" / "prony2.txt"
    proc = _cli("point", "--solver", "bem", "--prony", str(prony), "--load", "1e-6",
                "--speed", "1")
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["diagnostics"]["window"]["outcome"] == "target met"
    r = bem.solve(load=1e-6, speed=1.0, material=bem.read_prony(prony))
    for key, _ in JUDGED:
        assert rec[key] == getattr(r, key)
    assert abs(r.fields().mean("pressure") / r.load - 1.0) <= ROUNDOFF


def test_a_profile_file_point_end_to_end(tmp_path):
    case = suite.get_case("harmonics2-sls")
    profile = DATA / case["point"]["profile"]
    path = tmp_path / "f.csv"
    proc = _cli("point", "--solver", "bem", "--profile", str(profile), "--load", "0.2",
                "--speed", "1", "--fields", str(path))
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["hk"] is None and rec["profile_file"]["path"] == str(profile)
    _certified(case, rec)
    f = Fields.from_columns(fields.read_fields_csv(path))  # no window on a profile: uniform
    header = next(ln for ln in path.read_text().splitlines() if not ln.startswith("#"))
    assert f.uniform and header == "x_over_lambda,pressure,displacement,gap"
    assert "# " + runner.GRID_UNIFORM in path.read_text().splitlines()
    assert abs(f.mean("pressure") / 0.2 - 1.0) <= 1e-9


def test_the_suite_s_uniform_fields_files_still_read():
    for path in sorted((DATA / "fields").glob("*.csv")):
        f = Fields.from_columns(fields.read_fields_csv(path))
        cols = fields.read_fields_csv(path)
        assert f.uniform and "width" not in cols
        assert np.array_equal(f.widths, np.full(256, 1 / 256))


# ------------------------------------------------------------------------------ Fields
def _example():
    """Five cells of widths 1/4, 1/4, 1/8, 1/8, 1/4 over [−½, ½); pressure 0, 1, 4, 2, 0."""
    edges = np.array([-0.5, -0.25, 0.0, 0.125, 0.25, 0.5])
    x = np.array([-0.375, -0.125, 0.0625, 0.1875, 0.375])
    return Fields(x, [0.0, 1.0, 4.0, 2.0, 0.0], [1.0, -1.0, 0.0, 2.0, -1.0],
                  [2.0, 0.0, 0.0, 0.0, 4.0], edges=edges)


def test_fields_quadrature_on_a_small_non_uniform_grid():
    f = _example()
    assert not f.uniform
    assert np.array_equal(f.widths, [0.25, 0.25, 0.125, 0.125, 0.25])
    # mean σ = 1/4 + 4/8 + 2/8 = 1 (a plain mean of the values would say 7/5)
    assert f.mean("pressure") == 1.0 and f.integral("pressure") == 1.0
    assert f.mean("displacement") == 0.25 * 1 - 0.25 * 1 + 0.125 * 2 - 0.25 * 1
    assert f.mean("gap") == 0.5 + 1.0
    assert f.mean(f.pressure * f.gap) == 0.0  # complementarity, an array on the grid
    assert abs(f.l2("pressure") - math.sqrt(0.25 * 1 + 0.125 * 16 + 0.125 * 4)) <= ROUNDOFF
    assert f.linf("pressure") == 4.0 and f.linf("displacement") == 2.0
    # a sub-interval cuts cells: [−1/8, 1/16] holds 1/8 of σ = 1 and 1/16 of σ = 4
    assert abs(f.integral("pressure", -0.125, 0.0625) - 0.375) <= ROUNDOFF
    # periodic: two periods from any start hold twice the load
    assert abs(f.integral("pressure", -0.3, 1.7) - 2.0) <= ROUNDOFF
    with pytest.raises(ValueError):
        f.mean("stress")


def test_fields_resample_average_conserves_and_linear_interpolates():
    f = _example()
    # new cells [−5/8, −3/8], [−3/8, −1/8], [−1/8, 1/8], [1/8, 3/8]
    a = f.resample(4)
    assert a.uniform and np.array_equal(a.x_over_lambda, [-0.5, -0.25, 0.0, 0.25])
    assert np.allclose(a.pressure, [0.0, 0.5, 2.5, 1.0], rtol=0, atol=ROUNDOFF)
    assert abs(a.mean("pressure") - 1.0) <= ROUNDOFF
    assert abs(f.resample(8).mean("pressure") - 1.0) <= ROUNDOFF
    lin = f.resample(4, method="linear")  # between (−1/8, 1) and (1/16, 4) at 0: 1 + 3·(2/3)
    assert np.allclose(lin.pressure, [0.0, 0.5, 3.0, 4.0 / 3.0], rtol=0, atol=ROUNDOFF)
    with pytest.raises(ValueError):
        f.resample(0)
    with pytest.raises(ValueError):
        f.resample(4, method="cubic")


def test_fields_uniform_grid_unchanged_and_cells_checked():
    x = np.arange(8) / 8 - 0.5
    p = np.arange(8.0)
    u = Fields(x, p, p, p)
    assert u.uniform and u.edges is None and "width" not in u.as_dict()
    assert u.mean("pressure") == float(np.mean(p)) and np.array_equal(u.widths, np.full(8, 1 / 8))
    assert np.array_equal(u.resample(8).pressure, p)  # its own cells
    # widths give the same cells as edges (the first cell centred on its point)
    f = _example()
    g = Fields.from_columns(f.as_dict())
    assert np.array_equal(g.edges, f.edges)
    with pytest.raises(ValueError, match="one period"):
        Fields(x, p, p, p, widths=np.full(8, 0.1))
    with pytest.raises(ValueError, match="outside its cell"):
        Fields(x[::-1], p, p, p, edges=u.cell_edges)
    with pytest.raises(ValueError, match="not a uniform grid"):
        Fields(x ** 3, p, p, p).mean("pressure")


def test_a_window_result_s_fields_tile_the_period_with_its_panels(tmp_path):
    r = bem.solve(load=1e-6, speed=1.0)
    f = r.fields()
    win = r.diagnostics["window"]
    assert not f.uniform and np.array_equal(f.x_over_lambda, r.x_over_lambda)
    w = f.widths
    x = f.x_over_lambda
    fine = (x > win["from_x_over_lambda"]) & (x < win["to_x_over_lambda"])
    assert np.all(w[fine] == 1.0 / r.nodes)  # the window's panels keep their width
    # the coarse panels theirs, but the two next to the window, cut or stretched to meet it
    coarse = np.flatnonzero(w > 1.0 / r.nodes)
    assert np.sum(w[coarse] != 1.0 / win["coarse_nodes"]) == 2
    assert f.cell_edges[-1] - f.cell_edges[0] == 1.0
    assert abs(f.mean("pressure") / r.load - 1.0) <= ROUNDOFF
    # the runner answers it, and its cells survive the results store and the CSV
    from comparisons.store import Store
    spec = op.build("bem", load=1e-6, speed=1.0)
    out = runner.run(spec, fields=True, deep=True)
    assert out["ok"], out["error"]
    st = Store(str(tmp_path / "store"), note=lambda _: None)
    st.put(spec, out, fields=True)
    back = Fields.from_columns(st.get(spec, fields=True)["fields"])
    assert np.array_equal(back.edges, f.edges) and back.mean("pressure") == f.mean("pressure")
    fields.write_fields_csv(tmp_path / "f.csv", f)
    assert np.array_equal(Fields.from_columns(fields.read_fields_csv(tmp_path / "f.csv")).edges,
                          f.edges)
