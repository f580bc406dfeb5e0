"""``bench``: benchmarks that print figures (`comparisons.bench`)."""
from __future__ import annotations

from ._common import BadInput, Once, integer


def add_parser(sub):
    p = sub.add_parser("bench", help="benchmarks that print figures (speed, iterations, memory)")
    p.add_argument("--points", type=integer, action=Once, metavar="N",
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
    g.add_argument("--materials-fits", action="store_true",
                   help="the material readers and fits over the realistic test set (raw "
                        "isotherms, E(t)/J(t), FE cards, measured DMA curves) against the truth "
                        "they were made from: accepted, residuals, truth errors, seconds per fit")
    g.add_argument("--materials-peers", action="store_true",
                   help="the DMA Prony fit (defaults) against pyvisco's and ANSYS's fits on "
                        "pyvisco's example master curves: E', E'', tan δ residuals, per decade")
    g.add_argument("--surfaces", action="store_true",
                   help="the surface BEM: fixed grids 256² … 2^K a side (default K = 12) with "
                        "time, FFT pairs and memory per panel beside Tamaas's elastic solve, and "
                        "its adaptive default against the fixed grid it ends on")
    g.add_argument("--accepted", action="store_true",
                   help="the semi-analytic road over a random sample of analytic.ACCEPTED: "
                        "valid answers, the worst consistency residuals, every failure "
                        "(default 1000 points)")
    g.add_argument("--near-transition", action="store_true",
                   help="the BEM just below the full-contact load (1e-8 … 1e-3 below p̃_FC, "
                        "E∞/E0 up to 1e3) through `point --solver bem`, against the "
                        "semi-analytic road: refused, wrong, CPU, memory (default 100 points, "
                        "V/V0 half in 1e-3 … 1e4, half in the rest of 1e-30 … 1e30; JSON "
                        "lines in bench-near-transition-S<seed>.jsonl, resumed)")
    p.add_argument("--seed", type=integer, action=Once, metavar="S",
                   help="seed of the --honesty, --materials, --accepted or --near-transition "
                        "sample (default 20261123, 20261125, 2024, 20261129)")
    p.add_argument("--penetration-control", action="store_true",
                   help="with --near-transition: Δ/h = 1 − d given (`point --penetration`) "
                        "instead of the load")
    p.add_argument("--light", action="store_true",
                   help="with --honesty: light loads, p~/hk log-uniform in 1e-8 … 1e-4")
    p.add_argument("--front-door", action="store_true",
                   help="with --honesty: each point through `point --solver bem` (the runner "
                        "and its last line of defence), judging the printed record "
                        "(default 50 points)")
    p.add_argument("--cheap", action="store_true",
                   help="with --accepted: skip Solution.check(), only the constraints every "
                        "answer meets")
    p.add_argument("--workers", type=integer, action=Once, metavar="W",
                   help="with --materials or --near-transition: local processes that share "
                        "the points (default 1; the rows and figures do not depend on it, but "
                        "for the CPU times on a loaded machine)")
    p.add_argument("--max-log2n", type=integer, action=Once, metavar="K",
                   help="largest BEM mesh 2^K of the BEM speed/memory table (default 20; with "
                        "--surfaces the largest grid 2^K a side, default 12)")
    p.set_defaults(run=run)


def run(args):
    if args.points is not None and args.points < 1:
        raise BadInput(f"--points {args.points} is not allowed: an integer ≥ 1")
    if args.max_log2n is not None and not 3 <= args.max_log2n <= 24:
        raise BadInput(f"--max-log2n {args.max_log2n} is not allowed: an integer in [3, 24]")
    if args.cluster and args.max_log2n is not None:
        raise BadInput("--max-log2n is not allowed with --cluster: it sets the BEM tables")
    if args.seed is not None and not (args.honesty or args.materials or args.accepted
                                      or args.near_transition):
        raise BadInput("--seed is not allowed without --honesty, --materials, --accepted or "
                       "--near-transition: it seeds their sample")
    if args.light and not args.honesty:
        raise BadInput("--light is not allowed without --honesty: it chooses that sample")
    if args.front_door and not args.honesty:
        raise BadInput("--front-door is not allowed without --honesty: it is a mode of that "
                       "study")
    if args.workers is not None and not (args.materials or args.near_transition):
        raise BadInput("--workers is not allowed without --materials or --near-transition: it "
                       "shares that study's points")
    if args.workers is not None and args.workers < 1:
        raise BadInput(f"--workers {args.workers} is not allowed: an integer ≥ 1")
    if args.penetration_control and not args.near_transition:
        raise BadInput("--penetration-control is not allowed without --near-transition: it is "
                       "a mode of that study")
    if args.cheap and not args.accepted:
        raise BadInput("--cheap is not allowed without --accepted: it is a mode of that study")
    for study in ("honesty", "accepted", "near_transition"):
        if getattr(args, study) and args.max_log2n is not None:
            raise BadInput(f"--max-log2n is not allowed with --{study.replace('_', '-')}: it "
                           "sets the BEM tables")
    for name in ("points", "max_log2n"):
        for study in ("materials_peers", "materials_fits"):
            if getattr(args, study) and getattr(args, name) is not None:
                raise BadInput(f"--{name.replace('_', '-')} {getattr(args, name)} is not "
                               f"allowed with --{study.replace('_', '-')}: it fits its whole "
                               "set of curves")
    from .. import bench
    return bench.run(args)
