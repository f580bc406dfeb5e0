"""``mastercurve``: the friction master curve μ(V) at several temperatures
(`comparisons.mastercurve`)."""
from __future__ import annotations

from ._common import EXIT_FAILED, EXIT_OK, Once, integer, log_range, number


def add_parser(sub):
    from ..mastercurve import DEFAULT_RTOL
    p = sub.add_parser("mastercurve", help="friction master curve μ(V) at several temperatures "
                                           "(SI; figure, CSV and JSON)",
                       description="Solve μ at every (temperature, speed) of a material through "
                                   "the boundary-element road and write points.csv (each point "
                                   "as it is done), mastercurve.json and mastercurve.png.  SI "
                                   "units; see docs/materials.md.")
    p.add_argument("--material", required=True, action=Once, metavar="FILE",
                   help="a creep or relaxation series (Pa, s) or a DMA master curve (CSV, its "
                        "header naming the modulus unit), at the shift's reference temperature")
    g = p.add_mutually_exclusive_group(required=True)
    g.add_argument("--wlf", type=number, nargs=3, action=Once, metavar=("C1", "C2", "TREF"),
                   help="WLF shift log10 a_T = -C1 (T - TREF)/(C2 + T - TREF)")
    g.add_argument("--shift-table", action=Once, metavar="FILE",
                   help="shift table CSV (columns temperature, log_aT); T outside it is refused")
    p.add_argument("--temperatures", type=number, nargs="+", required=True, action=Once,
                   metavar="T", help="temperatures, in the unit of the shift")
    p.add_argument("--speeds", type=log_range, nargs="+", required=True, action=Once,
                   metavar="V", help="sliding speeds V [m/s] (values, or log ranges "
                                     "START:STOP:COUNT)")
    p.add_argument("--load", type=number, required=True, action=Once, metavar="P",
                   help="mean pressure p∞ [Pa]")
    p.add_argument("--wavelength", type=number, required=True, action=Once, metavar="L",
                   help="λ of the rigid sinusoid [m]")
    p.add_argument("--amplitude", type=number, required=True, action=Once, metavar="H",
                   help="h of the rigid sinusoid [m]")
    p.add_argument("--nu", type=number, required=True, action=Once, metavar="NU",
                   help="Poisson's ratio")
    m = p.add_mutually_exclusive_group()
    m.add_argument("--nodes", type=integer, action=Once, metavar="N",
                   help="a fixed mesh of N panels per period (default: adaptive)")
    m.add_argument("--rtol", type=number, action=Once, metavar="R",
                   help=f"accuracy of the adaptive mesh (default {DEFAULT_RTOL:g})")
    p.add_argument("--max-residual", type=number, action=Once, metavar="B",
                   help="DMA: the largest relative residual of the Prony fit (default 0.05)")
    p.add_argument("--per-decade", type=number, action=Once, metavar="K",
                   help="DMA: relaxation times per decade of the fit (default 2)")
    p.add_argument("--out", action=Once, metavar="DIR",
                   help="output folder (default ./mastercurve); a run's points.csv there is "
                        "continued when its parameters are the same")
    p.set_defaults(run=run)


def run(args) -> int:
    """0 every point solved, 1 some could not be, 2 bad input."""
    from .. import mastercurve
    failed = mastercurve.write_curve(
        "mastercurve" if args.out is None else args.out, args.material, wlf=args.wlf,
        shift_table=args.shift_table, temperatures=args.temperatures, speeds=args.speeds,
        mean_pressure=args.load, wavelength=args.wavelength, amplitude=args.amplitude,
        nu=args.nu, nodes=args.nodes, rtol=args.rtol, max_residual=args.max_residual,
        per_decade=args.per_decade)
    return EXIT_FAILED if failed else EXIT_OK
