"""The sub-panel contact edge: the fit with a discretisation tail on exact synthetic data.

Near an edge the panel pressures of the BEM are sigma ~ d^(1/2) (analytic corrections) plus a
discretisation error that decays like d^(-3/2): sigma^2 then carries a tail b h/d.  The edge fit
models it; here the data are exactly of that form, so the fit must return the edge to
rounding, wherever it sits in its panel, while a plain polynomial fit is off by a visible part
of a panel (the scatter the tail term removes on real solutions: test_bem_solver's Westergaard
orders).
"""
from __future__ import annotations

import numpy as np
import pytest

from bem import _edges

#: the tail fit on data of exactly its form, relative to h: its fixed point in d stops once the
#: zero moves by 1e-10 h (rounding of a 5-column least-squares fit is far below)
TOL_EXACT = 1e-9
#: a plain cubic on the same data errs by more than this (relative to h)
PLAIN_OFF = 1e-3


def _synthetic(edge, nodes, tail_in, tail_out):
    """sigma^2 inward and gap^(2/3) outward of an edge at `edge` (offset from the last contact
    centre, in wavelengths): cubics in the distance with a simple zero there, plus b h/d."""
    h = 1.0 / nodes
    m = np.arange(nodes // 4)
    d_in = edge + m * h          # inside: centre at -m h
    d_out = (m + 1) * h - edge   # outside: centre at (m + 1) h
    # the panel at the edge (m = 0 inside, where d may vanish) carries an O(1) error in a real
    # solution and is never fitted: any finite value there
    d_in[0] = h
    inside = 2.0 * d_in * (1.0 - 1.3 * d_in + 0.8 * d_in**2) + tail_in * h * h / d_in
    outside = 0.7 * d_out * (1.0 + 0.9 * d_out - 0.4 * d_out**2) + tail_out * h * h / d_out
    return inside, outside, h


@pytest.mark.parametrize("nodes", [4096, 65536])
@pytest.mark.parametrize("frac", [-0.45, -0.1, 0.0, 0.3, 0.5, 0.77, 1.2, 1.45])
def test_tail_fit_returns_the_edge_of_exact_data(nodes, frac):
    inside, outside, h = _synthetic(frac / nodes, nodes, 0.02, -0.015)
    got = _edges.edge_offset(inside, outside, h, nodes)
    assert abs(got - frac * h) < TOL_EXACT * h
    plain = _edges.edge_offset_plain(inside, outside, h, nodes)
    assert abs(plain - frac * h) > PLAIN_OFF * h  # the tail is what the plain fit misses


def test_tail_fit_without_tail_is_the_cubic_zero():
    """No tail (b = 0): both fits find the zero of the cubics."""
    nodes = 16384
    inside, outside, h = _synthetic(0.4 / nodes, nodes, 0.0, 0.0)
    assert abs(_edges.edge_offset(inside, outside, h, nodes) - 0.4 * h) < TOL_EXACT * h


def test_short_sides_keep_the_plain_fit():
    """A side with fewer panels than the tail fit needs falls back to the plain fit."""
    nodes = 4096
    inside, outside, h = _synthetic(0.3 / nodes, nodes, 0.0, 0.0)
    short_in, short_out = inside[:6], outside[:6]
    assert _edges.edge_offset(short_in, short_out, h, nodes) == \
        _edges.edge_offset_plain(short_in, short_out, h, nodes)


def test_a_side_whose_zero_moves_with_the_window_is_dropped():
    """A second scale in the gap behind the edge (a recovery layer of 6 panels, inside the fit
    window): that side's zero moves with the window, so the edge comes from the contact side
    alone, to the accuracy of exact data; averaged in, the gap side would move it visibly."""
    nodes = 4096
    inside, outside, h = _synthetic(0.3 / nodes, nodes, 0.02, 0.0)
    d_out = (np.arange(outside.size) + 1 - 0.3) * h
    # a weak layer: strong enough to move the zero with the window, weak enough that both fits
    # still find one (at 0.5 the gap side's fit finds none and the check is not exercised)
    layered = outside * (1.0 + 0.02 * np.exp(-d_out / (6.0 * h)))
    got = _edges.edge_offset(inside, layered, h, nodes)
    assert abs(got - _edges.edge_offset(inside, np.zeros(0), h, nodes)) < TOL_EXACT * h
    assert abs(got - 0.3 * h) < TOL_EXACT * h
    m1, m2 = 4, 16  # the windows of N = 4096: sqrt(N)/16 .. sqrt(N)/4, and .. sqrt(N)/2
    narrow = _edges._tail_fit_root(layered, 1.0, 1.0, m1, m2, got, h)
    wide = _edges._tail_fit_root(layered, 1.0, 1.0, m1, 2 * m2, got, h)
    assert narrow is not None and wide is not None
    assert abs(narrow - wide) > _edges.EDGE_WINDOW_AGREEMENT * h
    assert abs(0.5 * (got + narrow) - 0.3 * h) > 1e3 * TOL_EXACT * h


def test_a_side_cut_short_is_checked_on_the_windows_it_holds():
    """A gap cut by the next edge before the wide window ends is fitted over the first half of
    its panels and checked against all of them: with the recovery layer it is dropped, clean it
    counts; shorter than the check needs, it is dropped (two windows holding the same panels
    would agree whatever the data)."""
    nodes = 4096
    inside, outside, h = _synthetic(0.3 / nodes, nodes, 0.02, 0.0)
    d_out = (np.arange(outside.size) + 1 - 0.3) * h
    layered = outside * (1.0 + 0.02 * np.exp(-d_out / (6.0 * h)))
    m1, m2 = 4, 16
    alone = _edges.edge_offset(inside, np.zeros(0), h, nodes)
    for short in (layered[:2 * m2], layered[:m2 + 1]):
        got = _edges.edge_offset(inside, short, h, nodes)
        assert abs(got - alone) < TOL_EXACT * h and abs(got - 0.3 * h) < TOL_EXACT * h
    # the short layered side on its own windows: a zero, but one that moves with the window
    narrow = _edges._tail_fit_root(layered, 1.0, 1.0, m1, m2 - 1, alone, h)
    wide = _edges._tail_fit_root(layered, 1.0, 1.0, m1, 2 * m2 - 2, alone, h)
    assert narrow is not None and wide is not None
    assert abs(narrow - wide) > _edges.EDGE_WINDOW_AGREEMENT * h
    # a clean side cut as short counts alone, to the accuracy of exact data
    clean = outside[:2 * m2]
    assert abs(_edges.edge_offset(np.zeros(0), clean, h, nodes) - 0.3 * h) < TOL_EXACT * h


def test_a_fixed_point_that_has_not_settled_gives_no_zero(monkeypatch):
    """From a start 0.6 h off the fit's fixed point needs several passes; cut short, it gives no
    zero rather than an unsettled one."""
    nodes = 4096
    inside, _, h = _synthetic(0.3 / nodes, nodes, 0.02, 0.0)
    start = 0.9 * h
    root = _edges._tail_fit_root(inside, -1.0, 0.0, 4, 16, start, h)
    assert root is not None and abs(root - 0.3 * h) < TOL_EXACT * h
    monkeypatch.setattr(_edges, "TAIL_FIT_PASSES", 2)
    assert _edges._tail_fit_root(inside, -1.0, 0.0, 4, 16, start, h) is None


@pytest.mark.parametrize("jitter, counts", [(5e-10, True), (5e-8, False)])
def test_a_fixed_point_jittering_at_rounding_still_gives_its_zero(monkeypatch, jitter, counts):
    """On fine grids the fit's zero carries more rounding than 1e-10 h: a fixed point that has
    converged but still moves by 2 jitter (in h) each pass gives its zero after TAIL_FIT_PASSES
    when that is at most TAIL_FIT_JITTER times the window's extent (here 16 h: 1.6e-9 h), and
    none when it moves more."""
    nodes = 4096
    inside, _, h = _synthetic(0.3 / nodes, nodes, 0.02, 0.0)
    scale = 16 * h  # the window's extent, m2 = 16
    plain = _edges._cubic_zero_near
    sign = [1.0]

    def jittering(c, x):
        z = plain(c, x)
        sign[0] = -sign[0]
        return None if z is None else z + sign[0] * jitter * h / scale

    monkeypatch.setattr(_edges, "_cubic_zero_near", jittering)
    root = _edges._tail_fit_root(inside, -1.0, 0.0, 4, 16, 0.3 * h, h)
    if counts:
        assert root is not None and abs(root - 0.3 * h) < TOL_EXACT * h
    else:
        assert root is None
