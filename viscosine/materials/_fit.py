"""The Prony fit of a measured master curve (`fit_prony`) and its report (`FitReport`).

The fit takes a curve as measured and says how well it did: the scatter the data show, the
residuals per decade and the worst points, how far E'' is from the loss E' implies
(Kramers-Kronig), and how the number of terms was chosen.  It refuses nothing that is data.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field, replace

import numpy as np

from ..checks import bad, real
from ._dma import MasterCurve
from ._series import Maxwell

#: relaxation times per decade the held-out choice tries
PER_DECADE_CHOICES = (1.0, 1.5, 2.0, 3.0, 4.0, 6.0)
#: interleaved folds of the held-out choice (point i is held out in fold i % FOLDS)
FOLDS = 5
#: the fewest times per decade whose held-out residual is within this fraction of the best
PARSIMONY = 0.05
#: ... or below this relative residual (0.1 %: finer than any DMA measurement)
RESOLUTION = 1e-3
#: times per decade of the E'-only series behind the Kramers-Kronig figure
KK_PER_DECADE = 4.0
#: points listed in the report's worst points, for E' and for E''
WORST = 3
#: decades at each end of the window left out of the Kramers-Kronig figure: E'' there depends
#: on the spectrum outside the data, which E' alone does not fix
KK_EDGE = 1.0
#: fractions of the lowest measured E' tried, largest first, as the relaxed modulus of a fluid
FLUID_FLOORS = (1.0, 0.5, 0.25, 0.1, 0.03, 0.01)


@dataclass(frozen=True)
class FitReport:
    """How well a fitted Prony series reproduces the data it was fitted to.

    Residuals are relative, ``model/datum - 1``, at the data's frequencies (after merging).

    Attributes
    ----------
    window : (float, float)
        The measured frequencies ``(w_min, w_max)``, in rad per time unit of the series (shifted
        with the series by `Maxwell.at_temperature`).
    per_decade : float
        Candidate relaxation times per decade (given, or chosen: ``chosen_by``).
    candidates, terms : int
        Relaxation times offered to the fit, and those kept (non-zero amplitude).
    storage_max, storage_rms, loss_max, loss_rms, tan_delta_max, tan_delta_rms : float
        Largest and root-mean-square relative residual of E', E'' and tan δ.
    bound : float or None
        The largest relative residual on E' and E'' the fit was allowed (None: no bound).
    source : str or None
        The data file, when the curve was read from one.
    modulus_unit : str or None
        The unit of the moduli (``E_r``, ``E_i``) as the data gave it (``"MPa"``), or None.
    frequency_unit : str or None
        The unit the data gave their frequencies in (reports use it).
    loss_weight : float
        Weight of the E'' residuals against E' in the least squares (1: equal).
    chosen_by : str
        ``"given"`` (``per_decade`` passed) or ``"held-out"`` (the fewest times per decade whose
        held-out residual is within `PARSIMONY` of the best or below `RESOLUTION`; ``held_out``
        lists them).
    held_out : tuple of (float, float)
        ``(per_decade, held-out rms relative residual)`` of each choice tried.
    scatter : (float, float)
        Relative scatter of E' and E'' estimated from the data alone (`MasterCurve.scatter`;
        None for fewer than 7 points).
    kk : tuple of (float, float)
        ``(log10 frequency at the decade's start, median of measured E'' over the E'' implied by
        E')`` per decade, in the data's frequency unit; 1 for Kramers-Kronig-consistent data.
        The implied E'' is that of the series fitted to E' alone (`KK_PER_DECADE` times per
        decade); the outer `KK_EDGE` decades of the window are left out (NaN in ``decades``).
    kk_range : (float, float)
        Smallest and largest of the per-decade ratios (None when the window is too short to
        have decades away from its ends).
    decades : tuple of dict
        Per decade of frequency (data's unit): ``decade`` (log10 of its start), ``points``,
        ``storage_rms``, ``storage_max``, ``loss_rms``, ``loss_max``, ``kk``.
    worst : tuple of dict
        The `WORST` largest residuals of E' and of E'': ``modulus`` ("E'" or "E''"),
        ``frequency`` (data's unit), ``datum``, ``fit`` (data's modulus unit), ``residual``.
    points, merged : int
        Rows given, and rows merged into others (duplicate frequencies).
    drops : (int, float)
        Points where E' falls from its neighbour below, and the largest fall (relative).
    relaxed_floor : float or None
        Set when the unconstrained fit had no relaxed modulus (a fluid): the floor E_r was
        given (the lowest measured E' times the largest of `FLUID_FLOORS` that costs the fit
        less than `PARSIMONY` in residual norm).
    warnings : tuple of str
        What the user should know about the data or the fit.
    seconds : float
        Time of the fit (not compared).
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
    bound: float | None = None
    source: str | None = None
    modulus_unit: str | None = None
    frequency_unit: str | None = None
    loss_weight: float = 1.0
    chosen_by: str = "given"
    held_out: tuple = ()
    scatter: tuple = (None, None)
    kk: tuple = ()
    kk_range: tuple = (None, None)
    decades: tuple = ()
    worst: tuple = ()
    points: int = 0
    merged: int = 0
    drops: tuple = (0, 0.0)
    relaxed_floor: float | None = None
    warnings: tuple = ()
    seconds: float = field(default=0.0, compare=False)

    @property
    def max_residual(self) -> float:
        """The larger of the largest relative residuals of E' and E'' (what `bound` limits)."""
        return max(self.storage_max, self.loss_max)

    def summary(self) -> str:
        """One line: terms, residuals, scatter and the Kramers-Kronig figure, in per cent."""
        p = lambda v: "n/a" if v is None else f"{100 * v:.2g}"  # noqa: E731
        kk = self.kk_range
        kk_text = "n/a" if kk[0] is None else f"{kk[0]:.3g}..{kk[1]:.3g}"
        return (f"{self.terms} terms ({self.per_decade:g}/decade, {self.chosen_by}); relative "
                f"residual RMS/max: E' {p(self.storage_rms)}/{p(self.storage_max)} %, "
                f"E'' {p(self.loss_rms)}/{p(self.loss_max)} %; data scatter E' "
                f"{p(self.scatter[0])} %, E'' {p(self.scatter[1])} %; measured E''/E'' implied "
                f"by E' {kk_text}")

    def table(self) -> str:
        """The per-decade residuals, the worst points and the warnings, as lines of text."""
        fu, mu = self.frequency_unit or "rad/s", self.modulus_unit or "data unit"
        lines = [self.summary(),
                 f"decade [{fu}]  points  E' rms/max %  E'' rms/max %  E''/E''(E')"]
        for d in self.decades:
            lines.append(f"1e{d['decade']:+d}  {d['points']:6d}  {100 * d['storage_rms']:5.2f}/"
                         f"{100 * d['storage_max']:5.2f}   {100 * d['loss_rms']:5.2f}/"
                         f"{100 * d['loss_max']:6.2f}   "
                         + ("n/a" if d["kk"] is None else f"{d['kk']:.3g}"))
        for p in self.worst:
            lines.append(f"worst {p['modulus']}: {p['frequency']:.4g} {fu}: datum "
                         f"{p['datum']:.4g}, fit {p['fit']:.4g} {mu} ({100 * p['residual']:+.2f} %)")
        lines += [f"warning: {w}" for w in self.warnings]
        return "\n".join(lines)


def _kernels(omega, theta):
    """Storage and loss kernels ``x^2/(1 + x^2)``, ``x/(1 + x^2)`` with ``x = w theta``."""
    x = np.outer(omega, theta)
    return x * x / (1.0 + x * x), x / (1.0 + x * x)


def _density(w):
    """Weight of each point: its share of log frequency (half the gaps to its neighbours),
    capped at 3 times the median and normalised to mean 1, so that a decade sampled twice (two
    overlapping temperature sets) counts as much as a decade sampled once."""
    g = np.diff(np.log10(w))
    d = 0.5 * (np.concatenate([g[:1], g]) + np.concatenate([g, g[-1:]]))
    d = np.minimum(d, 3.0 * np.median(d))
    return d / d.mean()


def _times(w, per_decade, extend):
    lo = -math.log10(w[-1]) - extend
    hi = -math.log10(w[0]) + extend
    count = int(math.ceil((hi - lo) * per_decade - 1e-9)) + 1
    return np.logspace(lo, hi, count)


def _solve(w, e1, e2, theta, rw1, rw2, floor=0.0):
    """Non-negative least squares: ``E_r >= floor`` and ``E_i >= 0`` with E' rows weighted by
    ``rw1/E'`` and E'' rows by ``rw2/E''``; returns ``(E_r, E_i, residual norm)``."""
    from scipy.optimize import nnls

    k1, k2 = _kernels(w, theta)
    n, count = w.size, theta.size
    a = np.zeros((2 * n, count + 1))
    a[:n, 0] = rw1 / e1
    a[:n, 1:] = k1 * (rw1 / e1)[:, None]
    a[n:, 1:] = k2 * (rw2 / e2)[:, None]
    b = np.concatenate([rw1 * (1.0 - floor / e1), rw2])
    keep = np.any(a != 0.0, axis=1)          # rows of weight 0 (loss_weight 0) say nothing
    a, b = a[keep], b[keep]
    # columns to unit norm: a positive scaling keeps the constraint and mends the conditioning
    # (amplitudes span the rubbery to the glassy modulus)
    scale = np.linalg.norm(a, axis=0)
    scale[scale == 0.0] = 1.0
    z, rnorm = nnls(a / scale, b, maxiter=50 * (count + 1))
    coef = z / scale
    return floor + coef[0], coef[1:], rnorm


def _held_out(w, e1, e2, d, loss_weight, per_decade, extend):
    """RMS relative residual of the points of each fold predicted by a fit to the others."""
    num = den = 0.0
    idx = np.arange(w.size)
    for k in range(FOLDS):
        test = idx % FOLDS == k
        train = ~test
        if not test.any() or train.sum() < 3:
            continue
        tw = w[train]
        theta = _times(tw, per_decade, extend)
        rw = np.sqrt(d[train])
        e_r, amp, _ = _solve(tw, e1[train], e2[train], theta, rw, rw * math.sqrt(loss_weight))
        k1, k2 = _kernels(w[test], theta)
        r1 = (e_r + k1 @ amp) / e1[test] - 1.0
        r2 = (k2 @ amp) / e2[test] - 1.0
        num += float(np.sum(d[test] * (r1 * r1 + loss_weight * r2 * r2)))
        den += float(np.sum(d[test])) * (1.0 + loss_weight)
    return math.sqrt(num / den)


def _kk_ratio(w, e1, e2, d):
    """Measured E'' over the E'' of the series fitted to E' alone, at each point (NaN in the
    outer `KK_EDGE` decades).  Its times stay inside the window: E' cannot tell a time
    outside it from E_r (slower) or from nothing (faster), while E'' would."""
    theta = _times(w, KK_PER_DECADE, 0.0)
    e_r, amp, _ = _solve(w, e1, e2, theta, np.sqrt(d), np.zeros_like(d))
    implied = _kernels(w, theta)[1] @ amp
    x = np.log10(w)
    inner = (x >= x[0] + KK_EDGE) & (x <= x[-1] - KK_EDGE)
    ok = inner & (implied > 0.0)
    return np.where(ok, e2 / np.where(ok, implied, 1.0), np.nan)


def _per_decade_table(curve, r1, r2, kk):
    f = curve.in_unit(curve.omega)
    dec = np.floor(np.log10(f) + 1e-12).astype(int)
    rows, kks = [], []
    for k in np.unique(dec):
        m = dec == k
        inner = kk[m][np.isfinite(kk[m])]
        ratio = float(np.median(inner)) if inner.size else None
        if inner.size:
            kks.append((float(k), ratio))
        rows.append({"decade": int(k), "points": int(m.sum()),
                     "storage_rms": float(np.sqrt(np.mean(r1[m] ** 2))),
                     "storage_max": float(np.max(np.abs(r1[m]))),
                     "loss_rms": float(np.sqrt(np.mean(r2[m] ** 2))),
                     "loss_max": float(np.max(np.abs(r2[m]))), "kk": ratio})
    return tuple(rows), tuple(kks)


def _worst(curve, mod, r1, r2):
    f = curve.in_unit(curve.omega)
    out = []
    for name, r, datum, fit in (("E'", r1, curve.storage, mod.real),
                                ("E''", r2, curve.loss, mod.imag)):
        for j in np.argsort(-np.abs(r), kind="stable")[:WORST]:
            out.append({"modulus": name, "frequency": float(f[j]), "datum": float(datum[j]),
                        "fit": float(fit[j]), "residual": float(r[j])})
    return tuple(out)


def _warnings(curve, report_kk, scatter, floor, r1, r2):
    out = []
    fu, mu = curve.units
    count, fall = curve.drops
    if count:
        out.append(f"E' falls between neighbouring points {count} times, by up to "
                   f"{100 * fall:.3g} %: read as scatter between overlapping temperature sets (a "
                   "fall of tens of per cent means columns exchanged)")
    if curve.merged:
        spread = max(max(m[2], m[3]) for m in curve.merged)
        out.append(f"{len(curve.merged)} frequencies given more than once were merged "
                   f"(geometric mean; the values differed by up to {100 * spread:.3g} %)")
    lo, hi = report_kk
    if lo is not None and (lo < 0.9 or hi > 1.1):
        out.append(f"E'' is not the loss E' implies (Kramers-Kronig): measured/implied "
                   f"{lo:.3g}..{hi:.3g} per decade; the fit weighs E'' against E' "
                   "(loss_weight) and misses both")
    if floor is not None:
        out.append(f"the best fit has no relaxed modulus (a fluid below the data); E_r is "
                   f"floored at {floor:.4g} {mu} ({floor / curve.storage.min():.2g} x the "
                   "lowest measured E'): below the data the modulus is an extrapolation")
    s = max([v for v in scatter if v is not None] + [0.0])
    worst = max(float(np.max(np.abs(r1))), float(np.max(np.abs(r2))))
    if worst > max(0.05, 5.0 * s) and not out:
        out.append(f"the fit misses a point by {100 * worst:.3g} %, more than 5 times the "
                   f"data's scatter ({100 * s:.2g} %)")
    return tuple(out)


def _floored(w, e1, e2, theta, rw1, rw2, rnorm):
    """The fit with the largest relaxed modulus among `FLUID_FLOORS` times the lowest measured
    E' whose residual norm is within `PARSIMONY` of the unconstrained one (else the smallest)."""
    for share in FLUID_FLOORS:
        floor = share * float(e1.min())
        e_r, amp, r = _solve(w, e1, e2, theta, rw1, rw2, floor=floor)
        if r <= rnorm * (1.0 + PARSIMONY) or share == FLUID_FLOORS[-1]:
            return e_r, amp, floor


def fit_prony(curve: MasterCurve, *, per_decade: float | None = None, extend: float = 1.0,
              max_residual: float | None = None, loss_weight: float = 1.0) -> Maxwell:
    """Fit a generalised Maxwell series to a measured master curve (non-negative least squares).

    Relaxation times are fixed, log-spaced over ``1/w_max .. 1/w_min`` widened by ``extend``
    decades on each side; ``E_r`` and the ``E_i >= 0`` solve one scipy ``nnls`` problem whose
    residuals are relative (each datum's equation divided by the datum), weighted by each
    point's share of log frequency (a decade measured twice counts once) and by
    ``loss_weight`` on E''.  Terms the fit sets to zero are dropped.

    Parameters
    ----------
    curve : MasterCurve
        The data (frequencies in rad per time unit: the series' times come out in that unit).
    per_decade : float, optional
        Relaxation times per decade, in [0.5, 20].  Default: chosen from `PER_DECADE_CHOICES`
        by held-out residual (`FOLDS` interleaved folds; the fewest within `PARSIMONY` of the
        best, or below `RESOLUTION`), reported in ``fit.held_out``.
    extend : float
        Decades added to the span of times on each side (>= 0).
    max_residual : float, optional
        A bound on the largest relative residual of E' or E'' (> 0); a fit beyond it is
        refused.  Default None: no bound, the residuals are reported.
    loss_weight : float
        Weight of the E'' residuals against the E' residuals, >= 0 (1: equal; the friction of
        a sliding contact is set by E'', its contact by E').  It matters only when the data are
        not Kramers-Kronig consistent, where no series meets both.

    Returns
    -------
    Maxwell
        With ``fit`` set: a `FitReport` (residuals per decade, worst points, scatter,
        Kramers-Kronig figure, measured window).  When the best series has no relaxed modulus
        (a fluid: E' still falling at the lowest frequency), E_r is floored and the fit
        repeated (``fit.relaxed_floor``, a warning): at the lowest measured E' when that costs
        the fit less than `PARSIMONY` in residual norm, else at the largest of `FLUID_FLOORS`
        times it that does.  The BEM road needs a solid, and below the data any E_r is an
        extrapolation.

    Raises
    ------
    ValueError
        Bad options; with ``max_residual``, a fit that misses it (the message gives the worst
        point in the data's units and the Kramers-Kronig figure).
    """
    t0 = time.perf_counter()
    if not isinstance(curve, MasterCurve):
        raise bad("curve", curve, "a MasterCurve (see read_dma)")
    if per_decade is not None:
        per_decade = real("per_decade", per_decade, "relaxation times per decade in [0.5, 20], "
                          "or None (chosen by held-out residual)", lambda v: 0.5 <= v <= 20.0)
    extend = real("extend", extend, "decades in [0, 5]", lambda v: 0.0 <= v <= 5.0)
    bound = None if max_residual is None else real(
        "max_residual", max_residual, "a relative residual bound > 0, or None", lambda v: v > 0.0)
    lw = real("loss_weight", loss_weight, "a weight >= 0 of E'' against E' (1: equal)",
              lambda v: 0.0 <= v <= 1e6)
    w, e1, e2 = curve.omega, curve.storage, curve.loss
    d = _density(w)
    held = ()
    chosen_by = "given"
    if per_decade is None:
        held = tuple((p, _held_out(w, e1, e2, d, lw, p, extend)) for p in PER_DECADE_CHOICES)
        best = min(h for _, h in held)
        enough = max(best * (1.0 + PARSIMONY), RESOLUTION)
        per_decade = next(p for p, h in held if h <= enough)
        chosen_by = "held-out"
    theta = _times(w, per_decade, extend)
    rw1, rw2 = np.sqrt(d), np.sqrt(d * lw)
    e_r, amp, rnorm = _solve(w, e1, e2, theta, rw1, rw2)
    floor = None
    if not e_r > 0.0:   # a fluid: floor the relaxed modulus (see Returns)
        e_r, amp, floor = _floored(w, e1, e2, theta, rw1, rw2, rnorm)
    keep = amp > 0.0
    model = Maxwell(float(e_r), tuple(amp[keep].tolist()), tuple(theta[keep].tolist()))
    mod = model.modulus(w)
    r1 = mod.real / e1 - 1.0
    r2 = mod.imag / e2 - 1.0
    r3 = (mod.imag / mod.real) / (e2 / e1) - 1.0
    stats = [(float(np.max(np.abs(r))), float(np.sqrt(np.mean(r * r)))) for r in (r1, r2, r3)]
    kk = _kk_ratio(w, e1, e2, d)
    decades, kk_dec = _per_decade_table(curve, r1, r2, kk)
    kk_range = ((min(v for _, v in kk_dec), max(v for _, v in kk_dec)) if kk_dec
                else (None, None))
    scatter = curve.scatter()
    report = FitReport(
        window=curve.window, per_decade=per_decade, candidates=theta.size,
        terms=int(keep.sum()), storage_max=stats[0][0], storage_rms=stats[0][1],
        loss_max=stats[1][0], loss_rms=stats[1][1], tan_delta_max=stats[2][0],
        tan_delta_rms=stats[2][1], bound=bound, source=curve.source,
        modulus_unit=curve.modulus_unit, frequency_unit=curve.frequency_unit, loss_weight=lw,
        chosen_by=chosen_by, held_out=held, scatter=scatter, kk=kk_dec, kk_range=kk_range,
        decades=decades, worst=_worst(curve, mod, r1, r2), points=curve.points,
        merged=curve.points - w.size, drops=curve.drops, relaxed_floor=floor,
        warnings=_warnings(curve, kk_range, scatter, floor, r1, r2),
        seconds=time.perf_counter() - t0)
    if bound is not None and report.max_residual > bound:
        kk_text = "n/a" if kk_range[0] is None else f"{kk_range[0]:.3g}..{kk_range[1]:.3g}"
        p = max(report.worst, key=lambda q: abs(q["residual"]))
        fu, mu = curve.units
        raise bad("max_residual", bound, f"a bound the fit meets (its largest residual is "
                  f"{report.max_residual:.3g}): the best non-negative Prony "
                  f"series ({per_decade:g} times per decade) misses {p['modulus']} at "
                  f"{p['frequency']:.4g} {fu} by {100 * p['residual']:+.3g} % (datum "
                  f"{p['datum']:.4g}, fit {p['fit']:.4g} {mu}".rstrip() + f"); measured E''/E'' "
                  f"implied by E' is {kk_text} per decade (1 for consistent data), data scatter "
                  f"{100 * max([v for v in scatter if v is not None] + [0.0]):.2g} %")
    return replace(model, fit=report)
