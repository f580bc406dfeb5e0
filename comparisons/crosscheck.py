"""Cross-solver agreement on a grid of operating points, and the tolerances it is held to.

The grid covers partial contact at three speeds, the neighbourhood of the transition (1 % below
the full-contact load), full contact, light load, and another ratio and hk.  For each point and
mesh, `differences` returns the BEM − semi-analytic differences: relative for Δ/h and μ, absolute
for ka, ke and kê.  The BEM mesh is always pinned (``nodes=N``), never the BEM's adaptive default,
so that the differences are those of a known mesh.

`python -m comparisons crosscheck --nodes 1024 4096 ...` prints the worst of each over the grid
(rounded up); `python -m comparisons crosscheck --tolerances` prints `TOLERANCES`, the agreement
the tests assert, with the measured worst case and the margin of each.
"""
from __future__ import annotations

import math
import sys
from decimal import ROUND_CEILING, ROUND_FLOOR, ROUND_HALF_EVEN, Context
from typing import NamedTuple

from . import operating_point as op
from . import roads, runner

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
#: the meshes of the printed table and of TOLERANCES
NODES = (1024, 4096, 16384, 65536)


def round_up(x, digits=2):
    """The shortest `digits`-digit decimal whose float is ≥ x (a printed bound never below x)."""
    if not (math.isfinite(x) and x > 0):
        return x
    near = float(Context(prec=digits, rounding=ROUND_HALF_EVEN).create_decimal(x))
    return near if near >= x else float(Context(prec=digits, rounding=ROUND_CEILING).create_decimal(x))


def round_down(x, digits=2):
    """The `digits`-digit decimal whose float is ≤ x (for margins: never overstated)."""
    if not (math.isfinite(x) and x > 0):
        return x
    near = float(Context(prec=digits, rounding=ROUND_HALF_EVEN).create_decimal(x))
    return near if near <= x else float(Context(prec=digits, rounding=ROUND_FLOOR).create_decimal(x))


class Tolerance(NamedTuple):
    """One agreement tolerance: the tests assert ``difference < tolerance`` at every grid point.

    Attributes
    ----------
    tolerance : float
        The bound (two significant digits, rounded up from SAFETY × measured).
    measured : float
        The worst difference over the grid, as measured (see MEASURED).
    """

    tolerance: float
    measured: float

    @property
    def margin(self):
        """tolerance / measured (≥ SAFETY by construction)."""
        return self.tolerance / self.measured


#: the factor between the measured worst difference and the tolerance
SAFETY = 3.0
#: when and how the worst differences of TOLERANCES were measured
MEASURED = ("2026-11-24 with `python -m comparisons crosscheck` (BEM at fixed N, nested "
            "iteration, tol 1e-10), 2-core machine")
#: the worst difference over the grid at each N, exactly as measured
_WORST = {
    1024: {"penetration": 8.52861924846855e-06, "mu": 5.958117087084433e-05, "ka": 3.7129945301916933e-05, "ke": 4.199513804421795e-05, "ke_hat": 7.138280287803667e-06},
    4096: {"penetration": 5.985222281786691e-07, "mu": 4.632684662307667e-06, "ka": 2.052761390647362e-06, "ke": 2.1924574411941178e-06, "ke_hat": 6.813897886689957e-07},
    16384: {"penetration": 3.8966842951176935e-08, "mu": 1.3773255188507147e-07, "ka": 8.374041771119778e-08, "ke": 9.719682708686506e-08, "ke_hat": 1.1315187453675435e-08},
    65536: {"penetration": 5.5620355573409775e-09, "mu": 2.5452585377371462e-08, "ka": 7.90625476199125e-09, "ke": 8.790646377487832e-09, "ke_hat": 1.151989385828056e-09},
}


def _tolerances(worst):
    return {n: {k: Tolerance(round_up(SAFETY * v), v) for k, v in row.items()}
            for n, row in worst.items()}


#: N → quantity → Tolerance (relative for penetration and mu, absolute for ka, ke, ke_hat)
TOLERANCES = _tolerances(_WORST)


def _load(load, speed, ratio, hk):
    if isinstance(load, tuple):
        return load[1] * roads.transition_load(speed, ratio, hk)
    return load


def specs(nodes, grid=GRID):
    """The BEM specs of the grid at one mesh, in grid order."""
    return [op.at("bem", speed, load=_load(load, speed, ratio, hk), ratio=ratio, hk=hk,
                  nodes=nodes) for _, load, speed, ratio, hk in grid]


def differences(nodes, grid=GRID, run=runner.run):
    """[(label, spec, analytic record, bem record or None, {key: difference})] at one mesh.

    `run(spec)` returns runner.run's dict; the report passes one that reads its results store.
    """
    rows = []
    for (label, *_), spec in zip(grid, specs(nodes, grid)):
        ref = roads.analytic_solution(spec).as_dict()
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
        rows.append([str(n)] + [f"{round_up(w[k], 3):.2e}" if k in w else "nan" for k in RELATIVE + ABSOLUTE]
                    + [str(sum(x[3] is None for x in r))])
    return head, rows


def print_table(nodes_list):
    """Print the worst differences (rounded up) for each mesh; exit status 1 if a point failed."""
    head, rows = table(nodes_list)
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(r) + " |", flush=True)
    return 1 if any(r[-1] != "0" for r in rows) else 0


def tolerance_rows():
    """(header, rows) of TOLERANCES: N, quantity, tolerance, measured worst (rounded up), margin
    (rounded down)."""
    head = ["N", "quantity", "tolerance", "measured worst", "margin"]
    rows = []
    for n, row in TOLERANCES.items():
        for k in RELATIVE + ABSOLUTE:
            t = row[k]
            kind = "relative" if k in RELATIVE else "absolute"
            rows.append([str(n), f"{k} ({kind})", f"{t.tolerance:.1e}",
                         f"{round_up(t.measured):.1e}", f"{round_down(t.margin):.1f}×"])
    return head, rows


def print_tolerances():
    """Print TOLERANCES as a Markdown table (what the tests assert; nothing is run)."""
    head, rows = tolerance_rows()
    print(f"Agreement tolerances of the cross-solver tests: |BEM − semi-analytic| < tolerance at "
          f"every grid point, the BEM mesh pinned to N. Tolerance = {SAFETY:g} × the measured "
          f"worst, rounded up to two digits; measured {MEASURED}.")
    print()
    print("| " + " | ".join(head) + " |")
    print("|" + "---|" * len(head))
    for r in rows:
        print("| " + " | ".join(r) + " |")
