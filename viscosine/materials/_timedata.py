"""Time-domain data: a relaxation modulus E(t) or a creep compliance J(t), fitted directly.

`read_time_data` reads a table whose header names a time column and either a modulus column
(relaxation: ``E``, ``E(t)``, ``relaxation``, ``modulus``; ``G`` for shear) or a compliance
column (creep: ``J``, ``J(t)``, ``creep``, ``compliance``, ``D(t)``), any order and case, units in
brackets (``time [s]``, ``E [MPa]``, ``J [1/MPa]``)::

    # stress relaxation at 23 degC
    time [s], E [MPa]
    0.001, 1650.2
    ...

`fit_time_data` fits a Prony series by non-negative least squares on relative residuals, with
times fixed and log-spaced (``per_decade`` a decade, from the first time to the last widened by
``extend`` decades), as `fit_prony` does in frequency:

* relaxation: ``E(t) = E_r + sum_i E_i exp(-t/theta_i)``, E_r and E_i >= 0;
* creep: ``J(t) = J_g + sum_k J_k (1 - exp(-t/tau_k))``, J_g = J(0+) and J_k >= 0 (eq. 2.3:
  J0 = J_g + sum J_k), turned exactly into the relaxation form (`Maxwell.from_creep`).

The measured window is the time span: frequencies ``1/t_max .. 1/t_min`` (rad per time unit).
"""
from __future__ import annotations

import math
import time as _time
from dataclasses import dataclass, field, replace

import numpy as np

from ..checks import bad, real
from ._units import poisson
from ._files import _column_name, _data_lines
from ._series import Maxwell

KINDS = ("relaxation", "creep")
TIME_NAMES = ("time", "t", "t_s", "time_s")
MODULUS_NAMES = ("e", "e(t)", "relaxation", "relaxation_modulus", "modulus", "e_relax",
                 "g", "g(t)", "g_relax", "stress_relaxation_modulus")
COMPLIANCE_NAMES = ("j", "j(t)", "creep", "creep_compliance", "compliance", "d(t)", "d")
#: time units to seconds
SECONDS = {"s": 1.0, "sec": 1.0, "ms": 1e-3, "min": 60.0, "h": 3600.0, "hr": 3600.0}
MIN_POINTS = 5


@dataclass(frozen=True, eq=False)
class TimeData:
    """E(t) (``kind="relaxation"``) or J(t) (``"creep"``) samples, times ascending in seconds."""

    t: np.ndarray
    value: np.ndarray
    kind: str
    shear: bool = False
    modulus_unit: str | None = None
    source: str | None = None

    def tensile(self, nu=None) -> "TimeData":
        """These data as E(t): a shear modulus G(t) times 2 (1 + nu), the Poisson ratio ``nu``
        in (-1, 0.5] taken not to relax (E = 2 (1 + nu) G); tensile data as they are (``nu``
        unused)."""
        if not self.shear:
            return self
        nu = poisson(nu, f"the shear modulus G(t) of {self.source or 'TimeData'!r}")
        return replace(self, value=self.value * (2.0 * (1.0 + nu)), shear=False)

    @property
    def window(self):
        """``(1/t_max, 1/t_min)``: the frequencies the data measure, rad/s."""
        return 1.0 / float(self.t[-1]), 1.0 / float(self.t[0])  # noqa: E501


@dataclass(frozen=True)
class TimeFitReport:
    """How a Prony series fitted to E(t) or J(t) meets the data (relative residuals).

    ``window`` (rad per time unit, shifted with the series), ``kind``, ``per_decade``,
    ``candidates``, ``terms``, ``rms``/``max`` (of model/datum - 1), ``source``,
    ``modulus_unit``, ``points``, ``seconds``.
    """

    window: tuple
    kind: str
    per_decade: float
    candidates: int
    terms: int
    rms: float
    max: float
    source: str | None = None
    modulus_unit: str | None = None
    points: int = 0
    seconds: float = field(default=0.0, compare=False)

    @property
    def max_residual(self) -> float:
        return self.max

    def summary(self) -> str:
        what = "E(t)" if self.kind == "relaxation" else "J(t)"
        return (f"{self.terms} terms ({self.per_decade:g}/decade) fitted to {self.points} "
                f"points of {what}; relative residual RMS/max {100 * self.rms:.2g}/"
                f"{100 * self.max:.2g} %")


def _units_of_compliance(unit):
    """``'1/MPa'`` or ``'MPa^-1'`` -> ``'MPa'``; None when not a reciprocal modulus."""
    if unit is None:
        return None
    u = unit.replace(" ", "")
    if u.startswith("1/"):
        return u[2:]
    for tail in ("^-1", "-1", "⁻¹"):
        if u.endswith(tail):
            return u[: -len(tail)]
    return None


def time_header(fields):
    """``(time index, value index, kind, shear)`` when a header names a time column and a
    modulus or compliance column, else None."""
    names = [_column_name(f)[0] for f in fields]
    it = [i for i, n in enumerate(names) if n in TIME_NAMES]
    im = [i for i, n in enumerate(names) if n in MODULUS_NAMES]
    ij = [i for i, n in enumerate(names) if n in COMPLIANCE_NAMES]
    if len(it) != 1 or len(im) + len(ij) != 1:
        return None
    if im:
        return it[0], im[0], "relaxation", names[im[0]].startswith("g")
    return it[0], ij[0], "creep", False


def read_time_data(path) -> TimeData:
    """Read E(t) or J(t) samples (module docstring); ValueError ``time_data='path' ...``."""
    where = str(path)
    rows = _data_lines(path, "time_data")
    found = time_header(rows[0][1]) if rows else None
    if found is None:
        raise bad("time_data", where, "a header naming a time column and one modulus (E, E(t), "
                  "relaxation) or compliance (J, J(t), creep) column")
    it, iv, kind, shear = found
    head = rows[0][1]
    t_unit = _column_name(head[it])[1]
    factor = SECONDS.get((t_unit or "s").strip().lower())
    if factor is None:
        raise bad("time_data", where, f"a time unit s, ms, min or h (got {t_unit!r})")
    v_unit = _column_name(head[iv])[1]
    mod_unit = v_unit if kind == "relaxation" else _units_of_compliance(v_unit)
    t, v = [], []
    for number, f in rows[1:]:
        if len(f) != len(head):
            raise bad("time_data", where, f"{len(head)} fields on every line (line {number} "
                      f"has {len(f)})")
        try:
            a, b = float(f[it]), float(f[iv])
        except ValueError:
            raise bad("time_data", where, f"numbers (line {number})") from None
        if not (math.isfinite(a) and math.isfinite(b) and a > 0.0 and b > 0.0):
            raise bad("time_data", where, f"finite times and values > 0 (line {number})")
        t.append(a * factor)
        v.append(b)
    t, v = np.array(t), np.array(v)
    order = np.argsort(t, kind="stable")
    t, v = t[order], v[order]
    if np.unique(t).size < MIN_POINTS:
        raise bad("time_data", where, f"at least {MIN_POINTS} distinct times (got "
                  f"{np.unique(t).size})")
    return TimeData(t, v, kind, shear, mod_unit, where)


def fit_time_data(data: TimeData, *, per_decade: float = 2.0, extend: float = 1.0) -> Maxwell:
    """A Prony series fitted to E(t) or J(t) (module docstring), with a `TimeFitReport`.

    Raises
    ------
    ValueError
        A fit with no relaxed modulus (E_r = 0: the data show a fluid) or no instantaneous
        compliance (J(0+) = 0).
    """
    from scipy.optimize import nnls
    if not isinstance(data, TimeData):
        raise bad("data", data, "TimeData (see read_time_data)")
    per_decade = real("per_decade", per_decade, "times per decade in [0.5, 20]",
                      lambda v: 0.5 <= v <= 20.0)
    extend = real("extend", extend, "decades in [0, 5]", lambda v: 0.0 <= v <= 5.0)
    t0 = _time.perf_counter()
    t, y = data.t, data.value
    # no times below the first sample: their amplitudes (the glassy modulus) are seen only
    # through exp(-t/theta) of the earliest data, and scatter would set them at will
    lo, hi = math.log10(t[0]), math.log10(t[-1]) + extend
    count = int(math.ceil((hi - lo) * per_decade - 1e-9)) + 1
    times = np.logspace(lo, hi, count)
    decay = np.exp(-np.outer(t, 1.0 / times))
    a = np.empty((t.size, count + 1))
    a[:, 0] = 1.0
    a[:, 1:] = decay if data.kind == "relaxation" else 1.0 - decay
    a /= y[:, None]                         # relative residuals
    scale = np.linalg.norm(a, axis=0)
    scale[scale == 0.0] = 1.0
    z, _ = nnls(a / scale, np.ones(t.size), maxiter=50 * (count + 1))
    coef = z / scale
    keep = coef[1:] > 0.0
    if not coef[0] > 0.0:
        what = ("a relaxed modulus: the fit gives E_r = 0 (a fluid) beyond the last time"
                if data.kind == "relaxation" else
                "an instantaneous compliance: the fit gives J(0+) = 0 before the first time")
        raise bad("time_data", data.source or "TimeData", f"data that fix {what}")
    if data.kind == "relaxation":
        model = Maxwell(float(coef[0]), tuple(coef[1:][keep].tolist()),
                        tuple(times[keep].tolist()))
        fitted = model.relaxation(t)
    else:
        jk, tk = coef[1:][keep], times[keep]
        j0 = float(coef[0] + math.fsum(jk.tolist()))
        model = Maxwell.from_creep(j0, tuple(jk.tolist()), tuple(tk.tolist()))
        fitted = coef[0] + ((1.0 - np.exp(-np.outer(t, 1.0 / tk))) @ jk if jk.size else 0.0)
    r = fitted / y - 1.0
    report = TimeFitReport((1.0 / float(t[-1]), 1.0 / float(t[0])), data.kind, per_decade, count,
                           int(keep.sum()), float(np.sqrt(np.mean(r * r))),
                           float(np.max(np.abs(r))), data.source, data.modulus_unit,
                           int(t.size), _time.perf_counter() - t0)
    return replace(model, fit=report)
