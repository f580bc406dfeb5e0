"""One line case of the suite computed and certified (`compute`: the BEM's meshes, the
references, the certified scalars, patches and fields under `comparisons.suite_cases.RULE`; a
surface case goes to `comparisons.suite_surfaces.compute_surface`), and the case's fields file
(`write_fields`, `case_fields`).  `comparisons.suite` re-exports every name.
"""
from __future__ import annotations

import csv
import io
import math
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from . import roads as _roads
from ._errors import SuiteError
from ._io import read_columns, write_text
from .convergence import digits, rounded, study
from .fields import PATCH_KEYS, match_patches, neighbour_max, patch_records
from .suite_cases import (BEM_PRESSURE_FLOOR, FIELD_COLUMNS, FIELD_FLOOR, FIELD_POINTS,
                          LAYER_KEYS, SAFETY, _num, _problem, increasing_meshes, is_surface,
                          reference_of, two_roads)
from .suite_inputs import DATA, ProfileShape
from .suite_surfaces import compute_surface, surface_fields

# --------------------------------------------------------------------------- one case
def _scalar_keys(point, full_contact, n_patches):
    keys = ["mu", "tau_f"]
    if point.get("load") is None:
        keys += ["load"]
    elif not full_contact:  # in full contact Δ/h = 1 and s = 0 exactly
        keys += ["penetration", "separation"]
    if not full_contact:
        keys += ["contact_fraction"]
        if n_patches == 1:
            keys += ["ka", "ke"]
    if full_contact or n_patches == 1:
        keys += ["ke_hat"]
    if point.get("layer"):
        # the approach is Δ/h (1 in full contact) plus the mean compression, which under load
        # control is exact (`_exact`): in full contact under load control both are exact
        if point.get("load") is None:
            keys += ["approach", "mean_displacement"]
        elif not full_contact:
            keys += ["approach"]
    return keys


def _value(obj, key):
    """Scalar ``key`` of a BEM or Fourier result as a float (NaN when it has none); a layer's
    ``approach`` and ``mean_displacement`` are in the BEM's ``diagnostics["layer"]``."""
    v = getattr(obj, key, None)
    if v is None and key in LAYER_KEYS and obj is not None:
        v = (getattr(obj, "diagnostics", None) or {}).get("layer", {}).get(key)
    return float("nan") if v is None else float(v)


#: the Fourier reference's estimates are relative for these (absolute for ka, ke, ke_hat)
_FOURIER_RELATIVE = ("load", "penetration", "tau_f", "mu", "contact_fraction", "approach",
                     "mean_displacement")


def _fourier_evidence(ref, key):
    """(value, absolute error estimate) of scalar ``key`` from a Fourier result (NaN when it
    does not give one)."""
    v = _value(ref, key)
    est = ref.error_estimate or {}
    if key == "separation":  # s/h = 1 − Δ/h: the absolute error of Δ/h
        e = est.get("penetration")
        e = float("nan") if e is None else float(e) * abs(_value(ref, "penetration"))
    else:
        e = est.get(key)
        e = float("nan") if e is None else float(e) * (abs(v) if key in _FOURIER_RELATIVE
                                                         else 1.0)
    return v, e


FOURIER_METHOD = "bem convergence + fourier reference"


def _certify(value_ref, seq_nodes, seq_values, roads, fourier=None):
    """One scalar's record.  ``roads``: the semi-analytic value ``value_ref`` is certified; else
    the BEM's q_R, checked against ``fourier`` ((value, absolute estimate) of the Fourier
    reference; (NaN, NaN) when it failed) when given."""
    st = study(seq_nodes, seq_values)
    ev = {"nodes": [int(n) for n in seq_nodes], "values": [_num(v) for v in seq_values],
          "order": _num(st["order"]), "richardson": _num(st["richardson"]),
          "estimate": _num(st["estimate"]), "regime": st["regime"]}
    if fourier is not None:
        value = st["richardson"]
        gap = abs(value - fourier[0])
        # the digits both roads agree on, never more than the BEM's own study supports; no
        # reference value (a failed reference) leaves no agreement to certify
        err = max(SAFETY * st["estimate"], gap) if math.isfinite(gap) else math.inf
        nd = digits(value, err)
        return {"value": _num(value), "digits": nd, "rounded": rounded(value, nd),
                "error": _num(err), "method": FOURIER_METHOD, "bem": ev,
                "fourier": {"value": _num(fourier[0]), "estimate": _num(fourier[1])}}
    if roads:
        # the BEM's best value: extrapolated when its study is asymptotic, else the finest mesh
        # (no study at all, e.g. a failed mesh, certifies nothing)
        best = st["richardson"] if st["regime"] == "asymptotic" else st["finest"]
        value = value_ref
        err = abs(value_ref - best) if (math.isfinite(best) and math.isfinite(value_ref)
                                        and st["regime"] != "too few meshes") else math.inf
        how = "two roads"
    else:
        value = st["richardson"]
        err = SAFETY * st["estimate"]
        how = "bem convergence"
    nd = digits(value, err)
    rec = {"value": _num(value), "digits": nd, "rounded": rounded(value, nd), "error": _num(err),
           "method": how, "bem": ev}
    if roads:
        rec["analytic"] = _num(value_ref)
    return rec


def compute(case, base=DATA, progress=None):
    """Recompute one case: its certified scalars, patches and fields.

    Parameters
    ----------
    case : dict
        A case of ``suite.json`` (``name``, ``point``, ``nodes``).
    base : path
        Where the profile and Prony files of the case are.
    progress : callable, optional
        Called with one line of text per mesh.

    Returns
    -------
    (dict, dict)
        The ``certified`` record (as stored in ``suite.json``) and the fields columns on the
        stated grid (``x_over_lambda`` and, for each of FIELD_COLUMNS, the value and ``<col>_err``).
    """
    if is_surface(case):
        return compute_surface(case, progress)
    point = case["point"]
    nodes = increasing_meshes(case)
    roads = two_roads(point)
    reference = reference_of(case)
    problem = _problem(point, base)
    shape = ProfileShape(point, base)
    M = _field_points(case, nodes)
    meshes = _solve_meshes(point, nodes, problem, shape, M, progress)
    ref, four, ref_failures = _references(point, roads, reference, problem[1])
    four_ok = four is not None and bool(four.success)
    full = _full_contact(meshes.runs, ref)
    npatch = _patch_count(meshes.patches, full, roads)
    scalars = _certified_scalars(_scalar_keys(point, full, npatch), meshes, ref, four, four_ok,
                                 roads, full)
    patch_out = _certified_patches(meshes, full, npatch)
    fields, field_summary = _certified_fields(point, nodes, meshes.grid_fields, ref, M, roads)
    status, notes = _status(meshes.failures + ref_failures, meshes.runs, full,
                            four if four_ok else None)
    method = "two roads" if roads else FOURIER_METHOD if four is not None else "bem convergence"
    certified = {"method": method, "status": status,
                 "notes": notes, "scalars": scalars, "exact": _exact(point, full, problem),
                 "patches": patch_out, "fields": field_summary}
    if four is not None:
        certified["reference"] = _reference_record(four, four_ok)
    return certified, fields


def _field_points(case, nodes):
    """M, the points of the stated grid of the fields; SuiteError unless the two finest meshes
    are multiples of M (the grid's points are then panel centres of both)."""
    M = int(case.get("field_points", FIELD_POINTS))
    if nodes[-1] % M or nodes[-2] % M:
        raise SuiteError(f"case {case['name']}: the two finest meshes must be multiples of {M}")
    return M


class _Meshes(NamedTuple):
    """The BEM on every mesh of a case (`_solve_meshes`), coarse to fine."""

    nodes: list        # the meshes N
    runs: list         # the solution on each, None where the solve failed
    patches: list      # the patches on each (`patch_records`), None where the solve failed
    grid_fields: dict  # N -> the fields on the stated grid, for the two finest meshes solved
    failures: list     # a line per failed solve


def _solve_meshes(point, nodes, problem, shape, M, progress):
    """Solve the BEM on every mesh (`_Meshes`), with its patches and, on the two finest, its
    fields on the stated grid of M points; ``progress`` gets a line per mesh."""
    runs, patches, failures = [], [], []
    grid_fields = {}
    t0 = time.perf_counter()
    # each mesh is solve(nodes=n)'s answer; the grids below it are solved once for all meshes
    for n, r in zip(nodes, _roads.bem_meshes(point, nodes, problem), strict=True):
        runs.append(r if r.success else None)
        if not r.success:
            failures.append(f"N = {n}: {r.message.splitlines()[0][:200]}")
        patches.append(patch_records(r, shape) if r.success else None)
        if n in nodes[-2:] and r.success:
            # the stated grid's points are panel centres of N = n (a multiple of M): the
            # linear resampling gives the panel values themselves, not averages
            g = r.fields().resample(M, method="linear")
            grid_fields[n] = {c: getattr(g, c) for c in ("x_over_lambda",) + FIELD_COLUMNS}
        if progress:
            progress(f"N = {n}: {'ok' if r.success else 'FAILED'} "
                     f"({time.perf_counter() - t0:.2f} s)")
        t0 = time.perf_counter()
    return _Meshes(nodes, runs, patches, grid_fields, failures)


def _references(point, roads, reference, material):
    """(ref, four, failures): the semi-analytic solution on two roads (None otherwise, and None
    when it failed: nothing of it is then used), the Fourier reference when the case declares
    it (kept when it failed: the record says what it said) and a line per failure."""
    failures = []
    ref = _roads.analytic_solution(point) if roads else None
    if ref is not None and not ref.success:
        failures.append(f"semi-analytic: {ref.message}")
        ref = None
    four = _roads.fourier_solution(point, material) if reference == "fourier" else None
    if four is not None and not four.success:
        failures.append(f"Fourier reference: {four.message.splitlines()[0][:200]}")
    return ref, four, failures


def _full_contact(runs, ref):
    """Whether the case is in full contact: as the semi-analytic solution ``ref`` says, else as
    the finest mesh solved says (False when none was)."""
    if ref is not None:
        return bool(ref.full_contact)
    fin = next((r for r in reversed(runs) if r is not None), None)
    return bool(fin.full_contact) if fin is not None else False


def _patch_count(patches, full, roads):
    """The contact patches to certify: one in full contact, else the finest mesh's; when that
    mesh failed, one on two roads (the sinusoid) and none otherwise."""
    if full:
        return 1
    if patches[-1] is not None:
        return len(patches[-1])
    return 1 if roads else 0


def _certified_scalars(keys, meshes, ref, four, four_ok, roads, full):
    """The record of each scalar of ``keys`` (`_certify`): the BEM's study over the meshes,
    with the semi-analytic solution ``ref`` on two roads, or checked against the Fourier
    reference ``four`` when the case declares one (no agreement to certify when it failed)."""
    scalars = {}
    for k in keys:
        seq = [_value(r, k) if r is not None else float("nan") for r in meshes.runs]
        if k in ("ka", "ke", "ke_hat") and not full and not roads:
            # single patch on another profile: measured from its summit
            seq = [p[0][k] if p and len(p) == 1 else float("nan") for p in meshes.patches]
        a = _value(ref, k) if ref is not None else float("nan")
        fv = None
        if four is not None:
            fv = _fourier_evidence(four, k) if four_ok else (float("nan"), float("nan"))
        scalars[k] = _certify(a, meshes.nodes, seq, roads and ref is not None, fv)
        if roads and ref is None:
            scalars[k]["method"] = "two roads (semi-analytic failed)"
    return scalars


def _certified_patches(meshes, full, npatch):
    """The record of each quantity of each patch (PATCH_KEYS, BEM convergence) when there are
    several, the patches of every mesh matched to the finest mesh's."""
    patch_out = []
    if not full and npatch > 1:
        matched = [match_patches(meshes.patches[-1], p) for p in meshes.patches]
        for j in range(npatch):
            rec = {}
            for k in PATCH_KEYS:
                seq = [m[j][k] if m[j] is not None else float("nan") for m in matched]
                rec[k] = _certify(float("nan"), meshes.nodes, seq, False)
            patch_out.append(rec)
    return patch_out


def _exact(point, full, problem=None):
    """The quantities exact by construction: full contact or not, an imposed Δ/h, and in full
    contact ka = π, 2a/λ = 1, Δ/h = 1, s/h = 0 and no ke; on a layer under load control the
    mean compression (`layer_compression`) and, in full contact, the approach 1 + it."""
    exact = {"full_contact": full}
    if point.get("penetration") is not None:
        exact["penetration"] = float(point["penetration"])
    if full:
        exact.update(ka=math.pi, contact_fraction=1.0, penetration=1.0, separation=0.0, ke=None)
    if point.get("layer") and point.get("load") is not None:
        mean = layer_compression(point, problem or _problem(point))
        exact["mean_displacement"] = mean
        if full:
            exact["approach"] = 1.0 + mean
    return exact


def layer_compression(point, problem):
    """v̄₀/h, the mean compression of a load-controlled point's layer over h: the uniform mode
    under the mean pressure p̃ (static in the frame of the indenter: the relaxed compliance J0),
    ``C (k d) J0 p̃ / hk`` with C the layer's uniform compliance (``docs/layers.md`` §4, §7; 0
    for a bonded incompressible layer), in the order of operations of the BEM's own."""
    lay = _roads.layer(point["layer"])
    profile, material = problem
    return lay.uniform * lay.thickness * float(material.J0) * float(point["load"]) \
        / float(profile.amplitude)


def _status(failures, runs, full, four):
    """("complete" or "incomplete", notes): incomplete when a solve failed, or when a mesh or
    the Fourier reference ``four`` (None unless it succeeded) disagrees on full contact."""
    notes = []
    if failures:
        notes.append("solver failures: " + "; ".join(failures))
    # full is the semi-analytic road's, else the finest mesh's: a solution that differs from it
    # is a disagreement between the roads or between the meshes
    solved = [r for r in runs if r is not None] + ([] if four is None else [four])
    if any(bool(s.full_contact) != full for s in solved):
        notes.append("the roads or meshes disagree on full contact")
    return ("incomplete" if notes else "complete"), notes


def _reference_record(four, four_ok):
    """What the Fourier reference was and what it said (its caveats included), not its timing:
    the record must not change when nothing certified does.  On a layer, the layer it solved
    (k d, foundation, ν and its uniform compliance, as the reference describes it)."""
    rec = {"solver": "analytic.fourier_solve", "success": four_ok,
           "message": four.message.splitlines()[0][:300],
           "warnings": [w[:300] for w in four.warnings],
           "nodes": [int(n) for n in four.nodes],
           "shifts": int(four.shifts), "require_resolved": False}
    if getattr(four, "layer", None) is not None:
        rec["layer"] = {k: (_num(v) if isinstance(v, (int, float)) and not isinstance(v, bool)
                            else v) for k, v in dict(four.layer).items()}
    return rec


def _certified_fields(point, nodes, grid_fields, ref, M, roads):
    x = np.arange(M) / M - 0.5
    out = {"x_over_lambda": x}
    finest, second = nodes[-1], nodes[-2]
    bl = grid_fields.get(finest)
    bp = grid_fields.get(second)
    summary = {"file": None, "points": M, "grid": f"x_over_lambda = j/{M} - 1/2, j = 0..{M - 1}",
               "max_error": {}, "source": None}
    if roads and ref is not None:
        f = ref.fields(x)
        vals = {"pressure": f.pressure, "displacement": f.displacement, "gap": f.gap}
        summary["source"] = (f"semi-analytic values; error = largest |semi-analytic − BEM "
                             f"(N = {finest})| at the point and its neighbours")
        for c in FIELD_COLUMNS:
            a = np.asarray(vals[c], float)
            diff = np.abs(a - bl[c]) if bl is not None else np.full(M, np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(neighbour_max(diff), FIELD_FLOOR * np.max(np.abs(a)))
    else:
        summary["source"] = (f"BEM values at N = {finest}; error = {SAFETY:g} × largest change "
                             f"from N = {second} at the point and its neighbours (a pressure at "
                             f"least {BEM_PRESSURE_FLOOR:g} × its largest value)")
        for c in FIELD_COLUMNS:
            if bl is None:
                out[c] = np.full(M, np.nan)
                out[c + "_err"] = np.full(M, np.inf)
                continue
            a = np.asarray(bl[c], float)
            diff = np.abs(a - bp[c]) if bp is not None else np.full(M, np.inf)
            out[c] = a
            floor = BEM_PRESSURE_FLOOR if c == "pressure" else FIELD_FLOOR
            out[c + "_err"] = np.maximum(SAFETY * neighbour_max(diff), floor * np.max(np.abs(a)))
    for c in FIELD_COLUMNS:
        summary["max_error"][c] = _num(float(np.max(out[c + "_err"])))
    return out, summary


# --------------------------------------------------------------------------- fields files
FIELDS_HEADER = ["x_over_lambda"] + [c for col in FIELD_COLUMNS for c in (col, col + "_err")]


def write_fields(path, case, fields):
    """The fields CSV: ``#`` lines (case, grid, units, how the errors are certified), a header,
    then one row per grid point; values to 17 significant digits, errors to 3."""
    buf = io.StringIO()
    buf.write(f"# viscosine benchmark suite, case {case['name']}: {case['title']}\n")
    buf.write(f"# grid: {case['certified']['fields']['grid']}\n")
    buf.write("# units: pressure = sigma (1 - nu^2)/E0, displacement = v/h (into the body, "
              "from the mean line of the deformed surface), gap = gap/h\n")
    lay = case["point"].get("layer")
    if lay:
        dl = float(lay["thickness_over_wavelength"])
        buf.write(f"# on a layer: d/lambda = {dl!r} (k d = {2.0 * math.pi * dl!r}), "
                  f"{lay['foundation']} foundation, nu = {float(lay['nu'])!r}; the displacement "
                  "is from the mean line of the deformed surface as on the half-space (the "
                  "layer's mean compression, mean_displacement, is not in it)\n")
    buf.write("# <column>_err: certified absolute error of the value on the same row\n")
    buf.write(f"# {case['certified']['fields']['source']}\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(FIELDS_HEADER)
    for j in range(len(fields["x_over_lambda"])):
        row = [repr(float(fields["x_over_lambda"][j]))]
        for c in FIELD_COLUMNS:
            row += [repr(float(fields[c][j])), f"{float(fields[c + '_err'][j]):.3e}"]
        w.writerow(row)
    write_text(path, buf.getvalue())


def case_fields(case, base=DATA) -> dict:
    """The shipped fields of a case (columns of its fields CSV, `write_fields`; a surface
    case's arrays, `surface_fields`)."""
    if is_surface(case):
        return surface_fields(case, base)
    return read_columns(Path(base) / case["certified"]["fields"]["file"])
