"""Full contact of the sinusoid in closed form (Appendix B, one harmonic), for any material, on
the half-space or on a layer; and the layer's mean displacement under the mean pressure."""
from __future__ import annotations

import math

import numpy as np

from viscosine.checks import real

from .._layer import check_layer, layer_factor, uniform_compliance
from ._material import material


def full_contact(speed, *, hk=1.0, load=None, layer=None, **material_kw):
    """Full contact of the sinusoid, for any material (Appendix B, one harmonic), on the
    half-space or on a layer.

    With v = y − s on the whole period, k v̂_1 = hk/2 and s = 0.  On a layer mode 1 of the
    operator is 2 S J*(1), S = S(k d, ν) the layer factor (`layer_factor`), so
    σ̂_1 = (hk/4) E*(1)/S (S = 1 on the half-space) and

        σ = p̃ + (hk/2)|E*(1)|/S cos(2πX + arg E*(1)),
        p̃FC = (hk/2)|E*(1)|/S                 (full contact iff p̃ ≥ p̃FC),
        τ̃f = 4 S Im J*(1) |σ̂_1|² = −(hk)²/(4S) Im E*(1)   (Im J* |E*|² = −Im E*),
        kê = −arg E*(1)                       (the pressure maximum leads the crest; S is
                                               real, so the phase is the half-space's).

    The dissipation of mode 1 carries one S (its displacement) and |σ̂_1|² two 1/S: a layer
    stiffens the contact and raises the friction stress by 1/S, μ = τ̃f/p̃ at a given p̃.  The
    mean displacement of the layer (its uniform mode, relaxed compliance J0 since the mean
    pressure is static) is k v̄_0 = C (k d) J0 p̃ (`uniform_compliance` of
    `analytic.references._layer`), and the approach of the crest from the undeformed top face
    is Δ/h + v̄_0/h = 1 + v̄_0/h.

    Parameters
    ----------
    speed : float
        w = V τ_ref k ≥ 0.
    hk : float
        Amplitude h k > 0.
    load : float, optional
        p̃ (E_ref/(1 − ν²)); with it, ``mu`` = τ̃f/p̃ and whether the contact is full.
    layer : mapping, optional
        ``{"thickness": k d > 0, "foundation": "bonded" | "frictionless", "nu": ν}`` (see
        `fourier_solve`); None (default) is the half-space.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    dict
        ``load_threshold`` p̃FC, ``modulus`` E*(1) of the material (complex), ``tau_f``,
        ``ke_hat``; with ``load``: ``full_contact`` (p̃ ≥ p̃FC) and ``mu``.  With a layer also
        ``layer_factor`` S(k d) and, with ``load``, ``mean_displacement`` v̄_0/h and
        ``approach`` 1 + v̄_0/h.

    References
    ----------
    Appendix B (eqs B1–B8) of the paper; the layer factor: Menga, Afferrante & Carbone (2016).
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    hk = real("hk", hk, "a finite amplitude hk > 0", lambda v: v > 0.0)
    mat = material(**material_kw)
    lay = check_layer(layer)
    e1 = complex(mat.estar(np.array([1.0]), w)[0])
    out = {"load_threshold": 0.5 * hk * abs(e1), "modulus": e1,
           "tau_f": -0.25 * hk * hk * e1.imag, "ke_hat": -math.atan2(e1.imag, e1.real)}
    if lay is not None:
        s1 = layer_factor(lay["thickness"], lay["nu"], lay["foundation"])
        out["layer_factor"] = s1
        out["load_threshold"] /= s1
        out["tau_f"] /= s1
    if load is not None:
        p = real("load", load, "a finite mean pressure > 0", lambda v: v > 0.0)
        out["full_contact"] = p >= out["load_threshold"]
        out["mu"] = out["tau_f"] / p
        if lay is not None:
            out["mean_displacement"] = _mean_displacement(lay, mat, p, hk)
            out["approach"] = 1.0 + out["mean_displacement"]
    return out


def _relaxed_compliance(mat):
    """J0 = J(t → ∞) (the creep form's base, or 1/E_r)."""
    return mat.base if mat.form == "creep" else 1.0 / mat.base


def _mean_displacement(lay, mat, p, hk):
    """v̄_0/h: k v̄_0 = C (k d) J0 p̃ over hk (C of `uniform_compliance`, relaxed J0)."""
    return uniform_compliance(lay["nu"], lay["foundation"]) * lay["thickness"] \
        * _relaxed_compliance(mat) * p / hk
