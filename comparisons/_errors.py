"""The errors a command reports in one line on standard error, never as a traceback.

Raised by the command line (`comparisons.cli`) and by the library functions it calls (a sweep,
`verify`, `mastercurve`, the output checks of `_io`), which therefore never import the command
line: `comparisons.cli.main` prefixes the (sub)command and turns them into exit statuses.
"""
from __future__ import annotations


class BadInput(Exception):
    """Input outside what is supported: one line on standard error, exit status 2.

    ``prog`` names the (sub)command; `comparisons.cli.main` adds the subcommand's when it is None.
    """

    def __init__(self, message, prog=None):
        super().__init__(message)
        self.prog = prog


class Failed(BadInput):
    """The command could not do its work: one line on standard error, exit status 1."""


class InputError(ValueError):
    """Input outside what is supported, raised by the library (`runner`, the readers of `_io`):
    the command line reports it in one line on standard error, exit status 2."""


def one_line(exc):
    """The first line of an exception's text (its type's name when it has none): what a
    command prints of it on standard error."""
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__
