"""Just below the full-contact load: the BEM through the command line on a random sample.

``python -m comparisons bench --near-transition [--points 100] [--seed 20261129]
[--penetration-control]``.  Each point is drawn log-uniform: E∞/E0 in RATIO, the relative
distance d in DISTANCE, and V/V0 in one of two strata, alternately (`_speed`): the viscoelastic
window SPEED_WINDOW (even points) and the rest of the accepted speeds, SPEED_TAILS (odd
points).  Under load control the load is p̃_FC(V) (1 − d), p̃_FC from the semi-analytic road
(`analytic.transition_load`, |E(kV)| hk/2); under penetration control Δ/h = 1 − d (full
contact is Δ/h = 1).  Each point runs as a user runs it, one subprocess ``python -m
comparisons point --solver bem --load L --speed V --ratio R`` (or ``--penetration D``) at its
defaults (rtol 1e-6), whose CPU time and peak memory come from its own resource usage
(`os.wait4`).  Its JSON record is judged against `analytic.solve`: μ, the contact fraction and
Δ/h (the load under penetration control; relative) are right when their true error is at most
SAFETY times the record's ``error_estimate`` plus FLOOR (the two roads' agreement floor).  A
point without an answer (a non-zero exit, or no record within LIMIT seconds of CPU) is
refused.

Every finished point is appended at once as one JSON line to the output file (default
``bench-near-transition-S<seed>.jsonl``, under penetration control
``bench-near-transition-penetration-S<seed>.jsonl``, in the working folder); a rerun with the
same seed and file skips the points already there, so an interrupted run loses nothing it
finished.  The table goes to standard output (with the figures of each speed stratum),
progress to standard error.
"""
from __future__ import annotations

import json
import math
import os
import signal
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import analytic

#: the sample's box (log-uniform): E∞/E0, V/V0, and the relative distance below p̃_FC(V) (or
#: below Δ/h = 1).  The speeds come in two strata of equal size: the viscoelastic window
#: (beyond it |E(kV)| is within 5e-7 of E0 below, the glassy side is reached for every ratio
#: above), where the contact's shape depends on the speed, and the rest of the accepted range
#: (`bem.ACCEPTED`'s 1e-30 … 1e30), log-uniform over its 53 decades: drawn over all 60 decades
#: at once, only 12 % of the points would fall in the window
RATIO = (1.5, 1000.0)
SPEED_WINDOW = (1e-3, 1e4)
SPEED_TAILS = ((1e-30, 1e-3), (1e4, 1e30))
DISTANCE = (1e-8, 1e-3)
#: a record is right when each true error is at most SAFETY × its estimate plus FLOOR.  The
#: estimate is 1.5 × the largest difference of the last grids: errors that oscillate with the
#: edges' place in their panels can exceed it on one grid (measured up to 0.7 of it near full
#: contact); 3 is the factor the front-door study of the estimates uses.  FLOOR: the two roads
#: agree on μ to about 1e-11 relative, below which the reference's rounding decides
SAFETY = 3.0
FLOOR = 2e-11
#: keys judged (all relative), and those only reported (absolute)
JUDGED = ("mu", "contact_fraction", "penetration")
#: ... under penetration control (Δ/h is given, the load is an output, judged against the
#: record's own estimate of it, ``error_estimate["load"]``)
JUDGED_PENETRATION = ("mu", "contact_fraction", "load")
REPORTED = ("ka", "ke")
#: CPU limit of one point, seconds (RLIMIT_CPU of its process: then it is stopped and counted
#: as refused); the wall clock stops it at WALL_FACTOR times that (a shared machine)
LIMIT = 600.0
WALL_FACTOR = 6.0
#: default seed of the sample (20261128 drew the speeds in the window only)
SEED = 20261129


def _progress(msg):
    print(msg, file=sys.stderr, flush=True)


def sample(points, seed, control="load"):
    """The `points` operating points of a seed: dicts with the index, the speed's stratum
    ("window" for even indices, "tails" for odd ones), ratio, speed, distance, and the load
    (``control`` "load") or the penetration ("penetration")."""
    rng = np.random.default_rng(seed)
    ratios, unit, dists = (rng.uniform(0.0, 1.0, points) for _ in range(3))
    out = []
    for i in range(points):
        ratio = float(math.exp(_lerp(math.log(RATIO[0]), math.log(RATIO[1]), ratios[i])))
        dist = float(math.exp(_lerp(math.log(DISTANCE[0]), math.log(DISTANCE[1]), dists[i])))
        stratum = "window" if i % 2 == 0 else "tails"
        speed = _speed(float(unit[i]), stratum)
        p = {"index": i, "stratum": stratum, "ratio": ratio, "speed": speed, "distance": dist}
        if control == "load":
            p["load"] = analytic.transition_load(speed, ratio) * (1.0 - dist)
        else:
            p["penetration"] = 1.0 - dist
        out.append(p)
    return out


def _lerp(lo, hi, u):
    return lo + (hi - lo) * u


def _speed(u, stratum):
    """V/V0 for u in [0, 1): log-uniform in SPEED_WINDOW, or over the union SPEED_TAILS."""
    if stratum == "window":
        return float(math.exp(_lerp(math.log(SPEED_WINDOW[0]), math.log(SPEED_WINDOW[1]), u)))
    spans = [math.log(hi) - math.log(lo) for lo, hi in SPEED_TAILS]
    t = u * sum(spans)
    for (lo, _), span in zip(SPEED_TAILS, spans):
        if t < span:
            return float(math.exp(math.log(lo) + t))
        t -= span
    return SPEED_TAILS[-1][1]  # pragma: no cover (u < 1)


def _control(point):
    return "load" if "load" in point else "penetration"


def _judged(point):
    return JUDGED if _control(point) == "load" else JUDGED_PENETRATION


def _command(point):
    c = _control(point)
    return [sys.executable, "-m", "comparisons", "point", "--solver", "bem",
            f"--{c}", repr(point[c]), "--speed", repr(point["speed"]),
            "--ratio", repr(point["ratio"])]


def run_point(point, limit=LIMIT):
    """Run one point through the command line: a dict with the record (or the error), the
    exit status, its CPU seconds and peak resident memory (bytes; from `os.wait4`, this
    point's process alone) and wall seconds."""
    t0 = time.perf_counter()
    with tempfile.TemporaryFile("w+") as fo, tempfile.TemporaryFile("w+") as fe:
        proc = subprocess.Popen(_command(point), stdout=fo, stderr=fe, text=True,
                                start_new_session=True, preexec_fn=lambda: _cpu_limit(limit))
        stopped = False
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)
            if pid:
                break
            if time.perf_counter() - t0 > WALL_FACTOR * limit:
                os.killpg(proc.pid, signal.SIGKILL)  # its own session: this point's only
                pid, status, usage = os.wait4(proc.pid, 0)
                stopped = True
                break
            time.sleep(0.1)
        proc.returncode = os.waitstatus_to_exitcode(status)  # reaped here, not by Popen
        fo.seek(0)
        fe.seek(0)
        out, err = fo.read(), fe.read()
    cpu = usage.ru_utime + usage.ru_stime
    stopped = stopped or cpu >= limit  # RLIMIT_CPU's signal
    row = {"exit": proc.returncode, "stopped": stopped, "wall": time.perf_counter() - t0,
           "cpu": cpu, "max_rss": usage.ru_maxrss * 1024}
    record = None
    if proc.returncode == 0 and not stopped:
        try:
            record = json.loads(out.strip().splitlines()[-1])
        except (ValueError, IndexError):
            record = None
    row["record"] = record
    row["error"] = None if record is not None else (
        f"stopped at {limit:g} s of CPU" if stopped else (err.strip().splitlines() or ["?"])[-1])
    return row


def _cpu_limit(seconds):
    """In the point's process before it starts: its CPU time limited to `seconds`."""
    import resource
    s = int(math.ceil(seconds))
    resource.setrlimit(resource.RLIMIT_CPU, (s, s + 5))


def judge(point, record):
    """True errors of the record against the semi-analytic road, and the verdict (right when
    every JUDGED error is at most SAFETY × its estimate + FLOOR)."""
    c = _control(point)
    ref = analytic.solve(**{c: point[c]}, speed=point["speed"], ratio=point["ratio"])
    if not ref.success:
        return {"reference": False}
    est = dict(record.get("error_estimate") or {})
    judged_keys = _judged(point)
    relative = judged_keys
    errors, ratios, right = {}, {}, True
    for key in relative + REPORTED:
        a, b = record.get(key), getattr(ref, key)
        if a is None or b is None:
            continue
        e = abs(a - b) / abs(b) if key in relative else abs(a - b)
        errors[key] = e
        s = est.get(key)
        if s is not None:  # an error over an estimate of 0: None (JSON has no inf)
            ratios[key] = e / s if s > 0 else (0.0 if e == 0 else None)
        if key in judged_keys and not (s is not None and e <= SAFETY * s + FLOOR):
            right = False
    return {"reference": True, "errors": errors, "over_estimate": ratios, "right": right}


def _done(path, seed):
    """Rows already in the output file for this seed, by index."""
    rows = {}
    if not os.path.exists(path):
        return rows
    with open(path, encoding="utf-8") as fh:
        for line in fh:
            try:
                row = json.loads(line)
            except ValueError:
                continue  # a line cut by an interruption
            if row.get("seed") == seed:
                rows[row["point"]["index"]] = row
    return rows


def _line(row):
    p = row["point"]
    head = (f"| {p['index']:3d} | {p['ratio']:.4g} | {p['speed']:.4g} | {p['distance']:.2e} | "
            f"{row['cpu']:.1f} | {row['max_rss'] / 2**20:.0f} |")
    if row["record"] is None:
        return f"{head} refused | — | {row['error'][:100]} |"
    rec, j = row["record"], row["judged"]
    if not j.get("reference"):
        return f"{head} answered, N = {rec['nodes']} | no reference | |"
    worst = max(math.inf if j["over_estimate"].get(k) is None else j["over_estimate"][k]
                for k in _judged(p))
    errs = ", ".join(f"{k} {e:.1e}" for k, e in j["errors"].items())
    return (f"{head} {'right' if j['right'] else 'WRONG'}, N = {rec['nodes']} | "
            f"{worst:.2g} | {errs} |")


def _measure(point, seed, limit):
    """One point run and judged: its JSON line's contents."""
    _progress(f"point {point['index'] + 1}: E∞/E0 {point['ratio']:.4g}, V/V0 "
              f"{point['speed']:.4g}, d {point['distance']:.2e}")
    got = run_point(point, limit)
    row = {"seed": seed, "point": point, "exit": got["exit"], "cpu": got["cpu"],
           "wall": got["wall"], "max_rss": got["max_rss"], "record": got["record"],
           "error": got["error"], "command": " ".join(_command(point)[1:])}
    row["judged"] = judge(point, got["record"]) if got["record"] else None
    return row


def run(points=100, seed=SEED, path=None, limit=LIMIT, out=sys.stdout, workers=1,
        control="load"):
    """The study: print the table (rows as the points finish; ``workers`` points run at a
    time, each in its own process, CPU and memory measured per process) and the figures; 0
    when at most 1 % is refused and none is wrong, else 1.  ``control``: "load" (p̃∞ =
    p̃_FC(V)(1 − d)) or "penetration" (Δ/h = 1 − d)."""
    import concurrent.futures as cf
    import threading
    tag = "" if control == "load" else "-penetration"
    path = path or f"bench-near-transition{tag}-S{seed}.jsonl"
    pts = sample(points, seed, control)
    done = _done(path, seed)
    _progress(f"# near the transition: {points} points (seed {seed}); JSON lines in {path}"
              + (f" ({len(done)} already there)" if done else ""))
    given = ("p̃∞ = p̃_FC(V)(1 − d)" if control == "load" else
             "Δ/h = 1 − d (`--penetration`)")
    judged = JUDGED if control == "load" else JUDGED_PENETRATION
    print(f"# Just below full contact through `point --solver bem` (defaults)\n\n"
          f"{points} points, seed {seed}: E∞/E0 log-uniform in {RATIO}, V/V0 log-uniform in "
          f"{SPEED_WINDOW} (even points) and over {SPEED_TAILS} (odd points), {given} with d "
          f"in {DISTANCE}; right: true error of {', '.join(judged)} ≤ {SAFETY:g} × estimate "
          f"+ {FLOOR:g}; limit {limit:g} s of CPU a point; {workers} at a time; "
          f"{_load_average()}\n", file=out)
    print("| # | E∞/E0 | V/V0 | d | CPU [s] | peak [MiB] | verdict | worst error/estimate | "
          "true errors |", file=out)
    print("| ---: | ---: | ---: | ---: | ---: | ---: | --- | ---: | --- |", file=out)
    rows = {}
    todo = []
    for p in pts:
        row = done.get(p["index"])
        if row is not None and row["point"] == p:
            rows[p["index"]] = row
            print(_line(row), file=out, flush=True)
        else:
            todo.append(p)
    lock = threading.Lock()
    with open(path, "a", encoding="utf-8") as fh, \
            cf.ThreadPoolExecutor(max_workers=workers) as ex:
        futures = [ex.submit(_measure, p, seed, limit) for p in todo]
        for fut in cf.as_completed(futures):
            row = fut.result()
            with lock:
                fh.write(json.dumps(row, allow_nan=False) + "\n")
                fh.flush()
                os.fsync(fh.fileno())
            rows[row["point"]["index"]] = row
            print(_line(row), file=out, flush=True)
            _progress(f"{len(rows)}/{points} done")
    return _summary([rows[i] for i in sorted(rows)], out)


def _summary(rows, out):
    code = _figures(rows, out)
    for stratum in ("window", "tails"):
        part = [r for r in rows if r["point"].get("stratum") == stratum]
        if part and len(part) < len(rows):
            lo, hi = (SPEED_WINDOW if stratum == "window" else
                      (SPEED_TAILS[0][0], SPEED_TAILS[-1][1]))
            print(f"\n## V/V0 {'in' if stratum == 'window' else 'outside'} "
                  f"[{SPEED_WINDOW[0]:g}, {SPEED_WINDOW[1]:g}]"
                  + ("" if stratum == "window" else f" (within [{lo:g}, {hi:g}])"), file=out)
            _figures(part, out)
    return code


def _figures(rows, out):
    """The figures of `rows` (refused, wrong, per-key worst over the estimate, CPU, memory,
    N): 0 when at most 1 % is refused and none is wrong, else 1."""
    refused = [r for r in rows if r["record"] is None]
    answered = [r for r in rows if r["record"] is not None]
    judged = [r for r in answered if r["judged"].get("reference")]
    wrong = [r for r in judged if not r["judged"]["right"]]
    cpu = [r["cpu"] for r in rows]
    n = len(rows)
    print(f"\n- refused: {len(refused)} of {n} ({100.0 * len(refused) / max(n, 1):.1f} %)",
          file=out)
    for r in refused:
        print(f"  - #{r['point']['index']}: {r['error'][:150]} ({r['cpu']:.0f} s CPU)", file=out)
    print(f"- wrong: {len(wrong)} of {len(judged)} answered with a reference "
          f"({len(answered) - len(judged)} answered without one)", file=out)
    for key in dict.fromkeys(JUDGED + JUDGED_PENETRATION + REPORTED):
        vals = [math.inf if r["judged"]["over_estimate"][key] is None else
                r["judged"]["over_estimate"][key] for r in judged
                if key in r["judged"]["over_estimate"]]
        if vals:
            print(f"  - {key}: worst true error / estimate {max(vals):.2g}, "
                  f"{sum(v > 1 for v in vals)} above 1", file=out)
    if cpu:
        slow = max(rows, key=lambda r: r["cpu"])
        print(f"- CPU per point: median {statistics.median(cpu):.1f} s, slowest "
              f"{slow['cpu']:.1f} s (#{slow['point']['index']}); wall median "
              f"{statistics.median(r['wall'] for r in rows):.1f} s", file=out)
        print(f"- peak resident memory of the largest point: "
              f"{max(r['max_rss'] for r in rows) / 2**20:.0f} MiB", file=out)
        nodes = [r["record"]["nodes"] for r in answered]
        if nodes:
            print(f"- N reached: median 2^{math.log2(statistics.median(nodes)):.1f}, "
                  f"largest 2^{math.log2(max(nodes)):.0f}", file=out)
    return 0 if len(refused) <= 0.01 * n and not wrong else 1


def _load_average():
    try:
        one, five, fifteen = os.getloadavg()
    except OSError:  # pragma: no cover
        return "load average unavailable"
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"
