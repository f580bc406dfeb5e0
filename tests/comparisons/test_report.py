"""End to end: `report --quick` and `sweep --solver bem` into a temporary folder, and --resume."""
import json
import os
import re
import shutil
import subprocess
import sys

import pytest

from comparisons import operating_point as op
from comparisons import report


def _cli(*args, cwd):
    return subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True,
                          text=True, cwd=cwd)


def test_quick_report_writes_every_part(quick_report):
    out, proc = quick_report
    assert proc.returncode == 0, proc.stderr
    assert "report: [" in proc.stderr  # progress on standard error
    md = (out / "report.md").read_text()
    figures = (["material", "fig03a", "fig03b"] + [f"fig{n:02d}" for n in range(4, 13)]
               + ["fields", "convergence", "layers_mu", "layers_contact", "layers_full_contact"]
               + ["surface_pressure", "surface_mu", "surface_direction", "surface_persson"]
               + (["tamaas_dt"] if report.tamaas_installed() else []))
    for fig in figures:
        assert (out / f"{fig}.png").stat().st_size > 10_000
        assert f"({fig}.png)" in md
    for section in ["The material", "Fields: σ(x) and v(x)", "Scalars from both roads",
                    "Agreement of the two roads", "Convergence of the BEM",
                    "A layer of finite thickness", "Surfaces: a rigid periodic surface",
                    "A third code: Tamaas", "Provenance"]:
        assert f"## {section}" in md, section
    assert "numba" in md and "date (UTC)" in md
    assert re.search(r"^\| time: layer section: runs \(sum over processes\) \| [\d.]+ s \|$",
                     md, re.M)
    contents = next(ln for ln in md.splitlines() if ln.startswith("Contents: "))
    assert ("not in this report" in contents) != report.tamaas_installed()
    assert re.search(r"^\| runs done on \| (this process|\d+ local processes) \|$", md, re.M)
    html = (out / "report.html").read_text()
    assert html.count("data:image/png;base64,") == len(figures) and "src=\"fig" not in html


def test_quick_report_has_the_third_code_against_both_roads(quick_report):
    """Tamaas at three speeds around the friction peak, each (speed, dt) run its own store
    entry; its μ error halves with dt and its Richardson μ meets both roads."""
    pytest.importorskip("tamaas")  # the test extra installs it
    out, _ = quick_report
    specs = [json.loads(p.read_text())["spec"] for p in (out / "results").glob("*.json")]
    tamaas = [s for s in specs if s["solver"] == "tamaas"]
    assert len(tamaas) == 9 and {s["cells_per_step"] for s in tamaas} == {1, 2, 4}
    md = (out / "report.md").read_text()
    section = md.split("## A third code: Tamaas")[1].split("\n## ")[0]
    ratios = [float(r) for r in re.findall(r"^\| [\d.]+ \| [12] × T/N \|.* \| ([\d.]+) \|$",
                                           section, re.M)]
    # first order in dt: the error halves with the step (measured 1.93–2.07 at N = 128)
    assert len(ratios) == 6 and all(1.8 < r < 2.2 for r in ratios)
    mu = re.findall(r"^\| [\d.]+ \((below|at|above) the peak\) \| μ \|(.*)\|$", section, re.M)
    assert [m[0] for m in mu] == ["below", "at", "above"]
    for _, cells in mu:
        bem_diff, tamaas_diff = (abs(float(c)) for c in cells.split("|")[-2:])
        # measured at the quick meshes (BEM 1024, Tamaas 128): 1.9e-5 and 1.6e-3 relative
        assert bem_diff < 5e-5 and tamaas_diff < 3e-3


def test_without_tamaas_the_section_says_how_to_install_it(monkeypatch):
    monkeypatch.setattr(report, "tamaas_installed", lambda: False)
    cfg = report.config(True, workers=1)
    assert report.tamaas_runs(cfg) == []
    assert not any(s["solver"] == "tamaas" or s["load"] == report.TAMAAS_LOAD
                   for s, _ in report.runs(cfg))
    doc = report.Doc()
    report.tamaas_section(doc, None, None, cfg, {})
    md = doc.markdown()
    assert "pip install 'viscosine[peers]'" in md  # from PyPI
    assert "From a clone of the repository" in md and "pip install '.[peers]'" in md
    assert "--resume" in md


def test_quick_report_html_is_the_markdown_rendered(quick_report):
    """report.html renders report.md: code spans, tables, headings and embedded images."""
    out, _ = quick_report
    md = (out / "report.md").read_text()
    html = (out / "report.html").read_text()
    assert "<code>analytic/</code>" in html
    outside_code = re.sub(r"<pre>.*?</pre>|<code>.*?</code>", "", html, flags=re.S)
    assert "`" not in outside_code  # no Markdown code span left raw
    tables = re.findall(r"^\|(?:---\|)+$", md, re.M)
    assert html.count("<table>") == len(tables) > 5 and "| --- |" not in html
    assert html.count("<h2>") == len(re.findall(r"^## ", md, re.M))
    images = re.findall(r"^!\[[^\]]*\]\(([^)]+)\)$", md, re.M)
    assert html.count('<img src="data:image/png;base64,') == len(images)
    assert "![" not in html


def test_quick_report_agreement_is_within_the_measured_tolerances(quick_report):
    out, _ = quick_report
    md = (out / "report.md").read_text()
    row = re.search(r"^\| 4096 \| ([^|]+) \| ([^|]+) \| ([^|]+) \| ([^|]+) \| ([^|]+) \| 0 \|$", md, re.M)
    assert row, "grid table row at N = 4096 missing or a point did not converge"
    pen, mu, ka, ke, keh = (float(x) for x in row.groups())
    assert pen < 2e-6 and mu < 1.5e-5 and ka < 6e-4 and ke < 6e-4 and keh < 2.5e-6


@pytest.mark.slow  # about 15 s: the report rebuilt whole
def test_resume_recomputes_only_what_is_missing(quick_report, tmp_path):
    out = tmp_path / "report"  # a copy: the quick report is shared (tests/conftest.py)
    shutil.copytree(quick_report[0], out)
    results = out / "results"
    files = sorted(p for p in results.iterdir() if p.suffix == ".json")
    solver = {p: json.loads(p.read_text())["spec"]["solver"] for p in files}
    removed = ([p for p in files if solver[p] == "bem"][:2]
               + [p for p in files if solver[p] == "tamaas"][:1])
    removed = removed if len(removed) == 3 else files[:3]  # without tamaas: three BEM runs
    kept = next(p for p in files if p not in removed)
    mtime = kept.stat().st_mtime_ns
    figures = {p: p.stat().st_mtime_ns for p in out.glob("*.png")}
    for p in removed:
        p.unlink()
    proc = _cli("report", "--quick", "--resume", "--workers", "1", "--out", str(out), cwd=out)
    assert proc.returncode == 0, proc.stderr
    counts = re.findall(r"(\d+) (?:BEM|Tamaas) runs, (\d+) already done", proc.stderr)
    assert sum(int(n) - int(done) for n, done in counts) == 3
    assert all(p.exists() for p in removed)
    assert kept.stat().st_mtime_ns == mtime
    assert not any(p.name.endswith(".part.json") for p in results.iterdir())
    # the runs solved again are the same to the bit: no figure's inputs changed, none is drawn
    assert len(figures) >= 20
    assert {p: p.stat().st_mtime_ns for p in out.glob("*.png")} == figures


def test_bem_sweep_and_point_with_files(tmp_path):
    proc = _cli("sweep", "--solver", "bem", "--nodes", "512", "--load", "0.3", "1.0",
                "--speed", "0.5", "2", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    recs = [json.loads(line) for line in proc.stdout.splitlines()]
    assert [(r["load_asked"], r["speed"]) for r in recs] == [(0.3, 0.5), (0.3, 2.0), (1.0, 0.5), (1.0, 2.0)]
    assert all(abs(r["load"] / r["load_asked"] - 1.0) < 1e-8 for r in recs)  # achieved
    assert all(r["solver"] == "bem" and r["nodes"] == 512 and r["iterations"] >= 0 for r in recs)
    import analytic
    assert [r["full_contact"] for r in recs] == [analytic.solve(load=r["load_asked"], speed=r["speed"]).full_contact
                                                for r in recs] == [False, False, True, True]
    # a two-harmonic profile and a two-term Prony series read from files
    (tmp_path / "profile.txt").write_text("# k y over one period\n" + "\n".join(
        repr(float(__import__("math").cos(2 * 3.141592653589793 * (j / 64 - 0.5))
                   + 0.2 * __import__("math").cos(6 * 3.141592653589793 * (j / 64 - 0.5))))
        for j in range(64)) + "\n")
    (tmp_path / "prony.txt").write_text("J0 1.0\n0.5 1.0\n0.2 0.01\n")
    proc = _cli("point", "--solver", "bem", "--nodes", "1024", "--load", "0.2", "--speed", "1",
                "--profile", "profile.txt", "--prony", "prony.txt", "--fields", "f.csv", cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    rec = json.loads(proc.stdout)
    assert rec["mu"] > 0 and os.path.getsize(tmp_path / "f.csv") > 1000


def test_bem_bad_input_from_the_command_line(tmp_path):
    for args, word in [(["--nodes", "4"], "nodes"), (["--nodes", "12.5"], "nodes"),
                       (["--prony", "missing.txt"], "prony")]:
        proc = _cli("point", "--solver", "bem", "--load", "0.3", "--speed", "1", *args, cwd=tmp_path)
        assert proc.returncode == 2 and proc.stdout == ""
        lines = proc.stderr.strip().splitlines()
        assert len(lines) == 1 and word in lines[0].lower(), proc.stderr
    (tmp_path / "bad.txt").write_text("J0 1.0\n-0.5 1.0\n")
    proc = _cli("point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--prony", "bad.txt", cwd=tmp_path)
    assert proc.returncode == 2 and len(proc.stderr.strip().splitlines()) == 1


def test_runs_on_a_scheduler_are_credited_to_its_address(tmp_path, monkeypatch):
    """Provenance says where the runs went: the scheduler's address, not this machine's cores."""
    from comparisons import _cluster, runner
    from comparisons.store import Store

    class FakeCluster(_cluster.SerialExecutor):
        workers = 3
    monkeypatch.setattr(_cluster, "executor", lambda workers, scheduler: FakeCluster())
    jobs = [(op.at("bem", 1.0, load=0.3, nodes=64), False)]
    st = Store(str(tmp_path))
    _, where = report.execute(report.config(True), st, False, "tcp://10.0.0.1:8786", jobs=jobs)
    assert where == "Dask scheduler tcp://10.0.0.1:8786 (3 workers)"
    _, where = report.execute(report.config(True), st, True, "tcp://10.0.0.1:8786", jobs=jobs)
    assert where.startswith("none")  # --resume with everything stored runs nothing
