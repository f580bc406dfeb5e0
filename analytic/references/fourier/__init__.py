"""An independent Fourier-collocation reference for any Prony-series material.

The problem is the one of the package (rigid sinusoid k y = hk cos(2πX), X = x/λ, crest at 0,
sliding at speed V toward +x over a linear viscoelastic half-plane in plane strain, frictionless,
steady state, described in the frame of the indenter), but the material is any linear solid given
by a Prony series, in creep or in relaxation form.  Nothing here comes from the BEM road or from
the semi-analytic closure: the operator is the compliance of each Fourier mode, the contact is a
complementarity problem on equispaced collocation points.

Units, stated once: lengths in 1/k (k = 2π/λ), positions X = x/λ; pressures in E_ref/(1 − ν²) and
compliances in (1 − ν²)/E_ref for any reference modulus E_ref (E0 for the standard linear solid);
times in any τ_ref (τ for the standard linear solid); speed w = V τ_ref k (V/V0 of the paper).

Material, either form (times τ_i, θ_i > 0, amplitudes ≥ 0):

    creep        J(t) = J0 − Σ J_i e^{−t/τ_i},   J(0+) = J0 − Σ J_i > 0,
    relaxation   E(t) = E_r + Σ E_i e^{−t/θ_i},   E_r > 0.

Transform convention.  σ(X) = Σ_n σ̂_n e^{2πinX}; on the N points X_j = −½ + (j + φ)/N the
coefficients are σ̂_n = (1/N) Σ_j σ_j e^{−2πinX_j} (numpy's rfft over N, times the phase of the
shift φ, which cancels in every product below).  In the frame of the indenter the material
streams toward −x, so the displacement at X remembers the pressure at X + y, y > 0; mode n
(n ≠ 0) then displaces the surface by

    k v̂_n = (2/|n|) J*(n) σ̂_n,   J*(n) = J(0+) + Σ_i J_i/(1 − i n w τ_i),

with Im J*(n) > 0 for n > 0; the complex modulus with the same sign of i is

    E*(n) = E(0+) + ∫_0^∞ E′(s) e^{i n w s} ds = E_r + Σ_i E_i (−i n w θ_i)/(1 − i n w θ_i),

so that J*(n) E*(n) = 1 (for the standard linear solid, J0 = 1, J_1 = 1 − 1/ρ, τ_1 = 1 and
E_r = 1, E_1 = ρ − 1, θ_1 = 1/ρ give J* = (1 − inw/ρ)/(1 − inw) and E* = (1 − inw)/(1 − inw/ρ)).
In this convention arg E*(1) = −δ < 0 and the pressure leads the profile by the loss angle δ
(`analytic/full_contact.py` writes the conjugate, (1 + iw)/(1 + iw/ρ)).  Mode 0 of v is zero
(v from the mean line of the deformed surface).

Discrete problem on one grid (N points, shift φ): with C the circulant of the symbol above
(the trigonometric interpolant of the point values σ_j, Nyquist mode real),

    gap_j = (C σ)_j − y_j + s ≥ 0,   σ_j ≥ 0,   σ_j gap_j = 0,   mean σ = p̃  (or s given),

s the mean separation (Δ/h = 1 − s/hk).  It is solved by a primal-dual active set on the
restriction of C to the contact (a Toeplitz matrix for one patch: Levinson's recursion with
iterative refinement by FFT products, dense LU otherwise).  Friction, signed to be positive
when it resists (the paper's eq. 3.1 with the opposite sign), is the dissipation

    τ̃f = −(1/λ) ∫ σ ∂v/∂x dx = Σ_{n>0} 4 Im J*(n) |σ̂_n|².

C has no mode 0, so its restriction to a near-full contact is nearly singular; the solves use
C' = C + c0·(mean), c0 = 2 Re J*(1), which changes only the constant that s absorbs.

Accuracy.  The error of one grid oscillates with the position of the contact edges between the
points (at fixed N it changes sign, with an amplitude of order h², as the grid is shifted).
Each level N is therefore solved on M = `shifts` grids shifted by φ = 0, 1/M, …, (M − 1)/M of a
spacing and averaged (the trapezoidal rule over the period of the shift), which removes most of
it; the levels are then combined by Richardson's extrapolation where their differences show a
consistent order, and otherwise the finest level is reported.  Contact edges are located to
sub-grid accuracy by a least-squares fit, with the edge a free parameter, of the gap outside the
contact (accurate to O(h²) away from the edge, unlike the point values of σ, which carry a
sawtooth next to it) to the form the edge imposes: Σ_k b_k d^{k+3/2} at the leading edge and,
at the trailing edge, the creep operator applied to it, J(0+) d^p + Σ_i J_i L_i^p Φ_p(d/L_i)
(the recovery of the surface behind the contact over the creep lengths L_i = w τ_i/(2π)).
Memory layers shorter than a few points of the finest grid are not resolved
(`memory_resolution`): such points are refused unless asked for.

A layer of thickness d on a rigid foundation (``layer={"thickness": k d, "foundation": ...,
"nu": ν}``) replaces the half-space: only E depends on the frequency, so mode n of C becomes

    k v̂_n = (2/|n|) S(|n| k d, ν) J*(n) σ̂_n,

S the layer factor of `analytic.references._layer` (solved there from Navier's equations),
and the dissipation weighs mode n by S as well.  Δ/h keeps its meaning (from the mean line of the
deformed surface); the uniform mode, finite on a layer, gives the mean displacement
k v̄_0 = C (k d) J0 p̃ (relaxed J0: the mean pressure is static) and the approach of the
indenter from the undeformed top face, Δ/h + v̄_0/h.  d is a length of the solution (the
pressure varies over d at the edges of a thin layer's contact) that the grids must resolve
like a memory layer (`thickness_resolution`).

Where each job lives: `_material` (the Prony series, J*(n) and E*(n) at the mode frequencies),
`_closed_form` (full contact, Appendix B), `_grid` (the operator and the active-set solve on one
grid), `_measure` (the scalars and the edges of one grid), `_levels` (shifted grids averaged,
Richardson's extrapolation), `_result` (`FourierResult` and its assembly), `_solve`
(`fourier_solve`: inputs, resolution, the levels); the layer factor is `analytic.references._layer`.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014: eqs (2.2)–(2.5) (the
steady-sliding displacement), (3.1) (friction), Appendix A (the elastic limits) and Appendix B
(full contact).  The layer: Menga, Afferrante & Carbone, J. Mech. Phys. Solids 95 (2016)
517–529.
"""
from ._closed_form import full_contact
from ._levels import richardson
from ._material import Material, complex_compliance, complex_modulus, material
from ._result import FourierResult
from ._solve import (MAX_NODES, MIN_LAYER_POINTS, MIN_NODES, MIN_THICKNESS_POINTS, NODES, SHIFTS,
                     fourier_solve, memory_resolution, thickness_resolution)

__all__ = ["FourierResult", "MAX_NODES", "MIN_LAYER_POINTS", "MIN_NODES", "MIN_THICKNESS_POINTS",
           "Material", "NODES", "SHIFTS", "complex_compliance", "complex_modulus", "fourier_solve",
           "full_contact", "material", "memory_resolution", "richardson", "thickness_resolution"]

