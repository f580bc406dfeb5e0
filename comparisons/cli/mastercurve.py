"""``mastercurve``: the friction master curve μ(V) at one or several temperatures
(`comparisons.mastercurve`)."""
from __future__ import annotations

from .. import operating_point as op
from ._common import (EXIT_FAILED, EXIT_OK, BadInput, Once, WhichTime, dma_fit_options,
                      integer, log_range, number)

#: the standard linear solid's options, as `point --units SI` names them
_SLS = ("E0", "Einf", "tau_creep", "tau_relax")


def add_parser(sub):
    from ..mastercurve import DEFAULT_RTOL
    p = sub.add_parser("mastercurve", help="friction master curve μ(V) at one or several "
                                           "temperatures (SI; figure, CSV and JSON)",
                       description="Solve μ at every (temperature, speed) of a material through "
                                   "the boundary-element road and write points.csv (each point "
                                   "as it is done), mastercurve.json and mastercurve.png.  SI "
                                   "units; see docs/materials.md.")
    mat = p.add_argument_group("the material (SI): a file, or the standard linear solid")
    mat.add_argument("--material", action=Once, metavar="FILE",
                     help="a creep or relaxation series (Pa, s), a DMA master curve (CSV, its "
                          "header naming the modulus unit), at the shift's reference temperature, "
                          "E(t)/J(t), an FE Prony card, or raw isotherms (a temperature column "
                          "too: moved to --temperatures by the WLF fitted to them; no --wlf)")
    for option, unit, what in (("--E0", "Pa", "relaxed modulus of the standard linear solid"),
                               ("--Einf", "Pa", "instantaneous modulus E∞ > E0"),
                               ("--tau-creep", "s", "creep (retardation) time τ of eq. 2.3"),
                               ("--tau-relax", "s", "relaxation time τ E0/Einf (instead of "
                                                    "--tau-creep)")):
        mat.add_argument(option, type=number, action=Once,
                         metavar="E" if unit == "Pa" else "S",
                         help=f"without --material: the {what} [{unit}]")
    p.add_argument("--tau", action=WhichTime, dest="_tau")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--wlf", type=number, nargs=3, action=Once, metavar=("C1", "C2", "TREF"),
                   help="WLF shift log10 a_T = -C1 (T - TREF)/(C2 + T - TREF)")
    g.add_argument("--shift-table", action=Once, metavar="FILE",
                   help="shift table CSV (columns temperature, log_aT); T outside it is refused. "
                        "Without a shift the material is solved as given, at the one "
                        "temperature of --temperatures (its own)")
    p.add_argument("--temperatures", type=number, nargs="+", required=True, action=Once,
                   metavar="T", help="temperatures, in the unit of the shift (without one: "
                                     "the material's own temperature, one value)")
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
                   help="Poisson's ratio (also turns a --material of shear moduli into tensile "
                        "ones: E = 2 (1 + ν) G)")
    m = p.add_mutually_exclusive_group()
    m.add_argument("--nodes", type=integer, action=Once, metavar="N",
                   help="a fixed mesh of N panels per period (default: adaptive)")
    m.add_argument("--rtol", type=number, action=Once, metavar="R",
                   help=f"accuracy of the adaptive mesh (default {DEFAULT_RTOL:g})")
    dma_fit_options(p)
    p.add_argument("--reference-temperature", type=number, action=Once, metavar="T0",
                   help="raw isotherms: the temperature of their master curve and of the WLF "
                        "fitted to them (default: the isotherm nearest mid-range)")
    p.add_argument("--out", action=Once, metavar="DIR",
                   help="output folder (default ./mastercurve); a run's points.csv there is "
                        "continued when its parameters are the same")
    p.set_defaults(run=run)


def run(args) -> int:
    """0 every point solved, 1 some could not be, 2 bad input."""
    from .. import _materials, mastercurve
    failed = mastercurve.write_curve(
        "mastercurve" if args.out is None else args.out, _material(args), wlf=args.wlf,
        shift_table=args.shift_table, temperatures=args.temperatures, speeds=args.speeds,
        mean_pressure=args.load, wavelength=args.wavelength, amplitude=args.amplitude,
        nu=args.nu, nodes=args.nodes, rtol=args.rtol, max_residual=args.max_residual,
        reference_temperature=args.reference_temperature,
        per_decade=args.per_decade, loss_weight=args.loss_weight,
        **{k: getattr(args, k) for k in _materials.DATA_OPTIONS})
    return EXIT_FAILED if failed else EXIT_OK


def _material(args):
    """--material FILE (its name), or the standard linear solid of --E0 --Einf --tau-creep or
    --tau-relax (a `viscosine.materials.Maxwell` in Pa and s)."""
    from .. import _materials, mastercurve
    given = [f"--{k.replace('_', '-')}" for k in _SLS if getattr(args, k) is not None]
    if args.material is not None:
        if given:
            raise BadInput(f"{given[0]} is not allowed with --material: the material is the "
                           "file's")
        return args.material
    if not given:
        raise BadInput("the material is missing: --material FILE, or --E0 E --Einf E [Pa] with "
                       "--tau-creep or --tau-relax [s]")
    for option in ("--E0", "--Einf"):
        if option not in given:
            raise BadInput(f"{option} is missing: the standard linear solid takes --E0 --Einf "
                           "[Pa] with --tau-creep or --tau-relax [s]")
    for name in op.FIT_OPTIONS + _materials.DATA_OPTIONS:
        if getattr(args, name) is not None:
            raise op.refuse(name, op.FIT_ONLY if name in op.FIT_OPTIONS else
                            "it applies to measured data (--material FILE)")
    if args.tau_creep is not None and args.tau_relax is not None:
        raise BadInput("--tau-relax is not allowed with --tau-creep: one time of the solid "
                       "(the relaxation time is τ E0/Einf)")
    try:
        return mastercurve.standard_linear_solid(args.E0, args.Einf, tau_creep=args.tau_creep,
                                                 tau_relax=args.tau_relax)
    except ValueError as exc:
        raise BadInput(str(exc)) from None
