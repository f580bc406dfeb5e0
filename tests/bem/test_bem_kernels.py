"""Each numba kernel of bem/_kernels.py against a plain NumPy / SciPy twin."""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate, special

from bem import _kernels
from bem._influence import (MemorySources, _legendre01, _product_weights, _signed_offsets,
                            elastic_coefficients, memory_coefficients)

# Tolerances (what each one measures):
#: absolute error of Cl2 (|Cl2| <= 1.015): a few ulp of the series plus the quad twin
TOL_CL2 = 2e-15
#: error of a panel value relative to the largest panel value at that N (round-off)
TOL_PANEL = 1e-14
#: relative error of a quadrature rule's moments (round-off of the rule's construction)
TOL_RULE = 1e-13
#: agreement of a compiled loop with its NumPy twin (same arithmetic, other order)
TOL_LOOP = 1e-13


def _cl2_quad(theta):
    """Cl2(theta) = -int_0^theta log|2 sin(t/2)| dt, for theta in [-2 pi, 2 pi]."""
    f = lambda t: -np.log(abs(2.0 * np.sin(t / 2.0)))  # noqa: E731
    pts = [p for p in (-2 * np.pi, 0.0, 2 * np.pi) if min(0, theta) < p < max(0, theta)]
    val, _ = integrate.quad(f, 0.0, theta, points=pts or None, epsabs=1e-16, epsrel=1e-15,
                            limit=200)
    return val


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_cl2_against_quadrature_and_symmetries():
    thetas = np.concatenate([np.linspace(-6.2, 6.2, 61), [1e-8, 1e-3, np.pi, 2.5, 3.1]])
    got = np.empty_like(thetas)
    _kernels.cl2_array(thetas, got)
    ref = np.array([_cl2_quad(t) for t in thetas])
    assert np.max(np.abs(got - ref)) < TOL_CL2
    # odd, 2 pi periodic, Cl2(pi/2) = Catalan's constant
    assert _kernels.cl2(-0.7) == -_kernels.cl2(0.7)
    assert abs(_kernels.cl2(0.7 + 2 * np.pi) - _kernels.cl2(0.7)) < TOL_CL2
    assert abs(_kernels.cl2(np.pi / 2) - 0.915965594177219015054603514932) < TOL_CL2


@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
@pytest.mark.parametrize("nodes", [8, 64, 4096])
def test_panel_values_against_quadrature_of_green_function(nodes):
    """(2/pi)[Cl2] difference = -(2/pi) int_panel 2 pi log|2 sin(pi(X - u))| du (eq. 2.2)."""
    h = 1.0 / nodes
    xs = np.array([0.0, 0.3 * h, h, 1.5 * h, 2 * h, 3.7 * h, 0.1, 0.25, 0.4999, 0.5, -0.2])
    got = np.empty_like(xs)
    _kernels.panel_values(xs, nodes, got)
    ref = []
    for x in xs:
        f = lambda u: -2.0 * np.log(abs(2.0 * np.sin(np.pi * (x - u)))) * 2.0  # noqa: E731
        lo, hi = -h / 2, h / 2
        pts = [p for p in (x, x - 1.0, x + 1.0) if lo < p < hi]
        val, _ = integrate.quad(f, lo, hi, points=pts or None, epsabs=1e-17, epsrel=1e-14,
                                limit=200)
        ref.append(val)
    ref = np.array(ref)
    scale = got[0]
    assert np.max(np.abs(got - ref)) / scale < TOL_PANEL


def test_cl2_difference_series_matches_direct_difference_where_that_is_safe():
    # where delta is not small the direct difference has no cancellation to speak of
    for delta in (0.3, 0.1):
        for theta in np.linspace(0.95, 5.3, 23):
            direct = _kernels.cl2(theta + delta) - _kernels.cl2(theta - delta)
            assert abs(_kernels.cl2_difference(theta, delta) - direct) < 4 * TOL_CL2


def test_exponential_recursion_against_dense_sum():
    """E_m = sum_(q>=0) e^(-a q) S_(m+q) = sum_(q<n) e^(-a q) S_(m+q) / (1 - e^(-a n))."""
    rng = np.random.default_rng(1)
    for n, a in ((8, 0.3), (37, 1e-4), (64, 5.0), (16, 80.0)):
        src = rng.standard_normal(n)
        got = np.empty(n)
        _kernels.exponential_recursion(src, a, got)
        q = np.arange(n)
        ref = np.array([np.sum(np.exp(-a * q) * src[(m + q) % n]) for m in range(n)])
        ref /= -np.expm1(-a * n)
        assert np.max(np.abs(got - ref)) < TOL_LOOP * np.sum(np.abs(ref))


@pytest.mark.parametrize("n", [4, 6, 8, 16, 32])
@pytest.mark.parametrize("a", [0.0, 1e-3, 0.7, 9.0, 60.0, 119.0, 121.0, 5e3, 1e12])
def test_product_weights_integrate_polynomials_exactly(a, n):
    """The shared product rules integrate exp(-a t) t^k exactly for k < n (to the rounding of
    sum |w_q|, the rule's scale), and stay stable: sum |w_q| within 12x the weight's mass (for
    a >> n^2 it tends to the Lebesgue function of the n Legendre points at t = 0, 10.3 for
    n = 32)."""
    t, _ = _legendre01(n)
    w = _product_weights(a, n)
    mass = 1.0 if a == 0.0 else -np.expm1(-a) / a
    assert np.abs(w).sum() <= 12.0 * mass
    for k in (0, 1, n // 2, n - 1):
        # int_0^1 e^(-a t) t^k dt = k! P(k+1, a) / a^(k+1)  (regularised incomplete gamma)
        if a == 0.0:
            ref = 1.0 / (k + 1)
        else:
            ref = math.exp(special.gammaln(k + 1) + math.log(special.gammainc(k + 1, a))
                           - (k + 1) * math.log(a))
        assert abs(np.dot(w, t**k) - ref) <= TOL_RULE * np.abs(w).sum()


@pytest.mark.parametrize("length", [1e-9, 0.002, 0.3, 50.0])
def test_memory_sources_against_numpy_twin(length):
    """Source integrals against a dense composite Gauss-Legendre twin in NumPy (40 x 30
    points with the exponential in the weights), on every band of shared points (32 … 4
    points, out to 8192 panels and beyond), for memories far below, at and beyond a panel."""
    nodes = 20000
    a = (1.0 / nodes) / length
    offsets = np.r_[-10000:-9980, -8200:-8180, -300:-240, -40:40, 250:300, 8180:8200,
                    9980:10000]
    got = MemorySources(nodes, offsets)(a)
    g, gw = np.polynomial.legendre.leggauss(30)
    pieces = 40 if a < 80 else 400
    edges = np.linspace(0.0, 1.0 if a < 80 else min(1.0, 60.0 / a), pieces + 1)
    tt = (0.5 * (edges[1:] + edges[:-1])[:, None] + 0.5 * np.diff(edges)[:, None] * g).ravel()
    ww = (0.5 * np.diff(edges)[:, None] * gw).ravel() * np.exp(-a * tt)
    for i, mm in enumerate(offsets):
        if mm in (0, -1):
            continue  # the kinks: a graded rule, checked by the coefficients' tests
        full = np.empty_like(tt)
        _kernels.panel_values((mm + tt) / nodes, nodes, full)  # checked against quad above
        assert abs(got[i] - np.dot(ww, full)) < TOL_LOOP * abs(full).max() * np.sum(ww) * 10


def test_stencil_sum_against_numpy_twin():
    rng = np.random.default_rng(3)
    values, weights = rng.standard_normal(50), rng.standard_normal(6)
    for first, count in ((0, 45), (3, 20), (44, 1)):
        got = np.empty(count)
        _kernels.stencil_sum(values, first, weights, got)
        ref = np.array([np.dot(weights, values[first + j:first + j + 6]) for j in range(count)])
        assert np.max(np.abs(got - ref)) < TOL_LOOP * np.abs(values).max()


@pytest.mark.parametrize("length", [1e-9, 0.002, 50.0])
def test_far_memory_sources_from_the_elastic_column(length):
    """Given the grid's elastic column, the band farther than 8192 panels from the kinks is
    integrated from c at the panel centres (a 6-point stencil): against the dense twin there,
    and equal to the Legendre-point sources everywhere to rounding."""
    nodes = 20000
    a = (1.0 / nodes) / length
    offsets = _signed_offsets(nodes)
    elastic = elastic_coefficients(nodes)
    shared = MemorySources(nodes, offsets, elastic)
    assert any(vals is None for _, _, vals in shared.bands)  # the stencil band is there
    got, plain = shared(a), MemorySources(nodes, offsets)(a)
    assert np.max(np.abs(got - plain)) <= 1e-15 * np.abs(plain).max()
    g, gw = np.polynomial.legendre.leggauss(30)
    tt = 0.5 * (g + 1.0)
    ww = 0.5 * gw * np.exp(-a * tt) if a < 80 else None
    for mm in (8193, 9000, 10000, -9001, -8194):
        i = mm % nodes
        if ww is None:  # a far below a panel: only its first 60/a matters (Laguerre's regime)
            s, sw = np.polynomial.laguerre.laggauss(30)
            pts, wts = s / a, sw / a
        else:
            pts, wts = tt, ww
        full = np.empty_like(pts)
        _kernels.panel_values((mm + pts) / nodes, nodes, full)
        assert abs(got[i] - np.dot(wts, full)) < TOL_LOOP * abs(full).max() * np.sum(wts) * 10


def test_memory_sources_of_a_window_are_the_grid_ones():
    nodes, a = 4096, 0.37
    full = MemorySources(nodes, _signed_offsets(nodes))(a)
    offsets = np.arange(-301, 300)
    win = MemorySources(nodes, offsets)(a)
    assert np.max(np.abs(win - full[offsets % nodes])) <= 1e-15 * np.abs(full).max()


def test_terms_sharing_one_shift_are_summed_as_each_alone():
    """Shifted terms share their second integral's kernel values (one set per grid): the
    operator equals the sum of each term's own shifted coefficients, periodic and windowed.
    A 52-term stiff spectrum at a speed where 52 terms take the joint shift."""
    from comparisons.bench.materials import sample
    import bem
    from bem import _influence as inf
    p = sample(4, 20261125)[3]
    mat = bem.Prony(p["J0"], p["J"], p["tau"])
    nodes, speed = 4096, p["speed"] * 32  # memories over panels as at 2^17 at its own speed
    lengths = [speed * t / (2 * math.pi) for t in mat.tau]
    shifts = inf.collocation_shifts(1 / nodes, mat.j_plus, mat.terms, lengths)
    assert sum(d > 0 for d in shifts) > 40
    for span in (None, (-700, 1500)):
        got = inf.influence_coefficients_nd(mat.j_plus, mat.terms, speed, nodes, span)
        if span is None:
            want = mat.j_plus * inf.elastic_coefficients(nodes)
        else:
            want = np.empty(span[1])
            _kernels.panel_values(np.arange(span[0], span[0] + span[1]) / nodes, nodes, want)
            want = mat.j_plus * want
        for (j, _), ln, d in zip(mat.terms, lengths, shifts):
            want = want + j * inf.shifted_memory_coefficients(nodes, ln, d, span)
        assert np.max(np.abs(got - want)) <= 1e-14 * np.abs(want).max(), span


def test_memory_coefficients_tend_to_relaxed_and_to_zero():
    nodes = 64
    base = np.empty(nodes)
    m = np.arange(nodes)
    _kernels.panel_values(np.where(m <= nodes // 2, m, m - nodes) / nodes, nodes, base)
    slow = memory_coefficients(nodes, 1e-9)  # L << panel: relaxed response, same place
    assert np.max(np.abs(slow - base)) < 1e-6 * np.max(base)
    prev = None
    for length in (1e3, 1e4, 1e5):  # L >> wavelength: vanishes like 1/L
        mem = memory_coefficients(nodes, length)
        if prev is not None:
            assert abs(np.max(np.abs(prev)) / np.max(np.abs(mem)) - 10.0) < 1e-2
        prev = mem


def test_update_active_set_and_residuals_against_numpy():
    rng = np.random.default_rng(7)
    for _ in range(5):
        n = 50
        active = rng.random(n) < 0.5
        p = rng.standard_normal(n) * active
        g = rng.standard_normal(n) * ~active
        out = np.empty(n, np.bool_)
        changed = _kernels.update_active_set(active, p, g, out)
        ref = np.where(active, p > 0, g < 0)
        assert np.array_equal(out, ref) and changed == int(np.sum(ref != active))
        res = np.empty(4)
        g2 = g + 1e-3 * rng.standard_normal(n)
        _kernels.contact_residuals(active, p, g2, res)
        ref = [np.max(np.abs(p * g2)), np.max(np.abs(g2[active])) if active.any() else 0.0,
               max(0.0, -g2.min()), max(0.0, -p.min())]
        assert np.allclose(res, ref, rtol=0, atol=0)
