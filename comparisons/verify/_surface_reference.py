"""The reference of a surface verification, what is compared with it, and the tolerances.

The reference is the suite's surface case: its certified scalars (each with its certified
error) and its certified fields on the stated grid of M × M panel centres (M = 64,
`comparisons.suite.SURFACE_FIELD_POINTS`).  Fields on another grid of nx × ny panel centres are
compared on the points the two grids share: every (M/g)-th point of the stated grid and every
(nx/g)-th of the user's, g = gcd(nx, M) (and likewise along y), at least COMMON_MIN a side.

Measures: relative for μ, Δ/h_ref and the load; absolute for the contact fraction and the
number of patches; μ_lateral absolute over |μ| of the reference (the lateral force can
vanish).  Field norms on the shared points: σ L2 (root mean square) and L∞ over max σ of the
reference, u and gap (over h_ref) L2 and L∞.

Tolerances follow from the grid, as on the line: max(DEFAULT_RTOL, GRID_FACTOR · e_N), e_N
what viscosine's surface BEM on the same grid misses the reference by in the same measure (the
larger of its miss at N and half its miss at N/2, so that an error crossing zero at N does
not shrink it; for a scalar the solver gave itself, the BEM's own value's miss, and for one
derived from fields, the miss of the same derivation from the BEM's fields, keeping the columns
the user gave).  For the field norms too: a correct panel solver's
σ errs at the contact edges by a fixed fraction of the panels there, and the surface BEM
measures it on the grid asked about.  Above SURFACE_GRID_MAX_NODES the BEM measures the grid
of SURFACE_GRID_MAX_NODES instead (a looser tolerance, said in the verdict).
"""
from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass

import numpy as np

from .. import roads
from .. import suite as _suite
from ._surface_fields import scalars_from_fields
from ._tolerances import DEFAULT_RTOL, GRID_FACTOR

#: the scalars a surface verification compares, the norms of the fields
SURFACE_SCALARS = ("mu", "mu_lateral", "penetration", "contact_fraction", "load", "n_patches")
SURFACE_NORMS = ("pressure_L2", "pressure_Linf", "displacement_L2", "displacement_Linf",
                 "gap_Linf")
SURFACE_KEYS = SURFACE_SCALARS + SURFACE_NORMS
SURFACE_REL = ("mu", "penetration", "load")
SURFACE_LABELS = {"mu": "μ", "mu_lateral": "μ_lateral", "penetration": "Δ/h_ref",
                  "contact_fraction": "contact fraction", "load": "p̃∞",
                  "n_patches": "contact patches", "pressure_L2": "σ L2 / max σ",
                  "pressure_Linf": "σ L∞ / max σ", "displacement_L2": "u L2 / h_ref",
                  "displacement_Linf": "u L∞ / h_ref", "gap_Linf": "gap L∞ / h_ref"}
MEASURES = {"mu": "relative", "penetration": "relative", "load": "relative",
            "mu_lateral": "absolute (over |μ|)", "contact_fraction": "absolute",
            "n_patches": "count", "pressure_L2": "relative to max σ",
            "pressure_Linf": "relative to max σ", "displacement_L2": "absolute (over h_ref)",
            "displacement_Linf": "absolute (over h_ref)", "gap_Linf": "absolute (over h_ref)"}
#: the shared grid of the user's points and the stated grid has at least this many a side
COMMON_MIN = 16
#: the surface BEM measures e_N on no grid finer than this (about 10 s with its half)
SURFACE_GRID_MAX_NODES = 512
#: the resolutions of a surface --callable when --nodes is not given
SURFACE_DEFAULT_NODES = (64, 128, 256)


@dataclass
class SurfaceReference:
    """A surface case's certified values: ``scalars[key]`` = (value, absolute uncertainty),
    the fields on the stated grid (``x``, ``y``, each column and ``<column>_err``)."""

    point: dict
    case: dict
    scalars: dict
    fields: dict
    full_contact: bool
    road = "suite (certified)"

    @property
    def description(self):
        cert = self.case["certified"]
        return (f"the certified values of the suite case {self.case['name']} ({cert['method']}"
                f"; fields: {cert['fields']['source']})")

    @property
    def mu(self):
        return self.scalars["mu"][0]

    def shared(self, nx, ny):
        """((user step x, y), (reference step x, y)) of the points an nx × ny grid shares with
        the stated grid, or None when fewer than COMMON_MIN a side."""
        mx, my = self.fields["pressure"].shape
        gx, gy = math.gcd(nx, mx), math.gcd(ny, my)
        if gx < COMMON_MIN or gy < COMMON_MIN:
            return None
        return (nx // gx, ny // gy), (mx // gx, my // gy)

    def on_shared(self, nx, ny):
        """(reference columns, their uncertainty, user steps) on the shared points."""
        (ux, uy), (rx, ry) = self.shared(nx, ny)
        ref = {c: self.fields[c][::rx, ::ry] for c in _suite.FIELD_COLUMNS}
        unc = {c: self.fields[c + "_err"][::rx, ::ry] for c in _suite.FIELD_COLUMNS}
        return ref, unc, (ux, uy)


def surface_reference(point, case):
    """The `SurfaceReference` of a surface suite case."""
    cert = case["certified"]
    sc = {k: (float(r["value"]), float(r["error"]) if r["error"] is not None else math.inf)
          for k, r in cert["scalars"].items() if r["value"] is not None}
    for k in ("mu_lateral", "penetration", "contact_fraction", "n_patches"):
        if k in cert["exact"]:
            sc[k] = (float(cert["exact"][k]), 0.0)
    if point.get("load") is not None:
        sc["load"] = (float(point["load"]), 0.0)
    return SurfaceReference(point, case, sc, _suite.case_fields(case),
                            bool(cert["exact"]["full_contact"]))


def measure(key, value, ref, mu_ref):
    """The difference of ``value`` from ``ref`` in the verdict's measure (None without both)."""
    if value is None or ref is None:
        return None
    if key in SURFACE_REL:
        return abs(value - ref) / abs(ref) if ref != 0.0 else abs(value - ref)
    if key == "mu_lateral":
        return abs(value - ref) / abs(mu_ref) if mu_ref else abs(value - ref)
    return abs(value - ref)


def norms(fields, reference, pressure=None):
    """The field norms of a user's fields against the reference on the shared points (empty
    when the grids share too few); ``pressure`` replaces the fields' own (a diagnosis)."""
    p = fields["pressure"] if pressure is None else pressure
    nx, ny = p.shape
    if reference.shared(nx, ny) is None:
        return {}
    ref, _, (ux, uy) = reference.on_shared(nx, ny)
    pm = float(np.max(np.abs(ref["pressure"])))
    d = p[::ux, ::uy] - ref["pressure"]
    out = {"pressure_L2": float(np.sqrt(np.mean(d * d))) / pm,
           "pressure_Linf": float(np.max(np.abs(d))) / pm}
    if "displacement" in fields:
        d = fields["displacement"][::ux, ::uy] - ref["displacement"]
        out["displacement_L2"] = float(np.sqrt(np.mean(d * d)))
        out["displacement_Linf"] = float(np.max(np.abs(d)))
    if "gap" in fields:
        out["gap_Linf"] = float(np.max(np.abs(fields["gap"][::ux, ::uy] - ref["gap"])))
    return out


def reference_uncertainty(reference, nx, ny):
    """The reference's own uncertainty in each field norm on the shared points."""
    if reference.shared(nx, ny) is None:
        return {}
    ref, unc, _ = reference.on_shared(nx, ny)
    pm = float(np.max(np.abs(ref["pressure"])))
    out = {}
    for c, keys in (("pressure", ("pressure_L2", "pressure_Linf")),
                    ("displacement", ("displacement_L2", "displacement_Linf")),
                    ("gap", (None, "gap_Linf"))):
        scale = pm if c == "pressure" else 1.0
        if keys[0]:
            out[keys[0]] = float(np.sqrt(np.mean(unc[c] ** 2))) / scale
        out[keys[1]] = float(np.max(unc[c])) / scale
    return out


# ------------------------------------------------------------------------------ the tolerances
@functools.lru_cache(maxsize=32)
def _bem_at(point_json, nodes, columns):
    """(own scalars, scalars derived from its fields, its fields) of the surface BEM on
    ``nodes`` panels along x, keeping ``columns`` (cached: a run asks for one grid more than
    once); None when it cannot solve there."""
    point = json.loads(point_json)
    try:
        res = roads.surface_solution(point, int(nodes))
    except ValueError:
        return None
    if not res.success:
        return None
    fields = {"x": res.fields().x, "y": res.fields().y,
              **{c: np.asarray(getattr(res, c), float) for c in columns}}
    surf = roads.surface_on_grid(point["surface"], *res.shape)
    own = {k: float(getattr(res, k)) for k in ("mu", "mu_lateral", "penetration",
                                                "contact_fraction", "load")}
    own["n_patches"] = int(res.n_patches)
    return own, scalars_from_fields(fields, point, surf), fields


def _misses(reference, nodes, columns, own_keys):
    key = json.dumps(reference.point, sort_keys=True, default=float)
    got = _bem_at(key, int(nodes), tuple(columns))
    if got is None:
        return {}
    own, derived, fields = got
    out = {}
    for k in SURFACE_SCALARS:
        ref = reference.scalars.get(k, (None, None))[0]
        if ref is None or k == "n_patches":
            continue
        m = measure(k, (own if k in own_keys else derived).get(k), ref, reference.mu)
        if m is not None:
            out[k] = m
    out.update(norms(fields, reference))
    # the count a correct solver finds on this grid: judged only where it is the reference's
    out["n_patches_found"] = own["n_patches"]
    return out


def grid_errors(reference, nodes, columns=_suite.FIELD_COLUMNS, own_keys=()):
    """e_N of every scalar and field norm (the module's docstring) and ``n_patches_found``,
    the patches the surface BEM finds on this grid; ``own_keys``: the scalars the solver under
    test gave itself (the others are derived from its fields)."""
    at_n = _misses(reference, nodes, columns, own_keys)
    at_half = _misses(reference, int(nodes) // 2, columns, own_keys) if nodes % 2 == 0 else {}
    out = {k: max(e, 0.5 * at_half[k]) if k in at_half and k != "n_patches_found" else e
           for k, e in at_n.items()}
    return out


def tolerances(reference, nodes, columns, own_keys=(), rtol=DEFAULT_RTOL, rtol_given=False,
               tol=None):
    """({key: (tolerance, reason)} of every scalar and field norm on a grid of ``nodes`` panels
    along x (None: not known), the patches the BEM finds there (or None), lines that explain
    the reasons); ``own_keys`` as `grid_errors`."""
    out, found, explain = {}, None, []
    src = f"--rtol {rtol:.1e}" if rtol_given else f"the default --rtol {rtol:.1e}"
    if nodes is None or rtol_given:
        why = "" if rtol_given else ": the grid is not known (no fields, no nodes)"
        for k in SURFACE_KEYS:
            out[k] = (0.0 if k == "n_patches" else rtol, f"{src}{why}")
    else:
        n = int(nodes)
        measured = min(n, SURFACE_GRID_MAX_NODES)
        errs = grid_errors(reference, measured, columns, own_keys)
        found = errs.get("n_patches_found")
        where = (f"N = {n}" if measured == n else
                 f"N = {n}, measured on N = {measured} (the finest grid the BEM measures: "
                 "looser than this grid's own error)")
        law = f"max({rtol:.1e}, {GRID_FACTOR:g} e_N), {where}"
        explain.append("e_N: what viscosine's surface BEM on this grid misses the reference by "
                       "(the larger of its miss at N and half that at N/2), in the same measure "
                       "and from the same source (its own scalars, or derived from its fields "
                       "as yours are): a correct solver's discretisation error here")
        for k in SURFACE_KEYS:
            e = errs.get(k)
            if k == "n_patches":
                out[k] = (0.0, "a count: the surface BEM on this grid finds the reference's")
            elif e is None:
                out[k] = (rtol, f"the default {rtol:.1e}: viscosine's surface BEM on N = "
                                f"{measured} does not give this quantity to measure the grid's "
                                "error by")
            elif GRID_FACTOR * e > rtol:
                out[k] = (GRID_FACTOR * e, f"{law}: e_N = {e:.1e}")
            else:
                out[k] = (rtol, f"{law}: {rtol:.1e} binds (e_N = {e:.1e})")
    for k, v in (tol or {}).items():
        out[k] = (v, f"--tol {k}={v:g}")
    return out, found, explain
