"""The verdict of a surface verification: each quantity of the finest result against its
tolerance (`comparisons.verify._surface_reference`), the convergence study of all the results,
and the slips the inputs look like (`diagnose`)."""
from __future__ import annotations

import math

import numpy as np

from .._errors import bad_input
from ._diagnose import MIRRORED, SLIP_GAIN
from ._results import Result
from ._study import fit_order
from ._surface_fields import scalars_from_fields, surface_at
from ._surface_reference import (COMMON_MIN, MEASURES, SURFACE_LABELS, SURFACE_NORMS,
                                 SURFACE_SCALARS, measure, norms, reference_uncertainty,
                                 tolerances)
from ._tolerances import DEFAULT_RTOL

#: a pressure that matches the reference times c is reported when c is this far from 1
SCALE_SLIP = 0.01


def surface_result(fields, own, point, ref, option, name, nodes=None):
    """The `Result` of a surface's fields: its scalars derived from them (the solver's own
    ``own`` in their place where it gave them); bad input when its grid shares too few points
    with the reference's or cannot hold the surface."""
    nx, ny = fields["pressure"].shape
    if ref.shared(nx, ny) is None:
        m = ref.fields["pressure"].shape[0]
        raise bad_input(option, name, f"a {nx} x {ny} grid shares fewer than {COMMON_MIN} "
                        f"points a side with the reference's {m} x {m}",
                        f"panels per side a multiple of {COMMON_MIN}")
    sc = scalars_from_fields(fields, point, surface_at(point, nx, ny, option, name))
    source = "fields"
    if own:
        sc.update(own)
        source = "solver (fields for the rest)"
    return Result(nodes or nx, fields, sc, [], source, own=tuple(own))


def _grid(result):
    """N of a result: its fields' points along x, else its ``nodes``."""
    if result.fields is not None:
        return int(result.fields["pressure"].shape[0])
    return result.nodes


def _row(key, value, ref, diff, tol, ref_unc, solver_error=None, note=""):
    """One verdict row, in the shape of the line's (`comparisons.verify._compare`)."""
    tol, reason = tol
    ok = diff is not None and math.isfinite(diff)
    passed = bool(ok and diff <= tol)
    if not note and ref_unc is not None and math.isfinite(ref_unc) and ref_unc > 0.1 * tol:
        note = "the reference's uncertainty exceeds a tenth of the tolerance"
    if solver_error is not None and solver_error > tol:
        note = "; ".join(filter(None, [note, f"the solver's own error estimate "
                                             f"{solver_error:.1e} exceeds the tolerance"]))
    return {"key": key, "label": SURFACE_LABELS[key], "value": value, "reference": ref,
            "difference": diff, "measure": MEASURES[key], "tolerance": tol,
            "tolerance_reason": reason, "derivation_floor": 0.0, "floor_kind": None,
            "reference_uncertainty": ref_unc, "solver_error": solver_error, "passed": passed,
            "note": note}


def evaluate(results, reference, rtol=DEFAULT_RTOL, tol=None, rtol_given=False):
    """Verdicts of the finest result and the convergence study of all of them, in the shape
    of the line's `comparisons.verify.evaluate` (``verdict``, ``quantities``, ``tolerances``,
    ``floors``, ``failed``, ``nodes``, ``convergence``, ``diagnosis``)."""
    results = sorted(results, key=lambda r: (r.nodes is None, r.nodes or 0))
    best = results[-1]
    n = _grid(best)
    columns = tuple(c for c in ("pressure", "displacement", "gap")
                    if best.fields is None or c in best.fields)
    own_keys = tuple(best.own) if best.fields is not None else tuple(best.scalars)
    tols, found, explain = tolerances(reference, n, columns, own_keys, rtol, rtol_given, tol)
    mu_ref = reference.mu
    rows, shown, notes = [], [], []
    errs = best.errors or {}
    for k in SURFACE_SCALARS:
        val = best.scalars.get(k)
        ref, unc = reference.scalars.get(k, (None, None))
        if val is None or ref is None:
            continue
        if k == "n_patches" and found is not None and found != ref:
            notes.append(f"contact patches: not judged on this grid: viscosine's surface BEM "
                         f"on it finds {found}, the reference {ref:g} (yours: {val:g})")
            continue
        own = errs.get(k)
        rows.append(_row(k, val, ref, measure(k, val, ref, mu_ref), tols[k],
                         measure(k, ref + unc, ref, mu_ref) if unc is not None else None,
                         None if own is None else measure(k, ref + own, ref, mu_ref)))
        shown.append(k)
    if best.fields is not None:
        nm = norms(best.fields, reference)
        unc = reference_uncertainty(reference, *best.fields["pressure"].shape)
        for k in SURFACE_NORMS:
            if k in nm:
                rows.append(_row(k, nm[k], 0.0, nm[k], tols[k], unc.get(k)))
                shown.append(k)
    failed = [r["label"] for r in rows if not r["passed"]]
    groups = {}
    for k in shown:
        v, why = tols[k]
        groups.setdefault((f"{v:.1e}", why), []).append(SURFACE_LABELS[k])
    ev = {"verdict": "FAIL" if failed or not rows else "PASS", "quantities": rows,
          "tolerances": [f"{', '.join(labels)}: {v}, {why}" for (v, why), labels in
                         groups.items()] + explain + notes,
          "floors": [], "edges": None, "failed": failed, "nodes": n,
          "convergence": convergence(results, reference) if len(results) > 1 else None}
    ev["diagnosis"] = diagnose(best, reference, ev)
    return ev


def convergence(results, reference):
    """Per quantity: the values and differences from the reference over N, and the order of
    the differences (least squares over N)."""
    res = [r for r in results if r.nodes is not None]
    nodes = [r.nodes for r in res]
    out = {"nodes": nodes, "quantities": {}}
    rows = [norms(r.fields, reference) if r.fields is not None else {} for r in res]
    for k in SURFACE_SCALARS[:-1] + SURFACE_NORMS:
        if k in SURFACE_NORMS:
            vals = [nr.get(k) for nr in rows]
            errs = vals
        else:
            ref = reference.scalars.get(k, (None, None))[0]
            vals = [r.scalars.get(k) for r in res]
            if ref is None:
                continue
            errs = [measure(k, v, ref, reference.mu) for v in vals]
        if any(v is None for v in vals):
            continue
        out["quantities"][k] = {"values": vals, "errors": errs,
                                "order_vs_reference": fit_order(nodes, errs)}
    return out


# ------------------------------------------------------------------------------ diagnosis
def _pressure_l2(fields, reference, p):
    return norms(fields, reference, pressure=p).get("pressure_L2", math.inf)


def _field_slip(fields, reference):
    """A hint when the pressure matches the reference mirrored, moved by one panel, or scaled
    uniformly far better (SLIP_GAIN) than as it is; None otherwise."""
    p = fields["pressure"]
    base = _pressure_l2(fields, reference, p)
    if not base > 0.0:
        return None
    # σ(−x) at x_i is the value at the index −i (mod n): the grid is symmetric about 0
    mirrors = {"x → −x": ((0,), "x is mirrored, or the surface slides along −V·x̂"),
               "y → −y": ((1,), "y is mirrored: θ measured clockwise, or y points the other "
                                "way"),
               "x → −x, y → −y": ((0, 1), "the fields are turned by 180°: the surface slides "
                                          "toward −V (θ + 180°)")}
    tried = []
    for name, (axes, what) in mirrors.items():
        q = p
        for axis in axes:
            q = np.roll(np.flip(q, axis), 1, axis)
        tried.append((_pressure_l2(fields, reference, q), name, what))
    mir, name, what = min(tried)
    if mir < SLIP_GAIN * base:
        return (f"the fields match the reference mirrored ({name}; σ L2 / max σ {base:.1e} → "
                f"{mir:.1e}): {what} (docs/conventions.md, 'Surfaces')")
    moves = [(_pressure_l2(fields, reference, np.roll(p, k, axis)), k, axis)
             for axis in (0, 1) for k in (1, -1)]
    rolled, k, axis = min(moves)
    if rolled < SLIP_GAIN * base:
        way = ("+" if k > 0 else "−") + "xy"[axis]
        return (f"the fields match the reference once moved by one panel toward {way} (σ L2 / "
                f"max σ {base:.1e} → {rolled:.1e}, np.roll by {k:+d} along axis {axis}): "
                f"{'xy'[axis]} is one panel off its values (cell edges written for centres, or "
                "an index counted from 1?)")
    nx, ny = p.shape
    ref, _, (ux, uy) = reference.on_shared(nx, ny)
    pu, pr = p[::ux, ::uy], ref["pressure"]
    c = float(np.sum(pu * pr) / np.sum(pr * pr))
    if c > 0.0 and abs(c - 1.0) > SCALE_SLIP:
        scaled = _pressure_l2(fields, reference, p / c)
        if scaled < SLIP_GAIN * base:
            return (f"σ is {c:.3g} × the reference's everywhere (σ L2 / max σ {base:.1e} → "
                    f"{scaled:.1e} once divided by it): a pressure scale off? viscosine's is "
                    "σ(1 − ν²)/E0 with E0 the relaxed modulus (σ/E0 would be 1/(1 − ν²) = "
                    "1.33 × for ν = 0.5; σ(1 − ν²)/E∞ would be E0/E∞ ×)")
    return None


def diagnose(result, reference, ev):
    """Common slips recognised in a surface result, each a one-line hint: the friction or the
    lateral force of the opposite sign, fields mirrored in x or y, one panel off, or scaled
    uniformly, and pressures in Pa (σ a hundred times the reference's or more)."""
    out = []
    sc = result.scalars
    failed = {r["key"] for r in ev["quantities"] if not r["passed"]}

    def flipped(k, floor):
        v, r = sc.get(k), reference.scalars.get(k, (None, None))[0]
        return (v is not None and r is not None and abs(r) > floor
                and abs(v + r) <= MIRRORED * abs(r))

    if flipped("mu", 0.0):
        out.append(f"μ = {sc['mu']:.6g} against {reference.mu:.6g}: the friction has the "
                   "opposite sign; viscosine counts it positive when it resists the motion "
                   "(docs/conventions.md, 'Surfaces')")
    if flipped("mu_lateral", 1e-3 * abs(reference.mu)):
        out.append(f"μ_lateral = {sc['mu_lateral']:.6g} against "
                   f"{reference.scalars['mu_lateral'][0]:.6g}: the lateral force has the "
                   "opposite sign; viscosine's is the force the solid exerts on the surface, "
                   "along (−sin θ, cos θ), to the left of V")
    f = result.fields
    if f is not None and failed:
        slip = _field_slip(f, reference)
        out += [slip] if slip else []
        nx, ny = f["pressure"].shape
        ref, _, (ux, uy) = reference.on_shared(nx, ny)
        ratio = float(np.max(np.abs(f["pressure"]))) / float(np.max(np.abs(ref["pressure"])))
        if ratio >= 100.0:
            out.append(f"σ is {ratio:.2g} × the reference's: pressures in Pa? the fields are "
                       "in the conventions' units, σ(1 − ν²)/E0 (divide by E0/(1 − ν²))")
    return out
