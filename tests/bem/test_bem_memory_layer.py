"""The pressure memory layer: relaxation times of a Prony series and the BEM's report of how
many panels resolve the layer (below one panel the result says so)."""
import math

import numpy as np
import pytest

import analytic
import bem


def test_relaxation_time_of_the_standard_linear_solid():
    for ratio in (1.5, 3.0, 100.0):
        (t,) = bem.Prony.standard_linear_solid(ratio).relaxation_times
        assert t == pytest.approx(1.0 / ratio, rel=1e-14)  # τ E0/E∞


def test_relaxation_times_are_zeros_of_the_laplace_compliance():
    m = bem.Prony(1.0, (0.5, 0.2, 0.1), (1.0, 0.01, 30.0))
    ts = m.relaxation_times
    assert len(ts) == 3 and all(t > 0 for t in ts)
    for t in ts:
        s = -1.0 / t
        f = m.j_plus + sum(j / (1.0 + s * tau) for j, tau in m.terms)
        scale = m.j_plus + sum(abs(j / (1.0 + s * tau)) for j, tau in m.terms)
        assert abs(f) < 1e-13 * scale
    assert bem.Prony(1.0).relaxation_times == ()


def test_unresolved_layer_is_reported_where_it_matters():
    """A memory layer under a panel is measured always, and warned about only where its bound
    on μ (in the estimate) exceeds the accuracy asked (the default rtol on a fixed mesh)."""
    sls = bem.Prony.standard_linear_solid(3.0)
    r = bem.solve(profile=bem.Sinusoid(1.0), material=sls, speed=1e-6, nodes=1024, load=0.3)
    assert r.success and r.memory_layer_panels == pytest.approx(1e-6 / 3 * 1024 / (2 * math.pi), rel=1e-12)
    assert "memory layer" not in r.message and not r.warnings  # its bound: 5e-8 < 1e-6
    r = bem.solve(profile=bem.Sinusoid(1.0), material=sls, speed=1.0, nodes=1024, load=0.3)
    assert r.memory_layer_panels > 50 and "memory layer" not in r.message
    stiff = dict(load=0.3, speed=1e-3, ratio=1000.0)
    r = bem.solve(**stiff, nodes=1024)  # bound 7.5e-5 on μ > the default 1e-6: said
    note, = [w for w in r.warnings if "memory layer" in w]
    bound = float(note.split("by up to ")[1].split(" ")[0])
    assert 1e-6 < bound <= r.error_estimate["mu"] and "the default rtol=1e-06" in note
    r = bem.solve(**stiff, rtol=1e-3)  # the same layer, within the accuracy asked: quiet
    assert r.success and r.memory_layer_panels < 1 and not r.warnings


# --------------------------------------------------------------------------------------------
# The collocation shift of a memory term whose pressure layer is thinner than a panel
# --------------------------------------------------------------------------------------------
from bem import _influence  # noqa: E402  (the shift is internal to the coefficients)

#: a stiff material at low speed: memory length ~25 panels at N = 16384, layer 0.04 panel
STIFF_SLOW = dict(load=0.0011506985570461663, speed=0.009753117343529079,
                  ratio=593.1916580074861, hk=8.382036304275601)


def _model_ratio(h, length, j_local, j_i, delta):
    """sigma_i/sigma_(i+1) of the homogeneous model equations (collocation_shift's docstring)."""
    s = math.exp(-0.5 * h / length)
    e = math.exp(-delta / length)
    return s * s - j_i * (1 - s * s) * e * s / (j_local + j_i * (1 - s * e))


@pytest.mark.parametrize("ratio", [1.01, 1.5, 3.0])
def test_no_shift_for_soft_materials(ratio):
    """Up to E_inf/E0 = 3 the centred collocation never forms a sawtooth worse than -0.3 per
    panel: no shift, at any panel size against the memory length."""
    jp, ji = 1.0 / ratio, 1.0 - 1.0 / ratio
    for x in np.logspace(-6, 6, 400):  # h/L
        assert _influence.collocation_shift(x, 1.0, jp, ji) == 0.0


@pytest.mark.parametrize("ratio", [10.0, 100.0, 1000.0])
def test_shift_brings_the_sawtooth_ratio_to_its_bound(ratio):
    jp, ji = 1.0 / ratio, 1.0 - 1.0 / ratio
    shifted = 0
    for x in np.logspace(-6, 6, 400):
        d = _influence.collocation_shift(x, 1.0, jp, ji)
        assert 0.0 <= d <= 0.7 / 2.6 * x and d <= 0.1713  # (1 - k)/(2(1 + k)) h, 0.17 L
        r0 = _model_ratio(x, 1.0, jp, ji, 0.0)
        if r0 >= -_influence.SAWTOOTH_RATIO:
            assert d == 0.0
        else:
            shifted += 1
            assert _model_ratio(x, 1.0, jp, ji, d) == pytest.approx(-_influence.SAWTOOTH_RATIO,
                                                                    abs=1e-9)
        if x < 1e-3 * (jp / (jp + ji)) or x > 10.0:  # resolved layer, or memory within a panel
            assert d == 0.0
    assert shifted > 0


@pytest.mark.parametrize("frac", [0.05, 0.2, 0.3])
def test_shifted_coefficients_against_quadrature(frac):
    """The shifted memory coefficient is its defining integral at X_m - delta."""
    from scipy.integrate import quad
    nodes, length = 64, 0.02
    delta = frac / nodes
    coef = _influence.shifted_memory_coefficients(nodes, length, delta)
    one = np.empty(1)

    def c(x):
        bem._kernels.panel_values(np.array([x]), nodes, one)
        return one[0]

    for m in (0, 1, 2, -1, 5):
        x0 = m / nodes - delta
        kinks = sorted(b - x0 for b in ((k + 0.5) / nodes for k in range(-3, 40)) if b > x0)
        ref = quad(lambda y: math.exp(-y / length) * c(x0 + y), 0.0, 40 * length,
                   points=kinks[:45], limit=500, epsabs=1e-15, epsrel=1e-13)[0] / length
        assert abs(coef[m] - ref) <= 1e-13 * abs(ref), m


@pytest.mark.slow  # about 15 s
def test_stiff_slow_contact_has_no_sawtooth(monkeypatch):
    """E_inf/E0 ~ 600 at low speed: with the shift one patch, a monotone pressure except at
    the last few panels, and a handful of active-set steps; centred collocation (shift off)
    gives a sawtooth over the contact, a spurious second patch, and dozens of steps."""
    def solve():
        r = bem.solve(**STIFF_SLOW, nodes=16384, nested=False, max_outer=200)
        assert r.success, r.message
        s = np.asarray(r.fields().pressure)
        d = np.diff(s[s > 0])
        flips = int(np.count_nonzero(np.sign(d[1:]) != np.sign(d[:-1])))
        return r, flips

    r, flips = solve()
    assert r.n_patches == 1 and flips <= 8 and r.diagnostics["levels"][-1][1] <= 10
    ref = analytic.solve(**STIFF_SLOW)
    assert abs(r.mu / ref.mu - 1) < 2e-3 and abs(r.ka - ref.ka) < 1e-4
    monkeypatch.setattr(_influence, "SAWTOOTH_RATIO", 1.0)  # never shift
    r, flips = solve()
    assert r.n_patches == 2 and flips > 50 and r.diagnostics["levels"][-1][1] > 30


#: what the edge fits' memory lag may leave of the first-order edge shift (measured: at most
#: 0.083 of it, in ke at N = 1024; 0.042 at 4096, 0.017 at 16384; ka within 0.01)
LAG_LEFT = 0.1
#: a stiff four-term spectrum (E_inf/E0 = 1000) over two decades, and the standard linear solid
STIFF = bem.Prony(1.0, (0.2, 0.35, 0.15, 0.299), (1.0, 0.1, 0.01, 0.03))


def _first_order(material, speed, n):
    """(ka - ka_W, ke) over P = pi sum J_i L_i / J0 on N panels, L_i = w tau_i/(2 pi)
    (wavelengths): -1 and +1 by the paper's low-speed law (§3, the trailing edge retreats by
    sum J_i L_i/J0), the Westergaard base being the BEM's own on the same grid."""
    moment = sum(j * speed * t / (2 * math.pi) for j, t in material.terms) / material.J0
    p = math.pi * moment
    r = bem.solve(load=0.3, speed=speed, material=material, nodes=n)
    w = bem.solve(load=0.3, speed=0.0, material=material, nodes=n)
    return (r.ka - w.ka) / p, r.ke / p


@pytest.mark.parametrize("material", [STIFF, bem.Prony.standard_linear_solid(3.0)],
                         ids=["four-terms", "sls"])
@pytest.mark.parametrize("n", [1024, 4096])
def test_memory_far_below_a_panel_moves_the_edges_by_the_low_speed_law(material, n):
    """Memories of 1e-3 to 0.05 panel: the edge fits see the outer fields, whose edges are
    those of the elastic contact moved by the memory (the pressure's by sum J_i L_i/J_s toward
    +x, the gap's not at all); bem._edges.edge_lags puts the true edges back."""
    for fraction in (1e-3, 0.05):
        speed = fraction * 2 * math.pi / (n * max(material.tau))
        dka, ke = _first_order(material, speed, n)
        assert abs(dka + 1) < LAG_LEFT and abs(ke - 1) < LAG_LEFT, (fraction, dka, ke)


def test_without_the_memory_lag_the_contraction_is_missed(monkeypatch):
    """The check above can fail: without the lag the fits average the pressure's and the gap's
    edges, and ka stays Westergaard's."""
    from bem import _edges
    monkeypatch.setattr(_edges, "LAG_FRACTION", 0.0)
    speed = 0.01 * 2 * math.pi / (4096 * max(STIFF.tau))
    dka, ke = _first_order(STIFF, speed, 4096)
    assert abs(dka) < LAG_LEFT and abs(ke - 1) < LAG_LEFT


def test_memory_far_below_a_panel_against_the_semi_analytic_road():
    """The standard linear solid with E_inf/E0 = 1000 at memory lengths 0.01 and 0.05 panel of
    N = 16384, against the semi-analytic road: ka within its Westergaard discretisation error
    plus what the lag may leave (the shift itself is 5e-5 .. 2.4e-6)."""
    n = 16384
    for fraction in (0.01, 0.05):
        speed = fraction * 2 * math.pi / n
        shift = math.pi * (1 - 1e-3) * speed / (2 * math.pi)
        ref = analytic.solve(load=0.3, speed=speed, ratio=1000.0)
        r = bem.solve(load=0.3, speed=speed, ratio=1000.0, nodes=n)
        w = bem.solve(load=0.3, speed=0.0, ratio=1000.0, nodes=n)
        base = abs(w.ka - analytic.solve(load=0.3, speed=0.0, ratio=1000.0).ka)
        assert abs(r.ka - ref.ka) < base + LAG_LEFT * shift
        assert abs(r.ke - ref.ke) < LAG_LEFT * shift


def test_a_python_caller_sees_the_result_s_warnings():
    """The warnings the command line prints reach a caller of bem.solve as ViscosineWarning
    (and stay in result.warnings); a result without any raises none."""
    import warnings

    from viscosine import ViscosineWarning
    with pytest.warns(ViscosineWarning, match="memory layer") as caught:
        r = bem.solve(load=0.3, speed=1e-3, ratio=1000.0, nodes=1024)
    assert r.warnings and [str(w.message) for w in caught] == list(r.warnings)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = bem.solve(load=0.3, speed=1.0, nodes=1024)
    assert not r.warnings


def _model_ratio_all(h, j_plus, terms, lengths, shifts):
    """The sawtooth ratio sigma_i/sigma_(i+1) of the homogeneous model equations with every term
    (collocation_shifts' docstring): 1/r at the root r < 0 of F, 0 where F has none."""
    from scipy.optimize import brentq

    def f(r):
        out = j_plus
        for (j, _), ln, d in zip(terms, lengths, shifts):
            q, e = math.exp(-h / ln), math.exp(-d / ln)
            out += j * ((1 - math.sqrt(q) * e) + (1 - q) * math.sqrt(q) * e * r / (1 - q * r))
        return out

    return 0.0 if f(-1e12) >= 0 else 1.0 / brentq(f, -1e12, -1e-12, xtol=1e-14)


def _old_rule(h, j_plus, terms, lengths):
    """One shift per term from its own model (collocation_shift), the others counted as local."""
    local = [j * -math.expm1(-0.5 * h / ln) for (j, _), ln in zip(terms, lengths)]
    return [_influence.collocation_shift(h, ln, j_plus + sum(local) - local[i], terms[i][0])
            for i, ln in enumerate(lengths)]


def test_the_shift_of_many_terms_bounds_their_joint_sawtooth():
    """Random stiff spectra (8-64 terms, E_inf/E0 up to 1e4) on grids whose panels meet their
    memories: the shifts leave the sawtooth ratio of the model with all terms at least -k,
    share one value, and stay below 0.27 h; terms that shift alone under the one-term rule are
    shifted, and one term is collocation_shift exactly."""
    from comparisons.bench.materials import sample
    k = _influence.SAWTOOTH_RATIO
    worse = 0
    for p in sample(40, 7):
        mat = bem.Prony(p["J0"], p["J"], p["tau"])
        for n in (2 ** 12, 2 ** 16, 2 ** 20):
            h = 1.0 / n
            lengths = [p["speed"] * t / (2 * math.pi) for t in mat.tau]
            if not all(ln > 0 for ln in lengths):
                continue
            d = _influence.collocation_shifts(h, mat.j_plus, mat.terms, lengths)
            assert _model_ratio_all(h, mat.j_plus, mat.terms, lengths, d) >= -k - 1e-9
            assert len({x for x in d if x > 0}) <= 1 and max(d) <= 0.7 / 2.6 * h * (1 + 1e-12)
            old = _old_rule(h, mat.j_plus, mat.terms, lengths)
            assert all(x > 0 for x, o in zip(d, old) if o > 0)
            worse += _model_ratio_all(h, mat.j_plus, mat.terms, lengths, old) < -k
    assert worse > 0  # the one-term rule leaves joint sawtooths in this sample
    for x in np.logspace(-4, 3, 300):
        assert (_influence.collocation_shifts(x, 1e-3, ((0.999, 1.0),), (1.0,))[0]
                == _influence.collocation_shift(x, 1.0, 1e-3, 0.999))


def test_a_stiff_broad_spectrum_has_no_joint_sawtooth():
    """52 terms over 8 decades, E_inf/E0 = 8840, V/V0 = 8e-3: at N = 131072 its shortest
    memories span 1.3 to 4 panels and no single one forms a sawtooth, but together they do
    (model ratio -0.88): with the one-term rule the contact edge grew a fringe of alternating
    panels that moved two panels per active-set step and never settled (the adaptive default
    refused the point).  With the joint shift the grid converges in one step, one patch."""
    from comparisons.bench.materials import sample
    p = sample(4, 20261125)[3]
    mat = bem.Prony(p["J0"], p["J"], p["tau"])
    h = 1.0 / 131072
    lengths = [p["speed"] * t / (2 * math.pi) for t in mat.tau]
    old = _old_rule(h, mat.j_plus, mat.terms, lengths)
    assert max(old) == 0.0
    assert _model_ratio_all(h, mat.j_plus, mat.terms, lengths, old) < -0.85
    r = bem.solve(load=p["load"], speed=p["speed"], material=mat, nodes=131072)
    assert r.success and r.n_patches == 1, r.message
    assert r.diagnostics["levels"][-1][1] <= 2
    coarse = bem.solve(load=p["load"], speed=p["speed"], material=mat, nodes=65536)
    assert r.mu == pytest.approx(coarse.mu, rel=1e-7)


def _edge_residual(rho, load, n, panels_of_memory):
    """(BEM's ka and ke errors less their elastic (V = 0) ones) over the first-order shift
    S = (1 - 1/rho) V/2 of the standard linear solid, a memory of `panels_of_memory` panels."""
    speed = 2 * math.pi * panels_of_memory / n
    shift = (1 - 1 / rho) * speed / 2
    r = bem.solve(load=load, speed=speed, ratio=rho, nodes=n)
    x = analytic.solve(load=load, speed=speed, ratio=rho)
    r0 = bem.solve(load=load, speed=0.0, ratio=rho, nodes=n)
    x0 = analytic.solve(load=load, speed=0.0, ratio=rho)
    return (abs((r.ka - x.ka) - (r0.ka - x0.ka)) / shift,
            abs((r.ke - x.ke) - (r0.ke - x0.ke)) / shift, speed)


@pytest.mark.parametrize("rho", [30.0, 300.0])
def test_a_shifted_memory_moves_the_edges_by_its_collocation_shift(rho):
    """A memory of one to four panels on a stiff material is collocated delta downstream
    (bem._influence.collocation_shifts): its edges err by delta/L of the first-order shift, the
    share bem._estimate._unresolved_memory counts (measured: to three digits)."""
    from bem import _estimate, _influence
    n = 4096
    mat = bem.Prony.standard_linear_solid(rho)
    for panels in (1.0, 2.0, 3.9):
        dka, dke, speed = _edge_residual(rho, 0.3, n, panels)
        delta = _influence.collocation_shifts(1.0 / n, mat.j_plus, mat.terms,
                                              [speed / (2 * math.pi)])[0]
        share = delta * n / panels
        assert share > 0.02
        assert abs(dka - share) < 0.1 * share and abs(dke - share) < 0.1 * share, (panels, dka)
        bound = _estimate._unresolved_memory(mat, speed, n)
        assert max(dka, dke) * (1 - 1 / rho) * speed / 2 < bound


def test_what_the_memory_lag_leaves_falls_like_one_over_root_n():
    """A memory a hundredth of the edge fits' reach: what their lag correction leaves of the
    first-order shift falls like 1/sqrt(N), under LAG_RESIDUAL sqrt(4096/N), the share the
    estimate counts (measured 0.039, 0.0087 and 0.0043 on 4096, 65536 and 262144 panels)."""
    from bem import _edges, _estimate
    for n in (4096, 65536, 262144):
        reach = _edges.edge_lag_reach(1.0 / n, n) * n  # in panels
        dka, dke, _ = _edge_residual(1000.0, 0.1, n, 0.01 * reach)
        share = _estimate.LAG_RESIDUAL * math.sqrt(4096 / n)
        assert max(dka, dke) < share, (n, dka, dke)
        assert max(dka, dke) > 0.1 * share, (n, dka, dke)  # the model is not idle
