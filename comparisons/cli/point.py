"""``point``: solve one operating point, print one JSON object."""
from __future__ import annotations

import argparse

from .. import points
from ..plots.materials import report_fit
from ._common import (EXIT_FAILED, EXIT_OK, Once, accepted_ranges, check_output_file, resolve,
                      solver_options, units_si, validate)


def add_parser(sub):
    p = sub.add_parser("point", help="solve one operating point, print one JSON object",
                       description="Solve one operating point and print one JSON object.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.epilog_maker = accepted_ranges
    solver_options(p, several=False)
    p.add_argument("--fields", action=Once, metavar="FILE",
                   help="also write σ, v and the gap over one period to this CSV file (with "
                        "--surface: a .npz file of the grid and the fields, read by numpy.load)")
    p.set_defaults(run=run)


def run(args):
    if args.fields is not None:
        check_output_file("--fields", args.fields)
    files = {}
    si = units_si(args, files)
    spec = resolve(args, load=args.load, penetration=args.penetration, speed=args.speed,
                   files=files, si=si)
    validate(spec)
    report_fit(spec.get("_material"), ".", "point")  # a DMA fit: its figure beside the command
    return EXIT_OK if points.point(spec, fields=args.fields) else EXIT_FAILED
