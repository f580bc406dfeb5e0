"""Glue between the command line / report and the two roads: a point solved, checked, recorded.

The point is a `comparisons.operating_point.OperatingPoint` (made there, defaults applied,
options that do not apply refused), or a spec dict of the same keys (a stored one): numbers and
file descriptions only, so that nothing of one road leaks into the other and a point can cross
a process or network boundary.  Every record carries the material's description (``material``)
and ``time_unit``, the sentence that says which time the speed is measured in.

- :func:`validate` checks a point through the roads' own ``validate`` (the single source of the
  accepted ranges) and raises `comparisons._errors.BadInput` (exit status 2) naming the input
  as the user gave it (`comparisons.operating_point.named`).
- :func:`run` solves one point and returns a plain dict ``{"ok", "kind", "record", "error",
  "warnings", "fields", "spec", "seconds"}``; it never raises for a failing solve: any exception,
  an unconverged result or a result that fails the last line of defence
  (`comparisons.gate.check_record`) is ``ok = False`` with a one-line ``error``.

Each road is reached through one adapter of `comparisons.roads` (``analytic_record``,
``bem_record``, ``surface_record``) that returns the road's JSON record (``result.as_dict()``),
its fields and the constraint figures the last line of defence checks.
"""
from __future__ import annotations

import hashlib
import math
import os
import time
import warnings as _warnings

import numpy as np

import viscosine
from viscosine import ViscosineWarning
from viscosine import si as si_front  # `si` is the options' name here

from . import operating_point as op
from . import roads
from .gate import check_record, check_surface_record
from ._errors import BadInput
from ._errors import one_line as _one_line
from ._errors import reason as _reason
from ._io import file_bytes

def _si_scales(rec, info):
    """The `viscosine.si.SIScales` of a record's point, from the spec's ``si`` (its
    `SIScales.describe`)."""
    lam, h = info["wavelength"], info["amplitude"]
    k = 2.0 * math.pi / lam
    return si_front.SIScales(info.get("ratio"), h * k, rec["speed"], rec.get("load"),
                             rec.get("penetration"), k, info["plane_strain_modulus"], lam, h,
                             info["tau_ref"], {}, time_given=info.get("time_given"),
                             nu=info.get("nu"))


def si_block(rec, info):
    """The record's ``si`` block: its scalars in SI (m, Pa, m/s) from the spec's ``si``, and
    ``units`` (each key → its unit, `viscosine.si.UNITS`)."""
    from types import SimpleNamespace
    sc = _si_scales(rec, info)
    keys = ("success", "message", "full_contact", "ka", "ke", "ke_hat", "penetration",
            "separation", "load", "tau_f", "mu", "max_pressure", "x_max_pressure")
    r = si_front.result(SimpleNamespace(**{k_: rec.get(k_) for k_ in keys}), sc)
    out = {name: getattr(r, name) for name in (
        "contact_halfwidth", "eccentricity", "pressure_eccentricity", "penetration",
        "mean_separation", "mean_pressure", "friction_stress", "friction_coefficient",
        "max_pressure", "x_max_pressure", "wavelength", "amplitude", "plane_strain_modulus")}
    out["speed"] = rec["speed"] / (info["tau_ref"] * sc.k)
    if rec.get("layer"):  # the layer's thickness and the indenter's approach, in m
        out["thickness"] = rec["layer"]["thickness_over_wavelength"] * sc.wavelength
        out["approach"] = rec["layer"]["approach"] * sc.amplitude
    out["units"] = {k_: si_front.UNITS[k_] for k_ in out}
    return out


def surface_si_block(rec, info):
    """A surface record's ``si`` block: its scalars in SI (m, Pa, m/s) from the spec's ``si``
    (``wavelength`` is the cell's side Lx; h_ref is the record's surface amplitude k h_ref over
    k: for the bi-sinusoid twice the --amplitude h)."""
    lx, estar = info["wavelength"], info["plane_strain_modulus"]
    k = 2.0 * math.pi / lx
    h = rec["surface"]["amplitude"] / k
    out = {"mean_pressure": rec["load"] * estar, "friction_stress": rec["tau_f"] * estar,
           "max_pressure": rec["max_pressure"] * estar,
           "penetration": rec["penetration"] * h, "separation": rec["separation"] * h,
           "speed": rec["speed"] / (info["tau_ref"] * k), "length": lx, "amplitude": h,
           "plane_strain_modulus": estar}
    out["units"] = {k_: si_front.UNITS[k_] for k_ in out}
    return out


# ------------------------------------------------------------------------------ input files
def read_material(path, *, temperature=None, wlf=None, shift_table=None, max_residual=None,
                  per_decade=None, loss_weight=None, nu=None, si=False, **data_options):
    """Read a --material file of any accepted form: ``(description, Material)``
    (`comparisons._materials.read`; ``nu`` turns shear data into E', E''; ``data_options``
    its `_materials.DATA_OPTIONS`).

    Raises
    ------
    BadInput
    """
    from . import _materials
    try:
        m = _materials.read(path, temperature=temperature, wlf=wlf, shift_table=shift_table,
                            max_residual=max_residual, per_decade=per_decade,
                            loss_weight=loss_weight, nu=nu, si=si, **data_options)
    except ValueError as exc:
        raise BadInput(_one_line(exc)) from None
    return m.info, m


def read_input(name, path, door=op.CLI, **reader_options):
    """Read a --profile, --prony or --surface file: ``({"path", "sha256"}, parsed object)``.

    The file must be a regular UTF-8 text file; the parsing is the BEM's own
    (`bem.read_profile`, `bem.read_prony`, `bem.read_surface`, through `comparisons.roads`).
    Every refusal names the file as the user gave it: ``--prony PATH`` on the command line
    (``door`` CLI), ``prony path 'PATH'`` for a spec dict given in Python (``door`` PYTHON).

    Raises
    ------
    BadInput
    """
    label, shown = (f"--{name}", path) if door == op.CLI else (f"{name} path", repr(path))
    where = f"{label} {shown}"
    data = file_bytes(label, path, shown=shown)
    reader = {"profile": roads.read_profile, "prony": roads.read_prony,
              "surface": roads.read_surface}[name]
    try:
        obj = reader(path, **reader_options)
    except (ValueError, UnicodeDecodeError, OSError) as exc:
        raise BadInput(f"{where}: {_reason(exc)}") from None
    info = {"path": os.path.abspath(path), "sha256": hashlib.sha256(data).hexdigest()}
    info.update(reader_options)  # a surface file in metres: its units and Lx
    if name == "prony":  # a term below the BEM's floor is dropped, as from --material
        from . import _materials
        obj, dropped = _materials.negligible_dropped(obj)
        if dropped:
            info["dropped_terms"] = dropped
    return info, obj


def read_files(solver, files, *, profile=None, prony=None, material=None,
               material_options=None, surface=None) -> dict:
    """Read (and check) each input file of a BEM point or sweep once, into ``files`` (option ->
    ``(description, parsed)``, what `operating_point.build` takes); a file already there (a
    --units SI material or surface) is not read again.  Nothing on the semi-analytic road (the
    point refuses the options there).

    Raises
    ------
    BadInput
        a file that cannot be read, or is not what its option expects.
    """
    if solver != "bem":
        return files
    options = {k: v for k, v in (material_options or {}).items() if v is not None}
    in_si = bool(options.pop("si", False))
    for name, path in (("profile", profile), ("prony", prony)):
        if path is not None and name not in files:
            files[name] = read_input(name, path)
    if material is not None and prony is None and "material" not in files:
        files["material"] = read_material(material, **options, si=in_si)
    if surface is not None and surface.get("kind") == "file" and "surface" not in files:
        files["surface"] = read_input("surface", surface["path"])
    return files


# ------------------------------------------------------------------------------ validation
def validate(spec, door=op.PYTHON):
    """Check a point before any work; raise BadInput naming the input (on the command line,
    ``door`` CLI, by its option; in Python by its keyword) and what is allowed.

    The accepted ranges are the roads' own (`analytic.validate`, `bem.validate`, through
    `comparisons.roads`); the command line adds only the limits of its own options (points of
    the fields).
    """
    try:
        if spec["solver"] == "analytic":
            roads.validate_analytic(spec)
            if spec.get("field_points") is not None:
                op.check_field_points(spec["field_points"])
        elif spec["solver"] == "bem" and spec.get("surface") is not None:
            roads.validate_surface(spec, _bem_problem(spec, door)[1], _surface(spec, door))
        elif spec["solver"] == "bem":
            roads.validate_bem(spec, _bem_problem(spec, door))
        else:
            raise BadInput(f"solver={spec['solver']!r} is not allowed: analytic or bem")
    except BadInput:
        raise
    except ValueError as exc:
        raise op.named(exc, door, spec) from None


def _bem_problem(spec, door=op.PYTHON):
    """``(profile, material)`` of a BEM spec: its parsed profile and creep series (carried in
    the spec, else read again: a file that cannot be read is named at ``door``), None for the
    sinusoid of ``hk`` and the standard linear solid of ``ratio``."""
    profile = material = None
    if spec.get("profile") is not None:
        obj = spec.get("_profile")
        profile = obj if obj is not None else \
            read_input("profile", spec["profile"]["path"], door)[1]
    if spec.get("prony") is not None:
        obj = spec.get("_prony")
        material = obj if obj is not None else read_input("prony", spec["prony"]["path"], door)[1]
    elif spec.get("material") is not None:
        material = _material(spec).prony
    return profile, material


def _surface(spec, door=op.PYTHON):
    """A surface file's parsed Surface (carried in the spec, else read again), or None."""
    if spec["surface"].get("kind") != "file":
        return None
    obj = spec.get("_surface")
    if obj is not None:
        return obj
    desc = spec["surface"]
    extra = {k: desc[k] for k in ("units", "length") if desc.get(k) is not None}
    return read_input("surface", desc["path"], door, **extra)[1]


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
            obj = read_input("prony", spec["prony"]["path"], op.PYTHON)[1]
        info = {"form": "creep", **spec["prony"], "terms": len(obj.J),
                **_materials.references("creep", False, 1.0, None)}
    else:
        info = _materials.sls_description(spec.get("ratio"), spec.get("si"))
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
    out = {"spec": op.public(spec), "ok": False, "kind": "failed", "record": None, "error": None,
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
                n = spec.get("field_points") or op.DEFAULTS["field_points"]
                solved = roads.analytic_record(spec, n if fields else None, deep)
        rec = solved.record
        # the roads' own warnings are in the record already
        extra = [f"{w.category.__name__}: {w.message}" for w in caught
                 if not issubclass(w.category, ViscosineWarning)]
        rec["material"], rec["time_unit"] = describe_material(spec)
        if spec.get("si") is not None:
            rec["si_scales"] = spec["si"]
            if rec.get("success") and spec.get("surface") is not None:
                rec["si"] = surface_si_block(rec, spec["si"])
            elif rec.get("success"):
                rec["si"] = si_block(rec, spec["si"])
        if spec.get("material") is not None and rec.get("success"):
            from . import _materials
            text = _materials.extrapolation(_material(spec), spec["speed"],
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
                yield {"spec": op.public(specs[i]), "ok": False, "kind": "failed", "record": None,
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
