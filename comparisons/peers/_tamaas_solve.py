"""Tamaas as a third code: its inputs (`ACCEPTED`, `validate`), its import, and one run
stepped to steady sliding (`solve`; Tamaas's model in `_E_TAMAAS`, `_NU`, `_ESTAR0`).  Part of
`comparisons.peers.tamaas` (whose docstring says what Tamaas computes), which re-exports it.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass, replace

import numpy as np

from viscosine import Fields
from viscosine.checks import bad, integer, real

from .. import operating_point as _op
from ._tamaas_result import _TWO_PI, TamaasResult, _measure, _stepping

#: E∞/E0 and hk where a caller names none: the operating point's defaults (written once there)
RATIO, HK = _op.DEFAULTS["ratio"], _op.DEFAULTS["hk"]

#: the Tamaas versions this adapter was verified on (its conventions are measured, not assumed)
TAMAAS_REQUIREMENT = "tamaas>=2.9,<2.10"
_INSTALL = "pip install 'viscosine[peers]' (from a clone of the repository: pip install '.[peers]')"

# Tamaas's model: G∞ = model.mu = 1 (its update is right only then), ν = 0, E = 2(1 + ν) G∞
_NU = 0.0
_E_TAMAAS = 2.0 * (1.0 + _NU)
_ESTAR0 = _E_TAMAAS / (1.0 - _NU * _NU)  # relaxed plane-strain modulus in Tamaas units: 2

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
