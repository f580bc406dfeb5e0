"""``sweep``: solve every (load or penetration, speed) pair, one JSON object per line, in order."""
from __future__ import annotations

import argparse

from .. import points, sweep_outputs
from ..plots.materials import report_fit
from ._common import (EXIT_BAD_INPUT, EXIT_FAILED, EXIT_OK, Once, accepted_ranges,
                      check_output_dir, check_workers, material_options, parallel_options,
                      resolve, solver_options, units_si, validate)


def add_parser(sub):
    p = sub.add_parser("sweep", help="solve every (load, speed) pair, one JSON object per line",
                       description="Solve every (load or penetration, speed) pair, loads in the "
                                   "outer loop, and print one JSON object per line, in order.",
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.epilog_maker = accepted_ranges
    solver_options(p, several=True)
    parallel_options(p, "default 1: this process")
    p.add_argument("--fields", action=Once, metavar="DIR",
                   help="also write the fields of every point to DIR/<solver>_load<P>_speed<S>.csv")
    p.add_argument("--csv", action=Once, metavar="FILE",
                   help="also write one CSV row per solved point, as it is done; the header names "
                        "each column with its unit (speed [V/V0], or speed [m/s] with --units SI)")
    p.add_argument("--plot", action=Once, metavar="FILE",
                   help="also draw μ against the speed (log axis), one curve per load, to FILE "
                        "(.png, .pdf or .svg) when the sweep ends")
    p.set_defaults(run=run)


def run(args):
    check_workers(args)
    files = {}
    si = units_si(args, files)
    control = "load" if args.load is not None else "penetration"
    values, speeds = getattr(args, control), args.speed
    if args.fields is not None:
        check_output_dir("--fields", args.fields, create=False)
    points.read_files(args.solver, files, profile=args.profile, prony=args.prony,
                      material=args.material, material_options=material_options(args))
    base = resolve(args, speed=speeds[0], files=files, si=si, **{control: values[0]})
    # every input is checked before any work; the ranges are per input, so each value once
    for v in dict.fromkeys(values):
        validate(base.replace(**{control: v}))
    for s in dict.fromkeys(speeds):
        validate(base.replace(speed=s))
    sweep_outputs.check(args.csv, args.plot)
    report_fit(base.get("_material"), ".", "sweep")  # a DMA fit: its figure beside the command
    with sweep_outputs.Outputs(args.csv, args.plot, control=control, n_speeds=len(speeds),
                               si=si is not None, surface=base.get("surface") is not None) as out:
        failed, refused = points.sweep(base, control, values, speeds, workers=args.workers,
                                       scheduler=args.scheduler, fields=args.fields,
                                       on_record=out.add)
    return EXIT_BAD_INPUT if refused else (EXIT_FAILED if failed else EXIT_OK)
