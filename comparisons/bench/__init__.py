"""Benchmarks that print figures (never asserted in tests), run by `python -m comparisons bench`.

`bench` alone times a sweep of the semi-analytic solver through the command line (a fresh
`python -m comparisons sweep` process, as a user runs it) and in process; `--bem` adds the BEM
tables (`bem`: elastic limits, Appendix B, iterations, speed and memory; `trust`: the adaptive
default's cost and the memory per panel), `--bem-only` runs those alone; `--cluster` times one
BEM sweep (default 2000 points at N = 4096) in this process, in two local processes and on a
two-worker local Dask cluster, and checks that all three return the same records in the same
order.  `--honesty` (`trust`), `--materials` (`materials`) and `--accepted` (`accepted`) are
the studies of the BEM's error estimates, of broad Prony spectra and of the semi-analytic road
over its accepted inputs; `--near-transition` (`near_transition`) the BEM just below the
full-contact load through the command line; `--materials-peers` (`materials_peers`) the DMA fit
against pyvisco's and ANSYS's on pyvisco's example master curves; `--materials-fits`
(`materials_fits`) the readers and fits of raw isotherms, E(t)/J(t), FE cards and measured DMA
curves against the truth they were made from; `--surfaces` (`surfaces`) the cost of the surface BEM beside
Tamaas's elastic solver and its adaptive default.  Every table says how loaded the machine was (load average).
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


def _load_average():
    try:
        one, five, fifteen = os.getloadavg()
    except OSError:  # pragma: no cover - platforms without it
        return "load average unavailable"
    return f"load average {one:.2f} {five:.2f} {fifteen:.2f} on {os.cpu_count()} cores"


def cluster_specs(points=2000, nodes=4096):
    """A BEM sweep of `points` points at a pinned mesh: 40 loads × speeds, log-spaced."""
    from .. import operating_point as op
    nload = min(40, points)
    nspeed = max(1, points // nload)
    loads = np.logspace(-2, 0, nload)               # partial and full contact at ratio 3, hk 1
    speeds = np.logspace(-2, 2, nspeed)
    return [op.at("bem", float(s), load=float(p), nodes=nodes)
            for p in loads for s in speeds]


def cluster_sweep(points=2000, nodes=4096):
    """Print the wall time of one BEM sweep in 1 and 2 local processes and on a 2-worker local
    Dask cluster (one thread per worker); 0 when the three return identical records in order."""
    from .. import _cluster, runner
    specs = cluster_specs(points, nodes)
    print(f"# BEM sweep: {len(specs)} points (40 loads log-spaced 1e-2…1, speeds 1e-2…1e2), "
          f"N = {nodes} pinned, ratio 3, hk 1; {_load_average()} before", file=sys.stderr)
    runner.run(specs[0])                             # numba cache and imports, outside the clock
    rows, results = [], {}

    def timed(label, workers=None, scheduler=None):
        print(f"# {label} …", file=sys.stderr, flush=True)
        t0 = time.perf_counter()
        outs = list(runner.run_many(specs, workers=workers, scheduler=scheduler))
        dt = time.perf_counter() - t0
        results[label] = [o["record"] if o["ok"] else o["error"] for o in outs]
        rows.append((label, len(outs), dt, sum(not o["ok"] for o in outs)))

    timed("local, 1 process")
    timed("local, 2 processes", workers=2)
    try:
        from distributed import LocalCluster
    except ImportError:
        print(f"# no Dask cluster: {_cluster.INSTALL_HINT}", file=sys.stderr)
    else:
        with LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                          dashboard_address=None) as cl:
            t0 = time.perf_counter()
            with _cluster.executor(scheduler=cl.scheduler_address) as ex:
                list(ex.imap(runner.run, specs[:2]))  # workers warm (imports, numba cache)
            warm = time.perf_counter() - t0
            timed("Dask LocalCluster, 2 workers", scheduler=cl.scheduler_address)
    print(f"| what | points | wall time [s] | per point [ms] | failed |")
    print("| --- | ---: | ---: | ---: | ---: |")
    for label, n, dt, nf in rows:
        print(f"| {label} | {n} | {dt:.1f} | {1e3 * dt / n:.1f} | {nf} |")
    print(f"\n{_load_average()} after; machine: {os.cpu_count()} cores"
          + (f"; Dask workers warmed in {warm:.1f} s (not counted)" if len(rows) == 3 else ""))
    same = all(r == results["local, 1 process"] for r in results.values())
    print(f"identical records, in order, in every mode: {'yes' if same else 'NO'}")
    return 0 if same else 1


def run(args):
    """`python -m comparisons bench` (its parsed options): the defaults of its options are
    applied here; returns the exit status."""
    if args.cluster:
        return cluster_sweep(2000 if args.points is None else args.points)
    if args.materials_fits:
        from . import materials_fits
        return materials_fits.run()
    if args.materials_peers:
        from . import materials_peers, materials_peers_time
        status = materials_peers.run()
        print()
        materials_peers_time.run()
        return status
    if args.materials:
        from . import materials
        return materials.materials(200 if args.points is None else args.points,
                                   20261125 if args.seed is None else args.seed,
                                   workers=1 if args.workers is None else args.workers)
    if args.honesty:
        from . import trust
        seed = 20261123 if args.seed is None else args.seed
        if args.front_door:
            return trust.front_door(50 if args.points is None else args.points, seed,
                                    light=args.light)
        return trust.honesty(300 if args.points is None else args.points, seed,
                             light=args.light)
    if args.surfaces:
        from . import surfaces
        surfaces.run(12 if args.max_log2n is None else args.max_log2n)
        return 0
    if args.near_transition:
        from . import near_transition
        return near_transition.run(100 if args.points is None else args.points,
                                   near_transition.SEED if args.seed is None else args.seed,
                                   workers=1 if args.workers is None else args.workers,
                                   control="penetration" if args.penetration_control
                                   else "load")
    if args.accepted:
        from . import accepted
        return accepted.measure(1000 if args.points is None else args.points,
                                2024 if args.seed is None else args.seed, cheap=args.cheap)
    points = 1000 if args.points is None else args.points
    max_log2n = 20 if args.max_log2n is None else args.max_log2n
    rc = 0
    if not args.bem_only:
        rc |= analytic_sweep(points)
    if args.bem or args.bem_only:
        from . import bem, trust
        rc |= bem.tables(max_log2n)
        rc |= trust.cost()
        rc |= trust.memory(min(max_log2n, 20))
    return rc
