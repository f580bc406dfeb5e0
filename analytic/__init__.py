"""The semi-analytic road: the paper's own method, complete.

Steady sliding of a rigid sinusoid y = h cos(k(x − Vt)) over a standard linear solid
(J(t) = 1/E0 − (1/E1) e^{−t/τ}, 1/E∞ = 1/E0 − 1/E1) in plane strain, solved with Hunter's
transformation (eqs 2.7–2.8), the periodic elastic arc solution (Appendix A) and the closure
(2.14)–(2.15), re-derived in `analytic/DERIVATION.md`; full contact from Appendix B (Menga,
Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014).

Units, stated once: lengths in 1/k (k = 2π/λ), pressures in E0/(1 − ν²), times in τ.  The inputs
are the dimensionless groups: load p̃∞ = p∞(1 − ν²)/E0, speed V/V0 = Vτk, ratio E∞/E0 and hk;
`ACCEPTED` lists the range of each and why; a nonzero speed must also be at least
`SPEED_MIN` (0 itself is the elastic limit).  `solve_si` is a thin SI front on top.

The subpackage `analytic.references` holds codes that are not the paper's road: the Fourier
reference (`fourier_solve`, re-exported here under its public name), the surface reference and
Persson's theory; it shares no code with this road (see its docstring).

This package never imports `bem` (the two roads are independent).
"""
from viscosine import Fields

from ._accepted import ACCEPTED, SPEED_MIN, validate
from ._result import Patch, Solution
from .dimensional import solve_si
from .full_contact import modulus, threshold_speed, transition_load
from .references import fourier_solve, layer_factor  # public names of analytic.references
from .solver import solve, sweep

__all__ = ["ACCEPTED", "Fields", "Patch", "SPEED_MIN", "Solution", "fourier_solve", "layer_factor",
           "modulus", "solve", "solve_si", "sweep", "threshold_speed", "transition_load",
           "validate"]
