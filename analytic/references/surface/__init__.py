"""An independent reference for the steady sliding of a rigid periodic surface (3D contact).

A rigid surface with heights z(x, y) (positive toward the body: the highest point is the deepest
point of the indenter), periodic on a cell Lx × Ly (``aspect`` = Ly/Lx), slides at speed V in the
direction ê = (cos θ, sin θ) (θ = ``direction`` in degrees from +x, counter-clockwise) over a
linear viscoelastic half-space; frictionless, adhesionless, steady.  Everything is described in
the frame of the surface, where the material streams toward −V.  Nothing here comes from the
BEM road: the operator is the compliance of each Fourier mode, the contact a monotone
complementarity problem solved by operator splitting, the measurements and the error estimate
are this module's own.

Units, stated once: lengths over Lx for positions, 1/k for heights, displacements and gaps
(k = 2π/Lx; heights are given as k·z), wave vectors in k; pressures in E0/(1 − ν²) (E0 the
relaxed modulus; E_ref for a general series); times in τ (the creep time; τ_ref); speed
w = V τ k (V/V0 of the line contact).  Material: a Prony creep function
J(t) = J0 − Σ J_i e^{−t/τ_i}, J(0+) = J0 − Σ J_i > 0 (the standard linear solid of ratio
ρ = E∞/E0: J0 = 1, J_1 = 1 − 1/ρ, τ_1 = 1).

The operator (eq. 2.5 of the paper, generalised to a surface).  The elastic half-space displaces
its surface by k u_q = (2/|q|) J σ_q under the mode σ_q e^{i q·kX} (Boussinesq's 1/r kernel has
the transform 2π/|q| in two dimensions, as the plane-strain line has 2/|n|: the same symbol).
In the frame of the material the surface, and every mode of the pressure that moves with it,
passes at V ê: the mode at a material point reads σ_q e^{i q·k(x − V ê t)}, a harmonic load
e^{−iΩt} of the signed frequency Ω = (q·ê) k V.  Its steady response is the creep function's
transform J*(Ω τ) = J(0+) + ∫_0^∞ J′(s) e^{iΩs} ds, so

    k u_q = Ĉ(q) σ_q,   Ĉ(q) = (2/|q|) J*(q·ê),   J*(n) = J(0+) + Σ_i J_i/(1 − i n w τ_i),

J* taken at the signed variable n = q·ê (Im J* > 0 for n > 0: the pressure leads).  For a
surface uniform in y (q = (m, 0)) sliding along x this is the line contact's k v_m =
(2/|m|) J*(m) σ_m exactly; at an angle θ it is the line contact at the speed w cos θ.  Modes
across the sliding (q·ê = 0) are static and keep the relaxed J0 at every speed, so the limit
V → ∞ is the elastic contact with J(0+) only for a surface none of whose modes q ≠ 0 is
perpendicular to ê (a surface uniform in y sliding along x; the bi-sinusoid at 30°), not for the
bi-sinusoid sliding along x, whose cos(ky) family stays relaxed.

A layer of thickness d on a rigid foundation (``layer={"thickness": k d}`` or
``{"thickness_over_wavelength": d/Lx}``, with ``"foundation"`` and ``"nu"``) replaces the
half-space: only E depends on the frequency and mode q is a plane-strain mode along q, so its
symbol is the half-space's times the line's layer factor, Ĉ(q) S(|q| k d, ν) (S from Navier's
equations in `analytic.references._layer`, shared with the Fourier reference; 1 exactly from
|q| k d = 25 on).
Nothing else changes (the dissipation form weighs each mode by its symbol, full contact is
σ̂_q = ẑ_q/(Ĉ(q) S)); the uniform mode, finite on a layer, gives the mean compression
k v̄0 = C (k d) J0 p̃ (relaxed J0: the mean pressure is static; C = (1 − 2ν)/(1 − ν)² bonded,
1 frictionless) and the approach Δ/h_ref + v̄0/h_ref (docs/layers.md §4, §7).

Transform convention.  On the grid of nx × ny panel centres x_i = i/nx − ½,
y_j = (j/ny − ½)·aspect (the crest of the bi-sinusoid at i = nx/2, j = ny/2), point values
f_ij have the coefficients f̂(m, n) = (1/(nx ny)) Σ f_ij e^{−2πi(m x_i + n y_j/aspect)}, wave
vector q = (m, n/aspect) (numpy's rfft2 over the axes (x, y), the phase of the offset ½
cancelling in every product below).  The discrete operator is the symbol on the trigonometric
interpolant of the point values; on a Nyquist row or column (m = −nx/2, n = ny/2 for even
sizes) the interpolant is the average of the two aliases, so the symbol there is the average
of Ĉ over them (which keeps Ĉ(−q) = conj Ĉ(q) on the grid, so a real pressure gives a real
displacement).  Mode 0 of the displacement is zero (u from the mean plane of the deformed
surface).

The contact problem.  With z̃ = z − mean z, s the mean separation (the mean gap),

    gap = s − z̃ + u ≥ 0,   σ ≥ 0,   σ·gap = 0,   mean σ = p̃ (load control) or s given,

the penetration Δ/h_ref = 1 − s/h_ref, h_ref = max z − mean z.  Under load control it is the
variational inequality: σ in K = {σ ≥ 0, mean σ = p̃} with (Cσ − z̃)·(τ − σ) ≥ 0 for every τ in
K (s is the multiplier of the mean); under penetration control K = {σ ≥ 0} and Cσ − z̃ + s.
C is not symmetric (Im Ĉ is odd in q·ê), so the problem is no minimisation and the usual
conjugate-gradient contact solvers do not apply; but its symmetric part, the symbol Re Ĉ =
(2/|q|) Re J* > 0 (each term J_i/(1 + n²w²τ_i²) ≥ 0, J(0+) > 0), is positive semi-definite
(zero on mode 0 only, which K fixes), so A(σ) = Cσ − z̃ is a monotone affine operator.

Algorithm: Douglas–Rachford splitting (Lions & Mercier 1979) of 0 ∈ A(σ) + N_K(σ),

    σ_k = P_K(y_k),   r_k = (I + γA)^{−1}(2σ_k − y_k),   y_{k+1} = y_k + r_k − σ_k,

which converges for every γ > 0 whenever A and N_K are maximal monotone, symmetric or not
(Eckstein & Bertsekas 1992): its map T is firmly non-expansive.  Both steps are explicit here:
the resolvent is diagonal in Fourier space, r̂_q = (v̂_q + γ ẑ_q)/(1 + γ Ĉ(q)) (|1 + γĈ| ≥ 1
since Re Ĉ ≥ 0), two FFTs; the projection on K is max(y − t, 0) with t the root of
mean(max(y − t, 0)) = p̃ (Newton on a convex piecewise-linear function, a few passes), and at
the fixed point t = γ s.  γ = 1/√(max|Ĉ| min|Ĉ|), the geometric mean of the operator's
scales, balances the rates of the smooth and the stiff modes.  The iteration is accelerated
by Anderson's mixing (type II, memory `_MEMORY`) with the safeguard of Zhang, O'Donoghue &
Boyd (2020): a mixed step is kept only if its residual ‖T y − y‖ is below a summable sequence,
else the plain step is taken, so the global convergence of the plain iteration is kept.  It
stops when ‖T y − y‖∞ ≤ tol·max σ; the complementarity of the final (σ, s) is measured
directly (``diagnostics["complementarity"]``).  Each finer grid starts from the coarser one's
pressure and gap, interpolated.

Measurements on each grid:

* friction: the dissipation form τf = −mean(σ ∂u/∂ê) = Σ_q (q·ê) Im Ĉ(q)|σ̂_q|² (Parseval;
  each term ≥ 0), and the lateral force mean(σ ∂u/∂ê⊥) = −Σ_q (q·ê⊥) Im Ĉ(q)|σ̂_q|²,
  ê⊥ = (−sin θ, cos θ); μ and μ_lateral are these over the load.  The direct form uses the
  surface instead: in the contact u = z̃ − s, so τf = −mean(σ ∂z/∂ê) with the spectral slope
  of the surface; it does not see the operator, and the two agree to the discretisation error
  (``diagnostics["mu_direct"]``).  Why the lateral force is positive for a surface uniform in y
  sliding at 0 < θ < 90°: the solid pushes on such a surface only across its ridges, along −x,
  with the line contact's force μ_line(w cos θ) p̃ (the line slides at the speed w cos θ); −x
  has the component −cos θ along ê (μ = cos θ μ_line, resisting) and +sin θ along ê⊥, to the
  left of V: μ_lateral = sin θ μ_line(w cos θ).
* contact area: the nodal fraction (points with σ > 0), which is off by a band of half a cell
  along the edge, and a refined estimate (reported): the edge is located below the grid by a
  local quadratic least-squares fit of gap^{2/3} (linear in the distance d from the edge: the
  gap opens like d^{3/2}) over the gap points of a 9 × 9 window that have no contact point in
  their 3 × 3 neighbourhood (next to the edge the discrete gap carries its largest error), and
  each cell of the edge band contributes the part of its rectangle on the contact side of the
  fitted surface's tangent line at the cell centre, in closed form; other cells count 0 or 1.
* max_pressure: the nodal maximum refined by the vertex of a quadratic fitted on its 3 × 3
  neighbourhood; n_patches: the contact points' connected components (four neighbours, the
  grid periodic).

Mesh refinement and error estimate: the levels N_1 < N_2 < N_3 … (panels along x; ny in
proportion to the aspect) are solved in turn.  Each level is two grids, the surface moved by
half a panel along both axes between them (`SHIFTS`), and its scalars are their average: the
error of one grid oscillates as the contact edges move between the points (on a straight edge
along the grid, measured on the line contact at N = 1024: ±4e-6 in μ as the shift goes round,
against 6e-8 for the average of the two), and the average removes most of it.  The levels'
averages are then combined by Richardson's extrapolation from the last three (`richardson`):
where their differences shrink at a consistent order the finest level's error is estimated
from it, else from the last differences; the estimate is never below the spread of the finest
level's two grids.  The contact conditions of each grid are met to the iteration's tolerance,
so the estimate is of the discretisation only.

The iteration's cost, measured on the bi-sinusoid hk = 1, p̃ = 0.3, V/V0 = 1 from a uniform
start: the plain map needs 242, 331, 458 steps at N = 64, 128, 256 (about √N more each time:
the operator's condition number grows like N), the mixed one 57, 69, 85 and 105 at 512; a
grid started from the coarser one 59, 73, 92, 112 at N = 128 … 1024.  A step is two FFTs of
the grid and a few passes over it.

Where each job lives: `_inputs` (accepted ranges, the creep series and J*, the grids, the layer),
`_surface` (the heights sampled on a grid, h_ref), `_operator` (the symbols on one grid),
`_splitting` (Douglas–Rachford with Anderson's mixing), `_measure` (the measurements of one
grid), `_levels` (one grid of a level; Richardson's extrapolation), `_result` (`SurfaceSolution`),
`_solve` (`solve`); the layer factor is `analytic.references._layer`.

References
----------
N. Menga, C. Putignano, G. Carbone & G. P. Demelio, Proc. R. Soc. A 470, 20140392 (2014),
eq. (2.5) (the steady-sliding Green's function whose symbol is Ĉ on the line) and eq. (3.1)
(friction).  P.-L. Lions & B. Mercier, SIAM J. Numer. Anal. 16, 964 (1979); J. Eckstein &
D. P. Bertsekas, Math. Program. 55, 293 (1992) (Douglas–Rachford splitting); J. Zhang,
B. O'Donoghue & S. Boyd, SIAM J. Optim. 30, 3170 (2020) (safeguarded Anderson acceleration).
"""
from ._inputs import (ACCEPTED, LAYER_KEYS, MAX_NODES, MIN_NODES, NODES, TOL,
                      complex_compliance)
from ._levels import richardson
from ._result import SCALAR_KEYS, SurfaceSolution
from ._solve import SHIFTS, solve

__all__ = ["ACCEPTED", "LAYER_KEYS", "MAX_NODES", "MIN_NODES", "NODES", "SCALAR_KEYS", "SHIFTS",
           "SurfaceSolution", "TOL", "complex_compliance", "richardson", "solve"]

