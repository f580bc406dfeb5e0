"""Input checks both roads share: the refusal message and the range test of real inputs.

A refusal reads ``"name=value is not allowed: what is allowed (and why)"``; each road's
``ACCEPTED`` table maps a name to ``(low, high, what is allowed and why)``.
"""
from __future__ import annotations

import math
import numbers


def is_real(value) -> bool:
    """A real number that is not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool)


def bad(name, value, allowed) -> ValueError:
    """The ValueError that refuses ``name=value``, saying what is allowed."""
    shown = repr(float(value)) if is_real(value) else repr(value)
    return ValueError(f"{name}={shown} is not allowed: {allowed}")


def real(name, value, text) -> float:
    """``value`` as a finite float, else the refusal (``text``: what is allowed)."""
    if not is_real(value):
        raise bad(name, value, "a real number; " + text)
    v = float(value)
    if not math.isfinite(v):
        raise bad(name, v, "a finite number; " + text)
    return v


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
        v = real(name, value, text)
        test = tests.get(name)
        if not (test(v) if test is not None else low <= v <= high):
            raise bad(name, v, text)
        out[name] = v
    return out


def at_most_one_control(load, penetration) -> None:
    """Refuse a load and a penetration given together (each road's solve needs exactly one)."""
    if load is not None and penetration is not None:
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
