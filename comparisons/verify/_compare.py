"""The verdict of a verification: each quantity of the finest result against its tolerance
plus its floor, and the convergence study of all the results.

A quantity passes when its difference is at most its tolerance plus its floor, each floor stated
too: on a known grid, 0.1 of a spacing per contact edge for ka, ke, 2a/λ and the edges
(POSITION_PANELS: a correct solver's edges err by up to ~0.05 of a spacing with where each falls
in its cell, which e_N of one solver does not sample), and for a scalar derived from fields, at
least what the same derivation gives on the reference's own fields sampled on the same grid
(`derivation_floor`).  The verdict also names common slips the inputs look like (`diagnose`: a
mirrored sign or x, SI values without ``--units SI``, fields one panel off their x).
"""
from __future__ import annotations

import math

from viscosine.fields import WIDTH

from ._diagnose import diagnose
from ._quantities import COMPARED_KEYS, LABELS, REL, edge_differences, measure, norms
from ._reference import Reference
from ._results import Result
from ._scalars import scalars_from_fields
from ._study import convergence, order_notes
from ._tolerances import DEFAULT_RTOL, grid_size, tolerance_lines, tolerances

#: On a grid of N points no position is judged finer than this fraction of a spacing per contact
#: edge (`position_floor`, added to the tolerance like the derivation floor): a correct solver's
#: edges err by a few hundredths of a spacing, varying with where each edge falls in its cell, and
#: an edge read from fields cannot know how the solver discretised next to it; e_N samples one
#: solver at one such place.  Measured over the suite's 13 partial-contact SLS cases at N = 512 …
#: 4096 on viscosine's BEM and the Fourier collocation (analytic.fourier_solve, shifts=1), their
#: own ka, ke, 2a/λ and those derived from their fields, each over the spacing it implies per
#: edge: at most 0.047 (an edge from the Fourier fields, sls-hk0.05, N = 512; its own ka at
#: sls-light-v1 0.040, the BEM's 0.037).  A tenth is twice that, and a tenth of the one-panel
#: shift that must fail
POSITION_PANELS = 0.1


def derivation_floor(result: Result, reference: Reference):
    """What the derivation of scalars from fields costs on the result's grid.

    The same derivation (:func:`scalars_from_fields`) applied to the reference's own fields
    sampled on the result's grid (with the columns the result has), measured against the
    reference's scalars and edges.  A result whose fields are the reference's own samples differs
    by exactly this much; the verdict allows it on top of the tolerance.
    """
    if result.fields is None:
        return {}
    x = result.fields["x_over_lambda"]
    ref, _ = reference.fields(x)
    f = {"x_over_lambda": x, **{k: ref[k] for k in ("pressure", "displacement", "gap")
                                 if k in result.fields}}
    if WIDTH in result.fields:  # the same cells
        f[WIDTH] = result.fields[WIDTH]
    sc, patches = scalars_from_fields(f, reference.shape)
    out = {}
    for k in COMPARED_KEYS:
        if k in sc and k in reference.scalars and result.source == "fields":
            out[k] = measure(k, sc[k], reference.scalars[k][0])
    edges = edge_differences(reference.patches, patches) if reference.patches else None
    if edges:
        out["edges"] = max(max(abs(a), abs(b)) for a, b in edges)
    return out


def _points(result, reference):
    """N of a result: `grid_size` of its fields, else its ``nodes`` (None when not known)."""
    return grid_size(result.fields, reference)[0] if result.fields is not None else result.nodes


def position_floor(result: Result, reference: Reference):
    """The grid's resolution of the positions: {key: floor in the verdict's measure}.

    POSITION_PANELS of a spacing per contact edge on the result's grid (`grid_size` of its
    fields, else its ``nodes``): the edges POSITION_PANELS/N (x/λ), ka and ke 2π POSITION_PANELS/N
    (both edges off), 2a/λ 2 P POSITION_PANELS/N over the reference's 2a/λ (P patches).  Empty
    when N is not known or the reference has no patches (full contact).
    """
    n = _points(result, reference)
    if not n or not reference.patches:
        return {}
    d = POSITION_PANELS / n
    out = {"edges": d}
    c = reference.scalars.get("contact_fraction", (None, None))[0]
    if c:
        out["contact_fraction"] = 2.0 * len(reference.patches) * d / c
    if len(reference.patches) == 1:
        out["ka"] = out["ke"] = 2.0 * math.pi * d
    return out


def _floor_lines(rows, n):
    """One line per kind of floor that some row shown carries: the position floor (its values)
    and the derivation floor."""
    lines = []
    pos = [r for r in rows if r.get("floor_kind") == "position"]
    if pos:
        vals = ", ".join(f"{r['label']} {r['derivation_floor']:.1e}" for r in pos)
        lines.append(f"{', '.join(r['label'] for r in pos)}: + {POSITION_PANELS:g} spacing per "
                     f"edge on N = {n:.0f} ({vals}): a correct solver's edges err by up to ~0.05 "
                     "spacing, with where each edge falls in its cell, which e_N (one solver) "
                     "does not sample")
    der = [r["label"] for r in rows if r.get("floor_kind") == "derivation"]
    if der:
        lines.append(f"{', '.join(der)}: + what the same derivation from fields errs by on the "
                     "reference's own fields sampled on this grid (each in the report)")
    return lines


def evaluate(results, reference: Reference, rtol=DEFAULT_RTOL, tol=None, rtol_given=None,
             si=False):
    """Verdicts of the finest result, and the convergence study of all of them.

    A quantity passes when its difference from the reference is at most its tolerance
    (`tolerances`: for the scalars and the edges max(rtol, GRID_FACTOR · e_N) on the finest
    result's grid, or ``rtol`` when that grid is not known or ``rtol`` was asked for; the grid's
    FIELD_LAW for the field norms; ``tol`` for any) plus its floor: the larger of, for ka, ke,
    2a/λ and the edges on a known grid, the grid's resolution of a position (`position_floor`)
    and, for a quantity derived from fields, the derivation floor on the same grid
    (:func:`derivation_floor`).

    Returns
    -------
    dict
        ``verdict`` ("PASS"/"FAIL"), ``quantities`` (rows: key, label, value, reference,
        difference, measure, tolerance, tolerance_reason, derivation_floor (the floor added,
        whichever kind), floor_kind ("position", "derivation" or None without a floor),
        reference_uncertainty, solver_error (the solver's own estimate of its error, in the
        same measure, when it gave one), passed, note), ``tolerances`` (one line per
        tolerance: the quantities, the value and why), ``floors`` (one line per kind of floor
        added, and why), ``edges``, ``failed`` (the labels of
        the failing quantities), ``nodes``, ``convergence`` (or None; its ``notes`` say what
        negative orders mean, `order_notes`) and ``diagnosis``
        (common slips recognised in the inputs: `diagnose`; ``si``: the inputs were
        converted from SI units).
    """
    results = sorted(results, key=lambda r: (r.nodes is None, r.nodes or 0))
    best = results[-1]
    tols = tolerances(rtol, tol, best.fields, reference, rtol_given, nodes=best.nodes)
    derived = derivation_floor(best, reference)
    position = position_floor(best, reference)
    floor = {k: (max(derived.get(k, 0.0), position.get(k, 0.0)),
                 "position" if position.get(k, 0.0) > derived.get(k, 0.0) else "derivation")
             for k in set(derived) | set(position)}
    rows = _scalar_rows(best, reference, tols, floor)
    nm, nm_unc, _ = norms(best, reference)
    for k, v in nm.items():
        rows.append(_row(k, v, 0.0, v, "relative to max σ" if k.startswith("pressure")
                         else "absolute (over h)", tols[k], nm_unc.get(k), 0.0))
    edges, row = _edge_row(best, reference, tols["edges"], floor.get("edges", (0.0, None)))
    rows += [row] if row else []
    failed = [r["label"] for r in rows if not r["passed"]]
    shown = [r["key"] for r in rows]
    ev = {"verdict": "FAIL" if failed or not rows else "PASS", "quantities": rows,
          "tolerances": tolerance_lines(tols, shown),
          "floors": _floor_lines(rows, _points(best, reference)), "edges": edges,
          "failed": failed,
          "nodes": best.nodes,
          "convergence": convergence(results, reference) if len(results) > 1 else None}
    if ev["convergence"]:
        ev["convergence"]["notes"] = order_notes(ev["convergence"], rows)
    ev["diagnosis"] = diagnose(best, reference, ev, si=si)
    return ev


def _scalar_rows(best, reference, tols, floor):
    """The verdict rows of the scalars the result and the reference both give."""
    errs = best.errors or {}
    rows = []
    for k in COMPARED_KEYS:
        val = best.scalars.get(k)
        ref, unc = reference.scalars.get(k, (None, None))
        if val is None or ref is None:
            continue
        d = measure(k, val, ref)
        unc_m = unc / abs(ref) if (k in REL and ref) else unc
        own = errs.get(k)
        if own is not None and k in REL and ref:
            own = own / abs(ref)
        rows.append(_row(k, val, ref, d, "relative" if k in REL else "absolute (rad)",
                         tols[k], unc_m, *floor.get(k, (0.0, None)), solver_error=own))
    return rows


def _edge_row(best, reference, tol, floor):
    """(edge differences or None, the verdict row of the contact edges or None): with fields
    and a reference that knows its contact, a patch count or full contact that differs fails."""
    if best.fields is None or reference.full_contact is None:
        return None, None
    full = best.scalars.get("full_contact")
    if reference.full_contact or full:
        if bool(full) == bool(reference.full_contact):
            return None, None
        return None, _row("edges", math.inf, 0.0, math.inf, "absolute (x/λ)", tol, None, 0.0,
                          note=f"full contact: {full}, reference {reference.full_contact}")
    edges = edge_differences(reference.patches, best.patches)
    if edges is None:
        return None, _row("edges", math.inf, 0.0, math.inf, "absolute (x/λ)", tol, None, 0.0,
                          note=f"{len(best.patches)} patches, reference "
                               f"{len(reference.patches)}")
    worst = max(max(abs(a), abs(b)) for a, b in edges)
    return edges, _row("edges", worst, 0.0, worst, "absolute (x/λ)", tol, None, *floor)


def _row(key, value, ref, diff, measure, tol, ref_unc, floor, floor_kind=None, note="",
         solver_error=None):
    """One verdict row.  ``floor``: added to the tolerance; ``floor_kind``: "position" (the
    grid's resolution of a position, `position_floor`) or else the derivation floor."""
    tol, reason = tol
    floor = floor or 0.0
    position = floor_kind == "position"
    ok_diff = diff is not None and math.isfinite(diff)
    passed = bool(ok_diff and diff <= tol + floor)
    if not note:
        if floor > 0.0 and ok_diff and tol < diff <= tol + floor:
            note = ("the grid limits this check: the difference is within "
                    + (f"{POSITION_PANELS:g} of a spacing per edge ({floor:.1e})" if position else
                       f"what the same derivation errs by on the reference's own fields on this "
                       f"grid ({floor:.1e})"))
        elif floor > tol and ok_diff and diff > tol + floor:
            note = ("not explained by the grid: " + (
                f"it resolves a position to {floor:.1e}" if position else
                f"the derivation on this grid errs by only {floor:.1e}"))
        elif ref_unc is not None and math.isfinite(ref_unc) and ref_unc > 0.1 * tol:
            note = "the reference's uncertainty exceeds a tenth of the tolerance"
        if solver_error is not None and solver_error > tol:
            note = "; ".join(filter(None, [note, f"the solver's own error estimate "
                                                 f"{solver_error:.1e} exceeds the tolerance"]))
    return {"key": key, "label": LABELS[key], "value": value, "reference": ref,
            "difference": diff, "measure": measure, "tolerance": tol, "tolerance_reason": reason,
            "derivation_floor": floor, "floor_kind": floor_kind if floor > 0.0 else None,
            "reference_uncertainty": ref_unc,
            "solver_error": solver_error, "passed": passed, "note": note}

