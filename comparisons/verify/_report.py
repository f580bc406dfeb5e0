"""The report of a verification: ``DIR/report.md``, ``DIR/report.html`` (offline, images
embedded), ``DIR/verdict.json`` and the figures (the fields, the convergence study and, for a
Prony material, the material's E′, E″ and tan δ with the operating point's sliding frequency
marked).
"""
from __future__ import annotations

import datetime
import json
import math
import os
import platform
from pathlib import Path

import numpy as np

import viscosine

from .. import _html
from .._io import jsonable, write_text
from ..fields import wrap
from ..plots import materials as _materials_plots
from ..plots import verify as _plots
from ._compare import POSITION_PANELS
from ._quantities import LABELS
from ._study import ORDER_FLOOR


def fmt(v, spec=".6g"):
    """A value as the report and the verdict print it ("—" for none, yes/no, inf)."""
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float) and not math.isfinite(v):
        return "inf" if v > 0 else "—"
    return format(v, spec)


def _figures(folder, results, reference, ev, label):
    """Draw the fields of the finest result against the reference's and the convergence study
    into ``folder``: [(file name, caption)]."""
    names = []
    best = sorted(results, key=lambda r: r.nodes or 0)[-1]
    if best.fields is not None:
        f = best.fields
        x = f["x_over_lambda"]
        xw = np.array([wrap(v) for v in x], float)
        order = np.argsort(xw)
        ref, _ = reference.fields(x)
        cols = [k for k in ("pressure", "displacement") if k in f]
        _plots.fields_figure(os.path.join(folder, "fields.png"), xw[order],
                             {k: ref[k][order] for k in cols}, {k: f[k][order] for k in cols},
                             label=label, road=reference.road,
                             title=f"{label}, N = {best.nodes}, against the {reference.road} "
                                   "reference")
        names.append(("fields.png", f"σ and v of {label} (markers) against the reference (lines), "
                                    "and their difference"))
    conv = ev["convergence"]
    if conv and conv["quantities"]:
        curves = [(f"{LABELS[k]}: p = {fmt(q['order_vs_reference'], '.2f')}", q["errors"])
                  for k, q in conv["quantities"].items()]
        _plots.convergence_figure(os.path.join(folder, "convergence.png"), conv["nodes"], curves,
                                  floor=ORDER_FLOOR, title=f"Convergence of {label} against the "
                                                           f"{reference.road} reference")
        names.append(("convergence.png", f"Differences of {label} from the reference against N, "
                                         "with the fitted orders p"))
    return names


def _material_figure(folder, point):
    """E′, E″ and tan δ of the operating point's Prony material, its sliding frequency marked."""
    j0, terms = _materials_plots.prony_numbers(point["prony"])
    speed = float(point["speed"])
    _materials_plots.material_figure(os.path.join(folder, "material.png"), j0, terms,
                                     speeds=[speed], speeds_label=f"sliding frequency kV: ωτ_ref "
                                                                  f"= V/V0 = {speed:g}")
    return ("material.png", f"The material of {Path(point['prony']).name}: storage and loss "
                            f"moduli E′, E″ (units E_ref) and tan δ against ωτ_ref; vertical line: "
                            f"the sliding frequency of the operating point, ωτ_ref = V/V0 = "
                            f"{speed:g}")


def markdown(ev, point, reference, results, label, figures, inputs, case=None):
    """The report as Markdown."""
    lines = [f"# viscosine verify: {label}", ""]
    n_fail = len(ev["failed"])
    lines += [f"**Verdict: {ev['verdict']}**" + (
        f" — {n_fail} of {len(ev['quantities'])} quantities outside their tolerance: "
        + ", ".join(ev["failed"]) if n_fail else
        f" — all {len(ev['quantities'])} quantities within their tolerance"), ""]
    op = [[k, fmt(v) if isinstance(v, (int, float)) else str(v)] for k, v in point.items()
          if v is not None]
    if case:
        op.insert(0, ["suite case", f"{case['name']}: {case['title']}"])
    lines += ["## Operating point", "", _html.table(["input", "value"], op)]
    lines += ["## Reference", "", f"The reference is {reference.description}.", ""]
    lines += _verdict_lines(ev)
    best = sorted(results, key=lambda r: r.nodes or 0)[-1]
    if best.patches or reference.patches:
        lines += _patch_lines(best.patches, ev["edges"])
    for name, caption in figures:
        lines += [f"![{caption}]({name})", ""]
    if ev["convergence"]:
        lines += _convergence_lines(ev["convergence"])
    lines += ["## How the scalars are computed from fields", "", SCALARS_FROM_FIELDS, ""]
    prov = [["viscosine", viscosine.__version__], ["python", platform.python_version()],
            ["numpy", np.__version__],
            ["date (UTC)", datetime.datetime.now(datetime.timezone.utc)
             .strftime("%Y-%m-%d %H:%M:%S")]]
    prov += [[k, v] for k, v in inputs.items()]
    lines += ["## Provenance", "", _html.table(["item", "value"], prov)]
    return "\n".join(lines)


def _verdict_lines(ev):
    """The verdict per quantity, its tolerances and floors, and the diagnosis."""
    table = _html.table
    lines = [f"## Verdict per quantity (finest result, N = {ev['nodes']})", "",
             "Differences are relative for μ, τ̃f, Δ/h, s/h, p̃∞ and 2a/λ, absolute for ka, ke, "
             "kê (rad) and the contact edges (x/λ); field norms are over the solver's grid, σ "
             "relative to the reference's max σ, v and gap in units of h.", ""]
    own = any(r.get("solver_error") is not None for r in ev["quantities"])
    rows = [[r["label"], fmt(r["value"], ".10g"), fmt(r["reference"], ".10g"),
             fmt(r["difference"], ".2e"), r["measure"], fmt(r["tolerance"], ".1e"),
             fmt(r["derivation_floor"], ".1e"), fmt(r["reference_uncertainty"], ".1e")]
            + ([fmt(r.get("solver_error"), ".1e")] if own else [])
            + ["PASS" if r["passed"] else "FAIL", r["note"]] for r in ev["quantities"]]
    lines += [table(["quantity", "value", "reference", "difference", "measure", "tolerance",
                     "floor", "reference uncertainty"]
                    + (["solver's estimated error"] if own else []) + ["verdict", "note"], rows),
              "A quantity passes when its difference is at most its tolerance plus its floor: "
              f"for ka, ke, 2a/λ and the edges on a known grid at least {POSITION_PANELS:g} of a "
              "spacing per contact edge (the grid's resolution of a position), and for a scalar "
              "derived from fields at least what the same derivation gives on the reference's "
              "own fields sampled on the solver's grid (the rectangle rule on point samples of a "
              "field with square-root edges errs by O(M^-1.5))."
              + (" The solver's estimated error is its own (here: the size of the next term of "
                 "its extrapolation to dt → 0); it is shown, not added to the tolerance."
                 if own else ""), ""]
    lines += ["### The tolerances, and why", ""] + [f"- {t}" for t in ev["tolerances"]] + [""]
    if ev.get("floors"):
        lines += ["Floors added to the tolerances:", ""] + [f"- {t}" for t in ev["floors"]] + [""]
    if ev.get("diagnosis"):
        lines += ["### Diagnosis", "", "Common slips the inputs look like:", ""] + [
            f"- {d}" for d in ev["diagnosis"]] + [""]
    return lines


def _patch_lines(patches, edges):
    """The finest result's contact patches and their edges' differences from the reference's."""
    table = _html.table
    prow = []
    for j, p in enumerate(patches, 1):
        prow.append([str(j), fmt(p["trailing_edge"], ".8f"), fmt(p["leading_edge"], ".8f"),
                     fmt(p["load"], ".6g"), fmt(p["ka"], ".8f"), fmt(p["ke"], ".8f"),
                     fmt(p["ke_hat"], ".8f")])
    lines = ["### Contact patches from the solver's fields", "",
             table(["patch", "trailing edge", "leading edge", "load", "ka", "ke", "kê"], prow)
             if prow else "(no fields)\n"]
    if edges:
        lines += [table(["patch", "trailing edge − reference", "leading edge − reference"],
                        [[str(j), f"{a:.2e}", f"{b:.2e}"] for j, (a, b) in enumerate(edges, 1)])]
    return lines


def _convergence_lines(conv):
    """The solver's convergence study: its differences at each N, orders and Richardson."""
    lines = ["## Convergence study of the solver", "",
             "Order vs reference: least-squares slope of log |difference| against log N. "
             "Self-convergence: the order of successive differences and the Richardson "
             "value (comparisons.convergence.study), when N doubles from one result to the next.",
             ""]
    head = ["quantity"] + [f"N = {n}" for n in conv["nodes"]] + [
        "order vs reference", "self order", "Richardson", "Richardson − reference"]
    rows = []
    for k, q in conv["quantities"].items():
        rows.append([LABELS[k]] + [fmt(e, ".2e") for e in q["errors"]]
                    + [fmt(q["order_vs_reference"], ".2f"), fmt(q.get("self_order"), ".2f"),
                       fmt(q.get("richardson"), ".10g"), fmt(q.get("richardson_error"), ".2e")])
    lines += ["Differences from the reference at each N:", "", _html.table(head, rows)]
    lines += [f"- {note}" for note in conv.get("notes", [])] + ([""] if conv.get("notes")
                                                                  else [])
    return lines


SCALARS_FROM_FIELDS = (
    "p̃∞ = mean σ over the grid; τ̃f = −(1/2π) mean σ (ky)′ (eq. 3.1 with ∂v/∂x = ∂y/∂x on the "
    "contact); μ = τ̃f/p̃∞; s/h = mean gap (or, without a gap column, the mean of y/h − v over "
    "the contact points); Δ/h = 1 − s/h; contact points σ > 1e-9 max σ. Each edge by verify's "
    "own fit: σ² inside and gap^(2/3) outside have a simple zero at the edge, and the point "
    "values also carry a discretisation tail that decays away from it (like h/d for a panel "
    "solver, h the spacing, d the distance to the edge), so each side is fitted by least "
    "squares with a cubic plus b h/d over the points ~√M/16 … √M/4 from the edge (d measured "
    "from the zero found so far, iterated) and again over ~√M/16 … √M/2 (a side cut short by "
    "the next edge: its first half, then all of it); the sides whose zero moves by at most "
    "2e-3 h between the two give the edge (averaged; viscosine's BEM places its own edges so). "
    "Without one, plain cubics over ~√M/16 … √M/2, averaged over the sides whose two zeros "
    "agree to 0.1 h (a side that moves more has another scale next to the edge, such as a "
    "relaxation layer), else over both (σ² extrapolated linearly from the last two contact "
    "points when even those are too few). ka = π·width, "
    "ke = 2π(centre − summit), kê = 2π(centroid − summit); in full contact "
    "kê = arg(ŷ_n/σ̂_n)/n in the profile's dominant mode.")


def write_report(folder, ev, point, reference, results, label, inputs, case=None,
                 figures=True):
    """Write report.md, report.html (offline) and verdict.json into ``folder``."""
    os.makedirs(folder, exist_ok=True)
    figs = _figures(folder, results, reference, ev, label) if figures else []
    if figures and point.get("prony"):
        figs.append(_material_figure(folder, point))
    md = markdown(ev, point, reference, results, label, figs, inputs, case)
    write_text(Path(folder) / "report.md", md)
    write_text(Path(folder) / "report.html",
               _html.render(md, folder, title=f"viscosine verify: {label}"))
    doc = {"verdict": ev["verdict"], "failed": ev["failed"], "label": label, "point": point,
           "case": case["name"] if case else None, "reference": {
               "road": reference.road, "description": reference.description},
           "nodes": ev["nodes"], "quantities": ev["quantities"],
           "tolerances": ev["tolerances"], "floors": ev.get("floors", []),
           "diagnosis": ev["diagnosis"], "edges": ev["edges"],
           "convergence": ev["convergence"], "inputs": inputs,
           "results": [{"nodes": r.nodes, "source": r.source, "scalars": r.scalars,
                        "estimated_errors": r.errors, "patches": r.patches} for r in results]}
    write_text(Path(folder) / "verdict.json",
               json.dumps(jsonable(doc), indent=1, ensure_ascii=False, allow_nan=False) + "\n")

