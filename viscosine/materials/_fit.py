"""The Prony fit of a master curve (`fit_prony`) and its report (`FitReport`)."""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from ..checks import bad, real
from ._dma import MasterCurve
from ._series import Maxwell


@dataclass(frozen=True)
class FitReport:
    """How well a fitted Prony series reproduces the data it was fitted to.

    Residuals are relative, ``model/datum - 1``, at the data's frequencies.

    Attributes
    ----------
    window : (float, float)
        The measured frequencies ``(w_min, w_max)``, in rad per time unit of the series (shifted
        with the series by `Maxwell.at_temperature`).
    per_decade : float
        Candidate relaxation times per decade.
    candidates, terms : int
        Relaxation times offered to the fit, and those kept (non-zero amplitude).
    storage_max, storage_rms, loss_max, loss_rms, tan_delta_max, tan_delta_rms : float
        Largest and root-mean-square relative residual of E', E'' and tan δ.
    bound : float
        The largest relative residual on E' and E'' the fit was allowed.
    source : str or None
        The data file, when the curve was read from one.
    modulus_unit : str or None
        The unit of the moduli (``E_r``, ``E_i``) as the data gave it (``"MPa"``), or None
        when the data did not say.
    """

    window: tuple
    per_decade: float
    candidates: int
    terms: int
    storage_max: float
    storage_rms: float
    loss_max: float
    loss_rms: float
    tan_delta_max: float
    tan_delta_rms: float
    bound: float
    source: str | None = None
    modulus_unit: str | None = None

    @property
    def max_residual(self) -> float:
        """The larger of the largest relative residuals of E' and E'' (what `bound` limits)."""
        return max(self.storage_max, self.loss_max)

    def summary(self) -> str:
        """One line: terms, and max/RMS residuals in per cent."""
        return (f"{self.terms} terms ({self.per_decade:g}/decade); relative residual max/RMS: "
                f"E' {100 * self.storage_max:.2f}/{100 * self.storage_rms:.2f} %, "
                f"E'' {100 * self.loss_max:.2f}/{100 * self.loss_rms:.2f} %, "
                f"tan δ {100 * self.tan_delta_max:.2f}/{100 * self.tan_delta_rms:.2f} %")




def _kernels(omega, theta):
    """Storage and loss kernels ``x^2/(1 + x^2)``, ``x/(1 + x^2)`` with ``x = w theta``."""
    x = np.outer(omega, theta)
    return x * x / (1.0 + x * x), x / (1.0 + x * x)


def fit_prony(curve: MasterCurve, *, per_decade: float = 2, extend: float = 1.0,
              max_residual: float = 0.05) -> Maxwell:
    """Fit a generalised Maxwell series to a master curve (non-negative least squares).

    Relaxation times are fixed, log-spaced over ``1/w_max .. 1/w_min`` widened by ``extend``
    decades on each side; ``E_r`` and the ``E_i >= 0`` solve one scipy ``nnls`` problem in
    which each datum's equation is divided by the datum, so E' and E'' are fitted jointly in
    relative terms.  Terms the fit sets to zero are dropped.

    Parameters
    ----------
    curve : MasterCurve
        The data (frequencies in rad per time unit: the series' times come out in that unit).
    per_decade : float
        Relaxation times per decade, >= 0.5.  One per decade leaves a ripple of several per
        cent on E'' for a broad spectrum; two is the default.
    extend : float
        Decades added to the span of times on each side (>= 0).
    max_residual : float
        The largest relative residual on E' or E'' accepted (> 0).

    Returns
    -------
    Maxwell
        With ``fit`` set: a `FitReport` (residuals and the measured window).

    Raises
    ------
    ValueError
        A fit whose largest relative residual exceeds ``max_residual``, or whose relaxed
        modulus comes out zero (the data never reach a rubbery plateau the series can hold).
    """
    from scipy.optimize import nnls

    if not isinstance(curve, MasterCurve):
        raise bad("curve", curve, "a MasterCurve (see read_dma)")
    per_decade = real("per_decade", per_decade, "relaxation times per decade in [0.5, 20]",
                      lambda v: 0.5 <= v <= 20.0)
    extend = real("extend", extend, "decades in [0, 5]", lambda v: 0.0 <= v <= 5.0)
    bound = real("max_residual", max_residual, "a relative residual bound > 0", lambda v: v > 0.0)
    w, e1, e2 = curve.omega, curve.storage, curve.loss
    lo = -math.log10(w[-1]) - extend
    hi = -math.log10(w[0]) + extend
    count = int(math.ceil((hi - lo) * per_decade - 1e-9)) + 1
    theta = np.logspace(lo, hi, count)
    k1, k2 = _kernels(w, theta)
    a = np.zeros((2 * w.size, count + 1))
    a[: w.size, 0] = 1.0 / e1
    a[: w.size, 1:] = k1 / e1[:, None]
    a[w.size:, 1:] = k2 / e2[:, None]
    # columns to unit norm: a positive scaling keeps the constraint and mends the conditioning
    # (amplitudes span the rubbery to the glassy modulus)
    scale = np.linalg.norm(a, axis=0)
    z, _ = nnls(a / scale, np.ones(2 * w.size), maxiter=50 * (count + 1))
    coef = z / scale
    if not coef[0] > 0.0:
        raise bad("curve", curve.source or "MasterCurve", "data that reach a relaxed "
                   "(rubbery) plateau: the fit gives E_r = 0, a fluid, below the lowest "
                   f"frequency {w[0]:.3g}")
    keep = coef[1:] > 0.0
    model = Maxwell(float(coef[0]), tuple(coef[1:][keep].tolist()),
                    tuple(theta[keep].tolist()))
    mod = model.modulus(w)
    r1 = mod.real / e1 - 1.0
    r2 = mod.imag / e2 - 1.0
    r3 = (mod.imag / mod.real) / (e2 / e1) - 1.0
    stats = [(float(np.max(np.abs(r))), float(np.sqrt(np.mean(r * r)))) for r in (r1, r2, r3)]
    report = FitReport(window=curve.window, per_decade=per_decade, candidates=count,
                       terms=int(keep.sum()), storage_max=stats[0][0], storage_rms=stats[0][1],
                       loss_max=stats[1][0], loss_rms=stats[1][1], tan_delta_max=stats[2][0],
                       tan_delta_rms=stats[2][1], bound=bound, source=curve.source,
                       modulus_unit=curve.modulus_unit)
    if report.max_residual > bound:
        raise bad("max_residual", bound, f"a bound the fit meets: the best non-negative "
                   f"Prony series with {per_decade:g} times per decade misses the data by "
                   f"{100 * report.max_residual:.3g} % (E' {100 * report.storage_max:.3g} %, "
                   f"E'' {100 * report.loss_max:.3g} %); more times per decade, or data a "
                   "relaxation spectrum can fit")
    return replace(model, fit=report)


