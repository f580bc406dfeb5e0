"""Cross-solver agreement on a grid of operating points (issue 4's measured targets).

The grid covers partial contact at three speeds, the neighbourhood of the transition (1 % below
the full-contact load), full contact, light load, and another ratio and hk.  For each point and
mesh, `differences` returns the BEM − semi-analytic differences: relative for Δ/h and μ, absolute
for ka, ke and kê.  `python -m comparisons crosscheck --nodes 1024 4096 ...` prints the worst of each over the grid.
"""
from __future__ import annotations

import sys

import analytic

from . import runner

# (label, load, speed, ratio, hk); loads given as a fraction of p̃FC(V) where marked 'fc'
GRID = [
    ("partial, V/V0 = 0.1", 0.3, 0.1, 3.0, 1.0),
    ("partial, V/V0 = 1", 0.3, 1.0, 3.0, 1.0),
    ("partial, V/V0 = 10", 0.3, 10.0, 3.0, 1.0),
    ("near transition, V/V0 = 1", ("fc", 0.99), 1.0, 3.0, 1.0),
    ("near transition, V/V0 = 10", ("fc", 0.99), 10.0, 3.0, 1.0),
    ("full contact, V/V0 = 1", 1.0, 1.0, 3.0, 1.0),
    ("full contact, V/V0 = 0.1", 2.0, 0.1, 3.0, 1.0),
    ("light load, V/V0 = 1", 0.01, 1.0, 3.0, 1.0),
    ("ratio 10, V/V0 = 1", 0.5, 1.0, 10.0, 1.0),
    ("hk 0.5, V/V0 = 3", 0.1, 3.0, 3.0, 0.5),
    ("hk 2, V/V0 = 0.3", 0.6, 0.3, 3.0, 2.0),
]

RELATIVE = ("penetration", "mu")
ABSOLUTE = ("ka", "ke", "ke_hat")


def _load(load, speed, ratio, hk):
    if isinstance(load, tuple):
        return load[1] * analytic.transition_load(speed, ratio, hk)
    return load


def specs(nodes, grid=GRID):
    """The BEM specs of the grid at one mesh, in grid order."""
    return [runner.point_spec("bem", speed, load=_load(load, speed, ratio, hk), ratio=ratio, hk=hk,
                              nodes=nodes) for _, load, speed, ratio, hk in grid]


def differences(nodes, grid=GRID, run=runner.run):
    """[(label, spec, analytic record, bem record or None, {key: difference})] at one mesh.

    `run(spec)` returns runner.run's dict; the report passes one that reads its results store.
    """
    rows = []
    for (label, *_), spec in zip(grid, specs(nodes, grid)):
        ref = analytic.solve(load=spec["load"], speed=spec["speed"], ratio=spec["ratio"], hk=spec["hk"]).as_dict()
        out = run(spec)
        diff = {}
        if out["ok"]:
            rec = out["record"]
            for k in RELATIVE:
                diff[k] = abs(rec[k] - ref[k]) / abs(ref[k])
            for k in ABSOLUTE:
                if ref[k] is not None and rec[k] is not None:
                    diff[k] = abs(rec[k] - ref[k])
            if ref["full_contact"] != rec["full_contact"]:
                diff["full_contact"] = 1.0
        rows.append((label, spec, ref, out["record"] if out["ok"] else None, diff))
    return rows


def worst(rows):
    out = {}
    for *_, d in rows:
        for k, v in d.items():
            out[k] = max(out.get(k, 0.0), v)
    return out


def table(nodes_list, run=runner.run):
    """Markdown rows (header, rows) of the worst differences over the grid for each mesh."""
    head = ["N"] + [f"{k} ({'rel.' if k in RELATIVE else 'abs.'})" for k in RELATIVE + ABSOLUTE] + ["not converged"]
    rows = []
    for n in nodes_list:
        print(f"crosscheck: N = {n}", file=sys.stderr)
        r = differences(n, run=run)
        w = worst(r)
        rows.append([str(n)] + [f"{w.get(k, float('nan')):.2e}" for k in RELATIVE + ABSOLUTE]
                    + [str(sum(x[3] is None for x in r))])
    return head, rows


def print_table(nodes_list):
    head, rows = table(nodes_list)
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(r) + " |", flush=True)
    return 1 if any(r[-1] != "0" for r in rows) else 0
