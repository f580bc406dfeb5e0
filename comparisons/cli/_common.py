"""What the subcommands share: the parser class, the option types and actions, the exit
statuses and errors, the option groups of point and sweep (and of the parallel subcommands) and
the checks that turn their options into a validated spec before any work."""
from __future__ import annotations

import argparse
import math
import re

from .. import operating_point as op
from .. import roads, runner
from .._errors import BadInput, Failed
from .._io import check_output_dir, check_output_file, stderr

__all__ = ["EXIT_OK", "EXIT_FAILED", "EXIT_BAD_INPUT", "MAX_RANGE_COUNT", "BadInput", "Failed",
           "Parser", "Once", "number", "integer", "log_range", "solver_options",
           "parallel_options", "accepted_ranges", "check_output_file", "check_output_dir",
           "check_workers", "resolve", "units_si", "material_options", "validate", "stderr",
           "surface_description"]

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2
#: one log range START:STOP:COUNT holds at most this many values
MAX_RANGE_COUNT = 1_000_000


class Parser(argparse.ArgumentParser):
    #: a value that starts with '-' and a digit is a value (a negative number, 1e-3, or a log
    #: range such as -1:10:5), never an option: the roads then say what is allowed
    _VALUE = re.compile(r"^-(\d|\.\d)[\w.:+-]*$")

    def __init__(self, *a, **k):
        k.setdefault("allow_abbrev", False)  # --no must not silently mean --nodes
        super().__init__(*a, **k)
        self._negative_number_matcher = self._VALUE

    def error(self, message):  # one line, no usage dump
        raise BadInput(message, prog=self.prog)

    def format_help(self):  # an epilog made when asked for (it may import the roads)
        make = getattr(self, "epilog_maker", None)
        if make is not None:
            self.epilog = make()
        return super().format_help()


class Once(argparse.Action):
    """Store an option's value, refusing the option given twice (never silently the last)."""

    def __call__(self, parser, namespace, values, option_string=None):
        given = namespace.__dict__.setdefault("_given", set())
        if self.dest in given:
            parser.error(f"{option_string} given twice")
        given.add(self.dest)
        if self.nargs in ("+", "*"):  # a sweep token may be a list (a log range)
            values = [v for token in values
                      for v in (token if isinstance(token, list) else [token])]
        setattr(namespace, self.dest, values)


class WhichTime(argparse.Action):
    """A bare ``--tau``: refused, naming the two times to choose from (a relaxation time taken
    for a creep time shifts every speed by E∞/E0)."""

    def __init__(self, option_strings, dest, **kw):
        kw.setdefault("help", argparse.SUPPRESS)
        super().__init__(option_strings, dest, **kw)

    def __call__(self, parser, namespace, values, option_string=None):
        parser.error(f"{option_string} {values}: which time? (allowed: --tau-creep [s], the "
                     "creep time of eq. 2.3, or --tau-relax [s], the relaxation time τ E0/Einf)")


def number(text):
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def integer(text):
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None


def log_range(text):
    """Values of one sweep token: a number, or START:STOP:COUNT (COUNT log-spaced values from
    START to STOP, both included exactly).

    Raises
    ------
    argparse.ArgumentTypeError
    """
    if ":" not in text:
        return [number(text)]
    parts = text.split(":")
    bad = argparse.ArgumentTypeError
    if len(parts) != 3:
        raise bad(f"{text!r}: a log range is START:STOP:COUNT")
    a, b = (number(p) for p in parts[:2])
    try:
        k = int(parts[2])
    except ValueError:
        raise bad(f"{text!r}: COUNT must be an integer") from None
    if not (math.isfinite(a) and math.isfinite(b) and a > 0 and b > 0):
        raise bad(f"{text!r}: START and STOP of a log range must be finite and > 0")
    if not 1 <= k <= MAX_RANGE_COUNT or (k == 1 and a != b):
        raise bad(f"{text!r}: COUNT must be in [2, {MAX_RANGE_COUNT}] "
                  "(1 only when START = STOP)")
    if k == 1:
        return [a]
    la, lb = math.log10(a), math.log10(b)
    vals = [10.0 ** (la + (lb - la) * j / (k - 1)) for j in range(k)]
    vals[0], vals[-1] = a, b  # the ends exactly as written
    return vals


# ------------------------------------------------------------------------------ option groups
_SPEED_HELP = ("V τ_ref k ≥ 0, τ_ref the creep (retardation) time τ of the standard linear "
               "solid (not its relaxation time τ E0/E∞), or the time unit of the --prony/"
               "--material file (1 s for a DMA curve); every record states it (time_unit); "
               "with --units SI, V [m/s]")
_LOAD_HELP = ("p̃∞ = p∞(1 − ν²)/E_ref > 0, E_ref = E0 (or the --prony/--material file's "
              "reference modulus); with --units SI, p∞ [Pa]")


def solver_options(p, several):
    """Options shared by point and sweep; `several`: sweep's lists and ranges of values."""
    p.add_argument("--solver", choices=["analytic", "bem"], required=True, action=Once)
    g = p.add_mutually_exclusive_group(required=True)
    if several:
        rng = " (values, or log ranges START:STOP:COUNT)"
        g.add_argument("--load", type=log_range, nargs="+", action=Once, metavar="P",
                       help=_LOAD_HELP + rng)
        g.add_argument("--penetration", type=log_range, nargs="+", action=Once,
                       metavar="D", help="Δ/h in (0, 1]" + rng)
        p.add_argument("--speed", type=log_range, nargs="+", required=True,
                       action=Once, metavar="S", help=_SPEED_HELP + rng)
    else:
        g.add_argument("--load", type=number, action=Once, metavar="P",
                       help=_LOAD_HELP)
        g.add_argument("--penetration", type=number, action=Once, metavar="D",
                       help="Δ/h in (0, 1]; the load is then an output")
        p.add_argument("--speed", type=number, required=True, action=Once,
                       metavar="S", help=_SPEED_HELP)
    p.add_argument("--ratio", type=number, action=Once, metavar="R",
                   help="E∞/E0 (default 3); not with --prony or --material")
    p.add_argument("--hk", type=number, action=Once, metavar="H",
                   help="h k (default 1); not with --profile")
    p.add_argument("--nodes", type=integer, action=Once, metavar="N",
                   help="BEM: a fixed mesh of N panels per period (default: adaptive); analytic: "
                        "points of --fields (default 1024), only with --fields")
    p.add_argument("--rtol", type=number, action=Once, metavar="T",
                   help="BEM without --nodes: refine until every estimated error is below T "
                        f"(default {op.DEFAULTS['rtol']:g})")
    p.add_argument("--max-nodes", type=integer, action=Once, metavar="M",
                   help="BEM without --nodes: the finest mesh the refinement may reach")
    p.add_argument("--profile", action=Once, metavar="FILE",
                   help="BEM only: periodic profile file (bem.read_profile); replaces the sinusoid")
    p.add_argument("--prony", action=Once, metavar="FILE",
                   help="BEM only: Prony-series creep function file (bem.read_prony: creep "
                        "times, in tau_ref); replaces the standard linear solid")
    p.add_argument("--material", action=Once, metavar="FILE",
                   help="BEM only: a material file, told by its first line: a creep series "
                        "('J0 <value>' then 'J_i tau_i', creep times), a relaxation series "
                        "('E_r <value>' then 'E_i theta_i', relaxation times) or a DMA master "
                        "curve (CSV header frequency, storage, loss; fitted with a Prony series, "
                        "E_ref its relaxed modulus, tau_ref 1 s); also raw isotherms (a "
                        "temperature column too: superposed at --temperature), E(t)/J(t) tables "
                        "and FE Prony cards (ANSYS, Abaqus, LS-DYNA, pyvisco); docs/materials.md."
                        "  Not with --prony or --ratio")
    dma_fit_options(p)
    p.add_argument("--temperature", type=number, action=Once, metavar="T",
                   help="--material at temperature T: every time of the material multiplied by "
                        "a_T(T) (the file holds it at the shift's reference temperature); with "
                        "--wlf or --shift-table")
    shift = p.add_mutually_exclusive_group()
    shift.add_argument("--wlf", type=number, nargs=3, action=Once, metavar=("C1", "C2", "TREF"),
                       help="WLF shift log10 a_T = -C1 (T - TREF)/(C2 + T - TREF)")
    shift.add_argument("--shift-table", action=Once, metavar="FILE",
                       help="shift table CSV (columns temperature, log_aT), linear in log10 a_T, "
                            "no extrapolation")
    p.add_argument("--thickness", type=number, action=Once, metavar="D",
                   help="BEM only: a layer of thickness d on a rigid foundation in place of the "
                        "half-space, D = d/λ (with --units SI, d [m]); needs --foundation and "
                        "--nu; docs/layers.md")
    p.add_argument("--foundation", choices=["bonded", "frictionless"], action=Once,
                   help="with --thickness: the layer's lower face bonded to the foundation, or "
                        "lying on it without friction")
    surface_options(p)
    p.add_argument("--units", choices=["conventions", "SI"], action=Once,
                   help="SI: --load is p∞ [Pa] (--penetration Δ [m]), --speed V [m/s], with "
                        "--nu, --wavelength, --amplitude and the material (--E0 --Einf with "
                        "--tau-creep or --tau-relax, or --material: series files in Pa and s, a "
                        "DMA curve in its header's unit); the record adds 'si' (default: the "
                        "conventions' dimensionless groups)")
    for names, unit, what in ((("--E0",), "Pa", "relaxed modulus of the standard linear solid"),
                              (("--Einf",), "Pa", "instantaneous (glassy) modulus, > E0"),
                              (("--tau-creep",), "s", "creep (retardation) time τ of "
                               "the solid, eq. (2.3); the speed group is V τ k"),
                              (("--tau-relax",), "s", "relaxation time of the solid, τ E0/Einf "
                               "(instead of --tau-creep)"),
                              (("--nu",), "-", "Poisson's ratio (also, with --thickness, "
                               "the layer's: its factor S(kd, ν); and with a --material of "
                               "shear moduli, in any units, E = 2 (1 + ν) G; an LS-DYNA "
                               "card's own ν replaces it within 1e-3)"),
                              (("--wavelength",), "m", "λ of the sinusoid (with --surface: "
                               "the cell's side Lx)"),
                              (("--amplitude",), "m", "h of the sinusoid (with --surface "
                               "bisinusoid: h of each sinusoid; a FILE fixes its own)")):
        p.add_argument(*names, type=number, action=Once, metavar="X",
                       help=f"--units SI: {what} [{unit}]")
    p.add_argument("--tau", action=WhichTime, dest="_tau")


def dma_fit_options(p):
    """The options of reading and fitting a measured --material (point, sweep, mastercurve):
    one flag per keyword of the materials API (`comparisons._materials.FLAGS`)."""
    p.add_argument("--max-residual", type=number, action=Once, metavar="B",
                   help="DMA --material: the largest relative residual on E' or E'' the Prony "
                        "fit may leave, else refused (default: no bound, the residuals are "
                        "reported)")
    p.add_argument("--per-decade", type=number, action=Once, metavar="K",
                   help="DMA --material: relaxation times per decade of the fit (default: "
                        "chosen by held-out residual)")
    p.add_argument("--loss-weight", type=number, action=Once, metavar="W",
                   help="DMA --material: the fit's weight of E'' against E' (default 1: equal; "
                        "0 fits E' alone; large follows E''), >= 0")
    p.add_argument("--extend", type=number, action=Once, metavar="DECADES",
                   help="DMA, isotherms, E(t)/J(t) --material: decades of relaxation times the "
                        "fit adds beyond the data on each side, in [0, 5] (default 1)")
    p.add_argument("--material-kind", choices=["E", "G"], action=Once, dest="kind",
                   help="DMA --material: tensile (E', E'') or shear (G', G'', with --nu) moduli "
                        "(default: the column names say)")
    p.add_argument("--frequency-unit", choices=["Hz", "rad/s"], action=Once,
                   help="DMA or isotherms --material: the unit of the frequency column when the "
                        "header names none (default rad/s; a header's unit must agree)")
    p.add_argument("--vertical-shift", choices=["none", "temperature", "fitted"], action=Once,
                   dest="vertical",
                   help="raw isotherms: no vertical shift (default), T0 rho0/(T rho) (the file "
                        "states its temperature unit), or fitted per pair")
    p.add_argument("--shift-method", choices=["moduli", "tan_delta"], action=Once,
                   dest="method",
                   help="raw isotherms: horizontal shifts from log E' and log E'' (default) or "
                        "from log tan δ")


def surface_options(p):
    """The options of a surface (three-dimensional contact; BEM only; docs/surfaces.md)."""
    g = p.add_argument_group("surfaces (BEM only: a rigid periodic surface z = h(x, y) on a "
                             "cell Lx x Ly, lengths over Lx, heights as k z with k = 2π/Lx)")
    g.add_argument("--surface", action=Once, metavar="{bisinusoid,self-affine,FILE}",
                   help="the surface: bisinusoid (h cos kx + h_y cos 2πy/Ly: --hk, --hk-y, "
                        "--aspect), self-affine (--hurst --rolloff --short-cutoff "
                        "[--long-cutoff] --rms-slope|--rms-height [--seed] [--aspect]) or a "
                        "FILE of heights k z on a grid (rows along x, columns along y; "
                        "bem.read_surface)")
    g.add_argument("--direction", type=number, action=Once, metavar="DEG",
                   help="sliding direction θ in degrees from +x, counter-clockwise (default 0)")
    for name, what in (("--hk-y", "bisinusoid: k h_y, the amplitude along y (default --hk; 0: "
                                  "uniform in y, the line contact extruded)"),
                       ("--aspect", "Ly/Lx of the cell (default 1; a FILE's may say it in a "
                                    "'# aspect: A' line)"),
                       ("--hurst", "self-affine: Hurst exponent H in (0, 1)"),
                       ("--rolloff", "self-affine: roll-off wavenumber q_r/k"),
                       ("--short-cutoff", "self-affine: short-wavelength cut-off q_s/k (≤ 512)"),
                       ("--long-cutoff", "self-affine: long-wavelength cut-off q_l/k ≥ 1 "
                                         "(default 1)"),
                       ("--rms-slope", "self-affine: rms slope sqrt<|∇z|²> (or --rms-height)"),
                       ("--rms-height", "self-affine: rms height k z_rms (or --rms-slope)")):
        g.add_argument(name, type=number, action=Once, metavar="X", help=what)
    g.add_argument("--seed", type=integer, action=Once, metavar="N",
                   help="self-affine: seed of the random phases (default 0)")


#: the self-affine surface's parameters (keywords of bem.self_affine; options in
#: `operating_point.PARAMETERS`)
_SELF_AFFINE = ("hurst", "rolloff", "short_cutoff", "long_cutoff", "rms_slope", "rms_height",
                "seed")


def surface_description(args):
    """The spec's ``surface`` (a plain dict) of --surface and its options, or None without
    --surface (options of a surface without it are refused).  The values as given: the BEM's
    surface constructors check them (`runner.validate`)."""
    given = {k: getattr(args, k) for k in ("hk_y", "aspect", "direction", *_SELF_AFFINE)}
    if args.surface is None:
        extra = [k for k, v in given.items() if v is not None]
        if extra:
            name = op.option(extra[0])
            raise BadInput(f"{name} is not allowed without --surface: an option of a surface "
                           "(three-dimensional contact)")
        return None
    if args.solver != "bem":
        raise op.bem_only("surface", args.surface)
    if args.profile is not None:
        raise BadInput("--profile is not allowed with --surface: the surface replaces the "
                       "profile")
    kind = args.surface
    desc = {"aspect": given["aspect"]}
    if kind == "bisinusoid":
        wrong = [k for k in _SELF_AFFINE if given[k] is not None]
        if wrong:
            raise BadInput(f"{op.option(wrong[0])} is not allowed with --surface bisinusoid: "
                           "an option of --surface self-affine")
        desc.update(kind="bisinusoid", hk=args.hk, hk_y=given["hk_y"])
    elif kind == "self-affine":
        if args.hk is not None or given["hk_y"] is not None:
            raise BadInput(f"--{'hk' if args.hk is not None else 'hk-y'} is not allowed with "
                           "--surface self-affine: its relief is set by --rms-slope or "
                           "--rms-height")
        desc.update(kind="self_affine", **{k: given[k] for k in _SELF_AFFINE})
    else:
        if args.hk is not None or given["hk_y"] is not None or any(
                given[k] is not None for k in _SELF_AFFINE):
            extra = "--hk" if args.hk is not None else "--hk-y" if given["hk_y"] is not None \
                else next(op.option(k) for k in _SELF_AFFINE if given[k] is not None)
            raise BadInput(f"{extra} is not allowed with --surface FILE: the file fixes the "
                           "surface")
        desc.update(kind="file", path=kind)
    return desc


def parallel_options(p, what):
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=integer, action=Once, metavar="W",
                   help=f"local processes ({what})")
    g.add_argument("--scheduler", action=Once, metavar="ADDRESS",
                   help="run on the Dask distributed cluster of this scheduler (e.g. "
                        "tcp://host:8786; needs viscosine[cluster]); not with --workers")


def accepted_ranges():
    """The accepted range of every input of point and sweep, from analytic.ACCEPTED and
    bem.ACCEPTED (for --help)."""
    import textwrap

    from .. import roads
    tables = {"analytic": roads.accepted("analytic"), "bem": roads.accepted("bem")}
    rows = [("--load", "load"), ("--penetration", "penetration"), ("--speed", "speed"),
            ("--ratio", "ratio"), ("--hk", "hk"), ("--nodes", "nodes"), ("--rtol", "rtol"),
            ("--max-nodes", "max_nodes"), ("--profile", "profile"), ("--prony", "material")]
    lines = textwrap.wrap("accepted inputs (analytic.ACCEPTED and bem.ACCEPTED give the reason "
                          "for each bound; outside them: exit status 2, nothing solved):", 96)
    for option, key in rows:
        for road, table in tables.items():
            if key in table:
                lines += textwrap.wrap(f"{road}: {op.allowed_part(table[key][2])}", 96,
                                       initial_indent=f"  {option:<15}" if road == "analytic"
                                       or key not in tables["analytic"] else " " * 17,
                                       subsequent_indent=" " * 21)
    return "\n".join(lines)


# ------------------------------------------------------------------------------ shared checks
def check_workers(args):
    if getattr(args, "workers", None) is not None and args.workers < 1:
        raise BadInput(f"--workers {args.workers} is not allowed: an integer ≥ 1")


def resolve(args, *, load=None, penetration=None, speed=None, files=None, si=None):
    """The `OperatingPoint` of point's and sweep's options (`operating_point.build`: defaults,
    what applies)."""
    surface = surface_description(args)
    files = runner.read_files(args.solver, dict(files or {}), profile=args.profile,
                              prony=args.prony, material=args.material, surface=surface,
                              material_options={**material_options(args),
                                                "si": args.units == "SI" or None})
    point = op.build(args.solver, load=load, penetration=penetration, speed=speed,
                     ratio=args.ratio, hk=None if surface else args.hk, nodes=args.nodes,
                     rtol=args.rtol, surface=surface, direction=args.direction,
                     max_nodes=args.max_nodes, profile=args.profile, prony=args.prony,
                     fields=args.fields is not None, files=files, material=args.material,
                     material_options={**material_options(args),
                                       "si": args.units == "SI" or None},
                     si=si, layer=layer_options(args, si))
    if (args.nu is not None and si is None and args.thickness is None
            and not (point.get("material") or {}).get("shear_nu")):
        raise op.refuse("nu", "without --units SI, only for a layer (--thickness) or a "
                        "--material of shear moduli (E = 2 (1 + ν) G)", args.nu)
    return point


def layer_options(args, si):
    """``{"thickness_over_wavelength", "foundation", "nu"}`` of --thickness, --foundation and
    --nu (None without --thickness); with --units SI the thickness [m] over the wavelength.
    The values as given: `operating_point.build` and the BEM's Layer check them."""
    if args.solver == "analytic" and (args.thickness is not None or
                                      args.foundation is not None):
        raise op.bem_only("thickness" if args.thickness is not None else "foundation")
    if args.thickness is None:
        if args.foundation is not None:
            raise BadInput(f"--foundation {args.foundation} is not allowed without --thickness: "
                           "it is the lower face of a layer (give its thickness with "
                           "--thickness)")
        return None
    if args.foundation is None:
        raise op.missing("foundation", "--thickness needs it (bonded or frictionless: the "
                         "layer's lower face on the rigid foundation)")
    if args.nu is None:
        raise op.missing("nu", "--thickness needs the layer's Poisson ratio, in (-1, 0.5] "
                         "(its factor S(kd, ν))")
    d = args.thickness
    if si is not None:
        if not (math.isfinite(d) and d > 0.0):
            raise BadInput(f"--thickness {d!r} is not allowed: a finite layer thickness d > 0 "
                           "[m] (--units SI)")
        deep = [v for v in (args.penetration if isinstance(args.penetration, list)
                             else [args.penetration]) if v is not None]
        if deep and not op.penetration_clears_layer(max(deep), si["amplitude"], d):
            raise BadInput(f"--penetration {max(deep) * si['amplitude']!r} is not allowed: a "
                           f"penetration the layer can take: Δ < d = {d!r} [m]; deeper, the "
                           "indenter would reach the foundation")
        d = d / si["wavelength"]
    return {"thickness_over_wavelength": d, "foundation": args.foundation, "nu": args.nu}


def units_si(args, files):
    """``--units SI``: the SI values in ``args`` become the dimensionless groups (in place);
    returns the spec's ``si`` description, or None in the conventions' units."""
    given = {k: getattr(args, k) for k in ("E0", "Einf", "tau_creep", "tau_relax", "nu",
                                           "wavelength", "amplitude")}
    if args.units != "SI":
        extra = [k for k, v in given.items() if v is not None  # a layer's or a G curve's ν:
                 and not (k == "nu" and (args.thickness is not None or args.material is not None))]
        if extra:
            raise BadInput(f"--{extra[0].replace('_', '-')} is not allowed without --units SI: "
                           "an SI input (the conventions' groups need none)")
        return None
    for option in ("ratio", "hk", "profile", "prony"):
        if getattr(args, option) is not None:
            raise BadInput(f"--{option} is not allowed with --units SI: the SI problem is the "
                           "sinusoid of --amplitude, --wavelength on --E0 --Einf --tau-creep or "
                           "a --material file")
    if args.surface is not None:
        _surface_si(args, files)
        given["amplitude"] = args.amplitude  # a FILE's h_ref [m]
    material = None
    if args.material is not None:
        if args.solver != "bem":
            raise op.bem_only("material")
        opts = {k: v for k, v in material_options(args).items() if v is not None}
        files["material"] = runner.read_material(args.material, **opts, si=True)
        material = files["material"][1]
        # the ν that turned shear data into E (an LS-DYNA card's own) is the problem's too
        from .. import _materials
        args.nu = given["nu"] = _materials.problem_nu(material, args.nu)
    several = isinstance(args.speed, list)

    def listed(v):
        return None if v is None else (v if several else [v])
    out = op.resolve_si(args.solver, given, groups=roads.si_groups, loads=listed(args.load),
                            penetrations=listed(args.penetration), speeds=listed(args.speed),
                            material=material)
    for key in ("load", "penetration", "speed"):
        if out[key] is not None:
            setattr(args, key, out[key] if several else out[key][0])
    args.ratio, args.hk = out["ratio"], out["hk"]
    if args.surface is not None and args.surface not in ("bisinusoid", "self-affine"):
        args.hk = None  # the file's heights fix the surface (read in metres above)
    return out["si"]


def _surface_si(args, files):
    """--units SI with --surface: --wavelength is the cell's side Lx [m]; a FILE holds heights
    in metres (read here, its h_ref becomes the amplitude), the bi-sinusoid's --amplitude is h
    [m] of each sinusoid; a self-affine surface is given in the conventions' units only."""
    if args.surface == "self-affine":
        raise BadInput("--surface self-affine is not allowed with --units SI: its spectrum is "
                       "given in the conventions' units (wavenumbers over k = 2π/Lx); give its "
                       "heights as a FILE in metres instead")
    if args.hk_y is not None:
        raise BadInput("--hk-y is not allowed with --units SI: the SI bi-sinusoid has "
                       "--amplitude h [m] along both axes (a FILE in metres for others)")
    if args.surface == "bisinusoid":
        return
    if args.amplitude is not None:
        raise BadInput(f"--amplitude {args.amplitude!r} is not allowed with --surface FILE: the "
                       "file's heights fix h_ref (max z − mean z)")
    if args.wavelength is None:
        raise op.missing("wavelength", "with --units SI and --surface FILE it is the cell's "
                         "side Lx [m] (the file's heights are in metres)")
    info, surface = runner.read_input("surface", args.surface, units="SI",
                                      length=args.wavelength)
    files["surface"] = (info, surface)
    args.amplitude = surface.amplitude / (2.0 * math.pi / args.wavelength)


def material_options(args):
    """The --material file's options (`operating_point.MATERIAL_OPTIONS`), and ``nu``: --nu
    turns shear data (G', G'', G(t), a shear card) into tensile (also the SI problem's and a
    layer's ν)."""
    return {**{k: getattr(args, k) for k in op.MATERIAL_OPTIONS}, "nu": args.nu}


def validate(spec):
    """`runner.validate` of a point built from the command line: a refusal names the option."""
    runner.validate(spec, op.CLI)
