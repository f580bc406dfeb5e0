"""verify's diagnoses: each slip built on purpose into a candidate that is otherwise the exact
answer (the semi-analytic road's), and the verdict must name it."""
import json

import numpy as np
import pytest

import analytic
from comparisons import cli
from comparisons.verify import Result, evaluate, reference_for, results_from_fields

POINT = {"load": 0.3, "speed": 1.0, "ratio": 3.0, "hk": 1.0}
KEYS = ("mu", "tau_f", "penetration", "separation", "contact_fraction", "ka", "ke", "ke_hat")


@pytest.fixture(scope="module")
def ref():
    return reference_for(POINT)


def _fields(n, speed=1.0, scale_p=1.0, scale_v=1.0):
    x = np.arange(n) / n - 0.5
    f = analytic.solve(load=0.3, speed=speed).fields(x)
    return {"x_over_lambda": x, "pressure": f.pressure * scale_p,
            "displacement": f.displacement * scale_v, "gap": f.gap}


def _scalars(speed=1.0, keys=KEYS):
    s = analytic.solve(load=0.3, speed=speed)
    return {k: float(getattr(s, k)) for k in keys}


def _verdict(ref, fields=None, scalars=None):
    if fields is not None:
        return evaluate(results_from_fields([fields], ref.shape), ref)
    return evaluate([Result(None, None, scalars, [], "solver")], ref)


def test_the_exact_answer_has_no_diagnosis(ref):
    ev = _verdict(ref, fields=_fields(1024))
    assert ev["verdict"] == "PASS" and ev["diagnosis"] == []


def test_a_pressure_scaled_by_two_per_cent_is_named(ref):
    ev = _verdict(ref, fields=_fields(1024, scale_p=1.02))
    assert ev["verdict"] == "FAIL"
    assert any(d.startswith("σ is the reference × 1.020 everywhere: modulus or (1 − ν²) "
                            "scaling?") for d in ev["diagnosis"]), ev["diagnosis"]


def test_a_plane_stress_modulus_is_named_from_scalars(ref):
    sc = _scalars()
    sc["tau_f"] /= 0.75  # σ over E0 instead of E0/(1 − ν²), ν = 0.5
    ev = _verdict(ref, scalars=sc)
    assert ev["failed"] == ["τ̃f"]
    assert ev["diagnosis"] == ["τ̃f is the reference × 1.333 while μ agrees: modulus or "
                               "(1 − ν²) scaling? (the conventions' stresses are over "
                               "E0/(1 − ν²), E0 the relaxed modulus)"]
    sc = dict(_scalars(), load=0.3 * 1.05)
    sc["tau_f"] *= 1.05
    ev = _verdict(ref, scalars=sc)
    assert ev["diagnosis"][0].startswith("p̃∞ and τ̃f are the reference × 1.050")


def test_a_displacement_scaled_is_named(ref):
    ev = _verdict(ref, fields=_fields(1024, scale_v=2.0))
    assert any(d.startswith("v is the reference × 2.000 everywhere: a length scale off?")
               for d in ev["diagnosis"]), ev["diagnosis"]


@pytest.mark.parametrize("speed,text", [
    (3.0, "matches at E∞/E0 times the speed: relaxation time given as a creep time?"),
    (1.0 / 3.0, "matches at the speed divided by E∞/E0: creep time given as a relaxation "
                "time?"),
])
def test_a_swapped_time_is_named(ref, speed, text):
    for ev in (_verdict(ref, scalars=_scalars(speed)), _verdict(ref, fields=_fields(2048, speed))):
        assert ev["verdict"] == "FAIL"
        assert [d for d in ev["diagnosis"] if d.startswith(text)], ev["diagnosis"]


def test_another_speed_is_not_called_a_swap(ref):
    ev = _verdict(ref, scalars=_scalars(2.0))
    assert ev["verdict"] == "FAIL" and not [d for d in ev["diagnosis"] if "speed" in d]


def test_verify_in_si_names_a_relaxation_time_given_as_the_creep_time(tmp_path, capsys):
    """The candidate solved with the creep time τ; verify told the relaxation time τ E0/E∞ as
    --tau-creep: 14 of 15 quantities fail, and the diagnosis says why."""
    E0, nu, h, tau = 2.0e6, 0.5, 1e-4, 0.01
    lam = 2 * np.pi * h
    speed = 1.0 / (tau * 2 * np.pi / lam)  # V/V0 = 1
    f = _fields(1024)
    path = tmp_path / "si.csv"
    with open(path, "w", encoding="utf-8") as fh:
        fh.write("x_over_lambda,pressure,displacement,gap\n")
        for row in zip(f["x_over_lambda"], f["pressure"] * E0 / (1 - nu ** 2),
                       f["displacement"] * h, f["gap"] * h):
            fh.write(",".join(repr(float(v)) for v in row) + "\n")
    si = ["--load", repr(0.3 * E0 / (1 - nu ** 2)), "--speed", repr(speed), "--units", "SI",
          "--E0", str(E0), "--Einf", str(3 * E0), "--nu", str(nu), "--wavelength", repr(lam),
          "--amplitude", str(h), "--fields", str(path), "--no-figures"]
    rc = cli.main(["verify", *si, "--tau-creep", repr(tau / 3), "--out", str(tmp_path / "a")])
    out = capsys.readouterr().out
    assert rc == 1
    assert "diagnosis: matches at E∞/E0 times the speed: relaxation time given as a creep time?" \
        in out
    rc = cli.main(["verify", *si, "--tau-relax", repr(tau / 3), "--out", str(tmp_path / "b")])
    assert rc == 0, capsys.readouterr().out


def test_negative_orders_are_called_pre_asymptotic(ref, tmp_path, capsys):
    """Differences that grow with N (a bias growing with the grid) give negative orders: the
    study says they are no rate."""
    res = []
    for n in (1024, 2048, 4096):
        r, = results_from_fields([_fields(n, scale_p=1.0 + 1e-3 * n / 1024)], ref.shape)
        r.nodes = n
        res.append(r)
    ev = evaluate(res, ref)
    orders = {k: q["order_vs_reference"] for k, q in ev["convergence"]["quantities"].items()}
    assert orders["tau_f"] < 0 and orders["pressure_L2"] < 0
    note, = [n for n in ev["convergence"]["notes"] if "pre-asymptotic" in n]
    assert note.startswith("τ̃f") and "negative orders over N = 1024 … 4096 are " \
        "pre-asymptotic, not rates" in note
    assert json.dumps(ev["convergence"]["notes"])  # it goes into verdict.json
