"""The field container both roads return (no numerics here)."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: units of the four arrays, by `Fields.units`
UNITS = {
    "conventions": {"x_over_lambda": "x/λ (crest at 0)", "pressure": "σ(1 − ν²)/E0",
                    "displacement": "v/h (into the body, from the mean line of the deformed surface)",
                    "gap": "gap/h (0 in contact)"},
    "SI": {"x_over_lambda": "x/λ (crest at 0)", "pressure": "Pa", "displacement": "m", "gap": "m"},
}


def _frozen(a) -> np.ndarray:
    arr = np.array(a, dtype=float, copy=True)
    arr.flags.writeable = False
    return arr


@dataclass(frozen=True)
class Fields:
    """Pressure, surface displacement and gap over one period, in the frame of the indenter.

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
    """

    x_over_lambda: np.ndarray
    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    units: str = "conventions"

    def __post_init__(self):
        if self.units not in UNITS:
            raise ValueError(f"units={self.units!r} is not allowed: one of {sorted(UNITS)}")
        arrays = [_frozen(getattr(self, n)) for n in ("x_over_lambda", "pressure", "displacement", "gap")]
        if len({a.shape for a in arrays}) != 1 or arrays[0].ndim != 1:
            raise ValueError("x_over_lambda, pressure, displacement and gap must be 1-D arrays of one length")
        for n, a in zip(("x_over_lambda", "pressure", "displacement", "gap"), arrays):
            object.__setattr__(self, n, a)

    def as_dict(self) -> dict:
        """The four columns (as read-only arrays), keyed by their CSV names."""
        return {"x_over_lambda": self.x_over_lambda, "pressure": self.pressure,
                "displacement": self.displacement, "gap": self.gap}
