"""Tamaas as a third code: its transient viscoelastic contact solver stepped to steady sliding.

Tamaas (Frérot, Anciaux, Rey, Pham-Ba & Molinari, https://gitlab.com/tamaas/tamaas) solves the
normal contact of a rigid surface with a periodic half-space by a Polonsky–Keer conjugate-gradient
method on an FFT influence operator.  Its ``MaxwellViscoelastic`` solver makes the half-space a
generalised Maxwell solid stepped in time by backward Euler.  Nobody on this project wrote it,
it never sees the steady-sliding Green's function of eq. (2.5) nor Hunter's transformation of the
paper, and it reaches steady sliding the physical way: the material stays at rest in the lab
frame, the sinusoid is moved every time step, and the transient is run out.

What Tamaas computes (version 2.9, measured here and written where it bites)
------------------------------------------------------------------------------
* ``model_type.basic_1d`` is the plane-strain half-plane with a 1-D periodic surface: its
  displacement obeys û(q) = 2 p̂(q)/(E*|q|) for q ≠ 0 with E* = E/(1 − ν²) (``model.E_star``);
  system size 1 makes λ the unit of length.
* The traction is the pressure, positive in compression; the displacement is positive into the
  body; ``solve(p)`` imposes the mean pressure p, and the q = 0 mode of the displacement is the
  rigid approach fixed by the contact, so the gap is u − surface (0 in contact) and ``surface``
  is the indenter's protrusion into the body (crest = largest value).
* Each ``MaxwellViscoelastic.solve`` is one backward-Euler step of length ``time_step`` (the
  internal variables are updated after the solve: ``solve_should_update`` is true).  The branch
  moduli are shear moduli in the units of ``model.mu`` = E/(2(1 + ν)), which plays the long-term
  shear modulus G∞; the branch times are RELAXATION times.
* Its state update relaxes to the right long-term state only when G∞ = ``model.mu`` = 1: with any
  other value a constant imposed displacement relaxes to the wrong stress (measured: to 0.61 of
  the relaxed value at G∞ = ½).  Here G∞ = 1 (E = 2, ν = 0), so Tamaas's pressures are in units of
  G∞ and its relaxed plane-strain modulus is E0/(1 − ν²) = 2 G∞/(1 − ν) = 2.

The standard linear solid in those units
----------------------------------------
The paper's material (eq. 2.3) has creep compliance J(t) = 1/E0 − (1/E1) e^{−t/τ} with τ the
CREEP (retardation) time; its relaxation modulus is E(t) = E0 + (E∞ − E0) e^{−t/τ_R} with
relaxation time τ_R = τ E0/E∞.  So Tamaas gets one branch with modulus (E∞/E0 − 1) G∞ and time
τ/ratio (τ = 1).  Passing τ itself would shift every speed by the factor E∞/E0.  ν only scales
E* and drops out of every dimensionless output (ν = 0 here).

Units (the project's): lengths in λ (positions x/λ) or over h, pressures in E0/(1 − ν²), times in
τ; inputs load p̃∞ = p∞(1 − ν²)/E0, speed V/V0 = Vτk, ratio E∞/E0, hk.  In Tamaas's units:
λ = 1, h = hk/(2π), V = speed/(2π) per τ, a period takes T = 2π/speed, σ̃ = p_Tamaas/2.

Sliding and the steady state
----------------------------
The indenter advances toward +x by a whole number of grid cells per step, or by one cell in a
whole number of steps (``dt`` is snapped to the nearest such value), so that after every period
its crest is back on grid node 0 and the crest-frame fields are the lab fields rolled by N/2.
At every period end the fields and scalars are compared with the previous period's; the run is
steady when that change, and the tail of the geometric series it decays by, are below
``steady_rtol``.  With one cell per step (the default dt) the discrete steady state is an exact
travelling wave.

Output conventions: the crest frame (crest at x = 0, material streaming toward −x), σ(1 − ν²)/E0
positive in compression, v/h positive into the body from the mean line of the deformed surface,
gap/h, τ̃f = −(1/λ)∫σ̃ ∂v/∂x dx (positive when it resists: the paper's (1/λ)∫σ ∂v/∂x dx with the
sign of a resisting force made positive) and μ = τ̃f/p̃∞.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014: eq. (2.3) (the
material), eq. (3.1) and Appendix A (Westergaard's limits), the definitions of a, e, ê, Δ, τf.
"""
from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

import viscosine
from viscosine import Fields
from viscosine.checks import bad, integer, real, series
from viscosine.protocol import SCALAR_KEYS, Patch, plain

from .. import operating_point as _op
from ..convergence import richardson
from ..fields import true_runs

#: E∞/E0 and hk where a caller names none: the operating point's defaults (written once there)
RATIO, HK = _op.DEFAULTS["ratio"], _op.DEFAULTS["hk"]

#: the Tamaas versions this adapter was verified on (its conventions are measured, not assumed)
TAMAAS_REQUIREMENT = "tamaas>=2.9,<2.10"
_INSTALL = "pip install 'viscosine[peers]' (from a clone of the repository: pip install '.[peers]')"

# Tamaas's model: G∞ = model.mu = 1 (its update is right only then), ν = 0, E = 2(1 + ν) G∞
_NU = 0.0
_E_TAMAAS = 2.0 * (1.0 + _NU)
_ESTAR0 = _E_TAMAAS / (1.0 - _NU * _NU)  # relaxed plane-strain modulus in Tamaas units: 2

_TWO_PI = 2.0 * math.pi

#: name -> (low, high, what is allowed and why); bounds inclusive
ACCEPTED = {
    "load": (1e-8, 1e8,
             "a mean pressure p̃∞ = p∞(1 − ν²)/E0 in [1e-08, 1e+08] (below, the contact is far "
             "narrower than any affordable grid; above, full contact at any speed)"),
    "speed": (1e-9, 1e9,
              "V/V0 = Vτk in [1e-09, 1e+09] (a transient code needs motion; beyond, the run is "
              "the relaxed or glassy elastic solution to double precision, and the time step "
              "T/N spans 1e-10 to 1e+10 τ)"),
    "ratio": (1.0, 1e4,
              "E∞/E0 > 1 and ≤ 1e+04 (1 is an elastic material: no Maxwell branch)"),
    "hk": (1e-6, 1e6, "hk in [1e-06, 1e+06] (Tamaas's problem is linear: hk scales pressures)"),
    "nodes": (16, 2 ** 20,
              "an even number of grid nodes N per period in [16, 1048576] (each step is one "
              "Tamaas solve on N nodes, a period N steps at the default dt)"),
    "dt": (0.0, math.inf,
           "a finite time step > 0 in units of the creep time τ (snapped so the indenter advances "
           "a whole number of cells per step, or a cell in a whole number of steps), or None"),
    "tolerance": (1e-15, 1e-4, "Tamaas's Polonsky–Keer tolerance in [1e-15, 1e-4]"),
    "steady_rtol": (1e-12, 1e-1, "a steadiness tolerance (change per period) in [1e-12, 0.1]"),
    "max_periods": (2, 100000, "a whole number of periods in [2, 100000]"),
}


def _real(name, value):
    lo, hi, text = ACCEPTED[name]
    if name in ("ratio", "dt"):
        return real(name, value, text, lambda v: lo < v <= hi)
    return real(name, value, text, lambda v: lo <= v <= hi)


def _integer(name, value, even=False):
    lo, hi, text = ACCEPTED[name]
    return integer(name, value, text, lambda v: lo <= v <= hi and not (even and v % 2))


def validate(*, load=None, speed=None, ratio=None, hk=None, nodes=None, dt=None, tolerance=None,
             steady_rtol=None, max_periods=None):
    """Check the inputs of `solve` (those given); return them as plain numbers.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: what is allowed"`` for the first bad input.
    """
    out = {}
    for name, value in (("load", load), ("speed", speed), ("ratio", ratio), ("hk", hk),
                        ("dt", dt), ("tolerance", tolerance), ("steady_rtol", steady_rtol)):
        if value is not None:
            out[name] = _real(name, value)
    if nodes is not None:
        out["nodes"] = _integer("nodes", nodes, even=True)
    if max_periods is not None:
        out["max_periods"] = _integer("max_periods", max_periods)
    return out


def _import_tamaas():
    """The tamaas module, or an ImportError that says how to install it."""
    try:
        import tamaas
    except ImportError as exc:
        raise ImportError(f"the Tamaas peer needs the tamaas package ({TAMAAS_REQUIREMENT}); "
                          f"install it with: {_INSTALL}") from exc
    return tamaas


# ----------------------------------------------------------------------------- results
@dataclass(frozen=True)
class TamaasResult:
    """One operating point run by Tamaas to steady sliding (the project's result protocol).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (steady, every step of the last period converged), 0 or 1,
        what the run says, caveats.
    nit
        Time steps taken.
    load, speed, ratio, hk, nodes, dt
        Achieved p̃∞ (mean of σ̃ over the grid), V/V0, E∞/E0, hk, N and the time step used
        (units of τ, after snapping).
    full_contact, contact_fraction, ka, ke, ke_hat, penetration, separation, tau_f, mu
        The scalars of the conventions at the last period end (ka, ke, kê None with several
        patches; ke None in full contact); separation s/h = 1 − Δ/h.
    max_pressure, x_max_pressure
        Largest nodal σ̃ and its x/λ.
    n_patches, patches
        Contact patches (`Patch`).
    diagnostics
        steps, periods, dt_over_tau, dt_over_period, cells_per_step, steps_per_cell,
        steady_residual (largest relative change over the last period), steady_tail (its
        geometric tail, the estimated distance to the steady state), steady_history,
        solver_error (worst Tamaas error over the last period), tolerance,
        complementarity (largest |gap|/h where σ > 0, before it is set to 0),
        load_error (|mean σ̃ − p̃∞|/p̃∞), wall_time (s), tamaas_version.
    error_estimate
        None (one run has no error estimate; see `dt_study`).
    """

    success: bool
    status: int
    message: str
    warnings: tuple
    nit: int
    load: float
    speed: float
    ratio: float
    hk: float
    nodes: int
    dt: float
    full_contact: bool
    contact_fraction: float
    ka: float | None
    ke: float | None
    ke_hat: float | None
    penetration: float
    separation: float
    tau_f: float
    mu: float
    max_pressure: float
    x_max_pressure: float
    n_patches: int
    patches: tuple
    diagnostics: dict
    load_asked: float = math.nan
    error_estimate = None
    _fields: Fields | None = field(default=None, repr=False, compare=False)

    def scalars(self):
        """The eight scalars of the conventions (plain Python types, None where null)."""
        return {k: plain(getattr(self, k)) for k in SCALAR_KEYS}

    def as_dict(self):
        """The JSON record (serialisable with ``allow_nan=False``)."""
        rec = {"solver": "tamaas", "version": viscosine.__version__, "control": "load",
               "load_asked": self.load_asked, "speed": self.speed, "ratio": self.ratio,
               "hk": self.hk, "nodes": self.nodes, "dt": self.dt, "load": self.load}
        rec.update(self.scalars())
        rec.update({"separation": self.separation, "success": self.success,
                    "message": self.message, "warnings": list(self.warnings),
                    "max_pressure": self.max_pressure, "x_max_pressure": self.x_max_pressure,
                    "n_patches": self.n_patches, "patches": [asdict(p) for p in self.patches],
                    "diagnostics": self.diagnostics, "error_estimate": None})
        return plain(rec)

    def fields(self, x_over_lambda=None):
        """Pressure, displacement and gap at the last period end.

        Parameters
        ----------
        x_over_lambda : array_like, optional
            Positions x/λ in the crest frame; default Tamaas's grid j/N − ½, j = 0 … N − 1
            (the crest on node N/2).  Elsewhere the nodal values are interpolated linearly and
            periodically.

        Returns
        -------
        viscosine.Fields
            σ(1 − ν²)/E0, v/h and gap/h (conventions units).
        """
        f = self._fields
        if f is None:
            raise RuntimeError(f"no fields: the run failed ({self.message})")
        if x_over_lambda is None:
            return f
        X = np.atleast_1d(np.asarray(x_over_lambda, dtype=float))
        if X.ndim != 1 or not np.all(np.isfinite(X)):
            raise ValueError(f"x_over_lambda={x_over_lambda!r} is not allowed: a 1-D array of "
                             "finite positions x/λ")
        xp = f.x_over_lambda
        return Fields(X, *(np.interp(X, xp, a, period=1.0)
                           for a in (f.pressure, f.displacement, f.gap)))


# ----------------------------------------------------------------------------- measuring
def _edge_cells(g_near, g_far, s_in, s_next):
    """Where a contact edge lies between the last gap node and the first contact node.

    Returns the distance from the last gap node toward the contact, in cells (0 to 1).  Just
    outside an edge the gap grows like distance^(3/2), so gap^(2/3) is linear: it is
    extrapolated to zero from the two nearest gap nodes (measured on Westergaard's solution:
    edges within 0.15 cell at N = 256, 0.06 cell at N ≥ 512, against 0.3–0.7 cell for the
    nearest node).  With a single gap node, σ² (linear near the edge, σ ~ √distance) is
    extrapolated from the first two contact nodes instead.
    """
    if g_far is not None and g_far > g_near > 0.0:
        a, b = g_near ** (2.0 / 3.0), g_far ** (2.0 / 3.0)
        return min(a / (b - a), 1.0)
    if s_next is not None and s_next > s_in > 0.0:
        a, b = s_in * s_in, s_next * s_next
        return max(1.0 - a / (b - a), 0.0)
    return 0.5


def _measure(sigma, u, gap, h, load):
    """The scalars of one snapshot in the crest frame (arrays on x_j = j/N − ½).

    Returns a dict with the eight scalars, separation, max pressure and the patches.
    """
    n = sigma.size
    dx = 1.0 / n
    x = np.arange(n) * dx - 0.5
    # τ̃f = −(1/λ)∫σ̃ ∂u/∂x dx with a spectral derivative (u and x in λ): resisting > 0
    q = _TWO_PI * np.fft.rfftfreq(n, dx)
    uh = np.fft.rfft(u)
    uh[-1] = 0.0  # the Nyquist mode has no derivative on the grid
    slope = np.fft.irfft(1j * q * uh, n)
    tau_f = -float(np.mean(sigma * slope))
    tau_abs = float(np.mean(np.abs(sigma * slope)))
    s = float(np.mean(u))  # the mean gap: mean(u) − mean(profile), and the profile's mean is 0
    contact = sigma > 0.0
    jmax = int(np.argmax(sigma))
    out = {"tau_f": tau_f, "tau_abs": tau_abs, "mu": tau_f / load, "separation": s / h,
           "penetration": 1.0 - s / h, "max_pressure": float(sigma[jmax]),
           "x_max_pressure": float(x[jmax]), "load": float(np.mean(sigma))}
    runs = true_runs(contact)
    if len(runs) == 1 and runs[0][1] == n:  # full contact: σ̃ is p̃∞ + A cos(kx − δ) exactly
        delta = -float(np.angle(np.sum(sigma * np.exp(-1j * _TWO_PI * x))))
        patch = Patch(-0.5, 0.5, 1.0, out["load"], delta / _TWO_PI, 0.0, math.pi, None, delta)
        out.update(full_contact=True, contact_fraction=1.0, ka=math.pi, ke=None, ke_hat=delta,
                   patches=(patch,))
        return out
    def outside(i):  # the gap at node i, or None when i is in contact
        i %= n
        return None if contact[i] else float(gap[i])

    patches = []
    for first, length in runs:
        idx = (first + np.arange(length)) % n
        xs = x[first] + dx * np.arange(length)  # continuous across ±½
        sg = sigma[idx]
        nxt, prv = (float(sg[1]), float(sg[-2])) if length >= 2 else (None, None)
        trailing = xs[0] - dx * (1.0 - _edge_cells(outside(first - 1), outside(first - 2),
                                                   float(sg[0]), nxt))
        leading = xs[-1] + dx * (1.0 - _edge_cells(outside(first + length),
                                                   outside(first + length + 1), float(sg[-1]), prv))
        trailing, leading = float(trailing), float(leading)
        width = leading - trailing
        centroid = float(np.dot(xs, sg) / np.sum(sg))
        centre = 0.5 * (trailing + leading)
        wrap = math.floor(centre + 0.5)  # the crest nearest the patch; positions around it
        summit = float(min(max(wrap, trailing), leading))  # highest profile point in the patch
        patches.append(Patch(trailing - wrap, leading - wrap, width, float(np.sum(sg)) / n,
                             centroid - wrap, summit - wrap, math.pi * width,
                             _TWO_PI * (centre - summit), _TWO_PI * (centroid - summit)))
    width = sum(p.width for p in patches)
    one = patches[0] if len(patches) == 1 else None
    out.update(full_contact=False, contact_fraction=width,
               ka=None if one is None else one.ka, ke=None if one is None else one.ke,
               ke_hat=None if one is None else one.ke_hat, patches=tuple(patches))
    return out


def _stepping(dt, speed, nodes):
    """(cells per step, steps per cell, snapped dt) nearest the requested dt (geometrically).

    The indenter must come back onto grid node 0 after each period: so a step is a whole number
    of cells that divides N, or a cell is a whole number of steps.
    """
    t_cell = _TWO_PI / (speed * nodes)  # time to cross one cell, units of τ
    if dt is None:
        return 1, 1, t_cell
    r = dt / t_cell
    if r >= 1.0:
        divisors = [d for d in range(1, nodes + 1) if nodes % d == 0]
        m = min(divisors, key=lambda d: abs(math.log(d / r)))
        return m, 1, m * t_cell
    lo = max(1, math.floor(1.0 / r))
    s = min((lo, lo + 1), key=lambda k: abs(math.log(k * r)))
    return 1, s, t_cell / s


# ----------------------------------------------------------------------------- solve
def solve(*, load, speed, ratio=RATIO, hk=HK, nodes=512, dt=None, tolerance=1e-10,
          steady_rtol=1e-6, max_periods=400):
    """Run Tamaas's viscoelastic solver to steady sliding of the sinusoid and convert its output.

    Parameters
    ----------
    load : float
        p̃∞ = p∞(1 − ν²)/E0 (load control; Tamaas's ``solve`` imposes the mean pressure).
    speed : float
        V/V0 = Vτk, τ the creep time of eq. (2.3).
    ratio : float
        E∞/E0 > 1 (one Maxwell branch of modulus (ratio − 1) G∞, relaxation time τ/ratio).
    hk : float
        Amplitude times wavenumber.
    nodes : int
        Grid nodes N per period (even).
    dt : float, optional
        Time step in units of τ.  Default: T/N, the time the indenter takes to cross one cell
        (T = 2π/speed the period).  Why: the discrete steady state is then an exact travelling
        wave (no sub-cell ripple, a bitwise-periodic profile), a period costs N solves, and the
        backward-Euler error is set by the distance travelled per step rather than by the
        speed: μ comes out low by (2.5–4.4)/N relative (measured at p̃∞ = 0.15, E∞/E0 = 3,
        hk = 1 for V/V0 = 0.35, 1.06, 3.2 and N = 256, 512, 1024; 0.1–0.3 V/V0 alike at
        N = 256), i.e. 0.5–0.9 % at N = 512.  `dt_study` removes it by Richardson
        extrapolation.  Other values are snapped to a whole number of cells per step dividing
        N, or a whole number of steps per cell (geometrically nearest; the request is kept in
        ``diagnostics['dt_requested']`` and a warning says so).
    tolerance : float
        Tamaas's Polonsky–Keer tolerance per step (1e-10: μ then moves by < 1e-10 relative).
    steady_rtol : float
        Steady when the relative change of the fields and scalars over one period, and the
        geometric tail of those changes, are below this.
    max_periods : int
        Periods after which an unsteady run is reported as a failure.

    Returns
    -------
    TamaasResult
        The result protocol; ``fields()`` on Tamaas's grid.

    Raises
    ------
    ValueError
        Bad input: ``"name=value is not allowed: what is allowed"``.
    ImportError
        tamaas is not installed (the message says ``pip install 'viscosine[peers]'``).

    References
    ----------
    Eq. (2.3) (the standard linear solid; τ is the creep time), the definitions of a, e, ê, Δ
    and τf of the paper.
    """
    v = _checked(load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes, dt=dt,
                 tolerance=tolerance, steady_rtol=steady_rtol, max_periods=max_periods)
    tm = _import_tamaas()
    version = str(tm.__version__)
    stepping = _stepping(v.get("dt"), v["speed"], v["nodes"])
    warnings = _setup_warnings(version, v.get("dt"), stepping[2])
    h = v["hk"] / _TWO_PI  # the amplitude in λ, Tamaas's length unit
    run = _run_to_steady(tm, v, stepping, h)
    return _result(v, stepping, h, run, warnings, version)


def _checked(**inputs):
    """`validate` the inputs of `solve`, each of them required but dt."""
    v = validate(**inputs)
    for name in ("load", "speed", "ratio", "hk", "nodes", "tolerance", "steady_rtol",
                 "max_periods"):
        if name not in v:
            raise bad(name, None, ACCEPTED[name][2])
    return v


def _setup_warnings(version, dt_requested, dt_used):
    """The caveats known before the run: a Tamaas version this adapter was not verified on, a
    snapped time step."""
    warnings = []
    if not version.startswith("2.9."):
        warnings.append(f"tamaas {version} is not the version this adapter was verified "
                        f"on ({TAMAAS_REQUIREMENT})")
    if dt_requested is not None and abs(dt_used / dt_requested - 1.0) > 1e-9:
        warnings.append(f"dt snapped from {dt_requested!r} to {dt_used!r} (a whole number of "
                        "cells per step, or of steps per cell)")
    return warnings


@dataclass(frozen=True)
class _SteadyRun:
    """Tamaas stepped to the steady state, or for max_periods.

    ``snapshot`` is the last period end's (σ̃, u, gap, `_measure`'s scalars) in the crest frame,
    ``history`` the change over each period after the first (`_change`), ``tail`` the estimated
    distance to the steady state (`_tail`), ``worst`` the largest Tamaas error over the last
    period and ``wall`` the seconds taken.
    """

    snapshot: tuple
    history: list
    steps: int
    periods: int
    steady: bool
    tail: float
    worst: float
    wall: float = math.nan

    @property
    def residual(self):
        """The change over the last period (inf before the second period end)."""
        return self.history[-1] if self.history else math.inf


def _run_to_steady(tm, v, stepping, h):
    """Build Tamaas's model and step it to the steady state (`_SteadyRun`); Tamaas's logging is
    quietened meanwhile and restored after."""
    base = _profiles(h, v["nodes"], stepping[1])
    surface = np.array(base[0], dtype=np.float64, order="C")  # Tamaas keeps a view of it
    level = tm.get_log_level()
    tm.set_log_level(tm.LogLevel.error)  # Tamaas logs every solve at the info level
    t0 = time.perf_counter()
    try:
        model, solver = _maxwell_model(tm, surface, v["ratio"], v["tolerance"], stepping[2])
        run = _periods_to_steady(model, solver, surface, base, v, stepping, h)
    finally:
        tm.set_log_level(level)
    return replace(run, wall=time.perf_counter() - t0)


def _profiles(h, n, s_steps):
    """The sinusoid h cos 2π(x − k/(N s)) on the grid x = j/N at each sub-cell offset k < s: the
    indenter at any step is one of them rolled by whole cells, so it is bitwise periodic in
    time."""
    j = np.arange(n)
    return [h * np.cos(_TWO_PI * (j / n - k / (n * s_steps))) for k in range(s_steps)]


def _maxwell_model(tm, surface, ratio, tolerance, dt):
    """Tamaas's half-plane (G∞ = ``model.mu`` = 1) and its backward-Euler viscoelastic solver on
    ``surface``: the standard linear solid of eq. (2.3) as one Maxwell branch."""
    model = tm.ModelFactory.createModel(tm.model_type.basic_1d, [1.0], [surface.size])
    model.E, model.nu = _E_TAMAAS, _NU  # model.mu = G∞ = 1
    solver = tm.MaxwellViscoelastic(model, surface, tolerance, dt, [ratio - 1.0],
                                    [1.0 / ratio])  # relaxation time τ_R = τ E0/E∞
    return model, solver


def _periods_to_steady(model, solver, surface, base, v, stepping, h):
    """Step one period at a time until the change over a period is at Tamaas's tolerance, or it
    and its geometric tail are below steady_rtol, or max_periods have passed (`_SteadyRun`)."""
    target = v["load"] * _ESTAR0
    history, prev, steps = [], None, 0
    for period_no in range(1, v["max_periods"] + 1):
        steps, worst = _one_period(solver, surface, base, stepping, steps, target)
        snap = _snapshot(model, surface.size, h, v["load"])
        steady, tail = False, math.inf
        if prev is not None:
            history.append(_change(prev, snap, h))
            steady, tail = steadiness(history, v)
            if steady:
                break
        prev = snap
    return _SteadyRun(snap, history, steps, period_no, steady, tail, worst)


def steadiness(history, v):
    """(steady, tail) after a period whose change over the previous one is ``history[-1]``:
    steady when that change is at the solver's tolerance, or it and the tail of the geometric
    series the changes decay by (`_tail`) are below ``v["steady_rtol"]``."""
    tail = _tail(history)
    return (history[-1] <= 10.0 * v["tolerance"]
            or (history[-1] <= v["steady_rtol"] and tail <= v["steady_rtol"])), tail


def _one_period(solver, surface, base, stepping, steps, target):
    """Move the indenter and solve at every step of one period, after ``steps`` steps: (steps
    taken in all, the largest Tamaas error of the period)."""
    m_cells, s_steps, _ = stepping
    n = surface.size
    worst = 0.0
    for _ in range(_steps_per_period(n, stepping)):
        steps += 1
        # crest position in 1/s of a cell: m cells per step (s = 1) or 1/s (m = 1)
        cells, k = divmod(steps * m_cells, s_steps)
        surface[:] = np.roll(base[k], cells % n)
        worst = max(worst, float(solver.solve(target)))
    return steps, worst


def _steps_per_period(n, stepping):
    """Time steps in a period of N cells (``stepping``: `_stepping`'s m, s and dt)."""
    m_cells, s_steps, _ = stepping
    return n * s_steps // m_cells


def _snapshot(model, n, h, load):
    """(σ̃, u, gap, `_measure`'s scalars) at a period end: the crest is then on node 0, so the
    crest frame is the lab frame rolled by N/2."""
    sigma = np.roll(np.array(model.traction, dtype=float), n // 2) / _ESTAR0
    u = np.roll(np.array(model.displacement, dtype=float), n // 2)
    gap = np.roll(np.array(model["gap"], dtype=float), n // 2)
    return sigma, u, gap, _measure(sigma, u, gap, h, load)


def _tail(history):
    """The geometric tail c·q/(1 − q) of the changes per period, c the last and q its ratio to
    the one before: the estimated distance to the steady state (inf unless they shrink)."""
    if len(history) >= 2 and history[-2] > 0.0:
        q = history[-1] / history[-2]
        return history[-1] * q / (1.0 - q) if q < 1.0 else math.inf
    return math.inf


def _change(prev, snap, h):
    """Largest relative change between two period-end snapshots (fields and scalars)."""
    s0, u0, _, m0 = prev
    s1, u1, _, m1 = snap
    v0, v1 = u0 - np.mean(u0), u1 - np.mean(u1)
    scale_v = max(float(np.max(np.abs(v1))), 1e-300)
    return max(float(np.max(np.abs(s1 - s0)) / max(np.max(np.abs(s1)), 1e-300)),
               float(np.max(np.abs(v1 - v0))) / scale_v,
               abs(m1["tau_f"] - m0["tau_f"]) / max(m1["tau_abs"], 1e-300),
               abs(m1["separation"] - m0["separation"]) * h / scale_v)


def _result(v, stepping, h, run, warnings, version):
    """The `TamaasResult` of a run: its last period end's scalars and fields, its verdict, its
    caveats (``warnings`` and `_patch_warnings`) and its diagnostics."""
    meas = run.snapshot[3]
    n = v["nodes"]
    success, status, message = _verdict(run, v["tolerance"], v["steady_rtol"])
    return TamaasResult(
        success=success, status=status, message=message,
        warnings=tuple(warnings + _patch_warnings(meas, n)), nit=run.steps,
        load=meas["load"], speed=v["speed"], ratio=v["ratio"], hk=v["hk"], nodes=n,
        dt=stepping[2], full_contact=meas["full_contact"],
        contact_fraction=meas["contact_fraction"], ka=meas["ka"], ke=meas["ke"],
        ke_hat=meas["ke_hat"], penetration=meas["penetration"], separation=meas["separation"],
        tau_f=meas["tau_f"], mu=meas["mu"], max_pressure=meas["max_pressure"],
        x_max_pressure=meas["x_max_pressure"], n_patches=len(meas["patches"]),
        patches=meas["patches"], diagnostics=_diagnostics(v, stepping, h, run, version),
        load_asked=v["load"], _fields=_crest_fields(run.snapshot, h))


def _verdict(run, tolerance, steady_rtol):
    """(success, status, message): an answer only when the run is steady and every solve of its
    last period reached Tamaas's tolerance."""
    converged = run.worst <= tolerance * (1.0 + 1e-6)
    if run.steady and converged:
        return True, 0, (f"steady after {run.periods} periods ({run.steps} steps): change over "
                         f"the last period {run.residual:.1e}")
    why = [] if run.steady else [
        f"not steady after {run.periods} periods (change over the last period "
        f"{run.residual:.1e}, estimated distance to steady {run.tail:.1e} > steady_rtol = "
        f"{steady_rtol:g}); raise max_periods"]
    if not converged:
        why.append(f"Tamaas's solver stopped at error {run.worst:.1e} > tolerance {tolerance:g}")
    return False, 1, "; ".join(why)


def _patch_warnings(meas, n):
    """A caveat when a contact patch spans fewer than 8 of the N nodes (none in full contact)."""
    if len(meas["patches"]) and not meas["full_contact"] and min(
            p.width for p in meas["patches"]) * n < 8:
        return [f"a contact patch spans fewer than 8 of the {n} nodes: its edges and friction "
                "are poorly resolved"]
    return []


def _crest_fields(snapshot, h):
    """σ̃, v/h from the mean line of the deformed surface and gap/h of a snapshot, on x_j = j/N − ½
    (the crest frame)."""
    sigma, u, gap, _ = snapshot
    n = sigma.size
    gap_out = np.where(sigma > 0.0, 0.0, gap) / h  # Tamaas leaves its residual (≤ tolerance) there
    return Fields(np.arange(n) / n - 0.5, sigma, (u - np.mean(u)) / h, gap_out)


def _complementarity(snapshot, h):
    """The largest |gap|/h where σ > 0 in a snapshot (0 without contact)."""
    sigma, _, gap, _ = snapshot
    contact = sigma > 0.0
    return float(np.max(np.abs(gap[contact]))) / h if contact.any() else 0.0


def _diagnostics(v, stepping, h, run, version):
    """The diagnostics of a run (listed in `TamaasResult`); times in units of τ."""
    m_cells, s_steps, dt_used = stepping
    period = _TWO_PI / v["speed"]
    return {
        "steps": run.steps, "periods": run.periods,
        "steps_per_period": _steps_per_period(v["nodes"], stepping),
        "dt_over_tau": dt_used, "dt_over_period": dt_used / period,
        "dt_over_relaxation_time": dt_used * v["ratio"], "dt_requested": v.get("dt"),
        "cells_per_step": m_cells, "steps_per_cell": s_steps,
        "steady_residual": run.residual,
        "steady_tail": run.tail if math.isfinite(run.tail) else None,
        "steady_history": list(run.history), "solver_error": run.worst,
        "tolerance": v["tolerance"], "complementarity": _complementarity(run.snapshot, h),
        "load_error": abs(run.snapshot[3]["load"] / v["load"] - 1.0), "wall_time": run.wall,
        "tamaas_version": version}


# ----------------------------------------------------------------------------- dt study
#: the quantities a dt study extrapolates
STUDY_KEYS = ("mu", "tau_f", "penetration", "ka", "ke", "ke_hat", "contact_fraction")

#: the time steps of a dt study in cell crossings T/N (coarse to fine): halved twice, so that the
#: first-order Richardson value and the size of its next term both come out
CELLS_PER_STEP = (4, 2, 1)


def _order(dts, values):
    """Observed order p from three (dt, value) pairs, dt decreasing: solves
    (q1 − q0)/(q2 − q1) = (dt0^p − dt1^p)/(dt1^p − dt2^p); None when the differences do not
    shrink monotonically (no order to observe).

    Not `comparisons.convergence.observed_order`: this is exact for any ratios of the steps
    (the log–log fit of differences is right only for equal ratios) and refuses a
    non-monotone study; on halved steps the two agree to a few units in the last place."""
    (d0, d1, d2), (q0, q1, q2) = dts, values
    a, b = q1 - q0, q2 - q1
    if b == 0.0 or a / b <= 1.0:
        return None
    target = math.log(a / b)

    def f(p):
        return math.log((d0 ** p - d1 ** p) / (d1 ** p - d2 ** p)) - target

    lo, hi = 0.05, 10.0
    if f(lo) > 0.0 or f(hi) < 0.0:
        return None
    for _ in range(200):  # bisection: f increases with p
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) < 0.0 else (lo, mid)
    return 0.5 * (lo + hi)


def dt_study(*, load, speed, ratio=RATIO, hk=HK, nodes=512, dts=None, mesh_check=False,
             **options):
    """Run `solve` at several time steps and extrapolate to dt → 0 (backward Euler: first order).

    Parameters
    ----------
    load, speed, ratio, hk, nodes
        As in `solve`.
    dts : sequence of float, optional
        Time steps in units of τ (snapped as in `solve`), sorted here from coarse to fine.
        Default: 4, 2 and 1 grid-cell crossings (the finest is `solve`'s default).
    mesh_check : bool
        Also run the two finest steps at N/2 and report how much the extrapolated values move.
    **options
        tolerance, steady_rtol, max_periods (passed to `solve`).

    Returns
    -------
    dict
        Plain data: ``inputs``; ``rows`` (one per dt: dt/τ, dt/T, cells per step, steps per
        cell, the scalars of `STUDY_KEYS`, steps, periods, wall time, success, message);
        ``order`` (observed order of each quantity from the three finest steps, None if fewer
        than three or not monotone); ``richardson`` (first-order extrapolation from the two
        finest steps); ``error`` (its estimated error: the change of the extrapolation from
        the coarser pair, divided by dt_coarsest/dt_finest − 1, i.e. the size of the next
        term; None with two steps); ``mesh`` (None, or the extrapolation at N/2 and its
        difference); ``success`` and ``wall_time``.

    References
    ----------
    The definitions of a, e, ê, Δ and τf of the paper; the extrapolation is Richardson's.
    """
    v = validate(load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes)
    t_cell = _TWO_PI / (v["speed"] * v["nodes"])
    if dts is None:
        dts = tuple(c * t_cell for c in CELLS_PER_STEP)
    allowed = "a sequence of at least two time steps > 0 (units of τ)"
    steps = sorted(series("dts", dts, allowed), reverse=True)
    if len(steps) < 2:
        raise bad("dts", dts, allowed)
    dts = steps
    for d in dts:
        validate(dt=d)
    t0 = time.perf_counter()
    rows = _study_rows(dts, load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes, **options)
    used = [r["dt"] for r in rows]
    if len(set(used)) != len(used):
        raise bad("dts", dts, "time steps that stay distinct after snapping to the grid (see "
                  "solve)")
    out = {"inputs": {"load": load, "speed": speed, "ratio": ratio, "hk": hk, "nodes": nodes,
                      "dts": list(dts), **options},
           "rows": rows, "success": all(r["success"] for r in rows)}
    out.update(extrapolate(rows))
    out["mesh"] = None
    if mesh_check and nodes // 2 >= ACCEPTED["nodes"][0] and (nodes // 2) % 2 == 0:
        half = _study_rows(used[-2:], load=load, speed=speed, ratio=ratio, hk=hk,
                           nodes=nodes // 2, **options)
        ext = extrapolate(half)["richardson"]
        out["mesh"] = {"nodes": nodes // 2, "rows": half, "richardson": ext,
                       "difference": {k: (None if ext[k] is None or out["richardson"][k] is None
                                          else out["richardson"][k] - ext[k])
                                      for k in STUDY_KEYS}}
        out["success"] = out["success"] and all(r["success"] for r in half)
    out["wall_time"] = time.perf_counter() - t0
    return out


def _study_rows(dts, progress=None, results=None, **kw):
    """One `solve` per time step: the rows of a dt study (``progress(row)`` after each; the
    results appended to ``results`` when it is a list)."""
    rows = []
    for d in dts:
        r = solve(dt=d, **kw)
        if results is not None:
            results.append(r)
        dg = r.diagnostics
        row = {"dt": r.dt, "dt_over_period": dg["dt_over_period"],
               "cells_per_step": dg["cells_per_step"], "steps_per_cell": dg["steps_per_cell"],
               "nodes": r.nodes, "steps": dg["steps"], "periods": dg["periods"],
               "wall_time": dg["wall_time"], "success": r.success, "message": r.message}
        row.update({k: getattr(r, k) for k in STUDY_KEYS})
        rows.append(row)
        if progress is not None:
            progress(row)
    return rows


def extrapolate(rows):
    """Order, Richardson value and error estimate of every quantity (rows coarse → fine).

    The Richardson value is `comparisons.convergence.richardson`'s step of order 1 (backward
    Euler) with the ratio of the two finest steps."""
    dts = [r["dt"] for r in rows]
    order, rich, err = {}, {}, {}
    for k in STUDY_KEYS:
        q = [r[k] for r in rows]
        if any(x is None for x in q) or not all(r["success"] for r in rows):
            order[k] = rich[k] = err[k] = None
            continue
        rich[k] = richardson(q[-2], q[-1], 1.0, dts[-2] / dts[-1])
        order[k] = _order(dts[-3:], q[-3:]) if len(q) >= 3 else None
        if len(q) >= 3:
            coarser = richardson(q[-3], q[-2], 1.0, dts[-3] / dts[-2])
            err[k] = abs(rich[k] - coarser) / (dts[-3] / dts[-1] - 1.0)
        else:
            err[k] = None
    return {"order": order, "richardson": rich, "error": err}


@dataclass(frozen=True)
class DtExtrapolation:
    """A dt study on one grid, extrapolated to dt → 0 (`dt_extrapolation`).

    Attributes
    ----------
    nodes, cells_per_step
        The grid and the time steps (cell crossings T/N per step, coarse to fine).
    rows
        One per time step, as `dt_study`'s.
    richardson, error, order
        Of every quantity of `STUDY_KEYS` (`extrapolate`: first-order Richardson value from the
        two finest steps, its estimated error with three steps, observed order); with a single
        step, that step's values and no error.
    full_contact
        Of the finest step.
    success, message
        Whether every step is an answer, and what the steps say.
    results
        The `TamaasResult` of each step.
    """

    nodes: int
    cells_per_step: tuple
    rows: list
    richardson: dict
    error: dict
    order: dict
    full_contact: bool
    success: bool
    message: str
    results: tuple = field(repr=False, default=())

    def scalars(self):
        """The extrapolated scalars (STUDY_KEYS, None where undefined) and full_contact."""
        return {"full_contact": self.full_contact, **self.richardson}

    def fields(self):
        """σ, v/h and gap/h extrapolated to dt → 0 the same way, point by point (the two finest
        steps; the finest step's own with one step), on Tamaas's grid."""
        rs = self.results
        fine = rs[-1].fields()
        if len(rs) < 2:
            return fine
        coarse = rs[-2].fields()
        dc, df = rs[-2].dt, rs[-1].dt
        return Fields(fine.x_over_lambda, *(richardson(np.asarray(getattr(coarse, k)),
                                                       np.asarray(getattr(fine, k)), 1.0, dc / df)
                                            for k in ("pressure", "displacement", "gap")))


def dt_extrapolation(*, load, speed, ratio=RATIO, hk=HK, nodes=512, cells_per_step=CELLS_PER_STEP,
                     progress=None, **options):
    """`solve` at dt = c·T/N for each c of ``cells_per_step`` and the values at dt → 0.

    The same study as `dt_study` (and as the report's, through `extrapolate`), given in cell
    crossings, keeping each step's result so that the fields are extrapolated too.

    Parameters
    ----------
    load, speed, ratio, hk, nodes
        As in `solve`.
    cells_per_step : sequence of float
        Time steps in units of T/N (the time the indenter takes to cross a cell), sorted here
        coarse to fine; default 4, 2, 1.  One value: no extrapolation.
    progress : callable, optional
        Called with each step's row (see `dt_study`) as it finishes.
    **options
        tolerance, steady_rtol, max_periods (passed to `solve`).

    Returns
    -------
    DtExtrapolation

    Raises
    ------
    ValueError
        Bad input (``cells_per_step``: positive numbers, distinct after snapping).
    """
    v = validate(load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes)
    allowed = "one or more time steps > 0 in cell crossings T/N"
    cells = sorted(series("cells_per_step", cells_per_step, allowed, lambda c: c > 0.0),
                   reverse=True)
    if not cells:
        raise bad("cells_per_step", cells_per_step, allowed)
    t_cell = _TWO_PI / (v["speed"] * v["nodes"])
    results = []
    rows = _study_rows([c * t_cell for c in cells], progress=progress, results=results,
                       load=load, speed=speed, ratio=ratio, hk=hk, nodes=nodes, **options)
    used = [r["dt"] for r in rows]
    if len(set(used)) != len(used):
        raise bad("cells_per_step", cells_per_step, "time steps that stay distinct after "
                  "snapping to the grid (see solve)")
    if len(rows) >= 2:
        ext = extrapolate(rows)
    else:
        ext = {"richardson": {k: rows[0][k] for k in STUDY_KEYS},
               "error": dict.fromkeys(STUDY_KEYS), "order": dict.fromkeys(STUDY_KEYS)}
    ok = all(r.success for r in results)
    failed = [f"dt = {c:g} T/N: {r.message}" for c, r in zip(cells, results) if not r.success]
    message = ("; ".join(failed) if failed else
               f"{len(rows)} time steps ({', '.join(f'{c:g}' for c in cells)} × T/N), "
               + ("extrapolated to dt → 0" if len(rows) >= 2 else "no extrapolation"))
    return DtExtrapolation(nodes=int(nodes), cells_per_step=tuple(cells), rows=rows,
                           richardson=ext["richardson"], error=ext["error"], order=ext["order"],
                           full_contact=bool(results[-1].full_contact), success=ok,
                           message=message, results=tuple(results))


# ----------------------------------------------------------------------------- the table
def friction_peak(*, load, ratio=RATIO, hk=HK):
    """The speed V/V0 of the largest μ on the semi-analytic road, and that μ.

    A log-spaced scan of 61 speeds over 1e-3 ≤ V/V0 ≤ 1e3, refined by bounded Brent.
    """
    from scipy.optimize import minimize_scalar

    from .. import roads  # the comparison layer reaches the roads; the adapter itself does not

    def neg_mu(lg):
        return -roads.analytic_solution({"load": load, "speed": 10.0 ** lg, "ratio": ratio,
                                         "hk": hk}).mu

    lgs = np.linspace(-3.0, 3.0, 61)
    vals = [neg_mu(x) for x in lgs]
    i = int(np.argmin(vals))
    lo, hi = lgs[max(i - 1, 0)], lgs[min(i + 1, lgs.size - 1)]
    res = minimize_scalar(neg_mu, bounds=(lo, hi), method="bounded", options={"xatol": 1e-9})
    return 10.0 ** float(res.x), -float(res.fun)


def third_code_table(*, load=0.15, ratio=RATIO, hk=HK, speeds=None, nodes=512,
                     cells_per_step=CELLS_PER_STEP, mesh_check=False, **options):
    """Tamaas against the semi-analytic road: μ per dt, order, Richardson μ, analytic μ.

    Parameters
    ----------
    load, ratio, hk : float
        The operating point (default the paper's ratio 3, hk 1 at p̃∞ = 0.15).
    speeds : sequence of float, optional
        V/V0; default below, at and above the friction peak: peak/3, peak, 3·peak, the peak
        from `friction_peak`.
    nodes : int
        Tamaas's grid.
    cells_per_step : sequence of float
        The time steps of each dt study, in cell crossings (T/N): default 4, 2, 1.
    mesh_check : bool
        Add the extrapolation at N/2 (see `dt_study`).

    Returns
    -------
    dict
        Plain data: ``inputs``, ``peak_speed``, ``peak_mu``, ``rows`` (one per speed and dt:
        speed, dt/τ, dt/T, N, μ, Δ/h, ka, steps, periods, wall time), ``summary`` (one per
        speed: μ per dt, observed order, Richardson μ and its estimated error, analytic μ,
        relative difference, Δ/h and ka extrapolated and analytic, N, wall time).
    """
    from .. import roads

    peak, peak_mu = friction_peak(load=load, ratio=ratio, hk=hk)
    if speeds is None:
        speeds = (peak / 3.0, peak, 3.0 * peak)
    rows, summary = [], []
    for sp in speeds:
        t_cell = _TWO_PI / (sp * nodes)
        st = dt_study(load=load, speed=sp, ratio=ratio, hk=hk, nodes=nodes,
                      dts=[c * t_cell for c in cells_per_step], mesh_check=mesh_check, **options)
        a = roads.analytic_solution({"load": load, "speed": sp, "ratio": ratio, "hk": hk})
        for r in st["rows"]:
            rows.append({"speed": sp, **{k: r[k] for k in (
                "dt", "dt_over_period", "nodes", "mu", "penetration", "ka", "ke_hat", "steps",
                "periods", "wall_time", "success")}})
        R, E = st["richardson"], st["error"]
        summary.append({
            "speed": sp, "nodes": nodes, "mu_per_dt": [r["mu"] for r in st["rows"]],
            "dt_over_period": [r["dt_over_period"] for r in st["rows"]],
            "order": st["order"]["mu"], "mu_richardson": R["mu"], "mu_error": E["mu"],
            "mu_analytic": a.mu,
            "relative_difference": None if R["mu"] is None else R["mu"] / a.mu - 1.0,
            "penetration_richardson": R["penetration"], "penetration_analytic": a.penetration,
            "ka_richardson": R["ka"], "ka_analytic": a.ka,
            "ke_hat_richardson": R["ke_hat"], "ke_hat_analytic": a.ke_hat,
            "mesh": None if st["mesh"] is None else st["mesh"]["difference"]["mu"],
            "wall_time": st["wall_time"], "steps": sum(r["steps"] for r in st["rows"]),
            "success": st["success"]})
    return {"inputs": {"load": load, "ratio": ratio, "hk": hk, "nodes": nodes,
                       "cells_per_step": list(cells_per_step), **options},
            "peak_speed": peak, "peak_mu": peak_mu, "rows": rows, "summary": summary,
            "tamaas_version": tamaas_version()}


def tamaas_version():
    """The version of the installed tamaas (its ``__version__``); ImportError as in `solve`."""
    return str(_import_tamaas().__version__)


def format_table(data):
    """The summary of `third_code_table` as a Markdown table (with its parameters above it)."""
    inp = data["inputs"]
    lines = [f"Tamaas {data['tamaas_version']} against the semi-analytic road: p̃∞ = "
             f"{inp['load']:g}, E∞/E0 = {inp['ratio']:g}, hk = {inp['hk']:g}, dt = "
             f"{', '.join(f'{c:g}' for c in inp['cells_per_step'])} × T/N (T the period "
             f"transit time); friction peak at V/V0 = {data['peak_speed']:.4g} (μ = "
             f"{data['peak_mu']:.5f}).",
             "",
             "| V/V0 | N | μ per dt (coarse → fine) | order | Richardson μ | est. dt error | "
             "analytic μ | relative difference | wall time |",
             "|---|---|---|---|---|---|---|---|---|"]
    for s in data["summary"]:
        order = "–" if s["order"] is None else f"{s['order']:.2f}"
        err = "–" if s["mu_error"] is None else f"{s['mu_error']:.1e}"
        rd = "–" if s["relative_difference"] is None else f"{s['relative_difference']:+.1e}"
        rich = "–" if s["mu_richardson"] is None else f"{s['mu_richardson']:.6f}"
        lines.append(f"| {s['speed']:.4g} | {s['nodes']} | "
                     f"{', '.join(f'{m:.5f}' for m in s['mu_per_dt'])} | {order} | {rich} | "
                     f"{err} | {s['mu_analytic']:.6f} | {rd} | {s['wall_time']:.0f} s |")
    return "\n".join(lines)
