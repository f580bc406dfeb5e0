"""The last line of defence: a record is printed as a result only when it is a valid answer.

:func:`check_record` says why a road's JSON record must not be printed (or None): the road must
say success, every number must be finite and physical (to the round-off allowances below), the
achieved load or penetration must be the one asked for and, when the adapter gives them
(`comparisons.roads.Solved`), the constraint figures must hold: σ ≥ 0, gap ≥ 0, mean σ = load.
`comparisons.runner.run` applies it to every point it solves; the report and the results store
apply it to the records of a third code and to the records they read back.
"""
from __future__ import annotations

import math

import numpy as np

from viscosine.protocol import SCALAR_KEYS

from ._errors import one_line

#: round-off allowances of the physical checks
RANGE_ROUNDOFF = 1e-12     # Δ/h ≤ 1, ka ≤ π, contact fraction ≤ 1, μ ≥ 0, τf ≥ 0
CONSTRAINT_ROUNDOFF = 1e-8  # σ ≥ 0 (over max σ), gap ≥ 0 (over h): the solvers' own tolerances
CONTROL_MISMATCH = 1e-6    # achieved load (or Δ/h) against the one asked for, and mean σ = load


def _nonfinite(v, path=""):
    """The first path to a non-finite number in a JSON-like value, or None."""
    if isinstance(v, dict):
        for k, x in v.items():
            bad = _nonfinite(x, f"{path}.{k}" if path else str(k))
            if bad:
                return bad
    elif isinstance(v, (list, tuple)):
        for i, x in enumerate(v):
            bad = _nonfinite(x, f"{path}[{i}]")
            if bad:
                return bad
    elif isinstance(v, float) and not math.isfinite(v):
        return f"{path} = {v!r}"
    return None


def check_record(rec, spec, constraints=None, fields=None):
    """Why a record must not be printed as a result, or None when it is a valid answer.

    Checks: the road says success; every number finite; 0 < Δ/h ≤ 1, 0 < ka ≤ π (or null),
    0 < contact fraction ≤ 1, μ ≥ 0, τf ≥ 0 (to round-off); the achieved load (or Δ/h) is the one
    asked for; and, when the constraint figures are given, σ ≥ 0, gap ≥ 0 and mean σ = load.
    """
    if not isinstance(rec, dict):
        return "no record"
    if rec.get("success") is False:
        msg = one_line(rec.get("message") or "the solver reports failure")
        res = (rec.get("diagnostics") or {}).get("residuals")
        if res and "residual" not in msg:
            msg += "; residuals " + ", ".join(f"{k}={_fmt(v)}" for k, v in res.items())
        return msg  # the road's own words: not converged, accuracy target not reached, ...
    missing = [k for k in ("load", "speed") + SCALAR_KEYS if k not in rec]
    if missing:
        return f"invalid result: keys {', '.join(missing)} missing"
    bad = _nonfinite(rec)
    if bad:
        return f"invalid result: {bad} is not a finite number"
    for k in ("load", "speed", "contact_fraction", "penetration", "tau_f", "mu"):
        if not isinstance(rec[k], (int, float)) or isinstance(rec[k], bool):
            return f"invalid result: {k} = {_json(rec[k])} is not a finite number"
    # null is a statement: ka, kê with several patches, ke also in full contact; else a number
    several = isinstance(rec.get("n_patches"), int) and rec["n_patches"] > 1
    for k in ("ka", "ke", "ke_hat"):
        v = rec[k]
        if v is None and not several and not (k == "ke" and rec["full_contact"]):
            return f"invalid result: {k} = null with a single contact patch"
        if v is not None and (not isinstance(v, (int, float)) or isinstance(v, bool)):
            return f"invalid result: {k} = {_json(v)} is not a finite number"
    one = 1.0 + RANGE_ROUNDOFF
    if not 0.0 < rec["penetration"] <= one:
        return f"invalid result: penetration Δ/h = {rec['penetration']!r} outside (0, 1]"
    if rec["ka"] is not None and not 0.0 < rec["ka"] <= math.pi * one:
        return f"invalid result: ka = {rec['ka']!r} outside (0, π]"
    problem = _physical(rec) or _controls_and_constraints(rec, spec, constraints)
    if problem:
        return problem
    if fields is not None:
        for name, arr in fields.as_dict().items():
            if not np.all(np.isfinite(arr)):
                return f"invalid result: the field {name} is not finite"
    return None


#: the scalars every surface record holds (conventions.md, 'Surfaces')
SURFACE_KEYS = ("full_contact", "contact_fraction", "penetration", "tau_f", "mu", "mu_lateral",
                "n_patches", "max_pressure")


def check_surface_record(rec, spec, constraints=None):
    """`check_record` for a surface (three-dimensional contact): the road says success, the
    surface scalars are there and finite, 0 < Δ/h_ref ≤ 1, 0 < contact fraction ≤ 1, μ ≥ 0,
    the load (or Δ/h_ref) asked for, and the constraint figures when given."""
    if not isinstance(rec, dict):
        return "no record"
    if rec.get("success") is False:
        return one_line(rec.get("message") or "the solver reports failure")
    missing = [k for k in ("load", "speed", "direction") + SURFACE_KEYS if k not in rec]
    if missing:
        return f"invalid result: keys {', '.join(missing)} missing"
    bad = _nonfinite(rec)
    if bad:
        return f"invalid result: {bad} is not a finite number"
    if not 0.0 < rec["penetration"] <= 1.0 + RANGE_ROUNDOFF:
        return f"invalid result: penetration Δ/h_ref = {rec['penetration']!r} outside (0, 1]"
    return _physical(rec) or _controls_and_constraints(rec, spec, constraints)


def _physical(rec):
    """A contact fraction in (0, 1], a friction that resists and a positive load (or None)."""
    if not 0.0 < rec["contact_fraction"] <= 1.0 + RANGE_ROUNDOFF:
        return f"invalid result: contact_fraction = {rec['contact_fraction']!r} outside (0, 1]"
    for k in ("mu", "tau_f"):
        if rec[k] < -RANGE_ROUNDOFF:
            return f"invalid result: {k} = {rec[k]!r} < 0 (friction must resist the motion)"
    if not rec["load"] > 0.0:
        return f"invalid result: load = {rec['load']!r} ≤ 0"
    return None


def _controls_and_constraints(rec, spec, constraints):
    """The achieved control against the asked one, and the constraint figures (or None)."""
    for k in ("load", "penetration"):
        asked = spec.get(k)
        if asked is not None and abs(rec[k] / asked - 1.0) > CONTROL_MISMATCH:
            return f"invalid result: {k} = {rec[k]!r} is not the {asked!r} asked for"
    if constraints:
        if not all(isinstance(v, (int, float)) and math.isfinite(v) for v in constraints.values()):
            return f"invalid result: constraint figures not finite ({constraints})"
        if constraints["min_pressure"] < -CONSTRAINT_ROUNDOFF:
            return f"invalid result: negative pressure (min σ = {constraints['min_pressure']:.3e} of the pressure scale)"
        if constraints["min_gap"] < -CONSTRAINT_ROUNDOFF:
            return f"invalid result: interpenetration (min gap = {constraints['min_gap']:.3e} h)"
        if constraints["mean_pressure_error"] > CONTROL_MISMATCH:
            return (f"invalid result: mean σ differs from the load by "
                    f"{constraints['mean_pressure_error']:.3e} (relative)")
    return None


def _json(v):
    return "null" if v is None else repr(v)


def _fmt(v):
    return f"{v:.3e}" if isinstance(v, float) else repr(v)
