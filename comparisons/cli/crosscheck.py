"""``crosscheck``: BEM − semi-analytic differences on the grid of operating points
(`comparisons.crosscheck`)."""
from __future__ import annotations

from ._common import EXIT_OK, Once, integer, validate


def add_parser(sub):
    p = sub.add_parser("crosscheck",
                       help="BEM − semi-analytic differences on the grid of operating points")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--nodes", type=integer, nargs="+", action=Once, metavar="N",
                   help="BEM meshes (default 1024 4096 16384 65536)")
    g.add_argument("--tolerances", action="store_true",
                   help="print the agreement tolerances the tests use (Markdown), run nothing")
    p.set_defaults(run=run)


def run(args):
    from .. import crosscheck
    if args.tolerances:
        crosscheck.print_tolerances()
        return EXIT_OK
    nodes = args.nodes or list(crosscheck.NODES)
    for n in nodes:  # the same check as point --solver bem --nodes N, before any work
        validate(crosscheck.specs(n, crosscheck.GRID[:1])[0])
    return crosscheck.print_table(nodes)
