"""The errors a command reports in one line on standard error, never as a traceback.

Raised by the command line (`comparisons.cli`) and by the library functions it calls (a sweep,
`runner`, `verify`, `mastercurve`, the suite, the readers and output checks of `_io`), which
therefore never import the command line: `comparisons.cli.main` prefixes the (sub)command and
turns them into exit statuses.  One hierarchy::

    ValueError
        BadInput            input outside what is supported: exit status 2
            SuiteError      the suite's (an unknown case, unreadable suite data)
            MissingPackage  an optional extra not installed (--scheduler without distributed)
    RuntimeError
        Failed              the work could not be done: exit status 1
            StoreError      a stored result missing or not to be trusted
            ClusterError    the executor could not be set up (an unreachable scheduler)

In Python, bad input is therefore a ValueError, as the roads' own refusals are.
"""
from __future__ import annotations


class BadInput(ValueError):
    """Input outside what is supported: one line on standard error, exit status 2.

    ``prog`` names the (sub)command; `comparisons.cli.main` adds the subcommand's when it is None.
    """

    def __init__(self, message, prog=None):
        super().__init__(message)
        self.prog = prog


class Failed(RuntimeError):
    """The command could not do its work: one line on standard error, exit status 1.

    ``prog`` as for `BadInput`.
    """

    def __init__(self, message, prog=None):
        super().__init__(message)
        self.prog = prog


class SuiteError(BadInput):
    """Bad input to the suite (unknown case, unreadable data); one line for the command line."""


class MissingPackage(BadInput):
    """``distributed`` is not installed (the cluster extra): a request this installation cannot
    serve."""


class StoreError(Failed):
    """A stored result is missing or cannot be trusted."""


class ClusterError(Failed):
    """The executor could not be set up (unreachable scheduler)."""


def bad_input(option, value, problem, allowed=None):
    """The BadInput ``option value: problem; allowed: allowed`` (without the value when None)."""
    text = f"{option}: {problem}" if value is None else f"{option} {value}: {problem}"
    if allowed:
        text += f"; allowed: {allowed}"
    return BadInput(text)


def one_line(exc):
    """The first line of an exception's text (its type's name when it has none): what a
    command prints of it on standard error."""
    text = str(exc).strip().splitlines()
    return text[0] if text else type(exc).__name__


def reason(exc):
    """What a command prints of an exception after the option and value it names: for a
    refusal (`viscosine.checks.Refusal`) ``must be <what is allowed>`` (its why is the docs'
    and the Python message's), else its first line (`one_line`)."""
    from viscosine.checks import Refusal, allowed_part
    if isinstance(exc, Refusal):
        tail = f" [{exc.unit}]" if exc.unit else ""
        return f"must be {allowed_part(exc.allowed)}{tail}"
    return one_line(exc)

