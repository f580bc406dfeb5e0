"""The material figure's numbers (comparisons/plots/materials.py): E*(ω) = 1/J*(ω) of a Prony
creep function against its limits, the standard linear solid's closed form and its loss peak."""
import math

import numpy as np
import pytest

from comparisons.plots import materials as _figures

from conftest import ROUNDOFF

SLS3 = (1.0, [(2.0 / 3.0, 1.0)])                       # the paper's material, E∞/E0 = 3
PRONY3 = (1.0, [(0.3, 0.01), (0.3, 1.0), (0.3, 100.0)])  # J(0+) = 0.1


@pytest.mark.parametrize("J0, terms", [SLS3, PRONY3, (2.0, [(1.999, 0.5)])],
                         ids=["sls3", "prony3", "ratio2000"])
def test_limits_are_the_relaxed_and_glassy_moduli(J0, terms):
    jplus = J0 - sum(j for j, _ in terms)
    e1, e2, tan = _figures.complex_modulus([1e-12, 1e12], J0, terms)
    assert e1[0] == pytest.approx(1.0 / J0, rel=1e-10)      # E0 = 1/J0 at ω → 0
    assert e1[1] == pytest.approx(1.0 / jplus, rel=1e-9)    # E∞ = 1/J(0+) at ω → ∞
    assert np.all(e2 > 0.0) and np.all(tan > 0.0) and np.all(tan < 1e-8)


@pytest.mark.parametrize("J0, terms", [SLS3, PRONY3], ids=["sls3", "prony3"])
def test_loss_is_positive_and_storage_rises(J0, terms):
    w = np.logspace(-6, 6, 2001)
    e1, e2, tan = _figures.complex_modulus(w, J0, terms)
    assert np.all(e2 > 0.0)                   # the strain lags the stress: energy is dissipated
    assert np.all(np.diff(e1) > 0.0)          # from E0 up to E∞
    np.testing.assert_allclose(tan, e2 / e1, rtol=ROUNDOFF)


def test_standard_linear_solid_is_the_papers_modulus():
    """E*/E0 = (1 + iωτ)/(1 + iωτ/ρ) (the modulus E(kV) of the paper at ω = kV)."""
    for rho in (3.0, 10.0, 1e3):
        w = np.logspace(-4, 4, 81)
        e1, e2, _ = _figures.complex_modulus(w, 1.0, [(1.0 - 1.0 / rho, 1.0)])
        exact = (1 + 1j * w) / (1 + 1j * w / rho)
        np.testing.assert_allclose(e1 + 1j * e2, exact, rtol=1e-13)


def test_loss_tangent_peak_of_the_standard_linear_solid():
    """tan δ = ωτ(1 − 1/ρ)/(1 + ω²τ²/ρ) peaks at ωτ = √ρ with (ρ − 1)/(2√ρ); E″ at ωτ = ρ."""
    for rho in (3.0, 10.0):
        terms = [(1.0 - 1.0 / rho, 1.0)]
        f = lambda lw, i: -_figures.complex_modulus([10.0 ** lw], 1.0, terms)[i][0]  # noqa: E731
        from scipy.optimize import minimize_scalar
        peak = minimize_scalar(lambda lw: f(lw, 2), bounds=(-2, 3), method="bounded",
                               options={"xatol": 1e-10})
        assert 10.0 ** peak.x == pytest.approx(math.sqrt(rho), rel=1e-6)
        assert -peak.fun == pytest.approx((rho - 1.0) / (2.0 * math.sqrt(rho)), rel=1e-12)
        peak2 = minimize_scalar(lambda lw: f(lw, 1), bounds=(-2, 3), method="bounded",
                                options={"xatol": 1e-10})
        assert 10.0 ** peak2.x == pytest.approx(rho, rel=1e-6)


def test_not_a_creep_function_is_refused():
    for J0, terms in [(0.0, []), (1.0, [(-0.1, 1.0)]), (1.0, [(0.5, 0.0)]), (1.0, [(1.0, 1.0)])]:
        with pytest.raises(ValueError, match="is not allowed"):
            _figures.complex_modulus([1.0], J0, terms)


def test_plot_material_draws_on_the_given_axes(tmp_path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots()
    assert _figures.plot_material(ax, *PRONY3, speeds=[0.3, 3.0]) is ax
    assert ax.get_xscale() == ax.get_yscale() == "log"
    assert "J0 = 1" in ax.get_title() and "E∞/E0" in ax.get_title()
    assert sum(abs(line.get_xdata()[0] - 0.3) < 1e-12 for line in ax.lines) == 1  # marked kV
    plt.close(fig)
    path = _figures.material_figure(tmp_path / "m.png", *SLS3, speeds=[1.0])
    assert path.stat().st_size > 10_000


# ------------------------------------------------------------------------------ kept figures
_DRAWN = []  # the paths the writer below drew (a global: a closure would be an input)


def _draw_a(ax, data):
    ax.plot(data["x"], data["y"])
    ax.set_title(f"a {data['label']}")


def _draw_b(ax, data):
    ax.semilogy(data["x"], data["y"])
    ax.set_title(f"b {data['label']}")


def _write_figure(path_png, draw, data, *, extra=None):
    from comparisons import plots
    _DRAWN.append(path_png)
    fig, ax = plots.pyplot().subplots(figsize=(2.0, 2.0))
    draw(ax, data)
    title = ax.get_title()
    plots.save(fig, path_png, returned=title)
    return title


def test_a_figure_drawn_from_the_same_inputs_is_kept_and_any_change_redraws_it(tmp_path,
                                                                             monkeypatch):
    """`kept_when_unchanged`: the same inputs keep the PNG (not drawn, not touched, the same
    value returned); another value, another array, another drawing, another keyword, a PNG of
    other inputs, a PNG without the entry, a changed plots source and an input the digest
    cannot read draw it again."""
    from comparisons import plots
    # the writer and its drawings must be of the plots package for their code to be digested
    for f in (_draw_a, _draw_b, _write_figure):
        monkeypatch.setattr(f, "__module__", "comparisons.plots.test")
    write = plots.kept_when_unchanged(_write_figure)
    png = tmp_path / "f.png"
    data = {"x": np.arange(5.0), "y": np.arange(5.0) ** 2 + 1.0, "label": "μ"}

    def run(*args, **kw):
        n = len(_DRAWN)
        out = write(str(png), *args, **kw)
        return out, len(_DRAWN) > n, png.stat().st_mtime_ns

    title, did, t0 = run(_draw_a, data)
    assert did and title == "a μ"
    assert run(_draw_a, {**data})[:2] == ("a μ", False) and png.stat().st_mtime_ns == t0
    changed = [((_draw_a, {**data, "label": "ν"}), {}),
               ((_draw_a, {**data, "y": data["y"] * (1.0 + 1e-15)}), {}),
               ((_draw_b, data), {}),
               ((_draw_a, data), {"extra": 1.0})]
    for args, kw in changed:
        assert run(*args, **kw)[1], (args, kw)
        assert run(*args, **kw)[1] is False, (args, kw)  # and then kept
    plots.pyplot().figure().savefig(png)                   # a PNG without the entry
    assert run(_draw_a, data)[1]
    png.write_bytes(b"not a png")
    assert run(_draw_a, data)[1]
    monkeypatch.setattr(plots, "_source", lambda: "another source")
    assert run(_draw_a, data)[1] and not run(_draw_a, data)[1]
    for _ in range(2):  # an object the digest cannot read: drawn every time
        assert run(_draw_a, {**data, "label": object()})[1]
