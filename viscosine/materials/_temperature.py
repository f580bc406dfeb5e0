"""Time–temperature shifts: the WLF equation and tabulated shift factors."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import bad, real, reals, series


@dataclass(frozen=True)
class WLF:
    """Williams–Landel–Ferry shift: ``log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref)``.

    Parameters
    ----------
    C1 : float
        > 0 (dimensionless; 17.44 for the "universal" constants).
    C2 : float
        > 0, in the temperature unit (51.6 K for the "universal" constants).
    T_ref : float
        Reference temperature of the master curve (``a_T = 1``), same unit.

    Notes
    -----
    ``a_T`` multiplies times (relaxation is faster when hot: ``a_T < 1`` above ``T_ref``);
    a reduced frequency is ``w a_T``.  T at or below the pole ``T_ref - C2`` is refused.
    """

    C1: float
    C2: float
    T_ref: float

    def __post_init__(self):
        object.__setattr__(self, "C1", real("C1", self.C1, "a finite C1 > 0", lambda v: v > 0.0))
        object.__setattr__(self, "C2", real("C2", self.C2,
                                            "a finite C2 > 0 (in the temperature unit)",
                                            lambda v: v > 0.0))
        object.__setattr__(self, "T_ref", real("T_ref", self.T_ref,
                                               "a finite reference temperature"))

    def log10_aT(self, T):
        """``log10 a_T`` at T (scalar or array); T must be above ``T_ref - C2``."""
        arr = reals("T", T, "temperatures")
        dt = arr - self.T_ref
        outside = ~(np.isfinite(arr) & (self.C2 + dt > 0.0))
        if outside.any():
            v = float(arr.ravel()[np.flatnonzero(outside.ravel())[0]])
            raise bad("T", v, f"a finite temperature above the WLF pole T_ref - C2 = "
                      f"{self.T_ref - self.C2!r}")
        out = -self.C1 * dt / (self.C2 + dt)
        return float(out) if out.ndim == 0 else out

    def a_T(self, T):
        """Shift factor ``a_T = 10**log_aT(T)``."""
        return 10.0 ** self.log10_aT(T)


@dataclass(frozen=True)
class ShiftTable:
    """Tabulated shift ``log10 a_T(T)``, linear between the points, refused outside them.

    Parameters
    ----------
    T : sequence of float
        Temperatures, strictly increasing, at least 2.
    log_aT : sequence of float
        ``log10 a_T`` at each, strictly decreasing (relaxation is faster when hot).

    Notes
    -----
    Linear interpolation of ``log10 a_T`` keeps the table's monotony and never overshoots.
    """

    T: tuple
    log_aT: tuple

    def __post_init__(self):
        tt = series("T", self.T, "finite temperatures")
        ll = series("log_aT", self.log_aT, "finite values of log10 a_T")
        if len(tt) != len(ll):
            raise bad("log_aT", self.log_aT, f"one value per temperature ({len(tt)})")
        if len(tt) < 2:
            raise bad("T", self.T, "at least 2 temperatures")
        if any(b <= a for a, b in zip(tt, tt[1:])):
            raise bad("T", self.T, "strictly increasing temperatures")
        if any(b >= a for a, b in zip(ll, ll[1:])):
            raise bad("log_aT", self.log_aT, "log10 a_T strictly decreasing with T "
                      "(relaxation is faster when hot)")
        object.__setattr__(self, "T", tt)
        object.__setattr__(self, "log_aT", ll)

    def log10_aT(self, T):
        """``log10 a_T`` at T (scalar or array) inside the table."""
        arr = reals("T", T, "temperatures")
        outside = ~(np.isfinite(arr) & (arr >= self.T[0]) & (arr <= self.T[-1]))
        if outside.any():
            v = float(arr.ravel()[np.flatnonzero(outside.ravel())[0]])
            raise bad("T", v, f"a temperature inside the shift table [{self.T[0]!r}, "
                      f"{self.T[-1]!r}] (no extrapolation)")
        out = np.interp(arr, self.T, self.log_aT)
        return float(out) if np.ndim(out) == 0 else out

    def a_T(self, T):
        """Shift factor ``a_T = 10**log_aT(T)``."""
        return 10.0 ** self.log10_aT(T)


