"""One input validator for the whole project (viscosine.checks): a real input is a real number
that is not a bool; every refusal is one line "name=value is not allowed: what is allowed".  The
same bad values are refused, naming the parameter, by every front that takes reals."""
import math

import numpy as np
import pytest

import analytic
import bem
from viscosine import checks
from viscosine import materials as vm

#: not a real number, or not finite: refused wherever a real is asked for
BAD = ["1.0", True, np.bool_(True), math.nan, math.inf, -math.inf, None, [1.0], 1 + 0j]
#: None is "not given" where a parameter has a default or is optional
BAD_GIVEN = [v for v in BAD if v is not None]


def _refused(call, name, value):
    with pytest.raises(ValueError) as exc:
        call(value)
    msg = str(exc.value)
    assert msg.startswith(f"{name}=") and " is not allowed: " in msg, msg
    assert "\n" not in msg
    return msg


# ------------------------------------------------------------------ the validator itself
@pytest.mark.parametrize("value, ok", [
    (1, True), (0.5, True), (np.float64(0.5), True), (np.float32(0.5), True), (np.int64(3), True),
    (math.nan, True), (True, False), (np.bool_(False), False), ("1.0", False), (None, False),
    ([1.0], False), (np.array(1.0), False), (1 + 0j, False),
])
def test_is_real(value, ok):
    assert checks.is_real(value) is ok


def test_refusal_shows_the_value_on_one_line_and_short():
    assert str(checks.bad("x", np.float64(0.3), "y")) == "x=0.3 is not allowed: y"
    assert str(checks.bad("n", np.int64(7), "y")) == "n=7 is not allowed: y"
    assert str(checks.bad("x", np.bool_(True), "y")) == "x=True is not allowed: y"
    assert str(checks.bad("x", "a\nb", "y", unit="m")) == "x='a\\nb' is not allowed: y [m]"
    long = str(checks.bad("heights", np.arange(1000.0), "y"))
    assert "\n" not in long and " ... is not allowed: y" in long
    assert len(long.split(" is not allowed")[0]) == len("heights=") + checks.SHOWN_MAX
    assert str(checks.bad("n", 10 ** 400, "y")).startswith("n=1000")
    path = "/a/long/folder/" * 20 + "profile.csv"  # a file name is shown whole
    assert str(checks.bad("profile", path, "y")) == f"profile={path!r} is not allowed: y"


def test_real():
    assert checks.real("x", np.float32(0.5), "y") == 0.5
    assert type(checks.real("x", np.int64(2), "y")) is float
    assert checks.real("x", 2.0, "y", lambda v: v > 1.0) == 2.0
    with pytest.raises(ValueError, match=r"^x=0\.5 is not allowed: y$"):
        checks.real("x", 0.5, "y", lambda v: v > 1.0)
    with pytest.raises(ValueError, match=r"^x='1' is not allowed: y \[Pa\]$"):
        checks.real("x", "1", "y", unit="Pa")
    with pytest.raises(ValueError, match=r"^x=nan is not allowed: a finite number; y$"):
        checks.real("x", math.nan, "y", kind=True)
    with pytest.raises(ValueError, match=r"^x=True is not allowed: a real number; y$"):
        checks.real("x", True, "y", kind=True)
    with pytest.raises(ValueError, match=r"^x=1000"):
        checks.real("x", 10 ** 400, "y")


def test_integers():
    assert checks.positive_int("n", np.int64(8), 8) == 8
    for v in (7, 8.0, True, "8", None):
        with pytest.raises(ValueError, match=r"^n=.* is not allowed: an integer >= 8$"):
            checks.positive_int("n", v, 8)
    assert checks.integer("n", 4, "even", lambda v: v % 2 == 0) == 4
    with pytest.raises(ValueError, match=r"^n=3 is not allowed: even$"):
        checks.integer("n", 3, "even", lambda v: v % 2 == 0)


def test_series_and_arrays():
    assert checks.series("J", 0.5, "y") == (0.5,)
    assert checks.series("J", (), "y") == ()
    assert checks.series("J", np.array([1, 2]), "y") == (1.0, 2.0)
    assert checks.series("J", [np.float32(0.5), 1], "y", lambda v: v > 0.0) == (0.5, 1.0)
    for v in (["0.5"], [True, 1.0], [None], [[1.0], [2.0]], [1.0, math.nan], "0.5", {1.0},
              np.array([True, False])):
        with pytest.raises(ValueError, match=r"^J=.* is not allowed: .*y$"):
            checks.series("J", v, "y")
    with pytest.raises(ValueError, match=r"^J=\[-1\.0\] is not allowed: y$"):
        checks.series("J", [-1.0], "y", lambda v: v >= 0.0)
    a = np.arange(4.0)
    out = checks.reals("h", a, "y")
    assert out is not a and np.array_equal(out, a)
    assert checks.reals("h", [[1, 2], [3, 4]], "y").shape == (2, 2)


# ------------------------------------------------------------------ the fronts, one policy
@pytest.mark.parametrize("value", BAD, ids=repr)
@pytest.mark.parametrize("name", ["load", "speed", "tol"])
def test_bem_solve(name, value):
    kw = dict(load=0.3, speed=1.0, nodes=64)
    _refused(lambda v: bem.solve(**{**kw, name: v}), name, value)


@pytest.mark.parametrize("value", BAD_GIVEN, ids=repr)
@pytest.mark.parametrize("name", ["load", "penetration", "speed", "ratio", "hk", "rtol"])
def test_bem_validate(name, value):
    _refused(lambda v: bem.validate(**{name: v}), name, value)


@pytest.mark.parametrize("value", BAD, ids=repr)
@pytest.mark.parametrize("name", ["load", "speed", "ratio", "hk"])
def test_analytic_solve(name, value):
    kw = dict(load=0.3, speed=1.0)
    _refused(lambda v: analytic.solve(**{**kw, name: v}), name, value)


@pytest.mark.parametrize("value", BAD, ids=repr)
@pytest.mark.parametrize("name", ["load", "speed", "hk"])
def test_analytic_fourier_solve(name, value):
    kw = dict(load=0.3, speed=1.0, nodes=64, shifts=1)
    _refused(lambda v: analytic.fourier_solve(**{**kw, name: v}), name, value)


@pytest.mark.parametrize("value", BAD, ids=repr)
@pytest.mark.parametrize("make, name", [
    (lambda v: bem.Prony(v), "J0"),
    (lambda v: bem.Prony(1.0, (v,), (1.0,)), "J"),
    (lambda v: bem.Prony.standard_linear_solid(v), "ratio"),
    (lambda v: bem.Sinusoid(v), "hk"),
    (lambda v: bem.Harmonics((1.0, v), (0.0, 0.0)), "amplitudes"),
    (lambda v: vm.Maxwell(v), "E_r"),
    (lambda v: vm.Maxwell(1.0, (v,), (1.0,)), "E"),
    (lambda v: vm.Maxwell(1.0, (1.0,), (v,)), "theta"),
    (lambda v: vm.Maxwell.from_creep(v, (), ()), "J0"),
    (lambda v: vm.Maxwell(1.0).creep(E_ref=v), "E_ref"),
    (lambda v: vm.WLF(v, 50.0, 20.0), "C1"),
    (lambda v: vm.ShiftTable((0.0, v), (1.0, 0.0)), "T"),
], ids=lambda v: getattr(v, "__name__", repr(v)))
def test_materials_constructors(make, name, value):
    if value is None and name in ("J", "E", "theta", "T", "amplitudes"):
        value = [None]  # an element None (the sequence itself may be empty)
    _refused(make, name, value)


SI = dict(E0=1e6, Einf=3e6, tau_creep=0.01, nu=0.5, wavelength=1e-3, amplitude=1e-4, speed=0.05,
          mean_pressure=1e5)


@pytest.mark.parametrize("value", BAD_GIVEN, ids=repr)
@pytest.mark.parametrize("name", ["E0", "Einf", "tau_creep", "nu", "wavelength", "amplitude",
                                  "speed", "mean_pressure"])
@pytest.mark.parametrize("road", ["bem", "analytic"])
def test_the_si_front(road, name, value):
    solve_si = bem.solve_si if road == "bem" else analytic.solve_si
    extra = dict(nodes=64) if road == "bem" else {}
    msg = _refused(lambda v: solve_si(**{**SI, name: v}, **extra), name, value)
    assert msg.endswith("]")  # the unit of the SI input


def test_files_and_text_are_converted_before_validation(tmp_path):
    """The readers turn text into numbers; the Python API then takes them."""
    path = tmp_path / "p.txt"
    path.write_text("J0 1.0\n0.5 1.0\n")
    assert bem.read_prony(path) == bem.Prony(1.0, (0.5,), (1.0,))
    path = tmp_path / "r.txt"
    path.write_text("E_r 1.0\n2.0 0.5\n")
    assert vm.read_relaxation(path) == vm.Maxwell(1.0, (2.0,), (0.5,))
