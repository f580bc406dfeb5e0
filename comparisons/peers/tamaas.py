"""Tamaas as a third code: its transient viscoelastic contact solver stepped to steady sliding.

Tamaas (Frérot, Anciaux, Rey, Pham-Ba & Molinari, https://gitlab.com/tamaas/tamaas) solves the
normal contact of a rigid surface with a periodic half-space by a Polonsky–Keer conjugate-gradient
method on an FFT influence operator.  Its ``MaxwellViscoelastic`` solver makes the half-space a
generalised Maxwell solid stepped in time by backward Euler.  Nobody on this project wrote it,
it never sees the steady-sliding Green's function of eq. (2.5) nor Hunter's transformation of the
paper, and it reaches steady sliding the physical way: the material stays at rest in the lab
frame, the sinusoid is moved every time step, and the transient is run out.

What Tamaas computes (version 2.9, measured here and written where it bites)
------------------------------------------------------------------------------
* ``model_type.basic_1d`` is the plane-strain half-plane with a 1-D periodic surface: its
  displacement obeys û(q) = 2 p̂(q)/(E*|q|) for q ≠ 0 with E* = E/(1 − ν²) (``model.E_star``);
  system size 1 makes λ the unit of length.
* The traction is the pressure, positive in compression; the displacement is positive into the
  body; ``solve(p)`` imposes the mean pressure p, and the q = 0 mode of the displacement is the
  rigid approach fixed by the contact, so the gap is u − surface (0 in contact) and ``surface``
  is the indenter's protrusion into the body (crest = largest value).
* Each ``MaxwellViscoelastic.solve`` is one backward-Euler step of length ``time_step`` (the
  internal variables are updated after the solve: ``solve_should_update`` is true).  The branch
  moduli are shear moduli in the units of ``model.mu`` = E/(2(1 + ν)), which plays the long-term
  shear modulus G∞; the branch times are RELAXATION times.
* Its state update relaxes to the right long-term state only when G∞ = ``model.mu`` = 1: with any
  other value a constant imposed displacement relaxes to the wrong stress (measured: to 0.61 of
  the relaxed value at G∞ = ½).  Here G∞ = 1 (E = 2, ν = 0), so Tamaas's pressures are in units of
  G∞ and its relaxed plane-strain modulus is E0/(1 − ν²) = 2 G∞/(1 − ν) = 2.

The standard linear solid in those units
----------------------------------------
The paper's material (eq. 2.3) has creep compliance J(t) = 1/E0 − (1/E1) e^{−t/τ} with τ the
CREEP (retardation) time; its relaxation modulus is E(t) = E0 + (E∞ − E0) e^{−t/τ_R} with
relaxation time τ_R = τ E0/E∞.  So Tamaas gets one branch with modulus (E∞/E0 − 1) G∞ and time
τ/ratio (τ = 1).  Passing τ itself would shift every speed by the factor E∞/E0.  ν only scales
E* and drops out of every dimensionless output (ν = 0 here).

Units (the project's): lengths in λ (positions x/λ) or over h, pressures in E0/(1 − ν²), times in
τ; inputs load p̃∞ = p∞(1 − ν²)/E0, speed V/V0 = Vτk, ratio E∞/E0, hk.  In Tamaas's units:
λ = 1, h = hk/(2π), V = speed/(2π) per τ, a period takes T = 2π/speed, σ̃ = p_Tamaas/2.

Sliding and the steady state
----------------------------
The indenter advances toward +x by a whole number of grid cells per step, or by one cell in a
whole number of steps (``dt`` is snapped to the nearest such value), so that after every period
its crest is back on grid node 0 and the crest-frame fields are the lab fields rolled by N/2.
At every period end the fields and scalars are compared with the previous period's; the run is
steady when that change, and the tail of the geometric series it decays by, are below
``steady_rtol``.  With one cell per step (the default dt) the discrete steady state is an exact
travelling wave.

Output conventions: the crest frame (crest at x = 0, material streaming toward −x), σ(1 − ν²)/E0
positive in compression, v/h positive into the body from the mean line of the deformed surface,
gap/h, τ̃f = −(1/λ)∫σ̃ ∂v/∂x dx (positive when it resists: the paper's (1/λ)∫σ ∂v/∂x dx with the
sign of a resisting force made positive) and μ = τ̃f/p̃∞.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014: eq. (2.3) (the
material), eq. (3.1) and Appendix A (Westergaard's limits), the definitions of a, e, ê, Δ, τf.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from viscosine import Fields
from viscosine.checks import bad, series
from viscosine.protocol import SCALAR_KEYS  # noqa: F401  (part of the interface)

from ..convergence import richardson
from ._tamaas_result import _TWO_PI, TamaasResult  # noqa: F401
from ._tamaas_solve import (ACCEPTED, HK, RATIO, TAMAAS_REQUIREMENT,  # noqa: F401
                            _import_tamaas, solve, steadiness, validate)


# ----------------------------------------------------------------------------- dt study
#: the quantities a dt study extrapolates
STUDY_KEYS = ("mu", "tau_f", "penetration", "ka", "ke", "ke_hat", "contact_fraction")

#: the time steps of a dt study in cell crossings T/N (coarse to fine): halved twice, so that the
#: first-order Richardson value and the size of its next term both come out
CELLS_PER_STEP = (4, 2, 1)


def _order(dts, values):
    """Observed order p from three (dt, value) pairs, dt decreasing: solves
    (q1 − q0)/(q2 − q1) = (dt0^p − dt1^p)/(dt1^p − dt2^p); None when the differences do not
    shrink monotonically (no order to observe).

    Not `comparisons.convergence.observed_order`: this is exact for any ratios of the steps
    (the log–log fit of differences is right only for equal ratios) and refuses a
    non-monotone study; on halved steps the two agree to a few units in the last place."""
    (d0, d1, d2), (q0, q1, q2) = dts, values
    a, b = q1 - q0, q2 - q1
    if b == 0.0 or a / b <= 1.0:
        return None
    target = math.log(a / b)

    def f(p):
        return math.log((d0 ** p - d1 ** p) / (d1 ** p - d2 ** p)) - target

    lo, hi = 0.05, 10.0
    if f(lo) > 0.0 or f(hi) < 0.0:
        return None
    for _ in range(200):  # bisection: f increases with p
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def dt_study(*, load, speed, ratio=RATIO, hk=HK, nodes=512, dts=None, mesh_check=False,
             **options):
    """Run `solve` at several time steps and extrapolate to dt → 0 (backward Euler: first order).

    Parameters
    ----------
    load, speed, ratio, hk, nodes
        As in `solve`.
    dts : sequence of float, optional
        Time steps in units of τ (snapped as in `solve`), sorted here from coarse to fine.
        Default: 4, 2 and 1 grid-cell crossings (the finest is `solve`'s default).
    mesh_check : bool
        Also run the two finest steps at N/2 and report how much the extrapolated values move.
    **options
        tolerance, steady_rtol, max_periods (passed to `solve`).

    Returns
    -------
    dict
        Plain data: ``inputs``; ``rows`` (one per dt: dt/τ, dt/T, cells per step, steps per
        cell, the scalars of `STUDY_KEYS`, steps, periods, wall time, success, message);
        ``order`` (observed order of each quantity from the three finest steps, None if fewer
        than three or not monotone); ``richardson`` (first-order extrapolation from the two
        finest steps); ``error`` (its estimated error: the change of the extrapolation from
        the coarser pair, divided by dt_coarsest/dt_finest − 1, i.e. the size of the next
        term; None with two steps); ``mesh`` (None, or the extrapolation at N/2 and its
        difference); ``success`` and ``wall_time``.

    References
    ----------
    The definitions of a, e, ê, Δ and τf of the paper; the extrapolation is Richardson's.
    """
    v = validate(load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes)
    t_cell = _TWO_PI / (v["speed"] * v["nodes"])
    if dts is None:
        dts = tuple(c * t_cell for c in CELLS_PER_STEP)
    allowed = "a sequence of at least two time steps > 0 (units of τ)"
    steps = sorted(series("dts", dts, allowed), reverse=True)
    if len(steps) < 2:
        raise bad("dts", dts, allowed)
    dts = steps
    for d in dts:
        validate(dt=d)
    t0 = time.perf_counter()
    rows = _study_rows(dts, load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes, **options)
    used = [r["dt"] for r in rows]
    if len(set(used)) != len(used):
        raise bad("dts", dts, "time steps that stay distinct after snapping to the grid (see "
                  "solve)")
    out = {"inputs": {"load": load, "speed": speed, "ratio": ratio, "hk": hk, "nodes": nodes,
                      "dts": list(dts), **options},
           "rows": rows, "success": all(r["success"] for r in rows)}
    out.update(extrapolate(rows))
    out["mesh"] = None
    if mesh_check and nodes // 2 >= ACCEPTED["nodes"][0] and (nodes // 2) % 2 == 0:
        half = _study_rows(used[-2:], load=load, speed=speed, ratio=ratio, hk=hk,
                           nodes=nodes // 2, **options)
        ext = extrapolate(half)["richardson"]
        out["mesh"] = {"nodes": nodes // 2, "rows": half, "richardson": ext,
                       "difference": {k: (None if ext[k] is None or out["richardson"][k] is None
                                          else out["richardson"][k] - ext[k])
                                      for k in STUDY_KEYS}}
        out["success"] = out["success"] and all(r["success"] for r in half)
    out["wall_time"] = time.perf_counter() - t0
    return out


def _study_rows(dts, progress=None, results=None, **kw):
    """One `solve` per time step: the rows of a dt study (``progress(row)`` after each; the
    results appended to ``results`` when it is a list)."""
    rows = []
    for d in dts:
        r = solve(dt=d, **kw)
        if results is not None:
            results.append(r)
        dg = r.diagnostics
        row = {"dt": r.dt, "dt_over_period": dg["dt_over_period"],
               "cells_per_step": dg["cells_per_step"], "steps_per_cell": dg["steps_per_cell"],
               "nodes": r.nodes, "steps": dg["steps"], "periods": dg["periods"],
               "wall_time": dg["wall_time"], "success": r.success, "message": r.message}
        row.update({k: getattr(r, k) for k in STUDY_KEYS})
        rows.append(row)
        if progress is not None:
            progress(row)
    return rows


def extrapolate(rows):
    """Order, Richardson value and error estimate of every quantity (rows coarse → fine).

    The Richardson value is `comparisons.convergence.richardson`'s step of order 1 (backward
    Euler) with the ratio of the two finest steps."""
    dts = [r["dt"] for r in rows]
    order, rich, err = {}, {}, {}
    for k in STUDY_KEYS:
        q = [r[k] for r in rows]
        if any(x is None for x in q) or not all(r["success"] for r in rows):
            order[k] = rich[k] = err[k] = None
            continue
        rich[k] = richardson(q[-2], q[-1], 1.0, dts[-2] / dts[-1])
        order[k] = _order(dts[-3:], q[-3:]) if len(q) >= 3 else None
        if len(q) >= 3:
            coarser = richardson(q[-3], q[-2], 1.0, dts[-3] / dts[-2])
            err[k] = abs(rich[k] - coarser) / (dts[-3] / dts[-1] - 1.0)
        else:
            err[k] = None
    return {"order": order, "richardson": rich, "error": err}


@dataclass(frozen=True)
class DtExtrapolation:
    """A dt study on one grid, extrapolated to dt → 0 (`dt_extrapolation`).

    Attributes
    ----------
    nodes, cells_per_step
        The grid and the time steps (cell crossings T/N per step, coarse to fine).
    rows
        One per time step, as `dt_study`'s.
    richardson, error, order
        Of every quantity of `STUDY_KEYS` (`extrapolate`: first-order Richardson value from the
        two finest steps, its estimated error with three steps, observed order); with a single
        step, that step's values and no error.
    full_contact
        Of the finest step.
    success, message
        Whether every step is an answer, and what the steps say.
    results
        The `TamaasResult` of each step.
    """

    nodes: int
    cells_per_step: tuple
    rows: list
    richardson: dict
    error: dict
    order: dict
    full_contact: bool
    success: bool
    message: str
    results: tuple = field(repr=False, default=())

    def scalars(self):
        """The extrapolated scalars (STUDY_KEYS, None where undefined) and full_contact."""
        return {"full_contact": self.full_contact, **self.richardson}

    def fields(self):
        """σ, v/h and gap/h extrapolated to dt → 0 the same way, point by point (the two finest
        steps; the finest step's own with one step), on Tamaas's grid."""
        rs = self.results
        fine = rs[-1].fields()
        if len(rs) < 2:
            return fine
        coarse = rs[-2].fields()
        dc, df = rs[-2].dt, rs[-1].dt
        return Fields(fine.x_over_lambda, *(richardson(np.asarray(getattr(coarse, k)),
                                                       np.asarray(getattr(fine, k)), 1.0, dc / df)
                                            for k in ("pressure", "displacement", "gap")))


def dt_extrapolation(*, load, speed, ratio=RATIO, hk=HK, nodes=512, cells_per_step=CELLS_PER_STEP,
                     progress=None, **options):
    """`solve` at dt = c·T/N for each c of ``cells_per_step`` and the values at dt → 0.

    The same study as `dt_study` (and as the report's, through `extrapolate`), given in cell
    crossings, keeping each step's result so that the fields are extrapolated too.

    Parameters
    ----------
    load, speed, ratio, hk, nodes
        As in `solve`.
    cells_per_step : sequence of float
        Time steps in units of T/N (the time the indenter takes to cross a cell), sorted here
        coarse to fine; default 4, 2, 1.  One value: no extrapolation.
    progress : callable, optional
        Called with each step's row (see `dt_study`) as it finishes.
    **options
        tolerance, steady_rtol, max_periods (passed to `solve`).

    Returns
    -------
    DtExtrapolation

    Raises
    ------
    ValueError
        Bad input (``cells_per_step``: positive numbers, distinct after snapping).
    """
    v = validate(load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes)
    allowed = "one or more time steps > 0 in cell crossings T/N"
    cells = sorted(series("cells_per_step", cells_per_step, allowed, lambda c: c > 0.0),
                   reverse=True)
    if not cells:
        raise bad("cells_per_step", cells_per_step, allowed)
    t_cell = _TWO_PI / (v["speed"] * v["nodes"])
    results = []
    rows = _study_rows([c * t_cell for c in cells], progress=progress, results=results,
                       load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes, **options)
    used = [r["dt"] for r in rows]
    if len(set(used)) != len(used):
        raise bad("cells_per_step", cells_per_step, "time steps that stay distinct after "
                  "snapping to the grid (see solve)")
    if len(rows) >= 2:
        ext = extrapolate(rows)
    else:
        ext = {"richardson": {k: rows[0][k] for k in STUDY_KEYS},
               "error": dict.fromkeys(STUDY_KEYS), "order": dict.fromkeys(STUDY_KEYS)}
    ok = all(r.success for r in results)
    failed = [f"dt = {c:g} T/N: {r.message}" for c, r in zip(cells, results) if not r.success]
    message = ("; ".join(failed) if failed else
               f"{len(rows)} time steps ({', '.join(f'{c:g}' for c in cells)} × T/N), "
               + ("extrapolated to dt → 0" if len(rows) >= 2 else "no extrapolation"))
    return DtExtrapolation(nodes=int(nodes), cells_per_step=tuple(cells), rows=rows,
                           richardson=ext["richardson"], error=ext["error"], order=ext["order"],
                           full_contact=bool(results[-1].full_contact), success=ok,
                           message=message, results=tuple(results))


# ----------------------------------------------------------------------------- the table
def friction_peak(*, load, ratio=RATIO, hk=HK):
    """The speed V/V0 of the largest μ on the semi-analytic road, and that μ.

    A log-spaced scan of 61 speeds over 1e-3 ≤ V/V0 ≤ 1e3, refined by bounded Brent.
    """
    from scipy.optimize import minimize_scalar

    from .. import roads  # the comparison layer reaches the roads; the adapter itself does not

    def neg_mu(lg):
        return -roads.analytic_solution({"load": load, "speed": 10.0 ** lg, "ratio": ratio,
                                         "hk": hk}).mu

    lgs = np.linspace(-3.0, 3.0, 61)
    vals = [neg_mu(x) for x in lgs]
    i = int(np.argmin(vals))
    lo, hi = lgs[max(i - 1, 0)], lgs[min(i + 1, lgs.size - 1)]
    res = minimize_scalar(neg_mu, bounds=(lo, hi), method="bounded", options={"xatol": 1e-9})
    return 10.0 ** float(res.x), -float(res.fun)


def third_code_table(*, load=0.15, ratio=RATIO, hk=HK, speeds=None, nodes=512,
                     cells_per_step=CELLS_PER_STEP, mesh_check=False, **options):
    """Tamaas against the semi-analytic road: μ per dt, order, Richardson μ, analytic μ.

    Parameters
    ----------
    load, ratio, hk : float
        The operating point (default the paper's ratio 3, hk 1 at p̃∞ = 0.15).
    speeds : sequence of float, optional
        V/V0; default below, at and above the friction peak: peak/3, peak, 3·peak, the peak
        from `friction_peak`.
    nodes : int
        Tamaas's grid.
    cells_per_step : sequence of float
        The time steps of each dt study, in cell crossings (T/N): default 4, 2, 1.
    mesh_check : bool
        Add the extrapolation at N/2 (see `dt_study`).

    Returns
    -------
    dict
        Plain data: ``inputs``, ``peak_speed``, ``peak_mu``, ``rows`` (one per speed and dt:
        speed, dt/τ, dt/T, N, μ, Δ/h, ka, steps, periods, wall time), ``summary`` (one per
        speed: μ per dt, observed order, Richardson μ and its estimated error, analytic μ,
        relative difference, Δ/h and ka extrapolated and analytic, N, wall time).
    """
    from .. import roads

    peak, peak_mu = friction_peak(load=load, ratio=ratio, hk=hk)
    if speeds is None:
        speeds = (peak / 3.0, peak, 3.0 * peak)
    rows, summary = [], []
    for sp in speeds:
        t_cell = _TWO_PI / (sp * nodes)
        st = dt_study(load=load, speed=sp, ratio=ratio, hk=hk, nodes=nodes,
                      dts=[c * t_cell for c in cells_per_step], mesh_check=mesh_check, **options)
        a = roads.analytic_solution({"load": load, "speed": sp, "ratio": ratio, "hk": hk})
        for r in st["rows"]:
            rows.append({"speed": sp, **{k: r[k] for k in (
                "dt", "dt_over_period", "nodes", "mu", "penetration", "ka", "ke_hat", "steps",
                "periods", "wall_time", "success")}})
        R, E = st["richardson"], st["error"]
        summary.append({
            "speed": sp, "nodes": nodes, "mu_per_dt": [r["mu"] for r in st["rows"]],
            "dt_over_period": [r["dt_over_period"] for r in st["rows"]],
            "order": st["order"]["mu"], "mu_richardson": R["mu"], "mu_error": E["mu"],
            "mu_analytic": a.mu,
            "relative_difference": None if R["mu"] is None else R["mu"] / a.mu - 1.0,
            "penetration_richardson": R["penetration"], "penetration_analytic": a.penetration,
            "ka_richardson": R["ka"], "ka_analytic": a.ka,
            "ke_hat_richardson": R["ke_hat"], "ke_hat_analytic": a.ke_hat,
            "mesh": None if st["mesh"] is None else st["mesh"]["difference"]["mu"],
            "wall_time": st["wall_time"], "steps": sum(r["steps"] for r in st["rows"]),
            "success": st["success"]})
    return {"inputs": {"load": load, "ratio": ratio, "hk": hk, "nodes": nodes,
                       "cells_per_step": list(cells_per_step), **options},
            "peak_speed": peak, "peak_mu": peak_mu, "rows": rows, "summary": summary,
            "tamaas_version": tamaas_version()}


def tamaas_version():
    """The version of the installed tamaas (its ``__version__``); ImportError as in `solve`."""
    return str(_import_tamaas().__version__)


def format_table(data):
    """The summary of `third_code_table` as a Markdown table (with its parameters above it)."""
    inp = data["inputs"]
    lines = [f"Tamaas {data['tamaas_version']} against the semi-analytic road: p̃∞ = "
             f"{inp['load']:g}, E∞/E0 = {inp['ratio']:g}, hk = {inp['hk']:g}, dt = "
             f"{', '.join(f'{c:g}' for c in inp['cells_per_step'])} × T/N (T the period "
             f"transit time); friction peak at V/V0 = {data['peak_speed']:.4g} (μ = "
             f"{data['peak_mu']:.5f}).",
             "",
             "| V/V0 | N | μ per dt (coarse → fine) | order | Richardson μ | est. dt error | "
             "analytic μ | relative difference | wall time |",
             "|---|---|---|---|---|---|---|---|---|"]
    for s in data["summary"]:
        order = "–" if s["order"] is None else f"{s['order']:.2f}"
        err = "–" if s["mu_error"] is None else f"{s['mu_error']:.1e}"
        rd = "–" if s["relative_difference"] is None else f"{s['relative_difference']:+.1e}"
        rich = "–" if s["mu_richardson"] is None else f"{s['mu_richardson']:.6f}"
        lines.append(f"| {s['speed']:.4g} | {s['nodes']} | "
                     f"{', '.join(f'{m:.5f}' for m in s['mu_per_dt'])} | {order} | {rich} | "
                     f"{err} | {s['mu_analytic']:.6f} | {rd} | {s['wall_time']:.0f} s |")
    return "\n".join(lines)
