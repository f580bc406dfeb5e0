"""Contact window (light loads, adaptive mesh, load control, the sinusoid).

Once a periodic grid has located a single patch narrower than 1/64 of the period, the refinement
goes on in a window of about six patch widths around it, a block of panels of a periodic grid too
fine to be made (up to 2^50 panels per period).  The operator there is the Toeplitz block of the
periodic one, with the same exact coefficients (``influence_coefficients_nd(..., span)``), and
the pressure is zero outside; heights and the separation are measured from the crest, so that
gaps of the size of Delta keep their digits.  A window whose contact reaches its ends, or that
does not meet the target, gives no answer: the periodic grids go on.
"""
from __future__ import annotations

import math

import numpy as np

from ._estimate import ESTIMATE_SAFETY, MIN_PATCH_PANELS, _estimate, _level_scalars, _met, \
    _unresolved_memory
from ._grid import _solve_one
from ._influence import influence_coefficients_nd
from ._inputs import Prony, Sinusoid
from ._operator import WindowOperator
from ._result import CONVERGED


#: a single patch of at most this fraction of the period hands over to a contact window (its
#: grid is then at least 2^21/(6/64) = 2.2e7 panels per period, finer than the periodic cap;
#: and a stiff material's pressure relaxation layer, which the periodic grids resolve last, gets
#: tens of panels)
WINDOW_MAX_FRACTION = 1.0 / 64.0
#: panels of the first window level, and the most a window gets
WINDOW_START_PANELS = 1024
WINDOW_MAX_PANELS = 2 ** 21
#: the window spans at most this many (at least half as many) patch widths
WINDOW_SPAN = 6.0
#: the finest virtual grid of a window (positions j/nodes exact; panel values finite up to 2^52)
WINDOW_MAX_NODES = 2 ** 50


class _WindowGrid:
    """A contact window: panels ``first .. first + count - 1`` of a grid of ``nodes`` panels per
    period that is never made (light loads: a contact of a few panels of the largest periodic
    grid spans thousands of these).  The operator is the Toeplitz block of the periodic one
    (exact coefficients, :class:`WindowOperator`); the pressure is zero off the window, whose
    ends must stay free.  Heights are measured from the crest, ``k y - h k = -2 h k sin^2(pi
    X)``, and the separation likewise (``s = h k + s_window``), so that gaps and Delta, whose
    size is that of the window's drop, not of h, keep their digits.  The sinusoid only.
    """

    window = True
    layer = None  # the half-space only: a layer is not handed to a window

    def __init__(self, profile, material: Prony, speed: float, nodes: int, first: int,
                 count: int):
        self.n = count
        self.nodes = nodes
        self.first = first
        self.profile, self.material, self.speed = profile, material, speed
        self.h = 1.0 / nodes
        #: the operator's pieces, kept for the friction (elastic, unshifted memory columns)
        self.columns = {}
        self.op = WindowOperator(influence_coefficients_nd(
            material.j_plus, material.terms, speed, nodes, (-count, 2 * count + 1),
            self.columns), _window_preconditioner(material, speed, count, nodes))
        #: the grid whose panels decide the friction's form (the window's first: one form for
        #: all the grids whose differences make the estimate)
        self.form_nodes = nodes
        self.amp = float(profile.amplitude)
        self.y = -2.0 * self.amp * np.sin(np.pi * self.x) ** 2
        self.s_offset = self.amp
        self.scale = float(-self.y.min())

    @property
    def x(self):
        """Panel centres X = (first + j)/nodes - 1/2 (exact: integers below 2^53)."""
        return (self.first + np.arange(self.n)) / self.nodes - 0.5

    def extended(self, margin: int) -> "_WindowGrid":
        """The same grid's window with `margin` more panels at each end (the gaps just beyond
        the window, where no pressure is, for the validity gate and the fields)."""
        return _WindowGrid(self.profile, self.material, self.speed, self.nodes,
                           self.first - margin, self.n + 2 * margin)


def _window_preconditioner(material: Prony, speed: float, count: int, nodes: int):
    """Symbol of the preconditioner of a window of `count` panels: the periodic operator of
    period Lambda = 2 count/nodes (twice the window) on 2 count panels, ``Lambda (2/k) J*(k /
    Lambda) sinc(pi k/(2 count))`` for mode k (the symbol of the periodic operator, lengths
    scaled by Lambda).  It has the window's singularity and memory on scales below the window;
    what differs (a constant, which the separation takes, and smooth low-rank parts) costs
    GMRES a few steps.  The truncated kernel's own circulant, by contrast, carries the jump of a
    long memory at its wrap: for E_inf/E0 = 1000 its inverse left GMRES stagnating.  Mode 0
    takes mode 1's value (any nonzero value serves)."""
    period = 2.0 * count / nodes
    k = np.arange(count + 1, dtype=float)
    k[0] = 1.0
    return period * (2.0 / k) * material.jstar(k / period, speed) * np.sinc(k / (2.0 * count))


def _window_wanted(load, profile, values):
    """Whether a converged periodic grid hands over to a contact window: load control, the
    sinusoid, one patch of at most WINDOW_MAX_FRACTION of the period, located to within a few
    panels (at least MIN_PATCH_PANELS of them)."""
    return (load is not None and isinstance(profile, Sinusoid) and values["npatch"] == 1
            and values["contact_fraction"] <= WINDOW_MAX_FRACTION
            and values["min_panels"] >= MIN_PATCH_PANELS)


def _window_refine(res, pgrid, profile, material, speed, load, rtol, tol, max_outer,
                   restart, max_inner):
    """Refine a contact window until its estimate meets rtol (light loads).

    The window is centred on the patch of the periodic grid ``pgrid`` and spans
    WINDOW_SPAN (at least half that) times its width: panels ``first .. first + n - 1`` of a
    virtual grid of ``nodes = 2^k`` panels per period, with n = WINDOW_START_PANELS, 2n, ...
    up to WINDOW_MAX_PANELS (the same interval on every level, ``nodes`` doubling with n).
    Each level starts from the one before (the first from ``pgrid``); the estimate is that of
    the periodic grids (:func:`_estimate`) on the window's levels.  Returns a dict: ``reached``
    (the target met on a converged window whose contact keeps off its ends), ``res``, ``grid``,
    ``estimate``, ``levels`` (nodes per period, active-set steps, inner iterations, status)
    and ``summary`` (for the diagnostics).
    """
    patch = res["patches"][0]
    width = patch.width
    centre = 0.5 * (patch.trailing_edge + patch.leading_edge)
    n = WINDOW_START_PANELS
    nodes = 1 << max(0, math.ceil(math.log2(n / (WINDOW_SPAN * width))))
    first = int(round((centre + 0.5) * nodes - 0.5 * n))
    start = (res, pgrid)
    scalars, levels = [], []
    out = {"reached": False, "res": None, "grid": None, "estimate": None, "levels": levels}
    note = "not converged"
    grid = None
    finest = nodes * (WINDOW_MAX_PANELS // n)
    if finest > WINDOW_MAX_NODES or \
            ESTIMATE_SAFETY * _unresolved_memory(material, speed, finest,
                                                WINDOW_MAX_PANELS) > rtol:
        # the edge shift of the memory lengths the finest window grid leaves unresolved is
        # above the target on its own (a speed near 0): the periodic grids go on
        n = 2 * WINDOW_MAX_PANELS
        note = "not tried: a memory length stays unresolved on the finest window grid"
    while n <= WINDOW_MAX_PANELS and nodes <= WINDOW_MAX_NODES:
        grid = _WindowGrid(profile, material, speed, nodes, first, n)
        grid.coarse = pgrid
        if levels:
            grid.form_nodes = levels[0][0]  # one friction form per window
        wres = _solve_one(grid, load, None, [start], tol, max_outer, restart, max_inner)
        levels.append((nodes, wres["nit"], tuple(wres["inner"]), wres["status"]))
        if wres["status"] != CONVERGED:
            note = wres["message"]
            break
        values = _level_scalars(wres, grid, profile, material, speed, grid.amp)
        if values["npatch"] != 1:
            note = f"{values['npatch']} patches in the window"
            break
        scalars.append((nodes, values))
        estimate, reason, _ = _estimate(scalars, material, speed)
        out.update(res=wres, grid=grid, estimate=estimate)
        note = reason or "estimate above rtol"
        if reason is None and _met(estimate, values, rtol):
            out["reached"] = True
            note = "target met"
            break
        start = (wres, grid)
        n, nodes, first = 2 * n, 2 * nodes, 2 * first
    ends = grid.x[[0, -1]] if grid is not None else (None, None)
    out["summary"] = {"from_x_over_lambda": None if grid is None else float(ends[0]),
                      "to_x_over_lambda": None if grid is None else float(ends[1]),
                      "panels": 0 if grid is None else grid.n, "coarse_nodes": pgrid.n,
                      "outcome": note, "levels": [list(lv) for lv in levels]}
    return out

