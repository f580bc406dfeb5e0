"""DMA master curves as measured: `MasterCurve`, its data checks, and what the data say about
themselves (duplicates merged, scatter, points where E' falls).

A measured master curve is built from frequency sweeps at several temperatures shifted onto one
another: neighbouring temperature sets overlap, so E' may fall by a few per cent from one point to
the next and two points may share a frequency.  Those are data, not errors: the curve is sorted,
points whose frequencies agree within `MERGE_RTOL` are merged (geometric means), and the rest is
left to the fit, which reports it.  Only what is not data is refused: too few points, values that
are not finite, frequencies or moduli that are not positive.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..checks import bad, reals

#: fewest distinct frequencies of a DMA curve (and of a shift table's pair of columns) accepted
MIN_POINTS = 5
#: frequencies within this relative distance are one point (merged: geometric means)
MERGE_RTOL = 1e-3
#: neighbours on each side of a point in the local fit that estimates the scatter
SCATTER_HALF_WINDOW = 3


def _check_data(omega, storage, loss, where):
    """Refuse what is not data; ``where(j, text)`` names input row j (None: the whole curve)."""
    for name, arr in (("frequency", omega), ("storage", storage), ("loss", loss)):
        wrong = ~np.isfinite(arr)
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, f"finite values ({name} is {float(arr[j])!r})"))
    checks = [
        (omega <= 0.0, lambda j: f"frequencies > 0 (frequency {float(omega[j])!r})"),
        (storage <= 0.0, lambda j: f"a storage modulus > 0 (storage {float(storage[j])!r})"),
        (loss <= 0.0, lambda j: f"a loss modulus > 0: a solid that dissipates "
                                f"(loss {float(loss[j])!r})"),
    ]
    for wrong, text in checks:
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, text(j)))


def _merge(omega, storage, loss):
    """Sort by frequency and merge runs of frequencies within `MERGE_RTOL` of the run's first.

    Returns ``(omega, storage, loss, merged)``, ``merged`` a tuple of ``(frequency, points,
    storage spread, loss spread)`` per merged run (spread: largest over smallest value - 1).
    """
    order = np.argsort(omega, kind="stable")
    w, s, lo = omega[order], storage[order], loss[order]
    groups, start = [], 0
    for j in range(1, w.size + 1):
        if j == w.size or w[j] > w[start] * (1.0 + MERGE_RTOL):
            groups.append((start, j))
            start = j
    if len(groups) == w.size:
        return w, s, lo, ()
    out_w, out_s, out_l, merged = [], [], [], []
    for a, b in groups:
        gw, gs, gl = (np.exp(np.mean(np.log(v[a:b]))) for v in (w, s, lo))
        out_w.append(gw)
        out_s.append(gs)
        out_l.append(gl)
        if b - a > 1:
            merged.append((float(gw), b - a, float(s[a:b].max() / s[a:b].min() - 1.0),
                           float(lo[a:b].max() / lo[a:b].min() - 1.0)))
    return np.array(out_w), np.array(out_s), np.array(out_l), tuple(merged)


def local_scatter(x, y):
    """Relative scatter of ``exp(y)`` about a smooth curve: a robust standard deviation of the
    leave-one-out residuals of a local quadratic in ``x`` through the `SCATTER_HALF_WINDOW`
    neighbours on each side, each residual divided by ``sqrt(1 + leverage)``.

    For smooth data it measures the curvature the quadratic misses (a floor, ~1e-5 for a
    master curve sampled at 9 points per decade); for measured data, the scatter.  None with
    fewer than 7 points.
    """
    n = x.size
    m = SCATTER_HALF_WINDOW
    if n < 2 * m + 1:
        return None
    res = np.empty(n)
    for i in range(n):
        a = min(max(0, i - m), n - 2 * m - 1)
        idx = [j for j in range(a, a + 2 * m + 1) if j != i]
        xc = x[idx] - x[i]
        v = np.vander(xc, 3)
        coef, *_ = np.linalg.lstsq(v, y[idx], rcond=None)
        g = np.linalg.pinv(v.T @ v)
        lev = g[2, 2]                      # variance factor of the prediction at xc = 0
        res[i] = (y[i] - coef[2]) / math.sqrt(1.0 + lev)
    return float(1.4826 * np.median(np.abs(res - np.median(res))))


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """A DMA master curve in tensile form: ``E'(w)``, ``E''(w)`` at a reference temperature.

    Parameters
    ----------
    omega : array_like
        Angular frequencies, > 0, in rad per time unit, in any order: the curve is sorted, and
        points within a relative `MERGE_RTOL` of one another (two temperature sets on one
        frequency) are merged into their geometric mean (listed in ``merged``).
    storage, loss : array_like
        ``E'`` and ``E''`` (> 0), in any one modulus unit.
    source : str, optional
        Where the data came from (a file name), for provenance.
    modulus_unit : str, optional
        The unit of ``storage`` and ``loss`` (``"MPa"``), when known; see `PASCALS`.
    frequency_unit : {"rad/s", "Hz"}, optional
        The unit the data gave their frequencies in, for reports in the user's own numbers
        (``omega`` is always angular).
    notes : tuple of str
        What the reader did to the data (sorted, a units row, a column ignored...).
    shear_nu : float, optional
        The Poisson ratio ν the data's shear moduli were turned into these tensile ones with
        (E = 2 (1 + ν) G, `read_dma`); None for data measured in tension.

    Attributes
    ----------
    merged : tuple
        ``(frequency, points, storage spread, loss spread)`` of each merged run.
    points : int
        Rows given (before merging).

    Raises
    ------
    ValueError
        What is not data: fewer than `MIN_POINTS` distinct frequencies, non-finite or
        non-positive values, arrays of different sizes.  A storage modulus that falls or a loss
        that does not match it (Kramers-Kronig) is data: `fit_prony` reports it.
    """

    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    source: str | None = None
    modulus_unit: str | None = None
    frequency_unit: str | None = None
    notes: tuple = ()
    shear_nu: float | None = None

    def __post_init__(self):
        arrays = {}
        for name in ("omega", "storage", "loss"):
            arrays[name] = reals(name, getattr(self, name), "a 1-D sequence of numbers").ravel()
        sizes = [a.size for a in arrays.values()]
        if len(set(sizes)) != 1:
            raise bad("storage", self.storage, "as many values as omega and loss (sizes of "
                      f"omega, storage, loss: {sizes})")
        if self.frequency_unit not in (None, "rad/s", "Hz"):
            raise bad("frequency_unit", self.frequency_unit, "'rad/s', 'Hz' or None")

        def where(j, text):
            if j is None:
                return str(bad("omega", self.omega, text))
            return f"omega[{j}]={float(arrays['omega'][j])!r} is not allowed: {text}"
        _check_data(arrays["omega"], arrays["storage"], arrays["loss"], where)
        w, s, lo, merged = _merge(arrays["omega"], arrays["storage"], arrays["loss"])
        if w.size < MIN_POINTS:
            raise ValueError(where(None, f"at least {MIN_POINTS} points (got {w.size} distinct "
                                         "frequencies)"))
        for name, arr in (("omega", w), ("storage", s), ("loss", lo)):
            arr.flags.writeable = False
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "merged", merged)
        object.__setattr__(self, "points", sizes[0])
        object.__setattr__(self, "notes", tuple(self.notes))

    @property
    def tan_delta(self) -> np.ndarray:
        """Loss tangent ``E''/E'``."""
        return self.loss / self.storage

    @property
    def window(self) -> tuple:
        """``(w_min, w_max)``: the measured frequencies."""
        return float(self.omega[0]), float(self.omega[-1])

    @property
    def drops(self) -> tuple:
        """``(count, largest)``: points where E' falls from the previous one, and the largest
        relative fall (0.0 when none).  Every relaxation mode stiffens with frequency, so a fall
        is scatter between temperature sets (or columns exchanged, when large)."""
        ratio = self.storage[1:] / self.storage[:-1]
        fall = ratio < 1.0
        return int(fall.sum()), float(1.0 - ratio.min()) if fall.any() else 0.0

    def scatter(self) -> tuple:
        """``(E', E'')`` relative scatter estimated from the data alone (`local_scatter` of
        log E' and log E'' against log w); None for a curve of fewer than 7 points."""
        x = np.log10(self.omega)
        return local_scatter(x, np.log(self.storage)), local_scatter(x, np.log(self.loss))

    def in_unit(self, omega):
        """Angular frequencies in the data's own frequency unit (Hz: divided by 2 pi)."""
        w = np.asarray(omega, dtype=float)
        return w / (2.0 * math.pi) if self.frequency_unit == "Hz" else w

    @property
    def units(self) -> tuple:
        """``(frequency unit, modulus unit)`` to print the user's own numbers with."""
        return (self.frequency_unit or "rad/s"), (self.modulus_unit or "")
