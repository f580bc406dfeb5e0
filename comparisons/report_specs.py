"""The report's operating points (the paper's material `RATIO` and roughness `HK`, the speeds,
loads and penetrations of its figures, the points of its fields, scalars and convergence study,
Tamaas's points) as the specs of its runs, and the two roads read back at them (`semi_analytic`,
`stored`).  Part of `comparisons.report_numbers`, which re-exports it.
"""
from __future__ import annotations

import functools

from . import operating_point as op
from . import roads

# ---------------------------------------------------------------------------- operating points
RATIO, HK = 3.0, 1.0

FIG_SPEEDS = [0.01, 1.0, 2.0, 5.0, 10.0, 100.0]          # figures 4–6 (legend of figure 4)
PROFILE_SPEEDS = [0.01, 0.3, 1.0, 3.0, 100.0]             # figure 3
FIG7_PEN = [0.5, 0.8, 0.95]
FIG9_LOADS = [0.6, 0.8, 1.0, 1.2, 1.4]                    # (p̃FC)0 < p̃∞ < (p̃FC)∞
FIG12_LOADS = [0.1, 0.3, 0.6, 1.0, 1.4, 2.0]
FIELD_POINTS = [  # (label, load, speed)
    ("partial contact", 0.3, 1.0),
    ("near the transition", 0.66, 1.0),
    ("full contact", 1.0, 1.0),
]
SCALAR_EXTRA = [(0.05, 1.0), (0.3, 0.01), (0.3, 100.0), (1.3, 10.0)]  # (load, speed)
CONV_POINTS = [("partial contact, p̃∞ = 0.3, V/V0 = 1", 0.3, 1.0),
               ("near the transition, p̃∞ = 0.66, V/V0 = 1", 0.66, 1.0),
               ("full contact, p̃∞ = 1.0, V/V0 = 1", 1.0, 1.0)]


def bem_spec(load=None, speed=1.0, nodes=4096, penetration=None):
    """The point of a BEM run of the report (`comparisons.operating_point.at`) at p̃∞ = ``load``
    or Δ/h = ``penetration``, V/V0 = ``speed``, on ``nodes`` panels per period."""
    return op.at("bem", float(speed), load=None if load is None else float(load),
                 penetration=None if penetration is None else float(penetration),
                 ratio=RATIO, hk=HK, nodes=int(nodes))


TAMAAS_LOAD = 0.15


@functools.lru_cache(maxsize=None)
def tamaas_speeds():
    """(peak speed, peak μ, (speeds below, at and above the friction peak)) at TAMAAS_LOAD.

    The peak is the semi-analytic road's (`comparisons.peers.tamaas.friction_peak`); the three
    speeds are peak/3, peak and 3·peak rounded to four digits, so that the store's specs are
    plain, readable numbers.
    """
    from .peers import tamaas as peer
    peak, mu = peer.friction_peak(load=TAMAAS_LOAD, ratio=RATIO, hk=HK)
    return peak, mu, tuple(float(f"{v:.4g}") for v in (peak / 3.0, peak, 3.0 * peak))


def tamaas_spec(speed, nodes, cells):
    """The spec of a Tamaas run at p̃∞ = `TAMAAS_LOAD`, V/V0 = ``speed``, on ``nodes`` grid
    points, stepped by dt = ``cells`` × T/N."""
    return {"solver": "tamaas", "load": TAMAAS_LOAD, "penetration": None, "speed": float(speed),
            "ratio": RATIO, "hk": HK, "nodes": int(nodes), "cells_per_step": int(cells)}


# ---------------------------------------------------------------------------- both roads
def semi_analytic(load=None, speed=1.0, pen=None):
    """The semi-analytic solution at p̃∞ = ``load`` or Δ/h = ``pen``, V/V0 = ``speed``
    (`comparisons.roads.analytic_solution`); raises RuntimeError when it did not converge."""
    control = {"load": load} if pen is None else {"penetration": pen}
    sol = roads.analytic_solution({**control, "speed": speed, "ratio": RATIO, "hk": HK})
    if not sol.success:
        raise RuntimeError(f"semi-analytic solver failed at load={load}, Δ={pen}, V={speed}: "
                           f"{sol.message} {sol.residuals}")
    return sol


def stored(store, spec, fields=False):
    """A BEM record, or None when the run failed (failures are listed in the report)."""
    doc = store.get(spec, fields)
    return doc if doc["ok"] else None
