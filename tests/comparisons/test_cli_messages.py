"""Careless command lines: each is refused before any work with exit status 2 and ONE line on
standard error, at most 160 characters, beginning with the subcommand's prefix and naming the
option as typed, no phrase said twice (the CLI contract of `comparisons.cli`).

Run as a script (``python tests/comparisons/test_cli_messages.py``) it prints the count of lines that break
the contract and the longest message, over all the command lines below.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from comparisons.cli import main

PROG = "python -m comparisons"
SBR = (Path(__file__).resolve().parents[2] / "comparisons" / "data" / "suite" / "materials"
       / "dma-sbr.csv")
LIMIT = 160

P = ["point", "--solver", "analytic", "--speed", "1"]          # a point missing only its load
PB = ["point", "--solver", "bem", "--load", "0.1", "--speed", "1"]
PA = P + ["--load", "0.1"]
S = ["sweep", "--solver", "analytic", "--speed", "1"]
SI = ["point", "--solver", "analytic", "--units", "SI", "--load", "1e5", "--speed", "0.01",
      "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01", "--nu", "0.5",
      "--wavelength", "1e-3", "--amplitude", "1e-5"]
MC = ["mastercurve", "--wlf", "17.4", "51.6", "20", "--temperatures", "20", "--speeds", "0.01",
      "--load", "1e5", "--wavelength", "1e-3", "--amplitude", "1e-5", "--nu", "0.5",
      "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01"]


def _replace(argv, option, value):
    """``argv`` with the value after ``option`` replaced (the option's first value)."""
    i = argv.index(option)
    return argv[:i + 1] + [value] + argv[i + 2:]


BAD_REALS = ["0", "-1", "nan", "inf", "1e400", "abc"]

#: (argv, the option the message must name)
CASES = []
for value in BAD_REALS:
    CASES += [
        (P + ["--load", value], "--load"),
        (P + ["--penetration", value], "--penetration"),
        (_replace(PA, "--speed", "-1" if value == "0" else value), "--speed"),
        (PA + ["--ratio", value], "--ratio"),
        (PA + ["--hk", value], "--hk"),
        (PB + ["--nodes", value], "--nodes"),
        (PB + ["--rtol", value], "--rtol"),
        (PB + ["--max-nodes", value], "--max-nodes"),
        (S + ["--load", "0.1", value], "--load"),
        *([(_replace(SI, "--nu", value), "--nu")] if value != "0" else []),  # ν = 0 is fine
        (_replace(SI, "--E0", value), "--E0"),
        (_replace(SI, "--wavelength", value), "--wavelength"),
        (_replace(SI, "--amplitude", value), "--amplitude"),
        (_replace(SI, "--tau-creep", value), "--tau-creep"),
        (_replace(MC, "--load", value), "--load"),
        *([(_replace(MC, "--nu", value), "--nu")] if value != "0" else []),
        (["bench", "--points", value], "--points"),
        (["report", "--workers", value], "--workers"),
    ]
CASES += [
    (PA + ["--ratio", "1"], "--ratio"),
    (PA + ["--ratio", "1e9"], "--ratio"),
    (PA + ["--hk", "1e7"], "--hk"),
    (P + ["--load", "1e41"], "--load"),
    (P + ["--penetration", "1.5"], "--penetration"),
    (_replace(PA, "--speed", "1e31"), "--speed"),
    (PB + ["--nodes", "4"], "--nodes"),
    (PB + ["--nodes", "1e9"], "--nodes"),
    (PB + ["--nodes", "100.5"], "--nodes"),
    (PB + ["--rtol", "0.5"], "--rtol"),
    (PB + ["--max-nodes", "1000"], "--max-nodes"),
    (PB + ["--max-nodes", "2e9"], "--max-nodes"),
    (PB + ["--hk", "1e7"], "--hk"),
    (PB + ["--ratio", "1e9"], "--ratio"),
    (_replace(PB, "--load", "1e9"), "--load"),
    (_replace(PB, "--load", "1e-12"), "--load"),
    (PA + ["--penetration", "0.5"], "--penetration"),
    (PA + ["--nodes", "64"], "--nodes"),
    (PA + ["--rtol", "1e-3"], "--rtol"),
    (PA + ["--profile", "{bad}"], "--profile"),
    (PB + ["--profile", "{bad}"], "--profile"),
    (PB + ["--profile", "{missing}"], "--profile"),
    (PB + ["--profile", "{empty}"], "--profile"),
    (PB + ["--prony", "{bad}"], "--prony"),
    (PB + ["--prony", "{missing}"], "--prony"),
    (PB + ["--prony", "{stiff}"], "--prony"),      # a series out of the BEM's range: the file
    (PB + ["--material", "{longtau}"], "--material"),
    (PB + ["--material", "{missing}"], "--material"),
    (PB + ["--material", "{bad}"], "--material"),
    (PA + ["--fields", "{bad}/f.csv"], "--fields"),
    (PB + ["--max-residual", "0.1"], "--max-residual"),
    (PB + ["--material", "{empty}"], "--material"),
    (PB + ["--material", str(SBR), "--temperature", "100", "--shift-table", "{table}"],
     "--temperature"),
    (PB + ["--temperature", "20"], "--temperature"),
    (PB + ["--thickness", "0"], "--thickness"),
    (PB + ["--thickness", "-1"], "--thickness"),
    (PB + ["--surface", "bisinusoid", "--aspect", "0"], "--aspect"),
    (PB + ["--surface", "bisinusoid", "--hk-y", "-1"], "--hk-y"),
    (PB + ["--direction", "nan"], "--direction"),
    (_replace(SI, "--nu", "0.7"), "--nu"),
    (_replace(SI, "--Einf", "1e5"), "--Einf"),
    (_replace(SI, "--speed", "-1"), "--speed"),
    (_replace(SI, "--speed", "1e30"), "--speed"),
    (_replace(SI, "--amplitude", "1e3"), "--amplitude"),
    (SI[:-2], "--amplitude"),
    (SI + ["--tau-relax", "0.01"], "--tau-relax"),
    (["sweep", "--solver", "analytic", "--load", "0.1", "--speed", "1:0:3"], "--speed"),
    (["sweep", "--solver", "analytic", "--load", "0.1", "--speed", "1:10:0"], "--speed"),
    (["sweep", "--solver", "analytic", "--load", "0.1", "--speed", "1", "--workers", "0"],
     "--workers"),
    (_replace(MC, "--temperatures", "abc"), "--temperatures"),
    (_replace(MC, "--speeds", "-1"), "--speeds"),
    (_replace(MC, "--wavelength", "-1"), "--wavelength"),
    (MC + ["--nodes", "3"], "--nodes"),
    (MC + ["--rtol", "5"], "--rtol"),
    (_replace(MC, "--Einf", "1e5"), "--Einf"),
    (["verify", "--case", "no-such-case", "--scalars", "{missing}"], "--case"),
    (["verify", "--scalars", "{missing}", "--load", "0.1", "--speed", "1"], "--scalars"),
    (["verify", "--scalars", "{bad}", "--load", "0.1", "--speed", "1"], "--scalars"),
    (["verify", "--scalars", "{empty}", "--load", "-1", "--speed", "1"], "--load"),
    (["verify", "--scalars", "{empty}", "--load", "0.1", "--speed", "nan"], "--speed"),
    (["verify", "--scalars", "{empty}", "--load", "0.1", "--speed", "1", "--rtol", "-1"],
     "--rtol"),
    (["verify", "--scalars", "{empty}", "--load", "0.1", "--speed", "1", "--tol", "mu=abc"],
     "--tol"),
    (["suite", "--check", "--cases", "no-such-case"], "no-such-case"),
    (["suite", "--check", "--workers", "0"], "--workers"),
    (["bench", "--max-log2n", "99"], "--max-log2n"),
    (["report", "--out", "{bad}"], "--out"),
    # the materials' flags: a value out of range, a choice that is none, a flag without the
    # data it applies to
    (PB + ["--material", str(SBR), "--extend", "9"], "--extend"),
    (PB + ["--material", str(SBR), "--extend", "nan"], "--extend"),
    (PB + ["--extend", "1"], "--extend"),
    (PB + ["--material", str(SBR), "--frequency-unit", "kHz"], "--frequency-unit"),
    (PB + ["--material", str(SBR), "--frequency-unit", "rad/s"], "--frequency-unit"),
    (PB + ["--material", str(SBR), "--material-kind", "K"], "--material-kind"),
    (PB + ["--material", str(SBR), "--material-kind", "G"], "--material-kind"),
    (PB + ["--material", str(SBR), "--vertical-shift", "fitted"], "--vertical-shift"),
    (PB + ["--material", str(SBR), "--shift-method", "tan"], "--shift-method"),
    (MC + ["--shift-method", "moduli"], "--shift-method"),
    (PB + ["--material", str(SBR), "--nu", "0.7"], "--nu"),
    # an option for a form it does not apply to, a fit's refusal, --nu with tensile moduli
    (PB + ["--material", "{relax}", "--loss-weight", "2"], "--loss-weight"),
    (PB + ["--material", "{relax}", "--per-decade", "2"], "--per-decade"),
    (PB + ["--material", "{gt}", "--nu", "0.4", "--loss-weight", "2"], "--loss-weight"),
    (PB + ["--material", "{gt}", "--nu", "0.4", "--max-residual", "0.1"], "--max-residual"),
    (PB + ["--material", str(SBR), "--per-decade", "0"], "--per-decade"),
    (PB + ["--material", "{gt}", "--nu", "0.4", "--per-decade", "0"], "--per-decade"),
    (PB + ["--material", "{gt}", "--nu", "0.4", "--extend", "9"], "--extend"),
    (PB + ["--material", str(SBR), "--nu", "0.4", "--material-kind", "E"], "--nu"),
]
VS = ["verify", "--scalars", "{empty}"]
#: an option not given where it is needed: ``<option> is missing: <what needs it>`` (one form)
MISSING = [
    (SI[:-2], "--amplitude"),
    (SI[:9] + SI[11:], "--E0"),
    (VS + ["--load", "0.1"], "--speed"),
    (VS + ["--speed", "1"], "--load"),
    (VS + ["--case", "sls-partial-v1", "--units", "SI"], "--E0"),
    (VS + ["--case", "sls-partial-v1", "--units", "SI", "--E0", "1e6", "--nu", "0.5"],
     "--amplitude"),
    (VS + SI[5:9] + ["--units", "SI", "--E0", "1e6", "--Einf", "3e6", "--nu", "0.5",
                     "--wavelength", "1e-3", "--amplitude", "1e-5"], "--tau-creep"),
    (PB + ["--thickness", "0.5", "--nu", "0.5"], "--foundation"),
    (PB + ["--thickness", "0.5", "--foundation", "bonded"], "--nu"),
]
CASES += MISSING


def _argv(argv, tmp):
    files = {"bad": tmp / "bad.txt", "empty": tmp / "empty.txt", "missing": tmp / "missing.txt",
             "table": tmp / "table.csv", "relax": tmp / "relax.txt", "gt": tmp / "gt.csv",
             "stiff": tmp / "stiff.txt", "longtau": tmp / "longtau.txt"}
    return [a.format(**{k: str(v) for k, v in files.items()}) for a in argv]


def _files(tmp):
    (tmp / "bad.txt").write_text("not a profile\n1 2 3\nfoo\n")
    (tmp / "empty.txt").write_text("")
    (tmp / "table.csv").write_text("temperature,log_aT\n-10,3\n20,0\n80,-4\n")
    (tmp / "relax.txt").write_text("E_r 1\n2 0.5\n")
    (tmp / "stiff.txt").write_text("J0 1e9\n0.5 1\n")
    (tmp / "longtau.txt").write_text("J0 1\n0.5 1e40\n")
    (tmp / "gt.csv").write_text("time [s],G [MPa]\n" + "".join(    # G(t) = 1 + 2 exp(-t)
        f"{t!r},{1.0 + 2.0 * math.exp(-t)!r}\n" for t in (10.0 ** (k / 4) for k in range(-12, 9))))


def repeated_phrase(text, words=4):
    """A run of ``words`` words said twice in ``text`` (None if none)."""
    w = re.findall(r"[\w.+\-−]+", text.lower())
    seen = set()
    for i in range(len(w) - words + 1):
        phrase = " ".join(w[i:i + words])
        if phrase in seen:
            return phrase
        seen.add(phrase)
    return None


def problems(argv, option, status, err, tmp=None):
    """What is wrong with one refusal (empty: none).  The length is counted with the temporary
    folder written ``/tmp/x`` (a user's path is the user's)."""
    out = []
    if tmp is not None:
        err = err.replace(str(tmp), "/tmp/x")
    lines = err.splitlines()
    if status != 2:
        out.append(f"exit {status}")
    if len(lines) != 1:
        out.append(f"{len(lines)} lines")
    line = lines[0] if lines else ""
    if len(line) > LIMIT:
        out.append(f"{len(line)} chars")
    if not line.startswith(f"{PROG} {argv[0]}: "):
        out.append("prefix")
    if option not in line:
        out.append(f"does not name {option}")
    phrase = repeated_phrase(line)
    if phrase:
        out.append(f"repeats {phrase!r}")
    return out


@pytest.mark.parametrize("argv, option", CASES, ids=[" ".join(a[:1] + a[-2:]) for a, _ in CASES])
def test_refusal_is_one_short_line(argv, option, tmp_path, capsys):
    _files(tmp_path)
    status = main(_argv(argv, tmp_path))
    err = capsys.readouterr().err
    assert problems(argv, option, status, err, tmp_path) == [], err


@pytest.mark.parametrize("argv, option", MISSING, ids=[" ".join(a[-3:]) for a, _ in MISSING])
def test_a_missing_option_is_said_in_one_form(argv, option, tmp_path, capsys):
    _files(tmp_path)
    assert main(_argv(argv, tmp_path)) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"{PROG} {argv[0]}: {option} is missing: "), err


def test_at_least_sixty_lines():
    assert len(CASES) >= 60


if __name__ == "__main__":  # the measurement: violations and the longest message
    import contextlib
    import io
    import pathlib
    import signal
    import sys
    import tempfile

    def timeout(*_):
        raise TimeoutError("ran > 30 s (not refused)")
    signal.signal(signal.SIGALRM, timeout)
    tmp = pathlib.Path(tempfile.mkdtemp())
    _files(tmp)
    bad, longest = 0, ""
    for argv, option in CASES:
        err, out = io.StringIO(), io.StringIO()
        signal.alarm(30)
        try:
            with contextlib.redirect_stderr(err), contextlib.redirect_stdout(out):
                status = main(_argv(argv, tmp))
        except TimeoutError:
            status = "timeout"
        signal.alarm(0)
        text = err.getvalue()
        found = problems(argv, option, status, text, tmp)
        text = text.replace(str(tmp), "/tmp/x")
        first = text.splitlines()[0] if text.splitlines() else ""
        longest = max(longest, first, key=len)
        if found:
            bad += 1
            print(f"[{'; '.join(found)}] {' '.join(argv)[-70:]}\n    {text.strip()[:400]}",
                  file=sys.stdout)
    print(f"{bad} of {len(CASES)} command lines break the contract; longest message "
          f"{len(longest)} characters:\n{longest}")
