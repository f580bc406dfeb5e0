"""The report's numbers: its operating points, and what each of its figures and tables shows,
read back from the results store (`comparisons.store`) beside the semi-analytic road.

Every number is nondimensional (`docs/conventions.md`): loads p̃∞ = p∞(1 − ν²)/E0, speeds V/V0 =
Vτk, penetrations Δ/h, positions x/λ, pressures σ(1 − ν²)/E0, displacements v/h, on the paper's
material E∞/E0 = `RATIO` and roughness hk = `HK`.  A BEM run that failed is None here (the report
lists it); a semi-analytic solve that fails raises.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): eqs (2.7)–(2.15)
(the semi-analytic road), eq. (3.1) (friction), figures 3–12.
"""
from __future__ import annotations

import functools
import math

import numpy as np

from viscosine import Fields

from . import roads, runner
from .convergence import observed_order
from .convergence import richardson as _richardson

# ---------------------------------------------------------------------------- operating points
RATIO, HK = 3.0, 1.0

FIG_SPEEDS = [0.01, 1.0, 2.0, 5.0, 10.0, 100.0]          # figures 4–6 (legend of figure 4)
PROFILE_SPEEDS = [0.01, 0.3, 1.0, 3.0, 100.0]             # figure 3
FIG7_PEN = [0.5, 0.8, 0.95]
FIG9_LOADS = [0.6, 0.8, 1.0, 1.2, 1.4]                    # (p̃FC)0 < p̃∞ < (p̃FC)∞
FIG12_LOADS = [0.1, 0.3, 0.6, 1.0, 1.4, 2.0]
FIELD_POINTS = [  # (label, load, speed)
    ("partial contact", 0.3, 1.0),
    ("near the transition", 0.66, 1.0),
    ("full contact", 1.0, 1.0),
]
SCALAR_EXTRA = [(0.05, 1.0), (0.3, 0.01), (0.3, 100.0), (1.3, 10.0)]  # (load, speed)
CONV_POINTS = [("partial contact, p̃∞ = 0.3, V/V0 = 1", 0.3, 1.0),
               ("near the transition, p̃∞ = 0.66, V/V0 = 1", 0.66, 1.0),
               ("full contact, p̃∞ = 1.0, V/V0 = 1", 1.0, 1.0)]


def bem_spec(load=None, speed=1.0, nodes=4096, penetration=None):
    """The spec of a BEM run of the report (`comparisons.runner.point_spec`) at p̃∞ = ``load``
    or Δ/h = ``penetration``, V/V0 = ``speed``, on ``nodes`` panels per period."""
    return runner.point_spec("bem", float(speed), load=None if load is None else float(load),
                             penetration=None if penetration is None else float(penetration),
                             ratio=RATIO, hk=HK, nodes=int(nodes))


TAMAAS_LOAD = 0.15


@functools.lru_cache(maxsize=None)
def tamaas_speeds():
    """(peak speed, peak μ, (speeds below, at and above the friction peak)) at TAMAAS_LOAD.

    The peak is the semi-analytic road's (`comparisons.peers.tamaas.friction_peak`); the three
    speeds are peak/3, peak and 3·peak rounded to four digits, so that the store's specs are
    plain, readable numbers.
    """
    from .peers import tamaas as peer
    peak, mu = peer.friction_peak(load=TAMAAS_LOAD, ratio=RATIO, hk=HK)
    return peak, mu, tuple(float(f"{v:.4g}") for v in (peak / 3.0, peak, 3.0 * peak))


def tamaas_spec(speed, nodes, cells):
    """The spec of a Tamaas run at p̃∞ = `TAMAAS_LOAD`, V/V0 = ``speed``, on ``nodes`` grid
    points, stepped by dt = ``cells`` × T/N."""
    return {"solver": "tamaas", "load": TAMAAS_LOAD, "penetration": None, "speed": float(speed),
            "ratio": RATIO, "hk": HK, "nodes": int(nodes), "cells_per_step": int(cells)}


# ---------------------------------------------------------------------------- both roads
def semi_analytic(load=None, speed=1.0, pen=None):
    """The semi-analytic solution at p̃∞ = ``load`` or Δ/h = ``pen``, V/V0 = ``speed``
    (`comparisons.roads.analytic_solution`); raises RuntimeError when it did not converge."""
    control = {"load": load} if pen is None else {"penetration": pen}
    sol = roads.analytic_solution({**control, "speed": speed, "ratio": RATIO, "hk": HK})
    if not sol.success:
        raise RuntimeError(f"semi-analytic solver failed at load={load}, Δ={pen}, V={speed}: "
                           f"{sol.message} {sol.residuals}")
    return sol


def stored(store, spec, fields=False):
    """A BEM record, or None when the run failed (failures are listed in the report)."""
    doc = store.get(spec, fields)
    return doc if doc["ok"] else None


# ---------------------------------------------------------------------------- figures 3–12
SPEED_CURVE = np.logspace(-2, 2, 121)


def profiles(store, cfg, fixed):
    """Figure 3: v/h at p̃∞ = 0.3 (``fixed="load"``) or Δ/h = 0.8 (``"penetration"``), one curve
    per speed of `PROFILE_SPEEDS`: ``speed``, ``x`` and ``displacement`` (semi-analytic) and
    ``bem`` (its ``x`` and ``displacement`` at the collocation points, None when the run failed).
    """
    X = np.linspace(-0.5, 0.5, 801)
    curves = []
    for s in PROFILE_SPEEDS:
        sol = semi_analytic(0.3, s) if fixed == "load" else semi_analytic(None, s, 0.8)
        spec = (bem_spec(0.3, s, cfg.nodes) if fixed == "load" else
                bem_spec(None, s, cfg.nodes, penetration=0.8))
        doc = stored(store, spec, True)
        bem = None
        if doc:
            f = doc["fields"]
            bem = {"x": f["x_over_lambda"], "displacement": f["displacement"]}
        curves.append({"speed": s, "x": X, "displacement": sol.fields(X).displacement,
                       "bem": bem})
    return curves


def load_sweep(store, cfg, attr, xattr):
    """Figures 4–6: ``attr`` against ``xattr`` (record keys) along the load, one curve per
    speed of `FIG_SPEEDS`: ``speed``, ``x``, ``y`` and the BEM's ``bem_x``, ``bem_y``."""
    loads = np.linspace(0.005, 1.6, 160)
    curves = []
    for s in FIG_SPEEDS:
        sols = [semi_analytic(p, s) for p in loads]
        pts = [stored(store, bem_spec(p, s, cfg.nodes)) for p in cfg.loads_bem]
        pts = [d["record"] for d in pts if d]
        curves.append({"speed": s, "x": [getattr(q, xattr) for q in sols],
                       "y": [getattr(q, attr) for q in sols],
                       "bem_x": [d[xattr] for d in pts], "bem_y": [d[attr] for d in pts]})
    return curves


def ka_at_penetrations(store, cfg):
    """Figure 7: ka against V/V0, one curve per Δ/h of `FIG7_PEN`: ``penetration``,
    ``speed``, ``ka`` and the BEM's ``bem_speed``, ``bem_ka``."""
    curves = []
    for d in FIG7_PEN:
        pts = [stored(store, bem_spec(None, s, cfg.nodes, penetration=d)) for s in cfg.speeds_bem]
        curves.append({"penetration": d, "speed": SPEED_CURVE,
                       "ka": [semi_analytic(None, s, d).ka for s in SPEED_CURVE],
                       "bem_speed": [p["record"]["speed"] for p in pts if p],
                       "bem_ka": [p["record"]["ka"] for p in pts if p]})
    return curves


def full_contact_loads(store, cfg):
    """Figure 8: the full-contact load p̃FC against V/V0: semi-analytic ``speed``, ``load``
    (|E(kV)| hk/(2E0)); the BEM's ``bem_speed``, ``bem_load`` (p̃∞ − min σ of a run in full
    contact at p̃∞ = 2: the problem is linear there); ``limits``, p̃FC at V → 0 and V → ∞."""
    xs, ys = [], []
    for s in cfg.speeds_bem:
        doc = stored(store, bem_spec(2.0, s, cfg.nodes), True)
        if doc and doc["record"]["full_contact"]:
            xs.append(s)
            ys.append(2.0 - float(np.min(doc["fields"]["pressure"])))
    return {"speed": SPEED_CURVE,
            "load": [roads.transition_load(s, RATIO, HK) for s in SPEED_CURVE],
            "bem_speed": xs, "bem_load": ys, "limits": (0.5 * HK, 0.5 * HK * RATIO)}


def speed_sweep(store, cfg, loads, attr):
    """Figures 9 and 12: ``attr`` (a record key) against V/V0, one curve per load: ``load``,
    ``speed``, ``y`` (NaN where the semi-analytic road has no value) and the BEM's
    ``bem_speed``, ``bem_y``."""
    curves = []
    for p in loads:
        sols = [semi_analytic(p, s) for s in SPEED_CURVE]
        ys = [getattr(q, attr) for q in sols]
        pts = [stored(store, bem_spec(p, s, cfg.nodes)) for s in cfg.speeds_bem]
        pts = [d["record"] for d in pts if d and d["record"][attr] is not None]
        curves.append({"load": p, "speed": SPEED_CURVE,
                       "y": [np.nan if y is None else y for y in ys],
                       "bem_speed": [d["speed"] for d in pts], "bem_y": [d[attr] for d in pts]})
    return curves


def eccentricities(store, cfg, load):
    """Figures 10 and 11: ke and kê against V/V0 at p̃∞ = ``load``: ``speed``, ``ke`` (NaN
    where undefined), ``ke_hat``; the BEM's ``bem_ke`` and ``bem_ke_hat`` as (speeds, values);
    ``threshold``, the speed of the transition to full contact."""
    sols = [semi_analytic(load, s) for s in SPEED_CURVE]
    pts = [stored(store, bem_spec(load, s, cfg.nodes)) for s in cfg.speeds_bem]
    pts = [d["record"] for d in pts if d]
    return {"speed": SPEED_CURVE, "ke": [np.nan if q.ke is None else q.ke for q in sols],
            "ke_hat": [q.ke_hat for q in sols],
            "bem_ke": ([d["speed"] for d in pts if d["ke"] is not None],
                       [d["ke"] for d in pts if d["ke"] is not None]),
            "bem_ke_hat": ([d["speed"] for d in pts], [d["ke_hat"] for d in pts]),
            "threshold": roads.threshold_speed(load, RATIO, HK)}


# ---------------------------------------------------------------------------- fields & scalars
def field_comparison(store, cfg):
    """Per field point of `FIELD_POINTS`: ``label``, ``load``, ``speed``; the semi-analytic
    ``x``, ``pressure``, ``displacement`` on a fine grid; ``bem`` (None when the run failed):
    its ``x``, ``pressure``, ``displacement`` and their differences from the semi-analytic road
    at its collocation points; ``norms`` of those differences (L2 and L∞, the pressure's over
    max σ; the BEM grid's cells weigh them)."""
    X = np.linspace(-0.5, 0.5, 1001)
    rows = []
    for label, p, s in FIELD_POINTS:
        sol = semi_analytic(p, s)
        doc = stored(store, bem_spec(p, s, cfg.nodes), True)
        bem = norms = None
        if doc:
            f = Fields.from_columns(doc["fields"])  # the BEM grid, its cells weigh the norms
            a = sol.fields(f.x_over_lambda)
            dp = f.pressure - a.pressure
            dv = f.displacement - a.displacement
            pmax = a.linf("pressure")
            norms = {"pressure_L2": f.l2(dp) / pmax, "pressure_Linf": f.linf(dp) / pmax,
                     "displacement_L2": f.l2(dv), "displacement_Linf": f.linf(dv)}
            bem = {"x": f.x_over_lambda, "pressure": f.pressure, "displacement": f.displacement,
                   "pressure_difference": dp, "displacement_difference": dv}
        af = sol.fields(X)
        rows.append({"label": label, "load": p, "speed": s, "x": X, "pressure": af.pressure,
                     "displacement": af.displacement, "bem": bem, "norms": norms})
    return rows


SCALARS = ["ka", "ke", "ke_hat", "penetration", "mu"]


def scalar_table(store, cfg):
    """Per point (the field points and `SCALAR_EXTRA`): (label, load, speed, semi-analytic
    record, BEM record or None)."""
    labels = ["light load", "low speed", "high speed", "transition at high speed"]
    pts = [(lbl, p, s) for lbl, p, s in FIELD_POINTS] + \
          [(lbl, p, s) for lbl, (p, s) in zip(labels, SCALAR_EXTRA)]
    rows = []
    for lbl, p, s in pts:
        doc = stored(store, bem_spec(p, s, cfg.nodes))
        rows.append((lbl, p, s, semi_analytic(p, s).as_dict(), doc["record"] if doc else None))
    return rows


# ---------------------------------------------------------------------------- convergence
ROUNDOFF_FLOOR = 1e-13  # errors below this (relative to the quantity) are round-off, not discretisation
ORDER_FROM = 1024       # coarser meshes do not yet resolve the memory layer ε = (V/V0)/ρ at the edges


def fit_order(N, err, scale=1.0):
    """Observed order p from a least-squares fit of log err = c − p log N over the meshes
    N ≥ 1024 whose error is above the round-off floor.  Single steps scatter with where the contact
    edge falls inside its panel; the fit over several doublings is what is meaningful."""
    N, err = np.asarray(N, float), np.asarray(err, float)
    fine = N >= min(ORDER_FROM, N.max() / 2)
    return observed_order(N[fine], err[fine], ROUNDOFF_FLOOR * abs(scale))


def richardson(N, values, order):
    """Extrapolate the last two meshes assuming error ∝ N^(−order), with their ratio
    N[-1]/N[-2] (2 when the meshes double: more when a run between them failed)."""
    if len(values) < 2:
        return float("nan")
    return _richardson(values[-2], values[-1], order, N[-1] / N[-2])


def convergence(store, cfg):
    """Errors of the BEM against the semi-analytic solution for each convergence point."""
    out = []
    for label, p, s in CONV_POINTS:
        sol = semi_analytic(p, s)
        ref = sol.as_dict()
        data = {"N": [], "ka": [], "ke": [], "penetration": [], "mu": [], "pressure": []}
        vals = {k: [] for k in ("ka", "ke", "penetration", "mu")}
        for n in cfg.conv_nodes:
            doc = stored(store, bem_spec(p, s, n), True)
            if not doc:
                continue
            rec = doc["record"]
            data["N"].append(n)
            for k in vals:
                v = rec[k]
                vals[k].append(np.nan if v is None else v)
                data[k].append(np.nan if (v is None or ref[k] is None) else abs(v - ref[k]))
            f = Fields.from_columns(doc["fields"])
            a = sol.fields(f.x_over_lambda)
            data["pressure"].append(f.l2(f.pressure - a.pressure) / a.linf("pressure"))
        scale = {k: (ref[k] if k in ref and ref[k] is not None else 1.0) for k in data}
        orders = {k: fit_order(data["N"], data[k], scale[k]) for k in ("ka", "ke", "penetration", "mu", "pressure")}
        extrap = {k: richardson(data["N"], vals[k], orders[k]) for k in vals}
        out.append({"label": label, "load": p, "speed": s, "ref": ref, "data": data, "values": vals,
                    "orders": orders, "extrapolated": extrap})
    return out


# ---------------------------------------------------------------------------- Tamaas
def tamaas_study(store, cfg):
    """The Tamaas runs read back from the store, with both roads at the same points.

    Returns
    -------
    dict
        Plain data in the shape of `comparisons.peers.tamaas.third_code_table` (``inputs``,
        ``peak_speed``, ``peak_mu``, ``summary`` per speed: ``mu_per_dt``, ``dt_over_period``,
        ``order``, ``mu_richardson``, ``mu_error``, ``mu_analytic``, ``relative_difference``),
        each summary entry also carrying ``rows`` (one per time step), ``richardson``,
        ``error`` and ``order`` of every studied quantity, the semi-analytic ``analytic`` and
        ``bem`` records, and ``seconds`` (the Tamaas runs' wall time); plus ``seconds`` in all.
    """
    from .peers import tamaas as peer
    peak, peak_mu, speeds = tamaas_speeds()
    n = cfg.tamaas_nodes
    summary, total = [], 0.0
    for sp in speeds:
        rows, seconds = [], 0.0
        for c in peer.CELLS_PER_STEP:
            doc = store.get(tamaas_spec(sp, n, c))
            seconds += doc.get("seconds") or 0.0
            rec = doc["record"] if doc["ok"] else None
            row = {"cells_per_step": c, "dt_over_period": c / n, "success": rec is not None,
                   "dt": c * 2.0 * math.pi / (sp * n), "error": doc["error"]}
            if rec is not None:
                row.update(dt=rec["dt"], dt_over_period=rec["diagnostics"]["dt_over_period"],
                           steps=rec["diagnostics"]["steps"],
                           periods=rec["diagnostics"]["periods"])
            row.update({k: (rec or {}).get(k) for k in peer.STUDY_KEYS})
            rows.append(row)
        ext = peer.extrapolate(rows)  # the peer's own Richardson step (first order)
        a = semi_analytic(TAMAAS_LOAD, sp).as_dict()
        b = stored(store, bem_spec(TAMAAS_LOAD, sp, cfg.nodes))
        mu_r = ext["richardson"]["mu"]
        summary.append({
            "speed": sp, "nodes": n, "rows": rows, "seconds": seconds,
            "mu_per_dt": [r["mu"] for r in rows],
            "dt_over_period": [r["dt_over_period"] for r in rows],
            "order": ext["order"]["mu"], "mu_richardson": mu_r, "mu_error": ext["error"]["mu"],
            "mu_analytic": a["mu"],
            "relative_difference": None if mu_r is None else mu_r / a["mu"] - 1.0,
            "richardson": ext["richardson"], "error": ext["error"], "orders": ext["order"],
            "analytic": a, "bem": None if b is None else b["record"],
            "complete": all(r["success"] for r in rows)})
        total += seconds
    return {"inputs": {"load": TAMAAS_LOAD, "ratio": RATIO, "hk": HK, "nodes": n,
                       "cells_per_step": list(peer.CELLS_PER_STEP)},
            "peak_speed": peak, "peak_mu": peak_mu, "summary": summary, "seconds": total,
            "tamaas_version": peer.tamaas_version()}
