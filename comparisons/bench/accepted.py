"""Measure the semi-analytic road over a random sample of its accepted inputs.

    python -m comparisons bench --accepted [--points N] [--seed S] [--cheap]

Draws N points (default 1000, seed 2024) log-uniformly over `analytic.ACCEPTED` — a quarter under
penetration control, 3 % at speed 0, ratio − 1 log-uniform from one ulp of 1 — solves each and
prints how many succeed, the worst of every consistency residual (`Solution.check()` and the
closure residuals) with the point where it occurred, and every failure with its reason.
``--cheap`` skips `check()` (a few ms to a few s per point) and only asserts the constraints
every answer meets.  The numbers behind the accepted ranges.
"""
from __future__ import annotations

import json
import math
import sys
import time

import numpy as np

import analytic

def draw(rng):
    """One log-uniform point of the accepted box (a dict of solve's keywords)."""
    box = {name: analytic.ACCEPTED[name][:2]
           for name in ("load", "penetration", "speed", "ratio", "hk")}
    pt = {}
    if rng.random() < 0.25:
        pt["penetration"] = 10.0 ** rng.uniform(math.log10(box["penetration"][0]), 0.0)
    else:
        pt["load"] = 10.0 ** rng.uniform(*(math.log10(b) for b in box["load"]))
    low, high = math.log10(analytic.SPEED_MIN), math.log10(box["speed"][1])
    pt["speed"] = 0.0 if rng.random() < 0.03 else 10.0 ** rng.uniform(low, high)
    ratio_max = box["ratio"][1]
    pt["ratio"] = min(1.0 + 10.0 ** rng.uniform(math.log10(2.3e-16), math.log10(ratio_max - 1.0)),
                      ratio_max)
    pt["hk"] = 10.0 ** rng.uniform(*(math.log10(b) for b in box["hk"]))
    for name in ("load", "penetration", "hk"):  # 10**x may round just outside a bound
        if name in pt:
            low, high = box[name]
            pt[name] = min(max(pt[name], low), high)
    return pt


def violations(sol, pt):
    """The constraints every answer must meet that this one does not (empty when valid)."""
    bad = []
    for key in ("load", "ka", "ke_hat", "penetration", "separation", "tau_f", "mu",
                "max_pressure", "x_max_pressure"):
        if not math.isfinite(getattr(sol, key)):
            bad.append(f"{key} not finite")
    if sol.full_contact:
        if not (sol.ka == math.pi and sol.penetration == 1.0 and sol.separation == 0.0):
            bad.append("full contact not exact")
    elif not (0.0 < sol.ka < math.pi and 0.0 < sol.penetration <= 1.0 and sol.separation >= 0.0):
        bad.append("ka or Δ/h out of range")
    if not (sol.mu >= 0.0 and (sol.mu > 0.0) == (sol.speed > 0.0)):
        bad.append(f"mu = {sol.mu!r}")
    if "penetration" in pt and abs(sol.penetration / pt["penetration"] - 1.0) > 1e-11:
        bad.append(f"Δ/h = {sol.penetration!r} asked {pt['penetration']!r}")
    json.dumps(sol.as_dict(), allow_nan=False)
    return bad


def measure(points=1000, seed=2024, cheap=False, out=None) -> int:
    """Solve ``points`` points of `draw` (seeded) and print the study; 0 when every point gives
    a valid answer, else 1."""
    out = sys.stdout if out is None else out
    rng = np.random.default_rng(seed)
    worst, failures, n_ok, n_full = {}, [], 0, 0
    t0 = time.perf_counter()
    for _ in range(points):
        pt = draw(rng)
        try:
            sol = analytic.solve(**pt)
        except Exception as exc:  # counted and printed: this is what the measurement is for
            failures.append((pt, f"{type(exc).__name__}: {exc}"))
            continue
        if not sol.success:
            failures.append((pt, sol.message))
            continue
        bad = violations(sol, pt)
        if bad:
            failures.append((pt, "; ".join(bad)))
            continue
        n_ok += 1
        n_full += sol.full_contact
        items = dict(sol.residuals)
        if not cheap:
            items.update(sol.check())
        for key, val in items.items():
            val = -val if key in ("min_pressure", "min_gap") else val  # worst = most negative
            if key not in worst or val > worst[key][0]:
                worst[key] = (val, pt)
    print(f"{points} points (seed {seed}): {n_ok} valid answers ({n_full} in full contact), "
          f"{len(failures)} failures, {time.perf_counter() - t0:.0f} s", file=out)
    for key, (val, pt) in worst.items():
        shown = -val if key in ("min_pressure", "min_gap") else val
        print(f"  worst {key:20s} {shown: .2e} at {pt}", file=out)
    for pt, why in failures:
        print(f"  FAILED {pt}: {why}", file=out)
    return 0 if not failures else 1
