"""The certified benchmark suite: steady viscoelastic sliding cases with certified digits.

    python -m comparisons suite --check [--cases NAME ...] [--out DIR] [--resume] [--workers W]
                                        [--scheduler ADDRESS]
    python -m comparisons suite --certify [--cases NAME ...]          (maintainers)

This module reads the suite's cases, computes and certifies a case by mesh refinement, and
checks a recomputation against what is shipped.  Its neighbours: :mod:`comparisons.suite_inputs`
(where the data is, a case's indenter, the generators of the synthetic inputs),
:mod:`comparisons.suite_export` (``suite --export DIR``, ``suite --list``: the suite as plain
files, the summary tables), :mod:`comparisons.convergence` (the study and the digits rule below)
and :mod:`comparisons.fields` (the contact patches).

The suite lives in ``comparisons/data/suite/``: ``suite.json`` (the cases, their inputs and their
certified values), the profile and material files it names and one fields file per case
(``fields/NAME.csv``).  A case's material is the standard linear solid (``ratio``), a creep series
(``prony``: the format of :func:`bem.read_prony`) or a material file of any form (``material``: a
creep series, a relaxation series or a DMA master curve, read by
:func:`comparisons._materials.read`, with an optional ``temperature`` and ``wlf`` [C1, C2, T_ref]);
its profile is the sinusoid (``hk``) or a profile file (``profile``, :func:`bem.read_profile`).
A case may put a layer of thickness d on a rigid foundation in place of the half-space (``layer``:
``thickness_over_wavelength`` d/λ, ``foundation`` "bonded" or "frictionless", ``nu``; the plain
description both roads take through :mod:`comparisons.roads`, ``docs/layers.md``).  On a layer
the scalars keep their meaning (Δ/h = 1 − s/h, s measured to the mean line of the *deformed*
surface, as on the half-space) and two are added: ``approach`` (the indenter's crest from the
undeformed top face over h, Δ/h plus the layer's mean compression) and ``mean_displacement``
(that compression over h, C (k d) J0 p̃/hk: exact under load control, certified under
penetration control).

How a value is certified (one rule for every case)
--------------------------------------------------
Every case is solved by the BEM on the meshes ``nodes`` (powers of two).  The convergence study of
a scalar q uses the last ``LAST + 1`` meshes: the differences ``d_i = |q_i − q_{i−1}|``, the
observed order p (least-squares slope of log d_i against log N_i; no certification below 0.5,
capped at 4), the envelope ``D`` (the smallest line of slope −p above every d_i, taken at the
finest mesh), the Richardson value ``q_R = q_L + (q_L − q_{L−1})/(2^p − 1)`` and the error
estimate ``E = D/(2^p − 1)`` (the tail sum of the envelope; it bounds the error of q_L and
|q_R − q_L|).  When the last two differences are below ROUNDOFF |q| (1e-11 |q|) the study is in
the round-off regime: ``q_R = q_L`` and ``E`` = the larger of ROUNDOFF |q| and the last difference.
When the order is below MIN_ORDER but the values all lie within SCATTER_FLOOR |q| (1e-8 |q|) of
each other and move both up and down, they have settled and scatter (the sub-panel edge fits):
``q_R = q_L`` and ``E`` = their spread.  Values that only rise (or only fall) drift, however
little, and are not converging.

- Two roads (standard linear solid and sinusoid, where the semi-analytic road applies): the
  certified value is the semi-analytic one, a, and its certified digits are those on which the
  two roads agree, with the error ``e = |a − q_R|`` (q_R replaced by the finest value q_L when the
  study is in the round-off regime or its differences scatter without an order ≥ 0.5: the
  sub-panel edge estimates make single refinements scatter once they reach ~1e-10).
- BEM only (Prony series, other profiles): the certified value is q_R and ``e = SAFETY · E``
  (SAFETY = 10).
- BEM and the Fourier reference (a sinusoid case on a Prony material, or on the standard linear
  solid over a layer, that declares ``"reference": "fourier"``, opt-in per case): the case is
  also solved by
  :func:`analytic.fourier_solve` (dense Fourier collocation sharing no code with the BEM; creep
  series of the case's material, ``require_resolved=False``: its own estimates and refusals
  decide).  The certified value is q_R and ``e = max(SAFETY · E, |q_R − q_F|)``, q_F the Fourier
  value: the digits on which both roads agree, never more than the BEM's own study supports.
  The evidence records q_F and the reference's own error estimate (made absolute).  These
  broad-spectrum cases are where a BEM-only study is least safe (memory layers far below the
  panel width are handled by the edge fits, not resolved): an independent road is the check.
  On a layer the semi-analytic road does not apply (its closed forms are the half-space's), and
  the reference takes the same layer (mode n of its operator times S(|n| k d, ν)): the layer
  cases, the standard linear solid's included, are certified this way.

A failed BEM solve on any of the finest meshes, or a failed reference, certifies nothing (0
digits, case status "incomplete", the solver's message in the notes); ``--check`` then says when
a recomputation would certify more.

In every case the number of certified significant digits is the largest d with
``e < ½ · 10^(floor(log10 |value|) − d + 1)`` — half a unit of the last certified digit bounds e
— and that half unit at least 1e-10 |value| (RELATIVE_FLOOR, ten times the round-off level: the
round-off of the BEM's sums differs between machines, and a certified digit must survive
recomputation anywhere).
A quantity that is exact by construction (ka = π in full contact, the input of a
penetration-controlled case, the mean compression of a layer under load control, …) is listed as
exact.

Fields (σ, v, gap on the grid x_j = j/M − ½, M = FIELD_POINTS, a subset of the BEM's panel
centres) carry an absolute error per point: two roads, the semi-analytic value with the largest
|analytic − BEM| at the point and its two neighbours (finest mesh); otherwise (BEM only, and the
Fourier-referenced cases, whose reference is judged on the scalars), the finest mesh's
value with SAFETY × the largest change between the two finest meshes at the point and its two
neighbours (the tail sum of a first-order sequence, the pointwise order near a contact edge).
Every error is at least 1e-11 × the largest magnitude of its column (round-off).

Surface cases (``surfaces`` in ``suite.json``: a rigid periodic surface sliding over the
half-space or a layer, three-dimensional contact) are certified by `compute_surface` under
SURFACE_RULE: the surface BEM's study over its grids (the same `study`) checked against the
second opinion each case declares (the independent surface reference, on the half-space or the
case's layer; the semi-analytic line road for a surface uniform in y; the closed form of full
contact), with their
fields on a stated 2-D grid in ``fields/NAME.npz``.

`--check` recomputes every case and exits with status 1 when a certified digit changed: a scalar
moved by half a unit of its last certified digit or more, its recomputed evidence supports fewer
digits than shipped, a field value moved by more than its certified error, or an exact value
differs.  Recomputation that supports more digits than shipped is reported (run ``--certify``),
not a failure.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (the problem, the
standard linear solid of eq. 2.3, the friction of eq. 3.1).
"""
from __future__ import annotations

import csv
import hashlib
import io
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import NamedTuple

import numpy as np

from . import operating_point as op
from . import roads as _roads
from ._errors import SuiteError
from ._io import read_columns, temporary_name, write_text
from .convergence import (LAST, MAX_ORDER, MIN_ORDER, RELATIVE_FLOOR, ROUNDOFF, SCATTER_FLOOR,
                          digits, half_unit, rounded, study)
from .fields import PATCH_KEYS, match_patches, neighbour_max, patch_records
from .progress import Progress
from .suite_inputs import DATA, ProfileShape

# part of the suite's interface though this module does not use them: the cap on certified
# digits, and the generators of the synthetic inputs (the shipped files cite them as
# comparisons.suite.NAME)
from .convergence import MAX_DIGITS  # noqa: F401
from .suite_inputs import (BROAD24, LOGNORMAL32, RELAX16, SELF_AFFINE,  # noqa: F401
                           creep_spectrum, harmonic_heights, relaxation_spectrum,
                           self_affine_heights)

SUITE_FILE = DATA / "suite.json"

SAFETY = 10.0        # margin on the BEM's own error estimate (BEM-only cases and fields)
FIELD_FLOOR = 1e-11  # a field error is never below this × the largest magnitude of its column
FIELD_POINTS = 256   # the stated grid of the fields, x_j = j/M − 1/2

#: the certification rule, as written into the suite data and the exported README
RULE = (
    "Every case is solved by the BEM on meshes N = 2^10 ... 2^18. The convergence study of a "
    f"scalar q uses the {LAST + 1} finest meshes: the differences d_i = |q_i - q_(i-1)|, the "
    "observed order p (least-squares slope of log d_i against log N_i; nothing is certified "
    f"below {MIN_ORDER}, p is capped at {MAX_ORDER:g}), the envelope D (the smallest line of "
    "slope -p above every d_i, at the finest mesh), the Richardson value "
    "q_R = q_L + (q_L - q_(L-1))/(2^p - 1) and "
    "the error estimate E = D/(2^p - 1). When the last two differences are below "
    f"{ROUNDOFF:g} |q| the study is in the round-off regime: q_R = q_L and E is the larger of "
    f"{ROUNDOFF:g} |q| and the last difference. When p is below {MIN_ORDER} but the values of "
    f"the study all lie within {SCATTER_FLOOR:g} |q| of each other and move both up and down, "
    "they have settled and scatter (the sub-panel edge fits): q_R = q_L and E is their spread "
    "(largest minus smallest); values that move one way only drift and are not converging. "
    "Two roads (standard linear solid and sinusoid): the certified value is the semi-analytic one, "
    "a, with the error e = |a - q_R| (the digits on which the two roads agree; q_R is replaced by "
    "the finest value q_L when the study is in the round-off regime or its differences scatter "
    f"with an observed order below {MIN_ORDER}). BEM only (Prony "
    f"series, other profiles): the certified value is q_R with e = {SAFETY:g} E. BEM and the "
    "Fourier reference (sinusoid on a Prony material, or on the standard linear solid over a "
    "layer, where the semi-analytic road does not apply; cases that declare it): the point is "
    "also solved by the independent Fourier collocation of analytic.fourier_solve (the creep "
    "series of the case's material, the case's layer), and the certified value is q_R with "
    f"e = max({SAFETY:g} E, |q_R - q_F|), q_F the Fourier value: the digits on which both roads "
    "agree, never more than the BEM's own study supports; a failed reference certifies nothing. "
    "The certified "
    "significant digits are the largest d with e < 1/2 * 10^(floor(log10|value|) - d + 1) (half "
    "a unit of the last certified digit bounds e) and that half unit at least "
    f"{RELATIVE_FLOOR:g} |value| (ten times the round-off level, so that a certified digit "
    "survives recomputation on another machine). Fields on the stated grid carry "
    "an absolute error per point: two roads, the largest |semi-analytic - BEM(finest N)| at the "
    "point and its two neighbours; otherwise (the Fourier-referenced cases too: their reference "
    f"is judged on the scalars), {SAFETY:g} x the largest change between the two "
    f"finest meshes at the point and its neighbours; never below {FIELD_FLOOR:g} x the largest "
    "magnitude of the column. A failed solve on any of the finest meshes certifies nothing.")

FIELD_COLUMNS = ("pressure", "displacement", "gap")
TOP_KEYS = ("mu", "tau_f", "penetration", "separation", "load", "contact_fraction", "ka", "ke",
            "ke_hat", "approach", "mean_displacement")
#: the scalars of a layer only (`_scalar_keys`): read from the BEM's ``diagnostics["layer"]``
LAYER_KEYS = ("approach", "mean_displacement")


# --------------------------------------------------------------------------- the suite file
def load_suite(path=None) -> dict:
    """The suite as a dict (``version``, ``description``, ``rule``, ``cases``: a list of case
    dicts); ``path`` defaults to the shipped ``suite.json``."""
    path = SUITE_FILE if path is None else path
    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, ValueError) as exc:
        raise SuiteError(f"suite data {path}: cannot be read ({exc})") from None


def all_cases(suite) -> list:
    """Every case of the suite in its order: the line contacts (``cases``), then the surfaces
    (``surfaces``: rigid periodic surfaces, three-dimensional contact; `is_surface`)."""
    return list(suite["cases"]) + list(suite.get("surfaces", []))


def case_names(suite=None) -> list[str]:
    suite = suite or load_suite()
    return [c["name"] for c in all_cases(suite)]


def select(suite, names):
    """The cases named (all when ``names`` is empty), in suite order; SuiteError for an unknown
    name."""
    cases = all_cases(suite)
    if not names:
        return list(cases)
    known = {c["name"]: c for c in cases}
    bad = [n for n in names if n not in known]
    if bad:
        raise SuiteError(f"--cases {bad[0]}: must be one of the {len(known)} cases of "
                         f"`suite --list`, e.g. {', '.join(list(known)[:2])}")
    return [c for c in cases if c["name"] in set(names)]


def get_case(name, suite=None) -> dict:
    return select(suite or load_suite(), [name])[0]


def two_roads(point) -> bool:
    """True when the semi-analytic road applies (sinusoid on the standard linear solid, on the
    half-space: the road has no layer)."""
    return (not point.get("profile") and not point.get("prony") and not point.get("material")
            and not point.get("layer") and not point.get("surface"))


def is_surface(case_or_point) -> bool:
    """True for a surface case (or its point): a rigid periodic surface, ``point["surface"]``."""
    point = case_or_point.get("point", case_or_point)
    return bool(point.get("surface"))


#: the independent references a case may declare (``"reference"``), beyond the two roads
REFERENCES = ("fourier",)


def reference_of(case):
    """The independent reference a case declares (None or one of REFERENCES); SuiteError for
    one it may not have."""
    ref = case.get("reference")
    if ref is None:
        return None
    if ref not in REFERENCES:
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed: "
                         f"one of {', '.join(REFERENCES)} or none")
    p = case["point"]
    if p.get("profile") or two_roads(p):
        # the Fourier collocation solves the sinusoid only, and the standard linear solid on the
        # half-space has the semi-analytic road already (on a layer it has not: allowed)
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed here: a "
                         "sinusoid on a Prony material (prony or material) or over a layer, not "
                         + ("a profile file" if p.get("profile")
                            else "the standard linear solid on the half-space"))
    return ref


def data_path(rel) -> Path:
    return DATA / rel


#: what each form of a material file is called (in the export's inputs.json and prony.txt)
FORM_NAMES = {"creep": "creep series", "relaxation": "relaxation series (generalised Maxwell)",
              "dma": "DMA master curve"}


def case_material(point, base=DATA):
    """The :class:`comparisons._materials.Material` of a point that names a ``material`` file
    (any form: creep, relaxation, DMA; at ``temperature`` with ``wlf`` when given); SuiteError
    naming the file for a bad one."""
    from . import _materials
    wlf = point.get("wlf")
    try:
        return _materials.read(str(Path(base) / point["material"]),
                               temperature=point.get("temperature"),
                               wlf=tuple(float(v) for v in wlf) if wlf is not None else None)
    except ValueError as exc:
        raise SuiteError(f"material {point['material']}: {str(exc).splitlines()[0]}") from None


def _problem(point, base=DATA):
    """(profile, material) objects of the BEM for an operating point dict."""
    if point.get("prony"):
        material = _roads.read_prony(Path(base) / point["prony"])
    elif point.get("material"):
        material = case_material(point, base).prony
    else:
        material = _roads.standard_linear_solid(op.ratio_of(point))
    if point.get("profile"):
        profile = _roads.read_profile(Path(base) / point["profile"])
    else:
        profile = _roads.sinusoid(op.hk_of(point))
    return profile, material


def bem_solution(point, nodes, base=DATA, problem=None):
    """The BEM solution at an operating point on ``nodes`` panels (`roads.bem_solution`, Krylov
    tolerance `roads.BEM_TOL`); ``problem`` is read from the point's files under ``base`` when
    not given."""
    return _roads.bem_solution(point, nodes, problem or _problem(point, base))


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


def _num(v):
    """JSON-safe float (None for NaN/inf)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


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
    nodes = [int(n) for n in case["nodes"]]
    roads = two_roads(point)
    reference = reference_of(case)
    problem = _problem(point, base)
    shape = ProfileShape(point, base)
    M = _field_points(case, nodes)
    meshes = _solve_meshes(point, nodes, base, problem, shape, M, progress)
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


def _solve_meshes(point, nodes, base, problem, shape, M, progress):
    """Solve the BEM on every mesh (`_Meshes`), with its patches and, on the two finest, its
    fields on the stated grid of M points; ``progress`` gets a line per mesh."""
    runs, patches, failures = [], [], []
    grid_fields = {}
    for n in nodes:
        t0 = time.perf_counter()
        r = bem_solution(point, n, base, problem)
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
                             f"from N = {second} at the point and its neighbours")
        for c in FIELD_COLUMNS:
            if bl is None:
                out[c] = np.full(M, np.nan)
                out[c + "_err"] = np.full(M, np.inf)
                continue
            a = np.asarray(bl[c], float)
            diff = np.abs(a - bp[c]) if bp is not None else np.full(M, np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(SAFETY * neighbour_max(diff),
                                         FIELD_FLOOR * np.max(np.abs(a)))
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


# --------------------------------------------------------------------------- compare
def _as_float(v):
    return float("nan") if v is None else float(v)


def compare(old, new, old_fields=None, new_fields=None):
    """Differences between a shipped certification and a recomputed one.

    Returns
    -------
    (list of str, list of str)
        ``changed``: every certified digit that changed (each line names the quantity, both
        values and the difference); ``raised``: quantities the recomputation certifies to more
        digits than shipped.
    """
    changed, raised = [], []

    def one(label, o, n):
        if n is None:
            if o["digits"] > 0:
                changed.append(f"{label}: certified {o['rounded']} ({o['digits']} digits) but no "
                               "longer computed")
            return
        ov, nv = _as_float(o["value"]), _as_float(n["value"])
        if o["digits"] > 0:
            diff = abs(nv - ov) if math.isfinite(nv) else math.inf
            if not diff < half_unit(ov, o["digits"]):
                changed.append(f"{label}: certified {o['rounded']} ({o['digits']} digits), "
                               f"recomputed {nv!r}, difference {diff:.3e} ≥ half a unit "
                               f"{half_unit(ov, o['digits']):.1e}")
            elif n["digits"] < o["digits"]:
                changed.append(f"{label}: certified to {o['digits']} digits, the recomputed "
                               f"evidence supports {n['digits']} (error {n['error']})")
        if n["digits"] > o["digits"]:
            raised.append(f"{label}: {o['digits']} → {n['digits']} digits")

    for k, o in old["scalars"].items():
        one(k, o, new["scalars"].get(k))
    for k in new["scalars"]:
        if k not in old["scalars"] and new["scalars"][k]["digits"] > 0:
            raised.append(f"{k}: newly certified ({new['scalars'][k]['digits']} digits)")
    for k, v in old["exact"].items():
        if new["exact"].get(k, "missing") != v:
            changed.append(f"{k}: exact value {v!r}, recomputed {new['exact'].get(k, 'missing')!r}")
    if len(old["patches"]) != len(new["patches"]):
        changed.append(f"patches: {len(old['patches'])} certified, "
                       f"{len(new['patches'])} recomputed")
    else:
        for j, (po, pn) in enumerate(zip(old["patches"], new["patches"])):
            for k in PATCH_KEYS:
                one(f"patch {j + 1} {k}", po[k], pn[k])
    if old_fields is not None and new_fields is not None:
        for c in FIELD_COLUMNS:
            o, n, e = old_fields[c], new_fields[c], old_fields[c + "_err"]
            bad = ~(np.abs(n - o) <= e)
            if np.any(bad):
                j = np.unravel_index(int(np.flatnonzero(bad)[0]), bad.shape)
                if "x" in old_fields:  # a surface's: x along axis 0, y along axis 1
                    at = f"x = {old_fields['x'][j[0]]:.6f}, y = {old_fields['y'][j[1]]:.6f}"
                else:
                    at = f"x/λ = {old_fields['x_over_lambda'][j[0]]:.6f}"
                changed.append(f"field {c}: {int(bad.sum())} values moved by more than their "
                               f"certified error (first at {at}: "
                               f"{o[j]!r} → {n[j]!r}, error {e[j]:.2e})")
    return changed, raised


# --------------------------------------------------------------------------- check
def _case_key(case) -> str:
    """Hash of what determines a case's recomputation: its definition (the point with its
    ``layer``: thickness, foundation, ν), its input files, the version and the source of both
    roads."""
    import viscosine
    h = hashlib.sha256()
    # the whole point, its layer included: a case whose layer changed is never taken for the
    # one recomputed before (a half-space point has no "layer" key: its key is as it was)
    h.update(json.dumps({k: case[k] for k in ("name", "point", "nodes")}, sort_keys=True).encode())
    if is_surface(case):  # its second opinions and their grids (the line cases' keys unchanged)
        h.update(json.dumps({k: case.get(k) for k in ("references", "reference_nodes")},
                            sort_keys=True).encode())
    h.update(str(case.get("field_points", FIELD_POINTS)).encode())
    if case.get("reference"):  # only when declared: the keys of the other cases stay as they were
        h.update(f"reference={case['reference']}".encode())
    for k in ("profile", "prony", "material"):
        if case["point"].get(k):
            h.update((DATA / case["point"][k]).read_bytes())
    if case["point"].get("material"):
        # the conversion and the DMA fit are the material's reading, outside both roads' source
        from viscosine import materials as vm

        from . import _materials
        for mod in (vm, _materials):
            h.update(Path(mod.__file__).read_bytes())
    h.update(viscosine.__version__.encode())
    h.update(_roads.source_hash().encode())
    return h.hexdigest()[:20]


def _recompute(case):
    """Worker entry: recompute one case, given by name (the shipped definition) or as the
    case's definition being checked (plain data in, plain data out): the key saved is that of
    what was solved, its layer included."""
    case = get_case(case) if isinstance(case, str) else case
    t0 = time.perf_counter()
    cert, fields = compute(case)
    return {"name": case["name"], "key": _case_key(case), "certified": cert,
            "fields": {k: np.asarray(v).tolist() for k, v in fields.items()},
            "seconds": time.perf_counter() - t0}


def _recomputed(cases, out, resume, workers, scheduler, log):
    """Yield each case's recomputation (reusing finished ones from ``out`` with ``resume``)."""
    todo = []
    for case in cases:
        path = Path(out) / f"{case['name']}.json" if out else None
        if resume and path is not None and path.exists():
            try:
                doc = json.loads(path.read_text(encoding="utf-8"))
            except ValueError:
                doc = None
            if doc and doc.get("key") == _case_key(case):
                log(f"suite: {case['name']}: reused from {path}")
                yield doc
                continue
        # the definition checked (not the shipped one by name): a suite whose point or layer
        # differs is recomputed as it is, under its own key
        todo.append({k: case[k] for k in case if k != "certified"})

    def save(doc):
        if out:
            write_text(Path(out) / f"{doc['name']}.json", json.dumps(doc))
        return doc

    if not todo:
        return
    # one mechanism for every parallel run of the project (comparisons/_cluster.py): this
    # process, local processes or a Dask cluster; a case whose recomputation raises or whose
    # worker dies comes back as a Failure and is reported, the others go on
    from . import _cluster
    local = workers if (workers and workers > 1 and len(todo) > 1 and not scheduler) else None
    with _cluster.executor(local, scheduler) as ex:
        for i, value in ex.imap(_recompute, todo, ordered=False):
            if isinstance(value, _cluster.Failure):
                yield {"name": todo[i]["name"], "failed": value.error, "seconds": 0.0}
            else:
                yield save(value)


def check(names=(), out=None, resume=False, workers=1, scheduler=None, log=None, suite=None):
    """Recompute the cases and compare them with the shipped certification.

    Parameters
    ----------
    names : sequence of str
        Cases to check (all when empty).
    out : path, optional
        Folder where each recomputed case is written as soon as it is done.
    resume : bool
        Reuse the cases already recomputed in ``out`` (same definition, same version).
    workers : int
        Processes (1: in this process).
    scheduler : str, optional
        Address of a Dask distributed scheduler (instead of local processes).
    log : callable, optional
        Progress lines (default: standard error).
    suite : dict, optional
        The suite to check against (default: the shipped one): its cases' definitions (point,
        layer, meshes) are what is recomputed, its certification what they are compared with.

    Returns
    -------
    dict
        ``ok`` (no certified digit changed and every case recomputed), ``cases`` (per case:
        name, changed, raised, seconds, status; a case whose recomputation raised or whose
        worker died has status "failed" and says why in ``changed``) and ``seconds``.
    """
    progress = Progress()  # without a log: each case's line throttled, a change always shown
    say, tick = (log, log) if log else (progress.say, progress.update)
    suite = suite or load_suite()
    cases = select(suite, names)
    t0 = time.monotonic()
    results = []
    by_name = {c["name"]: c for c in cases}
    for i, doc in enumerate(_recomputed(cases, out, resume, workers, scheduler, tick), 1):
        case = by_name[doc["name"]]
        if "failed" in doc:  # the recomputation itself failed: nothing certified is confirmed
            results.append({"name": doc["name"], "raised": [], "seconds": 0.0,
                            "changed": [f"recomputation failed: {doc['failed']}"],
                            "status": "failed", "notes": [doc["failed"]]})
            say(f"suite: [{i}/{len(cases)}] {doc['name']}: FAILED ({doc['failed']})")
            continue
        old_fields = case_fields(case)
        new_fields = {k: np.asarray(v, float) for k, v in doc["fields"].items()}
        changed, raised = compare(case["certified"], doc["certified"], old_fields, new_fields)
        results.append({"name": doc["name"], "changed": changed, "raised": raised,
                        "seconds": doc.get("seconds", 0.0), "status": doc["certified"]["status"],
                        "notes": doc["certified"]["notes"]})
        what = "CHANGED" if changed else "ok"
        (say if changed else tick)(f"suite: [{i}/{len(cases)}] {doc['name']}: {what} "
                                   f"({doc.get('seconds', 0.0):.1f} s, "
                                   f"{time.monotonic() - t0:.0f} s in all)")
    progress.close()
    order = {c["name"]: i for i, c in enumerate(cases)}
    results.sort(key=lambda r: order[r["name"]])
    return {"ok": not any(r["changed"] for r in results), "cases": results,
            "seconds": time.monotonic() - t0}


# --------------------------------------------------------------------------- certify
def certify(names=(), log=None, suite_file=None):
    """Recompute the cases and write their certification into the suite data (maintainers)."""
    log = log or (lambda s: print(s, file=sys.stderr, flush=True))
    suite_file = SUITE_FILE if suite_file is None else suite_file
    suite = load_suite(suite_file)
    cases = select(suite, names)
    for case in cases:
        t0 = time.perf_counter()
        cert, fields = compute(case, progress=lambda s, n=case["name"]: log(f"suite: {n}: {s}"))
        surface = is_surface(case)
        rel = f"fields/{case['name']}.{'npz' if surface else 'csv'}"
        cert["fields"]["file"] = rel
        case["certified"] = cert
        (write_surface_fields if surface else write_fields)(DATA / rel, case, fields)
        log(f"suite: {case['name']}: certified in {time.perf_counter() - t0:.1f} s "
            f"(mu {cert['scalars']['mu']['digits']} digits)")
    suite["rule"] = RULE
    if suite.get("surfaces"):
        suite["surface_rule"] = SURFACE_RULE
    write_text(suite_file, json.dumps(suite, indent=1, ensure_ascii=False) + "\n")


def check_lines(res):
    """The lines `check`'s result ``res`` prints, one or more per case: ok (with its status
    when not complete), CHANGED or FAILED with what changed, and the digits that can be raised."""
    out = []
    for r in res["cases"]:
        if r["status"] == "failed":
            out.append(f"{r['name']}: FAILED")
            out += [f"  {line}" for line in r["changed"]]
        elif r["changed"]:
            out.append(f"{r['name']}: CHANGED")
            out += [f"  {line}" for line in r["changed"]]
        else:
            out.append(f"{r['name']}: ok" + (f" ({r['status']}: {'; '.join(r['notes'])[:300]})"
                                             if r["status"] != "complete" else ""))
        out += [f"  can be raised: {line} (run suite --certify --cases {r['name']})"
                for line in r["raised"]]
    return out


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
#: the reference's estimates are relative for these (absolute for mu_lateral, contact_fraction)
_SURFACE_RELATIVE = ("mu", "penetration")

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
    nodes = [int(n) for n in case["nodes"]]
    refs = surface_references(case)
    M = int(case.get("field_points", SURFACE_FIELD_POINTS))
    if nodes[-1] % M or nodes[-2] % M:
        raise SuiteError(f"case {case['name']}: the two finest grids must be multiples of {M}")
    runs, failures, grid_fields = [], [], {}
    for n in nodes:
        t0 = time.perf_counter()
        r = _roads.surface_solution(point, n)
        runs.append(r if r.success else None)
        if not r.success:
            failures.append(f"N = {n}: {r.message.splitlines()[0][:200]}")
        elif n in nodes[-2:]:
            grid_fields[n] = _surface_fields_of(r, M)
        if progress:
            progress(f"surface grid {n}: {'ok' if r.success else 'FAILED'} "
                     f"({time.perf_counter() - t0:.2f} s)")
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
        own = (fin.error_estimate or {}).get(k) if fin is not None else None
        if own is not None:  # the BEM's own estimate, made absolute (mu_lateral's is over |μ|)
            scale = abs(fin.mu) if k == "mu_lateral" else abs(vals[-1]) \
                if k in _SURFACE_RELATIVE else 1.0
            own = float(own) * scale
        fv = None
        if four is not None:
            if four.success:
                e = float(four.error_estimate.get(k, math.nan))
                fv = (float(getattr(four, k)), e * abs(float(getattr(four, k)))
                      if k in _SURFACE_RELATIVE else e)
            else:
                fv = (math.nan, math.nan)
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
