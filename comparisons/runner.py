"""Glue between the command line / report and the two roads.

An operating point is a plain dict of dimensionless numbers (a *spec*), so that nothing of one
road leaks into the other and a spec can cross a process or network boundary.  Keys:
``solver``, ``load`` | ``penetration``, ``speed``, ``ratio``, ``hk``, ``nodes``, ``rtol``,
``max_nodes``, ``profile``, ``prony`` (None, or ``{"path", "sha256"}`` of the file read) and
``field_points`` (analytic road: points of the written fields); with ``--material`` also
``material``, the description of the material (`comparisons._materials`: form, file, SHA-256,
reference modulus and time, temperature, fit residuals), which every record carries (for the
standard linear solid and ``--prony`` too) with ``time_unit``, the sentence that says which time
the speed is measured in.  Keys starting with ``_`` carry the parsed input files to the worker
and are never recorded.

- :func:`resolve` turns command-line options (None = not given) into a spec: it is the one place
  where defaults are applied and options that do not apply are refused.
- :func:`validate` checks a spec through the roads' own ``validate`` (the single source of the
  accepted ranges) and raises `comparisons._errors.BadInput` (exit status 2).
- :func:`run` solves one spec and returns a plain dict ``{"ok", "kind", "record", "error",
  "warnings", "fields", "spec", "seconds"}``; it never raises for a failing solve: any exception,
  an unconverged result or a result that fails the last line of defence
  (`comparisons.gate.check_record`) is ``ok = False`` with a one-line ``error``.

Each road is reached through one adapter of `comparisons.roads` (``analytic_record``,
``bem_record``) that returns the road's JSON record (``result.as_dict()``), its fields and the
constraint figures the last line of defence checks.
"""
from __future__ import annotations

import hashlib
import math
import os
import re
import time
import warnings as _warnings

import numpy as np

import viscosine
from viscosine import ViscosineWarning

from . import roads
from .gate import check_record, check_surface_record
from ._errors import BadInput
from ._errors import one_line as _one_line
from ._io import file_bytes

#: every default of the command line, applied in `resolve` only (rtol: the BEM's own default,
#: viscosine.DEFAULT_RTOL, the one value both read)
DEFAULTS = {"ratio": 3.0, "hk": 1.0, "rtol": viscosine.DEFAULT_RTOL, "field_points": 1024}
#: points of the analytic fields (--nodes with --fields): 8 … 2^20 (about 10 µs per point)
FIELD_POINTS = (8, 2 ** 20)

SPEC_KEYS = ("solver", "load", "penetration", "speed", "ratio", "hk", "nodes", "rtol", "max_nodes",
             "profile", "prony", "field_points")


# ------------------------------------------------------------------------------ specs
def point_spec(solver, speed, load=None, penetration=None, ratio=3.0, hk=1.0, nodes=None):
    """A spec for the report and the cross-check (numbers only; BEM ``nodes`` pinned or adaptive)."""
    spec = dict.fromkeys(SPEC_KEYS)
    spec.update(solver=solver, load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk)
    if solver == "bem":
        spec["nodes"] = nodes
        if nodes is None:
            spec["rtol"] = DEFAULTS["rtol"]
    return spec


def public(spec):
    """The spec without the parsed objects it carries to the worker (JSON-ready)."""
    return {k: v for k, v in spec.items() if not k.startswith("_")}


def resolve(solver, *, load=None, penetration=None, speed=None, ratio=None, hk=None, nodes=None,
            rtol=None, max_nodes=None, profile=None, prony=None, fields=False, files=None,
            material=None, material_options=None, si=None, layer=None, surface=None,
            direction=None):
    """Command-line options (None = not given) → spec, with the defaults applied here only.

    Options that do not apply to the chosen inputs are refused, never recorded as if used:
    ``hk`` with ``profile``, ``ratio`` with ``prony``, ``profile``/``prony``/``rtol``/
    ``max_nodes`` on the analytic road, ``nodes`` on the analytic road without fields (there it
    is the number of points of the written fields), ``rtol``/``max_nodes`` with a fixed BEM mesh.

    Parameters
    ----------
    files : dict, optional
        Already read input files ``{"profile": (info, object), "prony": (info, object),
        "material": (info, Material)}``, so that a sweep reads each file once; otherwise they
        are read here.
    material : str, optional
        A material file of any accepted form (`comparisons._materials`), BEM only, not with
        ``prony`` or ``ratio``.
    material_options : dict, optional
        ``temperature``, ``wlf``, ``shift_table``, ``max_residual``, ``per_decade`` of the
        material (None = not given); only with ``material``; ``si`` True reads the file in SI.
    si : dict, optional
        ``--units SI``: the ``si`` description of `resolve_si` (the values are then its groups).
    layer : dict, optional
        ``--thickness``: ``{"thickness_over_wavelength", "foundation", "nu"}``, BEM only; the
        spec's ``layer`` (checked by the BEM's Layer in `validate`).
    surface : dict, optional
        ``--surface``: the plain description of `comparisons.cli._common.surface_description`
        (BEM only); the spec then carries ``surface`` and ``direction`` (degrees), its ``hk`` is
        None (a bi-sinusoid's amplitudes are in the description) and its default ``rtol`` is
        ``viscosine.SURFACE_RTOL``.  A surface FILE is read here (``files["surface"]``).

    Raises
    ------
    BadInput
    """
    def refuse(option, why):
        raise BadInput(f"{option} is not allowed here: {why}")

    options = {k: v for k, v in (material_options or {}).items() if v is not None}
    in_si = options.pop("si", False)
    if options and material is None:
        refuse(_MATERIAL_OPTIONS[next(iter(options))], "it applies to a --material file (give "
               "the material with --material FILE)")
    if material is not None and prony is not None:
        refuse("--material", "--prony gives the material already (--material reads the same "
               "creep-series files, and relaxation series and DMA curves)")
    if solver == "analytic":
        if layer is not None:
            refuse("--thickness", "a BEM option (the semi-analytic road solves the half-space; "
                   "use --solver bem)")
        if profile is not None or prony is not None or material is not None:
            refuse("--profile" if profile is not None else (
                   "--prony" if prony is not None else "--material"),
                   "a BEM option (the semi-analytic road solves the sinusoid on the standard "
                   "linear solid; use --solver bem)")
        if rtol is not None or max_nodes is not None:
            refuse("--rtol" if rtol is not None else "--max-nodes",
                   "a BEM option (the semi-analytic road has no mesh)")
        if nodes is not None and not fields:
            refuse("--nodes", "on the semi-analytic road --nodes is the number of points of "
                   "--fields, and no --fields was given")
    elif solver == "bem":
        if hk is not None and profile is not None:
            refuse("--hk", "the --profile file fixes the indenter and its amplitude")
        if ratio is not None and prony is not None:
            refuse("--ratio", "the --prony file fixes the material")
        if ratio is not None and material is not None:
            refuse("--ratio", "the --material file fixes the material")
        if nodes is not None and (rtol is not None or max_nodes is not None):
            refuse("--rtol" if rtol is not None else "--max-nodes",
                   f"--nodes {nodes} fixes the mesh; --rtol and --max-nodes steer the adaptive "
                   "refinement (without --nodes)")
    else:
        raise BadInput(f"--solver {solver!r} is not allowed: analytic or bem")

    spec = dict.fromkeys(SPEC_KEYS)
    spec.update(solver=solver, load=load, penetration=penetration, speed=speed)
    if si is not None:  # only then: the spec of every other point keeps its keys (and hash)
        spec["si"] = si
    if layer is not None:  # likewise
        spec["layer"] = dict(layer)
    if surface is not None:  # likewise
        spec["surface"] = dict(surface)
        spec["direction"] = 0.0 if direction is None else direction
    if solver == "analytic":
        spec["ratio"] = DEFAULTS["ratio"] if ratio is None else ratio
        spec["hk"] = DEFAULTS["hk"] if hk is None else hk
        if fields:
            spec["field_points"] = DEFAULTS["field_points"] if nodes is None else nodes
        return spec
    files = dict(files or {})
    for option, path in (("profile", profile), ("prony", prony)):
        if path is not None and option not in files:
            files[option] = read_input(option, path)
    if material is not None and "material" not in files:
        files["material"] = read_material(material, **options, si=in_si)
    if surface is not None and surface.get("kind") == "file":
        if "surface" not in files:
            files["surface"] = read_input("surface", surface["path"])
        info, obj = files["surface"]
        spec["surface"] = {"kind": "file", **info}
        spec["_surface"] = obj
    fixed = prony is not None or material is not None
    spec["ratio"] = None if fixed else (DEFAULTS["ratio"] if ratio is None else ratio)
    spec["hk"] = None if profile is not None or surface is not None else (
        DEFAULTS["hk"] if hk is None else hk)
    spec["nodes"] = nodes
    if nodes is None:
        default = viscosine.SURFACE_RTOL if surface is not None else DEFAULTS["rtol"]
        spec["rtol"] = default if rtol is None else rtol
        spec["max_nodes"] = max_nodes
    for option in ("profile", "prony", "material"):
        if option in files:
            info, obj = files[option]
            spec[option] = info
            spec["_" + option] = obj
    return spec


# ------------------------------------------------------------------------------ SI inputs
#: the option the user typed behind each SI keyword
_SI_NAMES = {"mean_pressure": "--load", "penetration": "--penetration", "speed": "--speed",
             "E0": "--E0", "Einf": "--Einf", "tau": "--tau", "tau_creep": "--tau-creep",
             "tau_relax": "--tau-relax", "nu": "--nu", "wavelength": "--wavelength",
             "amplitude": "--amplitude", "E_ref": "--material"}


def resolve_si(solver, si, *, loads=None, penetrations=None, speeds, material=None):
    """``--units SI``: SI values of point or sweep turned into the dimensionless groups.

    Parameters
    ----------
    si : dict
        The SI options given (keywords of `viscosine.si`, None = not given): ``nu``,
        ``wavelength``, ``amplitude`` always; the standard linear solid's ``E0``, ``Einf`` and
        one time (``tau_creep``, alias ``tau``, or ``tau_relax``) unless ``material`` is given.
    loads, penetrations : list of float
        Mean pressures p∞ [Pa] or penetrations Δ [m] (exactly one list).
    speeds : list of float
        V [m/s].
    material : Material, optional
        Read with ``si=True``: reference modulus its relaxed modulus E_r [Pa], time 1 s.

    Returns
    -------
    dict
        ``load`` or ``penetration`` and ``speed`` (lists of groups), ``ratio`` (the solid's, or
        None), ``hk``, and ``si``: the JSON description of the scales (goes into the spec and
        every record).

    Raises
    ------
    BadInput
        A missing, extra or invalid SI option, or a group outside the road's accepted range,
        named by the option the user typed.
    """
    from viscosine import si as si_front  # `si` is the options' name here
    given = {k: v for k, v in si.items() if v is not None}
    need = ["nu", "wavelength", "amplitude"]
    if material is None:
        need += ["E0", "Einf"]
        if not {"tau", "tau_creep", "tau_relax"} & set(given):
            need.append("tau_creep")
    else:
        extra = [k for k in ("E0", "Einf", "tau", "tau_creep", "tau_relax") if k in given]
        if extra:
            raise BadInput(f"{_SI_NAMES[extra[0]]} is not allowed with --material: the "
                           "material file fixes the moduli and times")
    missing = [k for k in need if k not in given]
    if missing:
        raise BadInput(f"{_SI_NAMES[missing[0]]} is missing: --units SI needs --nu, "
                       "--wavelength, --amplitude [m] and the material (--material FILE, or "
                       "--E0 --Einf [Pa] with --tau-creep or --tau-relax [s])")
    control = "mean_pressure" if loads is not None else "penetration"
    values = loads if loads is not None else penetrations

    def scales(value, speed):
        try:
            if material is None:
                sc = si_front.scales(**{k: given.get(k) for k in ("E0", "Einf", "tau", "tau_creep",
                                                              "tau_relax")},
                                nu=given["nu"], wavelength=given["wavelength"],
                                amplitude=given["amplitude"], speed=speed, **{control: value})
            else:
                sc = si_front.material_scales(E_ref=material.info["E_ref"], tau_ref=1.0,
                                         nu=given["nu"], wavelength=given["wavelength"],
                                         amplitude=given["amplitude"], speed=speed,
                                         **{control: value})
            groups = roads.si_groups(solver, sc)
        except ValueError as exc:
            raise BadInput(_si_option_names(_one_line(exc))) from None
        return sc, groups

    sc, _ = scales(values[0], speeds[0])
    out = {"load": None, "penetration": None}
    key = "load" if loads is not None else "penetration"
    out[key] = [scales(v, speeds[0])[1][key] for v in values]
    out["speed"] = [scales(values[0], v)[1]["speed"] for v in speeds]
    out["ratio"], out["hk"] = sc.ratio, sc.hk
    out["si"] = {"units": "SI", "nu": given["nu"], "wavelength": sc.wavelength,
                 "amplitude": sc.amplitude, "E_ref": sc.estar * (1.0 - given["nu"] ** 2),
                 "tau_ref": sc.tau, "plane_strain_modulus": sc.estar,
                 "load_is": "p_inf (1 - nu^2)/E_ref, p_inf the --load [Pa]",
                 "speed_is": "V tau_ref k, V the --speed [m/s], k = 2 pi/wavelength"}
    return out


def _si_option_names(text):
    """'mean_pressure=…' of the SI front becomes '--load …' (the option the user typed)."""
    m = re.match(r"(\w+)=(\S+) is not allowed", text)
    if m and m.group(1) in _SI_NAMES:
        return f"{_SI_NAMES[m.group(1)]} {m.group(2)}{text[m.end(2):]}"
    return text


def si_block(rec, info):
    """The record's ``si`` block: its scalars in SI (m, Pa, m/s) from the spec's ``si``."""
    from types import SimpleNamespace

    from viscosine import si as si_front  # `si` is the options' name here
    lam, h = info["wavelength"], info["amplitude"]
    k = 2.0 * math.pi / lam
    sc = si_front.SIScales(None, h * k, rec["speed"], rec.get("load"), rec.get("penetration"), k,
                      info["plane_strain_modulus"], lam, h, info["tau_ref"], {})
    keys = ("success", "message", "full_contact", "ka", "ke", "ke_hat", "penetration",
            "separation", "load", "tau_f", "mu", "max_pressure", "x_max_pressure")
    r = si_front.result(SimpleNamespace(**{k_: rec.get(k_) for k_ in keys}), sc)
    out = {name: getattr(r, name) for name in (
        "contact_halfwidth", "eccentricity", "pressure_eccentricity", "penetration",
        "mean_separation", "mean_pressure", "friction_stress", "friction_coefficient",
        "max_pressure", "x_max_pressure", "wavelength", "amplitude", "plane_strain_modulus")}
    out["speed"] = rec["speed"] / (info["tau_ref"] * k)
    if rec.get("layer"):  # the layer's thickness and the indenter's approach, in m
        out["thickness"] = rec["layer"]["thickness_over_wavelength"] * lam
        out["approach"] = rec["layer"]["approach"] * h
    out["units"] = "m, Pa, m/s"
    return out


def surface_si_block(rec, info):
    """A surface record's ``si`` block: its scalars in SI (m, Pa, m/s) from the spec's ``si``
    (``wavelength`` is the cell's side Lx; h_ref is the record's surface amplitude k h_ref over
    k: for the bi-sinusoid twice the --amplitude h)."""
    lx, estar = info["wavelength"], info["plane_strain_modulus"]
    k = 2.0 * math.pi / lx
    h = rec["surface"]["amplitude"] / k
    return {"mean_pressure": rec["load"] * estar, "friction_stress": rec["tau_f"] * estar,
            "max_pressure": rec["max_pressure"] * estar,
            "penetration": rec["penetration"] * h, "separation": rec["separation"] * h,
            "speed": rec["speed"] / (info["tau_ref"] * k), "length": lx, "amplitude": h,
            "plane_strain_modulus": estar, "units": "m, Pa, m/s"}


#: the option behind each key of ``material_options``
_MATERIAL_OPTIONS = {"temperature": "--temperature", "wlf": "--wlf",
                     "shift_table": "--shift-table", "max_residual": "--max-residual",
                     "per_decade": "--per-decade"}


def read_material(path, *, temperature=None, wlf=None, shift_table=None, max_residual=None,
                  per_decade=None, si=False):
    """Read a --material file of any accepted form: ``(description, Material)``.

    See `comparisons._materials.read`.

    Raises
    ------
    BadInput
    """
    from . import _materials
    try:
        m = _materials.read(path, temperature=temperature, wlf=wlf, shift_table=shift_table,
                            max_residual=max_residual, per_decade=per_decade, si=si)
    except ValueError as exc:
        raise BadInput(_one_line(exc)) from None
    return m.info, m


# ------------------------------------------------------------------------------ input files
def read_input(option, path, **reader_options):
    """Read a --profile, --prony or --surface file: ``({"path", "sha256"}, parsed object)``.

    The file must be a regular UTF-8 text file; the parsing is the BEM's own
    (`bem.read_profile`, `bem.read_prony`, through `comparisons.roads`).  Every refusal names
    the option and the file.

    Raises
    ------
    BadInput
    """
    where = f"--{option} {path}"
    data = file_bytes(f"--{option}", path)
    reader = {"profile": roads.read_profile, "prony": roads.read_prony,
              "surface": roads.read_surface}[option]
    try:
        obj = reader(path, **reader_options)
    except (ValueError, UnicodeDecodeError, OSError) as exc:
        raise BadInput(f"{where}: {_one_line(exc)}") from None
    info = {"path": os.path.abspath(path), "sha256": hashlib.sha256(data).hexdigest()}
    info.update(reader_options)  # a surface file in metres: its units and Lx
    return info, obj


# ------------------------------------------------------------------------------ validation
def validate(spec):
    """Check a spec before any work; raise BadInput naming the input and what is allowed.

    The accepted ranges are the roads' own (`analytic.validate`, `bem.validate`, through
    `comparisons.roads`); the command line adds only the limits of its own options (mesh cap,
    points of the fields).
    """
    try:
        if spec["solver"] == "analytic":
            roads.validate_analytic(spec)
            n = spec.get("field_points")
            if n is not None:
                _check_int("nodes", n, *FIELD_POINTS, "points of the written fields")
        elif spec["solver"] == "bem" and spec.get("surface") is not None:
            roads.validate_surface(spec, _bem_problem(spec)[1], _surface(spec))
        elif spec["solver"] == "bem":
            roads.validate_bem(spec, _bem_problem(spec))
        else:
            raise BadInput(f"solver={spec['solver']!r} is not allowed: analytic or bem")
    except BadInput:
        raise
    except ValueError as exc:
        raise BadInput(_one_line(exc)) from None


def _check_int(name, value, low, high, what):
    from viscosine.checks import integer
    try:
        integer(name, value, f"an integer in [{low}, {high}] ({what})", lambda v: low <= v <= high)
    except ValueError as exc:
        raise BadInput(str(exc)) from None


def _bem_problem(spec):
    """``(profile, material)`` of a BEM spec: its parsed profile and creep series (carried in
    the spec, else read again), None for the sinusoid of ``hk`` and the standard linear solid
    of ``ratio``."""
    profile = material = None
    if spec.get("profile") is not None:
        obj = spec.get("_profile")
        profile = obj if obj is not None else read_input("profile", spec["profile"]["path"])[1]
    if spec.get("prony") is not None:
        obj = spec.get("_prony")
        material = obj if obj is not None else read_input("prony", spec["prony"]["path"])[1]
    elif spec.get("material") is not None:
        material = _material(spec).prony
    return profile, material


def _surface(spec):
    """A surface file's parsed Surface (carried in the spec, else read again), or None."""
    if spec["surface"].get("kind") != "file":
        return None
    obj = spec.get("_surface")
    if obj is not None:
        return obj
    desc = spec["surface"]
    extra = {k: desc[k] for k in ("units", "length") if desc.get(k) is not None}
    return read_input("surface", desc["path"], **extra)[1]


def _material(spec):
    """The spec's parsed --material (read again from its description when not carried)."""
    obj = spec.get("_material")
    if obj is None:
        from . import _materials
        try:
            obj = _materials.reread(spec["material"])
        except ValueError as exc:
            raise BadInput(_one_line(exc)) from None
    return obj


def describe_material(spec):
    """The record's ``material`` (a dict) and ``time_unit`` (a sentence) of a spec."""
    from . import _materials
    if spec.get("material") is not None:
        info = dict(spec["material"])
    elif spec.get("prony") is not None:
        obj = spec.get("_prony")
        if obj is None:
            obj = read_input("prony", spec["prony"]["path"])[1]
        info = {"form": "creep", **spec["prony"], "terms": len(obj.J),
                **_materials.references("creep", False, 1.0, None)}
    else:
        info = _materials.sls_description(spec.get("ratio"))
    return info, info.pop("time_unit")


# ------------------------------------------------------------------------------ one point
def run(spec, fields=False, deep=None):
    """Solve one operating point; never raises for a failing solve.

    Parameters
    ----------
    spec : dict
        See the module docstring.
    fields : bool
        Also return the fields (``viscosine.Fields``).
    deep : bool, optional
        Check σ ≥ 0, gap ≥ 0 and mean σ = load on the solution itself.  Default: always on the
        BEM (the panel values are at hand), on the semi-analytic road only with ``fields`` (its
        graded quadrature costs about ten solves).

    Returns
    -------
    dict
        ``ok``; ``kind`` ("ok", "failed": could not solve, "bad_input"); ``record`` (the JSON
        object, only when ok); ``error`` (one line); ``warnings`` (list of str); ``fields``;
        ``spec`` (public); ``seconds``.
    """
    t0 = time.perf_counter()
    out = {"spec": public(spec), "ok": False, "kind": "failed", "record": None, "error": None,
           "warnings": [], "fields": None, "seconds": 0.0}
    try:
        validate(spec)
    except BadInput as exc:
        out.update(kind="bad_input", error=str(exc), seconds=time.perf_counter() - t0)
        return out
    if deep is None:
        deep = spec["solver"] == "bem" or fields
    try:
        with _warnings.catch_warnings(record=True) as caught:
            _warnings.simplefilter("always")
            if spec["solver"] == "bem" and spec.get("surface") is not None:
                solved = roads.surface_record(spec, _bem_problem(spec)[1], _surface(spec),
                                              fields)
            elif spec["solver"] == "bem":
                solved = roads.bem_record(spec, _bem_problem(spec), fields)
            else:
                n = spec.get("field_points") or DEFAULTS["field_points"]
                solved = roads.analytic_record(spec, n if fields else None, deep)
        rec = solved.record
        # the roads' own warnings are in the record already
        extra = [f"{w.category.__name__}: {w.message}" for w in caught
                 if not issubclass(w.category, ViscosineWarning)]
        rec["material"], rec["time_unit"] = describe_material(spec)
        if spec.get("si") is not None:
            rec["si_scales"] = spec["si"]
            if rec.get("success"):
                rec["si"] = (surface_si_block(rec, spec["si"]) if spec.get("surface")
                             is not None else si_block(rec, spec["si"]))
        if spec.get("material") is not None and rec.get("success"):
            from . import _materials
            text = _materials.extrapolation(_material(spec).model, spec["speed"],
                                            rec["contact_fraction"])
            if text is not None:  # the modulus at these frequencies is the fit's guess
                extra.append(f"extrapolation: {text}")
        if extra:  # warnings raised during the solve belong to this point
            rec["warnings"] = list(rec.get("warnings") or []) + extra
        if spec.get("surface") is not None:
            problem = check_surface_record(rec, spec, solved.constraints)
        else:
            problem = check_record(rec, spec, solved.constraints, solved.fields)
    except Exception as exc:  # any failure of the solve: this point could not be solved
        out["error"] = f"could not solve: {type(exc).__name__}: {_one_line(exc)}"
    else:
        if problem:
            out["error"] = problem
        else:
            out.update(ok=True, kind="ok", record=rec, warnings=list(rec.get("warnings") or []))
            if fields:
                out["fields"] = solved.fields
    out["seconds"] = time.perf_counter() - t0
    return out


def run_many(specs, workers=None, scheduler=None, fields=False, chunksize=None):
    """Yield ``run(spec)`` for each spec, in order (local processes or a Dask cluster).

    A point whose worker fails is yielded as a failed run; the others are kept.
    """
    from . import _cluster
    specs = list(specs) if not hasattr(specs, "__len__") else specs
    ex = _cluster.executor(workers, scheduler)
    if chunksize is None:
        chunksize = max(1, min(64, len(specs) // (8 * max(1, ex.workers))))
    fn = _run_with_fields if fields else run
    with ex:
        for i, value in ex.imap(fn, specs, chunksize=chunksize):
            if isinstance(value, _cluster.Failure):
                yield {"spec": public(specs[i]), "ok": False, "kind": "failed", "record": None,
                       "error": f"could not solve: {value.error}", "warnings": [],
                       "fields": None, "seconds": 0.0}
            else:
                yield value


def _run_with_fields(spec):
    return run(spec, fields=True)


# ------------------------------------------------------------------------------ writing fields
def fields_header(record, spec, fields):
    """The leading ``#`` lines of a fields CSV (`comparisons.fields.write_fields_csv`):
    version, operating point (the inputs as given; for the BEM the mesh actually used), points,
    grid, units.  ASCII only, for any CSV reader.

    ``fields``: the `viscosine.Fields` written (or, for a uniform grid, its number of points).
    """
    n = fields if isinstance(fields, (int, np.integer)) else fields.x_over_lambda.size
    uniform = isinstance(fields, (int, np.integer)) or fields.uniform
    point = {k: spec.get(k) for k in ("solver", "load", "penetration", "speed", "ratio", "hk")}
    if spec.get("solver") == "bem":
        point["nodes"] = record.get("nodes")       # the mesh used (after any refinement)
        point["rtol"] = spec.get("rtol")            # set only when the mesh was adaptive
    text = " ".join(f"{k}={v if isinstance(v, str) else repr(v)}"
                    for k, v in point.items() if v is not None)
    lines = [f"viscosine {record.get('version', viscosine.__version__)} fields "
             "(python -m comparisons)",
             f"operating point: {text}"]
    for k in ("profile_file", "prony_file"):
        if record.get(k):
            lines.append(f"{k.replace('_file', '')}: {record[k]['path']} sha256={record[k]['sha256']}")
    m = spec.get("material")
    if m:
        where = str(m["path"]).encode("ascii", "backslashreplace").decode("ascii")
        lines.append(f"material: {where} sha256={m['sha256']} form={m['form']} "
                     f"E_ref={m['E_ref']!r} tau_ref={m['tau_ref']!r} temperature={m['temperature']!r}"
                     f" log10_aT={m['log10_aT']!r}")
    if record.get("time_unit"):
        lines.append(f"time: {record['time_unit']}")
    if record.get("layer"):
        lay = record["layer"]
        lines.append(f"layer: d/lambda={lay['thickness_over_wavelength']!r} "
                     f"kd={lay['thickness']!r} foundation={lay['foundation']} nu={lay['nu']!r} "
                     f"approach/h={lay['approach']!r} (the indenter's, from the undeformed "
                     "top face)")
    lines += [f"points: {n}", GRID_UNIFORM if uniform else GRID_NON_UNIFORM,
              "units: x_over_lambda = x/lambda (crest at 0); pressure = sigma (1 - nu^2)/E0; "
              "displacement = v/h (into the body, from the mean line of the deformed surface); "
              "gap = gap/h (0 in contact)" + ("" if uniform else "; width = x/lambda")]
    return lines


#: the header line that states the grid of a fields CSV
GRID_UNIFORM = ("grid: uniform, one cell of width 1/points per row; the mean over the period is "
                "the mean of a column")
GRID_NON_UNIFORM = ("grid: non-uniform (a contact window: fine panels around the contact, coarse "
                    "ones elsewhere); column width = the row's cell, the cells consecutive in row "
                    "order over one period, the first centred on its row; the mean over the "
                    "period is sum(width * column)")
