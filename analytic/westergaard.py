"""Westergaard's elastic solution for the periodic sinusoid: the first oracle.

Elastic half-space of plane-strain modulus m·E0/(1 − ν²) pressed by h cos(kx) (crest at x = 0)
with mean pressure p∞; m = 1 is the low-speed limit (E0), m = E∞/E0 the high-speed limit (E∞).
Units as in `analytic/__init__.py`: p̃ = p∞(1 − ν²)/E0, lengths in 1/k or over h.

    p̃* = m hk/2                       (full-contact load),
    sin²(ka/2) = p̃∞/p̃*                (contact half-width),
    σ(x)/p∞ = 2 cos(kx/2) sqrt(sin²(ka/2) − sin²(kx/2)) / sin²(ka/2),  |x| < a,
    Δ/h = (p̃∞/p̃*)(1 − ln(p̃∞/p̃*))     (penetration; s = h − Δ the mean separation),
    gap/h = 2[sin(kx/2) sqrt(sin²(kx/2) − sin²(ka/2)) − sin²(ka/2) arccosh(sin(kx/2)/sin(ka/2))]
            for a < |x| ≤ λ/2.

References: H. M. Westergaard, Bearing pressures and cracks, J. Appl. Mech. 6, A49–A53 (1939);
K. L. Johnson, J. A. Greenwood and J. G. Higginson, The contact of elastic regular wavy surfaces,
Int. J. Mech. Sci. 27, 383–396 (1985); the symmetric part of Appendix A, eqs (A8), (A9), (A11), of
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014.
"""
from __future__ import annotations

import math

import numpy as np


def full_contact_load(hk, modulus=1.0):
    """p̃*: the smallest load that gives full contact."""
    return 0.5 * modulus * hk


def half_angle(load, hk, modulus=1.0):
    """ka (π in full contact)."""
    s = load / full_contact_load(hk, modulus)
    return math.pi if s >= 1.0 else 2.0 * math.asin(math.sqrt(s))


def penetration(load, hk, modulus=1.0):
    """Δ/h."""
    s = load / full_contact_load(hk, modulus)
    return 1.0 if s >= 1.0 else s * (1.0 - math.log(s))


def pressure(x_over_lambda, load, hk, modulus=1.0):
    """σ(1 − ν²)/E0 at x/λ (crest frame)."""
    s = load / full_contact_load(hk, modulus)
    th = 2.0 * np.pi * np.asarray(x_over_lambda, dtype=float)
    if s >= 1.0:
        return load + full_contact_load(hk, modulus) * np.cos(th)
    inside = np.sin(0.5 * th) ** 2 < s
    root = np.sqrt(np.where(inside, s - np.sin(0.5 * th) ** 2, 0.0))
    return np.where(inside, 2.0 * load / s * np.abs(np.cos(0.5 * th)) * root, 0.0)


def gap(x_over_lambda, load, hk, modulus=1.0):
    """gap/h at x/λ (0 in the contact)."""
    s = load / full_contact_load(hk, modulus)
    th = 2.0 * np.pi * np.asarray(x_over_lambda, dtype=float)
    if s >= 1.0:
        return np.zeros_like(th)
    s2 = np.abs(np.sin(0.5 * th))
    outside = s2 * s2 > s
    sa = math.sqrt(s)
    x = np.where(outside, s2 / sa, 1.0)
    g = 2.0 * s * (x * np.sqrt(x * x - 1.0) - np.arccosh(x))
    return np.where(outside, g, 0.0)


def displacement(x_over_lambda, load, hk, modulus=1.0):
    """v/h from the mean line of the deformed surface: cos(kx) − s/h + gap/h."""
    X = np.asarray(x_over_lambda, dtype=float)
    return np.cos(2.0 * np.pi * X) - (1.0 - penetration(load, hk, modulus)) + gap(X, load, hk, modulus)
