"""The convergence study of the solver under test over several resolutions.

Per quantity the order of its error against the reference (least-squares slope over N), the
self-convergence order and Richardson value (:func:`comparisons.convergence.study`, the suite's
certification rule), and the error of the Richardson value.
"""
from __future__ import annotations

import math

from ..convergence import LAST, observed_order, study
from ._quantities import COMPARED_KEYS, LABELS, NORM_KEYS, measure, norms

ORDER_FLOOR = 1e-12  # differences below this are round-off: left out of the order fit


def fit_order(nodes, errors):
    """Order p of err ∝ N^−p: least squares over the finite errors above ORDER_FLOOR (NaN when
    fewer than two remain)."""
    return observed_order(nodes, errors, ORDER_FLOOR)


def convergence(results, reference):
    """Per quantity: values and errors against the reference over N, the order of the error,
    the self-convergence order and Richardson value, and the Richardson value's error."""
    res = [r for r in results if r.nodes is not None]
    nodes = [r.nodes for r in res]
    out = {"nodes": nodes, "quantities": {}}
    norm_rows = [norms(r, reference)[0] for r in res]
    for k in COMPARED_KEYS + NORM_KEYS[:-1]:
        if k in COMPARED_KEYS:
            vals = [r.scalars.get(k) for r in res]
            ref = reference.scalars.get(k, (None, None))[0]
            if ref is None or any(v is None for v in vals):
                continue
            errs = [measure(k, v, ref) for v in vals]
        else:
            vals = [nr.get(k) for nr in norm_rows]
            if any(v is None for v in vals):
                continue
            errs, ref = vals, 0.0
        q = {"values": vals, "errors": errs, "order_vs_reference": fit_order(nodes, errs)}
        if k in COMPARED_KEYS and len(vals) >= 3 and _doubling(nodes):
            st = study(nodes, vals, last=min(LAST, len(vals) - 1))
            q.update(self_order=st["order"], richardson=st["richardson"],
                     richardson_error=measure(k, st["richardson"], ref)
                     if math.isfinite(st["richardson"]) else None)
        out["quantities"][k] = q
    return out


def _doubling(nodes):
    return all(b == 2 * a for a, b in zip(nodes[:-1], nodes[1:]))


def order_notes(conv, rows):
    """What negative orders mean, one line per kind (empty when every order is ≥ 0).

    An order below 0 says the differences grew with N over the study's range: not a rate.
    Where the finest difference is within its tolerance (``rows``: the verdict rows), the
    differences sit at the level of the reference's uncertainty or the solver's round-off and
    scatter; elsewhere the grids are pre-asymptotic (too coarse for the leading error term to
    dominate), or the solver converges to another answer, which the verdict then shows.
    """
    if not conv:
        return []
    passed = {r["key"]: r["passed"] for r in rows}
    noise, early = [], []
    for k, q in conv["quantities"].items():
        for name in ("order_vs_reference", "self_order"):
            p = q.get(name)
            if p is not None and math.isfinite(p) and p < 0.0:
                (noise if passed.get(k) else early).append(LABELS[k])
                break
    n = conv["nodes"]
    span = f"N = {min(n)} … {max(n)}" if n else "these N"
    out = []
    if early:
        out.append(f"{', '.join(early)}: negative orders over {span} are pre-asymptotic, not "
                   "rates: the differences do not yet fall with N (the grids are too coarse for "
                   "the leading error term to dominate), or the solver converges to another "
                   "answer; add finer resolutions before reading an order")
    if noise:
        out.append(f"{', '.join(noise)}: negative orders, but the finest difference is within "
                   "its tolerance: the differences are at the level of the reference's "
                   "uncertainty or the solver's round-off, where no order can be measured")
    return out
