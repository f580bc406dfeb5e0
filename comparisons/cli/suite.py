"""``suite``: the certified benchmark suite, export it or check it (`comparisons.suite`,
`comparisons.suite_export`).

Its own messages: bad input is one line without the command's prefix (exit status 2), an
unreachable scheduler one line starting ``suite:`` (exit status 1).
"""
from __future__ import annotations

import sys

from ._common import EXIT_FAILED, EXIT_OK, check_output_dir


def add_parser(sub):
    p = sub.add_parser("suite", help="the certified benchmark suite: export it or check it")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--export", metavar="DIR", default=None,
                   help="write the suite as plain CSV/JSON into DIR (one folder per case)")
    g.add_argument("--check", action="store_true",
                   help="recompute every value; exit 1 if a certified digit changed")
    g.add_argument("--certify", action="store_true",
                   help="maintainers: recompute and rewrite the shipped certification")
    g.add_argument("--list", action="store_true", help="print the cases and their digits")
    p.add_argument("--cases", nargs="+", metavar="NAME", default=[],
                   help="restrict to these cases")
    p.add_argument("--out", metavar="DIR", default="suite-check",
                   help="--check: write each recomputed case here as soon as it is done "
                        "(default ./suite-check)")
    p.add_argument("--resume", action="store_true",
                   help="--check: reuse the cases already recomputed in --out (same case "
                        "definition, files, version and solver source)")
    p.add_argument("--workers", type=int, default=1, help="--check: processes (default 1)")
    p.add_argument("--scheduler", metavar="ADDRESS", default=None,
                   help="--check: a Dask distributed scheduler to run the cases on")
    p.set_defaults(run=run)


def run(args) -> int:
    """Exit status 0, 1 (a digit changed, a recomputation failed, the scheduler cannot be
    reached) or 2 (bad input)."""
    from .. import _cluster, suite, suite_export
    try:
        if args.workers < 1:
            raise suite.SuiteError(f"--workers {args.workers}: must be an integer >= 1")
        book = suite.load_suite()
        cases = suite.select(book, args.cases)
        if args.list:
            print(suite_export.summary_table(cases), end="")
            return EXIT_OK
        if args.export:
            check_output_dir("--export", args.export, create=False)
            dirs = suite_export.export(args.export, args.cases, book)
            print(f"suite: wrote {len(dirs)} cases and README.md to {args.export}",
                  file=sys.stderr)
            return EXIT_OK
        if args.certify:
            suite.certify(args.cases)
            return EXIT_OK
        if args.scheduler and args.workers != 1:
            raise suite.SuiteError("--scheduler and --workers are not allowed together: the "
                                   "cluster decides how many workers run")
        if args.out:
            check_output_dir("--out", args.out, create=False)
        res = suite.check(args.cases, out=args.out, resume=args.resume, workers=args.workers,
                          scheduler=args.scheduler, suite=book)
    except (suite.SuiteError, _cluster.MissingPackage):
        # bad input, or --scheduler without the cluster extra: `main` prints it, prefixed
        raise
    except _cluster.ClusterError as exc:  # an unreachable scheduler
        print(f"suite: {str(exc).splitlines()[0]}", file=sys.stderr)
        return EXIT_FAILED
    for line in suite.check_lines(res):
        print(line)
    n_bad = sum(bool(r["changed"]) for r in res["cases"])
    print(f"suite: {len(res['cases'])} cases checked in {res['seconds']:.0f} s, "
          f"{n_bad} with changed certified digits", file=sys.stderr)
    return EXIT_OK if res["ok"] else EXIT_FAILED
