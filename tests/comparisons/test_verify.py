"""`verify`: verdicts on the reference itself and on a perturbed copy, the convergence study of
viscosine's own BEM fields, the default tolerances, SI fields and the report files (the Python
API and bad input: test_verify_doors.py)."""
import json

import numpy as np
import pytest

import analytic
from comparisons import cli, suite, verify
from comparisons.verify import _compare, _edges, _quantities

CASE = "sls-partial-v1"


def _write_csv(path, fields, comment="# test fields", columns=("x_over_lambda", "pressure",
                                                                  "displacement", "gap")):
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(comment + "\n" + ",".join(columns) + "\n")
        for row in zip(*(np.asarray(fields[c], float) for c in columns)):
            fh.write(",".join(repr(float(v)) for v in row) + "\n")
    return path


def _reference_fields(m=1024):
    x = np.arange(m) / m - 0.5
    f = analytic.solve(load=0.3, speed=1.0, ratio=3.0, hk=1.0).fields(x)
    return {"x_over_lambda": x, "pressure": f.pressure, "displacement": f.displacement,
            "gap": f.gap}


def _run(capsys, *argv):
    rc = cli.main(["verify", *argv])
    out = capsys.readouterr()
    return rc, out.out, out.err


# ---------------------------------------------------------------------------- verdicts
def test_verify_passes_on_the_reference_itself(tmp_path, capsys):
    csv_path = _write_csv(tmp_path / "ref.csv", _reference_fields())
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(csv_path),
                        "--out", str(tmp_path / "rep"))
    assert rc == 0, out + err
    assert "FAIL" not in out and "verify: PASS" in err
    doc = json.loads((tmp_path / "rep" / "verdict.json").read_text(encoding="utf-8"))
    assert doc["verdict"] == "PASS" and doc["reference"]["road"] == "semi-analytic"
    norms = {q["key"]: q["value"] for q in doc["quantities"]}
    assert norms["pressure_Linf"] == 0.0 and norms["displacement_Linf"] == 0.0
    html = (tmp_path / "rep" / "report.html").read_text(encoding="utf-8")
    assert html.count("data:image/png;base64,") == 1  # one field figure, no convergence
    assert "semi-analytic road" in (tmp_path / "rep" / "report.md").read_text(encoding="utf-8")


def test_verify_fails_on_a_perturbed_copy_naming_the_pressure_linf_norm(tmp_path, capsys):
    """Noise of 1e-3 max σ is inside what the grid allows σ L∞ by default (a correct solver
    errs by up to ~0.45 (N·2a/λ)^-1/2 there: 6.7e-2 at N = 1024); a tolerance asked for with
    --tol holds it to that."""
    f = _reference_fields()
    rng = np.random.default_rng(20140392)
    f["pressure"] = f["pressure"] + 1e-3 * f["pressure"].max() * rng.uniform(-1, 1, 1024)
    csv_path = _write_csv(tmp_path / "noisy.csv", f)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(csv_path),
                        "--out", str(tmp_path / "rep0"), "--no-figures")
    line = next(s for s in out.splitlines() if " pressure_Linf " in s)
    assert line.startswith("PASS pressure_Linf") and "tolerance 6.7e-02" in line
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(csv_path), "--tol",
                        "pressure_Linf=1e-4", "--out", str(tmp_path / "rep"), "--no-figures")
    assert rc == 1
    assert "tolerance: σ L∞ / max σ: 1.0e-04, --tol pressure_Linf=0.0001" in out
    line = next(s for s in out.splitlines() if " pressure_Linf " in s)
    assert line.startswith("FAIL pressure_Linf (σ L∞ / max σ)")
    assert "σ L∞ / max σ" in err.splitlines()[-1]
    doc = json.loads((tmp_path / "rep" / "verdict.json").read_text(encoding="utf-8"))
    row = next(q for q in doc["quantities"] if q["key"] == "pressure_Linf")
    assert 0.9e-3 < row["difference"] <= 1e-3 and not row["passed"]
    assert "σ L∞ / max σ" in doc["failed"]


def test_orders_on_viscosine_own_bem_fields(tmp_path, capsys):
    """N = 1024 … 16384 on the report's convergence point (p̃∞ = 0.3, V/V0 = 1): the orders of
    the differences are the BEM's own (Δ/h and ka are derived from the fields exactly as the BEM
    derives them); measured μ 1.77, Δ/h 1.67, ka 1.89 (1.24 with a plain polynomial edge fit),
    σ L2 1.01."""
    rc, out, err = _run(capsys, "--case", CASE, "--callable", "comparisons.verify:viscosine_bem",
                        "--nodes", "1024", "2048", "4096", "8192", "16384",
                        "--out", str(tmp_path), "--no-figures")
    assert rc == 0, out + err
    conv = json.loads((tmp_path / "verdict.json").read_text(encoding="utf-8"))["convergence"]
    order = {k: q["order_vs_reference"] for k, q in conv["quantities"].items()}
    assert order["mu"] == pytest.approx(1.77, abs=0.05)
    assert order["penetration"] == pytest.approx(1.67, abs=0.05)
    assert order["ka"] == pytest.approx(1.89, abs=0.05)
    assert order["pressure_L2"] == pytest.approx(1.0, abs=0.05)
    assert "orders vs reference: mu 1.77" in out
    # the fields give the BEM's own Δ/h and ka on every mesh
    point = suite.get_case(CASE)["point"]
    for n, pen, ka in zip(conv["nodes"], conv["quantities"]["penetration"]["values"],
                          conv["quantities"]["ka"]["values"]):
        res = suite.bem_solution(point, n)
        assert pen == pytest.approx(res.penetration, rel=1e-12)
        assert ka == pytest.approx(res.ka, abs=1e-12)


# ---------------------------------------------------------------------------- default tolerances
def _bem_fields(n, point=None):
    return verify.viscosine_bem(point or suite.get_case(CASE)["point"], n)


def _verdict(path):
    return json.loads((path / "verdict.json").read_text(encoding="utf-8"))


def _bem_misses(case, nodes):
    """What viscosine's BEM on ``nodes`` panels misses the case's reference by, per scalar (the
    verdict's measure; the larger miss of its own value and of the value derived from its
    fields) and for the edges (derived from its fields): the grid law's e_N, recomputed here
    from the public pieces."""
    point, c = verify.point_from_case(case)
    ref = verify.reference_for(point, c)
    sc, patches = verify.scalars_from_fields(verify.viscosine_bem(point, nodes), ref.shape)
    own = suite.bem_solution(point, nodes, base="/").scalars()
    out = {}
    for k, (value, _) in ref.scalars.items():
        scale = abs(value) if k in verify.REL and value else 1.0
        misses = [abs(v[k] - value) / scale for v in (sc, own) if v.get(k) is not None]
        if misses:
            out[k] = max(misses)
    if ref.patches:
        out["edges"] = max(abs(p[e] - r[e]) for p, r in zip(patches, ref.patches)
                           for e in ("trailing_edge", "leading_edge"))
    return out


def _scalar_rows(doc):
    return {q["key"]: q for q in doc["quantities"] if q["key"] not in verify.FIELD_LAW}


@pytest.mark.parametrize("nodes", [512, 4096])
def test_defaults_pass_viscosine_bem_and_state_each_tolerance(tmp_path, capsys, nodes):
    """A correct solver at the resolutions people run passes by default: viscosine's BEM on
    N = 512 and 4096 panels (its σ L∞ is 1.2e-2 and 1.1e-2 of max σ there, where 1e-4 used to be
    asked), and the verdict says each tolerance and why, one line each.  A scalar's or the
    edges' tolerance is max(1e-4, 3 e_N), e_N the larger of the BEM's error at N and half its
    error at N/2."""
    rc, out, err = _run(capsys, "--case", CASE, "--callable", "comparisons.verify:viscosine_bem",
                        "--nodes", str(nodes), "--out", str(tmp_path), "--no-figures")
    assert rc == 0, out + err
    doc = _verdict(tmp_path)
    c = suite.get_case(CASE)["certified"]["scalars"]["contact_fraction"]["value"]
    rows = {q["key"]: q for q in doc["quantities"]}
    for key in verify.FIELD_LAW:
        assert rows[key]["tolerance"] == pytest.approx(verify.field_tolerance(key, nodes, c),
                                                       rel=1e-6)
        assert f"N = {nodes}" in rows[key]["tolerance_reason"]
    assert rows["pressure_Linf"]["tolerance"] == pytest.approx(1.4 / np.sqrt(nodes * c), rel=1e-3)
    half = _bem_misses(CASE, nodes // 2)
    scalars = _scalar_rows(doc)
    for key, row in scalars.items():  # the solver is the BEM: its difference is the error at N
        e_n = max(row["difference"], half[key] / 2)
        assert row["tolerance"] == pytest.approx(max(1e-4, 3 * e_n), rel=1e-9), key
        assert f"N = {nodes}" in row["tolerance_reason"]
    lines = [ln for ln in out.splitlines() if ln.startswith("tolerance: ")]
    assert lines == [f"tolerance: {t}" for t in doc["tolerances"]]
    # one line per tolerance as printed (the floor's quantities share one), and the five norms
    assert len(lines) == len({f"{q['tolerance']:.1e}" for q in scalars.values()}) + 5
    assert any("σ L∞ / max σ" in ln and "square-root contact edge" in ln for ln in lines)
    assert all(len(ln) < 230 for ln in lines if "e_N" in ln)
    assert doc["diagnosis"] == []


@pytest.mark.parametrize("case", ["sls-light-v1", "sls-below-fc-v1", "sls-ratio1000-full"])
def test_defaults_pass_viscosine_bem_where_its_grid_error_exceeds_1e_4(tmp_path, capsys, case):
    """Where viscosine's BEM on 512 panels misses the reference by more than 1e-4 (a contact of
    28 panels, s/h small below the transition, a relaxation layer of 0.02 panel), the default
    allows 3 × that error, and says so; it used to fail these by default."""
    rc, out, err = _run(capsys, "--case", case, "--callable", "comparisons.verify:viscosine_bem",
                        "--nodes", "512", "--out", str(tmp_path), "--no-figures")
    assert rc == 0, out + err
    wide = {k: q for k, q in _scalar_rows(_verdict(tmp_path)).items() if q["difference"] > 1e-4}
    assert wide  # the grid law, not 1e-4, passes them
    for key, row in wide.items():
        assert row["tolerance"] >= 3 * row["difference"]
        assert "N = 512: e_N = " in row["tolerance_reason"]
        # the line whose value is this tolerance (not one whose e_N prints the same)
        assert f"{verify.LABELS[key]}" in next(ln for ln in out.splitlines()
                                               if ln.startswith("tolerance: ")
                                               and f": {row['tolerance']:.1e}, " in ln)


FOURIER = """import numpy as np
import analytic


def solve(point, nodes):
    # one grid, unshifted: x_j = j/N - 1/2, as viscosine_bem lays out its panel centres
    kw = {k: point[k] for k in ("load", "penetration", "speed", "ratio", "hk") if k in point}
    r = analytic.fourier_solve(nodes=int(nodes), shifts=1, **kw)
    if not r.success:
        raise RuntimeError(r.message)
    return {k: np.asarray(getattr(r, k))
            for k in ("x_over_lambda", "pressure", "displacement", "gap")}
"""


#: the suite's partial-contact cases on the standard linear solid (the semi-analytic reference)
PARTIAL_SLS = [name for name in suite.case_names()
               if suite.two_roads(suite.get_case(name)["point"])
               and not suite.get_case(name)["certified"]["exact"]["full_contact"]]


def _fourier_points():
    """(case, N) with N = 512 and 1024 where the Fourier collocation resolves the material's
    memory (it refuses the rest: sls-partial-v0.1 at 512, sls-ratio1000 below 4096), else the
    first N ≤ 4096 that does."""
    from analytic.references.fourier import memory_resolution
    out = []
    for name in PARTIAL_SLS:
        p = suite.get_case(name)["point"]
        ok = [n for n in (512, 1024, 2048, 4096)
              if memory_resolution(p["speed"], n, ratio=p["ratio"])[1]]
        out += [(name, n) for n in ok if n <= 1024] or [(name, ok[0])]
    return out


@pytest.mark.parametrize("case,nodes", _fourier_points())
def test_defaults_pass_an_independent_solver(tmp_path, capsys, case, nodes):
    """The Fourier-collocation solver (analytic.fourier_solve: dense collocation on points,
    no code shared with bem/), its fields on one grid of N points, passes by default on every
    partial-contact SLS case of the suite: its edges come from its fields (the pressure's side of
    an edge with a relaxation layer next to it is left out of the plain fits: 0.54 spacing at
    sls-partial-v0.1, N = 1024, before), and each position is allowed a tenth of a spacing per
    edge (its own ka, ke, 2a/λ err by up to 0.04 of one at N = 512, where viscosine's BEM's
    e_N sets 1e-4); the verdict says so."""
    (tmp_path / "fourier_solver.py").write_text(FOURIER, encoding="utf-8")
    rc, out, err = _run(capsys, "--case", case, "--callable",
                        f"{tmp_path}/fourier_solver.py:solve", "--nodes", str(nodes),
                        "--out", str(tmp_path / "rep"), "--no-figures")
    assert rc == 0, out + err
    doc = _verdict(tmp_path / "rep")
    assert doc["nodes"] == nodes and len(doc["quantities"]) == 15
    floors = [ln for ln in out.splitlines() if ln.startswith("floor: ")]
    assert floors == [f"floor: {t}" for t in doc["floors"]]
    assert floors[0].startswith(f"floor: 2a/λ, ka, ke, contact edges (x/λ): + 0.1 spacing per "
                                f"edge on N = {nodes} (")


def test_the_independent_solver_set_covers_the_partial_sls_cases():
    assert len(PARTIAL_SLS) == 13 and {c for c, _ in _fourier_points()} == set(PARTIAL_SLS)


def test_the_measured_position_resolution_holds():
    """POSITION_PANELS is twice the worst measured (per edge, in spacings): an edge from the
    Fourier collocation's fields at sls-hk0.05, N = 512 (0.047), the Fourier's own ka at
    sls-light-v1, N = 512 (0.040) and viscosine's BEM's there (0.037); recomputed here."""
    n = 512
    point, case = verify.point_from_case("sls-hk0.05")
    ref = verify.reference_for(point, case)
    kw = {k: point[k] for k in ("load", "speed", "ratio", "hk")}
    f = analytic.fourier_solve(nodes=n, shifts=1, **kw)
    fields = {k: np.asarray(getattr(f, k)) for k in ("x_over_lambda", "pressure", "gap")}
    edges = _quantities.edge_differences(ref.patches,
                                         verify.scalars_from_fields(fields, ref.shape)[1])
    assert max(max(abs(a), abs(b)) for a, b in edges) * n == pytest.approx(0.047, abs=0.002)
    point, case = verify.point_from_case("sls-light-v1")
    ka = verify.reference_for(point, case).scalars["ka"][0]
    kw = {k: point[k] for k in ("load", "speed", "ratio", "hk")}
    own = {"Fourier": analytic.fourier_solve(nodes=n, shifts=1, **kw).ka,
           "BEM": suite.bem_solution(point, n).ka}
    spacings = {k: abs(v - ka) * n / (2 * np.pi) for k, v in own.items()}
    assert spacings == pytest.approx({"Fourier": 0.040, "BEM": 0.037}, abs=0.002)
    assert verify.POSITION_PANELS == pytest.approx(2 * 0.047, abs=0.01)


def test_a_relaxation_layer_is_left_out_of_the_plain_edge_fit(monkeypatch):
    """At V/V0 = 0.1 the pressure relaxes over ~5 spacings behind the leading edge (N = 1024):
    no side of the Fourier collocation's leading edge holds the model to 2e-3 spacing, and a
    plain fit through the pressure's side too put the edge 0.54 spacing off; without it, 0.003."""
    n = 1024
    point, case = verify.point_from_case("sls-partial-v0.1")
    ref = verify.reference_for(point, case)
    f = analytic.fourier_solve(nodes=n, shifts=1, load=0.3, speed=0.1, ratio=3.0, hk=1.0)
    fields = {k: np.asarray(getattr(f, k)) for k in ("x_over_lambda", "pressure", "gap")}

    def lead_error():
        patch = verify.scalars_from_fields(fields, ref.shape)[1][0]
        return abs(patch["leading_edge"] - ref.patches[0]["leading_edge"]) * n
    assert lead_error() < 0.005
    monkeypatch.setattr(_edges, "EDGE_HOLDS", np.inf)  # every side in the plain fits
    assert lead_error() > 0.5


def test_the_bems_own_scalars_pass_by_default(tmp_path, capsys):
    """A correct solver's own scalars, not only those read from its fields: viscosine's BEM's
    at sls-ratio1000 on N = 1024 (its μ 8.7e-4 off, more than what its fields give) pass."""
    case, n = "sls-ratio1000", 1024
    point, _ = verify.point_from_case(case)
    own = suite.bem_solution(point, n, base="/").scalars()
    keep = {k: v for k, v in own.items() if k in verify.COMPARED_KEYS and v is not None}
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"nodes": n, **keep}) + "\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", case, "--scalars", str(path), "--out",
                        str(tmp_path / "a"), "--no-figures")
    assert rc == 0, out + err
    mu = _scalar_rows(_verdict(tmp_path / "a"))["mu"]
    assert mu["difference"] > 5e-4 and mu["passed"]


def test_the_grid_law_needs_the_grid_and_yields_to_rtol(tmp_path, capsys):
    """Scalars without nodes get 1e-4 ('the grid is not known'); with nodes, the grid law of
    that N; an explicit --rtol is a flat tolerance of every scalar, as asked."""
    mu = suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"]
    case = "sls-ratio1000-full"
    mu_full = suite.get_case(case)["certified"]["scalars"]["mu"]["value"]
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"mu": mu * (1 + 5e-5)}) + "\n", encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", CASE, "--scalars", str(path), "--out",
                      str(tmp_path / "a"), "--no-figures")
    assert rc == 0 and "tolerance: μ: 1.0e-04, the default --rtol 1.0e-04" in out
    assert "the grid is not known" in out
    # 1 % off at N = 512 where the BEM itself is 1 % off: within the grid law, outside --rtol
    path.write_text(json.dumps({"nodes": 512, "mu": mu_full * 1.01}) + "\n", encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", case, "--scalars", str(path), "--out",
                      str(tmp_path / "b"), "--no-figures")
    e_n = max(_bem_misses(case, 512)["mu"], _bem_misses(case, 256)["mu"] / 2)
    row = _scalar_rows(_verdict(tmp_path / "b"))["mu"]
    assert rc == 0 and row["tolerance"] == pytest.approx(3 * e_n, rel=1e-9)
    assert row["tolerance"] > 0.01
    rc, out, _ = _run(capsys, "--case", case, "--scalars", str(path), "--rtol", "1e-3", "--out",
                      str(tmp_path / "c"), "--no-figures")
    assert rc == 1 and "tolerance: μ: 1.0e-03, --rtol 1.0e-03" in out


def test_the_measured_field_constants_hold():
    """MEASURED_FIELD_CONSTANTS are viscosine's BEM's own (the worst of the suite's 17 SLS cases
    at N = 512 … 8192; recomputed here where each was reached), and K = 3 × them."""
    for key, (const, where) in verify.MEASURED_FIELD_CONSTANTS.items():
        name, n = where.split(", N = ")
        point, case = verify.point_from_case(name)
        got = verify.field_constants(point, int(n), case)[key]
        assert got == pytest.approx(const, rel=0.02), (key, where, got)
        assert verify.FIELD_LAW[key][0] == pytest.approx(3 * const, rel=0.1)


def test_a_two_percent_mu_error_fails(tmp_path, capsys):
    """The solver's own μ 2 % off the reference, with correct fields: FAIL naming μ."""
    mu = suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"]
    (tmp_path / "solver_mu.py").write_text(
        "from comparisons import verify\n"
        "class Out:\n"
        "    def __init__(self, point, nodes):\n"
        "        self.fields = verify.viscosine_bem(point, nodes)\n"
        f"        self.scalars = {{'mu': {mu!r} * 1.02}}\n"
        "def solve(point, nodes):\n"
        "    return Out(point, nodes)\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", CASE, "--callable", f"{tmp_path}/solver_mu.py:solve",
                        "--nodes", "1024", "--out", str(tmp_path / "rep"), "--no-figures")
    assert rc == 1, out + err
    doc = _verdict(tmp_path / "rep")
    assert doc["failed"] == ["μ"]
    row = next(q for q in doc["quantities"] if q["key"] == "mu")
    assert row["difference"] == pytest.approx(0.02, rel=1e-9)
    # the same through JSON lines of scalars
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"mu": mu * 1.02}) + "\n", encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", CASE, "--scalars", str(path), "--out",
                      str(tmp_path / "rep2"), "--no-figures")
    assert rc == 1 and "FAIL mu" in out


@pytest.mark.parametrize("nodes", [1024, 4096])
def test_fields_rolled_by_one_panel_fail_and_are_diagnosed(tmp_path, capsys, nodes):
    f = _bem_fields(nodes)
    rolled = {k: (v if k == "x_over_lambda" else np.roll(v, 1)) for k, v in f.items()}
    path = _write_csv(tmp_path / "rolled.csv", rolled)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path),
                        "--no-figures")
    assert rc == 1
    failed = _verdict(tmp_path)["failed"]
    assert {"σ L2 / max σ", "v L∞ / h", "gap L∞ / h", "ke"} <= set(failed)
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert len(diag) == 1 and "one panel toward −x" in diag[0] and "np.roll by -1" in diag[0]


def test_a_mirrored_sign_or_x_is_diagnosed(tmp_path, capsys):
    ref = suite.get_case(CASE)["certified"]["scalars"]
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps({"mu": -ref["mu"]["value"], "ke": ref["ke"]["value"]}) + "\n",
                    encoding="utf-8")
    rc, out, _ = _run(capsys, "--case", CASE, "--scalars", str(path), "--out",
                      str(tmp_path / "a"), "--no-figures")
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert rc == 1 and len(diag) == 1
    assert diag[0].startswith("diagnosis: μ = -0.30361 against 0.30361: the friction has the "
                              "opposite sign") and "x is mirrored" not in diag[0]
    # fields mirrored in x: σ(−x), v(−x), gap(−x) on the grid x_j = j/N − 1/2
    f = _bem_fields(1024)
    mirror = (-np.arange(1024)) % 1024
    path = _write_csv(tmp_path / "mirrored.csv",
                      {k: (v if k == "x_over_lambda" else v[mirror]) for k, v in f.items()})
    rc, out, _ = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path / "b"),
                      "--no-figures")
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert rc == 1 and "the fields match the reference mirrored in x" in diag[0]
    assert any(d.startswith("diagnosis: ke = -0.2832") and "x is mirrored" in d for d in diag)
    assert any("x is mirrored too" in d for d in diag)  # μ's sign comes with it


def test_si_fields_without_units_are_diagnosed(tmp_path, capsys):
    E0, nu, h = 2.0e6, 0.5, 1e-4
    f = _reference_fields(512)
    si = dict(f, pressure=f["pressure"] * E0 / (1 - nu ** 2), displacement=f["displacement"] * h,
              gap=f["gap"] * h)
    path = _write_csv(tmp_path / "si.csv", si)
    rc, out, _ = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path),
                      "--no-figures")
    diag = [ln for ln in out.splitlines() if ln.startswith("diagnosis: ")]
    assert rc == 1
    assert any("σ is 2.7e+06 × the reference's: pressures in Pa without --units SI" in d
               for d in diag)
    assert any("v is 0.0001 × the reference's: lengths in m without --units SI" in d for d in diag)


def test_the_grid_limits_a_check_only_within_what_it_explains():
    """A difference the derivation floor explains is noted as the grid's limit; one far beyond
    it (1.5e-2 at a floor of 2e-4) is not."""
    tol = (1e-4, "test")
    inside = _compare._row("mu", 1.0, 1.0, 2.5e-4, "relative", tol, 0.0, 2e-4)
    assert inside["passed"] and inside["note"].startswith("the grid limits this check")
    beyond = _compare._row("mu", 1.0, 1.0, 1.5e-2, "relative", tol, 0.0, 2e-4)
    assert not beyond["passed"] and "grid limits" not in beyond["note"]
    assert beyond["note"] == ("not explained by the grid: the derivation on this grid errs by "
                              "only 2.0e-04")
    assert _compare._row("mu", 1.0, 1.0, 5e-5, "relative", tol, 0.0, 0.0)["note"] == ""


@pytest.mark.slow
def test_orders_of_the_worst_difference_over_the_crosscheck_grid():
    """docs/accuracy.md's table (worst over the grid of operating points) measured through verify on
    viscosine's BEM fields at N = 1024 … 16384: measured Δ/h 1.93, ka 2.16 (1.64 with a plain
    polynomial edge fit), σ L2 0.97 (the
    table, N up to 65536 and the BEM's own μ: 1.78, 1.68, ≈ 1; μ 1.93); μ derived from the
    fields 2.79 (the light-load point dominates its worst difference at N = 1024)."""
    from comparisons import crosscheck
    nodes = [1024, 2048, 4096, 8192, 16384]
    worst = {}
    for _, load, speed, ratio, hk in crosscheck.GRID:
        if isinstance(load, tuple):
            load = load[1] * analytic.transition_load(speed, ratio, hk)
        point = {"load": load, "speed": speed, "ratio": ratio, "hk": hk}
        ref = verify.reference_for(point)
        res = verify.results_from_fields([verify.viscosine_bem(point, n) for n in nodes], ref.shape)
        for k, q in verify.convergence(res, ref)["quantities"].items():
            worst[k] = np.maximum(worst.get(k, 0.0), np.array(q["errors"], float))
    order = {k: verify.fit_order(nodes, v) for k, v in worst.items()}
    assert order["penetration"] == pytest.approx(1.93, abs=0.1)
    assert order["ka"] == pytest.approx(2.16, abs=0.1)
    assert order["pressure_L2"] == pytest.approx(0.97, abs=0.1)
    assert order["mu"] > 1.7


def test_bem_reference_for_a_profile_case(tmp_path, capsys):
    point = suite.get_case("harmonics2-sls")["point"]
    path = point["profile"]
    f = verify.viscosine_bem({**point, "profile": str(suite.data_path(path))}, 4096)
    csv_path = _write_csv(tmp_path / "h2.csv", f)
    rc, out, err = _run(capsys, "--case", "harmonics2-sls", "--fields", str(csv_path),
                        "--rtol", "1e-3", "--tol", "pressure_Linf=0.05", "--out", str(tmp_path),
                        "--no-figures")
    assert rc == 0, out + err
    doc = json.loads((tmp_path / "verdict.json").read_text(encoding="utf-8"))
    assert doc["reference"]["road"] == "BEM"
    assert "certified values of the suite case harmonics2-sls" in doc["reference"]["description"]
    assert len(doc["results"][0]["patches"]) == 2
    assert "edges" in {q["key"] for q in doc["quantities"]}


LAYER_CASE = "sls-layer-frictionless-d0.1"


def test_a_layer_case_gives_the_callable_its_layer(tmp_path, capsys):
    """On a layer case the callable's point carries the case's ``layer`` (d/λ, foundation, ν):
    viscosine's BEM given it passes against the certified values; the same BEM on the
    half-plane (the layer dropped) fails, naming μ (35 % off)."""
    layer = suite.get_case(LAYER_CASE)["point"]["layer"]
    (tmp_path / "solvers.py").write_text(
        "import json\n"
        "from comparisons import verify\n"
        "def with_layer(point, nodes):\n"
        f"    open({str(tmp_path / 'seen.json')!r}, 'w').write(json.dumps(point))\n"
        "    return verify.viscosine_bem(point, nodes)\n"
        "def half_plane(point, nodes):\n"
        "    point = {k: v for k, v in point.items() if k != 'layer'}\n"
        "    return verify.viscosine_bem(point, nodes)\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", LAYER_CASE, "--callable",
                        f"{tmp_path}/solvers.py:with_layer", "--nodes", "1024", "--out",
                        str(tmp_path / "rep"), "--no-figures")
    assert rc == 0, out + err
    seen = json.loads((tmp_path / "seen.json").read_text(encoding="utf-8"))
    assert seen["layer"] == layer
    doc = _verdict(tmp_path / "rep")
    assert doc["reference"]["road"] == "BEM" and doc["point"]["layer"] == layer
    assert f"certified values of the suite case {LAYER_CASE}" in doc["reference"]["description"]
    rc, out, err = _run(capsys, "--case", LAYER_CASE, "--callable",
                        f"{tmp_path}/solvers.py:half_plane", "--nodes", "1024", "--out",
                        str(tmp_path / "rep2"), "--no-figures")
    assert rc == 1 and "FAIL mu" in out
    mu = next(q for q in _verdict(tmp_path / "rep2")["quantities"] if q["key"] == "mu")
    assert mu["difference"] > 0.3


def test_a_layer_case_is_refused_to_the_peer_and_a_bad_layer_to_the_api(tmp_path, capsys):
    rc, _, err = _run(capsys, "--case", LAYER_CASE, "--peer", "tamaas", "--out",
                      str(tmp_path), "--no-figures")
    assert rc == 2 and len(err.strip().splitlines()) == 1
    assert err.startswith("python -m comparisons verify: --peer tamaas: with a case on a layer "
                          f"({LAYER_CASE})")
    from comparisons._errors import BadInput
    with pytest.raises(BadInput, match=r"^layer .*nu"):
        verify.assert_agrees({"mu": 0.15}, {"load": 0.1, "speed": 1.0, "layer": {
            "thickness_over_wavelength": 0.1, "foundation": "bonded", "nu": 0.7}})
    with pytest.raises(BadInput, match=r"^layer .*not a layer description"):
        verify.assert_agrees({"mu": 0.15}, {"load": 0.1, "speed": 1.0, "layer": 0.1})


def test_scalars_jsonl_with_a_convergence_study(tmp_path, capsys):
    ref = suite.get_case(CASE)["certified"]["scalars"]
    lines = [{"nodes": n, "mu": ref["mu"]["value"] * (1 + 2.0 / n ** 2),
              "penetration": ref["penetration"]["value"] * (1 - 1.0 / n ** 2)}
             for n in (64, 128, 256, 512)]
    path = tmp_path / "s.jsonl"
    path.write_text("\n".join(json.dumps(d) for d in lines) + "\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", CASE, "--scalars", str(path), "--rtol", "1e-5",
                        "--out", str(tmp_path / "rep"))
    assert rc == 0, out + err
    doc = json.loads((tmp_path / "rep" / "verdict.json").read_text(encoding="utf-8"))
    conv = doc["convergence"]
    assert conv["quantities"]["mu"]["order_vs_reference"] == pytest.approx(2.0, abs=1e-6)
    assert conv["quantities"]["mu"]["self_order"] == pytest.approx(2.0, abs=1e-6)
    assert conv["quantities"]["mu"]["richardson_error"] < 1e-12
    # one result outside a tolerance
    rc, out, _ = _run(capsys, "--case", CASE, "--scalars", str(path), "--rtol", "1e-6",
                      "--out", str(tmp_path / "rep2"), "--no-figures")
    assert rc == 1 and "FAIL mu" in out


def test_a_prony_case_report_draws_its_material(tmp_path, capsys):
    """A Prony material (here a suite case's file) gets the E′, E″, tan δ figure, with the
    operating point's sliding frequency marked; a standard linear solid does not."""
    case = suite.get_case("prony3-partial")
    sc = {k: r["value"] for k, r in case["certified"]["scalars"].items()}
    path = tmp_path / "s.jsonl"
    path.write_text(json.dumps(sc) + "\n", encoding="utf-8")
    rc, out, err = _run(capsys, "--case", "prony3-partial", "--scalars", str(path),
                        "--out", str(tmp_path / "rep"))
    assert rc == 0, out + err
    md = (tmp_path / "rep" / "report.md").read_text(encoding="utf-8")
    assert "(material.png)" in md and "prony3.txt" in md and "V/V0 = 1" in md
    assert (tmp_path / "rep" / "material.png").stat().st_size > 10_000
    html = (tmp_path / "rep" / "report.html").read_text(encoding="utf-8")
    assert html.count("data:image/png;base64,") == 1
    rc, out, err = _run(capsys, "--case", CASE, "--scalars", str(path), "--rtol", "1",
                        "--out", str(tmp_path / "sls"))
    assert "material.png" not in (tmp_path / "sls" / "report.md").read_text(encoding="utf-8")


def test_si_fields_with_material_and_geometry(tmp_path, capsys):
    E0, nu, h = 2.0e6, 0.5, 1e-4
    f = _reference_fields(512)
    si = dict(f, pressure=f["pressure"] * E0 / (1 - nu ** 2), displacement=f["displacement"] * h,
              gap=f["gap"] * h)
    path = _write_csv(tmp_path / "si.csv", si)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(path), "--units", "SI",
                        "--E0", str(E0), "--nu", str(nu), "--amplitude", str(h),
                        "--rtol", "1e-3", "--out", str(tmp_path / "rep"), "--no-figures")
    assert rc == 0, out + err
    # the operating point in SI too: p∞ [Pa], V [m/s], E0, E∞ [Pa], τ [s], λ, h [m]
    lam = 2 * np.pi * h  # hk = 1
    rc, out, err = _run(capsys, "--load", repr(0.3 * E0 / (1 - nu ** 2)),
                        "--speed", repr(1.0 / (0.01 * 2 * np.pi / lam)), "--units", "SI",
                        "--E0", str(E0), "--Einf", str(3 * E0), "--tau-creep", "0.01", "--nu", str(nu),
                        "--wavelength", repr(lam), "--amplitude", str(h), "--fields", str(path),
                        "--rtol", "1e-3", "--out", str(tmp_path / "rep2"), "--no-figures")
    assert rc == 0, out + err
    point = json.loads((tmp_path / "rep2" / "verdict.json").read_text(encoding="utf-8"))["point"]
    assert point == pytest.approx({"load": 0.3, "speed": 1.0, "ratio": 3.0, "hk": 1.0}, rel=1e-14)
    rc, _, err = _run(capsys, "--case", CASE, "--fields", str(path), "--units", "SI")
    assert rc == 2 and err.strip() == ("python -m comparisons verify: --E0 is missing: --units "
                                       "SI needs --E0, --nu and --amplitude to convert SI fields")
    # E0, ν and h are checked by themselves: no stand-in for an option not given (--Einf)
    common = ("--case", CASE, "--fields", str(path), "--units", "SI", "--nu", str(nu),
              "--amplitude", str(h), "--rtol", "1e-3", "--no-figures")
    rc, _, err = _run(capsys, *common, "--E0", "-1", "--out", str(tmp_path / "rep3"))
    assert rc == 2 and "--E0 -1.0: must be a finite modulus > 0" in err, err
    rc, _, err = _run(capsys, *common, "--E0", "1e308", "--out", str(tmp_path / "rep4"))
    assert rc == 1 and "--Einf" not in err, err  # a modulus that large fails the fields
