"""The operating point of a verification: from a suite case, a dict or the command's options,
checked as the two roads accept it (conventions units; SI options converted)."""
from __future__ import annotations

from pathlib import Path

from viscosine.checks import Refusal, shown

from .. import operating_point as op
from .. import roads
from .. import suite as _suite
from .._errors import BadInput, bad_input
from .._errors import one_line as _one_line
from .._io import read_text


def point_from_case(name):
    """(operating point with absolute file paths, suite case) of a suite case."""
    try:
        case = _suite.get_case(name)
    except _suite.SuiteError:
        import difflib
        names = _suite.case_names()
        near = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        raise bad_input("--case", name, "not a suite case",
                        f"one of the {len(names)} cases of `suite --list`"
                        + (f" (closest: {', '.join(near)})" if near else
                           f", e.g. {', '.join(names[:2])}")) from None
    point = dict(case["point"])
    for k in ("profile", "prony", "material"):
        if point.get(k):
            point[k] = str(_suite.data_path(point[k]))
    return point, case


def is_surface_case(name):
    """Whether ``name`` is a surface case of the suite (an unknown name is `point_from_case`'s
    to refuse)."""
    try:
        return _suite.is_surface(_suite.get_case(name))
    except _suite.SuiteError:
        return False


def check_point(point, door=op.CLI):
    """BadInput unless the operating point dict is valid: the options that go together, then
    the ranges of the road that gives the reference (`_reference.reference_for`: the
    semi-analytic road's where it applies, else the BEM's), refused as every door refuses them
    (`comparisons.operating_point.named`, `refuse`, `missing`: on the command line, ``door``
    CLI, ``--load -1.0: must be ...``, ``--ratio 3.0 is not allowed here: ...``; in Python,
    ``door`` PYTHON, ``load=-1.0 is not allowed: ...``, ``ratio=3.0 is not allowed here: the
    prony file fixes the material``, ``speed is missing: ...``)."""
    def kw(name):  # the parameter as the user names it at this door
        return op.said(name, door)

    if point.get("load") is not None and point.get("penetration") is not None:
        raise op.refuse("penetration", f"give one of {kw('load')} and {kw('penetration')}",
                        shown(point["penetration"]), door)
    if point.get("load") is None and point.get("penetration") is None:
        raise op.missing("load", f"give {kw('load')} or {kw('penetration')}", door)
    if point.get("prony") and point.get("ratio") is not None:
        raise op.refuse("ratio", f"the {kw('prony')} file fixes the material",
                        shown(point["ratio"]), door)
    if point.get("profile") and point.get("hk") is not None:
        raise op.refuse("hk", f"the {kw('profile')} file fixes the indenter and its amplitude",
                        shown(point["hk"]), door)
    if point.get("speed") is None:
        raise op.missing("speed", "give the sliding speed V/V0", door)
    if point.get("layer") is not None:
        check_layer(point["layer"], "--layer" if door == op.CLI else "layer", point)
    problem = [None, None]
    for i, (k, reader) in enumerate((("profile", roads.read_profile),
                                     ("prony", roads.read_prony))):
        if point.get(k):
            path = point[k]
            read_text("--" + k, path, f"a {k} file (see bem.read_{k})")
            try:
                problem[i] = reader(path)
            except Refusal as exc:  # what the reader refuses, without its parameter's name
                raise bad_input("--" + k, path, exc.allowed,
                                f"the format of bem.read_{k}") from None
            except ValueError as exc:
                raise bad_input("--" + k, path, _one_line(exc),
                                f"the format of bem.read_{k}") from None
    try:  # the reference's road checks its own ranges (one table, one wording)
        if _suite.two_roads(point):
            roads.validate_analytic(point)
        else:
            roads.validate_bem(point, tuple(problem))
    except BadInput:
        raise
    except ValueError as exc:
        raise op.named(exc, door, point) from None
    return point


#: what a point's ``layer`` may be (the plain description of `comparisons.roads.layer`)
LAYER_ALLOWED = ("a dict with thickness_over_wavelength (d/λ) or thickness (k d), foundation "
                 "('bonded' or 'frictionless') and nu in (-1, 0.5]")


#: the finest mesh of the reference's convergence study (`_reference`: N = 2^10 … 2^18)
STUDY_FINEST = 2 ** 18


def check_layer(layer, option="layer", point=None):
    """BadInput unless ``layer`` is a plain layer description the BEM takes (the layer's own
    refusal, naming its parameter, in one line), thick enough for the reference's study
    (`STUDY_FINEST` panels: a thinner layer caps the mesh, `bem.Layer.finest_nodes`) and, under
    penetration control on the sinusoid of ``point``, one the penetration does not cross."""
    keys = {"thickness", "thickness_over_wavelength", "foundation", "nu"}
    if not isinstance(layer, dict) or not set(layer) <= keys:
        raise bad_input(option, layer, "not a layer description", LAYER_ALLOWED)
    try:
        lay = roads.layer(layer)
    except (TypeError, ValueError) as exc:
        raise bad_input(option, layer, str(exc).splitlines()[0], LAYER_ALLOWED) from None
    if lay.finest_nodes < STUDY_FINEST:
        raise bad_input(option, layer, f"too thin for the reference's convergence study (its "
                        f"lowest mode allows at most {lay.finest_nodes} panels)",
                        f"a layer that allows {STUDY_FINEST} panels (thicker)")
    pen, hk = (point or {}).get("penetration"), (point or {}).get("hk")
    if pen is not None and hk is not None and not op.penetration_clears_layer(pen, hk,
                                                                               lay.thickness):
        raise bad_input(option, layer, f"the penetration Δ/h = {pen!r} would reach the "
                        f"foundation (k d/hk = {lay.thickness / float(hk):.6g})",
                        "Δ/h < k d/hk")
    return layer


def complete(point):
    """The operating point without the options not given, with the defaults
    (`comparisons.operating_point.complete_case`), and its files' paths absolute."""
    point = op.complete_case(point)
    for k in ("profile", "prony"):
        if point.get(k):
            point[k] = str(Path(point[k]).resolve())
    return point


def point_and_case(case):
    """(operating point, suite case or None) of the Python API's ``case``: a suite case's name
    or an operating-point dict."""
    if isinstance(case, str):
        return point_from_case(case)
    if isinstance(case, dict):  # E∞/E0 and hk lead the point (its order shows in messages)
        return check_point(complete({"ratio": None, "hk": None, **case}), op.PYTHON), None
    raise TypeError(f"case={case!r}: a suite case name or an operating-point dict")


def point_from_args(args):
    """(operating point, case, SI scales or None) from the parsed options."""
    given = {k: getattr(args, k) for k in ("load", "penetration", "speed", "ratio", "hk",
                                            "profile", "prony")}
    if args.case:
        extra = [k for k, v in given.items() if v is not None]
        if extra:
            raise op.refuse(extra[0], "--case gives the operating point",
                            shown(given[extra[0]]))
        point, case = point_from_case(args.case)
        si = None
        if args.units == "SI":
            si = si_fields(args)
        return point, case, si
    if given["speed"] is None:
        raise op.missing("speed", "give --case NAME, or --speed with --load or --penetration")
    if args.units == "SI":
        if given["profile"] or given["prony"]:
            raise op.refuse("units", "SI points are the sinusoid on the standard linear "
                            "solid (not --profile or --prony)", "SI")
        need = [k for k in ("E0", "Einf", "nu", "wavelength", "amplitude")
                if getattr(args, k) is None]
        if args.tau_creep is None and args.tau_relax is None:
            need.insert(2, "tau_creep")
        if need:
            raise op.missing(need[0], "--units SI needs --E0 --Einf, --tau-creep or "
                             "--tau-relax, --nu --wavelength --amplitude")
        si = {k: getattr(args, k) for k in ("E0", "Einf", "tau_creep", "tau_relax", "nu",
                                             "wavelength", "amplitude")}
        control = ({"loads": [given["load"]]} if given["load"] is not None else
                   {"penetrations": [given["penetration"]]})
        # the SI door of every command (`operating_point.resolve_si`): the groups checked by
        # the reference's road (the sinusoid on the standard linear solid: semi-analytic)
        res = op.resolve_si("analytic", si, speeds=[given["speed"]], groups=roads.si_groups,
                            **control)
        point = {k: res[k][0] for k in ("load", "penetration") if res[k] is not None}
        point = dict(point, speed=res["speed"][0], ratio=res["ratio"], hk=res["hk"])
        return check_point(point), None, si_fields(args)
    # the options given, in the parser's order; a default follows them
    point = {k: v for k, v in given.items() if v is not None}
    return check_point(complete(point)), None, None


def si_fields(args):
    """(E0 [Pa], ν, amplitude h [m]) that convert SI fields (`to_conventions`), checked."""
    need = [k for k in ("E0", "nu", "amplitude") if getattr(args, k) is None]
    if need:
        raise op.missing(need[0], "--units SI needs --E0, --nu and --amplitude to convert SI "
                         "fields")
    from viscosine import si as si_front
    try:  # the SI front's own checks of E0, ν and h
        return si_front.field_scales(E0=args.E0, nu=args.nu, amplitude=args.amplitude)
    except ValueError as exc:
        raise op.named(exc) from None
