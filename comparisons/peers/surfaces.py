"""Third codes on periodic 2-D surfaces (three-dimensional contact): Tamaas and ContactMechanics.

Nobody on this project wrote either code.  On a rigid periodic surface z = h(x, y) pressed into
a half-space they give the elastic frictionless contact (`tamaas_elastic`,
`contactmechanics_elastic`: two Polonsky–Keer solvers on the same nodal FFT operator), and
Tamaas's transient viscoelastic solver, stepped with the surface moving until the sliding is
steady, gives the viscoelastic one (`tamaas_viscoelastic_surface`).  They witness the project's
surface solver without sharing any of its numerics.

* Tamaas (L. Frérot, G. Anciaux, V. Rey, S. Pham-Ba and J.-F. Molinari, *Tamaas: a library for
  elastic-plastic contact of periodic rough surfaces*, J. Open Source Softw. 5, 2121 (2020)):
  ``model_type.basic_2d`` with ``PolonskyKeerRey`` (elastic) or ``MaxwellViscoelastic``
  (a generalised Maxwell solid stepped by backward Euler; version 2.9 provides it on
  ``basic_2d``, measured here).
* ContactMechanics (Pastewka group, with SurfaceTopography and muGrid):
  ``PeriodicFFTElasticHalfSpace`` and its constrained conjugate-gradient solver
  (``make_system(...).minimize_proxy``).

What the codes compute (Tamaas 2.9.0, ContactMechanics 1.8.3; measured, written where it bites)
---------------------------------------------------------------------------------------------
* Both take the heights as the indenter's protrusion into the body (the crest is the largest
  value), the displacement u positive into the body and gap = u − z − (rigid approach) ≥ 0,
  the pressure positive in compression, and impose the mean pressure.  Their pressures are
  nodal values under the continuum's symbol 2/(E*|q|) on every grid mode (Nyquist modes
  included): on the same grid the two solve the same discrete problem, and agree to their
  tolerances (measured 6e-12 of the peak pressure at 1e-12 on a 64² bi-sinusoid).
* Tamaas's system size [Lx, Ly] goes with the array axes (0, 1); ContactMechanics's
  ``physical_sizes`` likewise.  Tamaas writes its iteration log through Python's standard
  error at its default log level; its last line gives the iterations of an elastic solve.
* ``MaxwellViscoelastic`` on ``basic_2d``: as on ``basic_1d`` (see
  `comparisons.peers.tamaas`), its branch moduli are shear moduli in units of ``model.mu``,
  which must be 1 (G∞ = 1, E = 2, ν = 0, so its relaxed plane-strain modulus is 2), and its
  times are RELAXATION times: the standard linear solid with E∞/E0 = ``ratio`` and creep time
  τ is one branch of modulus ratio − 1 and time τ/ratio.

Units and grid (the project's surface conventions)
--------------------------------------------------
Heights are given as k·z (k = 2π/Lx), an array of shape (nx, ny) indexed [i_x, i_y], node
(i, j) at x/Lx = i/nx − ½, y/Lx = (j/ny − ½)·Ly/Lx (``aspect`` = Ly/Lx): the bi-sinusoid
k z = hk [cos kx + cos ky] has its crest at (nx/2, ny/2).  Why k·z and not z/h_ref: the
contact depends on the amplitude, and k·z is what the line's profile files carry.  h_ref =
max z − mean z.  Outputs: pressure σ(1 − ν²)/E0 (E0 the relaxed modulus), displacement
(u − mean u)/h_ref into the body, gap/h_ref (0 in contact), separation s/h_ref (s the mean
gap), penetration Δ/h_ref = 1 − s/h_ref, contact_fraction (nodes in contact over nodes),
n_patches (patches of nodes in contact connected through their four neighbours on the periodic
grid), max_pressure.  Speeds V/V0 = V τ k, τ the creep time.  In Tamaas's units Lx = 1 (z_T =
k z/2π) and pressures are in G∞, so σ̃ = p_T/2; in ContactMechanics's the period is 2π (lengths
in 1/k) and E* is the modulus asked, so its pressures are σ̃ already.

Sliding and the steady state
----------------------------
The surface moves along a grid axis (θ = 0, 90, 180 or 270°) by whole cells per step, or by a
cell in whole steps (sub-cell positions from the trigonometric interpolant of the heights), so
that after every period it is back on the grid where it started and the lab fields at a period
end are the surface-frame fields; the run is steady by the line adapter's rule (the change
over a period and its geometric tail), and backward Euler's first-order error in dt is removed
by Richardson extrapolation over the time steps, as on the line.  What is new in 2-D: a mode of
the pressure that is constant along V (wavevector normal to V: present in any contact of a
2-D surface, not in the line's) does not move in the lab frame, so it sees the relaxed modulus
and settles over the creep time τ, not over a period.  The periods to steady sliding therefore
grow like V/V0 beyond V/V0 ≈ 1 (measured on the 32² bi-sinusoid: 2 periods at 0.1, 3 at 1, 14
at 10, 119 at 100), and the high-speed limit is not the glassy solution (it is glassy for the
modes that move, relaxed for those that do not): a run that starts glassy at V/V0 = 1e8 is
reported not steady, rightly.

Friction: the force the solid exerts on the surface is ∫σ ∇u dA (the body's outward normal
carries the slope of its deformed surface), so μ = −mean(σ ∂_V u)/p̄, positive when it resists
the motion (the line's τf/p∞, generalised), and μ_lateral = mean(σ ∂_⊥ u)/p̄ along
(−sin θ, cos θ); ∂ is the spectral derivative on the grid (Nyquist mode dropped).

References
----------
Frérot et al., J. Open Source Softw. 5, 2121 (2020) (Tamaas); Polonsky & Keer, Wear 231, 206
(1999) (both solvers); Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392
(2014), eq. (2.3) (the standard linear solid).
"""
from __future__ import annotations

import contextlib
import io
import math
import time

import numpy as np

from viscosine.checks import bad, series

from ..convergence import richardson
from ..fields import count_patches  # noqa: F401  (part of the interface)
from ._surfaces_grid import (_TWO_PI, ACCEPTED, DIRECTION, DIRECTIONS, HK,  # noqa: F401
                             RATIO, STEP_KEYS, _complementarity, _direction, _fields, _heights,
                             _integer, _measure, _modulus, _real, bisinusoid, grid)
from ._tamaas_result import _stepping
from ._tamaas_solve import (_E_TAMAAS, _ESTAR0, _NU, _change, _import_tamaas, _SteadyRun,
                            _steps_per_period, _verdict, steadiness)
from .contactmechanics import _import_contactmechanics
from .tamaas import CELLS_PER_STEP, _order


# ----------------------------------------------------------------------------- elastic
def _last_iteration(log):
    """The iteration number on the last line of Tamaas's log (None if there is none)."""
    for line in reversed(log.strip().splitlines()):
        first = line.split()[:1]
        if first and first[0].isdigit():
            return int(first[0])
    return None


def _elastic_record(code, version, ok, message, sigma, u, gap, z, h_ref, aspect, load, m, tol,
                    iterations, wall, error=None):
    """The plain dict an elastic solve returns (see `tamaas_elastic`)."""
    meas = _measure(sigma, u, z, h_ref, aspect, direction=None)
    return {"code": code, "version": version, "success": bool(ok), "message": message,
            "load": meas["load"], "load_asked": load, "modulus": m, "aspect": aspect,
            "shape": tuple(sigma.shape), "hk_ref": h_ref,
            "penetration": meas["penetration"], "separation": meas["separation"],
            "contact_fraction": meas["contact_fraction"], "full_contact": meas["full_contact"],
            "max_pressure": meas["max_pressure"], "n_patches": meas["n_patches"],
            "fields": _fields(sigma, u, gap, h_ref, aspect),
            "iterations": iterations, "wall_time": wall, "solver_error": error,
            "tolerance": tol, "complementarity": _complementarity(sigma, gap, h_ref),
            "load_error": abs(meas["load"] / load - 1.0)}


def tamaas_elastic(heights, aspect=1.0, *, load, modulus="relaxed", ratio=RATIO, tolerance=1e-8):
    """The elastic frictionless contact of a periodic surface by Tamaas's Polonsky–Keer solver.

    Parameters
    ----------
    heights : array_like, shape (nx, ny)
        k·z at x/Lx = i/nx − ½, y/Lx = (j/ny − ½)·aspect, positive toward the body.
    aspect : float
        Ly/Lx.
    load : float
        Mean pressure p̃ = p(1 − ν²)/E0.
    modulus : {'relaxed', 'glassy'} or float
        The half-space's plane-strain modulus: E0 ('relaxed'), E∞ = ratio·E0 ('glassy'), or
        E*/(E0/(1 − ν²)) itself.
    ratio : float
        E∞/E0, for 'glassy'.
    tolerance : float
        Tamaas's tolerance (its relative error measure).

    Returns
    -------
    dict
        ``code``, ``version``, ``success``, ``message``; ``load`` (the mean of σ̃ over the
        nodes) and ``load_asked``; ``modulus`` (E* in E0/(1 − ν²)), ``aspect``, ``shape``,
        ``hk_ref`` (k·h_ref); ``penetration`` Δ/h_ref, ``separation`` s/h_ref,
        ``contact_fraction``, ``full_contact``, ``max_pressure``, ``n_patches``; ``fields``
        (``x``, ``y``, ``pressure``, ``displacement``, ``gap``: see the module's units);
        ``iterations``, ``wall_time`` (s), ``solver_error``, ``tolerance``,
        ``complementarity`` (largest |gap|/h_ref in contact), ``load_error``.

    Raises
    ------
    ValueError
        Bad input (``"name=value is not allowed: ..."``).
    ImportError
        tamaas is not installed.
    """
    z, h_ref = _heights(heights)
    aspect, load = _real("aspect", aspect), _real("load", load)
    m, tol = _modulus(modulus, ratio), _real("tolerance", tolerance)
    tm = _import_tamaas()
    nx, ny = z.shape
    surface = np.array(z / _TWO_PI, order="C")  # Tamaas's unit of length is Lx
    start = time.perf_counter()
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, aspect], [nx, ny])
    model.E, model.nu = _E_TAMAAS * m, _NU  # E* = 2m: the relaxed modulus is 2, as in the line
    solver = tm.PolonskyKeerRey(model, surface, tol)
    log, level = io.StringIO(), tm.get_log_level()
    tm.set_log_level(tm.LogLevel.info)  # its last line counts the iterations
    try:
        with contextlib.redirect_stderr(log):
            error = float(solver.solve(load * _ESTAR0))
    finally:
        tm.set_log_level(level)
    wall = time.perf_counter() - start
    sigma = np.array(model.traction, dtype=float) / _ESTAR0
    u = np.array(model.displacement, dtype=float) * _TWO_PI  # back to 1/k, as the heights
    gap = np.array(model["gap"], dtype=float) * _TWO_PI
    ok = error <= tol * (1.0 + 1e-6)
    message = (f"converged: error {error:.1e}" if ok else
               f"Tamaas's solver stopped at error {error:.1e} > tolerance {tol:g}")
    return _elastic_record("tamaas", str(tm.__version__), ok, message, sigma, u, gap, z, h_ref,
                           aspect, load, m, tol, _last_iteration(log.getvalue()), wall, error)


def contactmechanics_elastic(heights, aspect=1.0, *, load, modulus="relaxed", ratio=RATIO,
                             tolerance=1e-8, max_iterations=100000):
    """The elastic frictionless contact of a periodic surface by ContactMechanics.

    ``PeriodicFFTElasticHalfSpace`` on the (nx, ny) grid of period 2π × 2π·aspect (lengths in
    1/k) with E* = the modulus asked, and its constrained conjugate-gradient solver under load
    control.

    Parameters
    ----------
    heights, aspect, load, modulus, ratio
        As in `tamaas_elastic`.
    tolerance : float
        Its tolerances: penetration ``pentol`` = tolerance·k·h_ref, force outside the contact
        ``forcetol`` = tolerance·p̃·(area per node), relative changes ``thermotol`` = tolerance.
    max_iterations : int
        Its iteration cap.

    Returns
    -------
    dict
        As `tamaas_elastic`'s (``solver_error`` None).

    Raises
    ------
    ValueError
        Bad input.
    comparisons._errors.MissingPackage
        ContactMechanics is not installed.
    """
    z, h_ref = _heights(heights)
    aspect, load = _real("aspect", aspect), _real("load", load)
    m, tol = _modulus(modulus, ratio), _real("tolerance", tolerance)
    maxiter = _integer("max_iterations", max_iterations)
    cls, make_system, topography_cls, version = _import_contactmechanics()
    sizes = (_TWO_PI, _TWO_PI * aspect)
    start = time.perf_counter()
    sub = cls(z.shape, m, physical_sizes=sizes, poisson=0.0)  # E* = young/(1 − ν²) = m
    system = make_system(substrate=sub, surface=topography_cls(z, physical_sizes=sizes,
                                                                periodic=True))
    area = float(sub.area_per_pt)
    res = system.minimize_proxy(external_force=load * sizes[0] * sizes[1], pentol=tol * h_ref,
                                forcetol=tol * load * area, thermotol=tol, maxiter=maxiter)
    wall = time.perf_counter() - start
    sigma = np.asarray(res.jac, dtype=float) / area  # p̃ at the nodes, compression > 0
    offset = float(res.offset)
    u = np.asarray(res.x, dtype=float) - offset  # so that gap = u − z, as Tamaas's
    return _elastic_record("contactmechanics", version, res.success, str(res.message), sigma,
                           u, u - z, z, h_ref, aspect, load, m, tol, int(res.nit), wall)


# ----------------------------------------------------------------------------- viscoelastic
def _shifted(z, axis, sign, s_steps):
    """The surface moved by k/s of a cell along the motion, k < s, by its trigonometric
    interpolant (k = 0: the heights themselves): every step's surface is one of them rolled by
    whole cells, so the motion is bitwise periodic."""
    out = [z]
    n = z.shape[axis]
    if s_steps > 1:
        shape = [1, 1]
        shape[axis] = n
        modes = np.fft.fftfreq(n, 1.0 / n).reshape(shape)
        zh = np.fft.fft(z, axis=axis)
        for k in range(1, s_steps):
            phase = np.exp(-2j * math.pi * modes * sign * k / (s_steps * n))
            out.append(np.ascontiguousarray(np.real(np.fft.ifft(zh * phase, axis=axis))))
    return out


def _snapshot(model, z, h_ref, aspect, direction):
    """(σ̃, u, gap, scalars) at a period end, when the surface is back where it started: the
    lab frame is then the surface's (lengths in Lx)."""
    sigma = np.array(model.traction, dtype=float) / _ESTAR0
    u = np.array(model.displacement, dtype=float)
    gap = np.array(model["gap"], dtype=float)
    return sigma, u, gap, _measure(sigma, u, z, h_ref, aspect, direction)


def _run_steady(tm, z, h_ref, aspect, motion, stepping, v):
    """Tamaas's Maxwell solid under the moving surface, one period at a time, until steady
    (`comparisons.peers.tamaas`'s rule: the change over a period, and its geometric tail, below
    ``steady_rtol``, or the change at Tamaas's tolerance)."""
    direction, axis, sign = motion
    m_cells, s_steps, dt = stepping
    n = z.shape[axis]
    base = _shifted(z, axis, sign, s_steps)
    surface = np.array(z, order="C")  # Tamaas keeps a view of it: updated in place
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, aspect], list(z.shape))
    model.E, model.nu = _E_TAMAAS, _NU  # G∞ = model.mu = 1: its update is right only then
    solver = tm.MaxwellViscoelastic(model, surface, v["tolerance"], dt, [v["ratio"] - 1.0],
                                    [1.0 / v["ratio"]])  # relaxation time τ E0/E∞
    target = v["load"] * _ESTAR0
    per_period = _steps_per_period(n, stepping)
    history, prev, steps = [], None, 0
    for period_no in range(1, v["max_periods"] + 1):
        worst = 0.0
        for _ in range(per_period):
            steps += 1
            cells, k = divmod(steps * m_cells, s_steps)
            surface[:] = np.roll(base[k], sign * (cells % n), axis=axis)
            worst = max(worst, float(solver.solve(target)))
        snap = _snapshot(model, z, h_ref, aspect, direction)
        steady, tail = False, math.inf
        if prev is not None:
            history.append(_change(prev, snap, h_ref))
            steady, tail = steadiness(history, v)
            if steady:
                break
        prev = snap
    return _SteadyRun(snap, history, steps, period_no, steady, tail, worst)


def _steppings(cells, shape, motion, v):
    """`comparisons.peers.tamaas`'s (cells per step, steps per cell, dt) nearest each of
    ``cells`` cell crossings per step, along the motion (period Lx, or Ly along y)."""
    axis = motion[1]
    n = shape[axis]
    length = 1.0 if axis == 0 else v["aspect"]  # the period along the motion, in Lx
    t_cell = _TWO_PI * length / (v["speed"] * n)  # units of τ
    return [_stepping(c * t_cell, v["speed"] / length, n) for c in cells]


def _one_step_size(tm, z, h_ref, aspect, motion, stepping, v):
    """One run to steady sliding with ``stepping`` (a row of the study) and its fields."""
    length = 1.0 if motion[1] == 0 else aspect
    start = time.perf_counter()
    run = _run_steady(tm, z, h_ref, aspect, motion, stepping, v)
    wall = time.perf_counter() - start
    success, _, message = _verdict(run, v["tolerance"], v["steady_rtol"])
    sigma, u, gap, meas = run.snapshot
    row = {"cells_per_step": stepping[0] / stepping[1], "steps_per_cell": stepping[1],
           "dt": stepping[2], "dt_over_period": stepping[2] * v["speed"] / (_TWO_PI * length),
           "steps": run.steps, "periods": run.periods, "wall_time": wall,
           "success": success, "message": message, "steady_residual": run.residual,
           "steady_tail": run.tail if math.isfinite(run.tail) else None,
           "solver_error": run.worst,
           "complementarity": _complementarity(sigma, gap, h_ref),
           **{k: meas[k] for k in ("load", "full_contact", "n_patches", "separation",
                                   *STEP_KEYS)}}
    return row, _fields(sigma, u, gap, h_ref, aspect)


def _extrapolated(rows, keys):
    """First-order Richardson value, its estimated error and the observed order of each key
    (rows coarse → fine), by the rule of `comparisons.peers.tamaas.extrapolate`."""
    dts = [r["dt"] for r in rows]
    rich, err, order = {}, {}, {}
    for k in keys:
        q = [r[k] for r in rows]
        if len(q) < 2:
            rich[k], err[k], order[k] = q[-1], None, None
            continue
        rich[k] = richardson(q[-2], q[-1], 1.0, dts[-2] / dts[-1])
        err[k] = order[k] = None
        if len(q) >= 3:
            coarser = richardson(q[-3], q[-2], 1.0, dts[-3] / dts[-2])
            err[k] = abs(rich[k] - coarser) / (dts[-3] / dts[-1] - 1.0)
            order[k] = _order(dts[-3:], q[-3:])
    return rich, err, order


def tamaas_viscoelastic_surface(heights, aspect=1.0, *, load, speed, direction=DIRECTION,
                                ratio=RATIO, cells_per_step=CELLS_PER_STEP, tolerance=1e-10,
                                steady_rtol=1e-6, max_periods=400):
    """Tamaas's viscoelastic solver under a sliding periodic surface, stepped to steady sliding
    at several time steps and extrapolated to dt → 0.

    The material (the standard linear solid, one Maxwell branch) stays at rest; the surface
    moves along V by a whole number of cells per step, or by one cell in a whole number of
    steps (sub-cell positions from the trigonometric interpolant of the heights), so that after
    every period (Lx/V, or Ly/V along y) it is back where it started and the lab fields are the
    surface-frame fields.  At every period end the change since the last is measured; a run is
    steady by the rule of `comparisons.peers.tamaas.solve`.  Backward Euler is first order in
    dt: the values of the two finest steps are extrapolated (Richardson), and with three steps
    the change of that extrapolation estimates its error, as the line adapter does.  The
    modes of the pressure constant along V settle over the creep time, not a period: beyond
    V/V0 ≈ 1 the periods to steady sliding grow like V/V0 (module docstring).

    Parameters
    ----------
    heights, aspect
        As in `tamaas_elastic` (k·z on the grid; Ly/Lx).
    load : float
        p̃∞ = p∞(1 − ν²)/E0, the mean pressure over the cell.
    speed : float
        V/V0 = Vτk, τ the creep time.
    direction : float
        θ in degrees from +x: 0, 90, 180 or 270 (modulo 360), a motion along a grid axis.
    ratio : float
        E∞/E0 > 1.
    cells_per_step : float or sequence of float
        Time steps in cell crossings (the time V takes over one cell): a whole number of cells
        dividing the nodes along V, or below 1 a cell in a whole number of steps (snapped to
        the nearest; the step used is in each row).  Default 4, 2, 1; one value, no
        extrapolation.
    tolerance : float
        Tamaas's tolerance per step.
    steady_rtol : float
        Steady when the relative change of the fields and scalars over one period, and the
        geometric tail of those changes, are below this.
    max_periods : int
        Periods after which an unsteady run is a failure.

    Returns
    -------
    dict
        ``success``, ``message``; the scalars ``mu``, ``mu_lateral``, ``tau_f``,
        ``penetration``, ``contact_fraction``, ``max_pressure`` extrapolated to dt → 0 (the
        finest step's with one step), ``error`` and ``order`` of each (None where undefined);
        ``load``, ``full_contact``, ``n_patches`` and ``separation`` of the finest step;
        ``fields`` (``x``, ``y``, ``pressure``, ``displacement``, ``gap`` extrapolated point by
        point, and ``load``, ``speed``, ``direction``: the conventions' ``.npz`` keys) and
        ``fields_finest`` (the finest step's, which hold σ ≥ 0 and gap ≥ 0 exactly);
        ``rows`` (one per time step, coarse → fine: the step, steps, periods, wall time,
        verdict, steadiness, the scalars); the cost ``steps`` and ``wall_time`` (s) in all;
        ``inputs`` and ``tamaas_version``.

    Raises
    ------
    ValueError
        Bad input (``"name=value is not allowed: ..."``).
    ImportError
        tamaas is not installed.

    References
    ----------
    Eq. (2.3) of the paper (τ the creep time); Frérot et al. (2020) (Tamaas).
    """
    z, h_ref = _heights(heights)
    motion = _direction(direction)
    v = {name: _real(name, value) for name, value in (
        ("aspect", aspect), ("load", load), ("speed", speed), ("ratio", ratio),
        ("tolerance", tolerance), ("steady_rtol", steady_rtol))}
    v["max_periods"] = _integer("max_periods", max_periods)
    allowed = "one or more time steps > 0 in cell crossings, distinct after snapping"
    cells = sorted(series("cells_per_step", cells_per_step, allowed, lambda c: c > 0.0),
                   reverse=True)
    if not cells:
        raise bad("cells_per_step", cells_per_step, allowed)
    steppings = _steppings(cells, z.shape, motion, v)
    if len({st[2] for st in steppings}) != len(steppings):
        raise bad("cells_per_step", cells_per_step, allowed)
    tm = _import_tamaas()
    z_t, h_t = z / _TWO_PI, h_ref / _TWO_PI  # Tamaas's unit of length is Lx
    level = tm.get_log_level()
    tm.set_log_level(tm.LogLevel.error)  # Tamaas logs every solve at the info level
    start = time.perf_counter()
    rows, fields = [], []
    try:
        for stepping in steppings:
            row, f = _one_step_size(tm, z_t, h_t, v["aspect"], motion, stepping, v)
            rows.append(row)
            fields.append(f)
    finally:
        tm.set_log_level(level)
    rich, err, order = _extrapolated(rows, STEP_KEYS)
    out_fields = dict(fields[-1])
    if len(rows) >= 2:
        ratio_dt = rows[-2]["dt"] / rows[-1]["dt"]
        for k in ("pressure", "displacement", "gap"):
            out_fields[k] = richardson(fields[-2][k], fields[-1][k], 1.0, ratio_dt)
    out_fields.update(load=rows[-1]["load"], speed=v["speed"], direction=motion[0])
    ok = all(r["success"] for r in rows)
    steps_used = [r["cells_per_step"] for r in rows]
    failed = [f"{r['cells_per_step']:g} cells per step: {r['message']}" for r in rows
              if not r["success"]]
    message = ("; ".join(failed) if failed else
               f"{len(rows)} time steps ({', '.join(f'{c:g}' for c in steps_used)} cell "
               "crossings), " + ("extrapolated to dt → 0" if len(rows) >= 2 else
                                       "no extrapolation"))
    fine = rows[-1]
    return {"success": ok, "message": message, **rich, "error": err, "order": order,
            "load": fine["load"], "full_contact": fine["full_contact"],
            "n_patches": fine["n_patches"], "separation": fine["separation"],
            "fields": out_fields, "fields_finest": fields[-1], "rows": rows,
            "steps": sum(r["steps"] for r in rows), "wall_time": time.perf_counter() - start,
            "inputs": {"shape": tuple(z.shape), "hk_ref": h_ref, "direction": motion[0],
                       "cells_per_step": cells, **v},
            "tamaas_version": str(tm.__version__)}
