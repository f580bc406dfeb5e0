"""The command line every part answers to.

    python -m comparisons point --solver {analytic,bem} (--load P | --penetration D) --speed S
                                [--ratio R] [--hk H] [--nodes N | --rtol T] [--max-nodes M]
                                [--profile F] [--prony F] [--fields FILE.csv]
                                [--material F [--max-residual B] [--per-decade K]
                                 [--temperature T (--wlf C1 C2 TREF | --shift-table F)]]
                                [--units SI --nu NU --wavelength L --amplitude H
                                 (--E0 E --Einf E (--tau-creep S | --tau-relax S) | --material F)]
    python -m comparisons sweep --solver {analytic,bem} (--load P [P ...] | --penetration D [D ...])
                                --speed S [S ...] [options of point]
                                [--workers W | --scheduler ADDRESS] [--fields DIR]
    python -m comparisons report [--out DIR] [--quick] [--resume] [--workers W | --scheduler A]
    python -m comparisons crosscheck [--nodes N ...] | --tolerances
    python -m comparisons bench [--points N] [--bem | --bem-only | --cluster | --honesty [--seed S] [--light] [--front-door] | --materials [--seed S]] [--max-log2n K]
    python -m comparisons suite ... | verify ...   (comparisons/suite.py, comparisons/verify.py)
    python -m comparisons mastercurve ...           (comparisons/mastercurve.py)

Materials (--material, temperatures, SI, the speed's time): comparisons/_materials.py and
docs/materials.md.

`point` prints one JSON object; `sweep` one per line, in order (loads outer, speeds inner); a
value of a sweep may be a log range START:STOP:COUNT.  Exit status: 0 every result printed;
1 a point could not be solved (reported on standard error, never printed as a result); 2 input
outside what is supported, refused before any work.  Either way one line per problem on standard
error, never a traceback.

Each subcommand is one ``add_*_parser`` function and one ``_cmd_*`` function; `SUBCOMMANDS`
lists the parser functions in the order of ``--help``, and a subcommand in a module of its own
(``add_parser(sub)``, ``main(args)``) is one line there: ``module_subcommand("name")``.
"""
from __future__ import annotations

import argparse
import json
import math
import os
import re
import stat
import sys
import time

from . import runner

EXIT_OK, EXIT_FAILED, EXIT_BAD_INPUT = 0, 1, 2
#: one log range START:STOP:COUNT holds at most this many values
MAX_RANGE_COUNT = 1_000_000


class BadInput(Exception):
    """Input outside what is supported: one line on standard error, exit status 2.

    ``prog`` names the (sub)command; `main` adds the subcommand's when it is None.
    """

    def __init__(self, message, prog=None):
        super().__init__(message)
        self.prog = prog


class Failed(BadInput):
    """The command could not do its work: one line on standard error, exit status 1."""


class _Parser(argparse.ArgumentParser):
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


class _Once(argparse.Action):
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


def _number(text):
    try:
        return float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number") from None


def _integer(text):
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
        return [_number(text)]
    parts = text.split(":")
    bad = argparse.ArgumentTypeError
    if len(parts) != 3:
        raise bad(f"{text!r}: a log range is START:STOP:COUNT")
    a, b = (_number(p) for p in parts[:2])
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


# ------------------------------------------------------------------------------ parsers
_SPEED_HELP = ("V τ_ref k ≥ 0, τ_ref the creep (retardation) time τ of the standard linear "
               "solid (not its relaxation time τ E0/E∞), or the time unit of the --prony/"
               "--material file (1 s for a DMA curve); every record states it (time_unit); "
               "with --units SI, V [m/s]")
_LOAD_HELP = ("p̃∞ = p∞(1 − ν²)/E_ref > 0, E_ref = E0 (or the --prony/--material file's "
              "reference modulus); with --units SI, p∞ [Pa]")


def _solver_options(p, several):
    """Options shared by point and sweep; `several`: sweep's lists and ranges of values."""
    p.add_argument("--solver", choices=["analytic", "bem"], required=True, action=_Once)
    g = p.add_mutually_exclusive_group(required=True)
    if several:
        rng = " (values, or log ranges START:STOP:COUNT)"
        g.add_argument("--load", type=log_range, nargs="+", action=_Once, metavar="P",
                       help=_LOAD_HELP + rng)
        g.add_argument("--penetration", type=log_range, nargs="+", action=_Once,
                       metavar="D", help="Δ/h in (0, 1]" + rng)
        p.add_argument("--speed", type=log_range, nargs="+", required=True,
                       action=_Once, metavar="S", help=_SPEED_HELP + rng)
    else:
        g.add_argument("--load", type=_number, action=_Once, metavar="P",
                       help=_LOAD_HELP)
        g.add_argument("--penetration", type=_number, action=_Once, metavar="D",
                       help="Δ/h in (0, 1]; the load is then an output")
        p.add_argument("--speed", type=_number, required=True, action=_Once,
                       metavar="S", help=_SPEED_HELP)
    p.add_argument("--ratio", type=_number, action=_Once, metavar="R",
                   help="E∞/E0 (default 3); not with --prony or --material")
    p.add_argument("--hk", type=_number, action=_Once, metavar="H",
                   help="h k (default 1); not with --profile")
    p.add_argument("--nodes", type=_integer, action=_Once, metavar="N",
                   help="BEM: a fixed mesh of N panels per period (default: adaptive); analytic: "
                        "points of --fields (default 1024), only with --fields")
    p.add_argument("--rtol", type=_number, action=_Once, metavar="T",
                   help="BEM without --nodes: refine until every estimated error is below T "
                        f"(default {runner.DEFAULTS['rtol']:g})")
    p.add_argument("--max-nodes", type=_integer, action=_Once, metavar="M",
                   help="BEM without --nodes: the finest mesh the refinement may reach")
    p.add_argument("--profile", action=_Once, metavar="FILE",
                   help="BEM only: periodic profile file (bem.read_profile); replaces the sinusoid")
    p.add_argument("--prony", action=_Once, metavar="FILE",
                   help="BEM only: Prony-series creep function file (bem.read_prony: creep "
                        "times, in tau_ref); replaces the standard linear solid")
    p.add_argument("--material", action=_Once, metavar="FILE",
                   help="BEM only: a material file, told by its first line: a creep series "
                        "('J0 <value>' then 'J_i tau_i', creep times), a relaxation series "
                        "('E_r <value>' then 'E_i theta_i', relaxation times) or a DMA master "
                        "curve (CSV header frequency, storage, loss; fitted with a Prony series, "
                        "E_ref its relaxed modulus, tau_ref 1 s); docs/materials.md.  Not with "
                        "--prony or --ratio")
    p.add_argument("--max-residual", type=_number, action=_Once, metavar="B",
                   help="DMA --material: the largest relative residual on E' or E'' the Prony "
                        "fit may leave (default 0.05), else refused")
    p.add_argument("--per-decade", type=_number, action=_Once, metavar="K",
                   help="DMA --material: relaxation times per decade of the fit (default 2)")
    p.add_argument("--temperature", type=_number, action=_Once, metavar="T",
                   help="--material at temperature T: every time of the material multiplied by "
                        "a_T(T) (the file holds it at the shift's reference temperature); with "
                        "--wlf or --shift-table")
    shift = p.add_mutually_exclusive_group()
    shift.add_argument("--wlf", type=_number, nargs=3, action=_Once, metavar=("C1", "C2", "TREF"),
                       help="WLF shift log10 a_T = -C1 (T - TREF)/(C2 + T - TREF)")
    shift.add_argument("--shift-table", action=_Once, metavar="FILE",
                       help="shift table CSV (columns temperature, log_aT), linear in log10 a_T, "
                            "no extrapolation")
    p.add_argument("--units", choices=["conventions", "SI"], action=_Once,
                   help="SI: --load is p∞ [Pa] (--penetration Δ [m]), --speed V [m/s], with "
                        "--nu, --wavelength, --amplitude and the material (--E0 --Einf with "
                        "--tau-creep or --tau-relax, or --material: series files in Pa and s, a "
                        "DMA curve in its header's unit); the record adds 'si' (default: the "
                        "conventions' dimensionless groups)")
    for names, unit, what in ((("--E0",), "Pa", "relaxed modulus of the standard linear solid"),
                              (("--Einf",), "Pa", "instantaneous (glassy) modulus, > E0"),
                              (("--tau-creep", "--tau"), "s", "creep (retardation) time τ of "
                               "the solid, eq. (2.3); the speed group is V τ k"),
                              (("--tau-relax",), "s", "relaxation time of the solid, τ E0/Einf "
                               "(instead of --tau-creep)"),
                              (("--nu",), "-", "Poisson's ratio"),
                              (("--wavelength",), "m", "λ of the sinusoid"),
                              (("--amplitude",), "m", "h of the sinusoid")):
        p.add_argument(*names, type=_number, action=_Once, metavar="X",
                       help=f"--units SI: {what} [{unit}]")


def _parallel_options(p, what):
    g = p.add_mutually_exclusive_group()
    g.add_argument("--workers", type=_integer, action=_Once, metavar="W",
                   help=f"local processes ({what})")
    g.add_argument("--scheduler", action=_Once, metavar="ADDRESS",
                   help="run on the Dask distributed cluster of this scheduler (e.g. "
                        "tcp://host:8786; needs viscosine[cluster]); not with --workers")


def _allowed(text):
    """The range part of an ACCEPTED reason: up to its first ': ' outside brackets (an
    interval such as (1, 10] closes with either)."""
    depth = 0
    for i, ch in enumerate(text):
        depth += (ch in "([") - (ch in ")]")
        if depth == 0 and text.startswith(": ", i):
            return text[:i]
    return text


def accepted_ranges():
    """The accepted range of every input of point and sweep, from analytic.ACCEPTED and
    bem.ACCEPTED (for --help)."""
    import textwrap

    import analytic
    import bem
    rows = [("--load", "load"), ("--penetration", "penetration"), ("--speed", "speed"),
            ("--ratio", "ratio"), ("--hk", "hk"), ("--nodes", "nodes"), ("--rtol", "rtol"),
            ("--max-nodes", "max_nodes"), ("--profile", "profile"), ("--prony", "material")]
    lines = textwrap.wrap("accepted inputs (analytic.ACCEPTED and bem.ACCEPTED give the reason "
                          "for each bound; outside them: exit status 2, nothing solved):", 96)
    for option, key in rows:
        for road, table in (("analytic", analytic.ACCEPTED), ("bem", bem.ACCEPTED)):
            if key in table:
                lines += textwrap.wrap(f"{road}: {_allowed(table[key][2])}", 96,
                                       initial_indent=f"  {option:<15}" if road == "analytic"
                                       or key not in analytic.ACCEPTED else " " * 17,
                                       subsequent_indent=" " * 21)
    return "\n".join(lines)


def add_point_parser(sub):
    p = sub.add_parser("point", help="solve one operating point, print one JSON object",
                       description="Solve one operating point and print one JSON object.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.epilog_maker = accepted_ranges
    _solver_options(p, several=False)
    p.add_argument("--fields", action=_Once, metavar="FILE.csv",
                   help="also write σ, v and the gap over one period to this CSV file")
    p.set_defaults(run=_cmd_point)


def add_sweep_parser(sub):
    p = sub.add_parser("sweep", help="solve every (load, speed) pair, one JSON object per line",
                       description="Solve every (load or penetration, speed) pair, loads in the "
                                   "outer loop, and print one JSON object per line, in order.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.epilog_maker = accepted_ranges
    _solver_options(p, several=True)
    _parallel_options(p, "default 1: this process")
    p.add_argument("--fields", action=_Once, metavar="DIR",
                   help="also write the fields of every point to DIR/<solver>_load<P>_speed<S>.csv")
    p.set_defaults(run=_cmd_sweep)


def add_report_parser(sub):
    p = sub.add_parser("report", help="cross-validation report on the paper's parameters")
    p.add_argument("--out", action=_Once, metavar="DIR", help="output folder (default ./report)")
    p.add_argument("--quick", action="store_true", help="coarser meshes and fewer points")
    p.add_argument("--resume", action="store_true",
                   help="reuse the results already in DIR/results (each one validated)")
    _parallel_options(p, "default: all cores")
    p.set_defaults(run=_cmd_report)


def add_bench_parser(sub):
    p = sub.add_parser("bench", help="benchmarks that print figures (speed, iterations, memory)")
    p.add_argument("--points", type=_integer, action=_Once, metavar="N",
                   help="points of the swept benchmark (default 1000; 2000 with --cluster)")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--bem", action="store_true", help="also run the BEM benchmark tables")
    g.add_argument("--bem-only", action="store_true", help="only the BEM benchmark tables")
    g.add_argument("--cluster", action="store_true",
                   help="a BEM sweep at N = 4096 in 1 and 2 local processes and on a 2-worker "
                        "local Dask cluster")
    g.add_argument("--honesty", action="store_true",
                   help="the BEM's error estimates and adaptive mesh against the semi-analytic "
                        "road on a random sample of the accepted inputs (default 300 points)")
    g.add_argument("--materials", action="store_true",
                   help="broad Prony spectra (8-64 terms, 2-20 decades, E∞/E0 up to 1e4) "
                        "through `point --solver bem --prony`, against the Fourier reference "
                        "(analytic.fourier_solve), with the standard linear solid's cost "
                        "(default 200 points)")
    p.add_argument("--seed", type=_integer, action=_Once, metavar="S",
                   help="seed of the --honesty or --materials sample (default 20261123, "
                        "20261125)")
    p.add_argument("--light", action="store_true",
                   help="with --honesty: light loads, p~/hk log-uniform in 1e-8 … 1e-4")
    p.add_argument("--front-door", action="store_true",
                   help="with --honesty: each point through `point --solver bem` (the runner "
                        "and its last line of defence), judging the printed record "
                        "(default 50 points)")
    p.add_argument("--max-log2n", type=_integer, action=_Once, metavar="K",
                   help="largest BEM mesh 2^K of the BEM speed/memory table (default 20)")
    p.set_defaults(run=_cmd_bench)


def add_crosscheck_parser(sub):
    p = sub.add_parser("crosscheck",
                       help="BEM − semi-analytic differences on the grid of operating points")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--nodes", type=_integer, nargs="+", action=_Once, metavar="N",
                   help="BEM meshes (default 1024 4096 16384 65536)")
    g.add_argument("--tolerances", action="store_true",
                   help="print the agreement tolerances the tests use (Markdown), run nothing")
    p.set_defaults(run=_cmd_crosscheck)


def module_subcommand(name):
    """Register a subcommand that lives in ``comparisons/<name>.py``, which provides
    ``add_parser(sub)`` (returning its parser) and ``main(args)`` (returning the exit status)."""
    def add(sub):
        import importlib
        try:
            module = importlib.import_module(f"{__package__}.{name}")
            p = module.add_parser(sub)
        except Exception as exc:  # a broken module must not take the other subcommands down
            why = f"{type(exc).__name__}: {runner._one_line(exc)}"

            def unavailable(args):
                raise Failed(f"unavailable ({why})")
            stub = sub.add_parser(name, help=f"(unavailable: {why})", add_help=False,
                                  prefix_chars="\0")
            stub.add_argument("rest", nargs=argparse.REMAINDER)  # whatever follows: same answer
            stub.set_defaults(run=unavailable)
            return
        if p is not None:
            p.set_defaults(run=module.main)
    add.__name__ = f"add_{name}_parser"
    return add


#: the subcommands, in the order of --help (one line per subcommand; a subcommand in a module
#: of its own is ``module_subcommand("name")``)
SUBCOMMANDS = [add_point_parser, add_sweep_parser, add_report_parser, add_crosscheck_parser,
               add_bench_parser, module_subcommand("suite"), module_subcommand("verify"),
               module_subcommand("mastercurve")]


def build_parser():
    parser = _Parser(prog="python -m comparisons",
                     description="viscosine: two roads to the steady viscoelastic sliding of a "
                                 "rigid periodic indenter")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    for add in SUBCOMMANDS:
        add(sub)
    return parser


# ------------------------------------------------------------------------------ shared checks
def _dump(obj):
    return json.dumps(obj, allow_nan=False)


def _stderr(text):
    print(text, file=sys.stderr, flush=True)


def _check_output_file(option, path):
    """An output file must be creatable: its folder exists, and it is not a folder/device/FIFO."""
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a file")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise BadInput(f"{option} {path}: the folder {folder} does not exist")
    if os.path.lexists(path):
        st = os.stat(path) if os.path.exists(path) else os.lstat(path)
        if not stat.S_ISREG(st.st_mode):
            raise BadInput(f"{option} {path}: {runner._kind(st.st_mode)}, not a regular file")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder {folder} is not writable")


def _check_output_dir(option, path, create):
    """An output folder: an existing folder, or (create) one whose parent exists."""
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a folder")
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise BadInput(f"{option} {path}: an existing file, not a folder")
    else:
        parent = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(parent):
            raise BadInput(f"{option} {path}: the folder {parent} does not exist")
        if not os.access(parent, os.W_OK | os.X_OK):  # it could not be made there
            raise BadInput(f"{option} {path}: the folder {parent} is not writable")
        if create:
            try:
                os.mkdir(path)
            except OSError as exc:
                raise BadInput(f"{option} {path}: cannot create the folder ({exc.strerror})") from None
    if os.path.isdir(path) and not os.access(path, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder is not writable")


def _check_workers(args):
    if getattr(args, "workers", None) is not None and args.workers < 1:
        raise BadInput(f"--workers {args.workers} is not allowed: an integer ≥ 1")


def _resolve(args, *, load=None, penetration=None, speed=None, files=None, si=None):
    try:
        return runner.resolve(args.solver, load=load, penetration=penetration, speed=speed,
                              ratio=args.ratio, hk=args.hk, nodes=args.nodes, rtol=args.rtol,
                              max_nodes=args.max_nodes, profile=args.profile, prony=args.prony,
                              fields=args.fields is not None, files=files,
                              material=args.material,
                              material_options={**_material_options(args),
                                                "si": args.units == "SI" or None},
                              si=si)
    except runner.InputError as exc:
        raise BadInput(str(exc)) from None


def _units_si(args, files):
    """``--units SI``: the SI values in ``args`` become the dimensionless groups (in place);
    returns the spec's ``si`` description, or None in the conventions' units."""
    given = {k: getattr(args, k) for k in ("E0", "Einf", "tau_creep", "tau_relax", "nu",
                                           "wavelength", "amplitude")}
    if args.units != "SI":
        extra = [k for k, v in given.items() if v is not None]
        if extra:
            raise BadInput(f"--{extra[0].replace('_', '-')} is not allowed without --units SI: "
                           "an SI input (the conventions' groups need none)")
        return None
    for option in ("ratio", "hk", "profile", "prony"):
        if getattr(args, option) is not None:
            raise BadInput(f"--{option} is not allowed with --units SI: the SI problem is the "
                           "sinusoid of --amplitude, --wavelength on --E0 --Einf --tau-creep or "
                           "a --material file")
    material = None
    if args.material is not None:
        if args.solver != "bem":
            raise BadInput("--material is not allowed here: a BEM option (the semi-analytic road "
                           "solves the sinusoid on the standard linear solid; use --solver bem)")
        opts = {k: v for k, v in _material_options(args).items() if v is not None}
        try:
            files["material"] = runner.read_material(args.material, **opts, si=True)
        except runner.InputError as exc:
            raise BadInput(f"{exc}") from None
        material = files["material"][1]
    several = isinstance(args.speed, list)

    def listed(v):
        return None if v is None else (v if several else [v])
    try:
        out = runner.resolve_si(args.solver, given, loads=listed(args.load),
                                penetrations=listed(args.penetration), speeds=listed(args.speed),
                                material=material)
    except runner.InputError as exc:
        raise BadInput(f"{exc}") from None
    for key in ("load", "penetration", "speed"):
        if out[key] is not None:
            setattr(args, key, out[key] if several else out[key][0])
    args.ratio, args.hk = out["ratio"], out["hk"]
    return out["si"]


def _material_options(args):
    return {"temperature": args.temperature, "wlf": args.wlf, "shift_table": args.shift_table,
            "max_residual": args.max_residual, "per_decade": args.per_decade}


def _validate(spec):
    try:
        runner.validate(spec)
    except runner.InputError as exc:
        raise BadInput(_option_names(str(exc))) from None


def _option_names(text):
    """'max_nodes=…' in a road's message becomes '--max-nodes …' (the option the user typed)."""
    m = re.match(r"(\w+)=(\S+) is not allowed", text)
    if m and m.group(1) in ("load", "penetration", "speed", "ratio", "hk", "nodes", "rtol",
                            "max_nodes"):
        return f"--{m.group(1).replace('_', '-')} {m.group(2)}{text[m.end(2):]}"
    return text


def _describe(spec):
    ctl = "load" if spec.get("load") is not None else "penetration"
    return f"{ctl}={spec[ctl]!r}, speed={spec['speed']!r}"


# ------------------------------------------------------------------------------ point
def _cmd_point(args):
    if args.fields is not None:
        _check_output_file("--fields", args.fields)
    files = {}
    si = _units_si(args, files)
    spec = _resolve(args, load=args.load, penetration=args.penetration, speed=args.speed,
                    files=files, si=si)
    _validate(spec)
    out = runner.run(spec, fields=args.fields is not None, deep=True)
    for w in out["warnings"]:
        _stderr(f"point: warning: {w}")
    if out["kind"] == "bad_input":
        raise BadInput(f"{out['error']}")
    if not out["ok"]:
        _stderr(f"point: {_describe(spec)}: {out['error']}")
        return EXIT_FAILED
    if args.fields is not None:
        _write_fields(args.fields, out, spec)
    print(_dump(out["record"]), flush=True)
    return EXIT_OK


def _write_fields(path, out, spec):
    f = out["fields"]
    try:
        runner.write_fields_csv(path, f, runner.fields_header(out["record"], spec, f))
    except OSError as exc:
        raise Failed(f"cannot write --fields {path} ({exc.strerror or exc})") from None


# ------------------------------------------------------------------------------ sweep
def _fmt_value(v):
    """Shortest exact text of a float for a file name: 0.3, 1 (not 1.0), 1e-05."""
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def field_file_name(spec, used, index):
    """``<solver>_<control><value>_speed<value>.csv``; unique within `used` (then ``_<index>``).

    Only digits, letters, ``.``, ``+``, ``-`` and ``_`` appear (floats are finite, validated).
    """
    ctl = "load" if spec.get("load") is not None else "penetration"
    stem = f"{spec['solver']}_{ctl}{_fmt_value(spec[ctl])}_speed{_fmt_value(spec['speed'])}"
    name = f"{stem}.csv"
    if name in used:
        name = f"{stem}_{index + 1}.csv"
    used.add(name)
    return name


def _cmd_sweep(args):
    from . import _cluster
    _check_workers(args)
    files = {}
    si = _units_si(args, files)
    control = "load" if args.load is not None else "penetration"
    values = args.load if args.load is not None else args.penetration
    speeds = args.speed
    total = len(values) * len(speeds)
    if args.fields is not None:
        _check_output_dir("--fields", args.fields, create=False)
    for option in ("profile", "prony", "material"):  # each file is read (and checked) once
        path = getattr(args, option)
        if path is not None and args.solver == "bem" and option not in files and not (
                option == "material" and args.prony is not None):
            try:
                files[option] = (runner.read_input(option, path) if option != "material" else
                                 runner.read_material(path, **{
                                     k: v for k, v in _material_options(args).items()
                                     if v is not None}))
            except runner.InputError as exc:
                raise BadInput(f"{exc}") from None
    base = _resolve(args, speed=speeds[0], files=files, si=si, **{control: values[0]})
    # every input is checked before any work; the ranges are per input, so each value once
    for v in dict.fromkeys(values):
        _validate({**base, control: v})
    for s in dict.fromkeys(speeds):
        _validate({**base, "speed": s})
    try:
        ex = _cluster.executor(args.workers, args.scheduler)
    except ValueError as exc:
        raise BadInput(f"{exc}") from None
    except _cluster.MissingPackage as exc:
        raise BadInput(f"{exc}") from None
    except _cluster.ClusterError as exc:
        raise Failed(f"{exc}") from None
    if args.fields is not None:
        _check_output_dir("--fields", args.fields, create=True)

    def spec_at(i):
        return {**base, control: values[i // len(speeds)], "speed": speeds[i % len(speeds)]}

    specs = (spec_at(i) for i in range(total))
    fn = runner._run_with_fields if args.fields is not None else runner.run
    chunk = max(1, min(64, total // (8 * max(1, ex.workers))))
    used, failed, bad = set(), 0, 0
    t0 = last = time.monotonic()
    with ex:
        for i, out in ex.imap(fn, specs, chunksize=chunk):
            spec = spec_at(i)
            where = f"sweep: point {i + 1}/{total} ({_describe(spec)})"
            if isinstance(out, _cluster.Failure):
                out = {"ok": False, "kind": "failed", "error": f"could not solve: {out.error}",
                       "warnings": []}
            for w in out["warnings"]:
                _stderr(f"{where}: warning: {w}")
            if out["ok"] and args.fields is not None:
                path = os.path.join(args.fields, field_file_name(spec, used, i))
                try:
                    _write_fields(path, out, spec)
                except Failed as exc:
                    out = {**out, "ok": False, "error": str(exc)}
            if out["ok"]:
                print(_dump(out["record"]), flush=True)
            else:
                failed += 1
                bad += out["kind"] == "bad_input"
                _stderr(f"{where}: {out['error']}")
            now = time.monotonic()
            if now - last > 2.0 or (i + 1 == total and now - t0 > 2.0):
                eta = ""
                if 10 <= i + 1 < total:  # an estimate only once a few points are in
                    eta = f" (about {(now - t0) / (i + 1) * (total - i - 1):.0f} s left)"
                _stderr(f"sweep: {i + 1}/{total} points, {failed} failed, {now - t0:.1f} s{eta}")
                last = now
    if failed:
        _stderr(f"sweep: {failed} of {total} points could not be solved")
    return EXIT_BAD_INPUT if bad else (EXIT_FAILED if failed else EXIT_OK)


# ------------------------------------------------------------------------------ report, bench, crosscheck
def _cmd_report(args):
    _check_workers(args)
    args.out = "report" if args.out is None else args.out
    _check_output_dir("--out", args.out, create=False)
    from . import _cluster, report
    try:
        return report.main(args)
    except _cluster.MissingPackage as exc:
        raise BadInput(f"{exc}") from None
    except _cluster.ClusterError as exc:
        raise Failed(f"{exc}") from None
    except OSError as exc:  # the folder went away or filled up during the run
        raise Failed(f"--out {args.out}: cannot write {exc.filename or 'the report'} "
                     f"({exc.strerror or exc})") from None


def _cmd_bench(args):
    if args.points is not None and args.points < 1:
        raise BadInput(f"--points {args.points} is not allowed: an integer ≥ 1")
    if args.max_log2n is not None and not 3 <= args.max_log2n <= 24:
        raise BadInput(f"--max-log2n {args.max_log2n} is not allowed: an integer in [3, 24]")
    if args.cluster and args.max_log2n is not None:
        raise BadInput("--max-log2n is not allowed with --cluster: it sets the BEM tables")
    if args.seed is not None and not (args.honesty or args.materials):
        raise BadInput("--seed is not allowed without --honesty or --materials: it seeds "
                       "their sample")
    if args.light and not args.honesty:
        raise BadInput("--light is not allowed without --honesty: it chooses that sample")
    if args.front_door and not args.honesty:
        raise BadInput("--front-door is not allowed without --honesty: it is a mode of that "
                       "study")
    if args.honesty and args.max_log2n is not None:
        raise BadInput("--max-log2n is not allowed with --honesty: it sets the BEM tables")
    from . import bench
    return bench.main(args)


def _cmd_crosscheck(args):
    from . import crosscheck
    if args.tolerances:
        crosscheck.print_tolerances()
        return EXIT_OK
    nodes = args.nodes or list(crosscheck.NODES)
    for n in nodes:  # the same check as point --solver bem --nodes N, before any work
        _validate(crosscheck.specs(n, crosscheck.GRID[:1])[0])
    return crosscheck.print_table(nodes)


# ------------------------------------------------------------------------------ main
def main(argv=None):
    """Run the command line; return the exit status (never raises, never prints a traceback)."""
    parser = _Parser(prog="python -m comparisons")  # for the messages, until the real one exists
    args = None
    try:
        parser = build_parser()
        args, extra = parser.parse_known_args(argv)
        if extra:
            stray_value = not extra[0].startswith("-") or re.fullmatch(r"-[\d.]\S*", extra[0])
            hint = (" (point takes one value of --load/--penetration/--speed; use sweep for "
                    "several)" if args.command == "point" and stray_value else "")
            raise BadInput(f"unrecognized arguments: {' '.join(extra)}{hint}")
        run = getattr(args, "run", None)
        if run is None:  # a module's parser that did not say what runs it
            import importlib
            run = importlib.import_module(f"{__package__}.{args.command}").main
        return run(args)
    except BadInput as exc:  # Failed too
        prog = exc.prog or " ".join([parser.prog] + ([args.command] if args else []))
        _stderr(f"{prog}: {_first_line(exc)}")
        return EXIT_FAILED if isinstance(exc, Failed) else EXIT_BAD_INPUT
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    except KeyboardInterrupt:
        _stderr("interrupted")
        return 130
    except BrokenPipeError:  # the reader went away (e.g. | head): stop quietly
        try:
            sys.stdout = open(os.devnull, "w")
        except OSError:
            pass
        return EXIT_FAILED
    except Exception as exc:  # a bug: still one line, and the status says it failed
        if os.environ.get("VISCOSINE_DEBUG"):
            raise
        _stderr(f"{parser.prog}: internal error: {type(exc).__name__}: {runner._one_line(exc)} "
                "(set VISCOSINE_DEBUG=1 for the traceback)")
        return EXIT_FAILED


def _first_line(exc):
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
