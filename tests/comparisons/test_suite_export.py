"""`suite --export` and `suite --list`: plain CSV/JSON a third code can read (profiles, creep
series, the material a case was converted from, layers) and the digits table."""
import csv
import hashlib
import json
from pathlib import Path

import numpy as np
import pytest

import bem
from comparisons import cli, suite


@pytest.fixture(scope="module")
def data():
    return suite.load_suite()


# ---------------------------------------------------------------------------- --export
def test_export_writes_readable_csv_and_json(tmp_path, data):
    names = ["sls-partial-v1", "harmonics2-sls", "sls-penetration-v1", "harmonics3-prony2"]
    rc = cli.main(["suite", "--export", str(tmp_path), "--cases", *names])
    assert rc == 0
    index = json.loads((tmp_path / "index.json").read_text(encoding="utf-8"))
    assert index["cases"] == sorted(names, key=suite.case_names().index)
    assert index["rule"] == suite.RULE
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    assert "How the digits are certified" in readme and all(n in readme for n in names)
    # a Prony material gets its E′, E″, tan δ figure, linked from the README
    assert (tmp_path / "harmonics3-prony2" / "material.png").stat().st_size > 10_000
    assert "(harmonics3-prony2/material.png)" in readme
    assert not any((tmp_path / n / "material.png").exists() for n in names[:3])
    for name in names:
        case = suite.get_case(name, data)
        d = tmp_path / name
        inputs = json.loads((d / "inputs.json").read_text(encoding="utf-8"))
        assert inputs["speed"] == case["point"]["speed"]
        assert inputs["control"] == ("load" if case["point"].get("load") is not None
                                     else "penetration")
        sc = json.loads((d / "scalars.json").read_text(encoding="utf-8"))
        for key, rec in case["certified"]["scalars"].items():
            assert sc["scalars"][key]["value"] == rec["value"]
            assert sc["scalars"][key]["digits"] == rec["digits"]
        with open(d / "scalars.csv", newline="", encoding="utf-8") as fh:
            rows = list(csv.DictReader(fh))
        mu = next(r for r in rows if r["quantity"] == "mu" and r["patch"] == "")
        assert float(mu["value"]) == case["certified"]["scalars"]["mu"]["value"]
        assert int(mu["certified_digits"]) == case["certified"]["scalars"]["mu"]["digits"]
        assert sum(r["quantity"] == "ka" and r["patch"] != "" for r in rows) == \
            len(case["certified"]["patches"])
        with open(d / "fields.csv", encoding="utf-8") as fh:
            body = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
        assert body[0] == suite.FIELDS_HEADER and len(body) == 1 + 256
        np.testing.assert_array_equal(np.array(body[1:], float)[:, 1],
                                      suite.case_fields(case)["pressure"])
        material = bem.read_prony(d / "prony.txt")
        profile = bem.read_profile(d / "profile.csv")
        if suite.two_roads(case["point"]):
            assert material.j_plus == pytest.approx(1.0 / case["point"]["ratio"], rel=1e-15)
            x = np.arange(64) / 64 - 0.5
            np.testing.assert_allclose(profile.sample(64), np.cos(2 * np.pi * x), atol=1e-15)
        else:
            assert profile.amplitude == pytest.approx(
                bem.read_profile(suite.data_path(case["point"]["profile"])).amplitude, rel=1e-15)


def test_export_of_a_material_file_case_writes_its_creep_series_and_the_original(tmp_path,
                                                                                    data):
    """A case that names a relaxation series or a DMA curve (at a temperature) exports the creep
    series the BEM solved as prony.txt, saying what it was converted from (form, SHA-256), and
    the original file byte for byte."""
    names = ["relax16-partial", "dma-sbr-40C-partial"]
    assert cli.main(["suite", "--export", str(tmp_path), "--cases", *names]) == 0
    readme = (tmp_path / "README.md").read_text(encoding="utf-8")
    for name in names:
        case = suite.get_case(name, data)
        p, d = case["point"], tmp_path / name
        m = suite.case_material(p)
        original = suite.data_path(p["material"]).read_bytes()
        sha = hashlib.sha256(original).hexdigest()
        src = Path(p["material"]).name
        assert (d / src).read_bytes() == original
        text = (d / "prony.txt").read_text(encoding="utf-8")
        head = [ln for ln in text.splitlines() if ln.startswith("#")]
        assert f"converted from {src}" in head[0] and sha in head[0]
        assert suite.FORM_NAMES[m.info["form"]] in head[0]
        pr = bem.read_prony(d / "prony.txt")
        assert pr.J0 == m.prony.J0 and list(pr.J) == list(m.prony.J)
        assert list(pr.tau) == list(m.prony.tau)
        inputs = json.loads((d / "inputs.json").read_text(encoding="utf-8"))
        mat = inputs["material"]
        assert mat["source_file"] == src and mat["source_sha256"] == sha
        assert mat["temperature"] == p.get("temperature") and mat["terms"] == m.info["terms"]
        assert "Fourier" in inputs["reference_road"]
        assert (d / "material.png").stat().st_size > 10_000
        assert f"({name}/material.png)" in readme
    dma = (tmp_path / "dma-sbr-40C-partial" / "prony.txt").read_text(encoding="utf-8")
    assert "DMA master curve" in dma and "at temperature 40" in dma and "C1 = 8.86" in dma


def test_list_prints_the_digits_table(capsys):
    assert cli.main(["suite", "--list", "--cases", "sls-partial-v1"]) == 0
    out = capsys.readouterr().out
    assert "| sls-partial-v1 |" in out and "two roads" in out and "| half-plane |" in out
