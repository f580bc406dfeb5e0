"""Input checks the whole project shares: the refusal message and the tests of real, integer
and series inputs.  Every copy elsewhere calls these.

A refusal is ``ValueError("name=value is not allowed: what is allowed (and why)")`` on one line
(`bad`: the value shown by `shown`, a long one cut short; an optional ``[unit]`` at the end).
Each road's ``ACCEPTED`` table maps a name to ``(low, high, what is allowed and why)``
(`check_reals`).

Policy, one for the project: a real input is a real number, ``numbers.Real`` (int, float,
numpy's integers and floats) that is not a bool (nor ``numpy.bool_``).  Strings are refused
here: the readers of files and command lines convert text to float before they validate.  An
integer input is a ``numbers.Integral`` that is not a bool (64.0 is refused).
"""
from __future__ import annotations

import math
import numbers

import numpy as np

#: a value shown in a refusal is cut to this many characters (but a string)
SHOWN_MAX = 100


def is_real(value) -> bool:
    """A real number (``numbers.Real``: int, float, numpy's numbers) that is not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_))


def is_integer(value) -> bool:
    """An integer (``numbers.Integral``: int, numpy's integers) that is not a bool."""
    return isinstance(value, numbers.Integral) and not isinstance(value, (bool, np.bool_))


def shown(value) -> str:
    """``value`` as a refusal shows it, on one line.

    An integer as itself, another real number as a Python float (``0.3``, not
    ``np.float64(0.3)``), anything else by its repr, cut to `SHOWN_MAX` characters unless it is
    a string (a file name is shown whole).
    """
    if isinstance(value, str):
        return repr(value)  # one line already
    if is_integer(value):
        try:
            text = repr(int(value))
        except ValueError:  # beyond the digits Python converts
            text = f"<an integer of {int(value).bit_length()} bits>"
    elif is_real(value):
        try:
            text = repr(float(value))
        except OverflowError:
            text = repr(value)
    elif isinstance(value, np.bool_):
        text = repr(bool(value))
    else:
        text = " ".join(repr(value).split())
    if len(text) > SHOWN_MAX:
        text = text[:SHOWN_MAX - 4] + " ..."
    return text


class Refusal(ValueError):
    """A refused input: the ValueError `bad` makes, carrying what it refuses, so that a front
    door can name the input as its user typed it (an option, a keyword) without reading the
    text back: ``name``, ``value``, ``allowed`` and ``unit`` (None without one)."""

    def __init__(self, name, value, allowed, unit=None):
        tail = f" [{unit}]" if unit else ""
        super().__init__(f"{name}={shown(value)} is not allowed: {allowed}{tail}")
        self.name, self.value, self.allowed, self.unit = name, value, allowed, unit

    def __reduce__(self):  # pickled across processes with its fields
        return (type(self), (self.name, self.value, self.allowed, self.unit))


def allowed_part(text) -> str:
    """What is allowed, without why: ``text`` (one line) up to its first ``': '`` outside
    brackets (an interval such as (1, 10] closes with either).  A refusal's text is
    ``"what is allowed: why"``; the command line shows only the first part."""
    text = " ".join(str(text).split())
    depth = 0
    for i, ch in enumerate(text):
        depth += (ch in "([") - (ch in ")]")
        if depth == 0 and text.startswith(": ", i):
            return text[:i]
    return text


def bad(name, value, allowed, unit=None) -> ValueError:
    """The ValueError (a `Refusal`) that refuses ``name=value``, saying what is allowed
    (``[unit]`` after)."""
    return Refusal(name, value, allowed, unit)


def real(name, value, allowed, test=None, *, unit=None, kind=False) -> float:
    """``value`` as a finite float passing ``test`` (a predicate on it), else the refusal.

    ``allowed``: what is allowed, the whole text of the refusal (with ``[unit]`` after it).
    ``kind``: begin the refusal of a value that is not a real number, or not finite, with that
    (``"a real number; "``, ``"a finite number; "``), for an ``allowed`` that states a range only.
    """
    if not is_real(value):
        raise bad(name, value, ("a real number; " if kind else "") + allowed, unit)
    try:
        v = float(value)
    except OverflowError:  # an integer beyond the floats
        raise bad(name, value, ("a finite number; " if kind else "") + allowed, unit) from None
    if not math.isfinite(v):
        raise bad(name, v, ("a finite number; " if kind else "") + allowed, unit)
    if test is not None and not test(v):
        raise bad(name, v, allowed, unit)
    return v


def integer(name, value, allowed, test=None) -> int:
    """``value`` as an int passing ``test``, else the refusal (``allowed``: what is allowed)."""
    if not is_integer(value) or (test is not None and not test(int(value))):
        raise bad(name, value, allowed)
    return int(value)


def positive_int(name, value, minimum=1) -> int:
    """``value`` as an int ``>= minimum``, else the refusal ``"an integer >= minimum"``."""
    return integer(name, value, f"an integer >= {minimum}", lambda v: v >= minimum)


def reals(name, values, allowed, *, unit=None) -> np.ndarray:
    """A real number or an array_like of them (any shape) as a new float array, else the refusal.

    Every element must be a real number (`is_real`): a string, a bool, None or a complex
    number anywhere is refused (``"real numbers; " + allowed``).  Finiteness is not checked.
    """
    if isinstance(values, np.ndarray) and values.dtype.kind in "iuf":
        return values.astype(float)
    why = "real numbers; " + allowed
    if isinstance(values, (str, bytes)):
        raise bad(name, values, why, unit)
    try:
        obj = np.asarray(values, dtype=object)
        flat = obj.ravel().tolist()
    except (TypeError, ValueError):
        raise bad(name, values, why, unit) from None
    if not all(is_real(v) for v in flat):
        raise bad(name, values, why, unit)
    try:
        return np.array([float(v) for v in flat], dtype=float).reshape(obj.shape)
    except OverflowError:  # an integer beyond the floats
        raise bad(name, values, allowed, unit) from None


def series(name, values, allowed, test=None, *, unit=None) -> tuple:
    """A real number or a 1-D sequence of them, each finite and passing ``test``, as a tuple of
    floats (empty for an empty sequence); else the refusal (``allowed``: what is allowed)."""
    arr = reals(name, values, allowed, unit=unit)
    if arr.ndim > 1:
        raise bad(name, values, "a 1-D sequence; " + allowed, unit)
    out = tuple(np.atleast_1d(arr).tolist())
    if not all(math.isfinite(v) and (test is None or test(v)) for v in out):
        raise bad(name, values, allowed, unit)
    return out


def check_reals(accepted, given, tests) -> dict:
    """The given real inputs as floats, each in its range of ``accepted``.

    ``given``: (name, value) pairs, None for "not given" (skipped).  ``tests``: name -> a
    predicate replacing the inclusive ``low <= v <= high`` of ``accepted[name]`` (an open bound,
    a set of isolated values).  Raises the refusal of the first bad input.
    """
    out = {}
    for name, value in given:
        if value is None:
            continue
        low, high, text = accepted[name]
        test = tests.get(name)
        out[name] = real(name, value, text,
                         test if test is not None else (lambda v: low <= v <= high), kind=True)
    return out


def at_most_one_control(load, penetration) -> None:
    """Refuse a load and a penetration given together (each road's solve needs exactly one)."""
    if load is not None and penetration is not None:
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
