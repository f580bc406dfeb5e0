"""``verify``: verify another code's results against viscosine's reference
(`comparisons.verify`).

Its option types name the option in their messages (``--load 'x': not a number``).
"""
from __future__ import annotations

import argparse

from ._common import WhichTime

#: the solid's two times (exactly one is given; a bare --tau is refused)
_TIMES = {"tau-creep": ": the creep (retardation) time of eq. (2.3)",
          "tau-relax": ": the relaxation time, tau_creep E0/Einf (instead of --tau-creep)"}


def _float_opt(name):
    def conv(text):
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"--{name} {text!r}: not a number") from None
        return v
    return conv


def _int_opt(name):
    def conv(text):
        try:
            return int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"--{name} {text!r}: not an integer") from None
    return conv


def add_parser(sub):
    from ..verify import (ALL_KEYS, DEFAULT_DT_CELLS, DEFAULT_NODES, DEFAULT_PEER_NODES,
                          DEFAULT_RTOL, GRID_FACTOR, SURFACE_DEFAULT_NODES, SURFACE_KEYS)
    p = sub.add_parser("verify", help="verify another code's results against viscosine's "
                                      "reference: verdict, report.md/.html, verdict.json",
                       description="Verify another code's results against viscosine's "
                                   "reference. The operating point is in the conventions' "
                                   "dimensionless units, or in SI with --units SI (then --load "
                                   "is p∞ in Pa, --penetration Δ in m, --speed V in m/s).")
    p.add_argument("--case", default=None, help="a suite case (see `suite --list`); a surface "
                                                "case (surface-...) takes 2-D fields")
    g = p.add_mutually_exclusive_group()
    g.add_argument("--load", type=_float_opt("load"), default=None,
                   help="p̃∞ = p∞(1 − ν²)/E0; with --units SI the mean pressure p∞ in Pa")
    g.add_argument("--penetration", type=_float_opt("penetration"), default=None,
                   help="Δ/h; with --units SI the penetration Δ in m")
    p.add_argument("--speed", type=_float_opt("speed"), default=None,
                   help="V/V0 = Vτk; with --units SI the sliding speed V in m/s")
    p.add_argument("--ratio", type=_float_opt("ratio"), default=None, help="E∞/E0 (default 3)")
    p.add_argument("--hk", type=_float_opt("hk"), default=None, help="h k (default 1)")
    p.add_argument("--profile", default=None, help="profile file (bem.read_profile)")
    p.add_argument("--prony", default=None, help="Prony creep function file (bem.read_prony)")
    src = p.add_mutually_exclusive_group(required=True)
    src.add_argument("--fields", nargs="+", metavar="F.csv", default=None,
                     help="fields CSV files (several: a convergence study); on a surface case "
                          ".npz files of the conventions (x, y, pressure[, displacement, gap])")
    src.add_argument("--scalars", metavar="F.jsonl", default=None,
                     help="JSON lines of scalars: a UTF-8 file of JSON objects, one per "
                     "result, keyed like the conventions (mu, tau_f, penetration, ka, ...; a "
                     "surface case: mu, mu_lateral, penetration, contact_fraction, load), with "
                     "'nodes' when there are several")
    src.add_argument("--callable", metavar="MODULE:FUNCTION", default=None,
                     help="function(point, nodes) returning fields")
    src.add_argument("--peer", choices=["tamaas"], default=None,
                     help="a third-party code: Tamaas, a dt study at each --nodes extrapolated "
                          "to dt → 0 (progress on standard error)")
    p.add_argument("--nodes", type=_int_opt("nodes"), nargs="+", default=None,
                   help="resolutions for --callable (default "
                        f"{' '.join(map(str, DEFAULT_NODES))}; on a surface case panels per "
                        f"side, default {' '.join(map(str, SURFACE_DEFAULT_NODES))}) or --peer "
                        "(default "
                        f"{' '.join(map(str, DEFAULT_PEER_NODES))}: about a minute on two cores)")
    dt = p.add_mutually_exclusive_group()
    dt.add_argument("--dt-cells", type=_float_opt("dt-cells"), nargs="+", default=None,
                    metavar="C", help="--peer: the dt study's time steps, in cell crossings T/N "
                    "(T the period), coarse to fine (default "
                    f"{' '.join(map(str, DEFAULT_DT_CELLS))}); the verdict is on the values extrapolated to dt → 0, with their "
                    "estimated error (one value: no extrapolation)")
    dt.add_argument("--dt", type=_float_opt("dt"), default=None,
                    help="--peer: a single time step in units of τ (no dt study)")
    p.add_argument("--rtol", type=_float_opt("rtol"), default=None,
                   help="a flat tolerance of every scalar and of the contact edges (default: "
                        f"max({DEFAULT_RTOL:g}, {GRID_FACTOR:g} e_N) on a grid of N points, "
                        "e_N what viscosine's BEM misses the reference by there; "
                        f"{DEFAULT_RTOL:g} when N is not known); the field norms' tolerances "
                        "follow from the grid (the verdict states each, and why)")
    p.add_argument("--tol", action="append", default=[], metavar="NAME=VALUE",
                   help=f"tolerance of one quantity: {', '.join(ALL_KEYS)}; on a surface case "
                        f"{', '.join(SURFACE_KEYS)}")
    p.add_argument("--units", choices=["conventions", "SI"], default="conventions",
                   help="SI: the fields files in Pa, m, m (with --E0 --nu --amplitude) and, "
                        "without --case, the operating point in SI: --load in Pa (or "
                        "--penetration in m), --speed in m/s, with --E0 --Einf, --tau-creep "
                        "or --tau-relax, --nu --wavelength --amplitude")
    for name, unit in (("E0", "Pa"), ("Einf", "Pa"), ("tau-creep", "s"), ("tau-relax", "s"),
                       ("nu", "-"), ("wavelength", "m"), ("amplitude", "m")):
        p.add_argument(f"--{name}", type=_float_opt(name), default=None,
                       help=f"--units SI: {name} [{unit}]" + _TIMES.get(name, ""))
    p.add_argument("--tau", action=WhichTime, dest="_tau")
    p.add_argument("--out", default="verify-report", help="output folder (default ./verify-report)")
    p.add_argument("--label", default=None, help="name of the solver under test in the report")
    p.add_argument("--no-figures", action="store_true", help="skip the figures")
    p.set_defaults(run=run)


def run(args) -> int:
    """0 the verdict is PASS, 1 FAIL (or a failure), 2 bad input."""
    from .. import verify
    return verify.run(args)
