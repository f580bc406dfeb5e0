"""A surface through the front doors: `point` and `sweep` with --surface answer what
`bem.solve_surface` answers (to the bit), write the fields as .npz, and refuse every odd surface
input with one line on standard error, exit status 2 and nothing on standard output.  Run in
process (`cli.main`)."""
import json

import numpy as np
import pytest

import bem
from comparisons import cli

POINT = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "64"]


def _run(capsys, argv):
    rc = cli.main(list(argv))
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def _same(rec, want):
    for key in ("mu", "mu_lateral", "contact_fraction", "penetration", "separation", "tau_f",
                "n_patches", "max_pressure", "nodes", "error_estimate", "patches"):
        assert rec[key] == want[key], key


@pytest.mark.parametrize("extra, surface, direction", [
    (["--surface", "bisinusoid"], bem.bisinusoid(1.0), 0.0),
    (["--surface", "bisinusoid", "--hk", "0.5", "--hk-y", "0.2", "--aspect", "2",
      "--direction", "30"], bem.bisinusoid(0.5, 0.2, aspect=2.0), 30.0),
    (["--surface", "self-affine", "--hurst", "0.8", "--rolloff", "2", "--short-cutoff", "6",
      "--rms-slope", "0.3", "--seed", "5", "--direction", "-45"],
     bem.self_affine(hurst=0.8, rolloff=2, short_cutoff=6, rms_slope=0.3, seed=5), -45.0),
])
def test_point_answers_what_python_answers(extra, surface, direction, capsys, tmp_path):
    f = tmp_path / "fields.npz"
    rc, out, err = _run(capsys, POINT + extra + ["--fields", str(f)])
    assert rc == 0, err
    rec = json.loads(out)
    ref = bem.solve_surface(load=0.3, speed=1.0, surface=surface, direction=direction, nodes=64)
    _same(rec, json.loads(json.dumps(ref.as_dict())))
    assert rec["direction"] == direction and rec["geometry"] == "surface"
    data = np.load(f)
    assert np.array_equal(data["pressure"], ref.pressure)
    assert np.array_equal(data["gap"], ref.gap)
    assert data["x"].shape == (64,) and float(data["direction"]) == direction


def test_surface_file_and_sweep(capsys, tmp_path):
    z = bem.self_affine(hurst=0.7, rolloff=2, short_cutoff=5, rms_slope=0.3, seed=1).sample(16, 16)
    path = tmp_path / "heights.txt"
    np.savetxt(path, z)
    rc, out, err = _run(capsys, ["sweep", "--solver", "bem", "--surface", str(path), "--load",
                                 "0.05", "0.1", "--speed", "0.5", "2", "--nodes", "64",
                                 "--fields", str(tmp_path / "f")])
    assert rc == 0, err
    recs = [json.loads(line) for line in out.splitlines()]
    assert [(r["load_asked"], r["speed"]) for r in recs] == [(0.05, 0.5), (0.05, 2.0),
                                                             (0.1, 0.5), (0.1, 2.0)]
    ref = bem.solve_surface(load=0.1, speed=2.0, surface=bem.sampled_surface(z), nodes=64)
    assert recs[-1]["mu"] == ref.mu
    assert len(list((tmp_path / "f").glob("*.npz"))) == 4


@pytest.mark.parametrize("extra, says", [
    (["--surface", "bisinusoid", "--hurst", "0.5"], "--hurst is not allowed"),
    (["--surface", "self-affine", "--hurst", "1.5", "--rolloff", "2", "--short-cutoff", "4",
      "--rms-slope", "0.1"], "--hurst 1.5: must be"),
    (["--surface", "self-affine", "--hurst", "0.5", "--rolloff", "2", "--short-cutoff", "4"],
     "exactly one of rms_slope and rms_height"),
    (["--surface", "self-affine", "--hk", "1", "--hurst", "0.5", "--rolloff", "2",
      "--short-cutoff", "4", "--rms-slope", "0.1"], "--hk is not allowed"),
    (["--surface", "bisinusoid", "--direction", "nan"], "--direction nan: must be"),
    (["--surface", "bisinusoid", "--aspect", "0"], "--aspect 0.0: must be"),
    (["--direction", "30"], "--direction is not allowed without --surface"),
    (["--surface", "bisinusoid", "--hk-y", "-1"], "--hk-y -1.0: must be"),
    (["--surface", "nofile.txt"], "--surface nofile.txt"),
])
def test_bad_surface_input_is_one_line_and_exit_2(extra, says, capsys):
    argv = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1"] + extra
    rc, out, err = _run(capsys, argv)
    assert rc == 2 and out == ""
    assert len(err.strip().splitlines()) == 1 and says in err, err


def test_bad_files_and_grids_are_refused(capsys, tmp_path):
    ramp = tmp_path / "ramp.txt"
    np.savetxt(ramp, np.add.outer(np.linspace(0, 1, 16), np.zeros(16)))
    nan = tmp_path / "nan.txt"
    z = bem.bisinusoid(1.0).sample(8, 8)
    z[2, 3] = np.nan
    np.savetxt(nan, z)
    ragged = tmp_path / "ragged.txt"
    ragged.write_text("1 2 3 4\n1 2 3 4\n1 2 3\n1 2 3 4\n")
    for path, says in ((ramp, "tiles the plane"), (nan, "finite"), (ragged, "rectangular")):
        rc, out, err = _run(capsys, POINT[:-2] + ["--surface", str(path)])
        assert rc == 2 and out == "" and says in err, err
    # a grid that would not fit in memory: refused up front with the size asked and available
    rc, out, err = _run(capsys, POINT[:-2] + ["--surface", "bisinusoid", "--nodes", "65536"])
    assert rc == 2 and out == "" and "GiB" in err and "memory" in err
    # a grid too coarse for the surface's modes
    rc, out, err = _run(capsys, POINT[:-2] + ["--surface", "self-affine", "--hurst", "0.5",
                                              "--rolloff", "4", "--short-cutoff", "20",
                                              "--rms-slope", "0.1", "--nodes", "16"])
    assert rc == 2 and out == "" and "--nodes 16: must be" in err, err


def test_the_readme_surface_command_prints_what_it_says(capsys, tmp_path):
    """The README's surface command, run as written (its --fields into a temporary folder),
    prints the values the README quotes."""
    import re
    import shlex
    from pathlib import Path
    text = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    line = next(ln for ln in text.splitlines()
                if ln.startswith("python -m comparisons point") and "--surface" in ln)
    promised = text.split(line, 1)[1].splitlines()[1]
    argv = shlex.split(line)[3:]
    argv[argv.index("--fields") + 1] = str(tmp_path / "p.npz")
    rc, out, err = _run(capsys, argv)
    assert rc == 0, err
    rec = json.loads(out)
    for key, value in re.findall(r'"(\w+)": ([-\d.e]+)', promised):
        assert repr(rec[key]) == value, key


def test_si_surfaces_answer_what_the_groups_answer(capsys, tmp_path):
    """--units SI with a surface FILE in metres (--wavelength is the cell's side Lx) and with
    the bi-sinusoid of --amplitude h [m] answer what the conventions' groups answer, and carry
    the SI block; bem.solve_surface_si likewise."""
    import math
    lx, nu, e0 = 0.01, 0.5, 5e6
    k, estar = 2 * math.pi / lx, e0 / (1 - nu ** 2)
    surf = bem.bisinusoid(0.1)
    path = tmp_path / "metres.txt"
    np.savetxt(path, surf.sample(32, 32) / k)
    si = ["--units", "SI", "--wavelength", str(lx), "--nu", str(nu), "--E0", str(e0),
          "--Einf", str(3 * e0), "--tau-creep", "1e-3", "--load", repr(0.03 * estar),
          "--speed", repr(1.0 / (1e-3 * k)), "--nodes", "64"]
    ref = bem.solve_surface(load=0.03, speed=1.0, surface=surf, nodes=64)
    for extra in (["--surface", str(path)], ["--surface", "bisinusoid", "--amplitude",
                                            repr(0.1 / k)]):
        rc, out, err = _run(capsys, ["point", "--solver", "bem"] + si + extra)
        assert rc == 0, err
        rec = json.loads(out)
        assert rec["mu"] == pytest.approx(ref.mu, rel=1e-10)
        assert rec["si"]["mean_pressure"] == pytest.approx(0.03 * estar, rel=1e-12)
        assert rec["si"]["penetration"] == pytest.approx(ref.penetration * 0.2 / k, rel=1e-9)
    r = bem.solve_surface_si(nu=nu, length=lx, speed=1.0 / (1e-3 * k), heights=surf.sample(
        32, 32) / k, E0=e0, Einf=3 * e0, tau_creep=1e-3, mean_pressure=0.03 * estar, nodes=64)
    assert r.success and r.mu == pytest.approx(ref.mu, rel=1e-10)
    assert r.friction_stress == pytest.approx(ref.tau_f * estar, rel=1e-10)
    for extra, says in ((["--surface", str(path), "--amplitude", "1e-4"], "--amplitude"),
                        (["--surface", "self-affine"], "--surface self-affine is not allowed")):
        rc, out, err = _run(capsys, ["point", "--solver", "bem"] + si + extra)
        assert rc == 2 and out == "" and says in err, err
