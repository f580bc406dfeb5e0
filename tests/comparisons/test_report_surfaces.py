"""The report's surface section: its check runs through the runner (the route the report takes)
hold what the section claims, its fields round-trip through the results store, and its figures
draw the numbers given."""
import math

import numpy as np
import pytest

from comparisons import report_numbers, report_surfaces, runner
from comparisons.store import Store


@pytest.fixture(scope="module")
def checks(tmp_path_factory):
    store = Store(str(tmp_path_factory.mktemp("store")))
    runs = report_surfaces._check_runs(32, 64)
    for spec, fields in runs:
        store.put(spec, runner.run(spec, fields=fields), fields)
    return [store.get(spec)["record"] for spec, _ in runs]


def test_the_checks_hold_along_the_reports_route(checks):
    ext, ridge, obl, obl_ref, full = checks
    a = report_numbers.semi_analytic(0.3, 1.0)
    est = ext["error_estimate"]
    assert abs(ext["mu"] - a.mu) <= est["mu"] * a.mu
    assert abs(ext["contact_fraction"] - a.contact_fraction) <= \
        est["contact_fraction"] * ext["contact_fraction"]  # relative
    assert abs(ridge["mu"]) < 1e-14
    w = report_numbers.semi_analytic(0.3, 0.0)
    assert abs(ridge["penetration"] / w.penetration - 1) <= ridge["error_estimate"]["penetration"]
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    assert obl["mu"] == pytest.approx(c * obl_ref["mu"], rel=1e-12)
    assert obl["mu_lateral"] == pytest.approx(s * obl_ref["mu"], rel=1e-12)
    assert full["full_contact"]
    assert full["mu"] == pytest.approx(report_numbers.semi_analytic(4.0, 1.0).mu, rel=1e-12)


def test_surface_fields_round_trip_through_the_store(tmp_path):
    store = Store(str(tmp_path))
    spec = report_surfaces.surface_spec(0.3, 1.0, 32, report_surfaces.BISINUSOID, 30.0)
    out = runner.run(spec, fields=True)
    store.put(spec, out, True)
    got = store.get(spec, fields=True)
    assert got["ok"] and np.array_equal(got["fields"]["pressure"], out["fields"].pressure)
    assert got["fields"]["x"].shape == (32,)
    # a truncated archive is not trusted: the run is missing again
    path = next(tmp_path.glob("*.npz"))
    path.write_bytes(path.read_bytes()[:100])
    assert store.problem(spec, fields=True) is not None


def test_the_figures_draw_what_they_are_given(tmp_path):
    from comparisons.plots import surfaces as plots
    x = np.arange(16) / 16 - 0.5
    f = {"x": x, "y": x, "pressure": np.maximum(0, np.cos(2 * np.pi * x)[:, None]
                                                + np.cos(2 * np.pi * x)[None, :])}
    assert plots.write_pressure_map(str(tmp_path / "m.png"), f, 30.0)
    assert plots.write_friction(str(tmp_path / "f.png"),
                                [{"load": 0.1, "speed": [0.1, 1], "mu": [0.1, 0.2]}])
    assert plots.write_direction(str(tmp_path / "d.png"),
                                 {"direction": [0, 45], "mu": [0.1, 0.2],
                                  "mu_lateral": [0.0, 0.1]})
    c = {"load": 0.1, "speed": [1.0], "persson_mu": [0.1], "persson_cf": [0.2]}
    for k in ("mu", "cf"):
        for st in ("mean", "min", "max"):
            c[f"{k}_{st}"] = [0.1]
    assert plots.write_persson(str(tmp_path / "p.png"), [c])
    for name in ("m", "f", "d", "p"):
        assert (tmp_path / f"{name}.png").stat().st_size > 5_000
