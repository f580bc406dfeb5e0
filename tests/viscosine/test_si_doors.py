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
    assert rc == 2 and "--tau-creep is missing: --units SI needs" in err and "--tau-relax" in err


# ------------------------------------------------------------------------ unit slips
RUBBER = dict(E0=5e6, Einf=15e6, tau_creep=0.01, nu=0.5, wavelength=1e-3, amplitude=1e-4,
              speed=0.01)


@pytest.mark.parametrize("door", [analytic.solve_si, lambda **kw: bem.solve_si(**kw)])
def test_mpa_typed_as_pa_is_named_at_the_si_doors(door):
    from viscosine import ViscosineWarning
    with pytest.warns(ViscosineWarning, match="MPa given as Pa"):
        r = door(**RUBBER, mean_pressure=0.1)  # 0.1 MPa meant
    assert r.success and r.contact_fraction < 1e-3
    note, = r.warnings
    assert note.startswith("a mean pressure of 0.1 Pa with E0 = 5e+06 Pa leaves a vanishing "
                           "sliver of contact")
    assert r.as_dict()["warnings"] == [note]
    with pytest.warns(ViscosineWarning, match="far outside linear theory"):
        r = door(**dict(RUBBER, E0=5.0, Einf=15.0), mean_pressure=1e5)  # the moduli in MPa
    assert "× the instantaneous plane-strain modulus" in r.warnings[-1]


def test_a_sensible_load_has_no_slip_warning():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = analytic.solve_si(**RUBBER, mean_pressure=1e5)
    assert r.warnings == () and r.as_dict()["warnings"] == []


def test_the_surface_si_door_names_a_slip():
    import numpy as np

    from viscosine import ViscosineWarning
    z = 1e-4 * np.cos(2 * np.pi * (np.arange(16) / 16 - 0.5))[:, None] * np.ones((1, 16))
    kw = dict(E0=5.0, Einf=15.0, tau_creep=0.01, nu=0.5, length=1e-3, speed=0.01, heights=z,
              nodes=16)
    with pytest.warns(ViscosineWarning, match="far outside linear theory"):
        r = bem.solve_surface_si(**kw, mean_pressure=1e5)
    assert any("E0 = 5 Pa" in w for w in r.warnings)
    assert r.as_dict()["warnings"] == list(r.warnings)


@pytest.mark.parametrize("solver", ["analytic", "bem"])
def test_a_pressure_in_pa_without_units_si_is_named_on_the_command_line(capsys, solver):
    rc, out, err = _cli(capsys, "point", "--solver", solver, "--load", "1e5", "--speed", "0.01")
    import json
    rec = json.loads(out)
    assert rc == 0 and rec["success"]
    note, = [w for w in rec["warnings"] if "outside linear theory" in w]
    assert note.startswith("p̃∞ = 1e+05 is 3.3e+04 × the instantaneous plane-strain modulus")
    assert "a mean pressure in Pa given without --units SI?" in note and note in err


def test_mpa_as_pa_on_the_command_line_si_is_named(capsys):
    import json
    rc, out, err = _cli(capsys, "point", "--solver", "analytic", "--units", "SI", "--load",
                        "0.1", "--speed", "0.01", "--E0", "5e6", "--Einf", "15e6",
                        "--tau-creep", "0.01", "--nu", "0.5", "--wavelength", "1e-3",
                        "--amplitude", "1e-4")
    rec = json.loads(out)
    note, = rec["warnings"]
    assert "vanishing sliver of contact" in note and "MPa given as Pa?" in note and note in err


# ------------------------------------------------------------------------ one protocol
def test_si_results_speak_the_result_protocol():
    import numpy as np
    a = analytic.solve_si(**RUBBER, mean_pressure=1e5)
    b = bem.solve_si(**RUBBER, mean_pressure=1e5, nodes=1024)
    for r in (a, b):
        assert r.mu == r.friction_coefficient == r.solution.mu
        assert r.contact_fraction == r.solution.contact_fraction
        assert r.n_patches == 1 and r.tau_f == r.friction_stress and r.status == 0
    assert a.nodes is None and b.nodes == 1024
    z = 1e-4 * np.cos(2 * np.pi * (np.arange(16) / 16 - 0.5))[:, None] * np.ones((1, 16))
    s = bem.solve_surface_si(**{k: v for k, v in RUBBER.items()
                                if k not in ("wavelength", "amplitude")},
                             length=1e-3, heights=z, mean_pressure=1e5, nodes=16)
    for name in ("mu", "contact_fraction", "full_contact", "n_patches", "status", "nodes",
                 "error_estimate", "warnings", "success", "message"):
        assert hasattr(s, name) and hasattr(a, name), name
    assert s.tau_f == s.friction_stress and s.nodes == 16


def test_si_records_explain_their_units_and_times():
    rec = analytic.solve_si(**dict(RUBBER, tau_creep=None, tau_relax=0.003),
                            mean_pressure=1e5).as_dict()
    si_ = rec["si"]
    assert si_["units"]["mean_pressure"] == "Pa" and si_["units"]["contact_halfwidth"] == "m"
    assert si_["units"]["friction_coefficient"] == "-" and set(si_["units"]) < set(si_)
    sc = rec["si_scales"]
    assert sc["time_given"] == "tau_relax" and sc["tau_relax"] == pytest.approx(0.003, rel=1e-15)
    assert sc["tau_creep"] == pytest.approx(0.009, rel=1e-15) and sc["tau_ref"] == sc["tau_creep"]
    assert sc["E_ref"] == pytest.approx(5e6, rel=1e-15) and sc["units"]["E_ref"] == "Pa"
    assert sc["units"]["tau_relax"] == "s" and sc["units"]["k"] == "1/m"
