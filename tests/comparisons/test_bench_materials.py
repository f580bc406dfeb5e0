"""The broad-spectrum study's sample is what it says it is (the study itself is a benchmark:
`python -m comparisons bench --materials`)."""
import math

import numpy as np
import pytest

from comparisons.bench import materials as bm


@pytest.mark.parametrize("shape", bm.SHAPES)
def test_spectrum_has_the_asked_ratio_span_and_terms(shape):
    rng = np.random.default_rng(3)
    j0, amps, tau = bm.spectrum(rng, shape, 40, 17.0, 2500.0)
    assert j0 == 1.0 and amps.size == tau.size == 40
    assert np.all(amps > 0) and np.all(np.diff(tau) > 0)
    assert math.isclose(j0 - amps.sum(), 1 / 2500.0, rel_tol=1e-9)  # J(0+) = E0/E∞
    assert math.isclose(math.log10(tau[-1] / tau[0]), 17.0, rel_tol=1e-12)


def test_sample_is_seeded_and_covers_its_ranges():
    a, b = bm.sample(40, 7), bm.sample(40, 7)
    assert a == b and a != bm.sample(40, 8)
    for p in a:
        assert bm.TERMS[0] <= p["terms"] <= bm.TERMS[1] and len(p["J"]) == p["terms"]
        assert bm.SPEED[0] <= p["speed"] <= bm.SPEED[1] and bm.LOAD[0] <= p["load"] <= bm.LOAD[1]
        assert bm.RATIO[0] <= p["ratio"] <= bm.RATIO[1]
    assert {p["shape"] for p in a} == set(bm.SHAPES)
