"""The semi-analytic road: the paper's own method, complete.

Steady sliding of a rigid sinusoid y = h cos(k(x − Vt)) over a standard linear solid
(J(t) = 1/E0 − (1/E1) e^{−t/τ}, 1/E∞ = 1/E0 − 1/E1) in plane strain, solved with Hunter's
transformation (eqs 2.7–2.8), the periodic elastic arc solution (Appendix A) and the closure
(2.14)–(2.15), re-derived in `analytic/DERIVATION.md`; full contact from Appendix B.

Units, stated once: lengths in 1/k (k = 2π/λ), pressures in E0/(1 − ν²), times in τ.  The inputs
are the dimensionless groups of `conventions.md`: load p̃∞ = p∞(1 − ν²)/E0, speed V/V0 = Vτk,
ratio E∞/E0 and hk.  `dimensional` is a thin SI front on top.

This package never imports `bem` (the two roads are independent).
"""
from .full_contact import modulus, threshold_speed, transition_load
from viscosine import Fields

from .solver import Solution, solve, validate

__all__ = ["Fields", "Solution", "modulus", "solve", "threshold_speed",
           "transition_load", "validate"]
