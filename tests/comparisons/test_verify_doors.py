"""`verify`'s other doors and edges: the Python API, bad input (files, options, the point in
the words of the door that took it, unwritable outputs), the peer options, scalars from fields
and the HTML renderer.  The verdicts and default tolerances are test_verify.py's."""
import json

import numpy as np
import pytest

import analytic
from comparisons import _html, cli, suite, verify
from comparisons.verify import _report
from test_verify import CASE, _reference_fields, _run, _verdict, _write_csv


# ---------------------------------------------------------------------------- Python API
def test_assert_agrees_on_fields_and_scalars():
    f = analytic.solve(load=0.3, speed=1.0).fields(np.arange(4096) / 4096 - 0.5)
    verify.assert_agrees(f, CASE, rtol=1e-4)
    verify.assert_agrees(f, {"load": 0.3, "speed": 1.0}, rtol=1e-4)  # an operating point
    ref = suite.get_case(CASE)["certified"]["scalars"]
    verify.assert_agrees({"mu": ref["mu"]["value"], "ka": ref["ka"]["value"]}, CASE, rtol=1e-12)


def test_assert_agrees_message_names_quantity_values_and_difference():
    ref = suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"]
    with pytest.raises(AssertionError) as info:
        verify.assert_agrees({"mu": ref * (1 + 1e-3)}, CASE, rtol=1e-4)
    msg = str(info.value)
    assert "μ (mu)" in msg and f"{ref * (1 + 1e-3):.10g}" in msg and f"{ref:.10g}" in msg
    assert "difference 1.000e-03 (relative) > tolerance 1.0e-04" in msg
    f = dict(_reference_fields())
    f["pressure"] = f["pressure"] + 1e-3 * f["pressure"].max() * np.cos(7 * np.arange(1024))
    with pytest.raises(AssertionError, match="σ L∞ / max σ"):
        verify.assert_agrees(f, CASE, rtol=1e-4, tol={"pressure_Linf": 1e-4})


# ---------------------------------------------------------------------------- bad input
BAD = {
    "missing": (None, "no such file"),
    "empty": (b"", "the file is empty"),
    "binary": (b"x_over_lambda,pressure\n\x00\x01\x02\n", "a binary file, not text"),
    "latin1": ("x_over_lambda,pressure\n0.0,caf\u00e9\n".encode("latin-1"), "not UTF-8 text"),
    "columns": (b"# comment\nx,p\n" + b"".join(b"%r,1\n" % (j / 8) for j in range(8)),
                "the columns x_over_lambda and pressure are required (found: x, p)"),
    "nonuniform": (b"x_over_lambda,pressure\n"
                   + b"".join(b"%r,1\n" % x for x in (-0.5, -0.4, -0.2, 0.0, 0.1, 0.2, 0.3, 0.4)),
                   "x_over_lambda is not a uniform grid over one period"),
    "repeated_end": (b"x_over_lambda,pressure\n" + b"".join(b"%r,1\n" % (j / 8 - 0.5)
                                                           for j in range(9)),
                     "the end point of the period is repeated"),
    "words": (b"x_over_lambda,pressure\n" + b"".join(b"%r,abc\n" % (j / 8 - 0.5) for j in range(8)),
              "not a number"),
}


@pytest.mark.parametrize("kind", sorted(BAD))
def test_bad_fields_files_exit_2_with_one_line(tmp_path, capsys, kind):
    content, expected = BAD[kind]
    path = tmp_path / f"{kind}.csv"
    if content is not None:
        path.write_bytes(content)
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path))
    assert rc == 2 and out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert lines[0].startswith(f"python -m comparisons verify: --fields {path}: ")
    assert expected in lines[0] and len(lines[0]) < 400


@pytest.mark.parametrize("argv,start", [
    (["--case", "nope"], "--case nope: not a suite case"),
    (["--load", "0.3"], "--speed is missing"),
    (["--load", "-1", "--speed", "1"], "--load -1.0: must be a mean pressure"),
    (["--load", "1e50", "--speed", "1"], "--load 1e+50: must be a mean pressure"),
    (["--case", CASE, "--speed", "1"], "--speed 1.0 is not allowed here: --case gives"),
    (["--case", CASE, "--tol", "mu"], "--tol mu: not NAME=VALUE"),
    (["--case", CASE, "--rtol", "-1"], "--rtol -1.0: must be a finite tolerance > 0"),
    (["--load", "0.3", "--speed", "1", "--prony", "/no/such/prony.txt"],
     "--prony /no/such/prony.txt: no such file"),
])
def test_bad_options_exit_2_with_one_line(tmp_path, capsys, argv, start):
    csv_path = _write_csv(tmp_path / "ref.csv", _reference_fields(64))
    rc, out, err = _run(capsys, *argv, "--fields", str(csv_path), "--out", str(tmp_path))
    assert rc == 2 and len(err.strip().splitlines()) == 1, err
    assert err.startswith("python -m comparisons verify: " + start) and len(err) < 400, err


@pytest.mark.parametrize("bad", [["--load", "-1"], ["--load", "1e50"], ["--penetration", "2"],
                                 ["--load", "0.1", "--ratio", "1"], ["--load", "0.1", "--hk", "0"],
                                 ["--load", "0.1", "--speed", "nan"]])
def test_the_point_is_refused_in_the_words_of_point(tmp_path, capsys, bad):
    """verify checks its point through the operating point's road, as ``point`` does: the same
    line after the command's name, for the same option and value."""
    argv = bad if "--speed" in bad else ["--speed", "1", *bad]
    rc, _, err_verify = _run(capsys, *argv, "--scalars", str(tmp_path / "s.jsonl"))
    assert rc == 2
    rc = cli.main(["point", "--solver", "analytic", *argv])
    err_point = capsys.readouterr().err
    assert rc == 2
    said = err_verify.split("verify: ", 1)[1]
    assert said == err_point.split("point: ", 1)[1] and ": must be " in said


def test_a_python_point_is_refused_by_its_keyword():
    with pytest.raises(ValueError, match=r"^load=-1.0 is not allowed: a mean pressure"):
        verify.assert_agrees({"mu": 0.1}, {"load": -1, "speed": 1.0})
    # options that do not go together, and one not given: the keywords, never an option
    with pytest.raises(ValueError) as info:
        verify.assert_agrees({"mu": 0.1}, {"load": 0.1, "penetration": 0.5, "speed": 1.0})
    assert str(info.value) == ("penetration=0.5 is not allowed here: give one of load and "
                               "penetration")
    with pytest.raises(ValueError) as info:
        verify.assert_agrees({"mu": 0.1}, {"load": 0.1})
    assert str(info.value) == "speed is missing: give the sliding speed V/V0"


def test_long_messages_keep_the_prefix_and_stay_under_400_characters(tmp_path, capsys):
    deep = tmp_path / ("a-rather-long-folder-name-" * 8)
    deep.mkdir()
    path = deep / ("fields-" * 20 + ".csv")
    path.write_bytes(BAD["columns"][0])
    rc, out, err = _run(capsys, "--case", CASE, "--fields", str(path), "--out", str(tmp_path))
    line = err.strip()
    assert rc == 2 and out == "" and "\n" not in line
    assert line.startswith("python -m comparisons verify: --fields ") and len(line) < 400
    rc, _, err = _run(capsys, "--case", "sls-partial-v2", "--scalars", str(path))
    assert rc == 2 and len(err.strip()) < 400
    assert "not a suite case" in err and "closest: sls-partial-v1" in err


def test_an_unwritable_out_is_refused_up_front_like_point_and_sweep(tmp_path, capsys,
                                                                     read_only_folder):
    locked = read_only_folder
    path = tmp_path / "s.jsonl"
    path.write_text('{"mu": 0.3}\n', encoding="utf-8")
    for out_dir, where in ((locked / "rep", f"the folder {locked} is not writable"),
                           (locked, "the folder is not writable")):
        rc, out, err = _run(capsys, "--case", CASE, "--scalars", str(path), "--out", str(out_dir))
        assert rc == 2 and out == ""
        assert err.strip() == f"python -m comparisons verify: --out {out_dir}: {where}"
    rc = cli.main(["point", "--solver", "analytic", "--load", "0.3", "--speed", "1", "--fields",
                   str(locked / "f.csv")])
    assert rc == 2 and capsys.readouterr().err.strip().endswith(
        f"the folder {locked} is not writable")


def test_a_report_that_cannot_be_written_is_one_line_status_1(tmp_path, capsys, monkeypatch):
    def refuse(*a, **k):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(_report, "write_text", refuse)
    path = tmp_path / "s.jsonl"
    path.write_text('{"mu": 0.3}\n', encoding="utf-8")
    rc, out, err = _run(capsys, "--case", CASE, "--scalars", str(path), "--out",
                        str(tmp_path / "rep"), "--no-figures")
    assert rc == 1 and out == ""
    assert err.strip() == (f"python -m comparisons verify: --out {tmp_path / 'rep'}: cannot write "
                           "the report (No space left on device)")


def test_help_says_the_si_units_of_the_operating_point(capsys):
    assert cli.main(["verify", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "--load LOAD p̃∞ = p∞(1 − ν²)/E0; with --units SI the mean pressure p∞ in Pa" in text
    assert "--speed SPEED V/V0 = Vτk; with --units SI the sliding speed V in m/s" in text
    assert "--dt-cells C [C ...]" in text and "default 4 2 1" in text


def test_bad_callable_and_scalars_exit_2(tmp_path, capsys):
    rc, _, err = _run(capsys, "--case", CASE, "--callable", "no_such_module:f")
    assert rc == 2 and err.startswith("python -m comparisons verify: --callable "
                                      "no_such_module:f: cannot import")
    path = tmp_path / "s.jsonl"
    path.write_text('{"mu": 0.3}\n{"mu": 0.31}\n', encoding="utf-8")
    rc, _, err = _run(capsys, "--case", CASE, "--scalars", str(path))
    assert rc == 2 and "2 results without 'nodes'" in err and len(err.strip().splitlines()) == 1


def test_peer_tamaas_is_called_with_the_operating_point(tmp_path, capsys, monkeypatch):
    """The wiring of --peer tamaas, with a stand-in module (the real one is tested with Tamaas):
    solve(*, load, speed, ratio, hk, nodes, dt) returning .fields() and .scalars()."""
    import sys
    import types
    calls = []

    class Out:
        def __init__(self, nodes):
            x = np.arange(nodes) / nodes - 0.5
            self._f = analytic.solve(load=0.3, speed=1.0).fields(x)

        def fields(self, x_over_lambda=None):
            return self._f

        def scalars(self):
            return {"mu": suite.get_case(CASE)["certified"]["scalars"]["mu"]["value"],
                    "ke": None, "full_contact": False}

    def solve(*, load, speed, ratio, hk, nodes, dt=None):
        calls.append((load, speed, ratio, hk, nodes, dt))
        return Out(nodes)

    fake = types.ModuleType("comparisons.peers.tamaas")
    fake.solve = solve
    monkeypatch.setitem(sys.modules, "comparisons.peers.tamaas", fake)
    rc, out, err = _run(capsys, "--case", CASE, "--peer", "tamaas", "--nodes", "2048", "4096",
                        "--dt", "0.5", "--out", str(tmp_path), "--no-figures")
    assert rc == 0, out + err
    assert calls == [(0.3, 1.0, 3.0, 1.0, 2048, 0.5), (0.3, 1.0, 3.0, 1.0, 4096, 0.5)]
    doc = json.loads((tmp_path / "verdict.json").read_text(encoding="utf-8"))
    assert doc["results"][-1]["source"] == "solver (fields for the rest)"
    mu = next(q for q in doc["quantities"] if q["key"] == "mu")
    assert mu["difference"] == 0.0  # the peer's own μ, not the one derived from its fields


def test_peer_tamaas_runs_a_dt_study_and_is_judged_on_the_extrapolation(tmp_path, capsys):
    """The real Tamaas on small grids (a second or two): progress on standard error, one line
    per run; the verdict on the values extrapolated to dt → 0 by the peer's own Richardson step
    (the one the report uses), each with its estimated error."""
    pytest.importorskip("tamaas", minversion="2.9")
    from comparisons.peers import tamaas as peer
    rc, out, err = _run(capsys, "--load", "0.15", "--speed", "1.058", "--peer", "tamaas",
                        "--nodes", "64", "128", "--dt-cells", "1", "4", "2", "--out",
                        str(tmp_path), "--no-figures")
    assert rc in (0, 1), err
    progress = [ln for ln in err.splitlines() if ln.startswith("verify: Tamaas N = ")]
    assert len(progress) == 6 and progress[0].startswith("verify: Tamaas N = 64, dt = 4 × T/N: "
                                                         "steady after")
    assert progress[-1].startswith("verify: Tamaas N = 128, dt = 1 × T/N") and "run 6 of 6" in \
        progress[-1]
    doc = _verdict(tmp_path)
    assert doc["results"][-1]["source"] == ("solver (fields for the rest); extrapolated to "
                                            "dt → 0")
    study = peer.dt_extrapolation(load=0.15, speed=1.058, nodes=128, cells_per_step=(4, 2, 1))
    mu = next(q for q in doc["quantities"] if q["key"] == "mu")
    assert mu["value"] == study.richardson["mu"]
    assert mu["solver_error"] == pytest.approx(study.error["mu"] / abs(mu["reference"]), rel=1e-12)
    raw = study.results[-1].mu
    assert abs(mu["value"] / mu["reference"] - 1) < 0.1 * abs(raw / mu["reference"] - 1)
    assert doc["inputs"]["--peer"] == "tamaas, dt = 4, 2, 1 × T/N, extrapolated to dt → 0"
    assert "the solver's estimated error" in out.splitlines()[0]


def test_peer_options_are_refused_without_the_peer(tmp_path, capsys):
    path = tmp_path / "s.jsonl"
    path.write_text('{"mu": 0.3}\n', encoding="utf-8")
    rc, _, err = _run(capsys, "--case", CASE, "--scalars", str(path), "--dt-cells", "2", "1")
    assert rc == 2 and "--dt-cells 2.0 1.0: without --peer" in err


# ---------------------------------------------------------------------------- scalars from fields
def test_scalars_from_fields_recover_a_sampled_solution():
    """On dense samples of the semi-analytic fields the derivation converges to the scalars."""
    sol = analytic.solve(load=0.3, speed=1.0)
    shape = suite.ProfileShape({"hk": 1.0})
    errs = []
    for m in (1024, 4096, 16384):
        x = np.arange(m) / m - 0.5
        f = sol.fields(x)
        sc, patches = verify.scalars_from_fields(
            {"x_over_lambda": x, "pressure": f.pressure, "gap": f.gap}, shape)
        assert len(patches) == 1 and not sc["full_contact"]
        errs.append([abs(sc["mu"] / sol.mu - 1), abs(sc["penetration"] / sol.penetration - 1),
                     abs(sc["ka"] - sol.ka), abs(sc["ke"] - sol.ke)])
    errs = np.array(errs)
    assert np.all(errs[-1] < [1e-5, 1e-9, 1e-6, 1e-6])
    assert np.all(errs[-1] < errs[0])
    # an offset grid (cell centres) gives the same to the same accuracy
    m = 4096
    x = (np.arange(m) + 0.5) / m - 0.5
    f = sol.fields(x)
    sc, _ = verify.scalars_from_fields({"x_over_lambda": x, "pressure": f.pressure}, shape)
    assert abs(sc["ka"] - sol.ka) < 1e-5 and "penetration" not in sc


def test_full_contact_phase_from_fields():
    sol = analytic.solve(load=2.0, speed=0.1)
    x = np.arange(256) / 256 - 0.5
    f = sol.fields(x)
    sc, patches = verify.scalars_from_fields({"x_over_lambda": x, "pressure": f.pressure},
                                             suite.ProfileShape({"hk": 1.0}))
    assert sc["full_contact"] and patches == [] and sc["ka"] == np.pi
    assert sc["ke_hat"] == pytest.approx(sol.ke_hat, abs=1e-12)
    assert sc["mu"] == pytest.approx(sol.mu, rel=1e-12)


# ---------------------------------------------------------------------------- the HTML renderer
def test_html_renderer_embeds_images_and_escapes(tmp_path):
    import base64
    png = base64.b64decode("iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNk"
                           "YPhfDwAChwGA60e6kgAAAABJRU5ErkJggg==")
    (tmp_path / "a.png").write_bytes(png)
    md = ("# Title <x>\n\nText with `a<b` and **bold**.\n\n```\nif a < b:\n```\n\n"
          + _html.table(["q", "verdict"], [["μ", "PASS"], ["x|y", "FAIL"]])
          + "\n- one\n- two\n\n![a caption](a.png)\n")
    page = _html.render(md, tmp_path, title="t")
    assert "<h1>Title &lt;x&gt;</h1>" in page and "<code>a&lt;b</code>" in page
    assert "<pre><code>if a &lt; b:</code></pre>" in page and "<strong>bold</strong>" in page
    assert "<td>x|y</td>" in page and '<span class="fail">FAIL</span>' in page
    assert "<ul><li>one</li><li>two</li></ul>" in page
    assert f'src="data:image/png;base64,{base64.b64encode(png).decode()}"' in page
    assert _html.render(md, tmp_path, title="t") == page  # deterministic


# ---------------------------------------------------------------------------- independence
def test_verify_imports_no_private_name_of_bem():
    import ast
    from pathlib import Path
    tree = ast.parse("\n".join(p.read_text(encoding="utf-8")  # every module of the package
                               for p in sorted(Path(verify.__file__).parent.glob("*.py"))))
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("bem"):
            assert not node.module.startswith("bem._"), node.module
            assert not any(a.name.startswith("_") for a in node.names)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) \
                and node.value.id == "bem":
            assert not node.attr.startswith("_"), node.attr
