"""The command line every part answers to (`conventions.md`).

    python -m comparisons point --solver {analytic,bem} --load P --speed S [--ratio R] [--hk H]
                                [--nodes N] [--fields FILE.csv]
    python -m comparisons point --solver {analytic,bem} --penetration D --speed S ...
    python -m comparisons sweep --solver {analytic,bem} --load P [P ...] --speed S [S ...]
                                [--ratio R] [--hk H] [--nodes N] [--workers W]
    python -m comparisons report [--out DIR] [--quick] [--resume]
    python -m comparisons bench [--points N] [--bem | --bem-only]
    python -m comparisons crosscheck [--nodes N ...]

`point` prints one JSON object; `sweep` one per line as each point is done (loads outer, speeds
inner).  Bad input: one line on standard error, exit status 2.  A point that does not converge is
reported on standard error (with its residuals) and makes the exit status 1; it is never printed
as a result.
"""
from __future__ import annotations

import argparse
import json
import sys
import time

from . import runner

EXIT_BAD_INPUT = 2
EXIT_FAILED = 1


class BadInput(Exception):
    """Raised for invalid command-line input; reported as one line, exit status 2."""


class _Parser(argparse.ArgumentParser):
    def error(self, message):  # one line, no usage dump (conventions: one line on stderr)
        raise BadInput(f"{self.prog}: {message}")


def _float(name):
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"--{name} {text!r}: not a number") from None
        return v
    return conv


def _int(name):
    def conv(text):
        try:
            return int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"--{name} {text!r}: not an integer") from None
    return conv


def _common(p):
    p.add_argument("--solver", choices=["analytic", "bem"], required=True)
    p.add_argument("--speed", type=_float("speed"), nargs="+", required=True, help="V/V0 = Vτk")
    p.add_argument("--ratio", type=_float("ratio"), default=3.0, help="E∞/E0 (default 3)")
    p.add_argument("--hk", type=_float("hk"), default=1.0, help="h k (default 1)")
    p.add_argument("--nodes", type=_int("nodes"), default=None,
                   help="BEM panels per period (default 4096); analytic: points of --fields")
    p.add_argument("--profile", default=None,
                   help="BEM only: periodic profile file (see bem.read_profile); replaces the sinusoid")
    p.add_argument("--prony", default=None,
                   help="BEM only: Prony-series creep function file (see bem.read_prony); replaces --ratio")


def build_parser():
    parser = _Parser(prog="python -m comparisons",
                     description="viscosine: two roads to viscoelastic sliding of a rigid sinusoid")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=_Parser)
    p = sub.add_parser("point", help="solve one operating point, print one JSON object")
    _common(p)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--load", type=_float("load"), nargs="+", help="p̃∞ = p∞(1 − ν²)/E0")
    g.add_argument("--penetration", type=_float("penetration"), nargs="+", help="Δ/h in (0, 1]")
    p.add_argument("--fields", default=None, help="write σ, v, gap over one period to this CSV")
    p = sub.add_parser("sweep", help="solve every (load, speed) pair, one JSON object per line")
    _common(p)
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--load", type=_float("load"), nargs="+")
    g.add_argument("--penetration", type=_float("penetration"), nargs="+")
    p.add_argument("--workers", type=_int("workers"), default=1, help="processes (default 1)")
    p = sub.add_parser("report", help="cross-validation report on the paper's parameters")
    p.add_argument("--out", default="report", help="output folder (default ./report)")
    p.add_argument("--quick", action="store_true", help="coarser meshes and fewer points (< 2 min)")
    p.add_argument("--resume", action="store_true", help="reuse results already written in --out")
    p.add_argument("--workers", type=_int("workers"), default=None, help="processes (default: all cores)")
    p = sub.add_parser("bench", help="benchmarks that print figures (speed, iterations, memory)")
    p.add_argument("--points", type=_int("points"), default=1000,
                   help="points of the analytic command-line sweep (default 1000)")
    p.add_argument("--bem", action="store_true", help="also run the BEM benchmark tables")
    p.add_argument("--bem-only", action="store_true", help="only the BEM benchmark tables")
    p.add_argument("--max-log2n", type=_int("max-log2n"), default=20,
                   help="largest BEM mesh 2^n of the BEM speed/memory benchmark (default 20)")
    p = sub.add_parser("crosscheck", help="BEM − semi-analytic differences on the grid of operating points")
    p.add_argument("--nodes", type=_int("nodes"), nargs="+", default=[1024, 4096, 16384, 65536])
    from . import suite, verify  # the benchmark suite and verify register their own options
    suite.add_parser(sub)
    verify.add_parser(sub)
    return parser


def _dump(obj):
    return json.dumps(obj, allow_nan=False)


def _check_point_args(args, single):
    """Range checks that argparse cannot express; raise BadInput with one line."""
    if single:
        for name in ("speed", "load", "penetration"):
            vals = getattr(args, name, None)
            if vals is not None and len(vals) != 1:
                raise BadInput(f"point: --{name} takes one value (got {len(vals)}); use sweep for several")
    if args.solver == "analytic" and (args.profile or args.prony):
        raise BadInput("--profile and --prony are BEM options (the analytic road solves the "
                       "sinusoid on the standard linear solid)")
    if args.nodes is not None and args.nodes < 8:
        raise BadInput(f"--nodes {args.nodes}: must be an integer ≥ 8")
    if getattr(args, "workers", 1) is not None and getattr(args, "workers", 1) < 1:
        raise BadInput(f"--workers {args.workers}: must be ≥ 1")


def _cmd_point(args):
    _check_point_args(args, single=True)
    spec = runner.spec_from_args(args, args.speed[0],
                                 load=args.load[0] if args.load else None,
                                 penetration=args.penetration[0] if args.penetration else None)
    try:
        runner.validate(spec)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    out = runner.run(spec, fields=args.fields is not None)
    if not out["ok"]:
        print(f"not converged: {out['error']}", file=sys.stderr)
        return EXIT_FAILED
    if args.fields:
        runner.write_fields_csv(args.fields, out["fields"])
    print(_dump(out["record"]))
    return 0


def _cmd_sweep(args):
    _check_point_args(args, single=False)
    control = "load" if args.load else "penetration"
    values = args.load if args.load else args.penetration
    specs = [runner.spec_from_args(args, s, **{control: v}) for v in values for s in args.speed]
    try:
        for sp in specs:
            runner.validate(sp)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
    failed = 0
    t0 = last = time.monotonic()
    for i, out in enumerate(runner.run_many(specs, workers=args.workers), 1):
        if out["ok"]:
            print(_dump(out["record"]), flush=True)
        else:
            failed += 1
            print(f"not converged: {out['spec']}: {out['error']}", file=sys.stderr, flush=True)
        now = time.monotonic()
        if now - last > 2.0 or (i == len(specs) and now - t0 > 2.0):
            print(f"sweep: {i}/{len(specs)} points, {now - t0:.1f} s", file=sys.stderr, flush=True)
            last = now
    return EXIT_FAILED if failed else 0


def main(argv=None):
    parser = build_parser()
    try:
        args = parser.parse_args(argv)
        if args.command == "point":
            return _cmd_point(args)
        if args.command == "sweep":
            return _cmd_sweep(args)
        if args.command == "report":
            from . import report
            return report.main(args)
        if args.command == "bench":
            from . import bench
            return bench.main(args)
        if args.command == "crosscheck":
            from . import crosscheck
            return crosscheck.print_table(args.nodes)
        if args.command in ("suite", "verify"):
            from . import suite, verify
            return {"suite": suite, "verify": verify}[args.command].main(args)
    except BadInput as exc:
        print(str(exc).splitlines()[0], file=sys.stderr)
        return EXIT_BAD_INPUT
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
