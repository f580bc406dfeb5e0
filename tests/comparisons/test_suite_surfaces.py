"""The suite's surface cases (three-dimensional contact): what they cover, their certification
rule judged from the stored evidence, the exact roads recomputed here, a coarse variant of the
certification recomputed whole, the shipped values against a fast recomputation, --check,
--export and --list, and the references refused where they cannot apply.

Certifying the eight cases takes about four minutes on two cores (`suite --certify`), and the
whole --check is test_suite.py's slow test: here the certification runs on a coarse variant
(grids 16 … 256, about three seconds) and the shipped values are judged against the surface BEM
at N = 256 within the sum of its own estimate and their certified error.
"""
import copy
import csv
import json
import math

import numpy as np
import pytest

import analytic
from comparisons import cli, roads, suite
from conftest import ROUNDOFF

NAMES = [c["name"] for c in suite.load_suite()["surfaces"]]


@pytest.fixture(scope="module")
def data():
    return suite.load_suite()


def _case(data, name):
    return next(c for c in data["surfaces"] if c["name"] == name)


def _jstar(n, w, ratio):
    """J*(n) of the standard linear solid, written here again from the conventions."""
    return 1.0 / ratio + (1.0 - 1.0 / ratio) / (1.0 - 1j * n * w)


# ---------------------------------------------------------------------------- what is shipped
def test_surface_cases_load_and_cover_what_the_suite_claims(data):
    cases = data["surfaces"]
    assert len(cases) >= 6 and data["surface_rule"] == suite.SURFACE_RULE
    assert set(NAMES) <= set(suite.case_names()) and not set(NAMES) & {
        c["name"] for c in data["cases"]}
    for c in cases:
        p, cert = c["point"], c["certified"]
        assert suite.is_surface(c) and not suite.two_roads(p)
        n = c["nodes"]
        assert all(b == 2 * a for a, b in zip(n[:-1], n[1:])) and len(n) >= suite.LAST + 1
        assert cert["status"] == "complete", (c["name"], cert["notes"])
        refs = suite.surface_references(c)
        assert ("surface_reference" in refs) == ("reference" in cert)
        for k, r in cert["scalars"].items():
            assert k in suite.SURFACE_KEYS and r["digits"] >= 2, (c["name"], k)
            assert r["error"] < suite.half_unit(r["value"], r["digits"])
        assert set(suite.SURFACE_KEYS) <= set(cert["scalars"]) | set(cert["exact"])
        f = suite.case_fields(c)
        m = c["field_points"]
        np.testing.assert_array_equal(f["x"], np.arange(m) / m - 0.5)
        for col in suite.FIELD_COLUMNS:
            assert f[col].shape == (m, m) and np.all(np.isfinite(f[col]))
            assert np.all(f[col + "_err"] >= 0)
    bis = [c for c in cases if c["point"]["surface"] == {"kind": "bisinusoid", "hk": 1.0}
           and c["point"]["direction"] == 0.0 and c["point"]["load"] == 0.3
           and not c["point"].get("layer")]
    speeds = sorted(c["point"]["speed"] for c in bis)
    assert speeds[0] < 1.0 < speeds[-1] and len(speeds) >= 3  # across the friction peak
    mu = [c["certified"]["scalars"]["mu"]["value"] for c in sorted(
        bis, key=lambda c: c["point"]["speed"])]
    assert mu[0] < max(mu) > mu[-1]
    kinds = {tuple(suite.surface_references(c)) for c in cases}
    assert {("surface_reference",), ("line", "surface_reference"),
            ("closed_form", "surface_reference")} <= kinds
    oblique = [c for c in cases if c["point"]["direction"] % 90.0 and "mu_lateral" in
               c["certified"]["scalars"] and not c["certified"]["exact"]["full_contact"]]
    assert oblique and all(abs(c["certified"]["scalars"]["mu_lateral"]["value"]) > 0.01
                           for c in oblique)
    rough = [c for c in cases if c["point"]["surface"]["kind"] == "self_affine"]
    assert rough and all(c["certified"]["exact"].get("n_patches", 0) > 1 for c in rough)
    # a layer is certified by two codes: the surface reference solves the same layer
    layered = [c for c in cases if c["point"].get("layer")]
    assert layered and all(suite.surface_references(c) == ("surface_reference",)
                           and c["certified"]["method"] == "bem convergence + surface reference"
                           and c["certified"]["reference"]["success"]
                           and all(r["agree"] for r in c["certified"]["scalars"].values())
                           for c in layered)


def test_each_digit_is_what_the_rule_gives_from_the_stored_evidence(data):
    """The BEM and the surface reference agree within 10 E + E_F and e = max(10 E, E_F, gap);
    an exact road's value with e = |a − q_R| (at least |a − q_F| too); the BEM alone 10 E."""
    for c in data["surfaces"]:
        refs = suite.surface_references(c)
        for k, r in c["certified"]["scalars"].items():
            ev = r["bem"]
            best = ev["richardson"] if ev["regime"] == "asymptotic" else ev["values"][-1]
            if "exact_road" in r:
                assert r["value"] == r["exact_road"]
                err = abs(r["value"] - best)
                if "reference" in r:
                    err = max(err, abs(r["value"] - r["reference"]["value"]))
            elif "reference" in r:
                gap = abs(ev["richardson"] - r["reference"]["value"])
                assert r["agree"] and gap <= suite.SAFETY * ev["estimate"] + \
                    r["reference"]["estimate"], (c["name"], k)
                err = max(suite.SAFETY * ev["estimate"], r["reference"]["estimate"], gap)
            else:
                assert not refs
                err = suite.SAFETY * ev["estimate"]
            assert r["error"] == pytest.approx(err, rel=1e-12), (c["name"], k)
            assert r["digits"] == suite.digits(r["value"], r["error"])


def test_the_full_contact_case_is_its_closed_form(data):
    """σ̂_q = ẑ_q/Ĉ(q) on the bi-sinusoid's four modes, summed here from J* of the
    conventions (docs/surfaces.md §2.2); the case is also above its full-contact load."""
    c = next(c for c in data["surfaces"] if "closed_form" in c.get("references", []))
    p = c["point"]
    th, w, load = math.radians(p["direction"]), p["speed"], p["load"]
    jc, js = _jstar(math.cos(th), w, p["ratio"]), _jstar(math.sin(th), w, p["ratio"])
    tau = 0.25 * (math.cos(th) * jc.imag / abs(jc) ** 2 + math.sin(th) * js.imag / abs(js) ** 2)
    lat = 0.25 * (math.sin(th) * jc.imag / abs(jc) ** 2 - math.cos(th) * js.imag / abs(js) ** 2)
    assert load > 0.5 * (1 / abs(jc) + 1 / abs(js))
    sc, ex = c["certified"]["scalars"], c["certified"]["exact"]
    assert sc["mu"]["value"] == pytest.approx(tau / load, rel=ROUNDOFF)
    assert sc["mu_lateral"]["value"] == pytest.approx(lat / load, rel=ROUNDOFF)
    assert ex["full_contact"] and ex["penetration"] == 1.0 and ex["contact_fraction"] == 1.0
    f = suite.case_fields(c)
    xx, yy = np.meshgrid(f["x"], f["y"], indexing="ij")
    # k z = cos kx + cos ky: each mode ±q carries z_q = 1/2, |q| = 1
    sigma = load + (0.5 / jc * np.exp(2j * np.pi * xx)).real + \
        (0.5 / js * np.exp(2j * np.pi * yy)).real
    assert np.max(np.abs(f["pressure"] - sigma)) <= ROUNDOFF * np.max(sigma)


def test_the_extruded_case_is_the_line_contact(data):
    c = next(c for c in data["surfaces"] if "line" in c.get("references", []))
    p = c["point"]
    a = analytic.solve(load=p["load"], speed=p["speed"], ratio=p["ratio"],
                       hk=p["surface"]["hk"])
    sc = c["certified"]["scalars"]
    for k in ("mu", "penetration", "contact_fraction"):
        assert sc[k]["value"] == pytest.approx(getattr(a, k), rel=ROUNDOFF)
    line = suite.get_case("sls-partial-v1")["certified"]["scalars"]
    assert sc["mu"]["rounded"] == suite.rounded(line["mu"]["value"], sc["mu"]["digits"])
    f = suite.case_fields(c)
    np.testing.assert_array_equal(f["pressure"][:, 0], f["pressure"][:, -1])  # uniform in y
    np.testing.assert_allclose(f["pressure"][:, 0], a.fields(f["x"]).pressure, rtol=0,
                               atol=ROUNDOFF * np.max(f["pressure"]))


# ---------------------------------------------------------------------------- recomputation
def _coarse(data, name, nodes=(16, 32, 64, 128, 256), reference_nodes=(32, 64, 128)):
    case = copy.deepcopy(_case(data, name))
    case["nodes"] = list(nodes)
    if "reference_nodes" in case:
        case["reference_nodes"] = list(reference_nodes)
    return case


@pytest.mark.parametrize("name", ["surface-anisotropic-30deg", "surface-layer-bonded-d0.5"])
def test_a_coarse_certification_agrees_with_what_is_shipped(data, name):
    """The whole rule on grids 16 … 256 (about three seconds): fewer digits, each consistent
    with the shipped ones (the two values within the sum of their errors)."""
    case = _coarse(data, name)
    cert, fields = suite.compute(case)
    shipped = _case(data, name)["certified"]
    assert cert["status"] == "complete" and cert["exact"] == shipped["exact"]
    for k, r in cert["scalars"].items():
        s = shipped["scalars"][k]
        assert r["digits"] <= s["digits"] and r["method"] == s["method"]
        assert abs(r["value"] - s["value"]) <= r["error"] + s["error"], k
    assert set(fields) == {"x", "y"} | {c + e for c in suite.FIELD_COLUMNS for e in ("", "_err")}


@pytest.mark.parametrize("name", NAMES)
def test_the_shipped_values_hold_against_the_bem_on_256_panels(data, name):
    """Each certified scalar is within the surface BEM's own estimate at N = 256 of its value
    there, plus the certified error (and the round-off of a closed form)."""
    c = _case(data, name)
    r = roads.surface_solution(c["point"], 256)
    assert r.success
    for k, rec in c["certified"]["scalars"].items():
        v = getattr(r, k)
        scale = abs(r.mu) if k == "mu_lateral" else abs(v)  # the others' are relative
        est = r.error_estimate[k] * scale
        assert abs(v - rec["value"]) <= est + rec["error"] + ROUNDOFF * abs(v), k
    for k, v in c["certified"]["exact"].items():
        if k in ("mu_lateral", "n_patches", "full_contact"):
            assert getattr(r, k) == pytest.approx(v, abs=1e-12), k


def test_check_of_the_full_contact_case_and_an_altered_value(tmp_path, data):
    name = "surface-bisinusoid-full-30deg"
    res = suite.check([name], out=tmp_path, log=lambda s: None)
    assert res["ok"] and res["cases"][0]["status"] == "complete"
    bad = copy.deepcopy(data)
    mu = _case(bad, name)["certified"]["scalars"]["mu"]
    mu["value"] += 3 * suite.half_unit(mu["value"], mu["digits"])
    res = suite.check([name], out=tmp_path, resume=True, suite=bad, log=lambda s: None)
    assert not res["ok"] and res["cases"][0]["changed"][0].startswith("mu: certified")
    moved = copy.deepcopy(data)
    f = suite.case_fields(_case(data, name))
    f["pressure"][3, 5] += 1e-6
    path = tmp_path / "moved.npz"
    np.savez(path, **f)
    _case(moved, name)["certified"]["fields"]["file"] = str(path)
    res = suite.check([name], out=tmp_path, resume=True, suite=moved, log=lambda s: None)
    (line,) = res["cases"][0]["changed"]
    assert line.startswith("field pressure: 1 values moved") and "x = -0.453125" in line


def test_a_disagreement_with_the_reference_certifies_nothing(data, monkeypatch):
    real = roads.surface_reference_solution

    class Off:
        def __init__(self, sol):
            self.__dict__.update({k: getattr(sol, k) for k in dir(sol) if not k.startswith("_")})
            self.mu = sol.mu * 1.01

    monkeypatch.setattr(roads, "surface_reference_solution", lambda p, n: Off(real(p, n)))
    cert, _ = suite.compute(_coarse(data, "surface-bisinusoid-v1"))
    assert cert["scalars"]["mu"]["digits"] == 0 and cert["scalars"]["mu"]["agree"] is False
    assert cert["status"] == "incomplete" and any("mu: the BEM and the surface reference "
                                                  "disagree" in n for n in cert["notes"])
    assert cert["scalars"]["penetration"]["digits"] > 0


@pytest.mark.parametrize("change, reference, why", [
    ({"layer": {"thickness_over_wavelength": 0.5, "foundation": "bonded", "nu": 0.5}},
     "closed_form", "over the half-space"),
    ({"surface": {"kind": "bisinusoid", "hk": 1.0, "hk_y": 0.5}}, "line", "uniform in y"),
    ({"surface": {"kind": "self_affine", "hurst": 0.8, "rolloff": 2.0, "short_cutoff": 8.0,
                  "rms_slope": 0.2, "seed": 0}}, "closed_form", "a bi-sinusoid"),
    ({}, "fourier", "one of surface_reference, line, closed_form"),
])
def test_a_reference_where_it_cannot_apply_is_refused(data, change, reference, why):
    case = copy.deepcopy(_case(data, "surface-bisinusoid-v1"))
    case["point"].update(change)
    case["references"] = [reference]
    with pytest.raises(suite.SuiteError) as exc:
        suite.compute(case)
    text = str(exc.value)
    assert len(text.splitlines()) == 1 and f"reference {reference!r} is not allowed" in text
    assert why in text


def test_the_case_key_follows_the_references_and_their_grids(data):
    case = _case(data, "surface-bisinusoid-v1")
    keys = {suite._case_key(case)}
    for change in ({"references": []}, {"reference_nodes": [64, 128, 256]},
                   {"nodes": case["nodes"][1:]}):
        keys.add(suite._case_key({**case, **change}))
    assert len(keys) == 4


# ---------------------------------------------------------------------------- export and list
def test_export_writes_a_surface_case_a_third_code_can_run(tmp_path, data):
    names = ["surface-anisotropic-30deg", "surface-layer-bonded-d0.5"]
    assert cli.main(["suite", "--export", str(tmp_path), "--cases", *names]) == 0
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "## Surfaces" in readme and suite.SURFACE_RULE in readme
    for name in names:
        c, d = _case(data, name), tmp_path / name
        inputs = json.loads((d / "inputs.json").read_text(encoding="utf-8"))
        assert inputs["geometry"] == "surface" and inputs["direction"] == c["point"]["direction"]
        assert inputs["surface"]["kind"] == "bisinusoid" and inputs["load"] == 0.3
        assert ("layer" in inputs) == bool(c["point"].get("layer"))
        # the harmonics of surface.csv are the surface's heights, exactly
        with open(d / "surface.csv", encoding="utf-8") as fh:
            rows = list(csv.DictReader(ln for ln in fh if not ln.startswith("#")))
        g = roads.surface_on_grid(c["point"]["surface"], 32, 32)
        x = np.arange(32) / 32 - 0.5
        xx, yy = np.meshgrid(x, x, indexing="ij")
        z = sum((complex(float(r["re"]), float(r["im"])) * np.exp(
            2j * np.pi * (int(r["m"]) * xx + int(r["n"]) * yy))).real for r in rows)
        np.testing.assert_allclose(z, g["heights"], atol=ROUNDOFF)
        sc = json.loads((d / "scalars.json").read_text(encoding="utf-8"))
        for k, r in c["certified"]["scalars"].items():
            assert sc["scalars"][k]["value"] == r["value"]
            assert sc["scalars"][k]["digits"] == r["digits"]
        with np.load(d / "fields.npz") as z:
            assert {"x", "y", "pressure", "displacement", "gap", "load", "speed",
                    "direction"} <= set(z.files)
            np.testing.assert_array_equal(z["pressure"], suite.case_fields(c)["pressure"])
            assert float(z["direction"]) == c["point"]["direction"]
    lay = json.loads((tmp_path / names[1] / "inputs.json").read_text(encoding="utf-8"))
    assert "surface reference" in lay["reference_road"]
    assert lay["layer"]["thickness_over_Lx"] == 0.5 and lay["layer"]["foundation"] == "bonded"


def test_list_names_the_surface_cases_and_their_body(capsys):
    assert cli.main(["suite", "--list", "--cases", "surface-layer-bonded-d0.5",
                     "surface-bisinusoid-v1"]) == 0
    out = capsys.readouterr().out
    assert "| surface-bisinusoid-v1 |" in out and "| half-space | 6 | 7 |" in out
    assert ("layer d/Lx = 0.5 (kd = 3.142), bonded, ν = 0.5 | 4 | 5 | bem convergence + "
            "surface reference |") in out


def test_both_solvers_estimates_are_made_absolute_in_one_convention():
    """The surface BEM and the surface reference give their estimates as the output contract
    says (relative for mu, penetration, contact_fraction); the suite makes them absolute the
    same way, mu_lateral's apart (the BEM's is over |mu|, the reference's absolute)."""
    from comparisons import suite_surfaces

    class Solution:
        mu, mu_lateral, penetration, contact_fraction = -0.25, 0.05, 0.8, 0.4
        error_estimate = {"mu": 1e-3, "mu_lateral": 2e-3, "penetration": 1e-4,
                          "contact_fraction": 1e-2}

    made = {k: suite_surfaces._absolute(Solution, k, 0.25) for k in suite.SURFACE_KEYS}
    assert made == pytest.approx({"mu": 2.5e-4, "mu_lateral": 5e-4, "penetration": 8e-5,
                                  "contact_fraction": 4e-3}, rel=1e-15)
    assert suite_surfaces._absolute(Solution, "mu_lateral", 1.0) == 2e-3
    Solution.error_estimate = {}
    assert suite_surfaces._absolute(Solution, "mu", 1.0) is None
    assert math.isnan(suite_surfaces._absolute(Solution, "mu", 1.0, math.nan))
