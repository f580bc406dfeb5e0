"""`python -m comparisons report`: the cross-validation report on the paper's parameters.

Both roads are run on E∞/E0 = 3, hk = 1 and overlaid on the paper's figures 3–12 (analytic curves,
BEM markers), the fields of both roads are compared at a few operating points, and a convergence
study by mesh refinement measures the BEM's error against the semi-analytic solution, its observed
order and a Richardson extrapolation.  The material's E′, E″ and tan δ are drawn with the sliding
frequencies of the report's speeds, and a third code, Tamaas (`comparisons.peers.tamaas`), is run
below, at and above the friction peak with its time step halved twice, against both roads (when
it is not installed, its section says how to install it).  A layer of finite thickness on a rigid
foundation, bonded or frictionless (`layers_section`), is solved by the BEM alone: μ and 2a/λ
against speed per thickness at p̃∞ = 0.3, and the full-contact load against thickness beside its
closed form (`docs/layers.md`).  A rigid periodic surface sliding over the half-space
(`comparisons.report_surfaces`) is solved by the surface BEM: checks against the line contact,
its pressure map, μ against speed and direction, and Persson's theory.

Every run (BEM or Tamaas) is its own file in `DIR/results/`, written as soon as it is finished
(`store.py`), so an interrupted report loses nothing and `--resume` does not recompute what is
done.  Progress goes to standard error.  report.md is the report; report.html is the same Markdown
rendered by `comparisons._html` with its figures embedded (readable offline).

This module is the report itself: the runs it needs (`runs`), the document written from them
(`write_report`, one function per section) and `build`, which does both.  Running the runs is
`comparisons.report_runs`; the numbers each figure and table shows are
`comparisons.report_numbers`'s; the figures are drawn by `comparisons.plots`; the document's
parts and formats are `comparisons.report_doc`'s and the layer section is
`comparisons.report_layers` (both re-exported here).

References
----------
Menga, Putignano, Carbone & Demelio, The sliding contact of a rigid wavy surface with a
viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014): eq. (2.3) (the material), eq. (2.5)
(the BEM's Green's function), eqs (2.7)–(2.15) (the semi-analytic road), eq. (3.1) (friction),
figures 3–12.
"""
from __future__ import annotations

import datetime
import math
import os
import platform
import sys
import time
from dataclasses import dataclass

import numpy as np

from . import crosscheck, report_runs, report_surfaces
from . import report_numbers as numbers
from ._io import write_text
from .peers.tamaas import CELLS_PER_STEP
from .report_doc import PAPER, TAMAAS_MISSING, Doc, _fmt, _png, _reldiff, _versions  # noqa: F401
from .report_layers import layers_section
from .report_numbers import (CONV_POINTS, FIELD_POINTS, FIG7_PEN, FIG9_LOADS, FIG12_LOADS,
                             FIG_SPEEDS, HK, PROFILE_SPEEDS, RATIO, SCALAR_EXTRA, TAMAAS_LOAD,
                             bem_spec, fit_order, tamaas_spec, tamaas_speeds)
from .store import Store
from .store import key as store_key


@dataclass
class Config:
    quick: bool
    nodes: int                      # BEM mesh of the figures and the field comparisons
    speeds_bem: np.ndarray          # BEM markers along speed sweeps
    loads_bem: np.ndarray           # BEM markers along load sweeps
    conv_nodes: list                # meshes of the convergence study
    grid_nodes: list                # meshes of the cross-solver grid
    workers: int
    tamaas_nodes: int               # Tamaas's grid (its cost grows like N²: N steps of N log N)
    layer_speeds: np.ndarray = None  # the layer section's speeds (holding speeds_bem)


def config(quick, workers=None):
    w = workers or os.cpu_count() or 1
    if quick:
        return Config(True, 1024, np.logspace(-2, 2, 5), np.array([0.1, 0.3, 0.7, 1.1]),
                      [2 ** n for n in range(8, 13)], [1024, 4096], w, 128,
                      np.logspace(-2, 2, 17))
    # the layer section's speeds, 8 per decade, hold the figures' 9 (the same floats): its
    # half-space curve is the figures' runs at p̃∞ = 0.3 and 24 more between them
    return Config(False, 4096, np.logspace(-2, 2, 9),
                  np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.1, 1.3]),
                  [2 ** n for n in range(8, 17)], [2 ** n for n in range(8, 17, 2)], w, 512,
                  np.logspace(-2, 2, 33))


# ---------------------------------------------------------------------------- the runs
def bem_runs(cfg):
    """Every BEM run the report needs: list of (spec, with_fields)."""
    runs = []
    N = cfg.nodes
    for s in PROFILE_SPEEDS:                                              # figure 3
        runs.append((bem_spec(0.3, s, N), True))
        runs.append((bem_spec(None, s, N, penetration=0.8), True))
    for s in FIG_SPEEDS:                                                  # figures 4–6
        for p in cfg.loads_bem:
            runs.append((bem_spec(p, s, N), False))
    for d in FIG7_PEN:                                                    # figure 7
        for s in cfg.speeds_bem:
            runs.append((bem_spec(None, s, N, penetration=d), False))
    for s in cfg.speeds_bem:                                              # figure 8
        runs.append((bem_spec(2.0, s, N), True))
    for p in sorted(set(FIG9_LOADS + FIG12_LOADS + [0.3])):               # figures 9–12
        for s in cfg.speeds_bem:
            runs.append((bem_spec(p, s, N), False))
    for _, p, s in FIELD_POINTS:                                          # fields
        runs.append((bem_spec(p, s, N), True))
    for p, s in SCALAR_EXTRA:                                             # scalar table
        runs.append((bem_spec(p, s, N), False))
    for _, p, s in CONV_POINTS:                                           # convergence
        for n in cfg.conv_nodes:
            runs.append((bem_spec(p, s, n), True))
    for n in cfg.grid_nodes:                                              # cross-solver grid
        runs.extend((spec, False) for spec in crosscheck.specs(n))
    if tamaas_installed():                                                # third code
        for s in tamaas_speeds()[2]:
            runs.append((bem_spec(TAMAAS_LOAD, s, N), False))
    runs.extend(numbers.layer_runs(N, cfg.layer_speeds))                  # a layer
    runs.extend(report_surfaces.surface_runs(cfg.quick))                  # surfaces
    # one run per spec (its store key: a layer's spec holds a dict); it keeps its fields if any
    # figure needs them
    merged = {}
    for spec, f in runs:
        k = store_key(spec)
        merged[k] = (spec, f or merged.get(k, (spec, False))[1])
    return list(merged.values())


def runs(cfg):
    """Every run of the report (BEM, then Tamaas): list of (spec, with_fields)."""
    return bem_runs(cfg) + tamaas_runs(cfg)


def tamaas_installed():
    """True when the third code can run here (the peers extra is installed)."""
    import importlib.util
    return importlib.util.find_spec("tamaas") is not None


def tamaas_runs(cfg):
    """One run per (speed, time step): independent, so each is its own store entry."""
    if not tamaas_installed():
        return []
    return [(tamaas_spec(s, cfg.tamaas_nodes, c), False) for s in tamaas_speeds()[2]
            for c in CELLS_PER_STEP]


def execute(cfg, store, resume, scheduler=None, jobs=None):
    """Run what is missing (locally or on a Dask cluster), writing each result as it is done
    (`comparisons.report_runs.run`).

    Parameters
    ----------
    jobs : list of (spec, with_fields), optional
        Default: every run of the report (`runs`).

    Returns
    -------
    (float, str)
        The seconds spent and where the runs went (local processes or the scheduler's address).
    """
    return report_runs.run(runs(cfg) if jobs is None else jobs, store, resume, cfg.workers,
                           scheduler)


# ---------------------------------------------------------------------------- the sections
def introduction(doc, cfg, failures):
    """The title, what the report shows and on which parameters, and the runs that failed."""
    doc.h(1, "viscosine: cross-validation report")
    doc.p(f"Steady sliding of a rigid sinusoid over a standard linear solid, E∞/E0 = {RATIO:g}, hk = {HK:g} "
          f"(the parameters of {PAPER}). Lines: semi-analytic road (`analytic/`, Hunter's transformation and "
          f"the closure (2.14)–(2.15)). Markers: boundary-element road (`bem/`, eq. 2.5 discretised "
          f"directly, N = {cfg.nodes} panels per period). Units, signs and output keys: "
          f"`docs/conventions.md`. {'Quick run (coarser meshes, fewer points).' if cfg.quick else ''}")
    doc.p("Contents: the material; the paper's figures 3–12 with both roads; fields; scalars; "
          "the two roads' agreement on a grid of operating points; the BEM's convergence; "
          "a layer of finite thickness (the BEM and the closed-form full-contact load); "
          "surfaces (three-dimensional contact: checks against the line contact, the pressure "
          "map, μ against speed and direction, Persson's theory); "
          + ("a third code, Tamaas, against both roads; " if tamaas_installed() else
             "a third code, Tamaas: **not in this report**, it is not installed (see its "
             "section: `pip install '.[peers]'` from a clone, then `--resume`); ")
          + "provenance.")
    if failures:
        doc.h(2, "Runs that did not converge")
        doc.p("These operating points are missing from the figures and tables below; they were not reported as results.")
        doc.table(["spec", "error"], [[str(s), e] for s, e in failures])


def material_section(doc, folder, cfg):
    """E′, E″ and tan δ of the report's material, with the sliding frequencies of its speeds."""
    from .plots import materials
    j0, j1 = 1.0, 1.0 - 1.0 / RATIO  # the SLS as a one-term Prony series, units E0 and τ
    materials.material_figure(_png(folder, "material"), j0, [(j1, 1.0)], speeds=cfg.speeds_bem,
                              speeds_label="kV at the BEM speeds of the figures",
                              title=f"Standard linear solid, E∞/E0 = {RATIO:g}: J0 = {j0:g}, "
                                    f"J1 = {j1:.4g}, τ1 = 1 (creep time)")
    doc.img("material.png", f"Storage and loss moduli E′, E″ (units E0) and loss tangent of "
                            f"the standard linear solid with E∞/E0 = {RATIO:g} against ωτ; "
                            f"vertical lines: the sliding frequencies ωτ = kVτ = V/V0 of the BEM "
                            f"markers (V/V0 = {', '.join(f'{v:.3g}' for v in cfg.speeds_bem)})")
    doc.p(f"The paper's standard linear solid (eq. 2.3) is the one-term Prony creep function "
          f"J(t) = J0 − J1 e^(−t/τ) with J0 = 1/E0 and J1 = 1/E0 − 1/E∞ = {j1:.4g}/E0, τ the "
          "creep (retardation) time; its relaxation time is τE0/E∞ "
          "(`docs/conventions.md`, 'Creep times, not relaxation times'). A wavenumber k sliding "
          "at speed V is loaded at the frequency ω = kV, so ωτ is the speed input V/V0 itself. "
          f"E′ rises from E0 to E∞ = {RATIO:g} E0; tan δ peaks at ωτ = √(E∞/E0) = "
          f"{math.sqrt(RATIO):.4g} (tan δ = {(RATIO - 1) / (2 * math.sqrt(RATIO)):.4g}) and E″ at "
          f"ωτ = E∞/E0 = {RATIO:g}, the inverse relaxation time.")


def paper_section(doc, folder, store, cfg):
    """The paper's figures 3–12: semi-analytic lines, BEM markers."""
    from .plots import paper
    figures = [  # (file, drawing, its numbers)
        ("fig03a", paper.fig3a, lambda: numbers.profiles(store, cfg, "load")),
        ("fig03b", paper.fig3b, lambda: numbers.profiles(store, cfg, "penetration")),
        ("fig04", paper.fig4, lambda: numbers.load_sweep(store, cfg, "penetration", "load")),
        ("fig05", paper.fig5, lambda: numbers.load_sweep(store, cfg, "ka", "load")),
        ("fig06", paper.fig6, lambda: numbers.load_sweep(store, cfg, "ka", "penetration")),
        ("fig07", paper.fig7, lambda: numbers.ka_at_penetrations(store, cfg)),
        ("fig08", paper.fig8, lambda: numbers.full_contact_loads(store, cfg)),
        ("fig09", paper.fig9, lambda: numbers.speed_sweep(store, cfg, FIG9_LOADS, "ka")),
        ("fig10", paper.fig10, lambda: numbers.eccentricities(store, cfg, 0.3)),
        ("fig11", paper.fig11, lambda: numbers.eccentricities(store, cfg, 1.0)),
        ("fig12", paper.fig12, lambda: numbers.speed_sweep(store, cfg, FIG12_LOADS, "mu")),
    ]
    for name, draw, data in figures:
        title = paper.write_figure(_png(folder, name), draw, data())
        doc.img(f"{name}.png", title + f" (E∞/E0 = {RATIO:g}, hk = {HK:g}; BEM N = {cfg.nodes})")


def fields_section(doc, folder, store, cfg):
    """σ(x) and v(x) of both roads at the field points, and the norms of their difference."""
    from .plots import fields
    rows = numbers.field_comparison(store, cfg)
    fields.write_figure(_png(folder, "fields"), rows)
    doc.img("fields.png", f"Pressure and displacement, BEM (markers, N = {cfg.nodes}) and "
                          "semi-analytic (lines); bottom: BEM − semi-analytic at the BEM "
                          "collocation points")
    doc.table(["operating point", "p̃∞", "V/V0", "σ: L2 / max σ", "σ: L∞ / max σ", "v: L2 / h",
               "v: L∞ / h"],
              [[r["label"], _fmt(r["load"]), _fmt(r["speed"])]
               + ([f"{n['pressure_L2']:.2e}", f"{n['pressure_Linf']:.2e}",
                   f"{n['displacement_L2']:.2e}", f"{n['displacement_Linf']:.2e}"]
                  if n else ["—"] * 4)
               for r in rows for n in [r["norms"]]])


def scalars_section(doc, store, cfg):
    """Both roads' scalars at the field points and a few more, and their differences."""
    trows = []
    for lbl, p, s, a, b in numbers.scalar_table(store, cfg):
        for k in numbers.SCALARS:
            av = a[k]
            bv = None if b is None else b[k]
            diff = "—" if (av is None or bv is None) else (
                f"{abs(av - bv):.2e}" if k in ("ke", "ke_hat", "ka") else _reldiff(bv, av))
            trows.append([lbl, _fmt(p), _fmt(s), k, _fmt(av, 10), _fmt(bv, 10), diff])
    doc.p("Differences: absolute for ka, ke, kê; relative for Δ/h and μ. BEM at N = "
          f"{cfg.nodes}.")
    doc.table(["operating point", "p̃∞", "V/V0", "quantity", "semi-analytic", "BEM", "difference"], trows)


def agreement_section(doc, store, cfg):
    """The cross-solver grid (`comparisons.crosscheck`) read from the store: the worst
    difference of the roads per mesh, its observed order, and the mesh that meets 1e-4."""
    doc.p("Grid: " + "; ".join(f"{lbl} (ratio {r:g}, hk {h:g})" for lbl, _, _, r, h in crosscheck.GRID)
          + ". Near the transition the load is 0.99 p̃FC(V). Worst BEM − semi-analytic difference over "
          "the grid: relative for Δ/h and μ, absolute for ka, ke and kê.")

    def from_store(spec):
        doc_ = store.get(spec)
        return {"ok": doc_["ok"], "record": doc_["record"], "error": doc_["error"]}
    head, grid_rows = crosscheck.table(cfg.grid_nodes, run=from_store)
    Ng = [int(r[0]) for r in grid_rows]
    grid_rows.append(["observed order"] + [_fmt(fit_order(Ng, [float(r[j]) for r in grid_rows]), 3)
                                           for j in range(1, len(head) - 1)] + [""])
    doc.table(head, grid_rows)
    below = [int(r[0]) for r in grid_rows[:-1] if float(r[1]) < 1e-4 and float(r[2]) < 1e-4]
    doc.p("Smallest mesh of this table at which the BEM agrees with the semi-analytic road to 1e-4 "
          f"in both Δ/h and μ over the whole grid: N = {min(below) if below else 'none'}.")


def convergence_section(doc, folder, store, cfg):
    """The BEM's errors against the semi-analytic solution by mesh refinement: figure, observed
    orders and Richardson values per convergence point."""
    from .plots import convergence
    conv = numbers.convergence(store, cfg)
    convergence.write_figure(_png(folder, "convergence"), conv)
    doc.img("convergence.png", "Error of the BEM against the semi-analytic solution; observed "
                               "orders p from a log–log fit over N ≥ 1024 above round-off "
                               "(dotted: N⁻¹, dashed: N⁻²)")
    for c in conv:
        doc.h(3, c["label"])
        head = ["N", "ka error", "ke error", "Δ/h error", "μ error", "σ rel. L2 error"]
        rows_ = []
        for i, n in enumerate(c["data"]["N"]):
            rows_.append([str(n)] + [_fmt(c["data"][k][i], 3) for k in ("ka", "ke", "penetration", "mu", "pressure")])
        rows_.append(["observed order"] + [_fmt(c["orders"][k], 3) for k in ("ka", "ke", "penetration", "mu", "pressure")])
        doc.table(head, rows_)
        doc.table(["quantity", "semi-analytic", "BEM finest", "Richardson", "|Richardson − semi-analytic|"],
                  [[k, _fmt(c["ref"][k], 12), _fmt(c["values"][k][-1] if c["values"][k] else None, 12),
                    _fmt(c["extrapolated"][k], 12),
                    "—" if c["ref"][k] is None or not math.isfinite(c["extrapolated"][k])
                    else f"{abs(c['extrapolated'][k] - c['ref'][k]):.2e}"]
                   for k in ("ka", "ke", "penetration", "mu")])


def tamaas_section(doc, folder, store, cfg, timings):
    """Tamaas against both roads below, at and above the friction peak (or how to install it)."""
    if not tamaas_installed():
        doc.p(TAMAAS_MISSING)
        return
    from .plots import peers
    data = numbers.tamaas_study(store, cfg)
    timings["Tamaas runs (sum over processes)"] = data["seconds"]
    n, s0 = cfg.tamaas_nodes, data["summary"]
    speeds = ", ".join(f"{e['speed']:.4g}" for e in s0)
    doc.p(f"Tamaas {data['tamaas_version']} (`comparisons.peers.tamaas`) is a third code nobody "
          "on this project wrote: its transient viscoelastic solver (a generalised Maxwell solid, "
          "backward Euler in time, Polonsky–Keer contact on an FFT grid) is stepped until the "
          "sliding is steady, and it never sees the steady-sliding Green's function (2.5) nor "
          "Hunter's transformation. It takes relaxation times, so it is given "
          f"τE0/E∞ = τ/{RATIO:g}. Operating points: p̃∞ = {TAMAAS_LOAD:g}, E∞/E0 = {RATIO:g}, "
          f"hk = {HK:g}, at V/V0 = {speeds}: below, at and "
          f"above the friction peak of the semi-analytic road (V/V0 = {data['peak_speed']:.4g}, "
          f"μ = {data['peak_mu']:.5f}). Tamaas's grid has N = {n} nodes; each run is stepped "
          f"with dt = {', '.join(str(c) for c in CELLS_PER_STEP)} × T/N (T = λ/V the period "
          "transit time, so the indenter crosses that many cells per step). Backward Euler is "
          "first order: its error halves with dt, and the Richardson value "
          "q + (q − q_2dt) from the two finest steps removes it; what remains is Tamaas's "
          f"spatial discretisation on N = {n} nodes. The BEM is at N = {cfg.nodes}.")
    ok = [e for e in s0 if e["complete"]]
    if ok:
        # what the figure draws, not the runs' wall times (a figure is redrawn when its
        # inputs change: `plots.kept_when_unchanged`)
        drawn = ("speed", "dt_over_period", "mu_per_dt", "mu_analytic", "relative_difference")
        peers.write_figure(_png(folder, "tamaas_dt"), {
            "inputs": data["inputs"], "summary": [{k: e[k] for k in drawn} for e in ok]})
        doc.img("tamaas_dt.png", f"Relative error of Tamaas's μ against the semi-analytic road as "
                                  f"dt is halved (p̃∞ = {TAMAAS_LOAD:g}, E∞/E0 = {RATIO:g}, "
                                  f"hk = {HK:g}, N = {n}); dashed: the Richardson value's "
                                  "error; dotted: slope 1 (first order)")
    doc.p(f"Tamaas's time-step study (N = {n}): the error of μ against the semi-analytic road "
          "and its ratio to the error at twice the step (2 for first order).")
    doc.table(["V/V0", "dt", "dt/τ", "steps (periods)", "μ Tamaas", "μ/μ_analytic − 1",
               "error(2dt)/error(dt)"], _tamaas_step_rows(s0))
    doc.p("Three codes at the same operating points. Tamaas's value is its Richardson "
          "extrapolation to dt → 0 with the estimated size of the next term and the observed "
          "order in dt; differences from the semi-analytic road are relative for μ and Δ/h, "
          f"absolute for ka. BEM at N = {cfg.nodes}, Tamaas at N = {n}.")
    doc.table(["V/V0", "quantity", "semi-analytic", "BEM", "Tamaas (dt → 0)",
               "est. dt error (absolute)", "order in dt", "BEM − semi-analytic",
               "Tamaas − semi-analytic"], _three_code_rows(s0))
    doc.p(f"Cost: {sum(len(e['rows']) for e in s0)} Tamaas runs, {data['seconds']:.1f} s "
          "in all (summed over processes; each is stored as it finishes, so `--resume` does not "
          "run it again).")


def _tamaas_step_rows(summary):
    """Per speed and time step: μ of Tamaas, its error and the ratio to the error at 2dt."""
    rows = []
    for e in summary:
        prev = None
        for r in e["rows"]:
            err = None if r["mu"] is None else r["mu"] / e["mu_analytic"] - 1.0
            ratio = "—" if (prev is None or err is None or err == 0.0) else f"{prev / err:.3f}"
            rows.append([_fmt(e["speed"], 4), f"{r['cells_per_step']} × T/N",
                         _fmt(r.get("dt"), 4), "—" if not r["success"] else
                         f"{r['steps']} ({r['periods']})", _fmt(r["mu"], 8),
                         "—" if err is None else f"{err:+.3e}", ratio])
            prev = err
    return rows


def _three_code_rows(summary):
    """Per speed (below, at, above the peak) and quantity: the three codes side by side."""
    rows = []
    for e, pos in zip(summary, ["below", "at", "above"]):
        a, b = e["analytic"], e["bem"]
        for k, rel in (("mu", True), ("penetration", True), ("ka", False)):
            t, te, order = e["richardson"][k], e["error"][k], e["orders"][k]
            bv = None if b is None else b[k]
            diff = (lambda v: "—" if v is None else
                    (f"{v / a[k] - 1.0:+.2e}" if rel else f"{v - a[k]:+.2e}"))
            rows.append([f"{_fmt(e['speed'], 4)} ({pos} the peak)", {"mu": "μ", "penetration":
                         "Δ/h", "ka": "ka"}[k], _fmt(a[k], 8), _fmt(bv, 8), _fmt(t, 8),
                         "—" if te is None else f"{te:.1e}",
                         "—" if order is None else f"{order:.2f}", diff(bv), diff(t)])
    return rows


def provenance_section(doc, cfg, where, timings):
    """Date, parameters, meshes, where the runs went, the machine, the versions and
    ``timings`` (seconds by item)."""
    doc.table(["item", "value"],
              [["date (UTC)", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")],
               ["parameters", f"E∞/E0 = {RATIO:g}, hk = {HK:g}, ν enters only through p̃∞ and τ̃f"],
               ["BEM mesh (figures, fields, scalars)", str(cfg.nodes)],
               ["BEM meshes (convergence)", ", ".join(str(n) for n in cfg.conv_nodes)],
               ["mode", "quick" if cfg.quick else "full"],
               ["runs done on", where or f"{cfg.workers} local processes"],
               ["Tamaas grid (third code)", f"N = {cfg.tamaas_nodes}, dt = "
                f"{', '.join(str(c) for c in CELLS_PER_STEP)} × T/N" if tamaas_installed()
                else "Tamaas not installed"],
               ["machine", f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()}"]]
              + [[k, v] for k, v in _versions().items()]
              + [[f"time: {k}", f"{v:.1f} s"] for k, v in timings.items()])


def write_report(folder, store, cfg, timings, failures, where=None):
    """Write the figures, report.md and report.html into ``folder``; the provenance table lists
    ``timings`` (which gains the Tamaas runs' time) and the time spent here.

    ``where`` says where the runs went (local processes or a Dask scheduler), for the
    provenance table.
    """
    t_start = time.monotonic()
    doc = Doc()
    introduction(doc, cfg, failures)
    doc.h(2, "The material")
    material_section(doc, folder, cfg)
    doc.h(2, "The paper's figures, both roads")
    paper_section(doc, folder, store, cfg)
    doc.h(2, "Fields: σ(x) and v(x) from both roads")
    fields_section(doc, folder, store, cfg)
    doc.h(2, "Scalars from both roads")
    scalars_section(doc, store, cfg)
    doc.h(2, "Agreement of the two roads on a grid of operating points")
    agreement_section(doc, store, cfg)
    doc.h(2, "Convergence of the BEM by mesh refinement")
    convergence_section(doc, folder, store, cfg)
    doc.h(2, "A layer of finite thickness")
    layers_section(doc, folder, store, cfg, timings)
    doc.h(2, "Surfaces: a rigid periodic surface sliding (three-dimensional contact)")
    report_surfaces.surfaces_section(doc, folder, store, cfg, timings, _png)
    doc.h(2, "A third code: Tamaas")
    tamaas_section(doc, folder, store, cfg, timings)
    doc.h(2, "Provenance")
    provenance_section(doc, cfg, where,
                       timings | {"figures and tables": time.monotonic() - t_start})
    write_text(os.path.join(folder, "report.md"), doc.markdown())
    write_text(os.path.join(folder, "report.html"), doc.html(folder))


def build(out, *, quick=False, workers=None, resume=False, scheduler=None) -> int:
    """Run what the report needs (`execute`) and write it into the folder ``out``.

    Returns
    -------
    int
        The runs that failed (each named in the report).
    """
    t0 = time.monotonic()
    cfg = config(quick, workers)
    os.makedirs(out, exist_ok=True)
    store = Store(os.path.join(out, "results"))
    seconds, where = execute(cfg, store, resume, scheduler)
    timings = {"runs (wall)": seconds}
    failures = [(spec, doc["error"]) for spec, _ in runs(cfg)
                for doc in [store.get(spec)] if not doc["ok"]]
    print("report: figures and tables", file=sys.stderr)
    write_report(out, store, cfg, timings, failures, where)
    print(f"report: wrote {os.path.join(out, 'report.md')} and report.html in "
          f"{time.monotonic() - t0:.0f} s", file=sys.stderr)
    if not tamaas_installed():
        print("report: without the Tamaas section (the third code is not installed; from a "
              "clone: pip install '.[peers]', then the same command with --resume)",
              file=sys.stderr)
    return len(failures)
