"""The surface reference's inputs: the accepted ranges, the creep series and its complex
compliance at the signed frequency q·ê, the grids asked for and the layer."""
from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np
from scipy.optimize import brentq

from viscosine.checks import bad, check_reals, is_integer, real, series

from .._layer import check_layer

_TWO_PI = 2.0 * math.pi

#: panels along x of the default grids (Richardson's extrapolation needs three)
NODES = (64, 128, 256)
#: the coarsest and the finest grid accepted, panels along x (the finest: 2048² points hold
#: ~10 arrays of 32 MiB in the iteration)
MIN_NODES, MAX_NODES = 8, 2048
#: default stopping tolerance of the iteration, relative to the peak pressure
TOL = 1e-10

ACCEPTED = {
    "load": (1e-12, 1e12, "a mean pressure p̃ = p∞(1 − ν²)/E0 in [1e-12, 1e12] (over the cell)"),
    "penetration": (0.0, 1.0, "a penetration Δ/h_ref in (0, 1] (1: the smallest load of full "
                    "contact)"),
    "speed": (0.0, 1e30, "a speed V/V0 = V τ k equal to 0 (the relaxed elastic solid) or in "
              "[1e-30, 1e30]"),
    "direction": (-360.0, 360.0, "a sliding direction θ in degrees from +x, in [−360, 360]"),
    "aspect": (1.0 / 64.0, 64.0, "a cell aspect Ly/Lx in [1/64, 64]"),
    "ratio": (1.0, 1e4, "E∞/E0 in [1, 1e4] (1 is the elastic solid)"),
    "tol": (1e-14, 1e-4, "a stopping tolerance in [1e-14, 1e-4] (relative to the peak "
            "pressure)"),
}
_TESTS = {"penetration": lambda v: 0.0 < v <= 1.0,
          "speed": lambda v: v == 0.0 or 1e-30 <= v <= 1e30}


def _material(ratio, material):
    """(J0, (J_i, ...), (τ_i, ...)) from at most one of ``ratio`` (default 3) and ``material``."""
    if material is None:
        r = 3.0 if ratio is None else check_reals(ACCEPTED, (("ratio", ratio),), {})["ratio"]
        return 1.0, (1.0 - 1.0 / r,), (1.0,)
    if ratio is not None:
        raise ValueError(f"ratio={ratio!r}, material={material!r} is not allowed: give at most "
                         "one of ratio and material")
    what = ("a creep series (J0, J, tau): J0 > 0, amplitudes J_i ≥ 0 and times tau_i > 0 of "
            "equal lengths, J(0+) = J0 − ΣJ_i > 0 (compliances in (1 − ν²)/E0, times in τ)")
    if isinstance(material, (str, bytes)) or not hasattr(material, "__len__") \
            or len(material) != 3:
        raise bad("material", material, what)
    j0, jj, tt = material
    j0 = real("material", j0, what, lambda v: v > 0.0)
    jj = series("material", jj, what, lambda v: v >= 0.0)
    tt = series("material", tt, what, lambda v: v > 0.0)
    if len(jj) != len(tt) or not j0 - math.fsum(jj) > 0.0:
        raise bad("material", material, what)
    return j0, jj, tt


def complex_compliance(n, speed, material):
    """J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i) at the signed frequency variable n = q·ê.

    Parameters
    ----------
    n : array_like
        q·ê, wave vector in k = 2π/Lx projected on the sliding direction.
    speed : float
        w = V τ k ≥ 0.
    material : (J0, J, tau)
        The creep series (compliances in (1 − ν²)/E0, times in τ).

    Returns
    -------
    ndarray of complex, in (1 − ν²)/E0.  Im J*(n) has the sign of n (the pressure leads).
    """
    j0, jj, tt = material
    n = np.asarray(n, dtype=float)
    out = np.full(n.shape, j0 - math.fsum(jj), dtype=complex)
    for a, t in zip(jj, tt):
        out += a / (1.0 - 1j * (n * (speed * t)))
    return out


def _check_nodes(nodes, surf):
    """The grids (panels along x), increasing; a single N gives N/4, N/2, N."""
    allowed = (f"an even number of panels along x in [{MIN_NODES}, {MAX_NODES}], or an "
               "increasing sequence of them (three or more for Richardson's extrapolation); "
               "one N solves N/4, N/2 and N")
    if nodes is None:
        if surf.kind == "array":
            nx0 = surf.values.shape[0]
            if nx0 > MAX_NODES:
                raise bad("heights", surf.values.shape, f"an array of at most {MAX_NODES} "
                          "points along x")
            seq = [nx0 * f for f in (1, 2, 4) if nx0 * f <= MAX_NODES]
        else:
            seq = list(NODES)
    elif is_integer(nodes):
        n = int(nodes)
        if not (MIN_NODES <= n <= MAX_NODES and n % 2 == 0):
            raise bad("nodes", nodes, allowed)
        seq = [n // 4, n // 2, n] if n % 8 == 0 and n // 4 >= MIN_NODES else [n]
        if surf.kind == "array":
            seq = [v for v in seq if v % surf.values.shape[0] == 0] or [n]
    else:
        if isinstance(nodes, (str, bytes)):
            raise bad("nodes", nodes, allowed)
        try:
            seq = list(nodes)
        except TypeError:
            raise bad("nodes", nodes, allowed) from None
        if not seq or not all(is_integer(v) and MIN_NODES <= v <= MAX_NODES and v % 2 == 0
                              for v in seq) \
                or any(b <= a for a, b in zip(seq[:-1], seq[1:])):
            raise bad("nodes", nodes, allowed)
        seq = [int(v) for v in seq]
    surf.check_nodes(seq)
    for n in seq:
        nx, ny = surf.grid_for(n)
        if nx * ny > MAX_NODES ** 2:
            raise bad("nodes", nodes if nodes is not None else seq,
                      f"grids of at most {MAX_NODES}² points (nx = {nx} gives ny = {ny} for "
                      f"this cell)")
    return tuple(seq)


#: the keys of the ``layer`` mapping: one of the two thicknesses, the foundation and ν
LAYER_KEYS = ("thickness", "thickness_over_wavelength", "foundation", "nu")


def _check_layer(layer):
    """The ``layer`` argument as ``{"thickness": k d, "foundation", "nu"}`` (None: the half-space).

    A mapping with ``"foundation"``, ``"nu"`` and exactly one of ``"thickness"`` (k d, k =
    2π/Lx) and ``"thickness_over_wavelength"`` (d/Lx); the entries are checked by
    `check_layer` of `analytic.references._layer` (shared with the Fourier reference), the first
    bad one refused by name (``layer['nu']=…``).
    """
    if layer is None:
        return None
    what = ("None (the half-space) or a mapping {'thickness': k d > 0 (k = 2π/Lx) or "
            "'thickness_over_wavelength': d/Lx > 0, 'foundation': 'bonded' or 'frictionless', "
            "'nu': a Poisson ratio in (-1, 0.5]}")
    if not isinstance(layer, Mapping):
        raise bad("layer", layer, what)
    keys = set(layer)
    given = [k for k in ("thickness", "thickness_over_wavelength") if k in keys]
    missing = [k for k in ("foundation", "nu") if k not in keys]
    extra = sorted(map(repr, keys - set(LAYER_KEYS)))
    if len(given) != 1 or missing or extra:
        why = "; ".join(x for x in (
            "neither thickness nor thickness_over_wavelength" if not given else
            "both thickness and thickness_over_wavelength" if len(given) == 2 else "",
            f"missing {', '.join(missing)}" if missing else "",
            f"unknown {', '.join(extra)}" if extra else "") if x)
        raise bad("layer", dict(layer), "a mapping with the keys foundation, nu and one of "
                  f"thickness (k d) and thickness_over_wavelength (d/Lx) ({why})")
    if given[0] == "thickness":
        kd = layer["thickness"]
    else:
        dl = real("layer['thickness_over_wavelength']", layer["thickness_over_wavelength"],
                  "a finite thickness d/Lx > 0 (layer=None for the half-space)",
                  lambda v: v > 0.0 and math.isfinite(_TWO_PI * v), kind=True)
        kd = _TWO_PI * dl
    try:
        return check_layer({"thickness": kd, "foundation": layer["foundation"],
                            "nu": layer["nu"]})
    except ValueError as exc:
        if given[0] == "thickness":
            raise
        # the thickness was given over Lx: name it so
        raise ValueError(str(exc).replace(
            f"layer['thickness']={kd!r}",
            f"layer['thickness_over_wavelength']={layer['thickness_over_wavelength']!r} "
            f"(k d = {kd!r})")) from None


def _shortest_relaxation(material):
    """The shortest relaxation time of the creep series (0 for an elastic solid).

    The relaxation times are −1/s at the zeros of J(0+) + Σ J_i/(1 + s τ_i); the shortest is
    the zero left of the leftmost pole −1/τ_min (the sum falls from J(0+) at −∞ to −∞ there).
    """
    j0, jj, tt = material
    terms = [(a, t) for a, t in zip(jj, tt) if a > 0.0]
    if not terms:
        return 0.0
    jplus = j0 - math.fsum(jj)
    f = lambda s: jplus + math.fsum(a / (1.0 + s * t) for a, t in terms)
    pole = -1.0 / min(t for _, t in terms)
    hi = pole * (1.0 + 1e-12)
    while f(hi) >= 0.0 and hi != pole:          # a hair left of the pole, where f < 0
        hi = pole + 0.5 * (hi - pole)
    lo = 2.0 * pole
    while f(lo) <= 0.0:
        lo *= 2.0
    return -1.0 / brentq(f, lo, hi, xtol=1e-300, rtol=1e-14)
