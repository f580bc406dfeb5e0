"""The certified benchmark suite: steady viscoelastic sliding cases with certified digits.

    python -m comparisons suite --check [--cases NAME ...] [--out DIR] [--resume] [--workers W]
                                        [--scheduler ADDRESS]
    python -m comparisons suite --certify [--cases NAME ...]          (maintainers)

This module reads the suite's cases and checks a recomputation against what is shipped; a case
is computed and certified by mesh refinement in :mod:`comparisons.suite_compute` (a surface case
in :mod:`comparisons.suite_surfaces`), on the rule's constants and a case's point of
:mod:`comparisons.suite_cases`; this module re-exports their names.  Its other neighbours:
:mod:`comparisons.suite_inputs` (where the data is, a case's indenter, the generators of the
synthetic inputs),
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

import hashlib
import json
import math
import sys
import time
import warnings
from pathlib import Path

import numpy as np

from . import roads as _roads
from ._errors import SuiteError
from ._io import write_text
from .convergence import half_unit
from .progress import Progress

# the names of the suite's modules, re-exported: one interface (``comparisons.suite.NAME``)
from .suite_cases import (BEM_PRESSURE_FLOOR, FIELD_COLUMNS, FIELD_FLOOR,  # noqa: F401
                          FIELD_POINTS, FORM_NAMES, LAYER_KEYS, REFERENCES, RULE, SAFETY,
                          TOP_KEYS, _problem, bem_solution, case_material, data_path,
                          is_surface, reference_of, two_roads)
from .suite_compute import (FIELDS_HEADER, FOURIER_METHOD, case_fields,  # noqa: F401
                            compute, layer_compression, write_fields)
from .suite_surfaces import (SURFACE_FIELD_POINTS, SURFACE_KEYS,  # noqa: F401
                             SURFACE_REFERENCES, SURFACE_RULE, compute_surface, surface_fields,
                             surface_references, write_surface_fields)

# part of the suite's interface though this module does not use them: the cap on certified
# digits, the convergence study's names, and the generators of the synthetic inputs (the
# shipped files cite them as comparisons.suite.NAME)
from .convergence import (LAST, MAX_DIGITS, MAX_ORDER, MIN_ORDER,  # noqa: F401
                          RELATIVE_FLOOR, ROUNDOFF, SCATTER_FLOOR, digits, rounded, study)
from .fields import PATCH_KEYS, match_patches, neighbour_max, patch_records  # noqa: F401
from .suite_inputs import DATA, ProfileShape  # noqa: F401
from .suite_inputs import (BROAD24, LOGNORMAL32, RELAX16, SELF_AFFINE,  # noqa: F401
                           creep_spectrum, harmonic_heights, relaxation_spectrum,
                           self_affine_heights)

SUITE_FILE = DATA / "suite.json"


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
    with warnings.catch_warnings():
        # a fixed mesh of the study: "refine N" does not apply, the study measures the error
        warnings.filterwarnings("ignore", message="the pressure memory layer spans")
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
