"""The tolerance of every quantity of a verification, and why.

The tolerances follow from the grid of the result (N: its fields' points per period,
else its ``--nodes`` or ``nodes``).  Scalars and edges: max(1e-4, 3 e_N), e_N what viscosine's
BEM misses the reference by on N panels, in the same measure and with the same derivation from
its fields (`grid_errors`: the larger of its error at N and half its error at N/2, so that an
error that happens to cross zero at N does not shrink it): the discretisation error of a correct
panel solver at this case; 1e-4 when N is not known.  An explicit ``--rtol`` is a flat tolerance
of every scalar and of the edges, as asked.  Field norms: FIELD_LAW (a square-root contact edge
keeps a correct solver's σ L∞ ~ (N·2a/λ)^(-1/2) and its σ L2 ~ N^(-1) at any practical N; 3 ×
the worst constant measured on viscosine's own BEM).  ``--tol NAME=VALUE`` sets any one.  The
verdict states each tolerance and why, one line each.
"""
from __future__ import annotations

import functools
import json
import math
import warnings

import numpy as np

from .. import suite as _suite
from ..fields import MIN_POINTS, as_grid, bem_fields
from ..suite_inputs import ProfileShape
from ._quantities import COMPARED_KEYS, LABELS, edge_differences, measure, norms
from ._reference import reference_for
from ._results import results_from_fields, viscosine_bem
from ._scalars import scalars_from_fields

DEFAULT_RTOL = 1e-4
#: On a known grid of N points the default tolerance of a scalar and of the contact edges is
#: max(DEFAULT_RTOL, GRID_FACTOR · e_N), e_N what viscosine's BEM misses the reference by on N
#: panels (`grid_errors`): a correct solver's discretisation error at the case, which the flat 1e-4
#: is not at N = 512 (2a/λ 2.7e-3 at sls-light-v1, μ 9.9e-3 at sls-ratio1000-full)
GRID_FACTOR = 3.0
#: `grid_errors` solves no grid finer than this (2 s there); a finer result gets DEFAULT_RTOL,
#: which its grid's error is then far below on the suite (μ of sls-ratio1000-full, its worst:
#: 3.7e-4 at N = 4096, 6e-9 at 16384)
GRID_MAX_NODES = 1 << 18

#: The default tolerances of the field norms, derived from the grid.  A square-root contact edge
#: leaves a correct solver an error at the edge panels that shrinks only like (panels across the
#: contact)^(-1/2) in L∞ and like N^(-1) in L2 (relative to max σ), and a displacement error like
#: N^(-3/2).  key -> (K, p, contact-aware): tolerance K·N^(-p), for σ with N·c in place of N
#: (L∞: K (N c)^(-1/2); L2: K N^(-1) c^(-1/2), c = 2a/λ of the reference, 1 in full contact).
#: K is 3 × the largest constant measured on viscosine's BEM at fixed N = 512, 1024, …, 8192
#: against the semi-analytic reference on the 17 standard-linear-solid cases of the suite
#: (MEASURED_FIELD_CONSTANTS, measured by `field_constants`; tests/comparisons/test_verify.py checks the
#: worst ones).
FIELD_LAW = {
    "pressure_Linf": (1.4, 0.5, True),
    "pressure_L2": (1.4, 1.0, True),
    "displacement_Linf": (2.6, 1.5, False),
    "displacement_L2": (0.18, 1.5, False),
    "gap_Linf": (2.6, 1.5, False),
}
#: key -> (largest constant, where): σ over 16 of the 17 cases; the 17th, sls-ratio1000 (E∞/E0 =
#: 1000 at V/V0 = 10: its relaxation layer spans under two panels at N = 1024), reaches 1.15 (L∞)
#: and 1.17 (L2), still inside K = 1.4
MEASURED_FIELD_CONSTANTS = {
    "pressure_Linf": (0.455, "sls-ratio10, N = 4096"),
    "pressure_L2": (0.465, "sls-partial-v1, N = 2048"),
    "displacement_Linf": (0.848, "sls-partial-v100, N = 1024"),
    "displacement_L2": (0.059, "sls-partial-v100, N = 1024"),
    "gap_Linf": (0.852, "sls-partial-v100, N = 1024"),
}


def grid_size(fields, reference):
    """(N, c) of the field law (FIELD_LAW) for fields on the user's grid against a reference.

    N is the number of points per period; on a non-uniform grid (cells of several widths) N is
    1/width of the coarsest cell holding a contact edge of the reference (1/the coarsest cell in
    full contact).  c is the narrowest patch width of the reference over λ (its contact
    fraction with one patch), 1 in full contact.
    """
    grid = as_grid(fields)
    m = grid.x_over_lambda.size
    edges = [e for p in reference.patches for e in (p["trailing_edge"], p["leading_edge"])]
    if grid.uniform:
        n = float(m)
    else:
        w = grid.widths
        if edges:
            ce = grid.cell_edges
            start = float(ce[0])
            where = [int(np.searchsorted(ce, start + (e - start) % 1.0, side="right")) - 1
                     for e in edges]
            n = 1.0 / float(max(w[min(max(i, 0), m - 1)] for i in where))
        else:
            n = 1.0 / float(np.max(w))
    if reference.full_contact or not reference.patches:
        c = 1.0
    else:
        c = min(p["leading_edge"] - p["trailing_edge"] for p in reference.patches)
        c = min(max(c, 1e-12), 1.0)
    return n, c


def field_tolerance(key, n, c):
    """The default tolerance of one field norm on N = n points, contact width c (FIELD_LAW)."""
    k, p, contact = FIELD_LAW[key]
    if not contact:
        return k * n ** -p
    return k * (n * c) ** -0.5 if key == "pressure_Linf" else k / (n * math.sqrt(c))


def _field_reason(key, n, c):
    k, p, contact = FIELD_LAW[key]
    const, where = MEASURED_FIELD_CONSTANTS[key]
    grid = f"N = {n:.0f}" + (f", c = 2a/λ = {c:.4g} of the reference" if contact and c < 1.0
                             else (", full contact (c = 1)" if contact else ""))
    if key == "pressure_Linf":
        law, why = f"{k:g} (N c)^-1/2", ("a square-root contact edge leaves a correct solver "
                                         "~(panels across the contact)^-1/2 at the edge panels")
    elif key == "pressure_L2":
        law, why = f"{k:g} N^-1 c^-1/2", ("the edge panels' error ~(N c)^-1/2 over a width "
                                          "~1/N gives a correct solver ~N^-1 c^-1/2")
    else:
        law, why = f"{k:g} N^-3/2", "a correct solver's displacement converges like N^-3/2"
    return (f"{law} with {grid}: {why}; K = 3 × {const:g}, the worst of viscosine's BEM on "
            f"the suite's standard-linear-solid cases at N = 512…8192 ({where})")


def field_constants(point, nodes, case=None):
    """The constants of FIELD_LAW that viscosine's BEM reaches at one operating point on N
    panels: each field norm against the reference over its law with K = 1 (how
    MEASURED_FIELD_CONSTANTS was measured, at N = 512 … 8192 on the suite's SLS cases)."""
    ref = reference_for(point, case)
    res = results_from_fields([viscosine_bem(point, nodes)], ref.shape)[0]
    nm = norms(res, ref)[0]
    n, c = grid_size(res.fields, ref)
    return {k: nm[k] / (field_tolerance(k, n, c) / FIELD_LAW[k][0]) for k in FIELD_LAW
            if k in nm}


@functools.lru_cache(maxsize=64)
def _bem_derived(point_json, nodes, columns):
    """(scalars, patches, own scalars): those derived from viscosine's BEM fields on ``nodes``
    panels, keeping only ``columns``, as from a user's, and the BEM's own (cached: a run asks
    for the same grid more than once); None when the BEM cannot solve there."""
    point = json.loads(point_json)
    if not MIN_POINTS <= nodes <= GRID_MAX_NODES:
        return None
    try:
        with warnings.catch_warnings():  # its coarse-grid caveats are about this very allowance
            warnings.simplefilter("ignore")
            res = _suite.bem_solution(point, int(nodes), base="/")
            if not res.success:
                return None
            x, p, v, g = bem_fields(res)
    except (RuntimeError, ValueError, ArithmeticError):
        return None
    f = {"x_over_lambda": x, "pressure": p, "displacement": v, "gap": g}
    f = {k: f[k] for k in ("x_over_lambda",) + columns}
    own = {k: v for k, v in res.scalars().items() if k in COMPARED_KEYS and v is not None}
    return (*scalars_from_fields(f, ProfileShape(point, base="/")), own)


def _bem_errors(reference, nodes, columns):
    key = json.dumps(reference.point, sort_keys=True, default=float)
    got = _bem_derived(key, int(nodes), tuple(columns))
    if got is None:
        return {}
    sc, patches, own = got
    out = {}
    for k in COMPARED_KEYS:  # a correct solver's miss: the BEM's own or its fields', the larger
        ref = reference.scalars.get(k, (None, None))[0]
        got_k = [m for m in (measure(k, sc.get(k), ref), measure(k, own.get(k), ref))
                 if m is not None]
        if got_k:
            out[k] = max(got_k)
    edges = edge_differences(reference.patches, patches) if reference.patches else None
    if edges:
        out["edges"] = max(max(abs(a), abs(b)) for a, b in edges)
    return out


def grid_errors(reference, nodes, columns=_suite.FIELD_COLUMNS):
    """e_N of every scalar and of the edges: what viscosine's BEM misses ``reference`` by on
    ``nodes`` panels, the larger of its error at N and half its error at N/2 (an error that
    happens to cross zero at N does not shrink it); for a scalar, the larger of the BEM's own
    value's miss and that of the value derived from its fields.

    Each in the verdict's measure (`measure`; edges: the worst, x/λ), with the scalars derived
    from the BEM's fields by `scalars_from_fields` keeping only ``columns``, as the verdict
    derives the user's.  A key is missing when the BEM at N does not give it (it cannot solve
    there, or finds another number of patches than the reference).
    """
    at_n = _bem_errors(reference, nodes, columns)
    at_half = _bem_errors(reference, int(nodes) // 2, columns)
    return {k: max(e, 0.5 * at_half[k]) if k in at_half else e for k, e in at_n.items()}


def _grid_tolerances(rtol, reference, nodes, columns):
    """{key: (tolerance, reason)} of the scalars and the edges on a known grid: max(rtol,
    GRID_FACTOR · e_N) (`grid_errors`); the keys where rtol binds share one reason."""
    n = int(round(nodes))
    errs = grid_errors(reference, n, columns)
    keys = COMPARED_KEYS + ("edges",)
    law = f"max({rtol:.1e}, {GRID_FACTOR:g} e_N), N = {n}"
    floor = [errs[k] for k in keys if k in errs and GRID_FACTOR * errs[k] <= rtol]
    out = {}
    for k in keys:
        e = errs.get(k)
        if e is None and n > GRID_MAX_NODES:
            out[k] = (rtol, f"the default {rtol:.1e}: N = {n} is above the {GRID_MAX_NODES} "
                            "panels on which viscosine's BEM measures the grid's error")
        elif e is None:
            out[k] = (rtol, f"the default {rtol:.1e}: viscosine's BEM on N = {n} panels does not "
                            "give this quantity to measure the grid's error by")
        elif GRID_FACTOR * e > rtol:
            out[k] = (GRID_FACTOR * e, f"{law}: e_N = {e:.1e} is viscosine's BEM's error on this "
                                       "grid (the larger of its error at N and half that at "
                                       "N/2), a correct solver's discretisation error here")
        else:
            out[k] = (rtol, f"{law}: {rtol:.1e} binds, viscosine's BEM errs by e_N ≤ "
                            f"{max(floor):.1e} on this grid")
    return out


def tolerances(rtol=DEFAULT_RTOL, tol=None, fields=None, reference=None, rtol_given=None,
               nodes=None):
    """The tolerance of every quantity and why: {key: (tolerance, reason)}.

    Scalars and the contact edges: ``rtol`` when it was asked for; else, on a known grid (that
    of ``fields``, else ``nodes``) and with a ``reference``, max(rtol, GRID_FACTOR · e_N)
    (`grid_errors`), and ``rtol`` without a grid.  Field norms: `field_tolerance` on the grid of
    ``fields`` against ``reference`` (FIELD_LAW), or ``rtol`` without fields.  ``tol``
    overrides any of them.  ``rtol_given``: whether ``rtol`` was asked for (else it is the
    default).
    """
    if rtol_given is None:
        rtol_given = rtol != DEFAULT_RTOL
    src = (f"--rtol {rtol:.1e}" if rtol_given else f"the default --rtol {rtol:.1e}")
    grid = "" if rtol_given else ": the grid is not known (no fields, no nodes)"
    out = {}
    for k in COMPARED_KEYS:
        out[k] = (rtol, f"{src} (relative for μ, τ̃f, Δ/h, s/h, p̃∞, 2a/λ; absolute in "
                        f"radians for ka, ke, kê){grid}")
    out["edges"] = (rtol, f"{src} (absolute, in x/λ){grid}")
    n = c = None
    if fields is not None and reference is not None:
        n, c = grid_size(fields, reference)
    if not rtol_given and reference is not None and (n or nodes):
        cols = [k for k in _suite.FIELD_COLUMNS if fields is None or k in fields]
        out.update(_grid_tolerances(rtol, reference, n or nodes, cols))
    for k in FIELD_LAW:
        if n is None:
            out[k] = (rtol, src)
        else:
            out[k] = (field_tolerance(k, n, c), _field_reason(k, n, c))
    for k, v in (tol or {}).items():
        out[k] = (v, f"--tol {k}={v:g}")
    return out


def tolerance_lines(tols, keys):
    """One line per distinct (tolerance as printed, reason) over the quantities shown, in their
    order (μ and τ̃f share their relative error, to round-off)."""
    groups = {}
    for k in keys:
        v, why = tols[k]
        groups.setdefault((f"{v:.1e}", why), []).append(LABELS[k])
    return [f"{', '.join(labels)}: {v}, {why}" for (v, why), labels in groups.items()]

