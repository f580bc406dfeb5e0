"""Every bad input of the semi-analytic road: a ValueError naming the parameter, its value and
what is allowed; from the command line one line on standard error and exit status 2."""
import math
import subprocess
import sys

import pytest

import analytic

BAD = [
    ("load", 0.0), ("load", -0.1), ("load", math.nan), ("load", math.inf),
    ("speed", -1.0), ("speed", math.nan), ("speed", math.inf),
    ("ratio", 1.0), ("ratio", 0.5), ("ratio", math.nan),
    ("hk", 0.0), ("hk", -2.0), ("hk", math.inf),
]
GOOD = dict(load=0.3, speed=1.0, ratio=3.0, hk=1.0)


@pytest.mark.parametrize("name,value", BAD)
def test_solve_bad_input(name, value):
    kw = {**GOOD, name: value}
    with pytest.raises(ValueError) as exc:
        analytic.solve(**kw)
    msg = str(exc.value)
    assert msg.startswith(f"{name}=") and repr(float(value)) in msg and "is not allowed" in msg


@pytest.mark.parametrize("value", [0.0, -0.5, 1.0000001, 2.0, math.nan])
def test_solve_penetration_bad_input(value):
    with pytest.raises(ValueError, match=r"penetration=.* is not allowed: .*Δ/h in \[1e-40, 1\]"):
        analytic.solve(penetration=value, speed=1.0)


def test_non_numbers_are_refused():
    with pytest.raises(ValueError, match="load"):
        analytic.solve(load="0.3", speed=1.0)
    with pytest.raises(ValueError, match="speed"):
        analytic.solve(load=0.3, speed=True)


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True, text=True)


@pytest.mark.parametrize("args,word", [
    (["--load", "-1", "--speed", "1"], "load"),
    (["--load", "0.3", "--speed", "-1"], "speed"),
    (["--load", "0.3", "--speed", "1", "--ratio", "1"], "ratio"),
    (["--load", "0.3", "--speed", "1", "--hk", "0"], "hk"),
    (["--penetration", "1.5", "--speed", "1"], "penetration"),
    (["--penetration", "0", "--speed", "1"], "penetration"),
    (["--load", "nan", "--speed", "1"], "load"),
    (["--load", "abc", "--speed", "1"], "load"),
    (["--load", "0.3"], "speed"),
])
def test_cli_bad_input(args, word):
    proc = _cli("point", "--solver", "analytic", *args)
    assert proc.returncode == 2
    assert proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and word in lines[0]


def test_cli_sweep_bad_input_prints_nothing():
    proc = _cli("sweep", "--solver", "analytic", "--load", "0.3", "-2", "--speed", "1")
    assert proc.returncode == 2 and proc.stdout == "" and len(proc.stderr.strip().splitlines()) == 1
