"""Time–temperature superposition: raw isotherms -> shift factors, WLF, a master curve.

`superpose` takes `Sweeps` (raw frequency sweeps at several temperatures, `read_sweeps`) and

1. finds the horizontal shift between each pair of neighbouring isotherms from the data alone:
   the shift ``d`` (decades of frequency) that minimises the mean squared distance between the
   two curves, each interpolated (linearly in log-log) at the other's points inside their
   overlap.  The curves compared are log E' and log E'' (``method="moduli"``), or log tan δ
   (``method="tan_delta"``, free of any vertical shift);
2. applies a vertical shift b_T to the moduli: none, the entropic ``T0 ρ0/(T ρ)`` (absolute
   temperatures; ρ from the file's density column, else 1), or ``"fitted"``: per pair, the
   common offset of log E' and log E'' that best overlays them at each trial shift;
3. chains the pair shifts into log10 a_T, zero at the reference temperature (linear between
   isotherms when the reference lies between two), with a standard error per isotherm from the
   scatter of each overlap (``sigma_d = 2.75 sqrt(ms / sum s^2)``, s the slopes of the compared
   curves: a flat overlap gives a large error);
4. fits WLF, ``log10 a_T = -C1 (T - T0)/(C2 + T - T0)``, by least squares on the steps
   between neighbours (independent, unlike the chained shifts), weighted by their errors; the
   range where it holds is the run of isotherms around T0 whose residual is within
   `HOLDS_SIGMAS` standard errors (and `HOLDS_FLOOR` decades); outside it below, an Arrhenius
   line ``log10 a_T = (Ea/(R ln 10)) (1/T - 1/T0')`` is fitted when at least 3 isotherms remain;
5. builds the `MasterCurve` at T0 from every point (frequency times a_T, moduli times b_T).

Convention: a_T multiplies times (`WLF`); a point measured at T and ω sits at the reduced
frequency ω a_T on the master curve at T0; a_T < 1 above T0.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..checks import bad, real
from ._dma import MasterCurve
from ._sweeps import Sweeps
from ._temperature import WLF

#: smallest overlap of two neighbouring isotherms, in decades of frequency, and points in it
MIN_OVERLAP_DECADES = 0.2
MIN_OVERLAP_POINTS = 4
#: step of the coarse search over shifts (decades); the best is then refined by Brent
SEARCH_STEP = 0.05
#: the error of a pair's shift over the independent-residual formula: measured on 24 seeded
#: test sets (2 and 5 % scatter, 19 isotherms), the steps' errors over that formula had a
#: standard deviation of 2.75
SIGMA_FACTOR = 2.75
#: a WLF residual within this many standard errors of the shift (or this many decades) holds
HOLDS_SIGMAS = 3.0
HOLDS_FLOOR = 0.05
METHODS = ("moduli", "tan_delta")
VERTICAL = (None, "temperature", "fitted")
#: the gas constant, J/(mol K)
R_GAS = 8.314462618


@dataclass(frozen=True)
class WLFFit:
    """WLF constants fitted to the shifts, and how well they hold.

    Attributes
    ----------
    wlf : WLF
        C1, C2 (temperature unit of the data) and T_ref (the reference temperature).
    C1_error, C2_error : float
        Standard errors from the weighted least squares.
    rms, max : float
        RMS and largest |residual| of log10 a_T over the isotherms used (decades).
    holds : (float, float)
        Lowest and highest temperature of the run of isotherms around T_ref where the WLF
        residual is within `HOLDS_SIGMAS` standard errors (or `HOLDS_FLOOR` decades).
    residuals : tuple of float
        log10 a_T(shift) - WLF, one per isotherm (all of them, those outside ``holds`` too).
    """

    wlf: WLF
    C1_error: float
    C2_error: float
    rms: float
    max: float
    holds: tuple
    residuals: tuple


@dataclass(frozen=True)
class ArrheniusFit:
    """``log10 a_T = A + B/T_K`` below the WLF range: activation energy ``Ea = B R ln 10``."""

    activation_energy: float   # J/mol
    A: float
    B: float
    rms: float
    range: tuple


@dataclass(frozen=True, eq=False)
class Superposition:
    """The result of `superpose`.

    Attributes
    ----------
    curve : MasterCurve
        Every measured point at T_ref (frequencies times a_T, moduli times b_T).
    reference_temperature : float
    shifts : tuple of dict
        One per isotherm, ascending T: ``temperature``, ``log10_aT``, ``log10_aT_error``,
        ``log10_bT``, ``points``, ``overlap_rms`` (the RMS distance, in decades of modulus
        (or tan δ), to the next colder isotherm after shifting; None for the coldest) and
        ``overlap_decades``.
    wlf : WLFFit
    arrhenius : ArrheniusFit or None
    method, vertical : str
    source, temperature_unit : str or None
    """

    curve: MasterCurve
    reference_temperature: float
    shifts: tuple
    wlf: WLFFit
    arrhenius: ArrheniusFit | None
    method: str
    vertical: str | None
    source: str | None = None
    temperature_unit: str | None = None
    notes: tuple = field(default=())

    def table(self) -> str:
        """The shift table and the WLF fit as lines of text (`shift_table_text`)."""
        return shift_table_text(self.as_dict())

    def as_dict(self) -> dict:
        """JSON-ready: the shift table, WLF (constants, errors, residuals, range), Arrhenius."""
        w = self.wlf
        out = {"reference_temperature": self.reference_temperature,
               "temperature_unit": self.temperature_unit, "method": self.method,
               "vertical": self.vertical, "shifts": [dict(s) for s in self.shifts],
               "wlf": {"C1": w.wlf.C1, "C2": w.wlf.C2, "T_ref": w.wlf.T_ref,
                       "C1_error": w.C1_error, "C2_error": w.C2_error, "rms": w.rms,
                       "max": w.max, "holds": list(w.holds), "residuals": list(w.residuals)},
               "arrhenius": None}
        if self.arrhenius is not None:
            a = self.arrhenius
            out["arrhenius"] = {"activation_energy": a.activation_energy, "A": a.A, "B": a.B,
                                "rms": a.rms, "range": list(a.range)}
        return out


def shift_table_text(d) -> str:
    """`Superposition.as_dict` (or a record's ``superposition``) as lines of text: the shift
    table, the WLF fit with its errors, residual and range, Arrhenius below."""
    u = d.get("temperature_unit") or ""
    w = d["wlf"]
    lines = [f"reference temperature {d['reference_temperature']:g} {u}; horizontal shifts "
             f"from {d['method']}, vertical {d['vertical'] or 'none'}",
             f"T [{u}]  log10 a_T  ± error  log10 b_T  points  overlap rms  WLF residual"]
    for s, r in zip(d["shifts"], w["residuals"]):
        ov = "-" if s["overlap_rms"] is None else f"{s['overlap_rms']:.4f}"
        lines.append(f"{s['temperature']:8.3g}  {s['log10_aT']:+9.4f}  "
                     f"{s['log10_aT_error']:7.4f}  {s['log10_bT']:+9.4f}  "
                     f"{s['points']:6d}  {ov:>11s}  {r:+.4f}")
    lines.append(f"WLF: C1 = {w['C1']:.4g} ± {w['C1_error']:.2g}, C2 = {w['C2']:.4g} ± "
                 f"{w['C2_error']:.2g} {u}, T_ref = {w['T_ref']:g} {u}; residual RMS "
                 f"{w['rms']:.3g}, max {w['max']:.3g} decades; holds over {w['holds'][0]:g} … "
                 f"{w['holds'][1]:g} {u}")
    a = d.get("arrhenius")
    if a is not None:
        lines.append(f"Arrhenius below: Ea = {a['activation_energy'] / 1e3:.4g} kJ/mol over "
                     f"{a['range'][0]:g} … {a['range'][1]:g} {u} (residual RMS {a['rms']:.3g})")
    return "\n".join(lines)


def _features(iso, log_b, method):
    """x = log10 w and the compared curves (rows) of an isotherm."""
    x = np.log10(iso.omega)
    if method == "tan_delta":
        return x, np.log10(iso.loss / iso.storage)[None, :]
    return x, np.vstack([np.log10(iso.storage), np.log10(iso.loss)]) + log_b


def _curve(x, f):
    """Monotone cubic (PCHIP) interpolants of the compared curves of one isotherm in log-log:
    between points a quarter decade apart, linear interpolation of a curved log E' is biased by
    up to 0.1 decade of shift; PCHIP neither overshoots on scatter nor carries that bias."""
    from scipy.interpolate import PchipInterpolator
    return x, f, [PchipInterpolator(x, fk) for fk in f]


def _overlap(a, b, d, slopes=False):
    """Residuals of curve b shifted by d against a in their overlap (and, with ``slopes``, the
    slopes of the compared curves there and the overlap's width), or None without overlap."""
    xa, fa, pa = a
    xb, fb, pb = b
    xs = xb + d
    lo, hi = max(xa[0], xs[0]), min(xa[-1], xs[-1])
    if hi - lo < MIN_OVERLAP_DECADES:
        return None
    ia = (xa >= lo) & (xa <= hi)
    ib = (xs >= lo) & (xs <= hi)
    if ia.sum() + ib.sum() < MIN_OVERLAP_POINTS or not ia.any() or not ib.any():
        return None
    res, slope = [], []
    for k in range(fa.shape[0]):
        res.append(fa[k, ia] - pb[k](xa[ia] - d))
        res.append(pa[k](xs[ib]) - fb[k, ib])
        if slopes:
            slope.append(pb[k](xa[ia] - d, 1))
            slope.append(pa[k](xs[ib], 1))
    if not slopes:
        return np.concatenate(res)
    return np.concatenate(res), np.concatenate(slope), hi - lo


def _pair(a, b, fitted_vertical):
    """Shift d (and vertical offset v) putting isotherm b on a; (d, v, ms, sigma, decades)."""
    from scipy.optimize import minimize_scalar
    xa, xb = a[0], b[0]
    span = (xa[-1] - xa[0]) + (xb[-1] - xb[0])
    lo = xa[0] - xb[-1] + MIN_OVERLAP_DECADES
    hi = xa[-1] - xb[0] - MIN_OVERLAP_DECADES
    if hi < lo:
        return None

    def cost(d):
        r = _overlap(a, b, d)
        if r is None:
            return math.inf
        v = float(np.mean(r)) if fitted_vertical else 0.0
        return float(np.mean((r - v) ** 2))
    grid = np.arange(lo, hi + SEARCH_STEP, SEARCH_STEP) if span > 0 else np.array([lo])
    costs = np.array([cost(d) for d in grid])
    if not np.isfinite(costs).any():
        return None
    j = int(np.argmin(costs))
    a_, b_ = grid[max(j - 1, 0)], grid[min(j + 1, grid.size - 1)]  # Brent inside the bracket
    best = minimize_scalar(cost, bounds=(a_, b_), method="bounded",
                           options={"xatol": 1e-6})
    d = float(best.x) if best.fun <= costs[j] else float(grid[j])
    if not all(math.isfinite(cost(d + k * 2.0 * SEARCH_STEP)) for k in (-1, 1)):
        return "edge"                 # the best overlay is at the least overlap allowed
    r, s, dec = _overlap(a, b, d, slopes=True)
    v = float(np.mean(r)) if fitted_vertical else 0.0
    if fitted_vertical:               # d and v fitted together: only the slopes' spread tells d
        s = s - float(np.mean(s))
    ms = float(np.mean((r - v) ** 2))
    # each datum enters twice (against the other curve's interpolant and as a node of that
    # interpolant) and neighbouring residuals share nodes: SIGMA_FACTOR widens the independent-
    # residual formula to the scatter measured over seeded test sets
    sigma = SIGMA_FACTOR * math.sqrt(ms / max(float(np.sum(s * s)), 1e-300))
    return d, v, ms, sigma, dec


def superpose(sweeps: Sweeps, reference_temperature, *, method: str = "moduli",
              vertical: str | None = None) -> Superposition:
    """Shift raw isotherms onto one master curve at ``reference_temperature`` (module docstring).

    Parameters
    ----------
    sweeps : Sweeps
        From `read_sweeps` (at least 3 isotherms).
    reference_temperature : float
        T0, inside the measured temperatures, in the file's unit.
    method : {"moduli", "tan_delta"}
        Compare log E' and log E'' (default), or log tan δ (no vertical shift enters it).
    vertical : {None, "temperature", "fitted"}
        No vertical shift, ``b_T = T0 ρ0/(T ρ)`` (absolute temperatures: the file must state
        its unit), or fitted per pair (``method="moduli"`` only: tan δ holds no vertical shift).

    Returns
    -------
    Superposition

    Raises
    ------
    ValueError
        Naming the argument: T0 outside the measured temperatures; neighbouring isotherms that
        do not overlap by `MIN_OVERLAP_DECADES` at any shift; a vertical shift the data cannot
        give.
    """
    if not isinstance(sweeps, Sweeps):
        raise bad("sweeps", sweeps, "raw isotherms from read_sweeps")
    if method not in METHODS:
        raise bad("method", method, "'moduli' (log E' and log E'') or 'tan_delta'")
    if vertical not in VERTICAL:
        raise bad("vertical", vertical, "None, 'temperature' (T0 rho0/(T rho)) or 'fitted'")
    if vertical == "fitted" and method == "tan_delta":
        raise bad("vertical", vertical, "None with method='tan_delta' (tan δ carries no "
                  "vertical shift to fit; use method='moduli')")
    temps = sweeps.temperatures
    t0 = real("reference_temperature", reference_temperature,
              f"a temperature inside the measured range [{temps[0]:g}, {temps[-1]:g}]",
              lambda v: temps[0] <= v <= temps[-1])
    log_b = np.zeros(temps.size)
    if vertical == "temperature":
        tk = sweeps.kelvin(temps)
        rho = np.array([iso.density or 1.0 for iso in sweeps.isotherms])
        t0k = float(sweeps.kelvin(t0))
        rho0 = float(np.interp(t0, temps, rho))
        log_b = np.log10(t0k * rho0 / (tk * rho))
    feats = [_curve(*_features(iso, lb, method)) for iso, lb in zip(sweeps.isotherms, log_b)]
    d = np.zeros(temps.size)
    var = np.zeros(temps.size)
    rows = [{"overlap_rms": None, "overlap_decades": None}]
    for i in range(1, temps.size):
        out = _pair(feats[i - 1], feats[i], vertical == "fitted")
        if out == "edge":
            raise bad("sweeps", sweeps.source or "Sweeps", f"isotherms that overlap: "
                      f"{temps[i - 1]:g} and {temps[i]:g} overlay best where they share only "
                      f"{MIN_OVERLAP_DECADES:g} decade, the least allowed (the true shift may lie "
                      "beyond): closer temperatures or a wider frequency range")
        if out is None:
            raise bad("sweeps", sweeps.source or "Sweeps", f"isotherms that overlap: "
                      f"{temps[i - 1]:g} and {temps[i]:g} share less than "
                      f"{MIN_OVERLAP_DECADES:g} decade of frequency at any shift")
        step, v, ms, sigma, dec = out
        d[i], var[i] = step, sigma * sigma
        if vertical == "fitted":
            log_b[i] = v               # feats[i - 1] carries its own offset already
            feats[i] = _curve(feats[i][0], feats[i][1] + v)
        rows.append({"overlap_rms": math.sqrt(ms), "overlap_decades": dec})
    log_a = np.cumsum(d)          # frequency shift of isotherm i onto isotherm 0
    log_a -= np.interp(t0, temps, log_a)
    if vertical == "fitted":
        log_b -= np.interp(t0, temps, log_b)
    err = _errors(temps, var, t0)
    step_err = np.sqrt(var)
    shifts = tuple({"temperature": float(t), "log10_aT": float(la), "log10_aT_error": float(e),
                    "log10_bT": float(lb), "points": int(iso.omega.size), **r}
                   for t, la, e, lb, iso, r in zip(temps, log_a, err, log_b, sweeps.isotherms,
                                                   rows))
    wlf = fit_wlf(temps, log_a, step_err, t0)
    arr = _arrhenius(sweeps, temps, log_a, wlf)
    omega = np.concatenate([iso.omega * 10.0 ** la for iso, la in zip(sweeps.isotherms, log_a)])
    e1 = np.concatenate([iso.storage * 10.0 ** lb for iso, lb in zip(sweeps.isotherms, log_b)])
    e2 = np.concatenate([iso.loss * 10.0 ** lb for iso, lb in zip(sweeps.isotherms, log_b)])
    order = np.argsort(omega, kind="stable")
    curve = MasterCurve(omega[order], e1[order], e2[order],
                        source=sweeps.source, modulus_unit=sweeps.modulus_unit)
    return Superposition(curve, t0, shifts, wlf, arr, method, vertical, sweeps.source,
                         sweeps.temperature_unit)


def _errors(temps, var, t0):
    """Standard error of log10 a_T at each isotherm: the pair variances summed from T0 out."""
    cum = np.cumsum(var)          # variance of the chain from isotherm 0
    at0 = np.interp(t0, temps, cum)
    return np.sqrt(np.abs(cum - at0))


def _wlf_model(t, c1, c2, t0):
    dt = t - t0
    return -c1 * dt / (c2 + dt)


def fit_wlf(T, log_aT, step_error=None, T_ref=None) -> WLFFit:
    """WLF constants fitted to shifts ``log10 a_T(T)``, and where they hold.

    The residuals are those of the steps between neighbouring temperatures (each measured
    independently, from one overlap), weighted by ``1/step_error``: the chained shifts share
    their errors, the steps do not, so the constants' standard errors are honest.

    Parameters
    ----------
    T, log_aT : array_like
        Temperatures, ascending, and shifts (at least 3).
    step_error : array_like, optional
        Standard error of each step ``log_aT[i] - log_aT[i-1]`` (``step_error[0]`` unused);
        default equal weights.
    T_ref : float, optional
        The reference (log10 a_T = 0 there; default the temperature where |log_aT| is least).

    Returns
    -------
    WLFFit
        ``residuals`` and ``holds`` judge the chained shifts against WLF, each against the
        error of its chain from T_ref (`HOLDS_SIGMAS`, `HOLDS_FLOOR`).
    """
    from scipy.optimize import least_squares
    t = np.asarray(T, float)
    y = np.asarray(log_aT, float)
    if t.size < 3:
        raise bad("T", T, "at least 3 temperatures to fit C1 and C2")
    se = np.full(t.size, 1.0) if step_error is None else np.asarray(step_error, float)
    se = np.maximum(se, 1e-3 * HOLDS_FLOOR)
    t0 = float(t[np.argmin(np.abs(y))]) if T_ref is None else float(T_ref)
    chain = _errors(t, se * se * (step_error is not None), t0)
    keep = np.ones(t.size, bool)
    for _ in range(4):                       # refit on the run of isotherms where it holds
        c1, c2 = _wlf_solve(t[keep], y[keep], se[keep], t0, least_squares)
        res = np.where(t > t0 - c2, y - _wlf_model(t, c1, c2, t0), np.inf)
        ok = np.abs(res) <= np.maximum(HOLDS_SIGMAS * chain, HOLDS_FLOOR)
        run = _run_around(t, ok, t0)
        if np.array_equal(run, keep) or run.sum() < 3:
            break
        keep = run
    tk, yk, sk = t[keep], y[keep], se[keep]
    jac = np.diff(_wlf_jac(tk, c1, c2, t0), axis=0) / sk[1:, None]
    r = (np.diff(yk) - np.diff(_wlf_model(tk, c1, c2, t0))) / sk[1:]
    dof = max(r.size - 2, 1)
    try:
        scale = float(r @ r) / dof if step_error is None else max(float(r @ r) / dof, 1.0)
        errs = np.sqrt(np.abs(np.diag(np.linalg.inv(jac.T @ jac) * scale)))
    except np.linalg.LinAlgError:
        errs = np.array([math.inf, math.inf])
    res_all = y - np.where(t > t0 - c2, _wlf_model(t, c1, c2, t0), np.nan)
    used = res_all[keep]
    return WLFFit(WLF(c1, c2, t0), float(errs[0]), float(errs[1]),
                  float(np.sqrt(np.mean(used ** 2))), float(np.max(np.abs(used))),
                  (float(tk.min()), float(tk.max())), tuple(float(v) for v in res_all))


def _run_around(t, ok, t0):
    """The contiguous run of ``ok`` isotherms that holds the one nearest T0."""
    i = int(np.argmin(np.abs(t - t0)))
    run = np.zeros(t.size, bool)
    if not ok[i]:
        run[i] = True
        return run
    lo = hi = i
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    while hi < t.size - 1 and ok[hi + 1]:
        hi += 1
    run[lo:hi + 1] = True
    return run


def _wlf_jac(t, c1, c2, t0):
    dt = t - t0
    return np.column_stack([-dt / (c2 + dt), c1 * dt / (c2 + dt) ** 2])


def _wlf_solve(t, y, se, t0, least_squares):
    """(C1, C2) > 0 fitting the steps of y, C2 above T0 - min T (the pole below every
    isotherm); several starts."""
    floor = max(t0 - t.min(), 0.0)
    dy, w = np.diff(y), 1.0 / se[1:]
    best = None
    for c2_start in (20.0, 50.0, 100.0, 300.0):
        p0 = [math.log(10.0), math.log(max(c2_start, 1.0))]

        def resid(p):
            c1, c2 = math.exp(p[0]), floor + math.exp(p[1])
            return (dy - np.diff(_wlf_model(t, c1, c2, t0))) * w
        sol = least_squares(resid, p0, method="lm", xtol=1e-14, ftol=1e-14, max_nfev=2000)
        if best is None or sol.cost < best.cost:
            best = sol
    return math.exp(best.x[0]), floor + math.exp(best.x[1])


def _arrhenius(sweeps, t, y, wlf):
    """Arrhenius fit to the isotherms below the WLF range (at least 3, absolute temperature
    known), else None."""
    below = t < wlf.holds[0]
    if below.sum() < 3:
        return None
    try:
        tk = sweeps.kelvin(t[below])
    except ValueError:
        return None
    a_mat = np.column_stack([np.ones(tk.size), 1.0 / tk])
    coef, *_ = np.linalg.lstsq(a_mat, y[below], rcond=None)
    rms = float(np.sqrt(np.mean((a_mat @ coef - y[below]) ** 2)))
    return ArrheniusFit(float(coef[1] * R_GAS * math.log(10.0)), float(coef[0]),
                        float(coef[1]), rms, (float(t[below].min()), float(t[below].max())))
