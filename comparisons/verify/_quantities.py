"""What verify compares, and how each difference is measured.

Each quantity is compared with the reference: relative difference for μ, τf, Δ/h, s/h, the load
and the contact fraction; absolute for ka, ke, kê (radians) and the contact edges (x/λ); field
norms over the user's grid (L2 by its quadrature): ``pressure_L2``, ``pressure_Linf`` (of
σ − σ_ref, over max |σ_ref|) and ``displacement_L2``, ``displacement_Linf``, ``gap_Linf`` (of v/h,
gap/h).
"""
from __future__ import annotations

import numpy as np

from viscosine.protocol import SCALAR_KEYS

from ..fields import as_grid, wrap

#: the scalars verify compares: the numbers among the protocol's scalars
#: (`viscosine.protocol.SCALAR_KEYS`, all but the flag full_contact) and the controls
#: separation and load; relatively (REL) or in absolute terms (ABS: positions, in radians)
REL = ("mu", "tau_f", "penetration", "separation", "load", "contact_fraction")
ABS = ("ka", "ke", "ke_hat")
COMPARED_KEYS = REL + ABS
assert set(COMPARED_KEYS) == (set(SCALAR_KEYS) - {"full_contact"}) | {"separation", "load"}
NORM_KEYS = ("pressure_L2", "pressure_Linf", "displacement_L2", "displacement_Linf", "gap_Linf",
             "edges")
ALL_KEYS = COMPARED_KEYS + NORM_KEYS
LABELS = {"mu": "μ", "tau_f": "τ̃f", "penetration": "Δ/h", "separation": "s/h",
          "load": "p̃∞", "contact_fraction": "2a/λ", "ka": "ka", "ke": "ke", "ke_hat": "kê",
          "pressure_L2": "σ L2 / max σ", "pressure_Linf": "σ L∞ / max σ",
          "displacement_L2": "v L2 / h", "displacement_Linf": "v L∞ / h",
          "gap_Linf": "gap L∞ / h", "edges": "contact edges (x/λ)"}


def measure(key, value, ref):
    """The difference of ``value`` from ``ref`` in the verdict's measure (relative for REL,
    absolute where ``ref`` is 0 and for the rest); None without both."""
    if value is None or ref is None:
        return None
    if key in REL:
        return abs(value - ref) / abs(ref) if ref != 0.0 else abs(value - ref)
    return abs(value - ref)


def edge_differences(ref_patches, patches):
    """(trailing, leading) edge differences (x/λ) of each reference patch from the patch whose
    centre is nearest it (modulo one period); None when the patch counts differ."""
    if len(ref_patches) != len(patches):
        return None
    diffs = []
    for r in ref_patches:
        best = min(patches, key=lambda q: abs(wrap(
            0.5 * (q["trailing_edge"] + q["leading_edge"])
            - 0.5 * (r["trailing_edge"] + r["leading_edge"]))))
        shift = round(0.5 * (r["trailing_edge"] + r["leading_edge"])
                      - 0.5 * (best["trailing_edge"] + best["leading_edge"]))
        diffs.append((best["trailing_edge"] + shift - r["trailing_edge"],
                      best["leading_edge"] + shift - r["leading_edge"]))
    return diffs


def norms(result, reference):
    """Field norms of a `Result` against a `Reference` on the result's grid (with the
    reference's uncertainty in the same norms), and the reference fields there."""
    if result.fields is None:
        return {}, {}, None
    f = result.fields
    grid = as_grid(f)  # the norms weigh each point by its cell
    ref, unc = reference.fields(f["x_over_lambda"])
    pm = float(np.max(np.abs(ref["pressure"])))
    out, out_unc = {}, {}
    dp = f["pressure"] - ref["pressure"]
    out["pressure_L2"] = grid.l2(dp) / pm
    out["pressure_Linf"] = grid.linf(dp) / pm
    out_unc["pressure_L2"] = grid.l2(unc["pressure"]) / pm
    out_unc["pressure_Linf"] = grid.linf(unc["pressure"]) / pm
    if "displacement" in f:
        dv = f["displacement"] - ref["displacement"]
        out["displacement_L2"] = grid.l2(dv)
        out["displacement_Linf"] = grid.linf(dv)
        out_unc["displacement_L2"] = grid.l2(unc["displacement"])
        out_unc["displacement_Linf"] = grid.linf(unc["displacement"])
    if "gap" in f:
        out["gap_Linf"] = grid.linf(f["gap"] - ref["gap"])
        out_unc["gap_Linf"] = grid.linf(unc["gap"])
    return out, out_unc, ref

