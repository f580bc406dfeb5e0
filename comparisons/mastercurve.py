"""`python -m comparisons mastercurve`: the friction master curve μ(V) of a material at several
temperatures, every point a boundary-element solve.

    python -m comparisons mastercurve (--material FILE | --E0 E --Einf E (--tau-creep S | --tau-relax S))
        [--wlf C1 C2 TREF | --shift-table FILE] --temperatures T [T ...] --speeds V [V ...]
        --load P --wavelength L --amplitude H --nu NU [--nodes N | --rtol R]
        [--max-residual B] [--per-decade K] [--out DIR]

Without --wlf or --shift-table the material is solved as given, at the one temperature it holds
at: ``--temperatures`` then takes that one value, which labels the curve (a_T = 1, `NoShift`).
The material is a file or the standard linear solid of ``--E0 --Einf`` [Pa] with its creep time
``--tau-creep`` (τ of eq. 2.3) or its relaxation time ``--tau-relax`` (τ E0/E∞) [s], as
``point --units SI`` takes it (`standard_linear_solid`).

SI throughout: ``--speeds`` V [m/s] (values or log ranges START:STOP:COUNT), ``--load`` the mean
pressure p∞ [Pa], ``--wavelength`` λ and ``--amplitude`` h [m] of the rigid sinusoid.  The
material is any file `comparisons._materials` reads (creep or relaxation series in Pa and s, or
a DMA master curve whose header names its modulus unit), taken at the shift's reference
temperature; at T every time is multiplied by a_T(T).  Its reference units are its relaxed
modulus E_r and 1 s (the speed group is V k × 1 s), the same at every temperature, so a point
(V, T) is the point (a_T V, T_ref): the curves collapse onto one against the reduced speed a_T V.

Each point goes through `comparisons.runner.run` (`bem.solve` and the last line of defence).
Written into ``--out`` (default ``./mastercurve``):

* ``points.csv``: one row per finished point, appended and flushed as each is done (an
  interrupted run loses nothing; the same command run again takes the finished points from it
  and solves the rest);
* ``mastercurve.json``: the parameters (with the material's file, SHA-256, fit residuals) and
  every point, when the run ends;
* ``shifts.png`` (raw isotherms as the material, moved by the WLF fitted to them): their
  shifts with their errors, the WLF and the range where it holds; the shift table is printed on
  standard error;
* ``mastercurve.png``: μ against log V, one curve per temperature, and μ against the reduced
  speed a_T V (hollow markers: the modulus was extrapolated beyond the DMA window).

Without ``--nodes`` the mesh is refined until the estimated relative error of μ (and the other
scalars) is below ``--rtol`` (default 1e-3): 0.35–1.5 s a point on a quiet core for the suite's
SBR curve at λ = 1 mm, h = 0.1 mm, p∞ = 0.1 MPa (docs/materials.md).

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): eq. (3.1) (the
friction), eqs (2.7)–(2.8) (the modulus at the sliding frequency k V).
"""
from __future__ import annotations

import json
import math
import os
import time
from dataclasses import dataclass, field

import numpy as np

from viscosine.checks import allowed_part

from . import operating_point as op
from ._errors import BadInput
from ._io import check_output_dir, jsonable, stderr, write_text
from .plots import mastercurve as figure
from .plots.materials import report_fit
from .progress import Progress

#: accuracy asked of every point without --nodes (relative, on μ, Δ/h; absolute on ka, ke)
DEFAULT_RTOL = op.DEFAULTS["mastercurve_rtol"]
#: the columns of points.csv (and the keys of each point in mastercurve.json)
COLUMNS = ("temperature", "speed", "log10_aT", "reduced_speed", "success", "mu", "mu_error",
           "friction_stress", "contact_fraction", "load", "speed_group", "nodes", "seconds",
           "extrapolated", "message")
UNITS = ("units: temperature in the unit of the shift; speed and reduced_speed (a_T V) in m/s; "
         "friction_stress in Pa; mu_error the estimated relative error of mu (NaN where the "
         "solver gives none); load p_inf (1 - nu^2)/E_ref and speed_group V k (1 s) the dimensionless groups "
         "(E_ref the relaxed modulus of the material); extrapolated 1 when the contact's "
         "harmonics probe the modulus outside the DMA window")


@dataclass(frozen=True)
class FrictionMasterCurve:
    """μ(V, T) of one material, one row per (temperature, speed), temperatures outer.

    Attributes
    ----------
    temperature, speed, log10_aT, reduced_speed : ndarray
        T (unit of the shift), V [m/s], log10 a_T(T), a_T V [m/s] (the speed at T_ref that
        gives the same point).
    success : ndarray of bool
        Whether the point is an answer (the others are NaN with their ``message``).
    mu, mu_error : ndarray
        Friction coefficient τf/p∞ (eq. 3.1) and its estimated relative error (NaN where
        the solver gives none: a fixed mesh may not).
    friction_stress, contact_fraction : ndarray
        τf [Pa] and 2a/λ.
    extrapolated : ndarray of bool
        The contact's harmonics k_n V (n = 1 … ⌈λ/2a⌉) leave the DMA window at T.
    message : tuple of str
        The solver's message, or why the point failed; extrapolation warnings appended.
    parameters : dict
        Everything that produced the table (material file, SHA-256, fit, shift, geometry).
    rows : tuple of dict
        The points as written to points.csv (keys `COLUMNS`).
    """

    temperature: np.ndarray
    speed: np.ndarray
    log10_aT: np.ndarray
    reduced_speed: np.ndarray
    success: np.ndarray
    mu: np.ndarray
    mu_error: np.ndarray
    friction_stress: np.ndarray
    contact_fraction: np.ndarray
    extrapolated: np.ndarray
    message: tuple
    parameters: dict = field(repr=False)
    rows: tuple = field(default=(), repr=False)

    @classmethod
    def from_rows(cls, rows, parameters):
        def col(name, dtype=float):
            return np.array([r[name] for r in rows], dtype=dtype)
        return cls(col("temperature"), col("speed"), col("log10_aT"), col("reduced_speed"),
                   col("success", bool), col("mu"), col("mu_error"), col("friction_stress"),
                   col("contact_fraction"), col("extrapolated", bool),
                   tuple(r["message"] for r in rows), parameters, tuple(rows))


@dataclass(frozen=True)
class NoShift:
    """The shift of a material solved only at the temperature it holds at, ``T_ref``: a_T = 1
    there (no time is moved), and no other temperature is defined."""

    T_ref: float

    def log10_aT(self, T):
        if float(T) != self.T_ref:
            raise ValueError(f"T={T!r} is not allowed: without a shift only the material's own "
                             f"temperature {self.T_ref:g}")
        return 0.0


def standard_linear_solid(E0, Einf, *, tau_creep=None, tau_relax=None):
    """The standard linear solid of the paper as a relaxation series in Pa and s:
    E(t) = E0 + (E∞ − E0) exp(−t/θ), θ = τ E0/E∞ the relaxation time of the creep time τ of
    eq. (2.3) (give exactly one of them).

    Raises
    ------
    ValueError
        Naming the command line's option (``--E0``, ``--Einf``, ``--tau-creep``, ``--tau-relax``),
        its value and what is allowed.

    References
    ----------
    Menga et al. (2014), eq. (2.3).
    """
    from viscosine import materials as vm
    from viscosine.checks import is_real

    def checked(option, v, lower, allowed):
        if not (is_real(v) and math.isfinite(float(v)) and float(v) > lower):
            raise ValueError(f"{option} {v!r} is not allowed: {allowed}")
        return float(v)
    e0 = checked("--E0", E0, 0.0, "a finite relaxed modulus > 0 [Pa]")
    einf = checked("--Einf", Einf, e0, f"a finite modulus > --E0 {e0:g} [Pa] (the solid "
                   "stiffens as it is loaded faster)")
    if (tau_creep is None) == (tau_relax is None):
        raise ValueError("--tau-creep or --tau-relax (exactly one) is required: the creep time "
                         "τ of eq. 2.3, or the relaxation time τ E0/Einf [s]")
    if tau_creep is not None:
        theta = checked("--tau-creep", tau_creep, 0.0, "a finite time > 0 [s]") * e0 / einf
    else:
        theta = checked("--tau-relax", tau_relax, 0.0, "a finite time > 0 [s]")
    return vm.Maxwell(e0, (einf - e0,), (theta,))


def _nan(v):
    return float("nan") if v is None else float(v)


def _row(T, V, log_a, out):
    """One point of the table from `runner.run`'s answer."""
    rec = out.get("record") or {}
    warn = [w for w in out.get("warnings") or [] if w.startswith("extrapolation:")]
    ok = bool(out["ok"])
    est = rec.get("error_estimate") or {}
    si = rec.get("si") or {}
    message = rec.get("message") if ok else out.get("error")
    return {"temperature": float(T), "speed": float(V), "log10_aT": float(log_a),
            "reduced_speed": float(V) * 10.0 ** log_a, "success": ok,
            "mu": _nan(rec.get("mu")) if ok else float("nan"),
            "mu_error": _nan(est.get("mu")) if ok else float("nan"),
            "friction_stress": _nan(si.get("friction_stress")) if ok else float("nan"),
            "contact_fraction": _nan(rec.get("contact_fraction")) if ok else float("nan"),
            "load": float(out["spec"]["load"]), "speed_group": float(out["spec"]["speed"]),
            "nodes": rec.get("nodes") if ok else None, "seconds": float(out.get("seconds", 0.0)),
            "extrapolated": bool(warn), "message": "; ".join([str(message or "")] + warn)}


def _key(T, V):
    return (repr(float(T)), repr(float(V)))


def friction_master_curve(material, *, shift, temperatures, speeds, mean_pressure, wavelength,
                          amplitude, nu, nodes=None, rtol=DEFAULT_RTOL, max_residual=None,
                          per_decade=None, loss_weight=None, done=None,
                          on_point=None, **data_options) -> FrictionMasterCurve:
    """Solve μ at every (temperature, speed) through `bem.solve` (via `runner.run`).

    Parameters
    ----------
    material : str or viscosine.materials.Maxwell
        A material file (creep or relaxation series in Pa and s, or a DMA curve whose header
        names its modulus unit), or a series (Pa, s; a DMA fit in its data's unit), at the
        shift's reference temperature.
    shift : viscosine.materials.WLF or viscosine.materials.ShiftTable
        a_T(T): every time of the material is multiplied by it at T.
    temperatures : sequence of float
        In the unit of the shift (a table must cover them).
    speeds : sequence of float
        V [m/s], > 0.
    mean_pressure : float
        p∞ [Pa].
    wavelength, amplitude : float
        λ and h of the rigid sinusoid [m].
    nu : float
        Poisson's ratio (also turns a file of shear moduli into tensile ones).
    nodes : int, optional
        A fixed mesh; default: adaptive to ``rtol``.
    rtol : float
        Accuracy of the adaptive mesh (default `DEFAULT_RTOL`).
    max_residual, per_decade, loss_weight : float, optional
        The DMA fit's bound, times per decade and weight of E'' against E' (DMA files only;
        `viscosine.materials.fit_prony`).
    **data_options
        The readers' and fits' other keywords, for a material file (``kind``,
        ``frequency_unit``, ``extend``, ``vertical``, ``method``:
        `comparisons._materials.DATA_OPTIONS`, docs/materials.md).
    done : dict, optional
        Rows already solved, keyed by ``(repr(T), repr(V))``: taken as they are.
    on_point : callable, optional
        ``on_point(row, index, total, reused)`` after each point (to write it, show progress).

    Returns
    -------
    FrictionMasterCurve

    Raises
    ------
    ValueError
        Bad input, before any point is solved: one line naming it as the command line does
        (``--load``, ``--speed``, ``--temperature``, ``--material FILE: ...``).

    References
    ----------
    Menga et al. (2014), eq. (3.1); eqs (2.7)–(2.8).
    """
    plan, parameters = prepare(material, shift=shift, temperatures=temperatures, speeds=speeds,
                               mean_pressure=mean_pressure, wavelength=wavelength,
                               amplitude=amplitude, nu=nu, nodes=nodes, rtol=rtol,
                               max_residual=max_residual, per_decade=per_decade,
                               loss_weight=loss_weight, **data_options)
    return solve(plan, parameters, done=done, on_point=on_point)


def solve(plan, parameters, *, done=None, on_point=None) -> FrictionMasterCurve:
    """Solve the points of `prepare`'s plan (those not in ``done``), in order."""
    from . import runner
    rows = []
    total = len(plan)
    for i, (T, V, log_a, spec) in enumerate(plan):
        old = (done or {}).get(_key(T, V))
        row = old if old is not None else _row(T, V, log_a, runner.run(spec))
        rows.append(row)
        if on_point is not None:
            on_point(row, i, total, old is not None)
    return FrictionMasterCurve.from_rows(rows, parameters)


def prepare(material, *, shift, temperatures, speeds, mean_pressure, wavelength, amplitude, nu,
            nodes=None, rtol=DEFAULT_RTOL, max_residual=None, per_decade=None, loss_weight=None,
            shift_info=None, reference_temperature=None, with_material=False, **data_options):
    """Every input checked and every point's spec built, before any solve.

    Returns ``([(T, V, log10 a_T, spec), ...], parameters)`` (and, ``with_material``, the
    material read, at its reference temperature: a `comparisons._materials.Material`); raises
    ValueError (one line).
    """
    from viscosine import materials as vm
    from viscosine.checks import real

    from . import _materials, roads, runner
    temps = [real("temperature", t, "a finite temperature") for t in temperatures]
    vs = [real("speed", v, "a finite sliding speed > 0", lambda x: x > 0.0, unit="m/s")
          for v in speeds]
    if not temps:
        raise ValueError("temperatures=[] is not allowed: at least one temperature")
    if not vs:
        raise ValueError("speeds=[] is not allowed: at least one speed [m/s]")
    if shift is not None and not isinstance(shift, (vm.WLF, vm.ShiftTable, NoShift)):
        raise ValueError(f"shift={shift!r} is not allowed: a viscosine.materials.WLF or "
                         "ShiftTable (a_T of the material's times), NoShift (one temperature), "
                         "or None (raw isotherms: the WLF fitted to them)")
    if isinstance(shift, NoShift) and any(t != shift.T_ref for t in temps):
        raise ValueError(f"--temperatures {' '.join(f'{t:g}' for t in temps)} is not allowed "
                         f"without a shift: only the material's own temperature, {shift.T_ref:g} "
                         "(others need --wlf or --shift-table)")
    if shift is not None and shift_info is None:
        shift_info = ({"kind": "WLF", "C1": shift.C1, "C2": shift.C2, "T_ref": shift.T_ref}
                      if isinstance(shift, vm.WLF) else
                      {"kind": "none", "T_ref": shift.T_ref} if isinstance(shift, NoShift) else
                      {"kind": "table", "T": [shift.T[0], shift.T[-1]]})
    unknown = sorted(set(data_options) - set(_materials.DATA_OPTIONS))
    if unknown:
        raise TypeError(f"prepare() got an unexpected keyword argument {unknown[0]!r}")
    if isinstance(material, (str, os.PathLike)):
        base = _materials.read(os.fspath(material), max_residual=max_residual,
                               per_decade=per_decade, loss_weight=loss_weight, nu=nu, si=True,
                               reference_temperature=reference_temperature, **data_options)
    else:
        for k, v in (("max_residual", max_residual), ("per_decade", per_decade),
                     ("loss_weight", loss_weight), *data_options.items()):
            if v is not None:
                raise ValueError(f"{k}={v!r} is not allowed with a Maxwell series: it steers "
                                 "how a material file is read or fitted")
        base = _materials.from_model(material)
    if reference_temperature is not None and base.info["form"] != "sweeps":
        raise ValueError(f"--reference-temperature {reference_temperature!r} is not allowed: "
                         "it sets the master curve of raw isotherms, and the material is a "
                         f"{base.info['form']} file")
    if base.info["form"] == "sweeps" and shift is not None:
        raise ValueError("--wlf is not allowed with raw isotherms: they are moved by the WLF "
                         "fitted to them (their master curve is at their own T_ref)")
    if shift is None:                         # raw isotherms: the WLF fitted to their shifts
        shift, shift_info = _materials.fitted_shift(base)
        if shift is None:
            raise ValueError("shift=None is not allowed: a material file of raw isotherms (or "
                             "give --wlf or --shift-table)")
    nu = _materials.problem_nu(base, nu)      # a shear card's own ν: one ν for E and E*
    si = {"nu": nu, "wavelength": wavelength, "amplitude": amplitude}
    groups = op.resolve_si("bem", si, loads=[mean_pressure], speeds=vs, material=base,
                           groups=roads.si_groups)
    plan = []
    for T in temps:
        m = _materials.at_temperature(base, shift, shift_info, T, option=(
            "--wlf" if isinstance(shift, vm.WLF) else "--shift-table"))
        for V, w in zip(vs, groups["speed"]):
            spec = op.OperatingPoint("bem", load=groups["load"][0], speed=w, hk=groups["hk"],
                                     nodes=nodes, rtol=None if nodes is not None else rtol,
                                     material=m.info, si=groups["si"],
                                     parsed={"material": m})
            plan.append((T, V, m.info["log10_aT"], spec))
        runner.validate(plan[-1][3])  # this temperature's material, before any work
    parameters = {"material": base.info, "shift": shift_info, "temperatures": temps,
                  "speeds": vs, "mean_pressure": float(mean_pressure),
                  "wavelength": float(wavelength), "amplitude": float(amplitude),
                  "nu": float(nu), "nodes": nodes, "rtol": None if nodes is not None else rtol,
                  "load": groups["load"][0], "hk": groups["hk"],
                  "time_unit": base.info["time_unit"]}
    return (plan, parameters, base) if with_material else (plan, parameters)


# ------------------------------------------------------------------------------ files
def _csv_value(v):
    if isinstance(v, bool):
        return "1" if v else "0"
    if v is None:
        return ""
    if isinstance(v, float):
        return repr(v)
    if isinstance(v, str):
        return '"' + v.replace('"', "'").replace("\n", " ") + '"'
    return str(v)


def _parameters_line(parameters):
    return "parameters: " + json.dumps(parameters, sort_keys=True, allow_nan=False)


def read_points(path):
    """(parameters line, rows keyed by (repr T, repr V)) of a points.csv, or (None, {})."""
    import csv
    if not os.path.exists(path):
        return None, {}
    with open(path, encoding="utf-8") as fh:
        lines = fh.read().splitlines()
    params = next((ln[2:] for ln in lines if ln.startswith("# parameters: ")), None)
    body = [ln for ln in lines if ln and not ln.startswith("#")]
    rows = {}
    if body:
        for r in csv.DictReader(body):
            if None in r or any(v is None for v in r.values()):
                continue  # a line cut short by an interruption: solved again
            try:
                row = {"temperature": float(r["temperature"]), "speed": float(r["speed"]),
                       "log10_aT": float(r["log10_aT"]),
                       "reduced_speed": float(r["reduced_speed"]),
                       "success": r["success"] == "1", "mu": float(r["mu"]),
                       "mu_error": float(r["mu_error"]),
                       "friction_stress": float(r["friction_stress"]),
                       "contact_fraction": float(r["contact_fraction"]),
                       "load": float(r["load"]), "speed_group": float(r["speed_group"]),
                       "nodes": int(r["nodes"]) if r["nodes"] else None,
                       "seconds": float(r["seconds"]), "extrapolated": r["extrapolated"] == "1",
                       "message": r["message"]}
            except (KeyError, ValueError):
                continue
            rows[_key(row["temperature"], row["speed"])] = row
    return params, rows


def _append(path, row):
    with open(path, "a", encoding="utf-8", newline="\n") as fh:
        fh.write(",".join(_csv_value(row[c]) for c in COLUMNS) + "\n")
        fh.flush()
        os.fsync(fh.fileno())


# ------------------------------------------------------------------------------ into a folder
def _isotherms_report(out, material_info):
    """Raw isotherms: their shift table on standard error and ``shifts.png`` into ``out``."""
    sp = material_info.get("superposition")
    if sp is None:
        return
    from viscosine import materials as vm

    from .plots.superposition import shifts_figure
    for line in vm.shift_table_text(sp).splitlines():
        stderr(f"mastercurve: {line}")
    path = shifts_figure(os.path.join(out, "shifts.png"), sp,
                         title=os.path.basename(material_info.get("path") or ""))
    stderr(f"mastercurve: wrote {path}")


def _raw_isotherms(material) -> bool:
    """Whether ``material`` is a file of raw isotherms (which carry their own shift)."""
    from viscosine import materials as vm
    if not isinstance(material, (str, os.PathLike)):
        return False
    try:
        return vm.material_form(os.fspath(material)) == "sweeps"
    except ValueError:
        return False                           # refused, by name, when it is read


def write_curve(out, material, *, wlf=None, shift_table=None, temperatures, speeds,
                mean_pressure, wavelength, amplitude, nu, nodes=None, rtol=None,
                max_residual=None, per_decade=None, loss_weight=None,
                reference_temperature=None, **data_options) -> int:
    """`python -m comparisons mastercurve`: check every input, then solve every point into the
    folder ``out`` (made when missing): ``points.csv`` continued when it holds a run with the
    same parameters, then ``mastercurve.json`` and ``mastercurve.png`` (and, for a DMA curve,
    the fit's figure ``<file stem>_fit.png``); progress on standard error.  ``wlf`` (C1, C2, TREF) or ``shift_table`` (a file) is the shift; the other keywords
    are `prepare`'s (``rtol`` default `DEFAULT_RTOL`).

    Returns
    -------
    int
        The points that could not be solved.

    Raises
    ------
    comparisons._errors.BadInput
        Bad input, before any point is solved, in one line naming the command line's option.
    """
    from . import _materials

    check_output_dir("--out", out, create=False)
    try:
        if wlf is None and shift_table is None and _raw_isotherms(material):
            shift, shift_info = None, None      # the WLF fitted to the isotherms
        elif wlf is None and shift_table is None:  # the material's own temperature only
            if len(temperatures) != 1:
                raise BadInput(f"--temperatures {' '.join(f'{t:g}' for t in temperatures)} is "
                               "not allowed without --wlf or --shift-table: one, the material's own")
            shift = NoShift(float(temperatures[0]))
            shift_info = {"kind": "none", "T_ref": shift.T_ref}
        else:
            shift, shift_info = _materials.shift_from_options(wlf, shift_table)
        plan, parameters, base = prepare(
            material, shift=shift, shift_info=shift_info, temperatures=temperatures,
            speeds=speeds, mean_pressure=mean_pressure, wavelength=wavelength,
            amplitude=amplitude, nu=nu, nodes=nodes,
            rtol=DEFAULT_RTOL if rtol is None else rtol,
            max_residual=max_residual, per_decade=per_decade, loss_weight=loss_weight,
            reference_temperature=reference_temperature, with_material=True, **data_options)
    except ValueError as exc:  # BadInput too (the runner's and file readers'), re-worded
        text = str(exc).strip().splitlines()[0]
        if text.startswith(("nodes=", "rtol=")) and " is not allowed: " in text:
            said, _, why = text.partition(" is not allowed: ")  # the road's, by keyword
            text = f"--{said.replace('=', ' ', 1)}: must be {allowed_part(why)}"
        for name, option in (("--speed ", "--speeds "), ("speed=", "--speeds "),
                             ("--temperature ", "--temperatures "),
                             ("nodes=", "--nodes "), ("rtol=", "--rtol "),
                             ("max_nodes=", "--nodes ")):
            if text.startswith(name):
                text = option + text[len(name):]
                break
        raise BadInput(text) from None
    check_output_dir("--out", out, create=True)
    csv_path = os.path.join(out, "points.csv")
    line = _parameters_line(parameters)
    old_params, done = read_points(csv_path)
    if old_params is not None and old_params != line:
        raise BadInput(f"--out {out}: its points.csv holds a run with other parameters; choose "
                       "another folder (or remove that file)")
    if old_params is None:
        write_text(csv_path, "".join(f"# {ln}\n" for ln in (
            "viscosine mastercurve points (python -m comparisons mastercurve)", line, UNITS))
            + ",".join(COLUMNS) + "\n")
    _isotherms_report(out, parameters["material"])
    report_fit(base, out, "mastercurve")       # a DMA fit: its figure into --out
    t0 = time.monotonic()
    failed = reused_rows = 0
    progress = Progress()

    def on_point(row, i, total, reused):
        nonlocal failed, reused_rows
        reused_rows += bool(reused)
        if not reused:
            _append(csv_path, row)
        failed += not row["success"]
        what = (f"mu = {row['mu']:.6g}" if row["success"] else f"FAILED: {row['message']}")
        extra = " (extrapolated)" if row["extrapolated"] else ""
        how = "from points.csv" if reused else f"{row['seconds']:.2f} s"
        line = (f"mastercurve: {i + 1}/{total} T = {row['temperature']:g}, V = "
                f"{row['speed']:.4g} m/s: {what}{extra} ({how}; {time.monotonic() - t0:.1f} s)")
        if row["success"]:
            progress.update(line, final=i + 1 == total)
        else:
            progress.say(line)

    table = solve(plan, parameters, done=done, on_point=on_point)
    progress.close()
    total = len(plan)
    doc = {"parameters": parameters, "columns": list(COLUMNS), "units": UNITS,
           "points": list(table.rows)}
    write_text(os.path.join(out, "mastercurve.json"),
               json.dumps(jsonable(doc), indent=1, allow_nan=False) + "\n")
    if table.success.any():
        figure.write_figure(os.path.join(out, "mastercurve.png"), table)
    kept = f" ({reused_rows} from points.csv)" if reused_rows else ""
    stderr(f"mastercurve: {total - failed}/{total} points{kept} in {time.monotonic() - t0:.1f} s; "
           f"wrote {csv_path}, mastercurve.json" + (", mastercurve.png"
                                                    if table.success.any() else ""))
    if failed:
        stderr(f"mastercurve: {failed} of {total} points could not be solved")
    return failed
