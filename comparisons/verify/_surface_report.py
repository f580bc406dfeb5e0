"""The report of a surface verification: ``DIR/report.md``, ``DIR/report.html`` (offline,
images embedded), ``DIR/verdict.json`` and the pressure map of the finest result."""
from __future__ import annotations

import datetime
import json
import os
import platform
from pathlib import Path

import numpy as np

import viscosine

from .. import _html
from .. import operating_point as op
from .._io import jsonable, write_text
from ..plots import surfaces as _plots
from . import _surface_fields
from ._report import fmt
from ._surface_reference import SURFACE_LABELS


def _lines(ev):
    table = _html.table
    own = any(r.get("solver_error") is not None for r in ev["quantities"])
    rows = [[r["label"], fmt(r["value"], ".10g"), fmt(r["reference"], ".10g"),
             fmt(r["difference"], ".2e"), r["measure"], fmt(r["tolerance"], ".1e"),
             fmt(r["reference_uncertainty"], ".1e")]
            + ([fmt(r.get("solver_error"), ".1e")] if own else [])
            + ["PASS" if r["passed"] else "FAIL", r["note"]] for r in ev["quantities"]]
    lines = [f"## Verdict per quantity (finest result, N = {ev['nodes']})", "",
             "Differences are relative for μ, Δ/h_ref and p̃∞, absolute for the contact "
             "fraction and the number of patches, and over |μ| of the reference for μ_lateral; "
             "field norms are on the points the solver's grid shares with the reference's "
             "stated grid, σ relative to the reference's max σ, u and gap over h_ref. A "
             "quantity passes when its difference is at most its tolerance.", "",
             table(["quantity", "value", "reference", "difference", "measure", "tolerance",
                    "reference uncertainty"] + (["solver's estimated error"] if own else [])
                   + ["verdict", "note"], rows),
             "### The tolerances, and why", ""]
    lines += [f"- {t}" for t in ev["tolerances"]] + [""]
    if ev["diagnosis"]:
        lines += ["### Diagnosis", "", "Common slips the inputs look like:", ""]
        lines += [f"- {d}" for d in ev["diagnosis"]] + [""]
    conv = ev["convergence"]
    if conv and conv["quantities"]:
        head = ["quantity"] + [f"N = {n}" for n in conv["nodes"]] + ["order vs reference"]
        body = [[SURFACE_LABELS[k]] + [fmt(e, ".2e") for e in q["errors"]]
                + [fmt(q["order_vs_reference"], ".2f")] for k, q in conv["quantities"].items()]
        lines += ["## Convergence study of the solver", "",
                  "Differences from the reference at each N; order: least-squares slope of "
                  "log |difference| against log N.", "", table(head, body)]
    return lines


def markdown(ev, point, reference, label, figures, inputs, case):
    """The report as Markdown."""
    n_fail = len(ev["failed"])
    lines = [f"# viscosine verify: {label}", "",
             f"**Verdict: {ev['verdict']}**" + (
                 f" — {n_fail} of {len(ev['quantities'])} quantities outside their tolerance: "
                 + ", ".join(ev["failed"]) if n_fail else
                 f" — all {len(ev['quantities'])} quantities within their tolerance"), ""]
    op = [["suite case", f"{case['name']}: {case['title']}"]]
    op += [[k, json.dumps(v, ensure_ascii=False) if isinstance(v, dict) else fmt(v)
            if isinstance(v, (int, float)) else str(v)] for k, v in point.items()
           if v is not None]
    lines += ["## Operating point", "", _html.table(["input", "value"], op),
              "## Reference", "", f"The reference is {reference.description}.", ""]
    lines += _lines(ev)
    for name, caption in figures:
        lines += [f"![{caption}]({name})", ""]
    lines += ["## How the scalars are computed from fields", "",
              " ".join(_surface_fields.__doc__.split("From the fields", 1)[1].split()), ""]
    prov = [["viscosine", viscosine.__version__], ["python", platform.python_version()],
            ["numpy", np.__version__],
            ["date (UTC)", datetime.datetime.now(datetime.timezone.utc)
             .strftime("%Y-%m-%d %H:%M:%S")]]
    prov += [[k, v] for k, v in inputs.items()]
    lines += ["## Provenance", "", _html.table(["item", "value"], prov)]
    return "\n".join(lines)


def write_report(folder, ev, point, reference, results, label, inputs, case, figures=True):
    """Write report.md, report.html (offline) and verdict.json into ``folder``."""
    os.makedirs(folder, exist_ok=True)
    figs = []
    best = sorted(results, key=lambda r: r.nodes or 0)[-1]
    if figures and best.fields is not None:
        _plots.write_pressure_map(os.path.join(folder, "pressure.png"), best.fields,
                                  op.direction_of(point),
                                  caption=f"{label}, N = {ev['nodes']}")
        figs.append(("pressure.png", f"σ of {label} on its grid (white: the contact outline; "
                                     "arrow: V)"))
    md = markdown(ev, point, reference, label, figs, inputs, case)
    write_text(Path(folder) / "report.md", md)
    write_text(Path(folder) / "report.html",
               _html.render(md, folder, title=f"viscosine verify: {label}"))
    doc = {"verdict": ev["verdict"], "failed": ev["failed"], "label": label, "point": point,
           "case": case["name"], "geometry": "surface",
           "reference": {"road": reference.road, "description": reference.description},
           "nodes": ev["nodes"], "quantities": ev["quantities"],
           "tolerances": ev["tolerances"], "floors": ev["floors"],
           "diagnosis": ev["diagnosis"], "convergence": ev["convergence"], "inputs": inputs,
           "results": [{"nodes": r.nodes, "source": r.source, "scalars": r.scalars,
                        "estimated_errors": r.errors} for r in results]}
    write_text(Path(folder) / "verdict.json",
               json.dumps(jsonable(doc), indent=1, ensure_ascii=False, allow_nan=False) + "\n")
