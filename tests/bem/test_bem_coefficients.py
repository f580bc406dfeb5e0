"""Real-space influence coefficients against their Fourier series; FFT products."""
from __future__ import annotations

import numpy as np
import pytest

import bem
from bem._operator import CirculantOperator

from _bem_references import aliased_symbol, brute_symbol, fourier_coefficients

# Tolerances (what each one measures):
#: closed-form aliased sums vs brute-force summation (round-off of both)
TOL_REFERENCE = 1e-13
#: real-space coefficients vs Fourier series, relative to max|C| (the accuracy asked of them)
TOL_COEFF = 1e-12
#: FFT convolution vs dense circulant sum, relative to the result's scale (round-off)
TOL_FFT = 1e-13

SLS = bem.Prony.standard_linear_solid(3.0)
TWO_TERM = bem.Prony(1.0, (0.5, 0.3), (1.0, 0.01))
SPEEDS = [0.0, 1e-6, 1e-3, 0.3, 1.0, 6.0, 100.0, 1e6]


@pytest.mark.parametrize("nodes,k,speed", [(16, 3, 0.3), (16, 5, 30.0), (16, 1, 5.0),
                                           (32, 16, 1e-6), (32, 7, 1e6), (64, 31, 1.0)])
def test_fourier_reference_closed_forms_against_brute_force(nodes, k, speed):
    """The reference itself: digamma / Hurwitz closed forms vs direct alternating sums."""
    for mat in (SLS, TWO_TERM):
        closed = aliased_symbol(nodes, mat.j_plus, mat.terms, speed)[k]
        brute = brute_symbol(nodes, k, mat.j_plus, mat.terms, speed)
        assert abs(closed - brute) <= TOL_REFERENCE * abs(closed)


@pytest.mark.parametrize("material", [SLS, TWO_TERM], ids=["sls", "two-term"])
@pytest.mark.parametrize("nodes", [8, 64, 256, 1024, 4096])
def test_coefficients_match_fourier_series(material, nodes):
    for speed in SPEEDS:
        c = bem.influence_coefficients(material, speed, nodes)
        ref, imag = fourier_coefficients(nodes, material.j_plus, material.terms, speed)
        assert imag < TOL_REFERENCE * np.max(np.abs(ref))  # reference is real
        err = np.max(np.abs(c - ref)) / np.max(np.abs(ref))
        assert err < TOL_COEFF, (speed, err)


def test_memory_part_vanishes_like_one_over_speed():
    nodes = 256
    elastic = bem.influence_coefficients(bem.Prony(1.0 / 3.0), 0.0, nodes)
    d = [np.max(np.abs(bem.influence_coefficients(SLS, w, nodes) - elastic))
         for w in (1e4, 1e5, 1e6)]
    assert abs(d[0] / d[1] - 10.0) < 1e-3 and abs(d[1] / d[2] - 10.0) < 1e-3
    relaxed = bem.influence_coefficients(bem.Prony(1.0), 0.0, nodes)
    assert np.max(np.abs(bem.influence_coefficients(SLS, 0.0, nodes) - relaxed)) < 1e-15


def test_symbol_and_positive_symmetric_part():
    """Mode 1 of the DFT is the compliance of mode 1 times sinc, up to aliasing; and
    the symmetric part of the operator is positive definite (Re Chat_k > 0)."""
    nodes = 1024
    for speed in (0.01, 1.0, 100.0):
        chat = np.fft.rfft(bem.influence_coefficients(SLS, speed, nodes))
        lead = 2.0 * SLS.jstar(1, speed) * np.sinc(1.0 / nodes)
        assert abs(chat[1] / lead - 1.0) < 1e-6
        assert np.all(chat[1:].real > 0)


@pytest.mark.parametrize("nodes", [8, 33, 256])
def test_fft_product_against_dense_circulant(nodes):
    rng = np.random.default_rng(nodes)
    c = bem.influence_coefficients(SLS, 0.7, nodes)
    op = CirculantOperator(c)
    i, j = np.indices((nodes, nodes))
    dense = c[(i - j) % nodes]  # v_i = sum_j C[(i - j) mod N] sigma_j
    for _ in range(3):
        x = rng.standard_normal(nodes)
        assert np.max(np.abs(op.apply(x) - dense @ x)) < TOL_FFT * np.max(np.abs(dense @ x)) * 10
    # the pseudo-inverse inverts on zero-mean data and returns zero mean
    v = dense @ rng.standard_normal(nodes)
    sig = op.pseudo_solve(v)
    assert abs(sig.mean()) < 1e-14 and np.max(np.abs(dense @ sig - v)) < 1e-12 * np.max(np.abs(v))


def test_memory_lies_behind_the_load():
    """Material streams toward -x: the delayed response sits at offsets X < 0."""
    nodes = 64
    c = bem.influence_coefficients(SLS, 1.0, nodes)
    behind = c[nodes - 5]  # offset -5/N
    ahead = c[5]
    assert behind > ahead


def test_influence_coefficients_bad_input():
    with pytest.raises(ValueError, match="nodes=7"):
        bem.influence_coefficients(SLS, 1.0, 7)
    with pytest.raises(ValueError, match="speed=-1"):
        bem.influence_coefficients(SLS, -1.0, 64)
    with pytest.raises(ValueError, match="material"):
        bem.influence_coefficients("sls", 1.0, 64)
