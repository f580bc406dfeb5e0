"""The pressure memory layer: relaxation times of a Prony series and the BEM's report of how
many panels resolve the layer (below one panel the result says so)."""
import math

import pytest

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


def test_unresolved_layer_is_reported():
    sls = bem.Prony.standard_linear_solid(3.0)
    r = bem.solve(profile=bem.Sinusoid(1.0), material=sls, speed=1e-6, nodes=1024, load=0.3)
    assert r.success and r.memory_layer_panels == pytest.approx(1e-6 / 3 * 1024 / (2 * math.pi), rel=1e-12)
    assert "memory layer" in r.message
    r = bem.solve(profile=bem.Sinusoid(1.0), material=sls, speed=1.0, nodes=1024, load=0.3)
    assert r.memory_layer_panels > 50 and "memory layer" not in r.message
