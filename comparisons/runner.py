"""Glue between the command line / report and the two solvers.

An operating point is a plain dict of dimensionless numbers (`spec`), so that nothing of one road
leaks into the other and a spec can cross a process boundary.  `run` returns a plain dict too:
{"ok", "record" (the JSON object of conventions.md), "error", "fields", "spec", "seconds"}.
"""
from __future__ import annotations

import csv
import math
import os
import time

import numpy as np

DEFAULT_NODES = 4096
DEFAULT_FIELD_POINTS = 1024


def spec_from_args(args, speed, load=None, penetration=None):
    return {"solver": args.solver, "load": load, "penetration": penetration, "speed": speed,
            "ratio": args.ratio, "hk": args.hk, "nodes": args.nodes,
            "profile": getattr(args, "profile", None), "prony": getattr(args, "prony", None)}


def point_spec(solver, speed, load=None, penetration=None, ratio=3.0, hk=1.0, nodes=None):
    return {"solver": solver, "load": load, "penetration": penetration, "speed": speed,
            "ratio": ratio, "hk": hk, "nodes": nodes, "profile": None, "prony": None}


def _finite(name, v, cond, allowed):
    if v is None or isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) or not cond(v):
        raise ValueError(f"{name} = {v!r}: must be {allowed}")


def validate(spec):
    """Raise ValueError (parameter, value, what is allowed) for an invalid operating point."""
    _finite("speed", spec["speed"], lambda v: v >= 0.0, "finite and ≥ 0")
    if spec.get("load") is not None:
        _finite("load", spec["load"], lambda v: v > 0.0, "finite and > 0")
    else:
        _finite("penetration", spec.get("penetration"), lambda v: 0.0 < v <= 1.0, "in (0, 1]")
    _finite("ratio", spec["ratio"], lambda v: v > 1.0, "finite and > 1")
    _finite("hk", spec["hk"], lambda v: v > 0.0, "finite and > 0")
    if spec["solver"] == "analytic":
        import analytic
        analytic.validate(load=spec.get("load"), speed=spec["speed"], ratio=spec["ratio"],
                          hk=spec["hk"], penetration=spec.get("penetration"))
    else:
        nodes = spec.get("nodes")
        if nodes is not None and (isinstance(nodes, bool) or not isinstance(nodes, int) or nodes < 8):
            raise ValueError(f"nodes = {nodes!r}: must be an integer ≥ 8")
        _bem_problem(spec)  # reads and checks --profile / --prony files


def _read(reader, name, path):
    try:
        return reader(path)
    except OSError as exc:
        raise ValueError(f"{name} = {path!r}: cannot read the file ({exc.strerror})") from None


def _bem_problem(spec):
    import bem
    if spec.get("prony"):
        material = _read(bem.read_prony, "prony", spec["prony"])
    else:
        material = bem.Prony.standard_linear_solid(spec["ratio"])
    profile = (_read(bem.read_profile, "profile", spec["profile"]) if spec.get("profile")
               else bem.Sinusoid(spec["hk"]))
    return profile, material


def run(spec, fields=False):
    """Solve one operating point with the solver the spec names."""
    t0 = time.perf_counter()
    out = {"spec": spec, "ok": False, "record": None, "error": None, "fields": None}
    if spec["solver"] == "analytic":
        import analytic
        if spec.get("load") is not None:
            sol = analytic.solve(load=spec["load"], speed=spec["speed"], ratio=spec["ratio"],
                                 hk=spec["hk"])
        else:
            sol = analytic.solve(penetration=spec["penetration"], speed=spec["speed"],
                                 ratio=spec["ratio"], hk=spec["hk"])
        if not sol.success:
            out["error"] = f"{sol.message}; residuals {sol.residuals}"
        else:
            out["ok"] = True
            out["record"] = sol.as_dict()
            if fields:
                n = spec.get("nodes") or DEFAULT_FIELD_POINTS
                f = sol.fields(np.arange(n) / n - 0.5)
                out["fields"] = {"x_over_lambda": f.x_over_lambda, "pressure": f.pressure,
                                 "displacement": f.displacement, "gap": f.gap}
    else:
        import bem
        profile, material = _bem_problem(spec)
        nodes = spec.get("nodes") or DEFAULT_NODES
        res = bem.solve(profile=profile, material=material, speed=spec["speed"], nodes=nodes,
                        load=spec.get("load"), penetration=spec.get("penetration"))
        if not res.success:
            out["error"] = f"{res.message}; residuals {res.residuals}"
        else:
            out["ok"] = True
            # the input load is echoed; with penetration control the load is the BEM's output
            load = spec["load"] if spec.get("load") is not None else float(res.load)
            rec = {"solver": "bem", "load": load, "speed": spec["speed"],
                   "ratio": spec["ratio"] if not spec.get("prony") else None, "hk": spec["hk"],
                   "nodes": nodes, "iterations": res.nit}
            for key in ("full_contact", "contact_fraction", "ka", "ke", "ke_hat", "penetration",
                        "tau_f", "mu"):
                v = getattr(res, key)
                rec[key] = None if v is None else (bool(v) if key == "full_contact" else float(v))
            out["record"] = rec
            if fields:
                out["fields"] = {"x_over_lambda": res.x_over_lambda, "pressure": res.pressure,
                                 "displacement": res.displacement, "gap": res.gap}
    out["seconds"] = time.perf_counter() - t0
    return out


def _run_plain(spec):
    return run(spec)


def run_many(specs, workers=1):
    """Yield run(spec) for each spec, in order, with `workers` processes."""
    if workers is None or workers <= 1 or len(specs) < 2:
        for sp in specs:
            yield run(sp)
        return
    from concurrent.futures import ProcessPoolExecutor
    chunk = max(1, min(64, len(specs) // (8 * workers)))
    with ProcessPoolExecutor(max_workers=workers) as pool:
        yield from pool.map(_run_plain, specs, chunksize=chunk)


def write_fields_csv(path, fields):
    """Write the fields of conventions.md (header line, four columns) to `path`."""
    tmp = f"{path}.part"
    with open(tmp, "w", newline="") as fh:
        w = csv.writer(fh)
        cols = ["x_over_lambda", "pressure", "displacement", "gap"]
        w.writerow(cols)
        for row in zip(*(np.asarray(fields[c], dtype=float) for c in cols)):
            w.writerow([repr(float(v)) for v in row])
    os.replace(tmp, path)
