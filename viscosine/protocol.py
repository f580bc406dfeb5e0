"""The result protocol both roads (and the peers) share: the scalar keys, the JSON helper and the
contact patch.  No numerics here.

Keys, units and signs as in ``docs/conventions.md`` ('Outputs: the scalars of one operating
point'); positions x/λ in the crest frame.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

#: a mean pressure above this many times the instantaneous (glassy) plane-strain modulus
#: E∞/(1 − ν²), i.e. p̃∞ J(0+) > LINEAR_LIMIT, strains the solid by order one even at the
#: stiffest response: outside linear theory, and usually a pressure in the wrong unit
LINEAR_LIMIT = 1.0
#: a partial contact covering less than this fraction of the period is a vanishing sliver
#: (1 µm of a 1 mm wavelength): usually a load in the wrong unit
SLIVER = 1e-3

#: the eight scalars of one operating point, in the order of the conventions
SCALAR_KEYS = ("full_contact", "contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f",
               "mu")


def plain(v, *, keep_nonfinite=False):
    """A JSON-ready copy: numpy scalars as Python, tuples as lists, dict keys as str.

    Non-finite floats become None (a record serialisable with ``allow_nan=False``), unless
    ``keep_nonfinite`` (for a checker that must still see them).
    """
    if isinstance(v, dict):
        return {str(k): plain(x, keep_nonfinite=keep_nonfinite) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [plain(x, keep_nonfinite=keep_nonfinite) for x in v]
    if isinstance(v, (bool, np.bool_)):
        return bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        v = float(v)
        return v if keep_nonfinite or math.isfinite(v) else None
    return v


@dataclass(frozen=True)
class Patch:
    """One contact patch (positions x/λ, crest frame).

    Attributes
    ----------
    trailing_edge, leading_edge : float
        The −x and +x edges (leading > trailing; the pair may straddle ±½).
    width : float
        leading − trailing, in wavelengths (2a/λ).
    load : float
        The part of p̃∞ the patch carries (the patches' loads add up to p̃∞).
    centroid : float
        x/λ of the pressure centroid over the patch (full contact: of the window centred on the
        pressure maximum, see the conventions).
    summit : float
        x/λ of the highest profile point inside the patch (0, the crest, for the sinusoid).
    ka, ke, ke_hat : float
        π·width, 2π(centre − summit) (None in full contact), 2π(centroid − summit).
    """

    trailing_edge: float
    leading_edge: float
    width: float
    load: float
    centroid: float
    summit: float
    ka: float
    ke: float | None
    ke_hat: float


def instantaneous_compliance(res) -> float:
    """J(0+) of a result's material in units of its reference compliance: the Prony series'
    ``j_plus`` (the BEM's ``material``), else 1/ratio of the standard linear solid, else 1."""
    material = getattr(res, "material", None)
    if getattr(material, "j_plus", None) is not None:
        return float(material.j_plus)
    ratio = getattr(res, "ratio", None)
    return 1.0 / float(ratio) if ratio else 1.0


def unit_slips(load, contact_fraction, j_plus, full_contact=False) -> dict:
    """The signs of a load in the wrong unit: ``{"strain": p̃∞ J(0+)}`` above LINEAR_LIMIT (the
    mean pressure over the instantaneous plane-strain modulus) and ``{"sliver": 2a/λ}`` for a
    partial contact below SLIVER; empty when neither."""
    out = {}
    if load is not None and math.isfinite(load) and load * j_plus > LINEAR_LIMIT:
        out["strain"] = load * j_plus
    if (not full_contact and contact_fraction is not None and math.isfinite(contact_fraction)
            and 0.0 <= contact_fraction < SLIVER):
        out["sliver"] = contact_fraction
    return out


def slip_warnings(load, contact_fraction, j_plus, full_contact=False) -> list:
    """`unit_slips` as the warnings of a dimensionless record (both line roads)."""
    found = unit_slips(load, contact_fraction, j_plus, full_contact)
    out = []
    if "strain" in found:
        out.append(f"p̃∞ = {load:.3g} is {found['strain']:.2g} × the instantaneous plane-strain "
                   f"modulus (p∞ > E∞/(1 − ν²); the limit {LINEAR_LIMIT:g}): far outside linear "
                   "theory; a mean pressure in Pa given without --units SI?")
    if "sliver" in found:
        out.append(f"p̃∞ = {load:.3g} leaves a vanishing sliver of contact (contact fraction "
                   f"{found['sliver']:.2g} < {SLIVER:g}): a load in the wrong unit (with --units "
                   "SI, MPa given as Pa?)")
    return out


def record(res, solver, *, inputs=None, error_estimate=None) -> dict:
    """The JSON record both roads' ``as_dict`` return (``allow_nan=False``-safe).

    ``res`` follows the result protocol (control, asked, load, speed, ratio, hk, ``scalars()``,
    separation, success, message, warnings, max_pressure, x_max_pressure, n_patches, patches,
    diagnostics); ``inputs`` are the road's own further inputs, recorded after hk.  The
    record's ``warnings`` add, to the result's own, a load that looks like a unit slip
    (`slip_warnings`: far above the modulus, or a vanishing sliver of contact).
    """
    from . import __version__
    rec = {"solver": solver, "version": __version__, "control": res.control,
           "load_asked": res.asked if res.control == "load" else None,
           "penetration_asked": res.asked if res.control == "penetration" else None,
           "load": res.load, "speed": res.speed, "ratio": res.ratio, "hk": res.hk}
    rec.update(inputs or {})
    rec.update(res.scalars())
    slips = (slip_warnings(res.load, res.contact_fraction, instantaneous_compliance(res),
                           res.full_contact) if res.success else [])
    rec.update({"separation": res.separation, "success": res.success,
                "message": res.message, "warnings": list(res.warnings) + slips})
    if res.success:
        rec.update({"max_pressure": res.max_pressure, "x_max_pressure": res.x_max_pressure,
                    "n_patches": res.n_patches,
                    "patches": [asdict(p) for p in res.patches]})
    else:
        rec.update({"max_pressure": None, "x_max_pressure": None, "n_patches": 0,
                    "patches": []})
    rec.update({"diagnostics": res.diagnostics, "error_estimate": error_estimate})
    return plain(rec)
