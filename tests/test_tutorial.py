"""docs/tutorial.md runs as written: its Python blocks in order in one namespace, its shell blocks
with bash, in a temporary folder; the figures it promises appear.

Every BEM call of the tutorial pins its mesh (``nodes=2048`` / ``--nodes 2048``), so this test
does not depend on the BEM's default mesh; the whole run (about 22 s of CPU) is marked slow.
"""
import contextlib
import io
import json
import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TUTORIAL = ROOT / "docs" / "tutorial.md"


def blocks():
    """(language, code) of every fenced block, in order."""
    return re.findall(r"^```(\w+)\n(.*?)^```$", TUTORIAL.read_text(encoding="utf-8"), re.M | re.S)


def test_every_bem_call_pins_its_mesh():
    code = blocks()
    assert {lang for lang, _ in code} == {"python", "sh"}
    calls = [c for _, c in code if "bem.solve(" in c or "bem.solve_surface(" in c]
    assert calls and all("nodes=" in c for c in calls)
    lines = [ln for _, c in code for ln in c.splitlines() if "--solver bem" in ln]
    assert lines and all("--nodes" in ln for ln in lines)


@pytest.mark.slow  # about 22 s of CPU: every block of the tutorial, its command lines included
def test_the_tutorial_runs_as_written(tmp_path, monkeypatch):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    monkeypatch.chdir(tmp_path)
    bin_dir = tmp_path / "bin"  # `python` on PATH is this interpreter, as after an install
    bin_dir.mkdir()
    wrapper = bin_dir / "python"  # a script, not a symlink: a venv's python finds its
    wrapper.write_text(f'#!/bin/sh\nexec "{sys.executable}" "$@"\n')  # packages by its path
    wrapper.chmod(0o755)
    env = {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}",
           "PYTHONPATH": f"{ROOT}{os.pathsep}{os.environ.get('PYTHONPATH', '')}"}
    namespace = {"__name__": "__tutorial__"}
    printed = io.StringIO()
    try:
        for i, (lang, code) in enumerate(blocks()):
            if lang == "python":
                with contextlib.redirect_stdout(printed):
                    exec(compile(code, f"{TUTORIAL.name}, block {i}", "exec"), namespace)
            else:
                proc = subprocess.run(["bash", "-e", "-c", code], capture_output=True, text=True,
                                      env=env, cwd=tmp_path)
                assert proc.returncode == 0, f"block {i}:\n{code}\n{proc.stderr}"
                assert "Traceback" not in proc.stderr
    finally:
        plt.close("all")
    assert (tmp_path / "surface.npz").stat().st_size > 100_000  # 128 x 128 fields
    assert json.loads((tmp_path / "surface.json").read_text())["direction"] == 30.0
    for name in ("friction.png", "friction_cli.png"):
        assert (tmp_path / name).stat().st_size > 10_000, name
    for name, n in (("sls.jsonl", 21), ("sls_bem.jsonl", 21), ("prony3.jsonl", 19)):
        assert len((tmp_path / name).read_text().splitlines()) == n, name
    # the numbers the text gives to check against are the ones printed
    text = TUTORIAL.read_text(encoding="utf-8")
    promised = re.findall(r"^It prints `([^`]+)`", text, re.M)
    promised += [ln.strip() for ln in text.splitlines() if ln.startswith("    V/V0 = ")]
    promised += [ln[4:] for ln in text.splitlines()  # the layer's two tables (10 and 9 lines)
                 if ln.startswith(("    bonded ", "    frictionless ", "    half-space "))]
    promised += [ln[4:] for ln in text.splitlines() if ln.startswith("    θ = ")]  # a surface
    out = printed.getvalue().splitlines()
    assert len(promised) == 31 and all(p in out for p in promised), (promised, out)
    # raw isotherms to the friction master curve: the shift figure, the curve and its record
    for name in ("sbr/shifts.png", "sbr/mastercurve.png"):
        assert (tmp_path / name).stat().st_size > 10_000, name
    run = json.loads((tmp_path / "sbr" / "mastercurve.json").read_text())
    assert len(run["points"]) == 12 and all(p["success"] for p in run["points"])
    mu = {(p["temperature"], p["speed"]): p for p in run["points"]}
    assert f"μ = {mu[(40.0, 1e-6)]['mu']:.4f}" in text and mu[(40.0, 1e-6)]["extrapolated"]
    assert sum(p["extrapolated"] for p in run["points"]) == 1
    sls = [json.loads(ln) for ln in (tmp_path / "sls.jsonl").read_text().splitlines()]
    assert f'"mu": {sls[0]["mu"]!r}' in text and sls[0]["speed"] == 0.01
    # what the text says: the BEM's circles sit on the semi-analytic curve
    analytic = namespace["analytic"]
    for s, mu in zip(namespace["bem_speeds"], namespace["mu_sls"]):
        assert mu == pytest.approx(analytic.solve(load=0.3, speed=s).mu, rel=1e-3)
    # and the Prony material's three humps (one per creep time) are where the text puts them
    mu = namespace["mu_prony"]
    humps = [float(namespace["prony_speeds"][i]) for i in range(1, len(mu) - 1)
             if mu[i - 1] < mu[i] > mu[i + 1]]
    assert len(humps) == 3 and all(0.3 < h / c < 3.0 for h, c in zip(humps, (0.01, 1.0, 100.0)))
    # the layer: what the text says changes.  The contact shrinks as either layer thins (a
    # stiffer body under the same load) and the frictionless layer is the softer of the two at
    # one thickness; the thin frictionless layer is refused (the crest reaches the foundation)
    res = namespace["layer_results"]
    for foundation, ds in (("bonded", (0.05, 0.1, 0.2, 0.5, None)),
                           ("frictionless", (0.1, 0.2, 0.5, None))):
        width = [res[foundation, d].contact_fraction for d in ds]
        assert all(res[foundation, d].success for d in ds)
        assert all(a < b for a, b in zip(width, width[1:])), (foundation, width)
    assert all(res["bonded", d].contact_fraction < res["frictionless", d].contact_fraction
               for d in (0.1, 0.2, 0.5))
    refused = res["frictionless", 0.05]
    assert not refused.success
    assert refused.diagnostics["layer"]["approach"] >= refused.diagnostics["layer"]["thickness"]
