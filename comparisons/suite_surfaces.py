"""The suite's surface cases: a rigid periodic surface over the half-space or a layer, certified
by `compute_surface` under `SURFACE_RULE` (the surface BEM's study checked against the second
opinions each case declares), and their fields files (``fields/NAME.npz``).
`comparisons.suite` re-exports every name.
"""
from __future__ import annotations

import math
import os
import time
from pathlib import Path

import numpy as np

from . import operating_point as op
from . import roads as _roads
from ._errors import SuiteError
from ._io import temporary_name
from .convergence import digits, rounded, study
from .suite_cases import FIELD_COLUMNS, FIELD_FLOOR, SAFETY, _num, increasing_meshes
from .suite_inputs import DATA

# --------------------------------------------------------------------------- surface cases
# A surface case (``suite["surfaces"]``) is a rigid periodic surface sliding over the half-space
# or a layer (three-dimensional contact, docs/surfaces.md): its point is the plain description
# of `comparisons.roads.surface` (``surface``), ``direction`` θ in degrees, ``load``, ``speed``,
# ``ratio`` and an optional ``layer``; ``nodes`` the surface BEM's grids (panels along x, each
# twice the one before); ``references`` the second opinions it declares (SURFACE_REFERENCES);
# ``reference_nodes`` the surface reference's grids.

#: the scalars a surface case certifies (conventions.md, 'Surfaces')
SURFACE_KEYS = ("mu", "mu_lateral", "penetration", "contact_fraction")
#: the stated grid of a surface case's fields: M × M panel centres x_i = i/M − ½ (a subset of
#: the panel centres of every BEM grid that is a multiple of M)
SURFACE_FIELD_POINTS = 64
#: the second opinions a surface case may declare, and what each is
SURFACE_REFERENCES = {
    "surface_reference": "the independent surface reference analytic.references.surface "
                         "(Douglas-Rachford splitting, its own measurements and Richardson "
                         "estimate)",
    "line": "the semi-analytic road of the line contact (the surface is uniform in y: the "
            "line's sinusoid at the speed w cos θ, docs/surfaces.md §2.3)",
    "closed_form": "full contact in closed form: each family of ridges is the line's Appendix B "
                   "at its speed component, w cos θ and w sin θ (docs/surfaces.md §2.2)",
}
#: the estimates of both surface solvers (the BEM's and the surface reference's) are relative
#: for these, as the output contract says; mu_lateral's is the one apart (`_absolute`)
_RELATIVE = ("mu", "penetration", "contact_fraction")

SURFACE_RULE = (
    "Surface cases (a rigid periodic surface, three-dimensional contact) are solved by the "
    "surface BEM (bem.solve_surface, fixed grids of N x N panels, N = 64 ... 1024, each with "
    "its own halvings) and the certified quantities are mu, mu_lateral, penetration (Delta/h_ref) "
    "and contact_fraction. The convergence study of each over the grids is the rule above "
    "(order, envelope, Richardson value q_R, estimate E). The second opinion is stated in each "
    "case's definition (references): the independent surface reference "
    "(analytic.references.surface, Douglas-Rachford splitting on its own grids, value q_F with "
    "its own absolute estimate E_F): the two must agree, |q_R - q_F| <= "
    f"{SAFETY:g} E + E_F, and the certified value is q_R with e = max({SAFETY:g} E, E_F, "
    "|q_R - q_F|), the digits both support; they certify nothing where they disagree or the "
    "reference failed. On a layer the reference solves the same layer (the symbol of each mode "
    "times its own layer factor S(|q| k d, nu), analytic.references._layer, from Navier's "
    "equations). "
    "A surface uniform in y (line): the certified value is the semi-analytic line road's a, "
    "with e = |a - q_R| (the finest value when the study has no order), and with the surface "
    "reference as well e is at least |a - q_F|. Full contact of the bi-sinusoid "
    "(closed_form): the certified value is the closed form a (each family of ridges the "
    "line's Appendix B at its speed component), e as for the line road. A case that declares "
    f"no second opinion: q_R with e = {SAFETY:g} E, the BEM's convergence alone. What holds "
    "by construction is exact: full contact (Delta/h_ref = 1, contact fraction 1), "
    "mu_lateral = 0 for a bi-sinusoid sliding along an axis (mirror symmetry about V), the "
    "number of contact patches where every grid and the reference count the same. Fields "
    "(pressure, displacement, gap over h_ref) on the "
    f"stated grid of {SURFACE_FIELD_POINTS} x {SURFACE_FIELD_POINTS} panel centres carry an "
    "absolute error per point: the line road's values with the largest |a - BEM(finest N)| at "
    f"the point and its 8 neighbours where it applies, else the finest grid's with {SAFETY:g} x "
    "the largest change between the two finest grids at the point and its 8 neighbours; never "
    f"below {FIELD_FLOOR:g} x the largest magnitude of the column.")


def surface_references(case):
    """The second opinions a surface case declares (a tuple of SURFACE_REFERENCES keys);
    SuiteError for one it may not have."""
    refs = tuple(case.get("references") or ())
    p = case["point"]
    surf = p["surface"]
    for ref in refs:
        if ref not in SURFACE_REFERENCES:
            raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed: one of "
                             f"{', '.join(SURFACE_REFERENCES)}")
        why = None
        if ref in ("line", "closed_form") and (surf.get("kind") != "bisinusoid"
                                               or p.get("layer") or (surf.get("aspect") or 1.0)
                                               != 1.0):
            why = "a bi-sinusoid on a square cell over the half-space"
        if ref == "line" and (surf.get("hk_y") != 0.0
                              or not math.cos(math.radians(op.direction_of(p))) > 0.0):
            why = "a surface uniform in y (hk_y = 0) sliding with a component along +x"
        if why:
            raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed here: {why}")
    if "line" in refs and "closed_form" in refs:
        raise SuiteError(f"case {case['name']}: references 'line' and 'closed_form' are not "
                         "allowed together: one exact road")
    return refs


def _absolute(sol, k, lateral_scale, none=None):
    """A surface solver's estimate of scalar ``k`` made absolute (``none`` where it gives
    none): a relative one times |value|; mu_lateral's times ``lateral_scale`` (the BEM's is
    over |μ|, the reference's absolute: 1)."""
    e = (sol.error_estimate or {}).get(k)
    if e is None:
        return none
    return float(e) * (abs(float(getattr(sol, k))) if k in _RELATIVE else lateral_scale)


def _lateral_vanishes(point) -> bool:
    """μ_lateral = 0 by the mirror about V: a bi-sinusoid (even in x and in y) sliding along
    an axis."""
    d = op.direction_of(point)
    return point["surface"].get("kind") == "bisinusoid" and d % 90.0 == 0.0


def _hk(surf):
    hk = op.hk_of(surf)
    return hk, hk if surf.get("hk_y") is None else float(surf["hk_y"])


def _exact_road(point, refs):
    """The exact road of a surface case: {key: value} of SURFACE_KEYS and its fields on x (a
    callable, or None), or (None, None) without one."""
    surf = point["surface"]
    th = math.radians(op.direction_of(point))
    if "closed_form" in refs:
        hk, hk_y = _hk(surf)
        cf = _roads.bisinusoid_full_contact(float(point["speed"]), math.degrees(th),
                                            op.ratio_of(point), hk, hk_y)
        load = float(point["load"])
        if not load >= cf["load_threshold"]:
            raise SuiteError(f"load {load!r} is below the full-contact load "
                             f"{cf['load_threshold']!r}: the closed form does not apply")
        return {"mu": cf["tau_f"] / load, "mu_lateral": cf["lateral"] / load,
                "penetration": 1.0, "contact_fraction": 1.0}, None
    if "line" in refs:
        c, s = math.cos(th), math.sin(th)
        line = dict(_roads.point_controls(point), speed=float(point["speed"]) * c,
                    ratio=op.ratio_of(point), hk=_hk(surf)[0])
        sol = _roads.analytic_solution(line)
        if not sol.success:
            raise SuiteError(f"the semi-analytic line road failed: {sol.message}")
        return {"mu": c * sol.mu, "mu_lateral": s * sol.mu, "penetration": sol.penetration,
                "contact_fraction": sol.contact_fraction}, sol.fields
    return None, None


def _surface_study(nodes, values):
    """The certified study of a surface scalar (`study` over the case's grids)."""
    st = study(nodes, values)
    return st, {"nodes": [int(n) for n in nodes], "values": [_num(v) for v in values],
                "order": _num(st["order"]), "richardson": _num(st["richardson"]),
                "estimate": _num(st["estimate"]), "regime": st["regime"]}


def _surface_scalar(key, nodes, values, own, exact, four):
    """One surface scalar's record: the BEM's study (``own``: its own estimate on the finest
    grid, absolute), the exact road's value ``exact`` (or None) and the surface reference's
    ``four`` ((value, absolute estimate), (NaN, NaN) when it failed, None when not declared)."""
    st, ev = _surface_study(nodes, values)
    ev["own_estimate"] = _num(own)
    rec = {"bem": ev}
    if exact is not None:
        best = st["richardson"] if st["regime"] == "asymptotic" else st["finest"]
        value = exact
        err = abs(exact - best) if (math.isfinite(best) and st["regime"] != "too few meshes") \
            else math.inf
        rec["exact_road"] = _num(exact)
        method = "exact road"
        if four is not None:
            err = max(err, abs(exact - four[0])) if math.isfinite(four[0]) else math.inf
    else:
        value = st["richardson"]
        err = SAFETY * st["estimate"]
        method = "bem convergence"
        if four is not None:
            gap = abs(value - four[0])
            # the digits both support; none where they disagree beyond their estimates (and
            # no verdict without a study or a reference value: nothing to certify either way)
            agree = bool(gap <= err + four[1]) if math.isfinite(gap) and math.isfinite(err) \
                else None
            rec["agree"] = agree
            err = max(err, four[1], gap) if agree else math.inf
            method = "bem convergence + surface reference"
    if four is not None:
        rec["reference"] = {"value": _num(four[0]), "estimate": _num(four[1])}
    nd = digits(value, err)
    rec.update(value=_num(value), digits=nd, rounded=rounded(value, nd), error=_num(err),
               method=method)
    return {k: rec[k] for k in ("value", "digits", "rounded", "error", "method", "bem")
            + tuple(k for k in ("exact_road", "reference", "agree") if k in rec)}


def _surface_fields_of(res, M):
    """The fields of a surface BEM result on the stated grid of M × M points."""
    n = res.shape[0]
    step = (n // M, res.shape[1] // M)
    return {c: np.asarray(getattr(res, c), float)[::step[0], ::step[1]] for c in FIELD_COLUMNS}


def _neighbour_max2(a):
    """The largest of each entry of a periodic 2-D array and its 8 neighbours."""
    out = a
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            out = np.maximum(out, np.roll(np.roll(a, dx, 0), dy, 1))
    return out


def compute_surface(case, progress=None):
    """Recompute one surface case: its certified scalars and its fields on the stated grid
    (`compute` for a surface case; the rule is SURFACE_RULE).

    Returns
    -------
    (dict, dict)
        The ``certified`` record and the fields: ``x``, ``y`` and, for each of FIELD_COLUMNS,
        the values and ``<col>_err`` on the M × M stated grid.
    """
    point = case["point"]
    nodes = increasing_meshes(case)
    refs = surface_references(case)
    M = int(case.get("field_points", SURFACE_FIELD_POINTS))
    if nodes[-1] % M or nodes[-2] % M:
        raise SuiteError(f"case {case['name']}: the two finest grids must be multiples of {M}")
    runs, failures, grid_fields = [], [], {}
    t0 = time.perf_counter()
    # each grid is solve_surface(nodes=n)'s answer; the grids below are solved once for all
    for n, r in zip(nodes, _roads.surface_meshes(point, nodes), strict=True):
        runs.append(r if r.success else None)
        if not r.success:
            failures.append(f"N = {n}: {r.message.splitlines()[0][:200]}")
        elif n in nodes[-2:]:
            grid_fields[n] = _surface_fields_of(r, M)
        if progress:
            progress(f"surface grid {n}: {'ok' if r.success else 'FAILED'} "
                     f"({time.perf_counter() - t0:.2f} s)")
        t0 = time.perf_counter()
    exact_vals, line_fields = _exact_road(point, refs)
    four, four_rec = None, None
    if "surface_reference" in refs:
        t0 = time.perf_counter()
        four = _roads.surface_reference_solution(point, case["reference_nodes"])
        four_rec = {"solver": "analytic.references.surface", "success": bool(four.success),
                    "message": four.message.splitlines()[0][:300],
                    "warnings": [w[:300] for w in four.warnings],
                    "nodes": [int(g[0]) for g in four.grids]}
        if not four.success:
            failures.append(f"surface reference: {four.message.splitlines()[0][:200]}")
        if progress:
            progress(f"surface reference: {'ok' if four.success else 'FAILED'} "
                     f"({time.perf_counter() - t0:.2f} s)")
    fin = runs[-1]
    full = bool(fin.full_contact) if fin is not None else False
    exact = {"full_contact": full}
    if full:
        exact.update(penetration=1.0, contact_fraction=1.0, separation=0.0)
    if _lateral_vanishes(point):
        exact["mu_lateral"] = 0.0
    counts = {r.n_patches for r in runs if r is not None}
    if four is not None and four.success:
        counts.add(int(four.n_patches))
    notes = []
    if len(counts) == 1 and all(r is not None for r in runs):
        exact["n_patches"] = counts.pop()
    else:
        notes.append("the grids (or the reference) count different numbers of contact patches: "
                     + ", ".join(str(r.n_patches) if r is not None else "—" for r in runs))
    scalars = {}
    for k in SURFACE_KEYS:
        if k in exact:
            continue
        vals = [float(getattr(r, k)) if r is not None else float("nan") for r in runs]
        own = _absolute(fin, k, abs(fin.mu)) if fin is not None else None
        fv = None
        if four is not None:
            fv = ((float(getattr(four, k)), _absolute(four, k, 1.0, math.nan))
                  if four.success else (math.nan, math.nan))
        a = exact_vals[k] if exact_vals is not None else None
        scalars[k] = _surface_scalar(k, nodes, vals, own, a, fv)
        if scalars[k].get("agree") is False:
            notes.append(f"{k}: the BEM and the surface reference disagree beyond their "
                         "estimates (nothing certified)")
    if failures:
        notes.insert(0, "solver failures: " + "; ".join(failures))
    if any(r is not None and bool(r.full_contact) != full for r in runs) or (
            four is not None and four.success and bool(four.full_contact) != full):
        notes.append("the grids or the reference disagree on full contact")
    fields, summary = _surface_fields(point, nodes, grid_fields, line_fields, M)
    if four is not None and four.success and four.pressure.shape[0] % M == 0:
        # the reference's own fields on its finest grid, beside the certified ones (evidence)
        st = four.pressure.shape[0] // M
        d = np.abs(np.asarray(four.pressure)[::st, ::st] - fields["pressure"])
        summary["reference_pressure_difference"] = _num(float(np.max(d)))
    exact_ref = [r for r in refs if r in ("line", "closed_form")]
    method = ("exact road: " + exact_ref[0]) if exact_ref else "bem convergence"
    method += " + surface reference" if four is not None else ""
    certified = {"method": method, "status": "incomplete" if notes and (
        failures or any("disagree" in n for n in notes)) else "complete",
        "notes": notes, "scalars": scalars, "exact": exact, "patches": [],
        "fields": summary}
    if four_rec is not None:
        certified["reference"] = four_rec
    return certified, fields


def _surface_fields(point, nodes, grid_fields, line_fields, M):
    """The certified fields of a surface case on the stated grid (SURFACE_RULE), and their
    summary."""
    x = np.arange(M) / M - 0.5
    surf = _roads.surface(point["surface"])
    y = (np.arange(M) / M - 0.5) * float(surf.aspect)
    out = {"x": x, "y": y}
    finest, second = nodes[-1], nodes[-2]
    bl, bp = grid_fields.get(finest), grid_fields.get(second)
    summary = {"file": None, "points": [M, M],
               "grid": f"x = i/{M} - 1/2, y = (j/{M} - 1/2) Ly/Lx, i, j = 0..{M - 1}",
               "max_error": {}, "source": None}
    if line_fields is not None:
        f = line_fields(x)
        vals = {"pressure": f.pressure, "displacement": f.displacement, "gap": f.gap}
        summary["source"] = (f"semi-analytic line road (uniform in y); error = largest "
                             f"|semi-analytic − BEM (N = {finest})| at the point and its "
                             "neighbours")
        for c in FIELD_COLUMNS:
            a = np.repeat(np.asarray(vals[c], float)[:, None], M, axis=1)
            diff = np.abs(a - bl[c]) if bl is not None else np.full((M, M), np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(_neighbour_max2(diff), FIELD_FLOOR * np.max(np.abs(a)))
    else:
        summary["source"] = (f"surface BEM at N = {finest}; error = {SAFETY:g} × largest change "
                             f"from N = {second} at the point and its neighbours")
        for c in FIELD_COLUMNS:
            if bl is None:
                out[c] = np.full((M, M), np.nan)
                out[c + "_err"] = np.full((M, M), np.inf)
                continue
            a = bl[c]
            diff = np.abs(a - bp[c]) if bp is not None else np.full((M, M), np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(SAFETY * _neighbour_max2(diff),
                                         FIELD_FLOOR * np.max(np.abs(a)))
    for c in FIELD_COLUMNS:
        summary["max_error"][c] = _num(float(np.max(out[c + "_err"])))
    return out, summary


def write_surface_fields(path, case, fields):
    """The fields of a surface case as ``.npz`` (the conventions' arrays ``x``, ``y``,
    ``pressure``, ``displacement``, ``gap`` and the scalars ``load``, ``speed``,
    ``direction``, with ``<column>_err`` the certified absolute error of each value), written
    through a temporary file renamed into place."""
    p = case["point"]
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_name(path)
    arrays = {k: np.asarray(fields[k], float) for k in ("x", "y") + tuple(
        c + s for c in FIELD_COLUMNS for s in ("", "_err"))}
    try:
        with open(tmp, "wb") as fh:
            np.savez_compressed(fh, **arrays, load=float(p["load"]), speed=float(p["speed"]),
                                direction=op.direction_of(p))
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def surface_fields(case, base=DATA) -> dict:
    """The shipped fields of a surface case (the arrays of its ``.npz``)."""
    with np.load(Path(base) / case["certified"]["fields"]["file"]) as z:
        return {k: np.asarray(z[k]) for k in z.files}
