"""Running the report's runs: each BEM run (`comparisons.runner`) or Tamaas run
(`comparisons.peers.tamaas`) in this process, in local processes or on a Dask cluster
(`comparisons._cluster`), written to the results store (`comparisons.store`) as soon as it is
done, so that an interrupted report loses nothing; progress on standard error.
"""
from __future__ import annotations

import math
import sys
import time

from . import gate, runner
from .progress import Progress


def run(jobs, store, resume, workers, scheduler=None):
    """Run the ``jobs`` not yet in ``store`` (all of them without ``resume``), longest first,
    in ``workers`` local processes or on the Dask ``scheduler``, each result written as it is
    done; progress on standard error.

    Parameters
    ----------
    jobs : list of (spec, with_fields)
    store : comparisons.store.Store
    resume : bool
        Skip the jobs whose results the store holds (each validated).
    workers : int
        Local processes (unused with a scheduler).
    scheduler : str, optional
        A Dask scheduler's address.

    Returns
    -------
    (float, str)
        The seconds spent and where the runs went (local processes or the scheduler's address).
    """
    from . import _cluster
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
    progress = Progress()
    if todo:
        with _cluster.executor(None if scheduler else workers, scheduler) as ex:
            where = (f"Dask scheduler {scheduler} ({ex.workers} workers)" if scheduler else
                     f"{ex.workers} local processes" if ex.workers > 1 else "this process")
            for i, (k, value) in enumerate(ex.imap(_run_one, todo, ordered=False), 1):
                spec, f = todo[k]
                if isinstance(value, _cluster.Failure):  # the worker died: a failed run
                    out = {"ok": False, "record": None, "error": value.error, "seconds": 0.0}
                else:
                    out = value[2]
                store.put(spec, out, f)
                _progress(progress, i, len(todo), t0, spec, out)
    progress.close()
    return time.monotonic() - t0, where


def _progress(progress, i, n, t0, spec, out):
    """The run's line: throttled (`comparisons.progress`), a failure always shown."""
    what = f"load={spec['load']}" if spec["load"] is not None else f"Δ/h={spec['penetration']}"
    if spec["solver"] == "tamaas":
        solver = f"tamaas N={spec['nodes']} dt={spec['cells_per_step']}·T/N"
    elif spec.get("surface") is not None:
        solver = (f"bem surface {spec['surface']['kind']} {spec['nodes']}² "
                  f"θ={spec['direction']:g}°")
    else:
        solver = f"bem N={spec['nodes']}"
        layer = spec.get("layer")
        if layer:
            solver += (f" layer d/λ={layer['thickness_over_wavelength']:g} "
                       f"{layer['foundation']}")
        if spec["hk"] != 1.0:
            solver += f" hk={spec['hk']:g}"
    status = "ok" if out["ok"] else "FAILED"
    line = (f"report: [{i}/{n}] {solver} {what} V/V0={spec['speed']:.4g} "
            f"{status} {out['seconds']:.2f} s ({time.monotonic() - t0:.0f} s)")
    if out["ok"]:
        progress.update(line, final=i == n)
    else:
        progress.say(line)


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
    if spec.get("surface") is not None:  # nodes a side: N² log N
        return float(spec["nodes"]) ** 2
    return float(spec["nodes"])


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
