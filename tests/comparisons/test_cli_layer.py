"""A layer through the front doors: `point` and `sweep` with --thickness, --foundation and --nu
answer what `bem.solve(layer=bem.Layer(...))` answers, in the conventions' units and in SI (and
`bem.solve_si(thickness=, foundation=)` answers what `--units SI` does); every odd layer input is
one line on standard error, exit status 2, nothing on standard output; an answer whose crest
goes through the layer is exit status 1, never printed.  Run in process (`cli.main`)."""
import json
import math

import pytest

import bem
from comparisons import cli

LAYER = ["--thickness", "0.1", "--foundation", "bonded", "--nu", "0.5"]
POINT = ["point", "--solver", "bem", "--load", "0.2", "--speed", "1", "--nodes", "2048"]
SCALARS = ("load", "contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu")


def _run(capsys, argv):
    rc = cli.main(list(argv))
    out = capsys.readouterr()
    assert "Traceback" not in out.err
    return rc, out.out, out.err


@pytest.mark.parametrize("foundation, nu", [("bonded", 0.5), ("frictionless", 0.3)])
def test_point_answers_what_python_answers(foundation, nu, capsys):
    """The record of `point` is `bem.solve(layer=...).as_dict()`: every scalar to the bit, and
    the layer block (k d, d/λ, foundation, ν, mean compression, approach) with it."""
    argv = POINT + ["--thickness", "0.1", "--foundation", foundation, "--nu", str(nu)]
    rc, out, err = _run(capsys, argv)
    assert rc == 0, err
    rec = json.loads(out)
    ref = bem.solve(load=0.2, speed=1.0, nodes=2048,
                    layer=bem.Layer(thickness_over_wavelength=0.1, foundation=foundation, nu=nu))
    want = json.loads(json.dumps(ref.as_dict()))
    for key in SCALARS:
        assert rec[key] == want[key], key
    assert rec["layer"] == want["layer"]
    assert rec["layer"]["thickness"] == pytest.approx(2 * math.pi * 0.1, rel=1e-15)
    assert rec["layer"]["foundation"] == foundation and rec["layer"]["nu"] == nu
    assert rec["layer"]["approach"] == pytest.approx(
        rec["penetration"] + rec["layer"]["mean_displacement"], rel=1e-15)
    # and the layer mattered: the half-space answers otherwise
    rc, out, _ = _run(capsys, POINT)
    half = json.loads(out)
    assert "layer" not in half and abs(half["mu"] - rec["mu"]) > 1e-3 * half["mu"]


def test_sweep_carries_the_layer_on_every_line(capsys):
    """Each line of a sweep is the point's record with its layer, in order."""
    rc, out, err = _run(capsys, ["sweep", "--solver", "bem", "--load", "0.1", "0.2",
                                 "--speed", "1", "--nodes", "1024"] + LAYER)
    assert rc == 0, err
    recs = [json.loads(line) for line in out.splitlines()]
    assert [r["load_asked"] for r in recs] == [0.1, 0.2]
    rc, out, _ = _run(capsys, ["point", "--solver", "bem", "--load", "0.2", "--speed", "1",
                               "--nodes", "1024"] + LAYER)
    assert json.loads(out)["mu"] == recs[1]["mu"]
    assert all(r["layer"]["thickness_over_wavelength"] == 0.1 for r in recs)


def test_si_front_door_is_the_si_python_front(capsys):
    """--units SI --thickness d [m] answers what bem.solve_si(thickness=d) answers, and its si
    block gives the thickness and the approach in metres."""
    si = dict(nu=0.5, wavelength=0.01, speed=1e-3, amplitude=1e-4, E0=1e6, Einf=3e6,
              tau_creep=0.1, mean_pressure=1e4)
    argv = ["point", "--solver", "bem", "--units", "SI", "--load", "1e4", "--speed", "1e-3",
            "--nu", "0.5", "--wavelength", "0.01", "--amplitude", "1e-4", "--E0", "1e6",
            "--Einf", "3e6", "--tau-creep", "0.1", "--nodes", "2048", "--thickness", "1e-3",
            "--foundation", "bonded"]
    rc, out, err = _run(capsys, argv)
    assert rc == 0, err
    rec = json.loads(out)
    py = bem.solve_si(**si, thickness=1e-3, foundation="bonded", nodes=2048)
    assert rec["mu"] == py.solution.mu
    assert rec["layer"]["thickness_over_wavelength"] == pytest.approx(0.1, rel=1e-15)
    assert rec["si"]["thickness"] == pytest.approx(1e-3, rel=1e-15)
    assert rec["si"]["approach"] == pytest.approx(
        py.solution.diagnostics["layer"]["approach"] * 1e-4, rel=1e-15)
    # the full-contact pressure of the SI front divides the half-space's by S(kd)
    half = bem.solve_si(**si, nodes=2048)
    s1 = float(bem.Layer(thickness_over_wavelength=0.1, foundation="bonded",
                         nu=0.5).factor([1.0])[0])
    assert py.full_contact_pressure == pytest.approx(half.full_contact_pressure / s1,
                                                     rel=1e-14)


def test_fields_header_names_the_layer(tmp_path, capsys):
    path = tmp_path / "f.csv"
    rc, _, err = _run(capsys, POINT + LAYER + ["--fields", str(path)])
    assert rc == 0, err
    head = [line for line in path.read_text().splitlines() if line.startswith("#")]
    assert any(line.startswith("# layer: d/lambda=0.1 ") and "foundation=bonded" in line
               for line in head), head


ODD = [
    (LAYER[:4], "--nu is missing"),
    (["--thickness", "0.1", "--nu", "0.5"], "--foundation is missing"),
    (["--foundation", "bonded"], "--foundation bonded is not allowed without --thickness"),
    (["--thickness", "0", "--foundation", "bonded", "--nu", "0.5"], "--thickness (d/λ) 0.0"),
    (["--thickness", "-0.1", "--foundation", "bonded", "--nu", "0.5"], "--thickness (d/λ) -0.1"),
    (["--thickness", "nan", "--foundation", "bonded", "--nu", "0.5"], "--thickness (d/λ) nan"),
    (["--thickness", "inf", "--foundation", "bonded", "--nu", "0.5"], "--thickness (d/λ) inf"),
    (["--thickness", "abc", "--foundation", "bonded", "--nu", "0.5"], "not a number"),
    (["--thickness", "0.1", "--foundation", "glued", "--nu", "0.5"], "invalid choice: 'glued'"),
    (["--thickness", "0.1", "--foundation", "bonded", "--nu", "0.6"], "--nu 0.6"),
    (["--thickness", "0.1", "--foundation", "bonded", "--nu", "-1"], "--nu -1.0"),
    (["--thickness", "0.1", "--foundation", "bonded", "--nu", "nan"], "--nu nan"),
    (["--thickness", "0.1", "--thickness", "0.2", "--foundation", "bonded", "--nu", "0.5"],
     "--thickness given twice"),
    # too thin for any grid, and too thin for the fixed mesh asked
    (["--thickness", "0.001", "--foundation", "bonded", "--nu", "0.5"],
     "--thickness (d/λ) 0.001: must be at most"),
    (["--thickness", "0.01", "--foundation", "bonded", "--nu", "0.5", "--nodes", "1048576"],
     "--nodes 1048576: must be at most"),
]


@pytest.mark.parametrize("extra, fragment", ODD, ids=[" ".join(e) for e, _ in ODD])
def test_odd_layer_input_is_refused_up_front(extra, fragment, capsys):
    base = ["point", "--solver", "bem", "--load", "0.2", "--speed", "1"]
    rc, out, err = _run(capsys, base + extra)
    assert rc == 2, err
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("python -m comparisons point: "), err
    assert fragment in lines[0], lines[0]


@pytest.mark.parametrize("argv, fragment", [
    (["point", "--solver", "analytic", "--load", "0.2", "--speed", "1"] + LAYER,
     "--thickness is not allowed here: a BEM option"),
    (["point", "--solver", "analytic", "--load", "0.2", "--speed", "1"] + LAYER[:4],
     "--thickness is not allowed here: a BEM option"),  # before asking for --nu
    (["point", "--solver", "analytic", "--load", "0.2", "--speed", "1", "--foundation",
      "bonded"], "--foundation is not allowed here: a BEM option"),
    (["point", "--solver", "bem", "--penetration", "9e-5", "--speed", "1e-3", "--units", "SI",
      "--nu", "0.5", "--wavelength", "0.01", "--amplitude", "1e-4", "--E0", "1e6", "--Einf",
      "3e6", "--tau-creep", "0.1", "--thickness", "5e-5", "--foundation", "bonded"],
     "is not allowed: a penetration the layer can take: Δ < d = 5e-05 [m]"),
    (["point", "--solver", "bem", "--penetration", "0.7", "--speed", "1"] + LAYER,
     "--penetration 0.7: must be Δ/h < k d/hk = 0.628319"),
    (["sweep", "--solver", "bem", "--penetration", "0.5", "0.7", "--speed", "1"] + LAYER,
     "--penetration 0.7: must be"),
    (["point", "--solver", "bem", "--load", "0.2", "--speed", "1", "--units", "SI", "--nu",
      "0.5", "--wavelength", "0.01", "--amplitude", "1e-4", "--E0", "1e6", "--Einf", "3e6",
      "--tau-creep", "0.1", "--thickness", "-1e-3", "--foundation", "bonded"],
     "--thickness -0.001 is not allowed: a finite layer thickness d > 0 [m]"),
    (["point", "--solver", "bem", "--load", "0.2", "--speed", "1", "--nu", "0.3"],
     "--nu is not allowed without --units SI"),
])
def test_layer_options_that_do_not_apply(argv, fragment, capsys):
    rc, out, err = _run(capsys, argv)
    assert rc == 2 and out == "", err
    assert len(err.strip().splitlines()) == 1 and fragment in err, err


def test_a_load_through_the_layer_is_not_an_answer(capsys):
    """A load whose crest would go through the layer is solved, found so, and reported on
    standard error with the reason (exit status 1); nothing is printed as a result."""
    rc, out, err = _run(capsys, ["point", "--solver", "bem", "--load", "3", "--speed", "1",
                                 "--nodes", "2048", "--thickness", "0.05", "--foundation",
                                 "frictionless", "--nu", "0.3"])
    assert rc == 1 and out == ""
    assert "reaches the foundation" in err


def test_verify_refuses_a_layer_its_reference_cannot_solve():
    """verify's reference is a convergence study up to 2^18 panels: a layer whose lowest mode
    allows fewer is refused up front, as is a penetration through the layer (one line each,
    naming the layer); a layer it can solve passes."""
    from comparisons._errors import BadInput
    from comparisons.verify._point import check_point
    base = {"load": 0.3, "speed": 1.0, "ratio": 3.0, "hk": 1.0}
    thin = {"thickness_over_wavelength": 0.01, "foundation": "bonded", "nu": 0.5}
    with pytest.raises(BadInput, match="too thin for the reference's convergence study"):
        check_point({**base, "layer": thin})
    ok = {"thickness_over_wavelength": 0.1, "foundation": "bonded", "nu": 0.5}
    assert check_point({**base, "layer": ok})["layer"] == ok
    deep = {"penetration": 0.7, "speed": 1.0, "ratio": 3.0, "hk": 1.0, "layer": ok}
    with pytest.raises(BadInput, match="would reach the foundation"):
        check_point(deep)
