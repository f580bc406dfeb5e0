"""How far the BEM's error estimates and its adaptive mesh can be trusted, measured against the
semi-analytic road.

Three studies, each printing its table (progress on standard error; each point's line is
printed as soon as it is done, so an interrupted run keeps what it finished):

* ``honesty``: a random sample over the whole input box the command line accepts (load
  1e-4 … 10, speed 1e-4 … 1e4, ratio 1.01 … 1000, hk 0.01 … 10, log-uniform; seeded).  At each
  point the BEM on a fixed mesh (default N = 4096) and the adaptive default (rtol 1e-6) are
  compared with the semi-analytic road: the true error of μ and Δ/h (relative) and of ka, ke
  (absolute) against the BEM's own ``error_estimate``; for the adaptive default, whether any
  answered point is off by more than 10 × rtol and how many points are refused.
* ``front door`` (``--honesty --front-door``): the same sample, but each point goes the way of
  ``python -m comparisons point --solver bem`` (`operating_point.build` → `runner.run`, the last line
  of defence included) and the JSON record a user would see is judged: answered or refused, its
  true errors against the semi-analytic road and its own ``error_estimate``.  For each answered
  point it also says whether the gate as it was before the fields carried their cells (a plain
  ``np.mean`` of the pressure column against the load, CONTROL_MISMATCH) would have refused it.
* ``cost``: on the report's operating points, the time of the adaptive default against a
  fixed N = 4096 solve (median ratio).
* ``memory``: the tracemalloc peak of one solve per panel at N = 2^20, and the largest N whose
  solve fits in 1 GiB.
"""
from __future__ import annotations

import concurrent.futures as cf
import math
import statistics
import sys
import time
import tracemalloc

import numpy as np

import analytic
import bem

from ..progress import Progress

#: the box of the random sample: name -> (low, high), log-uniform
BOX = {"load": (1e-4, 10.0), "speed": (1e-4, 1e4), "ratio": (1.01, 1000.0), "hk": (0.01, 10.0)}
#: the light-load sample (--light): the same box but the load, which is hk times a log-uniform
#: p~/hk down to the BEM's accepted bound (contacts of 1e-4 of the period and less)
LIGHT_LOAD_OVER_HK = (1e-8, 1e-4)
#: quantities compared: (key, relative?)
QUANTITIES = (("mu", True), ("penetration", True), ("ka", False), ("ke", False))


#: the study's progress line (in place on a terminal, a line every few seconds in a log)
_PROGRESS = Progress()


def _progress(msg):
    _PROGRESS.update(msg)


def sample(points, seed, light=False):
    """`points` operating points, log-uniform in BOX (deterministic for a seed); with `light`,
    the load is hk times a log-uniform p~/hk in LIGHT_LOAD_OVER_HK."""
    rng = np.random.default_rng(seed)
    cols = {k: np.exp(rng.uniform(math.log(lo), math.log(hi), points))
            for k, (lo, hi) in BOX.items()}
    if light:
        lo, hi = LIGHT_LOAD_OVER_HK
        # not below the accepted bound p~/hk = 1e-8 by rounding
        q = np.clip(np.exp(rng.uniform(math.log(lo), math.log(hi), points)), lo * (1 + 1e-12), hi)
        cols["load"] = cols["hk"] * q
    return [{k: float(cols[k][i]) for k in BOX} for i in range(points)]


def _errors(values, ref):
    """True errors of the BEM's scalars against the reference's (two mappings: a result's
    ``scalars()`` or a JSON record; None where either is undefined)."""
    out = {}
    for key, rel in QUANTITIES:
        a, b = values.get(key), ref.get(key)
        if a is None or b is None:
            out[key] = None
        elif rel:
            out[key] = abs(a - b) / abs(b) if b != 0 else (0.0 if a == b else math.inf)
        else:
            out[key] = abs(a - b)
    return out


def one_point(point, nodes=4096, rtol=None):
    """Both BEM modes at one point against the semi-analytic road (a plain dict)."""
    ref = analytic.solve(**point)
    row = {"point": point, "reference": bool(ref.success)}
    if not ref.success:
        return row
    for mode, kw in (("fixed", {"nodes": nodes}), ("adaptive", {} if rtol is None else {"rtol": rtol})):
        t0 = time.perf_counter()
        try:
            r = bem.solve(**point, **kw)
        except (ValueError, ArithmeticError, MemoryError, RuntimeError) as exc:
            row[mode] = {"success": False, "message": f"{type(exc).__name__}: {exc}",
                         "seconds": time.perf_counter() - t0, "nodes": None}
            continue
        est = dict(r.error_estimate) if r.error_estimate is not None else None
        row[mode] = {"success": bool(r.success), "message": r.message.splitlines()[0][:200],
                     "seconds": time.perf_counter() - t0, "nodes": int(r.nodes),
                     "errors": _errors(r.scalars(), ref.scalars()), "estimate": est}
    return row


def _run(points, fn, workers):
    if workers == 1:
        for p in points:
            yield fn(p)
        return
    with cf.ProcessPoolExecutor(max_workers=workers) as ex:
        yield from ex.map(fn, points)


def _fmt(v):
    return "-" if v is None else f"{v:.1e}"


def _describe(points, seed, light):
    """The sample, as the studies' headers state it."""
    return (f"{points} points, seed {seed}, log-uniform: " +
            ("load/hk {:g} … {:g}, ".format(*LIGHT_LOAD_OVER_HK) if light else "") +
            ", ".join(f"{k} {lo:g} … {hi:g}" for k, (lo, hi) in BOX.items()
                      if not (light and k == "load")))


def honesty(points=300, seed=20261123, nodes=4096, rtol=1e-6, workers=2, out=sys.stdout,
            light=False):
    """The honesty study and the adaptive study on one random sample (with `light`, the
    light-load sample); returns 0 when every target holds, 1 otherwise."""
    import functools
    pts = sample(points, seed, light)
    print(f"# Error estimates and the adaptive mesh against the semi-analytic road\n\n" +
          _describe(points, seed, light) + f"; fixed mesh N = {nodes}; adaptive default rtol = {rtol:g}\n", file=out)
    print("point  load  speed  ratio  hk | fixed: success, true/estimate of mu, Δ/h, ka, ke | "
          "adaptive: success, N, seconds, true errors of mu, Δ/h, ka, ke", file=out)
    rows = []
    fn = functools.partial(one_point, nodes=nodes, rtol=rtol)
    for i, row in enumerate(_run(pts, fn, workers)):
        rows.append(row)
        p = row["point"]
        head = f"{i:4d} {p['load']:.3g} {p['speed']:.3g} {p['ratio']:.4g} {p['hk']:.3g}"
        if not row["reference"]:
            print(head + " | semi-analytic road failed: point skipped", file=out, flush=True)
            continue
        f, a = row["fixed"], row["adaptive"]
        ratios = []
        for key, _ in QUANTITIES:
            e = (f.get("errors") or {}).get(key)
            s = (f.get("estimate") or {}).get(key)
            ratios.append("-" if e is None or s is None else f"{e / s:.2g}" if s > 0 else
                          ("0" if e == 0 else "inf"))
        errs = " ".join(_fmt((a.get("errors") or {}).get(k)) for k, _ in QUANTITIES)
        print(f"{head} | {f['success']!s:5} {' '.join(ratios)} | {a['success']!s:5} "
              f"{a['nodes']} {a['seconds']:.2f} {errs}" +
              ("" if a["success"] else f"  [{a['message'][:120]}]"), file=out, flush=True)
        _progress(f"honesty: {i + 1}/{points}")
    return _summary(rows, rtol, out)


def _summary(rows, rtol, out):
    ok = [r for r in rows if r["reference"]]
    print(f"\n## Honesty of the error estimate ({len(ok)} points with a semi-analytic "
          f"reference)\n", file=out)
    print("| mesh | quantity | points with an estimate | true < estimate | true < 3 × estimate | "
          "worst true/estimate |", file=out)
    print("| --- | --- | --- | --- | --- | --- |", file=out)
    good = True
    for mode in ("fixed", "adaptive"):
        for key, _ in QUANTITIES:
            pairs = []
            for r in ok:
                m = r[mode]
                if not m["success"]:
                    continue
                e = (m.get("errors") or {}).get(key)
                s = (m.get("estimate") or {}).get(key)
                if e is None or s is None:
                    continue
                pairs.append((e, s))
            if not pairs:
                continue
            below = sum(e <= s for e, s in pairs) / len(pairs)
            below3 = sum(e <= 3 * s for e, s in pairs) / len(pairs)
            worst = max((e / s if s > 0 else (0.0 if e == 0 else math.inf)) for e, s in pairs)
            good &= below >= 0.95 and below3 == 1.0
            print(f"| {mode} | {key} | {len(pairs)} | {100 * below:.1f} % | {100 * below3:.1f} % | "
                  f"{worst:.2g} |", file=out)
    ad = [r["adaptive"] for r in ok]
    answered = [a for a in ad if a["success"]]
    refused = [a for a in ad if not a["success"]]
    worst = {k: max([a["errors"][k] for a in answered if a["errors"].get(k) is not None],
                    default=0.0) for k, _ in QUANTITIES}
    over = [a for a in answered
            if any(v is not None and v > 10 * rtol for v in a["errors"].values())]
    secs = [a["seconds"] for a in ad]
    nodes = [a["nodes"] for a in answered]
    print(f"\n## The adaptive default (rtol = {rtol:g})\n", file=out)
    print(f"- answered: {len(answered)} of {len(ad)}; refused: {len(refused)} "
          f"({100 * len(refused) / max(len(ad), 1):.1f} %)", file=out)
    print(f"- answered points whose true error exceeds 10 × rtol: {len(over)}", file=out)
    print("- worst true error of an answered point: " +
          ", ".join(f"{k} {v:.1e}" for k, v in worst.items()), file=out)
    if nodes:
        print(f"- N used: median {int(statistics.median(nodes))}, largest {max(nodes)}", file=out)
    print(f"- seconds per point (adaptive): median {statistics.median(secs):.2f}, "
          f"largest {max(secs):.1f}", file=out)
    reasons = {}
    for a in refused:
        m = a["message"]
        key = m.split(":")[0][:90]
        reasons[key] = reasons.get(key, 0) + 1
    for k, v in sorted(reasons.items(), key=lambda kv: -kv[1]):
        print(f"  - refused ({v}): {k}", file=out)
    good &= not over and len(refused) <= 0.02 * len(ad)
    return 0 if good else 1


def front_door_point(point, rtol=None):
    """One point the way ``python -m comparisons point --solver bem --fields F`` runs it (the
    spec the command line builds, `runner.run` with its last line of defence), judged on the
    JSON record printed, against the semi-analytic road (a plain dict)."""
    import json

    from .. import gate, runner
    from .. import operating_point as op
    ref = analytic.solve(**point)
    row = {"point": point, "reference": bool(ref.success)}
    if not ref.success:
        return row
    spec = op.build("bem", load=point["load"], speed=point["speed"], ratio=point["ratio"],
                          hk=point["hk"], rtol=rtol, fields=True)
    t0 = time.perf_counter()
    res = runner.run(spec, fields=True, deep=True)
    front = {"ok": bool(res["ok"]), "error": res["error"], "seconds": time.perf_counter() - t0}
    if res["ok"]:
        rec = json.loads(json.dumps(res["record"], allow_nan=False))  # what is printed
        f = res["fields"]
        old = abs(float(np.mean(f.pressure)) / rec["load"] - 1.0)  # the gate before the cells
        front.update(nodes=rec["nodes"], errors=_errors(rec, ref.scalars()),
                     estimate=rec.get("error_estimate"), uniform=bool(f.uniform),
                     old_mean_error=old, old_gate_refuses=old > gate.CONTROL_MISMATCH)
    row["front"] = front
    return row


def front_door(points=50, seed=20261123, rtol=1e-6, workers=2, out=sys.stdout, light=False):
    """The front-door study (see the module docstring); 0 when every point with a reference is
    answered and every answered point is within 3 × its estimate and 10 × rtol, else 1."""
    import functools
    pts = sample(points, seed, light)
    print(f"# Through the front door: `python -m comparisons point --solver bem` against the "
          f"semi-analytic road\n\n" + _describe(points, seed, light) + f"; adaptive default rtol = {rtol:g}\n", file=out)
    print("point  load  speed  ratio  hk | answered, N, grid, seconds | true/estimate of mu, "
          "Δ/h, ka, ke | old gate: mean σ error, refuses?", file=out)
    rows = []
    fn = functools.partial(front_door_point, rtol=rtol)
    for i, row in enumerate(_run(pts, fn, workers)):
        rows.append(row)
        p = row["point"]
        head = f"{i:4d} {p['load']:.3g} {p['speed']:.3g} {p['ratio']:.4g} {p['hk']:.3g}"
        if not row["reference"]:
            print(head + " | semi-analytic road failed: point skipped", file=out, flush=True)
            continue
        f = row["front"]
        if not f["ok"]:
            print(f"{head} | refused [{(f['error'] or '')[:140]}]", file=out, flush=True)
        else:
            ratios = []
            for key, _ in QUANTITIES:
                e, s_ = f["errors"].get(key), (f["estimate"] or {}).get(key)
                ratios.append("-" if e is None or s_ is None else f"{e / s_:.2g}" if s_ > 0
                              else ("0" if e == 0 else "inf"))
            print(f"{head} | yes {f['nodes']} {'uniform' if f['uniform'] else 'window'} "
                  f"{f['seconds']:.2f} | {' '.join(ratios)} | {f['old_mean_error']:.1e} "
                  f"{'REFUSES' if f['old_gate_refuses'] else 'passes'}", file=out, flush=True)
        _progress(f"front door: {i + 1}/{points}")
    ok = [r for r in rows if r["reference"]]
    answered = [r["front"] for r in ok if r["front"]["ok"]]
    before = [f for f in answered if not f["old_gate_refuses"]]
    windows = [f for f in answered if not f["uniform"]]
    print(f"\n## Answered through the front door ({len(ok)} points with a semi-analytic "
          f"reference)\n", file=out)
    print(f"- now: {len(answered)} of {len(ok)} answered ({len(windows)} of them on a contact "
          f"window's non-uniform grid)", file=out)
    print(f"- with the gate as it was (np.mean of the pressure column): {len(before)} of "
          f"{len(ok)}; it refuses {len(answered) - len(before)} of today's answers, "
          f"{sum(not f['uniform'] for f in answered if f['old_gate_refuses'])} of them windows",
          file=out)
    good = len(answered) == len(ok)
    for key, _ in QUANTITIES:
        pairs = [(f["errors"][key], (f["estimate"] or {}).get(key)) for f in answered
                 if f["errors"].get(key) is not None and (f["estimate"] or {}).get(key) is not None]
        if not pairs:
            continue
        below3 = sum(e <= 3 * s_ for e, s_ in pairs)
        worst = max((e / s_ if s_ > 0 else (0.0 if e == 0 else math.inf)) for e, s_ in pairs)
        worst_true = max(e for e, _ in pairs)
        good &= below3 == len(pairs) and worst_true <= 10 * rtol
        print(f"- {key}: {below3} of {len(pairs)} within 3 × the record's estimate, worst "
              f"true/estimate {worst:.2g}, worst true error {worst_true:.1e}", file=out)
    refused = {}
    for r in ok:
        if not r["front"]["ok"]:
            k = (r["front"]["error"] or "").split(":")[0][:90]
            refused[k] = refused.get(k, 0) + 1
    for k, v in sorted(refused.items(), key=lambda kv: -kv[1]):
        print(f"  - refused ({v}): {k}", file=out)
    secs = [r["front"]["seconds"] for r in ok]
    if secs:
        print(f"- seconds per point: median {statistics.median(secs):.2f}, largest "
              f"{max(secs):.1f}", file=out)
    return 0 if good else 1


def cost(out=sys.stdout, repeats=3):
    """Adaptive default against a fixed N = 4096 on the report's operating points."""
    from .. import crosscheck
    pts = []
    for label, load, speed, ratio, hk in crosscheck.GRID:
        pts.append((label, dict(load=crosscheck._load(load, speed, ratio, hk), speed=speed,
                                ratio=ratio, hk=hk)))
    bem.solve(load=0.3, speed=1.0, nodes=4096)  # warm-up: compilation, FFT plans
    bem.solve(load=0.3, speed=1.0)
    print("\n## Cost of the adaptive default against a fixed N = 4096 (report's points)\n",
          file=out)
    print("| point | fixed 4096 [s] | adaptive [s] | ratio | N reached |", file=out)
    print("| --- | --- | --- | --- | --- |", file=out)
    ratios = []
    for label, kw in pts:
        _progress(f"cost: {label}")
        tf = min(_time(lambda: bem.solve(**kw, nodes=4096)) for _ in range(repeats))
        ta = min(_time(lambda: bem.solve(**kw)) for _ in range(repeats))
        r = bem.solve(**kw)
        ratios.append(ta / tf)
        print(f"| {label} | {tf:.4f} | {ta:.4f} | {ta / tf:.1f} | "
              f"{r.nodes}{'' if r.success else ' (refused)'} |", file=out)
    print(f"\nmedian ratio adaptive / fixed 4096: {statistics.median(ratios):.1f}", file=out)
    return 0


def _time(fn):
    t0 = time.perf_counter()
    fn()
    return time.perf_counter() - t0


def memory(exponent=20, out=sys.stdout):
    """tracemalloc peak per panel of one fixed-mesh solve at N = 2^exponent."""
    n = 2 ** exponent
    bem.solve(load=0.3, speed=1.0, nodes=4096)
    print(f"\n## Memory of one solve (tracemalloc peak, N = 2^{exponent})\n", file=out)
    print("| point | peak [MiB] | bytes per panel |", file=out)
    print("| --- | --- | --- |", file=out)
    worst = 0.0
    for label, kw in (("partial, p̃ = 0.3, V/V0 = 1", dict(load=0.3, speed=1.0)),
                      ("1.6 % below the transition, p̃ = 0.66, V/V0 = 1",
                       dict(load=0.66, speed=1.0)),
                      ("full, p̃ = 2, V/V0 = 1", dict(load=2.0, speed=1.0)),
                      ("stiff, E∞/E0 = 155, p̃ = 0.29, V/V0 = 0.13 (mostly in contact, "
                       "primal step)", dict(load=0.2866, speed=0.1326, ratio=154.7, hk=0.853))):
        _progress(f"memory: {label}")
        tracemalloc.start()
        bem.solve(**kw, nodes=n)
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
        worst = max(worst, peak / n)
        print(f"| {label} | {peak / 2**20:.0f} | {peak / n:.0f} |", file=out)
    fit = 2 ** int(math.floor(math.log2(2**30 / worst)))
    print(f"\nlargest power of two N whose solve fits in 1 GiB at {worst:.0f} bytes per panel: "
          f"{fit} (2^{int(math.log2(fit))})", file=out)
    return 0
