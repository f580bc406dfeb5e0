"""Benchmarks that print figures (never asserted in tests).

`python -m comparisons bench` times a sweep of the semi-analytic solver through the command line
(a fresh `python -m comparisons sweep` process, as a user runs it) and in process; `--bem` adds the
BEM tables (elastic limits, Appendix B, iterations, speed and memory), `--bem-only` runs those
alone.
"""
from __future__ import annotations

import os
import subprocess
import sys
import time

import numpy as np


def _sweep_cmd(loads, speeds):
    return ([sys.executable, "-m", "comparisons", "sweep", "--solver", "analytic", "--load"]
            + [repr(float(x)) for x in loads] + ["--speed"] + [repr(float(x)) for x in speeds])


def _timed(cmd):
    t0 = time.perf_counter()
    proc = subprocess.run(cmd, capture_output=True, text=True, env=dict(os.environ))
    dt = time.perf_counter() - t0
    if proc.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd[:6])} … failed ({proc.returncode}): {proc.stderr.strip()}")
    return dt, proc.stdout.count("\n")


def analytic_sweep(points=1000):
    """Print the wall time per point of a `points`-point command-line sweep (10 loads × speeds)."""
    nload = 10
    nspeed = max(1, points // nload)
    loads = np.linspace(0.05, 1.4, nload)          # partial and full contact at ratio 3, hk 1
    speeds = np.logspace(-2, 2, nspeed)
    print(f"# analytic sweep through the command line: {nload} loads × {nspeed} speeds "
          f"(log-spaced 1e-2…1e2), ratio 3, hk 1", file=sys.stderr)
    _timed(_sweep_cmd(loads[:1], speeds[:1]))       # warm the numba cache
    start, _ = _timed(_sweep_cmd(loads[:1], speeds[:1]))
    total, lines = _timed(_sweep_cmd(loads, speeds))
    n = nload * nspeed
    # in-process figure: the solver alone, without interpreter start-up or JSON printing
    import analytic
    t0 = time.perf_counter()
    for p in loads:
        for s in speeds:
            analytic.solve(load=p, speed=s)
    inproc = time.perf_counter() - t0
    print("| what | points | wall time [s] | per point [ms] |")
    print("| --- | ---: | ---: | ---: |")
    print(f"| command line, 1 point (interpreter start-up, imports) | 1 | {start:.3f} | — |")
    print(f"| command line sweep, total | {lines} | {total:.3f} | {1e3 * total / n:.3f} |")
    print(f"| command line sweep, start-up subtracted | {lines} | {total - start:.3f} | "
          f"{1e3 * (total - start) / n:.3f} |")
    print(f"| in process (`analytic.solve`) | {n} | {inproc:.3f} | {1e3 * inproc / n:.3f} |")
    return 0 if lines == n else 1


def main(args):
    rc = 0
    if not getattr(args, "bem_only", False):
        rc |= analytic_sweep(args.points)
    if getattr(args, "bem", False) or getattr(args, "bem_only", False):
        from . import _bench_bem
        rc |= _bench_bem.main(["--big-exponent", str(args.max_log2n)])
    return rc
