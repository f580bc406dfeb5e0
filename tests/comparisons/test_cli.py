"""The command line: the contract lines end to end, every way a solve can fail (exit 1, one line,
nothing printed as a result), the last line of defence, fields CSV files and sweeps.

Most tests call `cli.main` in process (what `python -m comparisons` runs); a few run the real
command in a subprocess, end to end."""
import dataclasses
import json
import math
import os
import subprocess
import sys
import warnings

import numpy as np
import pytest

import analytic
import bem
from comparisons import cli, fields, points, runner
from comparisons import operating_point as op

KEYS = {"solver", "load", "speed", "ratio", "hk", "full_contact", "contact_fraction", "ka", "ke",
        "ke_hat", "penetration", "tau_f", "mu", "version", "success", "message", "warnings",
        "diagnostics", "error_estimate", "max_pressure", "x_max_pressure", "n_patches", "patches"}


def _cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True,
                          text=True, cwd=cwd)


def _run(capsys, *argv):
    rc = cli.main(list(argv))
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _asked(r):
    """The (load, speed) a record answers (a road may report the achieved load apart)."""
    return (r.get("load_asked") or r["load"], r["speed"])


def _read_csv(path):
    with open(path) as fh:
        lines = fh.read().splitlines()
    comments = [ln for ln in lines if ln.startswith("#")]
    rest = [ln for ln in lines if not ln.startswith("#")]
    return comments, rest[0].split(","), np.array([r.split(",") for r in rest[1:]], dtype=float)


# ------------------------------------------------------------------------------ end to end
def test_point_end_to_end_prints_one_json_object_and_a_commented_csv(tmp_path):
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
    assert "nodes" not in rec or rec["nodes"] is None  # the fields' points are not a mesh
    comments, header, data = _read_csv(csv_path)
    assert header == ["x_over_lambda", "pressure", "displacement", "gap"]
    assert any("operating point: solver=analytic load=0.3 speed=1.0" in c for c in comments)
    assert "# points: 256" in comments and any("units:" in c for c in comments)
    assert any(c.startswith("# viscosine ") for c in comments)
    assert data.shape == (256, 4)
    assert data[0, 0] == -0.5 and data[128, 0] == 0.0
    assert np.all(data[:, 1] >= 0) and np.all(data[:, 3] >= 0)
    assert abs(data[:, 1].mean() - 0.3) < 5e-3  # midpoint rule of a √-edged field
    # a CSV reader that drops the # lines reads the columns by name
    import csv
    with open(csv_path) as fh:
        rows = list(csv.DictReader(line for line in fh if not line.startswith("#")))
    assert len(rows) == 256 and float(rows[128]["x_over_lambda"]) == 0.0
    assert [p.name for p in tmp_path.iterdir()] == ["f.csv"]  # no temporary file left


def test_bem_point_and_sweep_end_to_end_with_files(tmp_path):
    (tmp_path / "profile.txt").write_text("# k y over one period\n" + "\n".join(
        repr(math.cos(2 * math.pi * (j / 64 - 0.5)) + 0.2 * math.cos(6 * math.pi * (j / 64 - 0.5)))
        for j in range(64)) + "\n")
    (tmp_path / "prony.txt").write_text("J0 1.0\n0.5 1.0\n0.2 0.01\n")
    proc = _cli("point", "--solver", "bem", "--nodes", "1024", "--load", "0.2", "--speed", "1",
                "--profile", "profile.txt", "--prony", "prony.txt", "--fields", "f.csv",
                cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["mu"] > 0 and rec["nodes"] == 1024 and rec["iterations"] >= 0
    assert rec["hk"] is None and rec["ratio"] is None  # the files fix them
    import hashlib
    for key, name in (("profile_file", "profile.txt"), ("prony_file", "prony.txt")):
        assert rec[key]["path"] == str(tmp_path / name)
        assert rec[key]["sha256"] == hashlib.sha256((tmp_path / name).read_bytes()).hexdigest()
    comments, _, data = _read_csv(tmp_path / "f.csv")
    assert data.shape == (1024, 4) and any("sha256=" in c for c in comments)
    proc = _cli("sweep", "--solver", "bem", "--nodes", "512", "--load", "0.3", "1.0",
                "--speed", "0.5", "2", "--workers", "2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    recs = [json.loads(line) for line in proc.stdout.splitlines()]
    assert [_asked(r) for r in recs] == [(0.3, 0.5), (0.3, 2.0), (1.0, 0.5), (1.0, 2.0)]
    assert [r["full_contact"] for r in recs] == [False, False, True, True]


def test_odd_input_end_to_end_is_one_line_and_status_2(tmp_path):
    proc = _cli("point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "7")
    assert proc.returncode == 2 and proc.stdout == ""
    assert len(proc.stderr.strip().splitlines()) == 1 and "Traceback" not in proc.stderr


# ------------------------------------------------------------------------------ in process
def test_point_with_penetration_reports_the_load(capsys):
    rc, out, _ = _run(capsys, "point", "--solver", "analytic", "--penetration", "0.8", "--speed", "1")
    rec = json.loads(out)
    assert rc == 0
    assert rec["penetration"] == pytest.approx(0.8, rel=1e-13)
    assert rec["load"] == pytest.approx(analytic.solve(penetration=0.8, speed=1.0).load, rel=1e-15)


def test_full_contact_ke_is_null(capsys):
    rc, out, _ = _run(capsys, "point", "--solver", "analytic", "--load", "1.6", "--speed", "1")
    rec = json.loads(out)
    assert rc == 0 and rec["full_contact"] is True and rec["ke"] is None
    assert rec["ka"] == pytest.approx(np.pi)


def test_bem_record_is_complete(capsys):
    rc, out, _ = _run(capsys, "point", "--solver", "bem", "--load", "0.3", "--speed", "1",
                      "--nodes", "512")
    rec = json.loads(out)
    assert rc == 0 and KEYS | {"nodes", "iterations", "profile_file", "prony_file"} <= set(rec)
    assert rec["nodes"] == 512 and rec["success"] is True and rec["n_patches"] == 1
    assert rec["profile_file"] is None and rec["prony_file"] is None


@pytest.mark.parametrize("exc", [OverflowError("math range error"), ZeroDivisionError("float division"),
                                 FloatingPointError("overflow encountered"),
                                 np.linalg.LinAlgError("Singular matrix"),
                                 ValueError("f(a) and f(b) must have different signs"),
                                 MemoryError(), RuntimeError("did not converge"),
                                 KeyError("x"), AssertionError("internal")])
@pytest.mark.parametrize("solver", ["analytic", "bem"])
def test_every_exception_of_a_solve_is_one_line_and_status_1(exc, solver, monkeypatch, capsys):
    def boom(**kw):
        raise exc
    monkeypatch.setattr(analytic if solver == "analytic" else bem, "solve", boom)
    rc, out, err = _run(capsys, "point", "--solver", solver, "--load", "0.3", "--speed", "1",
                        *(["--nodes", "64"] if solver == "bem" else []))
    assert rc == 1 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and "could not solve" in lines[0] and type(exc).__name__ in lines[0]


def _patched_analytic(monkeypatch, **changes):
    real = analytic.solve

    def fake(**kw):
        return dataclasses.replace(real(**kw), **changes)
    monkeypatch.setattr(analytic, "solve", fake)


@pytest.mark.parametrize("changes,fragment", [
    ({"mu": math.nan}, "mu = "),      # nan, or null where the road writes JSON-ready records
    ({"ka": math.inf}, "ka = "),
    ({"penetration": 1.5}, "outside (0, 1]"),
    ({"penetration": 0.0}, "outside (0, 1]"),
    ({"ka": 4.0}, "outside (0, π]"),
    ({"mu": -0.1}, "mu = -0.1 < 0"),
    ({"tau_f": -1e-3}, "tau_f"),
    ({"contact_fraction": 1.2}, "contact_fraction"),
    ({"load": 0.31}, "is not the 0.3 asked for"),
])
def test_an_invalid_result_is_never_printed(changes, fragment, monkeypatch, capsys):
    _patched_analytic(monkeypatch, **changes)
    rc, out, err = _run(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")
    assert rc == 1 and out == ""
    assert len(err.strip().splitlines()) == 1 and fragment in err and "invalid result" in err


def test_null_is_only_accepted_where_it_means_something():
    spec = op.at("analytic", 1.0, load=0.3)
    rec = analytic.solve(load=0.3, speed=1.0).as_dict()
    rec.update(n_patches=1, success=True)
    assert runner.check_record(rec, spec) is None
    assert "ke = null with a single contact patch" in runner.check_record({**rec, "ke": None}, spec)
    assert runner.check_record({**rec, "ka": None, "ke": None, "ke_hat": None, "n_patches": 2},
                               spec) is None                    # several patches
    full = analytic.solve(load=1.6, speed=1.0).as_dict()
    full.update(n_patches=1, success=True)
    assert full["ke"] is None and runner.check_record(full, {**spec, "load": 1.6}) is None
    assert "mu = null" in runner.check_record({**rec, "mu": None}, spec)


def test_bem_fields_are_checked_negative_pressure_interpenetration_load(monkeypatch, capsys):
    real = bem.solve
    for mutate, fragment in [(lambda r: {"pressure": r.pressure - 0.5 * r.pressure.max()}, "negative pressure"),
                             (lambda r: {"gap": r.gap - 1e-3}, "interpenetration"),
                             (lambda r: {"pressure": r.pressure * 1.01}, "mean σ")]:
        def fake(**kw):
            r = real(**kw)
            return dataclasses.replace(r, **mutate(r))
        monkeypatch.setattr(bem, "solve", fake)
        rc, out, err = _run(capsys, "point", "--solver", "bem", "--load", "0.3", "--speed", "1",
                            "--nodes", "256")
        assert rc == 1 and out == "" and fragment in err, err


def test_unconverged_point_is_reported_not_printed(monkeypatch, capsys):
    """A failed solve goes to stderr with its residuals, exit status 1, nothing on stdout."""
    _patched_analytic(monkeypatch, success=False, status=1, message="root search did not converge")
    rc, out, err = _run(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")
    assert rc == 1 and out == ""
    assert "root search did not converge" in err and "residuals" in err
    assert len(err.strip().splitlines()) == 1


def test_bem_accuracy_target_not_reached_is_status_1_with_the_estimate(monkeypatch, capsys):
    real = bem.solve
    msg = "accuracy target not reached: estimated error 3.2e-05 > rtol 1e-06 at max_nodes 65536"

    def fake(**kw):
        return dataclasses.replace(real(**kw), success=False, status=4, message=msg)
    monkeypatch.setattr(bem, "solve", fake)
    rc, out, err = _run(capsys, "point", "--solver", "bem", "--load", "0.3", "--speed", "1",
                        "--nodes", "256")
    assert rc == 1 and out == "" and "estimated error 3.2e-05" in err
    assert len(err.strip().splitlines()) == 1


def test_warnings_go_to_stderr_one_line_each_and_the_result_is_printed(monkeypatch, capsys):
    real = analytic.solve

    def noisy(**kw):
        warnings.warn("overflow encountered in exp", RuntimeWarning)
        warnings.warn("second caveat", UserWarning)
        return real(**kw)
    monkeypatch.setattr(analytic, "solve", noisy)
    rc, out, err = _run(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")
    rec = json.loads(out)
    assert rc == 0
    assert "RuntimeWarning: overflow encountered in exp" in rec["warnings"]
    lines = err.strip().splitlines()
    assert lines == ["point: warning: RuntimeWarning: overflow encountered in exp",
                     "point: warning: UserWarning: second caveat"]


def test_a_fields_file_that_cannot_be_written_is_status_1(monkeypatch, tmp_path, capsys):
    def refuse(src, dst):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr("os.replace", refuse)  # the one atomic writer's rename
    rc, out, err = _run(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                        "--fields", str(tmp_path / "f.csv"))
    assert rc == 1 and out == "" and "No space left on device" in err
    assert list(tmp_path.iterdir()) == []  # the temporary file is removed


def test_fields_are_written_atomically_under_a_unique_temporary_name(monkeypatch, tmp_path):
    seen = []
    real = os.replace

    def spy(src, dst):
        seen.append(os.path.basename(src))
        return real(src, dst)
    monkeypatch.setattr("os.replace", spy)
    f = analytic.solve(load=0.3, speed=1.0).fields(np.arange(16) / 16 - 0.5)
    fields.write_fields_csv(tmp_path / "a.csv", f)
    fields.write_fields_csv(tmp_path / "a.csv", f)
    assert len(seen) == 2 and seen[0] != seen[1]
    assert all(f".{os.getpid()}." in s and s.startswith(".a.csv.") for s in seen)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["a.csv"]


# ------------------------------------------------------------------------------ sweeps
def test_log_ranges():
    assert cli.log_range("1e-2:1e2:5") == [0.01, 0.1, 1.0, 10.0, 100.0]
    vals = cli.log_range("0.3:3:41")
    assert len(vals) == 41 and vals[0] == 0.3 and vals[-1] == 3.0  # both ends exactly
    assert np.allclose(np.diff(np.log(vals)), math.log(10) / 40, rtol=1e-12)
    assert cli.log_range("2:2:1") == [2.0]
    assert cli.log_range("10:1:3") == [10.0, pytest.approx(10 ** 0.5), 1.0]  # decreasing is fine
    assert cli.log_range("0.25") == [0.25]


def test_sweep_order_ranges_and_lists_mix(capsys):
    rc, out, _ = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.2", "0.1:1:2",
                      "--speed", "1e-1:1e1:3")
    recs = [json.loads(line) for line in out.splitlines()]
    assert rc == 0
    assert [_asked(r) for r in recs] == [(p, s) for p in (0.2, 0.1, 1.0)
                                                       for s in (0.1, 1.0, 10.0)]
    for r in recs:  # the record is the road's own as_dict (plus what the command line adds)
        ref = analytic.solve(load=r["load"], speed=r["speed"]).as_dict()
        assert {k: r[k] for k in ref} == ref


@pytest.mark.parametrize("workers", [None, "2"])
def test_a_failing_point_is_reported_and_the_others_come_out(workers, monkeypatch, capsys):
    real = analytic.solve

    def flaky(**kw):
        if kw.get("load") == 0.5 and kw["speed"] == 2.0:
            raise ZeroDivisionError("float division by zero")
        if kw.get("load") == 0.2 and kw["speed"] == 3.0:
            return dataclasses.replace(real(**kw), mu=math.nan)
        return real(**kw)
    monkeypatch.setattr(analytic, "solve", flaky)  # forked workers inherit the patch
    argv = ["sweep", "--solver", "analytic", "--load", "0.2", "0.5", "--speed", "1", "2", "3"]
    rc, out, err = _run(capsys, *argv, *(["--workers", workers] if workers else []))
    recs = [json.loads(line) for line in out.splitlines()]
    assert rc == 1
    assert [_asked(r) for r in recs] == [(0.2, 1.0), (0.2, 2.0), (0.5, 1.0), (0.5, 3.0)]
    lines = err.strip().splitlines()
    assert any(ln.startswith("sweep: point 3/6 (load=0.2, speed=3.0): invalid result: mu = ")
               and ln.endswith("is not a finite number") for ln in lines)
    assert ("sweep: point 5/6 (load=0.5, speed=2.0): could not solve: ZeroDivisionError: float "
            "division by zero") in lines
    assert lines[-1] == "sweep: 2 of 6 points could not be solved"


def test_sweep_fields_one_file_per_point_named_after_it(tmp_path, capsys):
    out_dir = tmp_path / "fields"
    rc, out, _ = _run(capsys, "sweep", "--solver", "analytic", "--load", "0.3", "0.3", "1e-05",
                      "--speed", "1", "0.1:10:3", "--fields", str(out_dir), "--nodes", "32")
    assert rc == 0 and len(out.splitlines()) == 12
    names = sorted(p.name for p in out_dir.iterdir())
    assert "analytic_load0.3_speed1.csv" in names and "analytic_load1e-05_speed0.1.csv" in names
    # a repeated point gets its own file (the index of the point), nothing is overwritten
    assert "analytic_load0.3_speed1_5.csv" in names and len(names) == 12
    for n in names:
        assert all(c.isalnum() or c in "._+-" for c in n)
        comments, header, data = _read_csv(out_dir / n)
        assert data.shape == (32, 4) and header[0] == "x_over_lambda"
    rc, out, _ = _run(capsys, "sweep", "--solver", "bem", "--penetration", "0.8", "--speed", "1",
                      "--nodes", "64", "--fields", str(out_dir))
    assert rc == 0 and (out_dir / "bem_penetration0.8_speed1.csv").exists()


def test_field_file_names_are_unique_and_safe():
    used = set()
    spec = {"solver": "bem", "load": 1e20, "penetration": None, "speed": 1.0 / 3.0}
    a = points.field_file_name(spec, used, 0)
    b = points.field_file_name(spec, used, 7)
    assert a == "bem_load1e+20_speed0.3333333333333333.csv" and b.endswith("_8.csv") and a != b


def test_penetration_sweep_and_the_conventions_lines(capsys):
    rc, out, _ = _run(capsys, "sweep", "--solver", "analytic", "--penetration", "0.5", "0.9",
                      "--speed", "1", "--ratio", "3", "--hk", "1")
    assert rc == 0 and [json.loads(x)["penetration"] for x in out.splitlines()] == \
        [pytest.approx(0.5, rel=1e-12), pytest.approx(0.9, rel=1e-12)]
    rc, out, _ = _run(capsys, "sweep", "--solver", "bem", "--load", "0.3", "--speed", "1",
                      "--ratio", "3", "--hk", "1", "--nodes", "128")
    assert rc == 0 and json.loads(out)["nodes"] == 128
