"""`python -m comparisons report`: the cross-validation report on the paper's parameters.

Both roads are run on E∞/E0 = 3, hk = 1 and overlaid on the paper's figures 3–12 (analytic curves,
BEM markers), the fields of both roads are compared at a few operating points, and a convergence
study by mesh refinement measures the BEM's error against the semi-analytic solution, its observed
order and a Richardson extrapolation.  The material's E′, E″ and tan δ are drawn with the sliding
frequencies of the report's speeds, and a third code, Tamaas (`comparisons.peers.tamaas`), is run
below, at and above the friction peak with its time step halved twice, against both roads (when
it is not installed, its section says how to install it).

Every run (BEM or Tamaas) is its own file in `DIR/results/`, written as soon as it is finished
(`store.py`), so an interrupted report loses nothing and `--resume` does not recompute what is
done.  Progress goes to standard error.  report.md is the report; report.html is the same Markdown
rendered by `comparisons._html` with its figures embedded (readable offline).

References
----------
Menga, Putignano, Carbone & Demelio, The sliding contact of a rigid wavy surface with a
viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014): eq. (2.3) (the material), eq. (2.5)
(the BEM's Green's function), eqs (2.7)–(2.15) (the semi-analytic road), eq. (3.1) (friction),
figures 3–12.
"""
from __future__ import annotations

import datetime
import functools
import math
import os
import platform
import sys
import time
from dataclasses import dataclass, field

import numpy as np

from viscosine import Fields

from . import _html, crosscheck, gate, roads, runner
from ._io import write_text
from .convergence import observed_order
from .convergence import richardson as _richardson
from .store import Store

RATIO, HK = 3.0, 1.0


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


def config(quick, workers=None):
    w = workers or os.cpu_count() or 1
    if quick:
        return Config(True, 1024, np.logspace(-2, 2, 5), np.array([0.1, 0.3, 0.7, 1.1]),
                      [2 ** n for n in range(8, 13)], [1024, 4096], w, 128)
    return Config(False, 4096, np.logspace(-2, 2, 9),
                  np.array([0.05, 0.1, 0.2, 0.3, 0.5, 0.7, 0.9, 1.1, 1.3]),
                  [2 ** n for n in range(8, 17)], [2 ** n for n in range(8, 17, 2)], w, 512)


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


def _bem(load=None, speed=1.0, nodes=4096, penetration=None):
    return runner.point_spec("bem", float(speed), load=None if load is None else float(load),
                             penetration=None if penetration is None else float(penetration),
                             ratio=RATIO, hk=HK, nodes=int(nodes))


# ---------------------------------------------------------------------------- the BEM runs
def bem_runs(cfg):
    """Every BEM run the report needs: list of (spec, with_fields)."""
    runs = []
    N = cfg.nodes
    for s in PROFILE_SPEEDS:                                              # figure 3
        runs.append((_bem(0.3, s, N), True))
        runs.append((_bem(None, s, N, penetration=0.8), True))
    for s in FIG_SPEEDS:                                                  # figures 4–6
        for p in cfg.loads_bem:
            runs.append((_bem(p, s, N), False))
    for d in FIG7_PEN:                                                    # figure 7
        for s in cfg.speeds_bem:
            runs.append((_bem(None, s, N, penetration=d), False))
    for s in cfg.speeds_bem:                                              # figure 8
        runs.append((_bem(2.0, s, N), True))
    for p in sorted(set(FIG9_LOADS + FIG12_LOADS + [0.3])):               # figures 9–12
        for s in cfg.speeds_bem:
            runs.append((_bem(p, s, N), False))
    for _, p, s in FIELD_POINTS:                                          # fields
        runs.append((_bem(p, s, N), True))
    for p, s in SCALAR_EXTRA:                                             # scalar table
        runs.append((_bem(p, s, N), False))
    for _, p, s in CONV_POINTS:                                           # convergence
        for n in cfg.conv_nodes:
            runs.append((_bem(p, s, n), True))
    for n in cfg.grid_nodes:                                              # cross-solver grid
        runs.extend((spec, False) for spec in crosscheck.specs(n))
    if tamaas_installed():                                                # third code
        for s in tamaas_speeds()[2]:
            runs.append((_bem(TAMAAS_LOAD, s, N), False))
    # one run per spec; it keeps its fields if any figure needs them
    merged = {}
    for spec, f in runs:
        k = tuple(sorted(spec.items()))
        merged[k] = (spec, f or merged.get(k, (spec, False))[1])
    return list(merged.values())


def runs(cfg):
    """Every run of the report (BEM, then Tamaas): list of (spec, with_fields)."""
    return bem_runs(cfg) + tamaas_runs(cfg)


def _run_one(job):
    spec, with_fields = job
    if spec["solver"] == "tamaas":
        return spec, with_fields, run_tamaas(spec)
    return spec, with_fields, runner.run(spec, fields=with_fields)


def _cost(spec):
    """A rough relative cost, to start the long runs first (they then overlap the short ones)."""
    if spec["solver"] == "tamaas":
        # N/c steps per period of an N log N solve; more periods to steady at higher speed
        # (measured: 3, 4 and 8 periods at V/V0 = 0.35, 1.06 and 3.2)
        periods = 3.0 + 1.6 * max(spec["speed"] - 0.3, 0.0)
        return 10.0 * periods * spec["nodes"] ** 2 / spec["cells_per_step"]
    return float(spec["nodes"])


def execute(cfg, store, resume, scheduler=None, jobs=None):
    """Run what is missing (locally or on a Dask cluster), writing each result as it is done.

    Parameters
    ----------
    jobs : list of (spec, with_fields), optional
        Default: every run of the report (`runs`).

    Returns
    -------
    (float, str)
        The seconds spent and where the runs went (local processes or the scheduler's address).
    """
    from . import _cluster
    jobs = runs(cfg) if jobs is None else jobs
    todo = [j for j in jobs if not (resume and store.has(*j))]
    todo.sort(key=lambda j: -_cost(j[0]))
    counts = []
    for solver, name in (("bem", "BEM"), ("tamaas", "Tamaas")):
        n = sum(j[0]["solver"] == solver for j in jobs)
        if n or solver == "bem":
            done = n - sum(j[0]["solver"] == solver for j in todo)
            counts.append(f"{n} {name} runs, {done} already done")
    print(f"report: {'; '.join(counts)}", file=sys.stderr)
    t0 = time.monotonic()
    where = "none (every result read from the store)"
    if todo:
        workers = None if scheduler else cfg.workers
        with _cluster.executor(workers, scheduler) as ex:
            where = (f"Dask scheduler {scheduler} ({ex.workers} workers)" if scheduler else
                     f"{ex.workers} local processes" if ex.workers > 1 else "this process")
            for i, (k, value) in enumerate(ex.imap(_run_one, todo, ordered=False), 1):
                spec, f = todo[k]
                if isinstance(value, _cluster.Failure):  # the worker died: a failed run
                    out = {"ok": False, "record": None, "error": value.error, "seconds": 0.0}
                else:
                    out = value[2]
                store.put(spec, out, f)
                _progress(i, len(todo), t0, spec, out)
    return time.monotonic() - t0, where


def _progress(i, n, t0, spec, out):
    what = f"load={spec['load']}" if spec["load"] is not None else f"Δ/h={spec['penetration']}"
    if spec["solver"] == "tamaas":
        solver = f"tamaas N={spec['nodes']} dt={spec['cells_per_step']}·T/N"
    else:
        solver = f"bem N={spec['nodes']}"
    status = "ok" if out["ok"] else "FAILED"
    print(f"report: [{i}/{n}] {solver} {what} V/V0={spec['speed']:.4g} "
          f"{status} {out['seconds']:.2f} s ({time.monotonic() - t0:.0f} s)", file=sys.stderr)


# ---------------------------------------------------------------------------- Tamaas
TAMAAS_LOAD = 0.15
TAMAAS_CELLS = (4, 2, 1)  # dt = c·T/N (T = λ/V): the step halved twice, for a first-order study


def tamaas_installed():
    """True when the third code can run here (the peers extra is installed)."""
    import importlib.util
    return importlib.util.find_spec("tamaas") is not None


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


def _tamaas(speed, nodes, cells):
    return {"solver": "tamaas", "load": TAMAAS_LOAD, "penetration": None, "speed": float(speed),
            "ratio": RATIO, "hk": HK, "nodes": int(nodes), "cells_per_step": int(cells)}


def tamaas_runs(cfg):
    """One run per (speed, time step): independent, so each is its own store entry."""
    if not tamaas_installed():
        return []
    return [(_tamaas(s, cfg.tamaas_nodes, c), False) for s in tamaas_speeds()[2]
            for c in TAMAAS_CELLS]


def run_tamaas(spec):
    """One Tamaas run to steady sliding, as a store document (never raises)."""
    from .peers import tamaas as peer
    t0 = time.perf_counter()
    dt = spec["cells_per_step"] * 2.0 * math.pi / (spec["speed"] * spec["nodes"])
    try:
        res = peer.solve(load=spec["load"], speed=spec["speed"], ratio=spec["ratio"],
                         hk=spec["hk"], nodes=spec["nodes"], dt=dt)
        rec = res.as_dict()
        why = gate.check_record(rec, spec)
    except Exception as exc:  # a failure of the third code is this run's result
        text = str(exc).strip().splitlines()
        rec, why = None, f"{type(exc).__name__}: {text[0] if text else 'Tamaas failed'}"
    return {"ok": why is None, "record": rec if why is None else None, "error": why,
            "seconds": time.perf_counter() - t0}


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
        for c in TAMAAS_CELLS:
            doc = store.get(_tamaas(sp, n, c))
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
        a = _solve(TAMAAS_LOAD, sp).as_dict()
        b = _get(store, _bem(TAMAAS_LOAD, sp, cfg.nodes))
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
                       "cells_per_step": list(TAMAAS_CELLS)},
            "peak_speed": peak, "peak_mu": peak_mu, "summary": summary, "seconds": total,
            "tamaas_version": _tamaas_version()}


def _tamaas_version():
    try:
        from importlib.metadata import version
        return version("tamaas")
    except Exception:  # pragma: no cover - an unusual install: the module still says
        import tamaas
        return str(getattr(tamaas, "__version__", "unknown"))


# ---------------------------------------------------------------------------- analytic curves
def _solve(load=None, speed=1.0, pen=None):
    control = {"load": load} if pen is None else {"penetration": pen}
    sol = roads.analytic_solution({**control, "speed": speed, "ratio": RATIO, "hk": HK})
    if not sol.success:
        raise RuntimeError(f"semi-analytic solver failed at load={load}, Δ={pen}, V={speed}: "
                           f"{sol.message} {sol.residuals}")
    return sol


def _get(store, spec, fields=False):
    """A BEM record, or None when the run failed (failures are listed in the report)."""
    doc = store.get(spec, fields)
    return doc if doc["ok"] else None


# ---------------------------------------------------------------------------- figures
def _style(ax, xlabel, ylabel, title, logx=False):
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    return ax


def _colors(n):
    import matplotlib.pyplot as plt
    return plt.cm.viridis(np.linspace(0.0, 0.9, n))


def fig3(ax, store, cfg, fixed):
    """Deformed profile v/h for several V/V0 at p̃∞ = 0.3 (a) or Δ/h = 0.8 (b)."""
    X = np.linspace(-0.5, 0.5, 801)
    for c, s in zip(_colors(len(PROFILE_SPEEDS)), PROFILE_SPEEDS):
        sol = _solve(0.3, s) if fixed == "load" else _solve(None, s, 0.8)
        ax.plot(X, sol.fields(X).displacement, color=c, lw=1.2, label=f"V/V0 = {s:g}")
        spec = _bem(0.3, s, cfg.nodes) if fixed == "load" else _bem(None, s, cfg.nodes, penetration=0.8)
        doc = _get(store, spec, True)
        if doc:
            f = doc["fields"]
            step = max(1, len(f["x_over_lambda"]) // 48)
            ax.plot(f["x_over_lambda"][::step], f["displacement"][::step], "o", ms=3, color=c, mfc="none")
    ax.invert_yaxis()  # displacement is positive into the body: draw the surface as seen
    what = "p̃∞ = 0.3" if fixed == "load" else "Δ/h = 0.8"
    _style(ax, "x/λ (crest at 0, sliding toward +x)", "v/h (into the body)",
           f"Figure 3{'a' if fixed == 'load' else 'b'}: deformed profile at {what}")
    ax.legend(fontsize=7)
    return ax


def _load_sweep(ax, store, cfg, attr, xattr, ylabel, xlabel, title):
    loads = np.linspace(0.005, 1.6, 160)
    for c, s in zip(_colors(len(FIG_SPEEDS)), FIG_SPEEDS):
        sols = [_solve(p, s) for p in loads]
        xs = [getattr(q, xattr) for q in sols]
        ys = [getattr(q, attr) for q in sols]
        ax.plot(xs, ys, color=c, lw=1.2, label=f"V/V0 = {s:g}")
        pts = [_get(store, _bem(p, s, cfg.nodes)) for p in cfg.loads_bem]
        pts = [d["record"] for d in pts if d]
        ax.plot([d[xattr] for d in pts], [d[attr] for d in pts], "o", ms=4, color=c, mfc="none")
    _style(ax, xlabel, ylabel, title)
    ax.legend(fontsize=7)
    return ax


def fig4(ax, store, cfg):
    return _load_sweep(ax, store, cfg, "penetration", "load", "Δ/h", "p̃∞",
                       "Figure 4: penetration against load")


def fig5(ax, store, cfg):
    return _load_sweep(ax, store, cfg, "ka", "load", "ka", "p̃∞", "Figure 5: contact half-width against load")


def fig6(ax, store, cfg):
    return _load_sweep(ax, store, cfg, "ka", "penetration", "ka", "Δ/h",
                       "Figure 6: contact half-width against penetration")


SPEED_CURVE = np.logspace(-2, 2, 121)


def fig7(ax, store, cfg):
    for c, d in zip(_colors(len(FIG7_PEN)), FIG7_PEN):
        ax.plot(SPEED_CURVE, [_solve(None, s, d).ka for s in SPEED_CURVE], color=c, lw=1.2,
                label=f"Δ/h = {d:g}")
        pts = [_get(store, _bem(None, s, cfg.nodes, penetration=d)) for s in cfg.speeds_bem]
        ax.plot([p["record"]["speed"] for p in pts if p], [p["record"]["ka"] for p in pts if p],
                "o", ms=4, color=c, mfc="none")
    _style(ax, "V/V0", "ka", "Figure 7: contact half-width against speed at fixed penetration", logx=True)
    ax.legend(fontsize=7)
    return ax


def fig8(ax, store, cfg):
    ax.plot(SPEED_CURVE, [roads.transition_load(s, RATIO, HK) for s in SPEED_CURVE], "k-",
            lw=1.2, label="semi-analytic |E(kV)| hk/(2E0)")
    xs, ys = [], []
    for s in cfg.speeds_bem:  # BEM: in full contact p̃FC = p̃∞ − min σ (the problem is linear)
        doc = _get(store, _bem(2.0, s, cfg.nodes), True)
        if doc and doc["record"]["full_contact"]:
            xs.append(s)
            ys.append(2.0 - float(np.min(doc["fields"]["pressure"])))
    ax.plot(xs, ys, "o", ms=5, mfc="none", color="C3", label="BEM (p̃∞ − min σ at p̃∞ = 2)")
    ax.axhline(0.5 * HK, ls=":", color="0.5")
    ax.axhline(0.5 * HK * RATIO, ls=":", color="0.5")
    _style(ax, "V/V0", "p̃FC", "Figure 8: full-contact load against speed", logx=True)
    ax.legend(fontsize=7)
    return ax


def _speed_sweep(ax, store, cfg, loads, attr, ylabel, title, marker="o", label_fmt="p̃∞ = {:g}"):
    for c, p in zip(_colors(len(loads)), loads):
        sols = [_solve(p, s) for s in SPEED_CURVE]
        ys = [getattr(q, attr) for q in sols]
        ys = [np.nan if y is None else y for y in ys]
        ax.plot(SPEED_CURVE, ys, color=c, lw=1.2, label=label_fmt.format(p))
        pts = [_get(store, _bem(p, s, cfg.nodes)) for s in cfg.speeds_bem]
        pts = [d["record"] for d in pts if d and d["record"][attr] is not None]
        ax.plot([d["speed"] for d in pts], [d[attr] for d in pts], marker, ms=4, color=c, mfc="none")
    _style(ax, "V/V0", ylabel, title, logx=True)
    ax.legend(fontsize=7)
    return ax


def fig9(ax, store, cfg):
    return _speed_sweep(ax, store, cfg, FIG9_LOADS, "ka", "ka",
                        "Figure 9: contact half-width across the transition")


def _ecc(ax, store, cfg, load, title):
    sols = [_solve(load, s) for s in SPEED_CURVE]
    ax.plot(SPEED_CURVE, [np.nan if q.ke is None else q.ke for q in sols], "C0-", lw=1.2, label="ke")
    ax.plot(SPEED_CURVE, [q.ke_hat for q in sols], "C3--", lw=1.2, label="kê")
    pts = [_get(store, _bem(load, s, cfg.nodes)) for s in cfg.speeds_bem]
    pts = [d["record"] for d in pts if d]
    ax.plot([d["speed"] for d in pts if d["ke"] is not None], [d["ke"] for d in pts if d["ke"] is not None],
            "o", ms=4, color="C0", mfc="none", label="BEM ke")
    ax.plot([d["speed"] for d in pts], [d["ke_hat"] for d in pts], "s", ms=4, color="C3", mfc="none",
            label="BEM kê")
    vth = roads.threshold_speed(load, RATIO, HK)
    if 0 < vth < math.inf:
        ax.axvline(vth, ls=":", color="0.5")
    _style(ax, "V/V0", "ke, kê", title, logx=True)
    ax.legend(fontsize=7)
    return ax


def fig10(ax, store, cfg):
    return _ecc(ax, store, cfg, 0.3, "Figure 10: eccentricities at p̃∞ = 0.3 (partial contact)")


def fig11(ax, store, cfg):
    return _ecc(ax, store, cfg, 1.0, "Figure 11: eccentricities at p̃∞ = 1.0 (transition at the dotted line)")


def fig12(ax, store, cfg):
    return _speed_sweep(ax, store, cfg, FIG12_LOADS, "mu", "μ", "Figure 12: friction coefficient against speed")


FIGURES = [("fig03a", lambda ax, s, c: fig3(ax, s, c, "load")),
           ("fig03b", lambda ax, s, c: fig3(ax, s, c, "penetration")),
           ("fig04", fig4), ("fig05", fig5), ("fig06", fig6), ("fig07", fig7), ("fig08", fig8),
           ("fig09", fig9), ("fig10", fig10), ("fig11", fig11), ("fig12", fig12)]


# ---------------------------------------------------------------------------- fields & scalars
def field_comparison(store, cfg):
    """Per field point: (label, load, speed, analytic solution, BEM doc, norms)."""
    rows = []
    for label, p, s in FIELD_POINTS:
        sol = _solve(p, s)
        doc = _get(store, _bem(p, s, cfg.nodes), True)
        norms = None
        if doc:
            f = Fields.from_columns(doc["fields"])  # the BEM grid, its cells weigh the norms
            a = sol.fields(f.x_over_lambda)
            dp = f.pressure - a.pressure
            dv = f.displacement - a.displacement
            pmax = a.linf("pressure")
            norms = {"pressure_L2": f.l2(dp) / pmax, "pressure_Linf": f.linf(dp) / pmax,
                     "displacement_L2": f.l2(dv), "displacement_Linf": f.linf(dv)}
        rows.append((label, p, s, sol, doc, norms))
    return rows


def plot_fields(fig, rows):
    axes = fig.subplots(2, len(rows), sharex=True)
    for j, (label, p, s, sol, doc, norms) in enumerate(rows):
        X = np.linspace(-0.5, 0.5, 1001)
        af = sol.fields(X)
        top, bot = axes[0, j], axes[1, j]
        top.plot(X, af.pressure, "k-", lw=1.0, label="semi-analytic σ")
        twin = top.twinx()
        twin.plot(X, af.displacement, "C0-", lw=1.0)
        twin.set_ylabel("v/h", color="C0", fontsize=8)
        if doc:
            f = doc["fields"]
            step = max(1, len(f["x_over_lambda"]) // 64)
            top.plot(f["x_over_lambda"][::step], f["pressure"][::step], "o", ms=3, mfc="none", color="C3",
                     label="BEM σ")
            twin.plot(f["x_over_lambda"][::step], f["displacement"][::step], "s", ms=2.5, mfc="none", color="C0")
            a = sol.fields(f["x_over_lambda"])
            bot.plot(f["x_over_lambda"], f["pressure"] - a.pressure, "C3-", lw=0.8, label="Δσ")
            bot.plot(f["x_over_lambda"], f["displacement"] - a.displacement, "C0-", lw=0.8, label="Δv/h")
            bot.set_title(f"L∞: σ {norms['pressure_Linf']:.1e}·max σ, v {norms['displacement_Linf']:.1e}·h", fontsize=8)
        top.set_title(f"{label}\np̃∞ = {p:g}, V/V0 = {s:g}", fontsize=9)
        top.set_ylabel("σ(1 − ν²)/E0", fontsize=8)
        bot.set_xlabel("x/λ")
        bot.set_ylabel("BEM − semi-analytic", fontsize=8)
        top.legend(fontsize=7, loc="upper left")
        bot.legend(fontsize=7)
        for a_ in (top, bot):
            a_.grid(True, alpha=0.3)
    return fig


SCALARS = ["ka", "ke", "ke_hat", "penetration", "mu"]


def scalar_table(store, cfg):
    labels = ["light load", "low speed", "high speed", "transition at high speed"]
    pts = [(lbl, p, s) for lbl, p, s in FIELD_POINTS] + \
          [(lbl, p, s) for lbl, (p, s) in zip(labels, SCALAR_EXTRA)]
    rows = []
    for lbl, p, s in pts:
        doc = _get(store, _bem(p, s, cfg.nodes))
        rows.append((lbl, p, s, _solve(p, s).as_dict(), doc["record"] if doc else None))
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
    """Extrapolate the last two meshes assuming error ∝ N^(−order) (mesh ratio 2)."""
    if len(values) < 2:
        return float("nan")
    return _richardson(values[-2], values[-1], order)


def convergence(store, cfg):
    """Errors of the BEM against the semi-analytic solution for each convergence point."""
    out = []
    for label, p, s in CONV_POINTS:
        sol = _solve(p, s)
        ref = sol.as_dict()
        data = {"N": [], "ka": [], "ke": [], "penetration": [], "mu": [], "pressure": []}
        vals = {k: [] for k in ("ka", "ke", "penetration", "mu")}
        for n in cfg.conv_nodes:
            doc = _get(store, _bem(p, s, n), True)
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


def plot_convergence(fig, conv):
    axes = fig.subplots(1, len(conv))
    for ax, c in zip(np.atleast_1d(axes), conv):
        N = np.array(c["data"]["N"], float)
        for k, m in zip(("ka", "ke", "penetration", "mu", "pressure"), "os^dv"):
            e = np.array(c["data"][k], float)
            if np.all(~np.isfinite(e)) or not np.any(e > 0):
                continue
            lab = {"ka": "ka", "ke": "ke", "penetration": "Δ/h", "mu": "μ", "pressure": "σ (rel. L2)"}[k]
            ax.loglog(N, e, m + "-", ms=4, mfc="none", label=f"{lab}: p = {c['orders'][k]:.2f}")
        for p_, ls in ((1, ":"), (2, "--")):
            ax.loglog(N, (N / N[0]) ** (-p_) * 1e-2, "k" + ls, lw=0.6, alpha=0.5)
        ax.set_title(c["label"], fontsize=8)
        ax.set_xlabel("N (panels per period)")
        ax.set_ylabel("|BEM − semi-analytic|")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return fig


# ---------------------------------------------------------------------------- writing
@dataclass
class Doc:
    """The report as a list of parts, written out as Markdown; the HTML page is that Markdown
    rendered by `comparisons._html` (one text, two renderings: report.html is report.md)."""

    parts: list = field(default_factory=list)  # ("h", level, text) | ("p", text) | ("table", head, rows) | ("img", file, caption)

    def h(self, level, text):
        self.parts.append(("h", level, text))

    def p(self, text):
        self.parts.append(("p", text))

    def table(self, head, rows):
        self.parts.append(("table", head, rows))

    def img(self, name, caption):
        self.parts.append(("img", name, caption))

    def markdown(self):
        out = []
        for part in self.parts:
            if part[0] == "h":
                out.append("#" * part[1] + " " + part[2] + "\n")
            elif part[0] == "p":
                out.append(part[1] + "\n")
            elif part[0] == "table":
                out.append(_html.table(part[1], part[2]))  # escapes a '|' inside a cell
            else:
                out.append(f"![{part[2]}]({part[1]})\n")
        return "\n".join(out)

    def html(self, folder):
        """The offline page: report.md rendered, its images embedded (read from ``folder``)."""
        return _html.render(self.markdown(), folder, title="viscosine cross-validation")


def _fmt(v, digits=6):
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float) and not math.isfinite(v):
        return "—"
    return f"{v:.{digits}g}"


def _reldiff(a, b):
    if a is None or b is None:
        return "—"
    return f"{abs(a - b) / max(abs(b), 1e-300):.2e}"


def _versions():
    import matplotlib
    import numba
    import scipy
    try:
        from importlib.metadata import version
        vis = version("viscosine")
    except Exception:  # pragma: no cover - running from a source tree without install
        vis = "source tree"
    return {"viscosine": vis, "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "numba": numba.__version__, "matplotlib": matplotlib.__version__}


PAPER = ("Menga, Putignano, Carbone & Demelio, The sliding contact of a rigid wavy surface with a "
         "viscoelastic half-space, Proc. R. Soc. A 470, 20140392 (2014)")


def material_section(doc, save, cfg):
    """E′, E″ and tan δ of the report's material, with the sliding frequencies of its speeds."""
    import matplotlib.pyplot as plt
    from . import _figures
    j0, j1 = 1.0, 1.0 - 1.0 / RATIO  # the SLS as a one-term Prony series, units E0 and τ
    fig, ax = plt.subplots(figsize=(6.6, 4.4))
    _figures.plot_material(ax, j0, [(j1, 1.0)], speeds=cfg.speeds_bem,
                           speeds_label="kV at the BEM speeds of the figures",
                           title=f"Standard linear solid, E∞/E0 = {RATIO:g}: J0 = {j0:g}, "
                                 f"J1 = {j1:.4g}, τ1 = 1 (creep time)")
    save(fig, "material", f"Storage and loss moduli E′, E″ (units E0) and loss tangent of the "
                          f"standard linear solid with E∞/E0 = {RATIO:g} against ωτ; vertical "
                          f"lines: the sliding frequencies ωτ = kVτ = V/V0 of the BEM markers "
                          f"(V/V0 = {', '.join(f'{v:.3g}' for v in cfg.speeds_bem)})")
    doc.p(f"The paper's standard linear solid (eq. 2.3) is the one-term Prony creep function "
          f"J(t) = J0 − J1 e^(−t/τ) with J0 = 1/E0 and J1 = 1/E0 − 1/E∞ = {j1:.4g}/E0, τ the "
          "creep (retardation) time; its relaxation time is τE0/E∞ "
          "(`docs/conventions.md`, 'Creep times, not relaxation times'). A wavenumber k sliding "
          "at speed V is loaded at the frequency ω = kV, so ωτ is the speed input V/V0 itself. "
          f"E′ rises from E0 to E∞ = {RATIO:g} E0; tan δ peaks at ωτ = √(E∞/E0) = "
          f"{math.sqrt(RATIO):.4g} (tan δ = {(RATIO - 1) / (2 * math.sqrt(RATIO)):.4g}) and E″ at "
          f"ωτ = E∞/E0 = {RATIO:g}, the inverse relaxation time.")


#: what a report without the third code says, in its Tamaas section and at its top
TAMAAS_MISSING = (
    "Tamaas is not installed here, so this section has no results: everything else in this "
    "report stands on its own (both roads, the paper's figures, fields, agreement, convergence). "
    "Tamaas 2.9 is the extra `peers`. From a clone of the repository (the README's first "
    "command installs `.` without it) run `pip install '.[peers]'` in the same environment "
    "(from PyPI: `pip install 'viscosine[peers]'`; the test extra `'.[test]'` includes it), "
    "then the same report command again with `--resume`: it reuses every stored result and "
    "adds the nine Tamaas runs (under a minute on two cores with the default meshes, seconds "
    "with `--quick`).")


def tamaas_section(doc, save, store, cfg, timings):
    """Tamaas against both roads below, at and above the friction peak (or how to install it)."""
    if not tamaas_installed():
        doc.p(TAMAAS_MISSING)
        return
    import matplotlib.pyplot as plt
    from .peers import tamaas as peer
    data = tamaas_study(store, cfg)
    timings["Tamaas runs (sum over processes)"] = data["seconds"]
    n, s0 = cfg.tamaas_nodes, data["summary"]
    where = ["below", "at", "above"]
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
          f"with dt = {', '.join(str(c) for c in TAMAAS_CELLS)} × T/N (T = λ/V the period "
          "transit time, so the indenter crosses that many cells per step). Backward Euler is "
          "first order: its error halves with dt, and the Richardson value "
          "q + (q − q_2dt) from the two finest steps removes it; what remains is Tamaas's "
          f"spatial discretisation on N = {n} nodes. The BEM is at N = {cfg.nodes}.")
    ok = [e for e in s0 if e["complete"]]
    if ok:
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        peer.plot_dt_convergence(ax, {**data, "summary": ok})
        save(fig, "tamaas_dt", f"Relative error of Tamaas's μ against the semi-analytic road as "
                               f"dt is halved (p̃∞ = {TAMAAS_LOAD:g}, E∞/E0 = {RATIO:g}, "
                               f"hk = {HK:g}, N = {n}); dashed: the Richardson value's error; "
                               "dotted: slope 1 (first order)")
    rows = []
    for e in s0:
        prev = None
        for r in e["rows"]:
            err = None if r["mu"] is None else r["mu"] / e["mu_analytic"] - 1.0
            ratio = "—" if (prev is None or err is None or err == 0.0) else f"{prev / err:.3f}"
            rows.append([_fmt(e["speed"], 4), f"{r['cells_per_step']} × T/N",
                         _fmt(r.get("dt"), 4), "—" if not r["success"] else
                         f"{r['steps']} ({r['periods']})", _fmt(r["mu"], 8),
                         "—" if err is None else f"{err:+.3e}", ratio])
            prev = err
    doc.p(f"Tamaas's time-step study (N = {n}): the error of μ against the semi-analytic road "
          "and its ratio to the error at twice the step (2 for first order).")
    doc.table(["V/V0", "dt", "dt/τ", "steps (periods)", "μ Tamaas", "μ/μ_analytic − 1",
               "error(2dt)/error(dt)"], rows)
    rows = []
    for e, pos in zip(s0, where):
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
    doc.p("Three codes at the same operating points. Tamaas's value is its Richardson "
          "extrapolation to dt → 0 with the estimated size of the next term and the observed "
          "order in dt; differences from the semi-analytic road are relative for μ and Δ/h, "
          f"absolute for ka. BEM at N = {cfg.nodes}, Tamaas at N = {n}.")
    doc.table(["V/V0", "quantity", "semi-analytic", "BEM", "Tamaas (dt → 0)",
               "est. dt error (absolute)", "order in dt", "BEM − semi-analytic",
               "Tamaas − semi-analytic"], rows)
    doc.p(f"Cost: {sum(len(e['rows']) for e in s0)} Tamaas runs, {data['seconds']:.1f} s "
          "in all (summed over processes; each is stored as it finishes, so `--resume` does not "
          "run it again).")


def write_report(folder, store, cfg, timings, failures, where=None):
    """Write the figures, report.md and report.html; `timings` gains the time spent here.

    ``where`` says where the runs went (local processes or a Dask scheduler), for the
    provenance table.
    """
    t_start = time.monotonic()
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    doc = Doc()
    doc.h(1, "viscosine: cross-validation report")
    doc.p(f"Steady sliding of a rigid sinusoid over a standard linear solid, E∞/E0 = {RATIO:g}, hk = {HK:g} "
          f"(the parameters of {PAPER}). Lines: semi-analytic road (`analytic/`, Hunter's transformation and "
          f"the closure (2.14)–(2.15)). Markers: boundary-element road (`bem/`, eq. 2.5 discretised "
          f"directly, N = {cfg.nodes} panels per period). Units, signs and output keys: "
          f"`docs/conventions.md`. {'Quick run (coarser meshes, fewer points).' if cfg.quick else ''}")
    doc.p("Contents: the material; the paper's figures 3–12 with both roads; fields; scalars; "
          "the two roads' agreement on a grid of operating points; the BEM's convergence; "
          + ("a third code, Tamaas, against both roads; " if tamaas_installed() else
             "a third code, Tamaas: **not in this report**, it is not installed (see its "
             "section: `pip install '.[peers]'` from a clone, then `--resume`); ")
          + "provenance.")
    if failures:
        doc.h(2, "Runs that did not converge")
        doc.p("These operating points are missing from the figures and tables below; they were not reported as results.")
        doc.table(["spec", "error"], [[str(s), e] for s, e in failures])
    def save(fig, name, caption):  # every figure is written as it is finished, then captioned
        fig.tight_layout()
        fig.savefig(os.path.join(folder, f"{name}.png"), dpi=110)
        plt.close(fig)
        doc.img(f"{name}.png", caption)

    doc.h(2, "The material")
    material_section(doc, save, cfg)

    doc.h(2, "The paper's figures, both roads")
    for name, fn in FIGURES:
        fig, ax = plt.subplots(figsize=(6.4, 4.4))
        fn(ax, store, cfg)
        save(fig, name, ax.get_title() + f" (E∞/E0 = {RATIO:g}, hk = {HK:g}; BEM N = {cfg.nodes})")

    doc.h(2, "Fields: σ(x) and v(x) from both roads")
    rows = field_comparison(store, cfg)
    fig = plt.figure(figsize=(4.2 * len(rows), 6.0))
    plot_fields(fig, rows)
    save(fig, "fields", f"Pressure and displacement, BEM (markers, N = {cfg.nodes}) and semi-analytic "
                        "(lines); bottom: BEM − semi-analytic at the BEM collocation points")
    doc.table(["operating point", "p̃∞", "V/V0", "σ: L2 / max σ", "σ: L∞ / max σ", "v: L2 / h", "v: L∞ / h"],
              [[lbl, _fmt(p), _fmt(s)] + ([f"{n['pressure_L2']:.2e}", f"{n['pressure_Linf']:.2e}",
                                           f"{n['displacement_L2']:.2e}", f"{n['displacement_Linf']:.2e}"]
                                          if n else ["—"] * 4)
               for lbl, p, s, _, _, n in rows])

    doc.h(2, "Scalars from both roads")
    trows = []
    for lbl, p, s, a, b in scalar_table(store, cfg):
        for k in SCALARS:
            av = a[k]
            bv = None if b is None else b[k]
            diff = "—" if (av is None or bv is None) else (
                f"{abs(av - bv):.2e}" if k in ("ke", "ke_hat", "ka") else _reldiff(bv, av))
            trows.append([lbl, _fmt(p), _fmt(s), k, _fmt(av, 10), _fmt(bv, 10), diff])
    doc.p("Differences: absolute for ka, ke, kê; relative for Δ/h and μ. BEM at N = "
          f"{cfg.nodes}.")
    doc.table(["operating point", "p̃∞", "V/V0", "quantity", "semi-analytic", "BEM", "difference"], trows)

    doc.h(2, "Agreement of the two roads on a grid of operating points")
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

    doc.h(2, "Convergence of the BEM by mesh refinement")
    conv = convergence(store, cfg)
    fig = plt.figure(figsize=(4.6 * len(conv), 4.2))
    plot_convergence(fig, conv)
    save(fig, "convergence", "Error of the BEM against the semi-analytic solution; observed orders p from "
                             "a log–log fit over N ≥ 1024 above round-off (dotted: N⁻¹, dashed: N⁻²)")
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

    doc.h(2, "A third code: Tamaas")
    tamaas_section(doc, save, store, cfg, timings)

    doc.h(2, "Provenance")
    ver = _versions()
    doc.table(["item", "value"],
              [["date (UTC)", datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M:%S")],
               ["parameters", f"E∞/E0 = {RATIO:g}, hk = {HK:g}, ν enters only through p̃∞ and τ̃f"],
               ["BEM mesh (figures, fields, scalars)", str(cfg.nodes)],
               ["BEM meshes (convergence)", ", ".join(str(n) for n in cfg.conv_nodes)],
               ["mode", "quick" if cfg.quick else "full"],
               ["runs done on", where or f"{cfg.workers} local processes"],
               ["Tamaas grid (third code)", f"N = {cfg.tamaas_nodes}, dt = "
                f"{', '.join(str(c) for c in TAMAAS_CELLS)} × T/N" if tamaas_installed()
                else "Tamaas not installed"],
               ["machine", f"{platform.machine()}, {os.cpu_count()} cores, {platform.system()}"]]
              + [[k, v] for k, v in ver.items()]
              + [[f"time: {k}", f"{v:.1f} s"] for k, v in
                 (timings | {"figures and tables": time.monotonic() - t_start}).items()])
    md = doc.markdown()
    write_text(os.path.join(folder, "report.md"), md)
    write_text(os.path.join(folder, "report.html"), doc.html(folder))
    return conv


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
