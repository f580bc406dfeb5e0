"""The report's numbers: what each of its figures and tables shows, read back from the results
store (`comparisons.store`) beside the semi-analytic road, at its operating points
(`comparisons.report_specs`, re-exported here).

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

import math

import numpy as np

from viscosine import Fields

from . import operating_point as op
from . import roads
from .convergence import observed_order
from .convergence import richardson as _richardson

# the report's operating points and the two roads read back at them (`comparisons.report_specs`)
from .report_specs import (CONV_POINTS, FIELD_POINTS, FIG7_PEN, FIG9_LOADS,  # noqa: F401
                           FIG12_LOADS, FIG_SPEEDS, HK, PROFILE_SPEEDS, RATIO, SCALAR_EXTRA,
                           TAMAAS_LOAD, bem_spec, semi_analytic, stored, tamaas_spec,
                           tamaas_speeds)


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


# ---------------------------------------------------------------------------- a layer
#: the layer section's operating point: the report's load of figure 12 (and of the README)
LAYER_LOAD = 0.3
#: Poisson ratio of every layer of the section.  The bonded layer's factor S_B and its uniform
#: mode depend on ν (½: incompressible, the stiffest thin layer); the frictionless layer's S_F and
#: its uniform compression (free ends: C = 1 in (1 − ν²)d/E) do not, so that in the report's
#: dimensionless numbers (p̃ = p(1 − ν²)/E0) a frictionless layer's answer is the same for
#: every ν (docs/layers.md §1, §4; tests/comparisons/test_report_layers.py checks it bit for bit)
LAYER_NU = 0.5
#: d/λ of the friction and contact figures, per foundation (None: the half-space).  At
#: p̃∞ = 0.3 a frictionless layer thinner than d/λ ≈ 0.15 is compressed as a whole so far
#: (its uniform mode: strain p̃∞ with free ends) that below V/V0 ≈ 1 the indenter's crest
#: would reach the foundation (the BEM refuses such an answer; measured at N = 4096: d/λ = 0.1
#: from V/V0 ≤ 0.56, d/λ = 0.05 from V/V0 ≤ 1.8), so its panel starts at d/λ = 0.2
LAYER_THICKNESSES = {"bonded": (0.05, 0.1, 0.2, 0.5, 1.0, None),
                     "frictionless": (0.2, 0.5, 1.0, None)}
#: the full-contact figure: closed-form curves of p̃FC against d/λ at these speeds, BEM markers
#: (Δ/h = 1) at `LAYER_FC_MARKERS`
LAYER_FC_SPEEDS = (0.01, 1.0, 100.0)
LAYER_FC_MARKERS = (0.02, 0.05, 0.1, 0.2, 0.5, 1.0)
LAYER_FC_CURVE = np.logspace(math.log10(0.02), math.log10(2.0), 61)
#: amplitude of the BEM's full-contact markers.  Full contact is linear in the amplitude (σ =
#: p̃∞ + hk × a function of V and kd: Appendix B), so p̃FC/hk does not depend on hk; at hk = 1
#: the crest of most of these layers would reach the foundation (`full_contact_clears`), at
#: hk = 0.01 it clears every one of them (the thinnest, frictionless d/λ = 0.02 at V/V0 = 100,
#: needs hk < 0.03)
LAYER_FC_HK = 0.01


def layer_description(d_over_lambda, foundation):
    """The plain description of the section's layer (`comparisons.roads.layer`); None for the
    half-space (``d_over_lambda`` None)."""
    if d_over_lambda is None:
        return None
    return {"thickness_over_wavelength": float(d_over_lambda), "foundation": foundation,
            "nu": LAYER_NU}


def layer_spec(load=None, speed=1.0, nodes=4096, d_over_lambda=None, foundation="bonded",
               penetration=None, hk=HK):
    """The spec of a BEM run of the layer section: `bem_spec` with the layer's description
    (``layer``, read by `comparisons.roads`) and the amplitude ``hk``.  On the half-space
    (``d_over_lambda`` None) at the report's hk it *is* `bem_spec`, so that the section's
    half-space runs are the same store entries as the figures' above."""
    return op.at("bem", float(speed), load=None if load is None else float(load),
                 penetration=None if penetration is None else float(penetration),
                 ratio=RATIO, hk=float(hk), nodes=int(nodes),
                 layer=layer_description(d_over_lambda, foundation))


def full_contact_clears(d_over_lambda, foundation, p_fc, hk=HK):
    """True when, in full contact at the load ``p_fc`` (= p̃FC), the indenter's crest stays
    above the foundation of the section's layer: approach·h < d, with the approach (over h) of
    ``docs/layers.md`` §7, Δ/h + C kd J0 p̃/hk = 1 + C kd p̃FC/hk (J0 = 1/E0 for the standard
    linear solid; C of §4: (1 − 2ν)/(1 − ν)² bonded, 0 at ν = ½, and 1 frictionless with free
    ends).  The BEM refuses an answer whose crest reaches the foundation; linear theory has no
    such limit, the body does."""
    kd = 2.0 * math.pi * float(d_over_lambda)
    return hk + uniform_compliance(foundation) * kd * p_fc < kd


def uniform_compliance(foundation):
    """C of the section's layer (``docs/layers.md`` §4, free ends): the uniform compression
    under a mean pressure p̃ is C d p̃ J0; (1 − 2ν)/(1 − ν)² bonded (0 at ν = ½), 1
    frictionless.  The BEM reports its own in ``diagnostics["layer"]["uniform_compliance"]``
    (tests/comparisons/test_report_layers.py compares them)."""
    if foundation == "frictionless":
        return 1.0
    return (1.0 - 2.0 * LAYER_NU) / (1.0 - LAYER_NU) ** 2


def layer_runs(nodes, speeds):
    """Every BEM run of the layer section: list of (spec, with_fields), no fields.

    μ and 2a/λ at p̃∞ = `LAYER_LOAD` at ``speeds`` on ``nodes`` panels for every layer of
    `LAYER_THICKNESSES` (the half-space's are the report's own runs when ``speeds`` holds the
    figures' speeds); the full-contact load (Δ/h = 1) at `LAYER_FC_HK` on every marker layer
    and speed, and at the report's hk where the layer has no uniform compression (C = 0: the
    bonded incompressible layer, whose approach is Δ/h = 1 exactly) and clears it (d > h,
    `full_contact_clears`; with C > 0 whether it clears depends on p̃FC, an output).
    """
    out = []
    for foundation, ds in LAYER_THICKNESSES.items():
        for d in ds:
            if d is None and foundation != next(iter(LAYER_THICKNESSES)):
                continue  # the half-space is in every panel: its runs once
            out += [(layer_spec(LAYER_LOAD, s, nodes, d, foundation), False) for s in speeds]
    for foundation in LAYER_THICKNESSES:
        for d in LAYER_FC_MARKERS:
            for s in LAYER_FC_SPEEDS:
                out.append((layer_spec(None, s, nodes, d, foundation, penetration=1.0,
                                       hk=LAYER_FC_HK), False))
                if uniform_compliance(foundation) == 0.0 and full_contact_clears(d, foundation,
                                                                                   0.0):
                    out.append((layer_spec(None, s, nodes, d, foundation, penetration=1.0),
                                False))
    return out


def layer_of(rec):
    """The layer a BEM record describes (thickness, foundation, ν, uniform compliance, mean
    displacement, approach): the record's ``layer``, or where older records kept it,
    ``diagnostics["layer"]``; None on the half-space."""
    return rec.get("layer") or (rec.get("diagnostics") or {}).get("layer")


def _peak(speeds, values):
    """(speed, value) of the largest of positive sampled values: the vertex of the parabola in
    (log V, log value) through the largest sample and its two neighbours (the sample itself at
    an end).  On figure 12's μ at p̃∞ = 0.3, 8 speeds per decade, it is off the semi-analytic
    peak by 7e-5 in μ and 1.4e-3 in V/V0 (relative); 4 per decade, 4.5e-3 and 2.5e-3."""
    v = np.log(np.asarray(values, float))
    x = np.log10(np.asarray(speeds, float))
    i = int(np.nanargmax(v))
    if i == 0 or i == v.size - 1 or not np.all(np.isfinite(v[i - 1:i + 2])):
        return float(speeds[i]), float(np.exp(v[i]))
    a, b, c = np.polyfit(x[i - 1:i + 2], v[i - 1:i + 2], 2)
    return float(10.0 ** (-b / (2.0 * a))), float(np.exp(c - b * b / (4.0 * a)))


def layer_sweeps(store, cfg):
    """The friction and contact figures of the layer section: μ and 2a/λ against V/V0 at
    p̃∞ = `LAYER_LOAD` for every layer of `LAYER_THICKNESSES`.

    Returns
    -------
    dict
        ``load``, ``nu``, ``nodes``; ``curves``: per foundation, one dict per thickness
        (``d_over_lambda``, None for the half-space; ``speed``, ``mu``, ``contact_fraction``
        and their ``mu_error`` and ``contact_fraction_error`` (both relative), the BEM's
        own estimates, None where it gives none; ``peak`` (V/V0, μ) by `_peak`; ``failed``,
        the speeds whose run failed); ``analytic``: the semi-analytic half-space (``speed``,
        ``mu``, ``contact_fraction`` = ka/π, ``peak`` its friction peak) and ``half_space_mu``,
        the largest relative difference of the BEM's half-space μ from it.
    """
    from .peers import tamaas as peer  # the semi-analytic road's friction peak
    curves = {}
    for foundation, ds in LAYER_THICKNESSES.items():
        curves[foundation] = []
        for d in ds:
            c = {"d_over_lambda": d, "speed": [], "mu": [], "contact_fraction": [],
                 "mu_error": [], "contact_fraction_error": [], "failed": []}
            for s in cfg.layer_speeds:
                doc = stored(store, layer_spec(LAYER_LOAD, s, cfg.nodes, d, foundation))
                if doc is None:
                    c["failed"].append(float(s))
                    continue
                rec = doc["record"]
                est = rec.get("error_estimate") or {}
                c["speed"].append(float(s))
                c["mu"].append(rec["mu"])
                c["contact_fraction"].append(rec["contact_fraction"])
                c["mu_error"].append(est.get("mu"))
                c["contact_fraction_error"].append(est.get("contact_fraction"))
            c["peak"] = _peak(c["speed"], c["mu"]) if c["mu"] else (None, None)
            curves[foundation].append(c)
    sols = [semi_analytic(LAYER_LOAD, s) for s in SPEED_CURVE]
    half = next(c for c in curves["bonded"] if c["d_over_lambda"] is None)
    diff = [abs(m / semi_analytic(LAYER_LOAD, s).mu - 1.0)
            for s, m in zip(half["speed"], half["mu"])]
    return {"load": LAYER_LOAD, "nu": LAYER_NU, "nodes": cfg.nodes, "curves": curves,
            "analytic": {"speed": SPEED_CURVE, "mu": [q.mu for q in sols],
                         "contact_fraction": [q.ka / math.pi for q in sols],
                         "peak": peer.friction_peak(load=LAYER_LOAD, ratio=RATIO, hk=HK)},
            "half_space_mu": max(diff) if diff else None}


def layer_full_contact(store, cfg):
    """The full-contact figure of the layer section: p̃FC against d/λ at `LAYER_FC_SPEEDS`.

    Returns
    -------
    dict
        ``d_over_lambda`` (the curves' abscissae); ``curves``: per foundation, one dict per
        speed: ``speed``, ``load`` (the closed form, `comparisons.roads.full_contact_load`),
        ``clears`` (`full_contact_clears` at the report's hk, per abscissa), ``half_space``
        (p̃FC of the half-space, `comparisons.roads.transition_load`), ``markers``: one dict
        per marker thickness with ``d_over_lambda``, ``closed_form``, ``bem`` (the BEM's load at
        Δ/h = 1 and hk = `LAYER_FC_HK`, times HK/hk; None when the run failed), ``bem_error``
        (its estimate, relative, scaled alike; None without one), ``bem_hk1`` (at the report's
        hk, None where not run or failed), ``approach`` (the BEM's at hk = `LAYER_FC_HK`).
    """
    curves = {}
    scale = HK / LAYER_FC_HK
    for foundation in LAYER_THICKNESSES:
        curves[foundation] = []
        for s in LAYER_FC_SPEEDS:
            load = [roads.full_contact_load(s, RATIO, HK, layer_description(d, foundation))
                    for d in LAYER_FC_CURVE]
            markers = []
            for d in LAYER_FC_MARKERS:
                doc = stored(store, layer_spec(None, s, cfg.nodes, d, foundation,
                                               penetration=1.0, hk=LAYER_FC_HK))
                rec = doc["record"] if doc else None
                est = ((rec or {}).get("error_estimate") or {}).get("load")
                hk1 = None
                if uniform_compliance(foundation) == 0.0 and full_contact_clears(d, foundation,
                                                                                   0.0):
                    doc1 = stored(store, layer_spec(None, s, cfg.nodes, d, foundation,
                                                    penetration=1.0))
                    hk1 = doc1["record"]["load"] if doc1 else None
                markers.append({
                    "d_over_lambda": d,
                    "closed_form": roads.full_contact_load(s, RATIO, HK,
                                                           layer_description(d, foundation)),
                    "bem": None if rec is None else rec["load"] * scale,
                    "bem_error": est, "bem_hk1": hk1,
                    "approach": None if rec is None else layer_of(rec)["approach"]})
            curves[foundation].append({
                "speed": s, "load": load,
                "clears": [full_contact_clears(d, foundation, p) for d, p in
                           zip(LAYER_FC_CURVE, load)],
                "half_space": roads.transition_load(s, RATIO, HK), "markers": markers})
    return {"d_over_lambda": LAYER_FC_CURVE, "curves": curves}


def layer_findings(sweeps, fc):
    """What the layer section's figures show, as numbers (from `layer_sweeps` and
    `layer_full_contact`).

    Returns
    -------
    dict
        ``thinnest``: per foundation, the thinnest layer's ``d_over_lambda``, its friction
        ``peak`` and the half-space's (V/V0, μ), ``crossing`` (the V/V0 where its μ meets the
        half-space's, interpolated in log V: below it the layer's μ is the larger; None when the
        curves do not cross), ``mu_ratio_low`` and ``mu_ratio_high`` (its μ over the
        half-space's at the lowest and highest speed) and ``contact_ratio`` (its 2a/λ over the
        half-space's, smallest and largest over the speeds); ``exponent``: per foundation, the
        slope −d log p̃FC/d log d between the two thinnest markers at V/V0 = 1 (3 for a squeezed
        incompressible film, 1 for a thin frictionless layer); ``speed_spread``: per foundation,
        the largest relative spread over the speeds of the BEM's p̃FC on a layer over the
        half-space's closed-form p̃FC, at one thickness (0 up to the BEM's error when the layer
        only rescales p̃FC(V), mode 1 alone carrying full contact: it is 1/S(kd)).
    """
    thinnest, exponent, spread = {}, {}, {}
    for f, cs in sweeps["curves"].items():
        half = next(c for c in cs if c["d_over_lambda"] is None)
        thin = min((c for c in cs if c["d_over_lambda"] is not None),
                   key=lambda c: c["d_over_lambda"])
        hmu = dict(zip(half["speed"], half["mu"]))
        hcf = dict(zip(half["speed"], half["contact_fraction"]))
        sp = [s for s in thin["speed"] if s in hmu]
        r = [m / hmu[s] for s, m in zip(thin["speed"], thin["mu"]) if s in hmu]
        crossing = None
        for i in range(len(r) - 1):
            if (r[i] - 1.0) * (r[i + 1] - 1.0) < 0.0:
                x0, x1 = math.log10(sp[i]), math.log10(sp[i + 1])
                crossing = 10.0 ** (x0 + (1.0 - r[i]) * (x1 - x0) / (r[i + 1] - r[i]))
                break
        cr = [c / hcf[s] for s, c in zip(thin["speed"], thin["contact_fraction"]) if s in hcf]
        thinnest[f] = {"d_over_lambda": thin["d_over_lambda"], "peak": thin["peak"],
                       "half_space_peak": half["peak"], "crossing": crossing,
                       "mu_ratio_low": r[0] if r else None, "mu_ratio_high": r[-1] if r else None,
                       "contact_ratio": (min(cr), max(cr)) if cr else (None, None)}
    for f, cs in fc["curves"].items():
        one = next(c for c in cs if c["speed"] == 1.0)
        (d1, p1), (d2, p2) = [(q["d_over_lambda"], q["closed_form"]) for q in one["markers"][:2]]
        exponent[f] = math.log(p1 / p2) / math.log(d2 / d1)
        ratios = np.array([[np.nan if q["bem"] is None else q["bem"] / c["half_space"]
                            for q in c["markers"]] for c in cs])
        spread[f] = float(np.nanmax(np.ptp(ratios, axis=0) / np.min(ratios, axis=0)))
    return {"thinnest": thinnest, "exponent": exponent, "speed_spread": spread}
