"""The SI doors: the solid's time by name on every door (a bare tau refused), the same result
protocol on every SI result, self-explaining SI records, and warnings for unit slips."""
import pytest

import analytic
import bem
from comparisons import cli
from viscosine import si

SLS = dict(E0=1e6, Einf=3e6, nu=0.5, wavelength=1e-3, amplitude=1e-4, speed=0.05)
TIME_HINT = r"which time\? give tau_creep .* or tau_relax"


def _cli(capsys, *argv):
    rc = cli.main(list(argv))
    out = capsys.readouterr()
    return rc, out.out, out.err


# ------------------------------------------------------------------------ which time
@pytest.mark.parametrize("door", [
    lambda kw: si.scales(**kw),
    lambda kw: analytic.solve_si(**kw),
    lambda kw: bem.solve_si(**kw, nodes=512),
])
def test_a_bare_tau_is_refused_naming_the_two_times(door):
    with pytest.raises(ValueError, match=r"^tau=0\.01 is not allowed: " + TIME_HINT):
        door(dict(SLS, tau=0.01, mean_pressure=2e4))


def test_the_surface_door_refuses_a_bare_tau_too():
    import numpy as np
    z = 1e-4 * np.cos(2 * np.pi * (np.arange(16) / 16 - 0.5))[:, None] * np.ones((1, 16))
    with pytest.raises(ValueError, match=r"^tau=0\.01 is not allowed: " + TIME_HINT):
        bem.solve_surface_si(E0=1e6, Einf=3e6, tau=0.01, nu=0.5, length=1e-3, speed=0.05,
                             heights=z, mean_pressure=2e4, nodes=16)


def test_relaxation_and_creep_times_are_the_same_solid():
    a = si.scales(**SLS, tau_creep=0.01, mean_pressure=2e4)
    b = si.scales(**SLS, tau_relax=0.01 / 3, mean_pressure=2e4)
    assert b.tau == pytest.approx(a.tau, rel=1e-15) and b.speed == pytest.approx(a.speed,
                                                                                   rel=1e-15)


POINT_SI = ["--units", "SI", "--E0", "1e6", "--Einf", "3e6", "--nu", "0.5", "--wavelength",
            "1e-3", "--amplitude", "1e-4", "--load", "2e4", "--speed", "0.05"]


@pytest.mark.parametrize("argv", [
    ["point", "--solver", "analytic", *POINT_SI, "--tau", "0.01"],
    ["sweep", "--solver", "analytic", *POINT_SI, "--tau", "0.01"],
    ["verify", "--scalars", "x.jsonl", *POINT_SI, "--tau", "0.01"],
])
def test_a_bare_tau_option_is_refused_in_one_line(capsys, argv):
    rc, out, err = _cli(capsys, *argv)
    assert rc == 2 and out == ""
    line, = err.strip().splitlines()
    assert "--tau 0.01: which time?" in line and "--tau-creep" in line and "--tau-relax" in line
    assert len(line) - len("python -m comparisons " + argv[0] + ": ") <= 160


def test_verify_needs_one_of_the_two_times(capsys):
    rc, _, err = _cli(capsys, "verify", "--scalars", "x.jsonl", *POINT_SI)
    assert rc == 2 and "--tau-creep: missing with --units SI" in err and "--tau-relax" in err
