"""``report``: the cross-validation report on the paper's parameters (`comparisons.report`)."""
from __future__ import annotations

from ._common import (EXIT_FAILED, EXIT_OK, Failed, Once, check_output_dir, check_workers,
                      parallel_options)


def add_parser(sub):
    p = sub.add_parser("report", help="cross-validation report on the paper's parameters")
    p.add_argument("--out", action=Once, metavar="DIR", help="output folder (default ./report)")
    p.add_argument("--quick", action="store_true", help="coarser meshes and fewer points")
    p.add_argument("--resume", action="store_true",
                   help="reuse the results already in DIR/results (each one validated)")
    parallel_options(p, "default: all cores")
    p.set_defaults(run=run)


def run(args):
    check_workers(args)
    out = "report" if args.out is None else args.out
    check_output_dir("--out", out, create=False)
    from .. import report
    try:  # MissingPackage (exit status 2) and ClusterError (1) reach main as they are
        failed = report.build(out, quick=args.quick, workers=args.workers, resume=args.resume,
                              scheduler=args.scheduler)
    except OSError as exc:  # the folder went away or filled up during the run
        raise Failed(f"--out {out}: cannot write {exc.filename or 'the report'} "
                     f"({exc.strerror or exc})") from None
    return EXIT_FAILED if failed else EXIT_OK
