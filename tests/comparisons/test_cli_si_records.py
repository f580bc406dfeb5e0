"""The command line's --units SI records say what the Python SI door says: ``si`` with its
``units`` object (key → unit), ``si_scales`` as `viscosine.si.SIScales.describe` (both times of
the solid and which was given), the material the user gave in Pa and s, and a unit slip said in
the SI inputs."""
import json

import pytest

import analytic
from comparisons import cli
from viscosine import si as si_front

from conftest import ROUNDOFF

SOLID = dict(E0=1e6, Einf=3e6, nu=0.5, wavelength=1e-3, amplitude=1e-4)
SI = ["--units", "SI", "--E0", "1e6", "--Einf", "3e6", "--nu", "0.5", "--wavelength", "1e-3",
      "--amplitude", "1e-4"]


def _record(capsys, *argv):
    rc = cli.main([str(a) for a in argv])
    out = capsys.readouterr()
    assert rc == 0, out.err
    return json.loads(out.out), out.err


@pytest.fixture(autouse=True)
def _in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)


@pytest.mark.parametrize("time", ["tau_relax", "tau_creep"])
def test_an_si_record_is_the_python_doors(time, capsys):
    rec, _ = _record(capsys, "point", "--solver", "analytic", *SI, f"--{time.replace('_', '-')}",
                     "0.01", "--load", "2e4", "--speed", "0.05")
    ref = analytic.solve_si(**SOLID, **{time: 0.01}, mean_pressure=2e4, speed=0.05).as_dict()
    # si: every scalar with its unit, as a key -> unit object
    units = rec["si"].pop("units")
    assert units == {k: si_front.UNITS[k] for k in rec["si"]}
    for k in ("friction_coefficient", "contact_halfwidth", "mean_pressure", "penetration"):
        assert rec["si"][k] == pytest.approx(ref["si"][k], rel=1e-9), k
    # si_scales: the scales of SIScales.describe, both times and which was given
    scales, want = rec["si_scales"], ref["si_scales"]
    for k in set(want) - {"load_is", "speed_is"}:
        assert scales[k] == (pytest.approx(want[k], rel=ROUNDOFF)
                             if isinstance(want[k], float) else want[k]), k
    assert scales["time_given"] == time and scales["units"]["tau_relax"] == "s"
    assert scales["tau_relax"] == pytest.approx(scales["tau_creep"] / 3.0, rel=ROUNDOFF)
    # the material as given, in Pa and s: no E_ref = 1 beside si_scales' E_ref
    m = rec["material"]
    assert (m["E0"], m["Einf"]) == (1e6, 3e6) and m["E_ref"] == scales["E_ref"] == 1e6
    assert m[time] == pytest.approx(0.01, rel=ROUNDOFF) and m["tau_ref"] == scales["tau_ref"]
    assert m["time_given"] == time and m["units"] == "SI"


def test_the_conventions_material_block_keeps_its_reference_units(capsys):
    rec, _ = _record(capsys, "point", "--solver", "analytic", "--load", "0.3", "--speed", "1")
    assert rec["material"]["E_ref"] == 1.0 and "E0" not in rec["material"]
    assert "si" not in rec and "si_scales" not in rec


@pytest.mark.parametrize("solver", ["analytic", "bem"])
def test_a_unit_slip_is_said_in_the_si_inputs(solver, capsys):
    # 3 Pa on a 1 MPa solid: a vanishing sliver of contact (MPa given as Pa?)
    rec, err = _record(capsys, "point", "--solver", solver, *SI, "--tau-creep", "0.01",
                       "--load", "3", "--speed", "0.05")
    slips = [w for w in rec["warnings"] if "sliver" in w]
    assert slips == [w for w in si_front.slip_warnings(
        si_front.scales(**SOLID, tau_creep=0.01, speed=0.05, mean_pressure=3.0),
        rec["load"], rec["contact_fraction"], 1.0 / 3.0, rec["full_contact"])]
    assert len(slips) == 1 and slips[0].startswith("a mean pressure of 3 Pa with E0 = 1e+06 Pa")
    assert not any("p̃∞" in w for w in rec["warnings"])   # not the conventions' wording
    assert f"point: warning: {slips[0]}" in err
    # without --units SI the same point keeps the conventions' wording
    plain, _ = _record(capsys, "point", "--solver", solver, "--load", repr(rec["load"]),
                       "--speed", repr(rec["speed"]))
    assert any(w.startswith("p̃∞ = ") and "sliver" in w for w in plain["warnings"])


def test_a_surface_record_says_its_unit_slip_in_the_units_given(capsys):
    """A surface point 1.7 × above the glassy modulus: its record carries the slip as the
    line's does, in SI under --units SI (as bem.solve_surface_si says it), in the conventions'
    groups otherwise, and the command line prints it."""
    import bem
    load, nu, h = 5.0, 0.5, 1e-4   # p̃∞ J(0+) = 5/3
    pressure = load * 1e6 / (1 - nu ** 2)
    rec, err = _record(capsys, "point", "--solver", "bem", "--surface", "bisinusoid", *SI,
                       "--tau-creep", "0.01", "--load", repr(pressure), "--speed", "0.05",
                       "--nodes", "32")
    lx = 1e-3
    from viscosine import ViscosineWarning
    with pytest.warns(ViscosineWarning, match="plane-strain modulus"):
        want = bem.solve_surface_si(nu=nu, length=lx, speed=0.05, surface=bem.bisinusoid(
            2 * 3.141592653589793 * h / lx), E0=1e6, Einf=3e6, tau_creep=0.01,
            mean_pressure=pressure, nodes=32).warnings
    slips = [w for w in rec["warnings"] if "plane-strain modulus" in w]
    assert slips == [w for w in want if "plane-strain modulus" in w] and len(slips) == 1
    assert slips[0].startswith(f"a mean pressure of {pressure:.3g} Pa with E0 = 1e+06 Pa is 1.7 ×")
    assert not any("p̃∞" in w for w in rec["warnings"]) and f"point: warning: {slips[0]}" in err
    plain, err = _record(capsys, "point", "--solver", "bem", "--surface", "bisinusoid",
                         "--hk", repr(rec["surface"]["hk"]), "--load", repr(rec["load"]),
                         "--speed", repr(rec["speed"]), "--nodes", "32")
    slips = [w for w in plain["warnings"] if "plane-strain modulus" in w]
    assert len(slips) == 1 and slips[0].startswith("p̃∞ = 5 is 1.7 ×") and slips[0] in err
    # under the limit: no slip
    calm, _ = _record(capsys, "point", "--solver", "bem", "--surface", "bisinusoid",
                      "--load", "0.3", "--speed", "1", "--nodes", "32")
    assert not any("plane-strain modulus" in w or "sliver" in w for w in calm["warnings"])
