"""The operating point: one frozen type, made here and nowhere else.

Every door builds its point here: the command line (``point``, ``sweep``, ``bench``'s front
door, ``mastercurve``) with `build`, the report, the cross-check and the benchmarks with
`at`, ``verify`` and the suite read a case's point with `ratio_of`, `hk_of` and
`complete_case` (the case vocabulary: a plain dict of the keys given, no None).  This module is
the one place where

- the defaults apply (`DEFAULTS`: E∞/E0, hk, the adaptive meshes' accuracy targets, the points
  of the analytic fields, the sliding direction);
- options that do not apply are refused (`build`: a BEM option on the semi-analytic road, a
  material option without a material file, a mesh option beside a fixed mesh ...);
- SI input becomes the conventions' groups (`resolve_si`; the scales are echoed in the point's
  ``si`` and so in every record);
- the depth rule of a layer is written (`penetration_clears_layer`);
- a refusal names what the user typed (`PARAMETERS`, `named`, `refuse`, `missing`): on the
  command line its option (``--max-nodes 3 is not allowed: ...``, ``--ratio 3.0 is not allowed
  here: ...``, ``--E0 is missing: ...``), in Python its keyword (``max_nodes=3 ...``,
  ``ratio=3.0 is not allowed here: ...``, ``E0 is missing: ...``).

A point is a `OperatingPoint` (frozen); it reads like the plain spec dict it replaces
(``point["load"]``, ``point.get("layer")``: a read-only mapping of its public keys, the parsed
input files under ``"_profile"``, ``"_prony"``, ``"_material"``, ``"_surface"``), so that the
roads' adapters (`comparisons.roads`) take it as they take a dict, and `spec` is its JSON.
"""
from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping
from dataclasses import dataclass, field

import viscosine
from viscosine.checks import Refusal, shown
from viscosine.checks import allowed_part as _allowed_part

from ._errors import BadInput
from ._errors import one_line as _one_line

# ------------------------------------------------------------------------------ the defaults
#: every default of an operating point, applied in this module only.  ``rtol`` is the line
#: BEM's accuracy target (viscosine.DEFAULT_RTOL, the one value bem.solve reads too),
#: ``surface_rtol`` the surface BEM's (viscosine.SURFACE_RTOL), ``mastercurve_rtol`` the
#: master curve's (a curve of many points at 1e-3, not one at 1e-6).  Not to be confused with
#: verify's comparison tolerance (`comparisons.verify.DEFAULT_RTOL`), which judges a result.
DEFAULTS = {"ratio": 3.0, "hk": 1.0, "rtol": viscosine.DEFAULT_RTOL,
            "surface_rtol": viscosine.SURFACE_RTOL, "mastercurve_rtol": 1e-3,
            "field_points": 1024, "direction": 0.0}
#: points of the analytic fields (--nodes with --fields): 8 … 2^20 (about 10 µs per point)
FIELD_POINTS = (8, 2 ** 20)

# ------------------------------------------------------------------------------ the names
#: every parameter of an operating point → (the command line's option, the Python keyword).
#: A refusal (`viscosine.checks.Refusal`) names its parameter; `named` says it the way the
#: user typed it.  Several keywords may stand behind one option (the SI front's
#: ``mean_pressure`` is ``--load`` in SI; a layer's d/λ is ``--thickness``).
PARAMETERS = {
    "load": ("--load", "load"), "penetration": ("--penetration", "penetration"),
    "speed": ("--speed", "speed"), "ratio": ("--ratio", "ratio"), "hk": ("--hk", "hk"),
    "nodes": ("--nodes", "nodes"), "field_points": ("--nodes", "nodes"),
    "rtol": ("--rtol", "rtol"), "max_nodes": ("--max-nodes", "max_nodes"),
    "profile": ("--profile", "profile"), "prony": ("--prony", "prony"),
    "material": ("--material", "material"),
    "temperature": ("--temperature", "temperature"), "wlf": ("--wlf", "wlf"),
    "shift_table": ("--shift-table", "shift_table"),
    "max_residual": ("--max-residual", "max_residual"),
    "per_decade": ("--per-decade", "per_decade"),
    "loss_weight": ("--loss-weight", "loss_weight"),
    "extend": ("--extend", "extend"), "kind": ("--material-kind", "kind"),
    "frequency_unit": ("--frequency-unit", "frequency_unit"),
    "vertical": ("--vertical-shift", "vertical"), "method": ("--shift-method", "method"),
    "layer": ("--thickness (d/λ)", "layer"),
    "thickness_over_wavelength": ("--thickness (d/λ)", "thickness_over_wavelength"),
    "foundation": ("--foundation", "foundation"), "nu": ("--nu", "nu"),
    "surface": ("--surface", "surface"), "direction": ("--direction", "direction"),
    "hk_y": ("--hk-y", "hk_y"), "aspect": ("--aspect", "aspect"),
    "hurst": ("--hurst", "hurst"), "rolloff": ("--rolloff", "rolloff"),
    "short_cutoff": ("--short-cutoff", "short_cutoff"),
    "long_cutoff": ("--long-cutoff", "long_cutoff"),
    "rms_slope": ("--rms-slope", "rms_slope"), "rms_height": ("--rms-height", "rms_height"),
    "seed": ("--seed", "seed"),
    # --units SI: the SI front's keywords (viscosine.si) behind the options typed
    "mean_pressure": ("--load", "mean_pressure"), "E0": ("--E0", "E0"),
    "Einf": ("--Einf", "Einf"), "tau": ("--tau-creep", "tau"),
    "tau_creep": ("--tau-creep", "tau_creep"), "tau_relax": ("--tau-relax", "tau_relax"),
    "wavelength": ("--wavelength", "wavelength"), "amplitude": ("--amplitude", "amplitude"),
    "E_ref": ("--material", "E_ref"),
}
CLI, PYTHON = 0, 1


def option(name):
    """The command-line option of a parameter (``max_nodes`` → ``--max-nodes``)."""
    return PARAMETERS[name][CLI] if name in PARAMETERS else "--" + name.replace("_", "-")


def named(exc, door=CLI, point=None):
    """A road's refusal as `BadInput` naming the parameter as the user gave it: on the command
    line (``door`` CLI) its option and only what is allowed (``--load 0.0: must be ...``), in
    Python its keyword and the whole reason.  The parameter comes from the
    refusal itself (`viscosine.checks.Refusal`), never from its text; any other error keeps its
    text.  ``point``: the point refused (a whole layer is named by its thickness d/λ)."""
    if not isinstance(exc, Refusal) or exc.name not in PARAMETERS:
        return BadInput(_one_line(exc))
    name, value = exc.name, exc.value
    if door == CLI and name == "layer" and point is not None and point.get("layer"):
        value = point["layer"].get("thickness_over_wavelength")  # the layer as typed: its d/λ
    said = PARAMETERS[name][door]
    if door == CLI and name == "material" and point is not None:
        given = next((k for k in ("prony", "material") if point.get(k)), None)
        if given:  # a series read from a file: the file as typed, and which number is out
            path = os.path.basename(point[given].get("path", ""))
            return BadInput(f"--{given} {path}: {_one_line(exc.allowed).split('; ')[0]}")
    if door == CLI:  # one short line: what is allowed; why is in --help and the docs
        return must_be(said, shown(value), allowed_part(exc.allowed), exc.unit)
    tail = f" [{exc.unit}]" if exc.unit else ""
    return BadInput(f"{said}={shown(value)} is not allowed: {_one_line(exc.allowed)}{tail}")


def must_be(said, value, allowed, unit=None):
    """The command line's one form of a value out of range, ``<option> <value>: must be
    <allowed>[ [unit]]`` (``--load -1.0: must be ...``): every door's, the options that are a
    command's own (verify's ``--rtol``, ``--tol``, ``--dt``) included.  A string ``value`` is
    shown as typed."""
    tail = f" [{unit}]" if unit else ""
    return BadInput(f"{said} {value if isinstance(value, str) else shown(value)}: must be "
                    f"{allowed}{tail}")


def allowed_part(text):
    """What is allowed, without why (the --help's table of ranges): a reason up to its first
    ': ' outside brackets (`viscosine.checks.allowed_part`)."""
    return _allowed_part(_one_line(text))


def said(name, door=CLI):
    """A parameter as the user names it at a door: its option on the command line (``door``
    CLI, ``--max-nodes``), its keyword in Python (``door`` PYTHON, ``max_nodes``)."""
    if name in PARAMETERS:
        return PARAMETERS[name][door]
    return option(name) if door == CLI else name


def refuse(name, why, value=None, door=CLI):
    """The BadInput of an option that does not apply (``why`` says it at the same door): on
    the command line ``<option>[ value] is not allowed here: why`` (``--ratio 3.0 ...``), in
    Python ``<keyword>[=value] is not allowed here: why`` (``ratio=3.0 ...``)."""
    sep = " " if door == CLI else "="
    text = said(name, door) if value is None else f"{said(name, door)}{sep}{value}"
    return BadInput(f"{text} is not allowed here: {why}")


def missing(name, needs, door=CLI):
    """The one form of an option not given, at every door: ``<option> is missing: <needs>``
    (``--E0 is missing: --units SI needs --E0, --nu and --amplitude to convert SI fields``;
    in Python its keyword, ``door`` PYTHON).  ``needs``: what asks for it, and what to give."""
    return BadInput(f"{said(name, door)} is missing: {needs}")


#: why each option of the boundary-element road is refused on the semi-analytic one
_BEM_ONLY = {
    "thickness": "the semi-analytic road solves the half-space",
    "foundation": "the semi-analytic road solves the half-space",
    "profile": "the semi-analytic road: sinusoid, standard linear solid",
    "prony": "the semi-analytic road: sinusoid, standard linear solid",
    "material": "the semi-analytic road: sinusoid, standard linear solid",
    "surface": "the semi-analytic road solves the line contact",
    "rtol": "the semi-analytic road has no mesh",
    "max_nodes": "the semi-analytic road has no mesh",
}


def bem_only(name, value=None):
    """The refusal of a boundary-element option with ``--solver analytic`` (one wording)."""
    why = _BEM_ONLY[name]
    tail = "" if "mesh" in why else "; use --solver bem"
    return refuse(name, f"a BEM option ({why}{tail})", value)


# ------------------------------------------------------------------------------ the type
#: the keys every point has (its JSON), in order; `OPTIONAL_KEYS` only when given, so that the
#: point of every other run keeps its keys (and its hash in the results store)
SPEC_KEYS = ("solver", "load", "penetration", "speed", "ratio", "hk", "nodes", "rtol", "max_nodes",
             "profile", "prony", "field_points")
OPTIONAL_KEYS = ("si", "layer", "surface", "direction", "material")


@dataclass(frozen=True)
class OperatingPoint(Mapping):
    """One operating point, dimensionless (the conventions' groups), defaults applied.

    Read like a mapping of its public keys (`SPEC_KEYS`, and `OPTIONAL_KEYS` when set); the
    parsed input files it carries to the worker under ``"_" + option`` (never recorded).
    ``profile``, ``prony``, ``material``: the description of the file read (path, SHA-256,
    ...); ``si``: the SI scales of ``--units SI``; ``layer``: ``{"thickness_over_wavelength",
    "foundation", "nu"}``; ``surface``: a plain surface description (`comparisons.roads.surface`).
    """

    solver: str
    load: float | None = None
    penetration: float | None = None
    speed: float | None = None
    ratio: float | None = None
    hk: float | None = None
    nodes: int | None = None
    rtol: float | None = None
    max_nodes: int | None = None
    profile: dict | None = None
    prony: dict | None = None
    field_points: int | None = None
    si: dict | None = None
    layer: dict | None = None
    surface: dict | None = None
    direction: float | None = None
    material: dict | None = None
    parsed: dict = field(default_factory=dict, compare=False, repr=False)

    def keys(self):
        return [k for k in SPEC_KEYS] + [k for k in OPTIONAL_KEYS if getattr(self, k) is not None]

    def __iter__(self):
        return iter(self.keys())

    def __len__(self):
        return len(self.keys())

    def __getitem__(self, key):
        if key.startswith("_"):
            return self.parsed[key[1:]]
        if key in SPEC_KEYS or (key in OPTIONAL_KEYS and getattr(self, key) is not None):
            return getattr(self, key)
        raise KeyError(key)

    def replace(self, **changes):
        """This point with ``changes`` (a sweep's next value), its parsed files kept."""
        return dataclasses.replace(self, **changes)

    def spec(self):
        """The point as JSON (the public keys; what every record and the store keep)."""
        return {k: self[k] for k in self.keys()}


def public(spec):
    """A point's JSON: its keys without the parsed files (a point or a spec dict)."""
    return {k: v for k, v in spec.items() if not k.startswith("_")}


def from_spec(spec):
    """A point from a spec dict (a stored one, or one of the older plain form); keys starting
    with ``_`` are its parsed files."""
    if isinstance(spec, OperatingPoint):
        return spec
    public = {k: v for k, v in spec.items() if not k.startswith("_")}
    parsed = {k[1:]: v for k, v in spec.items() if k.startswith("_")}
    return OperatingPoint(**public, parsed=parsed)


def at(solver, speed, load=None, penetration=None, ratio=None, hk=None, nodes=None, *,
       layer=None, surface=None, direction=None):
    """A point of numbers only (the report, the cross-check, the benchmarks): the sinusoid of
    ``hk`` (a plain ``surface`` description instead, then no hk) on the standard linear solid,
    on the half-space or a plain ``layer``; the BEM's mesh ``nodes`` pinned, else adaptive at
    the default accuracy."""
    ratio = DEFAULTS["ratio"] if ratio is None else ratio
    hk = None if surface is not None else (DEFAULTS["hk"] if hk is None else hk)
    kw = dict(layer=None if layer is None else dict(layer))
    if surface is not None:
        kw.update(surface=dict(surface),
                  direction=DEFAULTS["direction"] if direction is None else float(direction))
    if solver == "bem":
        kw.update(nodes=nodes, rtol=None if nodes is not None else DEFAULTS[
            "surface_rtol" if surface is not None else "rtol"])
    return OperatingPoint(solver, load, penetration, speed, ratio, hk, **kw)


# ------------------------------------------------------------------------------ a case's point
def ratio_of(point):
    """E∞/E0 of a case's point dict (the default where it names none)."""
    r = point.get("ratio")
    return DEFAULTS["ratio"] if r is None else float(r)


def hk_of(point):
    """hk of a case's point dict (the default where it names none)."""
    h = point.get("hk")
    return DEFAULTS["hk"] if h is None else float(h)


def direction_of(point):
    """The sliding direction θ [degrees] of a case's point dict (default along +x)."""
    d = point.get("direction")
    return DEFAULTS["direction"] if d is None else float(d)


def complete_case(point):
    """A case's point dict without the options not given, with the defaults E∞/E0 and hk where
    no file replaces them (``verify``'s point; the order of its keys as given)."""
    point = dict(point)
    if not point.get("prony") and not point.get("material") and point.get("ratio") is None:
        point["ratio"] = DEFAULTS["ratio"]
    if not point.get("profile") and not point.get("surface") and point.get("hk") is None:
        point["hk"] = DEFAULTS["hk"]
    return {k: v for k, v in point.items() if v is not None}


# ------------------------------------------------------------------------------ layers
def penetration_clears_layer(penetration, amplitude, thickness):
    """The depth rule of a layer, one copy: a penetration ``penetration`` of an indenter of
    amplitude ``amplitude`` leaves the foundation untouched (Δ < d; any one unit: Δ/h with hk
    and k d, or metres).  Deeper, the indenter would reach the foundation."""
    return float(penetration) * float(amplitude) < float(thickness)


# ------------------------------------------------------------------------------ the command line
#: the options of a --material file (keys of ``material_options``)
MATERIAL_OPTIONS = ("temperature", "wlf", "shift_table", "max_residual", "per_decade",
                    "loss_weight", "extend", "kind", "frequency_unit", "vertical", "method")
#: those that steer the Prony fit of a DMA curve (refused for any other material)
FIT_OPTIONS = ("max_residual", "per_decade", "loss_weight")
#: why a fit option is refused where no DMA curve is fitted (every door says it)
FIT_ONLY = "it applies to a DMA curve (--material FILE with E', E'')"


def build(solver, *, load=None, penetration=None, speed=None, ratio=None, hk=None, nodes=None,
          rtol=None, max_nodes=None, profile=None, prony=None, fields=False, files=None,
          material=None, material_options=None, si=None, layer=None, surface=None,
          direction=None):
    """Command-line options (None = not given) → the `OperatingPoint`, defaults applied.

    Options that do not apply to the chosen inputs are refused, never recorded as if used:
    ``hk`` with ``profile``, ``ratio`` with ``prony``, ``profile``/``prony``/``rtol``/
    ``max_nodes`` on the analytic road, ``nodes`` on the analytic road without fields (there it
    is the number of points of the written fields), ``rtol``/``max_nodes`` with a fixed BEM mesh.

    Parameters
    ----------
    files : dict
        The input files, read (`comparisons.runner.read_files`): ``{"profile": (info, object),
        "prony": (info, object), "material": (info, Material), "surface": (info, Surface)}``
        for each file option given.
    material : str, optional
        A material file of any accepted form (`comparisons._materials`), BEM only, not with
        ``prony`` or ``ratio``.
    material_options : dict, optional
        `MATERIAL_OPTIONS` of the material (None = not given); only with ``material`` (the fit's
        `FIT_OPTIONS` only with a DMA curve: `comparisons._materials.read` refuses them for a
        series); ``si`` True reads the file in SI; ``nu`` (the Poisson ratio of a G', G''
        curve) is not checked here, since --nu is also --units SI's and a layer's.
    si : dict, optional
        ``--units SI``: the ``si`` description of `resolve_si` (the values are then its groups).
    layer : dict, optional
        ``{"thickness_over_wavelength", "foundation", "nu"}``, BEM only (checked by the BEM's
        Layer when the point is validated).
    surface : dict, optional
        A plain surface description (BEM only); the point then carries ``surface`` and
        ``direction``, its ``hk`` is None and its default ``rtol`` is the surface's.

    Raises
    ------
    BadInput
    """
    _refuse_inapplicable(solver, ratio=ratio, hk=hk, nodes=nodes, rtol=rtol,
                         max_nodes=max_nodes, profile=profile, prony=prony, fields=fields,
                         material=material, material_options=material_options, layer=layer)
    kw = dict(solver=solver, load=load, penetration=penetration, speed=speed, si=si,
              layer=None if layer is None else dict(layer))
    if surface is not None:
        kw["surface"] = dict(surface)
        kw["direction"] = DEFAULTS["direction"] if direction is None else direction
    if solver == "analytic":
        kw["ratio"] = DEFAULTS["ratio"] if ratio is None else ratio
        kw["hk"] = DEFAULTS["hk"] if hk is None else hk
        if fields:
            kw["field_points"] = DEFAULTS["field_points"] if nodes is None else nodes
        return OperatingPoint(**kw)
    files = dict(files or {})
    wanted = [n for n, v in (("profile", profile), ("prony", prony), ("material", material))
              if v is not None]
    if surface is not None and surface.get("kind") == "file":
        wanted.append("surface")
    if any(n not in files for n in wanted):  # read by the caller (`runner.read_files`)
        raise TypeError(f"files={sorted(files)}: the parsed {', '.join(wanted)} file(s) needed")
    parsed = {}
    if "surface" in wanted:
        info, parsed["surface"] = files["surface"]
        kw["surface"] = {"kind": "file", **info}
    fixed = prony is not None or material is not None
    kw["ratio"] = None if fixed else (DEFAULTS["ratio"] if ratio is None else ratio)
    kw["hk"] = None if profile is not None or surface is not None else (
        DEFAULTS["hk"] if hk is None else hk)
    kw["nodes"] = nodes
    if nodes is None:
        default = DEFAULTS["surface_rtol" if surface is not None else "rtol"]
        kw["rtol"] = default if rtol is None else rtol
        kw["max_nodes"] = max_nodes
    for name in ("profile", "prony", "material"):
        if name in files:
            kw[name], parsed[name] = files[name]
    return OperatingPoint(**kw, parsed=parsed)


def _refuse_inapplicable(solver, *, ratio, hk, nodes, rtol, max_nodes, profile, prony, fields,
                         material, material_options, layer):
    """`build`'s refusals: every option given where it does not apply (BadInput)."""
    options = {k: v for k, v in (material_options or {}).items() if v is not None}
    options.pop("si", None)  # how the file was read (`runner.read_files`)
    options.pop("nu", None)  # a G', G'' curve's ν: also --units SI's and a layer's (cli)
    if options and material is None:
        name = next(iter(options))
        raise refuse(name, FIT_ONLY if name in FIT_OPTIONS else "it applies to a --material "
                     "file (give the material with --material FILE)")
    if material is not None and prony is not None:
        raise refuse("material", "--prony gives the material already (--material reads the same "
                     "creep-series files, and relaxation series and DMA curves)")
    if solver == "analytic":
        for name, value in (("thickness", layer), ("profile", profile), ("prony", prony),
                            ("material", material), ("rtol", rtol), ("max_nodes", max_nodes)):
            if value is not None:
                raise bem_only(name)
        if nodes is not None and not fields:
            raise refuse("nodes", "on the semi-analytic road --nodes is the number of points of "
                         "--fields, and no --fields was given")
    elif solver == "bem":
        if hk is not None and profile is not None:
            raise refuse("hk", "the --profile file fixes the indenter and its amplitude")
        if ratio is not None and (prony is not None or material is not None):
            raise refuse("ratio", f"the --{'prony' if prony is not None else 'material'} file "
                         "fixes the material")
        if nodes is not None and (rtol is not None or max_nodes is not None):
            raise refuse("rtol" if rtol is not None else "max_nodes",
                         f"--nodes {nodes} fixes the mesh; --rtol and --max-nodes steer the "
                         "adaptive refinement (without --nodes)")
    else:
        raise BadInput(f"--solver {solver!r} is not allowed: analytic or bem")


# ------------------------------------------------------------------------------ SI inputs
def resolve_si(solver, si, *, loads=None, penetrations=None, speeds, material=None, groups):
    """``--units SI``: SI values of a point or a sweep turned into the dimensionless groups.

    Parameters
    ----------
    si : dict
        The SI options given (keywords of `viscosine.si`, None = not given): ``nu``,
        ``wavelength``, ``amplitude`` always; the standard linear solid's ``E0``, ``Einf`` and
        one time (``tau_creep`` or ``tau_relax``) unless ``material`` is given.
    loads, penetrations : list of float
        Mean pressures p∞ [Pa] or penetrations Δ [m] (exactly one list).
    speeds : list of float
        V [m/s].
    material : Material, optional
        Read with ``si=True``: reference modulus its relaxed modulus E_r [Pa], time 1 s.
    groups : callable
        ``groups(solver, scales)``: the road's dimensionless groups of the SI scales, each
        checked by the road (`comparisons.roads.si_groups`; this module calls no road).

    Returns
    -------
    dict
        ``load`` or ``penetration`` and ``speed`` (lists of groups), ``ratio`` (the solid's, or
        None), ``hk``, and ``si``: the JSON description of the scales
        (`viscosine.si.SIScales.describe`: values, ``units`` key → unit, the solid's
        ``tau_creep``, ``tau_relax`` and ``time_given``); the point's ``si``, so every record
        echoes the conversion as ``si_scales``.

    Raises
    ------
    BadInput
        A missing, extra or invalid SI option, or a group outside the road's accepted range,
        named by the option the user typed.
    """
    given = {k: v for k, v in si.items() if v is not None}
    need = ["nu", "wavelength", "amplitude"]
    if material is None:
        need += ["E0", "Einf"]
        if not {"tau", "tau_creep", "tau_relax"} & set(given):
            need.append("tau_creep")
    else:
        extra = [k for k in ("E0", "Einf", "tau", "tau_creep", "tau_relax") if k in given]
        if extra:
            raise BadInput(f"{option(extra[0])} is not allowed with --material: the "
                           "material file fixes the moduli and times")
    absent = [k for k in need if k not in given]
    if absent:
        raise missing(absent[0], "--units SI needs --nu, --wavelength, --amplitude and "
                      "--material or --E0 --Einf --tau-creep (or --tau-relax)")
    if material is None and "tau_creep" in given and "tau_relax" in given:
        raise BadInput(f"--tau-relax {shown(given['tau_relax'])} is not allowed with "
                       "--tau-creep: give one time of the solid")
    key = "load" if loads is not None else "penetration"
    values = loads if loads is not None else penetrations

    def scales(value, speed):
        return _si_scales(solver, given, material, speed,
                          {"mean_pressure" if key == "load" else "penetration": value}, groups)

    sc, _ = scales(values[0], speeds[0])
    out = {"load": None, "penetration": None}
    out[key] = [scales(v, speeds[0])[1][key] for v in values]
    out["speed"] = [scales(values[0], v)[1]["speed"] for v in speeds]
    out["ratio"], out["hk"] = sc.ratio, sc.hk
    # the scales as the Python door's records give them (`viscosine.si.SIScales.describe`):
    # each value, its unit, and for the solid both times and which was given
    out["si"] = dict(sc.describe(), load_is="p_inf (1 - nu^2)/E_ref, p_inf the --load [Pa]",
                     speed_is="V tau_ref k, V the --speed [m/s], k = 2 pi/wavelength")
    return out


def _si_scales(solver, given, material, speed, control, groups):
    """The SI front's scales of one point and its groups, checked by the road (a refusal named
    by the option typed)."""
    from viscosine import si as si_front
    geometry = dict(nu=given["nu"], wavelength=given["wavelength"],
                    amplitude=given["amplitude"], speed=speed, **control)
    try:
        if material is None:
            sc = si_front.scales(**{k: given.get(k) for k in ("E0", "Einf", "tau", "tau_creep",
                                                              "tau_relax")}, **geometry)
        else:
            sc = si_front.material_scales(E_ref=material.info["E_ref"], tau_ref=1.0, **geometry)
        return sc, groups(solver, sc)
    except ValueError as exc:
        raise named(exc) from None


def check_field_points(n):
    """The points of the analytic fields (``--nodes`` with ``--fields``), in `FIELD_POINTS`."""
    from viscosine.checks import integer
    low, high = FIELD_POINTS
    integer("nodes", n, f"an integer in [{low}, {high}] (points of the written fields)",
            lambda v: low <= v <= high)


__all__ = ["DEFAULTS", "FIELD_POINTS", "PARAMETERS", "CLI", "PYTHON", "SPEC_KEYS",
           "OPTIONAL_KEYS", "MATERIAL_OPTIONS", "FIT_OPTIONS", "FIT_ONLY", "OperatingPoint",
           "at", "build", "bem_only", "refuse", "missing", "said", "named", "must_be", "option",
           "public", "from_spec", "ratio_of", "hk_of", "direction_of", "complete_case",
           "penetration_clears_layer", "resolve_si", "check_field_points"]
