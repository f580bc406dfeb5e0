"""Sweeps as tables: both roads' ``sweep`` functions are this loop around their own ``solve``.

No numerics here: a sweep solves every (load or penetration, speed) pair — loads in the outer
loop, speeds in the inner, as on the command line — and gathers the results of the result
protocol into a dict of 1-D arrays.  Bad input raises ValueError before any work (every point is
checked by ``validate`` first).  A point that fails (an unconverged result, or an ArithmeticError,
LinAlgError, MemoryError or RuntimeError raised by the solver) is a row with ``success`` False,
NaN values and its message; it never stops the other points.
"""
from __future__ import annotations

import math

import numpy as np

#: the scalar columns every table has (NaN where the result has None or failed)
SCALARS = ("contact_fraction", "ka", "ke", "ke_hat", "penetration", "separation", "tau_f", "mu",
           "max_pressure", "x_max_pressure")
#: the keys of an error estimate, when the road gives one
ERROR_KEYS = ("contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu")


def _values(name, values):
    arr = np.atleast_1d(np.asarray(values, dtype=float))
    if arr.ndim != 1 or arr.size == 0:
        raise ValueError(f"{name}={values!r} is not allowed: a non-empty 1-D sequence of numbers")
    return arr


def _float(v):
    return math.nan if v is None else float(v)


def sweep(solve, validate, *, load=None, penetration=None, speed, errors=False, extra=(),
          **options):
    """Run ``solve(load=…|penetration=…, speed=…, **options)`` over the outer product.

    Parameters
    ----------
    solve : callable
        One road's keyword-only ``solve``.
    validate : callable
        Called as ``validate(load=…|penetration=…, speed=…, **options)`` for every point before
        any is solved; raises ValueError on bad input.
    load, penetration : sequence of float
        Exactly one: the controls, outer loop.
    speed : sequence of float
        Inner loop.
    errors : bool
        Add the columns ``error_<key>`` from ``result.error_estimate``.
    extra : sequence of str
        Further result attributes to tabulate (plain numbers, e.g. ``"nodes"``).
    **options
        Passed to every solve (ratio, hk, material, …).

    Returns
    -------
    dict of ndarray
        ``load`` (achieved), ``speed``, ``success``, ``full_contact``, the scalars, ``n_patches``,
        ``message`` (object array), and the requested extras.
    """
    if (load is None) == (penetration is None):
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give exactly "
                         "one of load and penetration")
    control = "load" if load is not None else "penetration"
    outer = _values(control, load if load is not None else penetration)
    inner = _values("speed", speed)
    n = outer.size * inner.size
    table = {"load": np.full(n, math.nan), "speed": np.repeat(inner[None, :], outer.size, 0).ravel(),
             "success": np.zeros(n, bool), "full_contact": np.zeros(n, bool),
             "n_patches": np.zeros(n, int), "message": np.empty(n, dtype=object)}
    if control == "penetration":
        table["penetration_asked"] = np.repeat(outer, inner.size)
    for key in SCALARS:
        table[key] = np.full(n, math.nan)
    for key in extra:
        table[key] = np.full(n, math.nan)
    if errors:
        for key in ERROR_KEYS:
            table[f"error_{key}"] = np.full(n, math.nan)
    for c in outer:
        for s in inner:
            validate(**{control: float(c)}, speed=float(s), **options)
    i = 0
    for c in outer:
        for s in inner:
            try:
                res = solve(**{control: float(c)}, speed=float(s), **options)
            except (ArithmeticError, MemoryError, RuntimeError, np.linalg.LinAlgError) as exc:
                table["message"][i] = f"{type(exc).__name__}: {exc}"
                if control == "load":
                    table["load"][i] = c
                i += 1
                continue
            table["message"][i] = res.message
            table["load"][i] = float(res.load) if control == "penetration" else c
            if res.success:
                table["success"][i] = True
                table["full_contact"][i] = bool(res.full_contact)
                table["n_patches"][i] = int(res.n_patches)
                for key in SCALARS:
                    table[key][i] = _float(getattr(res, key))
                for key in extra:
                    table[key][i] = _float(getattr(res, key))
                if errors and res.error_estimate is not None:
                    for key in ERROR_KEYS:
                        table[f"error_{key}"][i] = _float(res.error_estimate.get(key))
            i += 1
    return table
