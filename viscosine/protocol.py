"""The result protocol both roads (and the peers) share: the scalar keys, the JSON helper and the
contact patch.  No numerics here.

Keys, units and signs as in ``docs/conventions.md`` ('Outputs: the scalars of one operating
point'); positions x/λ in the crest frame.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass

import numpy as np

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


def record(res, solver, *, inputs=None, error_estimate=None) -> dict:
    """The JSON record both roads' ``as_dict`` return (``allow_nan=False``-safe).

    ``res`` follows the result protocol (control, asked, load, speed, ratio, hk, ``scalars()``,
    separation, success, message, warnings, max_pressure, x_max_pressure, n_patches, patches,
    diagnostics); ``inputs`` are the road's own further inputs, recorded after hk.
    """
    from . import __version__
    rec = {"solver": solver, "version": __version__, "control": res.control,
           "load_asked": res.asked if res.control == "load" else None,
           "penetration_asked": res.asked if res.control == "penetration" else None,
           "load": res.load, "speed": res.speed, "ratio": res.ratio, "hk": res.hk}
    rec.update(inputs or {})
    rec.update(res.scalars())
    rec.update({"separation": res.separation, "success": res.success,
                "message": res.message, "warnings": list(res.warnings)})
    if res.success:
        rec.update({"max_pressure": res.max_pressure, "x_max_pressure": res.x_max_pressure,
                    "n_patches": res.n_patches,
                    "patches": [asdict(p) for p in res.patches]})
    else:
        rec.update({"max_pressure": None, "x_max_pressure": None, "n_patches": 0,
                    "patches": []})
    rec.update({"diagnostics": res.diagnostics, "error_estimate": error_estimate})
    return plain(rec)
