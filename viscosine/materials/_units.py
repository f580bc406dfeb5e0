"""The units a material file may state: modulus units in pascals, frequency units."""
from __future__ import annotations

#: modulus units a DMA header may name (``storage [MPa]``), in pascals (matched ignoring case)
PASCALS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/mm2": 1e6, "n/mm^2": 1e6,
           "psi": 6894.757293168361}
