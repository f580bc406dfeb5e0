"""The README's examples print what it says they print: its digits come from the code as it is,
not from a past run.  Each example runs as written (the shell ones with bash, the `viscosine`
command on the PATH, in a temporary folder) and every number it promises is compared with what
came out.  The surface examples are checked beside their solver (tests/bem/test_bem_surface.py,
tests/comparisons/test_cli_surface.py); docs/tutorial.md by tests/test_tutorial.py."""
import contextlib
import io
import json
import os
import re
import shlex
import subprocess
import sys
from pathlib import Path

from comparisons import cli

ROOT = Path(__file__).resolve().parents[1]
TEXT = (ROOT / "README.md").read_text(encoding="utf-8")


def _blocks(lang):
    return re.findall(rf"^```{lang}\n(.*?)^```$", TEXT, re.M | re.S)


def _run(capsys, argv):
    rc = cli.main(argv)
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


def test_the_python_start_example_prints_what_it_says():
    block = next(b for b in _blocks("python") if "analytic.solve(" in b and "bem.solve(" in b)
    code = "\n".join(ln for ln in block.splitlines() if not ln.startswith("# "))
    promised = [ln[2:] for ln in block.splitlines() if ln.startswith("# ")]
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(compile(code, "README.md, Start", "exec"), {"__name__": "__readme__"})
    assert out.getvalue().splitlines() == promised


def test_the_point_commands_print_what_they_say(capsys):
    lines = [ln for ln in TEXT.splitlines() if ln.startswith("python -m comparisons point")
             and "--surface" not in ln and '# "' in ln]
    assert len(lines) == 2
    for line in lines:
        command, promised = line.split("#", 1)
        rc, out, err = _run(capsys, shlex.split(command)[3:])
        assert rc == 0, err
        rec = json.loads(out)
        estimate = re.search(r'"error_estimate": \{(.*?)[,}]', promised)
        scalars = promised[:estimate.start()] if estimate else promised
        pairs = re.findall(r'"(\w+)": ([-\d.e+]+)', scalars)
        assert pairs, line
        for key, value in pairs:
            assert repr(rec[key]) == value, (key, rec[key], value)
        if estimate:  # printed to two digits
            for key, value in re.findall(r'"(\w+)": ([-\d.e+]+)', estimate.group(1)):
                assert f"{rec['error_estimate'][key]:.1e}" == value, key


def test_the_verify_command_prints_what_it_says(capsys, tmp_path, monkeypatch):
    line = next(ln for ln in TEXT.splitlines() if ln.startswith("python -m comparisons verify"))
    after = TEXT.split(line, 1)[1].splitlines()[1:3]
    monkeypatch.chdir(tmp_path)  # its report goes to ./verify-report
    rc, out, err = _run(capsys, shlex.split(line)[3:])
    assert rc == 0, err
    lines = out.splitlines()
    count = int(re.search(r"\((\d+) quantities", after[0]).group(1))
    assert sum(ln.startswith("PASS ") for ln in lines) == count
    orders = next(ln for ln in lines if ln.startswith("orders vs reference: "))
    for key, value in re.findall(r"(\w+) ([\d.]+)", after[0].split("orders vs reference: ")[1]):
        assert f" {key} {value}," in orders + ",", (key, value, orders)
    assert after[1][2:] in lines + err.splitlines()  # the verdict (on either stream)
    assert (tmp_path / "verify-report" / "report.md").exists()


def test_your_material_in_si_runs_as_written(tmp_path):
    """The DMA example: the friction curve it prints, row by row, to the last digit."""
    head = TEXT.split("## Your material, in SI", 1)[1]
    block = re.search(r"^```sh\n(.*?)^```$", head, re.M | re.S).group(1)
    code = "\n".join(ln for ln in block.splitlines() if not ln.startswith("# "))
    promised = re.findall(r"([\d.e+-]+,[\d.e+-]+)", "\n".join(
        ln for ln in block.splitlines() if ln.startswith("# ")))
    assert len(promised) == 5
    (tmp_path / "comparisons").symlink_to(ROOT / "comparisons")  # its file, from the clone
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    proc = subprocess.run(["bash", "-e", "-o", "pipefail", "-c", code], capture_output=True,
                          text=True, cwd=tmp_path, env=env)
    assert proc.returncode == 0 and "Traceback" not in proc.stderr, proc.stderr
    rows = proc.stdout.splitlines()
    assert rows[0] == "speed,mu" and rows[1:] == promised
    assert (tmp_path / "my-rubber" / "mastercurve.png").stat().st_size > 10_000
