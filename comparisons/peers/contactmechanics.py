"""ContactMechanics as a third code for the elastic layer: its layer operator and contact solver.

ContactMechanics (Pastewka group, https://github.com/ContactEngineering/ContactMechanics; with
muGrid, SurfaceTopography and NuMPI) solves the normal contact of a rigid periodic surface with
an elastic substrate by a Polonsky–Keer constrained conjugate-gradient method on an FFT Green's
function.  Its ``PeriodicFFTElasticHalfSpace(..., thickness=d, poisson=ν)`` is an elastic layer
of thickness d on a rigid flat.  Nobody on this project wrote it: it checks the layer of
`bem` (``bem.Layer``, ``docs/layers.md``) in the elastic limit, where the BEM's operator is the
relaxed solid's (``speed=0``).

What ContactMechanics computes (version 1.8.3, measured here and written where it bites)
-----------------------------------------------------------------------------------------
* The layer is BONDED to its foundation: on a 2-D grid the stiffness of a mode along x is the
  half-space's, π E* |q| (q = 1/wavelength), divided by S_B(|k| d, ν) of ``docs/layers.md`` §1
  (measured to 1.1e-15 relative for ν = 0, 0.3, 0.45, k d = 0.01 … 30, every mode of N = 256;
  S_F differs from it by up to 67 %).  Its uniform mode is the bonded layer's uniaxial strain,
  stiffness E(1 − ν)/((1 + ν)(1 − 2ν) d), i.e. C = (1 − 2ν)/(1 − ν)² of ``docs/layers.md`` §4
  (to 3.3e-16).
* On a 1-D grid ``thickness`` is IGNORED (the 1-D Green's function is the half-plane's whatever
  the thickness).  So the problem is put on an N × 1 grid with the profile independent of y:
  only modes along x are loaded, and the problem is the plane-strain one of viscosine.
* At ν = ½ exactly, with a Python float, building the layer raises ZeroDivisionError (its
  uniform stiffness is E(1 − ν)/((1 + ν)(1 − 2ν) d), infinite there).  Given as a NumPy float,
  the division gives inf with a warning and the uniform compliance 0, which is the bonded
  incompressible layer's (C = 0); that is what this adapter passes (the warning silenced).  The
  modes n ≠ 0 of its hyperbolic form lose accuracy as the layer thins at ν = ½ (measured
  4e-13 relative at k d = 0.01, 2e-14 at 0.05, 1.3e-15 at 0.3).
* The half-space (``thickness=None``) on an N × 1 grid fails in ContactMechanics's default
  uniform stiffness (it reads the mode (0, 1) that a one-row grid lacks); its uniform stiffness
  is given here as ``stiffness_q0`` = the stiffness of mode 1.  It only moves the mean of the
  displacement, which the conventions remove.
* Pressures are point values at the grid nodes (the Green's function is the continuum's symbol
  on modes |n| ≤ N/2, no aliasing): a collocation of the pressure, where `bem` has panels of
  constant pressure integrated exactly.  The two converge to the same continuum problem; their
  differences are measured in ``tests/validation/test_peer_contactmechanics.py``.
* Its displacement u is positive into the body, its forces negative in compression, and its
  constraint is gap = u − (height + offset) ≥ 0: ``heights`` is the indenter's protrusion into
  the body (crest = largest value), ``offset`` the rigid approach.  Under load control
  (``external_force``) the offset is an output.

Units (the project's, docs/conventions.md)
------------------------------------------
Lengths in 1/k (k = 2π/λ): ContactMechanics's period is 2π.  Pressures in the plane-strain
modulus E/(1 − ν²): ContactMechanics's ``young`` is 1 − ν², so that its contact modulus E* =
young/(1 − ν²) is 1 and its pressure (force per node / area per node) is p̃ = p(1 − ν²)/E
itself; against `bem` with ``speed=0`` (the relaxed solid), E = E0 and p̃ is the project's
p̃∞ = p∞(1 − ν²)/E0.  Heights are k y.  Node j of the grid is at x/λ = j/N − ½ (the crest of the
sinusoid on node N/2), the panel centres of `bem`.

Outputs follow the conventions: σ̃ positive in compression, v/h into the body from the mean line
of the deformed surface, gap/h, s/h the mean gap, Δ/h = 1 − s/h; on a layer the uniform
compression v̄₀/h (``mean_displacement``) and the crest's ``approach`` = Δ/h + v̄₀/h from the
undeformed top face (``docs/layers.md`` §7).

References
----------
Polonsky & Keer, Wear 231, 206 (1999) (the solver); Carbone & Mangialardi, JMPS 56, 684 (2008),
eq. (A.30) (ContactMechanics's layer); docs/layers.md (S_B, S_F, C).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

import viscosine
from viscosine import Fields
from viscosine.checks import bad, integer, real

from .. import operating_point as _op
from .._errors import MissingPackage
from ..fields import true_runs

#: hk where a caller names none: the operating point's default (written once there)
HK = _op.DEFAULTS["hk"]

#: the ContactMechanics release this adapter was verified on (the ``peers`` extra pins it, and
#: muGrid, SurfaceTopography and NuMPI, to releases with CPython 3.11 wheels)
CONTACTMECHANICS_REQUIREMENT = "ContactMechanics==1.8.3"
_INSTALL = "pip install 'viscosine[peers]' (from a clone of the repository: pip install '.[peers]')"

_TWO_PI = 2.0 * math.pi
_PERIOD = _TWO_PI  # ContactMechanics's period: lengths in 1/k

#: name -> (low, high, what is allowed and why); bounds inclusive
ACCEPTED = {
    "load": (1e-8, 1e8, "a mean pressure p̃ = p(1 − ν²)/E in [1e-08, 1e+08]"),
    "hk": (1e-6, 1e6, "hk in [1e-06, 1e+06] (the problem is linear: hk scales pressures)"),
    "thickness": (1e-3, 1e6,
                  "k d in [0.001, 1e+06], or None for the half-space (at ν = ½ ContactMechanics's "
                  "hyperbolic form of S is 1.6e-10 off at k d = 0.001, and worse as (k d)^-2 "
                  "below)"),
    "nu": (-1.0, 0.5, "a Poisson ratio ν in (−1, 0.5]"),
    "nodes": (16, 2 ** 20, "an even number of grid nodes N per period in [16, 1048576]"),
    "tolerance": (1e-15, 1e-4,
                  "the solver's tolerance in [1e-15, 1e-4] (penetration over hk, force outside "
                  "the contact over the load, relative change of the offset)"),
    "max_iterations": (10, 10 ** 7, "a whole number of iterations in [10, 10000000]"),
}


def validate(*, load=None, hk=None, thickness=None, nu=None, nodes=None, tolerance=None,
             max_iterations=None):
    """Check the inputs of `solve` and `compliance` (those given; ``thickness=None`` is the
    half-space); return them as plain numbers.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: what is allowed"`` for the first bad input.
    """
    out = {}
    for name, value in (("load", load), ("hk", hk), ("thickness", thickness),
                        ("tolerance", tolerance)):
        if value is not None:
            lo, hi, text = ACCEPTED[name]
            out[name] = real(name, value, text, lambda v, lo=lo, hi=hi: lo <= v <= hi)
    if nu is not None:
        lo, hi, text = ACCEPTED["nu"]
        out["nu"] = real("nu", nu, text, lambda v: lo < v <= hi)
    if nodes is not None:
        lo, hi, text = ACCEPTED["nodes"]
        out["nodes"] = integer("nodes", nodes, text, lambda v: lo <= v <= hi and not v % 2)
    if max_iterations is not None:
        lo, hi, text = ACCEPTED["max_iterations"]
        out["max_iterations"] = integer("max_iterations", max_iterations, text,
                                        lambda v: lo <= v <= hi)
    return out


def _import_contactmechanics():
    """(PeriodicFFTElasticHalfSpace, make_system, Topography, version), or MissingPackage."""
    try:
        from ContactMechanics import PeriodicFFTElasticHalfSpace, make_system
        from SurfaceTopography import Topography
    except ImportError as exc:
        raise MissingPackage(f"the ContactMechanics peer needs {CONTACTMECHANICS_REQUIREMENT}; "
                             f"install it with: {_INSTALL}") from exc
    # the installed distribution's version: ContactMechanics.__version__ is discovered from git
    # and, installed in a virtual environment inside another git checkout (as the README's
    # commands do), is that checkout's commit
    from importlib.metadata import version
    return PeriodicFFTElasticHalfSpace, make_system, Topography, version("ContactMechanics")


def _substrate(cls, nodes, thickness, nu):
    """ContactMechanics's substrate in the project's units: an N × 1 grid of period 2π (lengths
    in 1/k), E* = young/(1 − ν²) = 1, a bonded layer of thickness k d (None: the half-space,
    its uniform stiffness that of mode 1)."""
    young = 1.0 - nu * nu
    if thickness is None:
        return cls((nodes, 1), young, physical_sizes=(_PERIOD, _PERIOD), poisson=nu,
                   stiffness_q0=math.pi / _PERIOD)  # π E* q of mode 1: only the mean of u
    # a NumPy ν: at ν = ½ its uniform stiffness is then inf (compliance 0) instead of a
    # ZeroDivisionError; silenced, as that is the bonded incompressible layer's answer
    with np.errstate(divide="ignore"):
        return cls((nodes, 1), young, physical_sizes=(_PERIOD, _PERIOD), thickness=thickness,
                   poisson=np.float64(nu))


# ----------------------------------------------------------------------------- compliance
@dataclass(frozen=True)
class Compliance:
    """ContactMechanics's surface compliance of the modes along x (units of the project).

    Attributes
    ----------
    modes : ndarray
        n = 0 … N/2 (k_n = n k).
    compliance : ndarray
        k v̂_n / p̃̂_n: the displacement (in 1/k) of mode n per unit pressure p̃ = p(1 − ν²)/E.
        The half-space's is 2/|n|; mode 0 is the layer's uniform compression C·k d (NaN on the
        half-space, whose uniform mode is unbounded).
    factor : ndarray
        S_n = compliance·|n|/2, ContactMechanics's layer factor (mode 0: NaN).
    uniform : float
        C = compliance[0]/(k d), the uniform compliance in (1 − ν²)/E per unit thickness
        (NaN on the half-space).
    thickness, nu, nodes, version
        The input and ContactMechanics's version.
    """

    modes: np.ndarray
    compliance: np.ndarray
    factor: np.ndarray
    uniform: float
    thickness: float | None
    nu: float
    nodes: int
    version: str


def compliance(*, thickness=None, nu=0.0, nodes=256):
    """ContactMechanics's surface compliance of the modes along x of an N × 1 grid.

    Parameters
    ----------
    thickness : float, optional
        k d of the layer (bonded: ContactMechanics's only layer); None, the half-space.
    nu : float
        Poisson ratio in (−1, ½].
    nodes : int
        N (even): modes 0 … N/2.

    Returns
    -------
    Compliance

    Raises
    ------
    ValueError
        Bad input (``"name=value is not allowed: ..."``).
    MissingPackage
        ContactMechanics is not installed (the message says ``pip install 'viscosine[peers]'``).
    """
    v = validate(nu=nu, nodes=nodes, **({} if thickness is None else {"thickness": thickness}))
    cls, _, _, version = _import_contactmechanics()
    n = v["nodes"]
    sub = _substrate(cls, n, v.get("thickness"), v["nu"])
    # u^ = G p^ with G = 1/(π E* q), q = |n|/period: k v^/p̃^ = G (k = 1, E* = 1)
    g = np.array(sub.greens_function, dtype=float)[:, 0] * float(sub.contact_modulus)
    modes = np.arange(n // 2 + 1)
    factor = np.full(modes.shape, math.nan)
    factor[1:] = 0.5 * g[1:] * modes[1:]
    kd = v.get("thickness")
    uniform = math.nan if kd is None else float(g[0]) / kd
    if kd is None:
        g[0] = math.nan
    return Compliance(modes, g, factor, uniform, kd, v["nu"], n, version)


# ----------------------------------------------------------------------------- contact
@dataclass(frozen=True)
class ContactMechanicsResult:
    """The elastic frictionless contact of a periodic profile, by ContactMechanics.

    Attributes
    ----------
    success, message
        Whether ContactMechanics's solver converged, and what it says.
    nit
        Its iterations.
    load
        Achieved p̃ (the mean of σ̃ over the grid); ``load_asked`` the input.
    hk, thickness, nu, nodes
        The input (thickness k d, None for the half-space).
    full_contact, contact_fraction, contact_nodes
        Every node in contact; the contact width over λ, its edges placed between the last
        node in contact and the first out of it by extrapolating gap^(2/3) (linear in the
        distance just outside an edge, where the gap grows like distance^(3/2)) from the two
        nearest nodes out of contact; the fraction of nodes in contact (that width to ±1/N).
    penetration, separation
        Δ/h and s/h = 1 − Δ/h (s the mean gap: from the mean line of the deformed surface).
    mean_displacement, approach
        Layer only (None on the half-space): the uniform compression v̄₀/h and the crest's
        approach Δ/h + v̄₀/h from the undeformed top face.
    max_pressure, x_max_pressure, n_patches
        The largest nodal σ̃ and its x/λ; the contact patches.
    diagnostics
        iterations, offset (ContactMechanics's rigid approach, in 1/k), complementarity (largest
        gap/h at a node in contact), load_error (|mean σ̃ − p̃|/p̃), tolerance, wall_time (s),
        contactmechanics_version.
    """

    success: bool
    message: str
    nit: int
    load: float
    load_asked: float
    hk: float
    thickness: float | None
    nu: float
    nodes: int
    full_contact: bool
    contact_fraction: float
    contact_nodes: float
    penetration: float
    separation: float
    mean_displacement: float | None
    approach: float | None
    max_pressure: float
    x_max_pressure: float
    n_patches: int
    diagnostics: dict
    _fields: Fields | None = field(default=None, repr=False, compare=False)

    def fields(self):
        """σ(1 − ν²)/E, v/h (into the body, from the deformed mean line) and gap/h on the grid
        x/λ = j/N − ½ (a `viscosine.Fields`)."""
        if self._fields is None:
            raise RuntimeError(f"no fields: the solve failed ({self.message})")
        return self._fields


def _edge_cells(g1, g2):
    """How far beyond the last node in contact its edge lies, in cells (0 to 1), from the gaps
    g1, g2 at the first and second nodes out of contact: gap^(2/3) is linear in the distance
    just outside an edge, and is extrapolated to zero.  ½ when that is not possible."""
    if g2 is None or not g2 > g1 > 0.0:
        return 0.5
    a, b = g1 ** (2.0 / 3.0), g2 ** (2.0 / 3.0)
    return min(max(1.0 - a / (b - a), 0.0), 1.0)


def _widths(contact, gap):
    """The widths (over λ) of the contact patches: runs of nodes in contact, each extended at
    both ends by `_edge_cells`."""
    n = contact.size
    runs = true_runs(contact)
    if len(runs) == 1 and runs[0][1] == n:
        return [1.0]

    def out(i):
        i %= n
        return None if contact[i] else float(gap[i])

    widths = []
    for first, length in runs:
        left = _edge_cells(out(first - 1), out(first - 2))
        right = _edge_cells(out(first + length), out(first + length + 1))
        widths.append((length - 1 + left + right) / n)
    return widths


def _heights(profile, hk, nodes):
    """(k y at x/λ = j/N − ½ minus its mean, h k): the sinusoid hk cos(2πx/λ), or ``profile``,
    an object with ``sample(N)`` and ``amplitude`` (a `bem` profile) or N heights k y."""
    if profile is None:
        return hk * np.cos(_TWO_PI * (np.arange(nodes) / nodes - 0.5)), hk
    if hasattr(profile, "sample"):
        y = np.asarray(profile.sample(nodes), dtype=float)
        return y - np.mean(y), float(profile.amplitude)
    y = np.asarray(profile, dtype=float)
    if y.shape != (nodes,) or not np.all(np.isfinite(y)) or np.ptp(y) == 0.0:
        raise bad("profile", profile, f"N = {nodes} finite heights k y at x/λ = j/N − ½, not "
                  "all equal (or an object with sample(N) and amplitude, e.g. bem.Sinusoid)")
    y = y - np.mean(y)
    return y, float(np.max(y))


def solve(*, load, hk=HK, thickness=None, nu=0.0, nodes=256, profile=None, tolerance=1e-12,
          max_iterations=100000):
    """The elastic frictionless contact of a periodic profile on a bonded layer (or the
    half-space), by ContactMechanics's Polonsky–Keer solver under load control.

    Parameters
    ----------
    load : float
        Mean pressure p̃ = p(1 − ν²)/E (E the relaxed modulus E0 against `bem` at ``speed=0``).
    hk : float
        Amplitude of the sinusoid hk cos(2πx/λ) (not with ``profile``).
    thickness : float, optional
        k d of the bonded layer; None, the half-space.
    nu : float
        Poisson ratio in (−1, ½] (on the half-space only a unit: it drops out).
    nodes : int
        Grid nodes N per period (even), at x/λ = j/N − ½.
    profile : optional
        Instead of the sinusoid: an object with ``sample(N)`` (k y at x/λ = j/N − ½) and
        ``amplitude`` (h k = max − mean), such as ``bem.Harmonics``, or the N heights k y.
    tolerance : float
        ContactMechanics's tolerances: penetration ``pentol`` = tolerance·hk (in 1/k), force
        outside the contact ``forcetol`` = tolerance·p̃·(area per node), and the relative
        changes ``thermotol`` = tolerance.
    max_iterations : int
        Its iteration cap.

    Returns
    -------
    ContactMechanicsResult

    Raises
    ------
    ValueError
        Bad input (``"name=value is not allowed: ..."``).
    MissingPackage
        ContactMechanics is not installed (the message says ``pip install 'viscosine[peers]'``).
    """
    if profile is not None and hk != HK:
        raise bad("hk", hk, f"{HK!r} (the default) with a profile: its amplitude is the profile's")
    v = validate(load=load, hk=hk, nu=nu, nodes=nodes, tolerance=tolerance,
                 max_iterations=max_iterations,
                 **({} if thickness is None else {"thickness": thickness}))
    n, p_asked, kd = v["nodes"], v["load"], v.get("thickness")
    y, h = _heights(profile, v["hk"], n)
    cls, make_system, topography_cls, version = _import_contactmechanics()
    start = time.perf_counter()
    sub = _substrate(cls, n, kd, v["nu"])
    topo = topography_cls(y[:, None], physical_sizes=(_PERIOD, _PERIOD), periodic=True)
    system = make_system(substrate=sub, surface=topo)
    area = float(sub.area_per_pt)
    tol = v["tolerance"]
    res = system.minimize_proxy(external_force=p_asked * _PERIOD * _PERIOD, pentol=tol * h,
                                forcetol=tol * p_asked * area, thermotol=tol,
                                maxiter=v["max_iterations"])
    wall = time.perf_counter() - start
    sigma = np.asarray(res.jac, dtype=float)[:, 0] / area   # p̃ at the nodes, compression > 0
    u = np.asarray(res.x, dtype=float)[:, 0]                # into the body, in 1/k
    offset = float(res.offset)
    gap = u - y - offset
    contact = sigma > 0.0
    complementarity = float(np.max(np.abs(gap[contact]))) / h if contact.any() else 0.0
    gap[contact] = 0.0
    gap = np.maximum(gap, 0.0)  # a node out of contact may penetrate by the tolerance
    s = float(np.mean(gap)) / h
    widths = _widths(contact, gap)
    full = bool(contact.all())
    x = np.arange(n) / n - 0.5
    jmax = int(np.argmax(sigma))
    mean_u = float(np.mean(u)) / h
    fields = Fields(x, sigma, (u - np.mean(u)) / h, gap / h)
    load_got = float(np.mean(sigma))
    diagnostics = {"iterations": int(res.nit), "offset": offset,
                   "complementarity": complementarity,
                   "load_error": abs(load_got - p_asked) / p_asked, "tolerance": tol,
                   "wall_time": wall, "contactmechanics_version": version,
                   "viscosine_version": viscosine.__version__}
    return ContactMechanicsResult(
        success=bool(res.success), message=str(res.message), nit=int(res.nit), load=load_got,
        load_asked=p_asked, hk=h, thickness=kd, nu=v["nu"], nodes=n, full_contact=full,
        contact_fraction=float(sum(widths)), contact_nodes=float(np.mean(contact)),
        penetration=1.0 - s, separation=s,
        mean_displacement=None if kd is None else mean_u,
        approach=None if kd is None else 1.0 - s + mean_u,
        max_pressure=float(sigma[jmax]), x_max_pressure=float(x[jmax]),
        n_patches=len(widths) if not full else 1, diagnostics=diagnostics,
        _fields=fields)
