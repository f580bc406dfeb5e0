"""The units a material file may state: modulus units in pascals, frequency units."""
from __future__ import annotations

#: modulus units a DMA header may name (``storage [MPa]``), in pascals (matched ignoring case)
PASCALS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/mm2": 1e6, "n/mm^2": 1e6,
           "psi": 6894.757293168361}

#: what a Poisson ratio may be (the shear data's conversion E = 2 (1 + nu) G)
POISSON_ALLOWED = "a Poisson ratio in (-1, 0.5]"


def poisson(nu, what):
    """``nu`` checked as the Poisson ratio that turns ``what`` (shear moduli) into tensile
    ones, E = 2 (1 + nu) G; ValueError ``nu=... is not allowed`` when missing or outside
    (-1, 0.5]."""
    from ..checks import bad, real
    if nu is None:
        raise bad("nu", nu, f"{POISSON_ALLOWED} to turn {what} into tensile moduli "
                  "(E = 2 (1 + nu) G)")
    return real("nu", nu, POISSON_ALLOWED, lambda v: -1.0 < v <= 0.5)
