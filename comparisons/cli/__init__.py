"""The command line every part answers to.

    python -m comparisons point --solver {analytic,bem} (--load P | --penetration D) --speed S
                                [--ratio R] [--hk H] [--nodes N | --rtol T] [--max-nodes M]
                                [--profile F] [--prony F] [--fields FILE.csv]
                                [--material F [--max-residual B] [--per-decade K] [--loss-weight W]
                                 [--extend D] [--material-kind {E,G}] [--frequency-unit U]
                                 [--vertical-shift V] [--shift-method M]
                                 [--nu NU (shear moduli: E = 2 (1 + ν) G)]
                                 [--temperature T (--wlf C1 C2 TREF | --shift-table F)]]
                                [--units SI --nu NU --wavelength L --amplitude H
                                 (--E0 E --Einf E (--tau-creep S | --tau-relax S) | --material F)]
    python -m comparisons sweep --solver {analytic,bem} (--load P [P ...] | --penetration D [D ...])
                                --speed S [S ...] [options of point]
                                [--workers W | --scheduler ADDRESS] [--fields DIR]
    python -m comparisons report [--out DIR] [--quick] [--resume] [--workers W | --scheduler A]
    python -m comparisons crosscheck [--nodes N ...] | --tolerances
    python -m comparisons bench [--points N] [--bem | --bem-only | --cluster | --honesty [--seed S] [--light] [--front-door] | --materials [--seed S] [--workers W] | --accepted [--seed S] [--cheap]] [--max-log2n K]
    python -m comparisons suite ... | verify ...   (comparisons/suite.py, comparisons/verify/)
    python -m comparisons mastercurve ...           (comparisons/mastercurve.py)

Materials (--material, temperatures, SI, the speed's time): comparisons/_materials.py and
docs/materials.md.

`point` prints one JSON object; `sweep` one per line, in order (loads outer, speeds inner); a
value of a sweep may be a log range START:STOP:COUNT.  Exit status: 0 every result printed;
1 a point could not be solved (reported on standard error, never printed as a result); 2 input
outside what is supported, refused before any work.  Either way one line per problem on standard
error, never a traceback.

Each subcommand is one module of this package: ``add_parser(sub)`` adds its parser to the
subparsers ``sub`` and sets its ``run`` (``p.set_defaults(run=run)``), ``run(args)`` returns the
exit status; it parses and calls the library, nothing more (``_common``: what they share).
`SUBCOMMANDS` lists the modules in the order of ``--help``.  A subcommand module imports its
library module when it runs (or in ``add_parser`` for a default its help states), so a library
module that cannot be imported takes only its own subcommand down.
"""
from __future__ import annotations

import argparse
import os
import re
import sys

from .._errors import one_line
from . import bench, crosscheck, mastercurve, point, report, suite, sweep, verify
from ._common import (EXIT_BAD_INPUT, EXIT_FAILED, EXIT_OK, BadInput, Failed, Parser, log_range,
                      stderr)

__all__ = ["main", "build_parser", "SUBCOMMANDS", "BadInput", "Failed", "log_range",
           "EXIT_OK", "EXIT_FAILED", "EXIT_BAD_INPUT"]

#: the subcommands, in the order of --help
SUBCOMMANDS = (point, sweep, report, crosscheck, bench, suite, verify, mastercurve)


def _add(sub, module):
    """``module.add_parser(sub)``; a module whose parser cannot be made (a library it needs
    fails to import) becomes a stub that says so, the other subcommands unharmed."""
    try:
        module.add_parser(sub)
    except Exception as exc:
        why = f"{type(exc).__name__}: {one_line(exc)}"
        name = module.__name__.rpartition(".")[2]

        def unavailable(args):
            raise Failed(f"unavailable ({why})")
        stub = sub.add_parser(name, help=f"(unavailable: {why})", add_help=False,
                              prefix_chars="\0")
        stub.add_argument("rest", nargs=argparse.REMAINDER)  # whatever follows: same answer
        stub.set_defaults(run=unavailable)


#: the program's name in --help and in every message, unless the caller names it otherwise
PROG = "python -m comparisons"


def build_parser(prog=PROG):
    parser = Parser(prog=prog,
                    description="viscosine: two roads to the steady viscoelastic sliding of a "
                                "rigid periodic indenter")
    sub = parser.add_subparsers(dest="command", required=True, parser_class=Parser)
    for module in SUBCOMMANDS:
        _add(sub, module)
    return parser


def main(argv=None, prog=PROG):
    """Run the command line; return the exit status (never raises, never prints a traceback).
    ``prog`` names the program in --help and the messages (``viscosine`` for that command)."""
    parser = Parser(prog=prog)  # for the messages, until the real one exists
    args = None
    try:
        parser = build_parser(prog)
        args, extra = parser.parse_known_args(argv)
        if extra:
            stray_value = not extra[0].startswith("-") or re.fullmatch(r"-[\d.]\S*", extra[0])
            hint = (" (point takes one value of --load/--penetration/--speed; use sweep for "
                    "several)" if args.command == "point" and stray_value else "")
            raise BadInput(f"unrecognized arguments: {' '.join(extra)}{hint}")
        return args.run(args)
    except (BadInput, Failed) as exc:
        prog = exc.prog or " ".join([parser.prog] + ([args.command] if args else []))
        stderr(f"{prog}: {one_line(exc)}")
        return EXIT_FAILED if isinstance(exc, Failed) else EXIT_BAD_INPUT
    except SystemExit as exc:  # --help, --version
        return exc.code if isinstance(exc.code, int) else EXIT_OK
    except KeyboardInterrupt:
        stderr("interrupted")
        return 130
    except BrokenPipeError:  # the reader went away (e.g. | head): stop quietly
        try:
            sys.stdout = open(os.devnull, "w")
        except OSError:
            pass
        return EXIT_FAILED
    except Exception as exc:  # a bug: still one line, and the status says it failed
        if os.environ.get("VISCOSINE_DEBUG"):
            raise
        stderr(f"{parser.prog}: internal error: {type(exc).__name__}: {one_line(exc)} "
               "(set VISCOSINE_DEBUG=1 for the traceback)")
        return EXIT_FAILED
