"""`verify` on the suite's surface cases: the defaults pass two correct solvers (viscosine's
surface BEM and the independent surface reference, each on a moderate grid), and fail fields
one panel off and a μ 2 % off, naming the slip; other slips diagnosed, the report files, bad
input, and the Python API."""
import json

import numpy as np
import pytest

from analytic.references import surface as sr
from comparisons import cli, suite, verify
from comparisons.verify import _surface_fields

CASE = "surface-bisinusoid-v1"
OBLIQUE = "surface-anisotropic-30deg"
LAYER = "surface-layer-bonded-d0.5"


def _run(capsys, *argv):
    rc = cli.main(["verify", *argv])
    out = capsys.readouterr()
    return rc, out.out, out.err


def _verdict(folder):
    return json.loads((folder / "verdict.json").read_text(encoding="utf-8"))


def _bem(case, nodes):
    return verify.viscosine_bem(suite.get_case(case)["point"], nodes)


def _write_npz(path, fields, **extra):
    np.savez(path, **fields, **extra)
    return str(path)


REFERENCE_SOLVER = """import numpy as np
from analytic.references import surface as sr

class Out:
    def __init__(self, r, own):
        self.fields = {"x": r.x, "y": r.y, "pressure": r.pressure,
                       "displacement": r.displacement, "gap": r.gap}
        self.scalars = {k: getattr(r, k) for k in own}

def _solve(point, nodes):
    s = point["surface"]
    hk = s["hk"]
    hk_y = hk if s.get("hk_y") is None else s["hk_y"]
    return sr.solve(load=point["load"], speed=point["speed"], direction=point["direction"],
                    ratio=point["ratio"], heights={(1, 0): hk, (0, 1): hk_y},
                    nodes=(nodes // 4, nodes // 2, nodes))

def solve(point, nodes):
    return Out(_solve(point, nodes), ("mu", "mu_lateral", "penetration", "contact_fraction"))

def fields_only(point, nodes):
    return Out(_solve(point, nodes), ())
"""


# ---------------------------------------------------------------------------- correct solvers
def test_defaults_pass_viscosine_surface_bem_and_state_each_tolerance(tmp_path, capsys):
    rc, out, err = _run(capsys, "--case", CASE, "--callable", "comparisons.verify:viscosine_bem",
                        "--nodes", "64", "128", "--out", str(tmp_path))
    assert rc == 0, out + err
    doc = _verdict(tmp_path)
    assert doc["geometry"] == "surface" and doc["verdict"] == "PASS" and doc["nodes"] == 128
    keys = [q["key"] for q in doc["quantities"]]
    assert keys == list(verify.SURFACE_KEYS)
    for q in doc["quantities"]:
        assert q["tolerance_reason"] and q["difference"] <= q["tolerance"], q
    assert "tolerance: μ: " in out and "e_N: what viscosine's surface BEM" in out
    assert "orders vs reference: mu " in out and "verify: PASS" in err
    assert "certified values of the suite case surface-bisinusoid-v1" in (
        tmp_path / "report.md").read_text(encoding="utf-8")
    assert (tmp_path / "report.html").read_text(encoding="utf-8").count(
        "data:image/png;base64,") == 1
    # the same fields as a file of the conventions, every scalar derived from them
    f = _bem(CASE, 64).fields
    path = _write_npz(tmp_path / "bem64.npz", f, load=0.3, speed=1.0, direction=0.0)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", path, "--out", str(tmp_path / "f"),
                        "--no-figures")
    assert rc == 0, out + err
    assert _verdict(tmp_path / "f")["results"][0]["source"] == "fields"


@pytest.mark.parametrize("case", [CASE, OBLIQUE])
def test_defaults_pass_the_independent_surface_reference(tmp_path, capsys, case):
    """The surface reference on grids of 16 … 64 (its fields on 64 × 64, its scalars
    extrapolated): its own scalars, and those derived from its fields."""
    (tmp_path / "ref.py").write_text(REFERENCE_SOLVER, encoding="utf-8")
    for fn in ("solve", "fields_only"):
        rc, out, err = _run(capsys, "--case", case, "--callable", f"{tmp_path}/ref.py:{fn}",
                            "--nodes", "64", "--out", str(tmp_path / fn), "--no-figures")
        assert rc == 0, out + err
        assert "FAIL" not in out


# ---------------------------------------------------------------------------- slips that fail
@pytest.mark.parametrize("nodes", [64, 128])
@pytest.mark.parametrize("axis, way", [(0, "−x"), (1, "−y")])
def test_fields_one_panel_off_fail_and_are_diagnosed(tmp_path, capsys, axis, way, nodes):
    f = _bem(CASE, nodes).fields
    rolled = {k: v if k in ("x", "y") else np.roll(v, 1, axis=axis) for k, v in f.items()}
    path = _write_npz(tmp_path / "rolled.npz", rolled)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", path, "--out", str(tmp_path),
                        "--no-figures")
    assert rc == 1
    failed = _verdict(tmp_path)["failed"]
    assert {"σ L2 / max σ", "u L2 / h_ref", "gap L∞ / h_ref"} <= set(failed)
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert len(diag) == 1 and f"one panel toward {way}" in diag[0]
    assert f"np.roll by -1 along axis {axis}" in diag[0]


def test_a_two_percent_mu_error_fails(tmp_path, capsys):
    """The solver's own μ 2 % off, with correct fields: FAIL naming μ alone."""
    (tmp_path / "solver_mu.py").write_text(
        "from comparisons import verify\n"
        "def solve(point, nodes):\n"
        "    out = verify.viscosine_bem(point, nodes)\n"
        "    out.scalars['mu'] *= 1.02\n"
        "    return out\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", CASE, "--callable", f"{tmp_path}/solver_mu.py:solve",
                        "--nodes", "64", "--out", str(tmp_path / "rep"), "--no-figures")
    assert rc == 1, out + err
    doc = _verdict(tmp_path / "rep")
    assert doc["failed"] == ["μ"]
    row = next(q for q in doc["quantities"] if q["key"] == "mu")
    assert row["difference"] == pytest.approx(0.02, abs=1e-3) and row["tolerance"] < 0.005
    # the same through JSON lines of scalars on that grid
    mu = suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"]
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"mu": mu * 1.02, "nodes": 64}) + "\n", encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", CASE, "--scalars", str(path), "--out",
                      str(tmp_path / "rep2"), "--no-figures")
    assert rc == 1 and "FAIL mu" in out and _verdict(tmp_path / "rep2")["failed"] == ["μ"]


def test_a_uniformly_scaled_pressure_is_diagnosed(tmp_path, capsys):
    f = dict(_bem(CASE, 64).fields)
    f["pressure"] = f["pressure"] * 0.75  # a pressure scale off by 3/4
    path = _write_npz(tmp_path / "scaled.npz", f)
    rc, out, _ = _run(capsys, "--case", CASE, "--fields", path, "--out", str(tmp_path),
                      "--no-figures")
    assert rc == 1 and "FAIL load" in out
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert len(diag) == 1 and "σ is 0.75 × the reference's everywhere" in diag[0]


def test_friction_and_lateral_force_of_the_opposite_sign_are_diagnosed(tmp_path, capsys):
    sc = suite.get_case(OBLIQUE)["certified"]["scalars"]
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"mu": -sc["mu"]["value"],
                                "mu_lateral": -sc["mu_lateral"]["value"]}) + "\n",
                    encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", OBLIQUE, "--scalars", str(path), "--out",
                      str(tmp_path), "--no-figures")
    assert rc == 1
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert len(diag) == 2 and "friction has the opposite sign" in diag[0]
    assert "lateral force has the opposite sign" in diag[1] and "to the left of V" in diag[1]


@pytest.mark.parametrize("direction, expected", [
    (-30.0, "mirrored (y → −y; "), (210.0, "mirrored (x → −x, y → −y; ")])
def test_fields_of_a_mirrored_direction_are_diagnosed(tmp_path, capsys, direction, expected):
    """The oblique case solved at −θ (θ clockwise) or θ + 180° (sliding toward −V)."""
    point = dict(suite.get_case(OBLIQUE)["point"], direction=direction)
    path = _write_npz(tmp_path / "m.npz", verify.viscosine_bem(point, 64).fields)
    rc, out, _ = _run(capsys, "--case", OBLIQUE, "--fields", path, "--out", str(tmp_path),
                      "--no-figures")
    assert rc == 1
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert sum(expected in d for d in diag) == 1, diag


def test_the_half_space_answer_fails_the_layer_case(tmp_path, capsys):
    """viscosine_bem solves the case's layer; the same solver without it fails."""
    (tmp_path / "no_layer.py").write_text(
        "from comparisons import verify\n"
        "def solve(point, nodes):\n"
        "    point.pop('layer')\n"
        "    return verify.viscosine_bem(point, nodes)\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", LAYER, "--callable", "comparisons.verify:viscosine_bem",
                        "--nodes", "64", "--out", str(tmp_path / "a"), "--no-figures")
    assert rc == 0, out + err
    rc, out, _ = _run(capsys, "--case", LAYER, "--callable", f"{tmp_path}/no_layer.py:solve",
                      "--nodes", "64", "--out", str(tmp_path / "b"), "--no-figures")
    assert rc == 1 and {"μ", "Δ/h_ref"} <= set(_verdict(tmp_path / "b")["failed"])


# ---------------------------------------------------------------------------- scalars from fields
def test_scalars_from_fields_are_the_direct_forms_of_the_bem_on_its_grid():
    """On the BEM's own fields: the load, μ and μ_lateral from the surface's slope (the direct
    form the BEM's friction_mismatch measures against), Δ/h_ref from the mean gap, the patch
    count; the contact fraction within the BEM's own estimate of its own."""
    from comparisons import roads
    point = suite.get_case(OBLIQUE)["point"]
    res = roads.surface_solution(point, 128)
    f = res.fields()
    fields = {"x": f.x, "y": f.y, "pressure": f.pressure, "gap": f.gap,
              "displacement": f.displacement}
    sc = _surface_fields.scalars_from_fields(fields, point,
                                             roads.surface_on_grid(point["surface"], 128, 128))
    assert sc["load"] == pytest.approx(0.3, rel=1e-12)
    assert sc["mu"] == pytest.approx(res.mu, rel=res.residuals["friction_mismatch"] * 1.01)
    assert sc["penetration"] == pytest.approx(res.penetration, rel=1e-12)
    assert abs(sc["contact_fraction"] - res.contact_fraction) <= \
        res.error_estimate["contact_fraction"] * res.contact_fraction  # relative
    assert sc["n_patches"] == res.n_patches == 1 and not sc["full_contact"]
    # without a gap, Δ/h_ref from the displacement at the contact points: the same
    del fields["gap"]
    again = _surface_fields.scalars_from_fields(
        fields, point, roads.surface_on_grid(point["surface"], 128, 128))
    assert again["penetration"] == pytest.approx(res.penetration, rel=1e-9)


def test_patches_are_counted_across_the_cell_s_edges():
    c = np.zeros((16, 16), bool)
    c[0, 3] = c[15, 3] = True       # one patch across x's edge
    c[7, 0] = c[7, 15] = True       # one across y's
    c[9, 9] = True
    assert _surface_fields.count_patches(c) == 3


# ---------------------------------------------------------------------------- the API, bad input
def test_assert_agrees_on_a_surface_case():
    out = _bem(CASE, 64)
    ev = verify.assert_agrees(out, CASE)
    assert ev["verdict"] == "PASS"
    mu = suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"]
    with pytest.raises(AssertionError, match=r"μ \(mu\): .* > tolerance"):
        verify.assert_agrees({"mu": 1.02 * mu, "nodes": 64}, CASE)


@pytest.mark.parametrize("argv, start", [
    (["--peer", "tamaas"], f"--peer tamaas: with a surface case ({CASE})"),
    (["--callable", "comparisons.verify:viscosine_bem", "--units", "SI", "--E0", "1e6"],
     f"--units SI: with a surface case ({CASE})"),
    (["--callable", "comparisons.verify:viscosine_bem", "--tol", "ka=0.1"],
     "--tol ka=0.1: unknown quantity 'ka'; allowed: mu, mu_lateral"),
    (["--callable", "comparisons.verify:viscosine_bem", "--speed", "1"],
     "--speed 1.0 is not allowed here: --case gives the operating point"),
])
def test_bad_options_on_a_surface_case_exit_2_with_one_line(tmp_path, capsys, argv, start):
    rc, out, err = _run(capsys, "--case", CASE, *argv, "--out", str(tmp_path))
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert err.startswith("python -m comparisons verify: " + start), err


def _fields(n):
    x = np.arange(n) / n - 0.5
    return {"x": x, "y": x, "pressure": np.ones((n, n)), "gap": np.zeros((n, n))}


@pytest.mark.parametrize("make, expected", [
    (lambda p: p.write_bytes(b"not a zip"), "not a readable .npz"),
    (lambda p: np.savez(p, **{k: v for k, v in _fields(64).items() if k != "pressure"}),
     "no array pressure"),
    (lambda p: np.savez(p, **dict(_fields(64), x=np.arange(64) / 64)),
     "x, y are not the panel centres of a 64 x 64 grid"),
    (lambda p: np.savez(p, **dict(_fields(64), gap=np.zeros((64, 32)))), "gap of shape"),
    (lambda p: np.savez(p, **_fields(40)), "a 40 x 40 grid shares fewer than 16 points"),
    (lambda p: np.savez(p, **_fields(64), speed=3.0), "speed = 3 in the file, the case"),
])
def test_bad_fields_files_on_a_surface_case_exit_2_with_one_line(tmp_path, capsys, make,
                                                                  expected):
    path = tmp_path / "f.npz"
    make(path)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path))
    assert rc == 2 and out == "" and len(err.strip().splitlines()) == 1, err
    assert err.startswith(f"python -m comparisons verify: --fields {path}") and expected in err


def test_a_grid_that_cannot_hold_the_surface_is_bad_input(tmp_path, capsys):
    """The self-affine surface's finest mode (q_s = 8k) needs 18 points a side for its slope."""
    path = tmp_path / "f.npz"
    np.savez(path, **_fields(16))
    rc, out, err = _run(capsys, "--case", "surface-selfaffine-seed0", "--fields", str(path),
                        "--out", str(tmp_path))
    assert rc == 2 and len(err.strip().splitlines()) == 1
    assert "a 16 x 16 grid cannot hold the case's surface (a grid of at least 18 x 18" in err
