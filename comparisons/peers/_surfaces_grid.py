"""Third codes on rigid periodic surfaces: the inputs they accept (`ACCEPTED`, `DIRECTIONS`),
the project's grid and bi-sinusoid (`grid`, `bisinusoid`), and how a run's fields are measured
(`_measure`: μ, the lateral coefficient, the contact).  Part of `comparisons.peers.surfaces`,
which re-exports it.
"""
from __future__ import annotations

import math

import numpy as np

from viscosine.checks import bad, integer, real

from .. import operating_point as _op
from ..fields import count_patches

_TWO_PI = 2.0 * math.pi
#: E∞/E0, hk and the sliding direction where a caller names none: the operating point's
#: defaults (written once there)
RATIO, HK, DIRECTION = _op.DEFAULTS["ratio"], _op.DEFAULTS["hk"], _op.DEFAULTS["direction"]

#: name -> (low, high, what is allowed and why); bounds inclusive
ACCEPTED = {
    "load": (1e-8, 1e8, "a mean pressure p̃∞ = p∞(1 − ν²)/E0 in [1e-08, 1e+08]"),
    "speed": (1e-9, 1e9,
              "V/V0 = Vτk in [1e-09, 1e+09] (a transient code needs motion; beyond, every step "
              "is a relaxed or an instantaneous elastic solve to double precision)"),
    "ratio": (1.0, 1e4, "E∞/E0 > 1 and ≤ 1e+04 (1 is an elastic material: no Maxwell branch)"),
    "aspect": (1e-3, 1e3, "Ly/Lx in [0.001, 1000]"),
    "modulus": (1e-6, 1e6,
                "'relaxed' (E0), 'glassy' (E∞ = ratio·E0) or E*/(E0/(1 − ν²)) in [1e-06, 1e+06]"),
    "tolerance": (1e-15, 1e-4, "the solver's tolerance in [1e-15, 1e-4]"),
    "steady_rtol": (1e-12, 1e-1, "a steadiness tolerance (change per period) in [1e-12, 0.1]"),
    "max_periods": (2, 100000, "a whole number of periods in [2, 100000]"),
    "max_iterations": (10, 10 ** 7, "a whole number of iterations in [10, 10000000]"),
}

#: the directions of sliding supported (degrees): the surface must come back onto the grid after
#: a whole number of steps, which a motion along a grid axis does; direction -> (axis, sign)
DIRECTIONS = {0: (0, 1), 90: (1, 1), 180: (0, -1), 270: (1, -1)}

#: the scalars of a viscoelastic run that are extrapolated in the time step
STEP_KEYS = ("mu", "mu_lateral", "tau_f", "penetration", "contact_fraction", "max_pressure")


# ----------------------------------------------------------------------------- inputs
def _real(name, value):
    lo, hi, text = ACCEPTED[name]
    if name == "ratio":
        return real(name, value, text, lambda v: lo < v <= hi)
    return real(name, value, text, lambda v: lo <= v <= hi)


def _integer(name, value):
    lo, hi, text = ACCEPTED[name]
    return integer(name, value, text, lambda v: lo <= v <= hi)


def _heights(heights):
    """The heights k·z as a C-ordered float array of shape (nx, ny), and h_ref·k."""
    allowed = ("an array of shape (nx, ny), nx ≥ 4 and ny ≥ 1, of finite heights k·z (positive "
               "toward the body) at x/Lx = i/nx − ½, y/Lx = (j/ny − ½)·Ly/Lx, not all equal")
    try:
        z = np.array(heights, dtype=float, order="C")
    except (TypeError, ValueError):
        raise bad("heights", heights, allowed) from None
    if z.ndim != 2 or z.shape[0] < 4 or z.shape[1] < 1 or not np.all(np.isfinite(z)):
        raise bad("heights", heights, allowed)
    h_ref = float(np.max(z) - np.mean(z))
    if not h_ref > 0.0:
        raise bad("heights", heights, allowed)
    return z, h_ref


def _modulus(modulus, ratio):
    """E*/(E0/(1 − ν²)) of ``modulus`` ('relaxed', 'glassy' with ``ratio``, or a number)."""
    if isinstance(modulus, str):
        if modulus == "relaxed":
            return 1.0
        if modulus == "glassy":
            return _real("ratio", ratio)
        raise bad("modulus", modulus, ACCEPTED["modulus"][2])
    return _real("modulus", modulus)


def _direction(direction):
    """(θ in degrees in [0, 360), axis, sign) for a direction along a grid axis."""
    allowed = "0, 90, 180 or 270 degrees (modulo 360): a motion along a grid axis"
    d = real("direction", direction, allowed)
    key = round(d % 360.0, 9) % 360.0
    if key not in DIRECTIONS:
        raise bad("direction", direction, allowed)
    return float(key), *DIRECTIONS[int(key)]


def grid(shape, aspect=1.0):
    """The node positions of a grid: x/Lx = i/nx − ½ and y/Lx = (j/ny − ½)·aspect.

    Parameters
    ----------
    shape : tuple of int
        (nx, ny).
    aspect : float
        Ly/Lx.

    Returns
    -------
    x, y : ndarray
        1-D arrays of lengths nx and ny (units of Lx).
    """
    nx, ny = shape
    return np.arange(nx) / nx - 0.5, (np.arange(ny) / ny - 0.5) * aspect


def bisinusoid(nodes, hk=HK):
    """The bi-sinusoid k z = hk [cos kx + cos ky] on a square nodes × nodes grid.

    Its crest is at node (nodes/2, nodes/2) and h_ref = 2h.

    Parameters
    ----------
    nodes : int
        Nodes per side.
    hk : float
        h·k, the amplitude of each cosine.

    Returns
    -------
    ndarray
        Heights k·z, shape (nodes, nodes).
    """
    x, y = grid((nodes, nodes))
    return hk * (np.cos(_TWO_PI * x)[:, None] + np.cos(_TWO_PI * y)[None, :])


# ----------------------------------------------------------------------------- measuring
def _slope(u, axis, length):
    """∂u/∂(x or y) along ``axis`` by the spectral derivative (period ``length``), the Nyquist
    mode dropped (it has no derivative on the grid)."""
    n = u.shape[axis]
    q = _TWO_PI * np.fft.fftfreq(n, length / n)
    if n % 2 == 0:
        q[n // 2] = 0.0
    shape = [1, 1]
    shape[axis] = n
    return np.real(np.fft.ifft(1j * q.reshape(shape) * np.fft.fft(u, axis=axis), axis=axis))


def _measure(sigma, u, z, h_ref, aspect, direction=DIRECTION):
    """The scalars of one solution on the grid.

    ``sigma`` in E0/(1 − ν²); ``u``, ``z`` and ``h_ref`` in one length unit, that of Lx = 1
    (the slopes are ratios of lengths).  Friction along the direction θ (degrees).
    """
    load = float(np.mean(sigma))
    contact = sigma > 0.0
    out = {"load": load, "contact_fraction": float(np.mean(contact)),
           "full_contact": bool(contact.all()), "n_patches": count_patches(contact),
           "max_pressure": float(np.max(sigma))}
    s = float(np.mean(u) - np.mean(z))  # the mean gap, u − z − approach with Tamaas's u
    out.update(separation=s / h_ref, penetration=1.0 - s / h_ref)
    if direction is not None:
        th = math.radians(direction)
        c, sn = round(math.cos(th), 15), round(math.sin(th), 15)  # exact on the grid axes
        ux, uy = _slope(u, 0, 1.0), _slope(u, 1, aspect)
        along = sigma * (c * ux + sn * uy)
        tau_f = -float(np.mean(along))
        out.update(tau_f=tau_f, tau_abs=float(np.mean(np.abs(along))), mu=tau_f / load,
                   mu_lateral=float(np.mean(sigma * (c * uy - sn * ux))) / load)
    return out


def _fields(sigma, u, gap, h_ref, aspect):
    """The fields of the conventions: x, y, σ̃, (u − mean u)/h_ref and gap/h_ref (0 in contact,
    a node out of contact that penetrates by the solver's tolerance set to 0)."""
    x, y = grid(sigma.shape, aspect)
    g = np.where(sigma > 0.0, 0.0, np.maximum(gap, 0.0))
    return {"x": x, "y": y, "pressure": sigma, "displacement": (u - np.mean(u)) / h_ref,
            "gap": g / h_ref}


def _complementarity(sigma, gap, h_ref):
    """The largest |gap|/h_ref at a node in contact (0 without contact)."""
    contact = sigma > 0.0
    return float(np.max(np.abs(gap[contact]))) / h_ref if contact.any() else 0.0
