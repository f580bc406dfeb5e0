"""The field container both roads return, with the geometry of its grid.

A `Fields` is pressure, displacement and gap at points over one period, x/λ ∈ one period of
length 1.  Each point stands for a *cell*: the cells follow one another in the order of the
points and together make the period.  A uniform grid (the default, ``edges=None``) has cells of
width 1/n centred on its points; a non-uniform one (the boundary-element road after a contact
window: fine panels around a small contact, coarse ones elsewhere) carries its cell edges.  The
quadrature is the one the cells imply: a field is taken constant over each cell, so that the
mean over the period is Σ_i width_i f_i and integrals are exact for the BEM's piecewise-constant
panel pressures.  Every mean, integral or norm of a field goes through the methods here, never
through ``np.mean`` of a raw column, which is wrong on a non-uniform grid.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .checks import integer

#: units of the four arrays, by `Fields.units`
UNITS = {
    "conventions": {"x_over_lambda": "x/λ (crest at 0)", "pressure": "σ(1 − ν²)/E0",
                    "displacement": "v/h (into the body, from the mean line of the deformed surface)",
                    "gap": "gap/h (0 in contact)"},
    "SI": {"x_over_lambda": "x/λ (crest at 0)", "pressure": "Pa", "displacement": "m", "gap": "m"},
}
#: the four columns, in their CSV order; a non-uniform grid adds WIDTH
COLUMNS = ("x_over_lambda", "pressure", "displacement", "gap")
WIDTH = "width"
#: the length of one period in x/λ
PERIOD = 1.0
#: a uniform grid: x_j = x_0 + j/n with |Δx·n − 1| below this (also what `comparisons.verify`
#: accepts as a uniform grid)
UNIFORM_SPACING = 1e-6
#: cells must make one period to this (absolute, x/λ), and a point may lie outside its cell by
#: this fraction of the cell's width (round-off of positions written in decimal)
SPAN_TOLERANCE = 1e-9
IN_CELL_TOLERANCE = 1e-6
RESAMPLE_METHODS = ("average", "linear")


def _frozen(a) -> np.ndarray:
    arr = np.array(a, dtype=float, copy=True)
    arr.flags.writeable = False
    return arr


def _edges_from_widths(x, widths):
    """Cell edges from widths: consecutive cells, the first centred on its point."""
    w = np.asarray(widths, dtype=float)
    if w.shape != x.shape:
        raise ValueError(f"widths has shape {w.shape}, the points {x.shape}: one width per point")
    if not np.all(np.isfinite(w)) or not np.all(w > 0.0):
        raise ValueError("widths must be finite and positive (x/λ)")
    return x[0] - 0.5 * w[0] + np.concatenate(([0.0], np.cumsum(w)))


def _check_edges(x, e):
    """ValueError unless e are n + 1 increasing edges over one period with x_i in cell i."""
    if e.shape != (x.size + 1,):
        raise ValueError(f"edges has shape {e.shape}: n + 1 = {x.size + 1} cell edges expected")
    if not np.all(np.isfinite(e)):
        raise ValueError("edges must be finite (x/λ)")
    w = np.diff(e)
    if not np.all(w > 0.0):
        i = int(np.flatnonzero(~(w > 0.0))[0])
        raise ValueError(f"cell {i} has width {w[i]!r}: edges must increase strictly")
    span = float(e[-1] - e[0])
    if not abs(span - PERIOD) <= SPAN_TOLERANCE:
        raise ValueError(f"the cells span {span!r} in x/λ, not one period (1)")
    slack = IN_CELL_TOLERANCE * w + 4.0 * np.finfo(float).eps * (1.0 + np.abs(x))
    out = (x < e[:-1] - slack) | (x > e[1:] + slack)
    if out.any():
        i = int(np.flatnonzero(out)[0])
        raise ValueError(f"point {i} (x/λ = {x[i]!r}) lies outside its cell "
                         f"[{e[i]!r}, {e[i + 1]!r}]: the cells follow the points in order")


@dataclass(frozen=True, init=False)
class Fields:
    """Pressure, surface displacement and gap over one period, in the frame of the indenter,
    with the cells of the grid they are given on.

    Parameters
    ----------
    x_over_lambda, pressure, displacement, gap : array_like
        One value per point (1-D, one length); see Attributes.
    units : str
        ``"conventions"`` (default) or ``"SI"``.
    widths : array_like, optional
        The width of each point's cell (x/λ, positive, summing to one period).  The cells follow
        one another in the order of the points, the first centred on its point.
    edges : array_like, optional
        Instead of ``widths``: the n + 1 cell edges (x/λ, increasing, spanning one period;
        point i in [edges[i], edges[i + 1]]).  Without either, the grid is uniform: cells of
        width 1/n centred on points x_j = x_0 + j/n.

    Attributes
    ----------
    x_over_lambda : ndarray
        Positions x/λ, crest of the indenter at 0, material streaming toward −x.
    pressure : ndarray
        Contact pressure, positive in compression: σ(1 − ν²)/E0, or Pa when ``units == "SI"``.
    displacement : ndarray
        Surface displacement, positive into the body, measured from the mean line of the deformed
        surface: v/h, or m.
    gap : ndarray
        Gap between indenter and surface (0 in contact): gap/h, or m.
    units : str
        ``"conventions"`` (the dimensionless groups above) or ``"SI"``.
    edges : ndarray or None
        The cell edges of a non-uniform grid; None for a uniform one (see `cell_edges`).
    """

    x_over_lambda: np.ndarray
    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    units: str = "conventions"
    edges: np.ndarray | None = None

    def __init__(self, x_over_lambda, pressure, displacement, gap, units="conventions", *,
                 widths=None, edges=None):
        if units not in UNITS:
            raise ValueError(f"units={units!r} is not allowed: one of {sorted(UNITS)}")
        arrays = [_frozen(a) for a in (x_over_lambda, pressure, displacement, gap)]
        if len({a.shape for a in arrays}) != 1 or arrays[0].ndim != 1:
            raise ValueError("x_over_lambda, pressure, displacement and gap must be 1-D arrays "
                             "of one length")
        for n, a in zip(COLUMNS, arrays):
            object.__setattr__(self, n, a)
        object.__setattr__(self, "units", units)
        x = arrays[0]
        e = None
        if widths is not None and edges is not None:
            raise ValueError("widths and edges given: one of them describes the cells")
        if widths is not None:
            if x.size == 0:
                raise ValueError("widths of an empty grid")
            e = _edges_from_widths(x, widths)
        elif edges is not None:
            e = np.array(edges, dtype=float)
        if e is not None:
            _check_edges(x, e)
            e = _frozen(e)
        object.__setattr__(self, "edges", e)

    # ------------------------------------------------------------------ the grid
    @property
    def uniform(self) -> bool:
        """True for a uniform grid (no cell edges carried)."""
        return self.edges is None

    def _check_uniform(self):
        if self.__dict__.get("_uniform_checked"):
            return
        x = self.x_over_lambda
        n = x.size
        if n == 0:
            raise ValueError("no points: an empty grid has no cells")
        if n > 1:
            d = np.diff(x)  # one temporary, in place: 2^24 points are 128 MiB each
            d *= n
            d -= 1.0
            spread = float(np.max(np.abs(d, out=d)))
            if not spread < UNIFORM_SPACING:
                raise ValueError(
                    "the points are not a uniform grid over one period (spacing × n − 1 "
                    f"reaches {spread:.2e}) and carry no cells: give widths= or edges= to "
                    "integrate over them")
        self.__dict__["_uniform_checked"] = True  # the arrays are read-only: once is enough

    @property
    def cell_edges(self) -> np.ndarray:
        """The n + 1 cell edges (x/λ); on a uniform grid x_0 − 1/(2n) + j/n."""
        if self.edges is not None:
            return self.edges
        self._check_uniform()
        n = self.x_over_lambda.size
        return self.x_over_lambda[0] + (np.arange(n + 1) - 0.5) / n

    @property
    def widths(self) -> np.ndarray:
        """The width of each point's cell (x/λ): the quadrature weights of a mean over the
        period; 1/n each on a uniform grid."""
        if self.edges is not None:
            return np.diff(self.edges)
        self._check_uniform()
        n = self.x_over_lambda.size
        return np.full(n, 1.0 / n)

    def _values(self, what) -> np.ndarray:
        if isinstance(what, str):
            if what not in COLUMNS:
                raise ValueError(f"{what!r} is not a field: one of {', '.join(COLUMNS)}")
            return getattr(self, what)
        a = np.asarray(what, dtype=float)
        if a.shape != self.x_over_lambda.shape:
            raise ValueError(f"an array of shape {a.shape} on a grid of {self.x_over_lambda.size} "
                             "points: one value per point")
        return a

    # ------------------------------------------------------------------ quadrature
    def mean(self, what) -> float:
        """Mean over the period of a field (a column name or an array of one value per point).

        Σ_i width_i f_i over the cells (one period has length 1 in x/λ); on a uniform grid the
        plain mean of the values.  The mean of ``"pressure"`` is the load p̃∞.
        """
        v = self._values(what)
        if self.edges is None:
            self._check_uniform()
            return float(np.mean(v))
        return float(np.sum(self.widths * v)) / float(self.edges[-1] - self.edges[0])

    def integral(self, what, lo=None, hi=None) -> float:
        """∫ f d(x/λ) from ``lo`` to ``hi`` (default: over the period), the field constant on
        each cell and periodic (lo ≤ hi, any real bounds; a cell cut by a bound counts its
        part).  Over the period it equals `mean` (the period has length 1)."""
        v = self._values(what)
        if lo is None and hi is None:
            if self.edges is None:
                self._check_uniform()
                return float(np.sum(v)) / v.size
            return float(np.sum(self.widths * v))
        if lo is None or hi is None:
            raise ValueError("give both lo and hi (x/λ), or neither for the whole period")
        lo, hi = float(lo), float(hi)
        if not (np.isfinite(lo) and np.isfinite(hi)) or hi < lo:
            raise ValueError(f"lo={lo!r}, hi={hi!r}: finite bounds with lo ≤ hi")
        return float(np.sum(self._overlaps(np.array([lo, hi]), v)))

    def l2(self, what) -> float:
        """L2 norm over the period, √(Σ_i width_i f_i²) (the root mean square: the period has
        length 1)."""
        v = self._values(what)
        return float(np.sqrt(self.mean(v * v)))

    def linf(self, what) -> float:
        """L∞ norm, max_i |f_i| (the largest value at a point; cells do not change it)."""
        v = self._values(what)
        return float(np.max(np.abs(v))) if v.size else 0.0

    def _overlaps(self, t, v):
        """∫ f over each interval [t_k, t_k+1] of increasing bounds t (any reals; the field
        constant on each cell, periodic): whole periods, and the pieces of the cells below each
        bound folded into the period."""
        e = self.cell_edges
        rel = e - e[0]
        span = float(rel[-1])
        k = np.floor((t - e[0]) / span)
        r = np.clip((t - e[0]) - k * span, 0.0, span)
        cuts = np.unique(np.concatenate((rel, r)))
        mid = 0.5 * (cuts[:-1] + cuts[1:])
        cell = np.clip(np.searchsorted(rel, mid, side="right") - 1, 0, v.size - 1)
        below = np.concatenate(([0.0], np.cumsum(np.diff(cuts) * v[cell])))
        at = below[np.searchsorted(cuts, r, side="left")]
        return np.diff(k) * below[-1] + np.diff(at)

    # ------------------------------------------------------------------ other grids
    def resample(self, n, method="average") -> "Fields":
        """The fields on the uniform grid x_j = j/n − ½ (j = 0 … n − 1) of one period.

        Parameters
        ----------
        n : int
            Points of the new grid (≥ 1).
        method : {"average", "linear"}
            ``"average"`` (default): each new value is the mean of the field over the new cell
            [x_j − 1/(2n), x_j + 1/(2n)], the field constant on each of its own cells
            (conservative: every integral over whole new cells, the load among them, is kept;
            a contact narrower than a new cell is smeared over it).  ``"linear"``: periodic
            linear interpolation between the points (the values at points shared by both grids
            are kept exactly; a contact narrower than the new spacing can fall between points).

        Returns
        -------
        Fields
            Uniform (no edges), in the same units.
        """
        n = integer("n", n, "an integer ≥ 1", lambda v: v >= 1)
        if method not in RESAMPLE_METHODS:
            raise ValueError(f"method={method!r} is not allowed: one of "
                             f"{', '.join(RESAMPLE_METHODS)}")
        X = np.arange(n) / n - 0.5
        if method == "linear":
            cols = [np.interp(X, self.x_over_lambda, getattr(self, c), period=PERIOD)
                    for c in COLUMNS[1:]]
        else:
            t = X[0] + (np.arange(n + 1) - 0.5) / n
            cols = [self._average_onto(t, getattr(self, c)) for c in COLUMNS[1:]]
        return Fields(X, *cols, units=self.units)

    def _average_onto(self, t, v):
        """Cell means of the piecewise-constant v over the consecutive cells [t_j, t_j+1] of one
        period (each new cell the sum of the pieces it holds, over its width)."""
        e = self.cell_edges
        e0 = float(e[0])
        span = float(e[-1] - e[0])
        tw = np.diff(t)
        cuts = np.unique(np.concatenate((e - e0, np.mod(t[:-1] - e0, span))))
        cuts = np.append(cuts[cuts < span], span)
        length = np.diff(cuts)
        mid = 0.5 * (cuts[:-1] + cuts[1:])
        cell = np.clip(np.searchsorted(e - e0, mid, side="right") - 1, 0, v.size - 1)
        target = np.searchsorted(t - t[0], np.mod(mid + e0 - t[0], PERIOD), side="right") - 1
        target = np.clip(target, 0, tw.size - 1)
        return np.bincount(target, weights=length * v[cell], minlength=tw.size) / tw

    # ------------------------------------------------------------------ columns
    def as_dict(self) -> dict:
        """The columns (read-only arrays) keyed by their CSV names: the four fields and, on a
        non-uniform grid, ``width`` (each point's cell, x/λ)."""
        d = {"x_over_lambda": self.x_over_lambda, "pressure": self.pressure,
             "displacement": self.displacement, "gap": self.gap}
        if self.edges is not None:
            d[WIDTH] = self.widths
        return d

    @classmethod
    def from_columns(cls, columns, units="conventions") -> "Fields":
        """A `Fields` from columns keyed like the CSV (a ``width`` column makes the grid
        non-uniform: cells in the order of the rows, the first centred on its point)."""
        missing = [c for c in COLUMNS if c not in columns]
        if missing:
            raise ValueError(f"columns {', '.join(missing)} missing")
        w = columns.get(WIDTH)
        return cls(*(columns[c] for c in COLUMNS), units=units, widths=w)
