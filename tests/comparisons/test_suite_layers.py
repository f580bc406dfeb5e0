"""The certified suite's layer cases: what they cover, that the layer matters, the full-contact
case against its closed form, a partial case recomputed on coarse meshes, the case key, and the
references that cannot apply.  The whole recomputation is test_suite.py's slow test."""
import copy
import json
import math

import numpy as np
import pytest

from comparisons import cli, suite
from test_suite import compute_with_fourier_spy


@pytest.fixture(scope="module")
def data():
    return suite.load_suite()


def _layer_cases(data):
    return [c for c in data["cases"] if c["point"].get("layer")]


# ---------------------------------------------------------------------------- layers
LAYER_FULL = "sls-layer-bonded-d0.5-full"


def _uniform_compliance(layer):
    """C of docs/layers.md §4 (lateral ends free), written out here."""
    nu = layer["nu"]
    return 1.0 if layer["foundation"] == "frictionless" else (1 - 2 * nu) / (1 - nu) ** 2


def test_layer_cases_load_and_cover_two_thicknesses_both_foundations_and_a_broad_spectrum(
        data):
    """≥ 4 layer cases: two thicknesses or more, both foundations, one on a broad spectrum the
    suite ships; each in partial contact (but one) with the indenter's approach well clear of the
    foundation, certified by the BEM's study checked against the Fourier reference on the same
    layer (the semi-analytic road has no layer), complete, to ≥ 6 digits in μ and Δ/h."""
    cases = _layer_cases(data)
    series = {c["name"]: suite._problem(c["point"])[1] for c in cases
              if c["point"].get("prony") or c["point"].get("material")}
    assert len(cases) >= 4
    layers = [c["point"]["layer"] for c in cases]
    assert len({lay["thickness_over_wavelength"] for lay in layers}) >= 2
    assert {lay["foundation"] for lay in layers} == {"bonded", "frictionless"}
    assert any(c["point"].get("prony") in ("materials/broad24.txt", "materials/lognormal32.txt")
               for c in cases)
    assert sum(not c["certified"]["exact"]["full_contact"] for c in cases) >= 4
    assert any(c["certified"]["exact"]["full_contact"] for c in cases)
    for c in cases:
        p, cert, lay = c["point"], c["certified"], c["point"]["layer"]
        assert set(lay) == {"thickness_over_wavelength", "foundation", "nu"}, c["name"]
        assert not suite.two_roads(p) and suite.reference_of(c) == "fourier"
        assert cert["method"] == suite.FOURIER_METHOD and cert["status"] == "complete"
        assert cert["reference"]["success"] and cert["reference"]["layer"]["foundation"] == \
            lay["foundation"]
        kd = 2 * math.pi * lay["thickness_over_wavelength"]
        assert cert["reference"]["layer"]["thickness"] == pytest.approx(kd, rel=1e-15)
        sc, ex = cert["scalars"], cert["exact"]
        assert sc["mu"]["digits"] >= 6, c["name"]
        # the mean compression is exact under load control: C (k d) J0 p̃/hk
        j0 = series[c["name"]].J0 if c["name"] in series else 1.0
        mean = _uniform_compliance(lay) * kd * j0 * p["load"] / p["hk"]
        assert ex["mean_displacement"] == pytest.approx(mean, rel=1e-15, abs=1e-300)
        approach = ex["approach"] if ex["full_contact"] else sc["approach"]["value"]
        if not ex["full_contact"]:
            assert sc["penetration"]["digits"] >= 6 and sc["approach"]["digits"] >= 6
            assert approach == pytest.approx(sc["penetration"]["value"] + mean, abs=1e-9)
        else:
            assert approach == 1.0 + mean
        assert approach * p["hk"] < 0.6 * kd, c["name"]  # well clear of the foundation


def test_the_layer_matters_in_the_layer_cases(data):
    """μ on each partial-contact layer case differs from the same point on the half-space by
    more than 1 %: the semi-analytic road's for the standard linear solid, the certified
    broad24-partial for the broad spectrum (the same point)."""
    import analytic
    for c in _layer_cases(data):
        p = c["point"]
        if c["certified"]["exact"]["full_contact"]:
            continue
        if p.get("prony"):
            half = next(h for h in data["cases"] if h["point"].get("prony") == p["prony"]
                        and not h["point"].get("layer") and h["point"]["load"] == p["load"]
                        and h["point"]["speed"] == p["speed"])
            mu_half = half["certified"]["scalars"]["mu"]["value"]
        else:
            mu_half = analytic.solve(load=p["load"], speed=p["speed"], ratio=p["ratio"],
                                     hk=p["hk"]).mu
        mu = c["certified"]["scalars"]["mu"]["value"]
        assert abs(mu / mu_half - 1.0) > 0.01, (c["name"], mu, mu_half)


def test_the_full_contact_layer_case_is_its_closed_form(data):
    """Full contact on a layer: mode 1 of the operator carries S(kd), so p̃FC is the
    half-space's over S, τ̃f (and μ at a given p̃) the half-space's over S, and kê the
    half-space's (S is real).  The certified digits hold against the semi-analytic road's
    half-space full contact (Appendix B) divided by S, and the load is above the layer's p̃FC."""
    import analytic
    from comparisons import roads
    case = suite.get_case(LAYER_FULL, data)
    p, lay = case["point"], case["point"]["layer"]
    kd = 2 * math.pi * lay["thickness_over_wavelength"]
    s = analytic.layer_factor(kd, lay["nu"], lay["foundation"])
    half = analytic.solve(load=p["load"], speed=p["speed"], ratio=p["ratio"], hk=p["hk"])
    assert half.full_contact
    pfc = roads.full_contact_load(p["speed"], p["ratio"], p["hk"], lay)
    assert pfc == pytest.approx(analytic.transition_load(p["speed"], p["ratio"], p["hk"]) / s,
                                rel=1e-14)
    assert p["load"] > 1.2 * pfc
    cert = case["certified"]
    assert cert["exact"]["full_contact"] and cert["exact"]["penetration"] == 1.0
    closed = {"mu": half.mu / s, "tau_f": half.tau_f / s, "ke_hat": half.ke_hat}
    assert set(cert["scalars"]) == set(closed)
    for k, v in closed.items():
        rec = cert["scalars"][k]
        assert rec["digits"] >= 9, k
        assert abs(rec["value"] - v) < suite.half_unit(rec["value"], rec["digits"]), k


def test_the_full_contact_layer_case_recomputes(tmp_path):
    """--check of the full-contact layer case (every mesh, the reference: under a second)."""
    res = suite.check([LAYER_FULL], out=tmp_path, log=lambda s: None)
    assert res["ok"] and not res["cases"][0]["raised"], res["cases"]


def test_a_layer_case_on_coarse_meshes_agrees_with_what_is_shipped(data, monkeypatch):
    """The thin frictionless layer recomputed on N = 2^10 … 2^14 only (about a second, the
    Fourier reference on the same layer included): every scalar within the coarse study's error
    of the shipped value, never more digits; the Fourier reference is called with the case's
    layer as k d; the fields within both errors."""
    shipped = suite.get_case("sls-layer-frictionless-d0.1", data)
    case = copy.deepcopy(shipped)
    case["nodes"] = [1024, 2048, 4096, 8192, 16384]
    cert, fields, kw = compute_with_fourier_spy(case, monkeypatch)
    lay = shipped["point"]["layer"]
    assert kw["layer"] == {"thickness": 2 * math.pi * lay["thickness_over_wavelength"],
                           "foundation": lay["foundation"], "nu": lay["nu"]}
    assert cert["status"] == "complete" and cert["method"] == suite.FOURIER_METHOD
    assert set(cert["scalars"]) == set(shipped["certified"]["scalars"])
    assert cert["exact"] == shipped["certified"]["exact"]
    for k, rec in cert["scalars"].items():
        old = shipped["certified"]["scalars"][k]
        assert abs(rec["value"] - old["value"]) <= rec["error"] + old["error"], k
        assert 0 < rec["digits"] <= old["digits"], k
    old_fields = suite.case_fields(shipped)
    for col in suite.FIELD_COLUMNS:
        assert np.all(np.abs(fields[col] - old_fields[col])
                      <= fields[col + "_err"] + old_fields[col + "_err"]), col


def test_the_case_key_changes_with_the_layer(data):
    """A layer changed in any part (thickness, foundation, ν), or removed, is another case to
    --check --resume: never mistaken for the one recomputed before."""
    case = suite.get_case("sls-layer-bonded-d0.1", data)
    key = suite._case_key(case)
    assert suite._case_key(copy.deepcopy(case)) == key
    changes = [("thickness_over_wavelength", 0.1 + 1e-12), ("foundation", "frictionless"),
               ("nu", 0.49)]
    keys = {key}
    for name, value in changes:
        other = copy.deepcopy(case)
        other["point"]["layer"][name] = value
        keys.add(suite._case_key(other))
    gone = copy.deepcopy(case)
    del gone["point"]["layer"]
    keys.add(suite._case_key(gone))
    assert len(keys) == len(changes) + 2


def test_a_changed_layer_is_not_reused_by_resume(tmp_path, data):
    """--resume reuses a saved recomputation only under the same key: the saved full-contact
    layer case is reused as it is, not once its layer is thinner."""
    suite.check([LAYER_FULL], out=tmp_path, log=lambda s: None)
    lines = []
    suite.check([LAYER_FULL], out=tmp_path, resume=True, log=lines.append)
    assert any("reused" in s for s in lines)
    other = copy.deepcopy(data)
    case = next(c for c in other["cases"] if c["name"] == LAYER_FULL)
    case["point"]["layer"]["thickness_over_wavelength"] = 0.45
    lines = []
    res = suite.check([LAYER_FULL], out=tmp_path, resume=True, suite=other, log=lines.append)
    assert not any("reused" in s for s in lines)
    assert not res["ok"]  # a thinner layer is another answer: the shipped digits change


def test_the_semi_analytic_road_has_no_layer():
    """A layer turns the semi-analytic road off for the standard linear solid and allows the
    Fourier reference there; without the declaration the case would be BEM-only."""
    case = copy.deepcopy(suite.get_case("sls-partial-v1"))
    assert suite.two_roads(case["point"])
    case["point"]["layer"] = {"thickness_over_wavelength": 0.1, "foundation": "bonded",
                              "nu": 0.5}
    assert not suite.two_roads(case["point"])
    assert suite.reference_of(case) is None
    case["reference"] = "fourier"
    assert suite.reference_of(case) == "fourier"


@pytest.mark.parametrize("name, reference, why", [
    ("prony2-full", "semi-analytic", "one of fourier or none"),
    ("sls-above-fc-v1", "fourier", "not the standard linear solid on the half-space"),
    ("harmonics3-prony2", "fourier", "not a profile file"),
])
def test_a_reference_where_it_cannot_apply_is_refused(name, reference, why):
    case = dict(suite.get_case(name), reference=reference)
    with pytest.raises(suite.SuiteError) as info:
        suite.compute(case)
    text = str(info.value)
    assert len(text.splitlines()) == 1 and f"reference {reference!r} is not allowed" in text
    assert why in text and name in text


def test_export_and_list_state_the_layer(tmp_path, capsys, data):
    """What a third code needs to run a layer case: d/λ and k d, the foundation, ν, C, S(kd),
    the definitions of Δ/h (from the mean line of the deformed surface, as on the half-space)
    and of the approach, in inputs.json and the README; --list names the layer."""
    names = ["sls-layer-frictionless-d0.1", "broad24-layer-bonded-d0.2"]
    assert cli.main(["suite", "--export", str(tmp_path), "--cases", *names]) == 0
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "## Layers" in readme and "mean line of the deformed surface" in readme
    for name in names:
        case = suite.get_case(name, data)
        lay = case["point"]["layer"]
        inputs = json.loads((tmp_path / name / "inputs.json").read_text(encoding="utf-8"))
        got = inputs["layer"]
        assert got["thickness_over_wavelength"] == lay["thickness_over_wavelength"]
        assert got["thickness_kd"] == pytest.approx(2 * math.pi * lay["thickness_over_wavelength"],
                                                    rel=1e-15)
        assert got["foundation"] == lay["foundation"] and got["nu"] == lay["nu"]
        assert got["uniform_compliance_C"] == pytest.approx(_uniform_compliance(lay), rel=1e-15)
        assert got["layer_factor_mode_1"] == pytest.approx(
            case["certified"]["reference"]["layer"]["factor_mode_1"], rel=1e-14)
        assert got["mean_displacement"] == case["certified"]["exact"]["mean_displacement"]
        assert "mean line of the deformed surface" in got["approach"]
        assert "approach = Delta/h + v0/h" in got["approach"]
        assert "bonded" in got["definition"] and "frictionless" in got["definition"]
        assert "same layer" in inputs["reference_road"]
        assert f"- {name}: d/λ = {lay['thickness_over_wavelength']:g}, k d = " in readme
        sc = json.loads((tmp_path / name / "scalars.json").read_text(encoding="utf-8"))
        assert sc["scalars"]["approach"]["digits"] == \
            case["certified"]["scalars"]["approach"]["digits"]
    assert cli.main(["suite", "--list", "--cases", *names]) == 0
    out = capsys.readouterr().out
    assert "layer d/λ = 0.1 (kd = 0.6283), frictionless, ν = 0.3" in out
    assert "layer d/λ = 0.2 (kd = 1.257), bonded, ν = 0.45" in out
