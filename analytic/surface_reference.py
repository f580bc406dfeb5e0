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
equations in `analytic._layer`, the Fourier reference's own; 1 exactly from |q| k d = 25 on).
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

References
----------
N. Menga, C. Putignano, G. Carbone & G. P. Demelio, Proc. R. Soc. A 470, 20140392 (2014),
eq. (2.5) (the steady-sliding Green's function whose symbol is Ĉ on the line) and eq. (3.1)
(friction).  P.-L. Lions & B. Mercier, SIAM J. Numer. Anal. 16, 964 (1979); J. Eckstein &
D. P. Bertsekas, Math. Program. 55, 293 (1992) (Douglas–Rachford splitting); J. Zhang,
B. O'Donoghue & S. Boyd, SIAM J. Optim. 30, 3170 (2020) (safeguarded Anderson acceleration).
"""
from __future__ import annotations

import math
import numbers
import time
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np
from scipy import fft as sfft
from scipy import ndimage
from scipy.optimize import brentq, minimize

from viscosine.checks import bad, check_reals, is_integer, real, series
from viscosine.protocol import plain

from ._layer import check_layer, layer_factor, uniform_compliance

_TWO_PI = 2.0 * math.pi

#: panels along x of the default grids (Richardson's extrapolation needs three)
NODES = (64, 128, 256)
#: the coarsest and the finest grid accepted, panels along x (the finest: 2048² points hold
#: ~10 arrays of 32 MiB in the iteration)
MIN_NODES, MAX_NODES = 8, 2048
#: default stopping tolerance of the iteration, relative to the peak pressure
TOL = 1e-10
#: Anderson's memory: 8 differences (measured on the bi-sinusoid at 256²: 5 → 111, 10 → 95
#: evaluations of the map; each kept difference costs two passes over the grid)
_MEMORY = 8
#: iterations of the map before a level is declared not converged
_MAX_ITERATIONS = 20000
#: the safeguard's bound on a mixed step's residual: D ‖g_0‖ (k + 1)^−(1+ε)
_SAFE_D, _SAFE_EPS = 1e6, 1e-6
#: a contact patch with fewer points than this on the finest grid is warned of
_MIN_PATCH_POINTS = 16

ACCEPTED = {
    "load": (1e-12, 1e12, "a mean pressure p̃ = p∞(1 − ν²)/E0 in [1e-12, 1e12] (over the cell)"),
    "penetration": (0.0, 1.0, "a penetration Δ/h_ref in (0, 1] (1: the smallest load of full "
                    "contact)"),
    "speed": (0.0, 1e30, "a speed V/V0 = V τ k equal to 0 (the relaxed elastic solid) or in "
              "[1e-30, 1e30]"),
    "direction": (-360.0, 360.0, "a sliding direction θ in degrees from +x, in [−360, 360]"),
    "aspect": (1.0 / 64.0, 64.0, "a cell aspect Ly/Lx in [1/64, 64]"),
    "ratio": (1.0, 1e4, "E∞/E0 in [1, 1e4] (1 is the elastic solid)"),
    "tol": (1e-14, 1e-4, "a stopping tolerance in [1e-14, 1e-4] (relative to the peak "
            "pressure)"),
}
_TESTS = {"penetration": lambda v: 0.0 < v <= 1.0,
          "speed": lambda v: v == 0.0 or 1e-30 <= v <= 1e30}


# --------------------------------------------------------------------------------------------
# Inputs: the material and the surface
# --------------------------------------------------------------------------------------------
def _material(ratio, material):
    """(J0, (J_i, ...), (τ_i, ...)) from at most one of ``ratio`` (default 3) and ``material``."""
    if material is None:
        r = 3.0 if ratio is None else check_reals(ACCEPTED, (("ratio", ratio),), {})["ratio"]
        return 1.0, (1.0 - 1.0 / r,), (1.0,)
    if ratio is not None:
        raise ValueError(f"ratio={ratio!r}, material={material!r} is not allowed: give at most "
                         "one of ratio and material")
    what = ("a creep series (J0, J, tau): J0 > 0, amplitudes J_i ≥ 0 and times tau_i > 0 of "
            "equal lengths, J(0+) = J0 − ΣJ_i > 0 (compliances in (1 − ν²)/E0, times in τ)")
    if isinstance(material, (str, bytes)) or not hasattr(material, "__len__") \
            or len(material) != 3:
        raise bad("material", material, what)
    j0, jj, tt = material
    j0 = real("material", j0, what, lambda v: v > 0.0)
    jj = series("material", jj, what, lambda v: v >= 0.0)
    tt = series("material", tt, what, lambda v: v > 0.0)
    if len(jj) != len(tt) or not j0 - math.fsum(jj) > 0.0:
        raise bad("material", material, what)
    return j0, jj, tt


def complex_compliance(n, speed, material):
    """J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i) at the signed frequency variable n = q·ê.

    Parameters
    ----------
    n : array_like
        q·ê, wave vector in k = 2π/Lx projected on the sliding direction.
    speed : float
        w = V τ k ≥ 0.
    material : (J0, J, tau)
        The creep series (compliances in (1 − ν²)/E0, times in τ).

    Returns
    -------
    ndarray of complex, in (1 − ν²)/E0.  Im J*(n) has the sign of n (the pressure leads).
    """
    j0, jj, tt = material
    n = np.asarray(n, dtype=float)
    out = np.full(n.shape, j0 - math.fsum(jj), dtype=complex)
    for a, t in zip(jj, tt):
        out += a / (1.0 - 1j * (n * (speed * t)))
    return out


class _Surface:
    """k·z as one of: a callable of (x/Lx, y/Lx), point values at the panel centres, harmonics.

    ``kind`` is "callable", "array" or "harmonics"; `sample` gives k z on a level's grid.
    """

    def __init__(self, heights, aspect):
        self.aspect = aspect
        what = ("a callable f(x, y) → k·z (x, y over Lx, arrays of one shape), a 2-D array of "
                "k·z at the panel centres x_i = i/nx − ½, y_j = (j/ny − ½)·aspect (nx, ny ≥ 2, "
                "finite, not flat), or a mapping {(m, n): c} of harmonics "
                "k·z = Σ Re[c e^{2πi(m x + n y/aspect)}] (integers m, n; complex c; not all "
                "zero)")
        self.what = what
        if callable(heights):
            self.kind, self.func = "callable", heights
            return
        if isinstance(heights, dict):
            modes = {}
            for key, c in heights.items():
                if not (isinstance(key, tuple) and len(key) == 2 and all(map(is_integer, key))
                        and isinstance(c, numbers.Complex) and not isinstance(c, bool)
                        and math.isfinite(abs(complex(c)))):
                    raise bad("heights", heights, what)
                m, n = int(key[0]), int(key[1])
                # (m, n) and (−m, −n) describe one real mode: fold onto one of them
                if (m, n) < (0, 0) and not (m == 0 and n == 0):
                    m, n, c = -m, -n, complex(c).conjugate()
                modes[(m, n)] = modes.get((m, n), 0.0) + complex(c)
            modes = {k: c for k, c in modes.items() if k != (0, 0) and c != 0.0}
            if not modes:
                raise bad("heights", heights, what)
            self.kind, self.modes = "harmonics", modes
            self.max_m = max(abs(m) for m, _ in modes)
            self.max_n = max(abs(n) for _, n in modes)
            return
        if isinstance(heights, (str, bytes)):
            raise bad("heights", heights, what)
        try:
            arr = np.asarray(heights)
        except (TypeError, ValueError):
            raise bad("heights", heights, what) from None
        if arr.ndim != 2 or arr.dtype.kind not in "iuf" or min(arr.shape) < 2 \
                or not np.all(np.isfinite(arr)) or np.ptp(arr) == 0.0:
            raise bad("heights", heights, what)
        self.kind, self.values = "array", arr.astype(float)

    def grid_for(self, nx):
        """(nx, ny) of the level with nx panels along x."""
        if self.kind == "array":
            nx0, ny0 = self.values.shape
            return nx, ny0 * nx // nx0
        return nx, max(2, 2 * int(round(0.5 * nx * self.aspect)))

    def check_nodes(self, levels):
        """Refuse grids on which this surface is not represented."""
        if self.kind == "array":
            nx0 = self.values.shape[0]
            if any(n % nx0 for n in levels):
                raise bad("nodes", list(levels), f"multiples of the array's {nx0} points along "
                          "x (each grid holds the array's interpolant)")
        if self.kind == "harmonics":
            n0 = levels[0]
            nx, ny = self.grid_for(n0)
            if 2 * self.max_m >= nx or 2 * self.max_n >= ny:
                raise bad("nodes", list(levels), f"grids whose Nyquist modes exceed the "
                          f"harmonics (|m| < nx/2, |n| < ny/2 with ny = nx·aspect rounded even): "
                          f"the coarsest has nx = {nx}, ny = {ny} for |m| ≤ {self.max_m}, "
                          f"|n| ≤ {self.max_n}")

    def sample(self, nx, ny, shift=0.0):
        """k z at the panel centres of the nx × ny grid (shape (nx, ny)), the surface moved by
        ``shift`` of a panel along both axes (z(x + shift/nx, y + shift·aspect/ny))."""
        x = (np.arange(nx) + shift) / nx - 0.5
        y = ((np.arange(ny) + shift) / ny - 0.5) * self.aspect
        if self.kind == "callable":
            xx, yy = np.meshgrid(x, y, indexing="ij")
            try:
                out = np.asarray(self.func(xx, yy), dtype=float)
            except Exception as exc:  # any failure of the user's function is a bad input
                raise bad("heights", self.func, self.what + f" (calling it raised {exc!r})") \
                    from None
            if out.shape == ():
                out = np.full((nx, ny), float(out))
            if out.shape != (nx, ny) or not np.all(np.isfinite(out)):
                raise bad("heights", self.func, self.what + f" (it returned shape {out.shape} "
                          f"or non-finite values for arrays of shape {(nx, ny)})")
            return out
        if self.kind == "harmonics":
            out = np.zeros((nx, ny))
            for (m, n), c in self.modes.items():
                ex = np.exp(1j * _TWO_PI * m * x)
                ey = np.exp(1j * _TWO_PI * n * y / self.aspect)
                out += (c * np.outer(ex, ey)).real
            return out
        return _interpolate(self.values, nx, ny, shift)

    def extent(self, fine):
        """k h_ref = max z − mean z, from the finest grid's samples ``fine``.

        The array's own samples define it; a callable's or the harmonics' maximum is polished
        from the best grid point by a local search (the crest may lie between points).
        """
        if self.kind == "array":
            return float(self.values.max() - self.values.mean())
        nx, ny = fine.shape
        i, j = np.unravel_index(np.argmax(fine), fine.shape)
        x0 = np.array([i / nx - 0.5, (j / ny - 0.5) * self.aspect])
        if self.kind == "harmonics":
            def neg(p):
                return -sum((c * np.exp(1j * _TWO_PI * (m * p[0] + n * p[1] / self.aspect))).real
                            for (m, n), c in self.modes.items())
        else:
            def neg(p):
                return -float(np.asarray(self.func(np.array([[p[0]]]), np.array([[p[1]]])),
                                         dtype=float).ravel()[0])
        step = np.array([1.0 / nx, self.aspect / ny])
        res = minimize(neg, x0, method="Nelder-Mead",
                       options={"xatol": 1e-12, "fatol": 1e-15, "maxiter": 2000,
                                "initial_simplex": [x0, x0 + [step[0], 0], x0 + [0, step[1]]]})
        top = max(float(fine.max()), -float(res.fun)) if np.isfinite(res.fun) else fine.max()
        if self.kind == "harmonics":
            return float(top)  # mean 0: mode (0, 0) is dropped
        return float(top - fine.mean())


def _interpolate(values, nx, ny, shift=0.0):
    """The trigonometric interpolant of ``values`` (panel centres) at the centres of nx × ny,
    moved by ``shift`` of a new panel along both axes.

    Zero padding of the spectrum, axis by axis; an even axis's Nyquist coefficient is split
    equally between +N/2 and −N/2 (the real interpolant of the cosine the samples hold); the
    shift is the phase e^{2πi m shift/N} of mode m.
    """
    out = values
    for axis, new in ((0, nx), (1, ny)):
        old = out.shape[axis]
        if new == old and shift == 0.0:
            continue
        # both grids start at −½: the phase (−1)^m of that offset is the same on both
        spec = np.fft.fft(out, axis=axis) / old
        pad = np.zeros(spec.shape[:axis] + (new,) + spec.shape[axis + 1:], dtype=complex)
        half = (old - 1) // 2
        sl = [slice(None)] * 2
        sl[axis] = slice(0, half + 1)
        pad[tuple(sl)] = spec[tuple(sl)]
        sl[axis] = slice(new - half, new)
        src = [slice(None)] * 2
        src[axis] = slice(old - half, old)
        if half:
            pad[tuple(sl)] = spec[tuple(src)]
        if old % 2 == 0:
            nyq = [slice(None)] * 2
            nyq[axis] = old // 2
            up, down = list(nyq), list(nyq)
            down[axis] = new - old // 2
            pad[tuple(up)] += 0.5 * spec[tuple(nyq)]
            pad[tuple(down)] += 0.5 * spec[tuple(nyq)]
        if shift != 0.0:
            phase = np.exp(1j * _TWO_PI * np.fft.fftfreq(new) * shift)
            pad *= phase.reshape((-1, 1) if axis == 0 else (1, -1))
        out = (np.fft.ifft(pad, axis=axis) * new).real
    return out


# --------------------------------------------------------------------------------------------
# The operator on one grid
# --------------------------------------------------------------------------------------------
class _Grid:
    """Wave vectors and the alias-averaged symbols of an nx × ny grid (rfft2 layout)."""

    def __init__(self, nx, ny, aspect, theta, speed, material, layer=None):
        self.nx, self.ny, self.aspect = nx, ny, aspect
        self.e = (math.cos(math.radians(theta)), math.sin(math.radians(theta)))
        self.speed, self.material = speed, material
        mx = np.fft.fftfreq(nx, 1.0 / nx)[:, None] * np.ones((1, ny // 2 + 1))
        ny_ = np.arange(ny // 2 + 1, dtype=float)[None, :] * np.ones((nx, 1))
        # the aliases of a Nyquist row (m = −nx/2 ~ +nx/2) or column (n = ny/2 ~ −ny/2)
        alt_m = np.where(np.abs(mx) * 2 == nx, -mx, mx) if nx % 2 == 0 else mx
        alt_n = np.where(ny_ * 2 == ny, -ny_, ny_) if ny % 2 == 0 else ny_
        self._pairs = [(a, b / aspect) for a in (mx, alt_m) for b in (ny_, alt_n)]
        # on a layer each alias's S(|q| k d, ν) (the half-space: None, its arithmetic unchanged)
        self._factors = [None] * 4 if layer is None else [
            layer_factor(np.hypot(qx, qy) * layer["thickness"], layer["nu"],
                         layer["foundation"]) for qx, qy in self._pairs]
        c = self.average(lambda qx, qy, f: self._compliance(qx, qy, f))
        self.symbol = c
        mag = np.abs(c)
        mag = mag[mag > 0.0]
        self.scales = (float(mag.min()), float(mag.max()))
        e, p = self.e, (-self.e[1], self.e[0])
        # (q·ê) Im Ĉ and (q·ê⊥) Im Ĉ: the dissipation and the lateral force per |σ̂_q|²
        self.dissipation = self.average(
            lambda qx, qy, f: (qx * e[0] + qy * e[1]) * self._compliance(qx, qy, f).imag)
        self.lateral = self.average(
            lambda qx, qy, f: -(qx * p[0] + qy * p[1]) * self._compliance(qx, qy, f).imag)
        self.slope = self.average(lambda qx, qy, f: 1j * (qx * e[0] + qy * e[1]))
        self.slope_lateral = self.average(lambda qx, qy, f: 1j * (qx * p[0] + qy * p[1]))
        # rfft2 holds the columns n = 1 … ny/2 − 1 once for the pair ±q: weight 2 in sums
        w = np.full(c.shape, 2.0)
        w[:, 0] = 1.0
        if ny % 2 == 0:
            w[:, -1] = 1.0
        self.weight = w

    def average(self, f):
        """f(qx, qy, S) on the rfft2 layout, averaged over the aliases of the Nyquist rows and
        columns (S: the alias's layer factor, None on the half-space)."""
        vals = [f(qx, qy, s) for (qx, qy), s in zip(self._pairs, self._factors)]
        return 0.25 * (vals[0] + vals[1] + vals[2] + vals[3])

    def _compliance(self, qx, qy, factor=None):
        q = np.hypot(qx, qy)
        j = complex_compliance(qx * self.e[0] + qy * self.e[1], self.speed, self.material)
        out = np.zeros(q.shape, dtype=complex)
        nz = q > 0.0
        if factor is None:
            out[nz] = 2.0 * j[nz] / q[nz]
        else:                                   # a layer: the mode's factor S(|q| k d, ν)
            out[nz] = 2.0 * j[nz] * factor[nz] / q[nz]
        return out

    def rfft(self, f):
        return sfft.rfft2(f)

    def irfft(self, f):
        return sfft.irfft2(f, (self.nx, self.ny))

    def apply(self, sigma):
        """k u = C σ (mode 0 of u is 0)."""
        return self.irfft(self.symbol * self.rfft(sigma))

    def spectral_sum(self, weights, sigma):
        """Σ_q weights(q) |σ̂_q|² over the whole spectrum (σ̂ normalised by the points)."""
        sh = self.rfft(sigma) / (self.nx * self.ny)
        return float(np.sum(self.weight * weights * (sh.real ** 2 + sh.imag ** 2)))


# --------------------------------------------------------------------------------------------
# The contact problem on one grid: Douglas–Rachford splitting with Anderson's mixing
# --------------------------------------------------------------------------------------------
def _project(y, load, t):
    """max(y − t, 0) with t the root of mean(max(y − t, 0)) = load, from the guess t.

    f(t) = mean(max(y − t, 0)) − load is convex, decreasing and piecewise linear: Newton's
    method from the left of the root stays there and ends on its linear piece exactly; from
    the right its first step lands on the left.
    """
    n = y.size
    for _ in range(200):
        above = y > t
        count = int(np.count_nonzero(above))
        if count == 0:          # nothing above t: the step that puts the peak alone in contact
            t = float(y.max()) - load * n
            continue
        excess = float(np.sum(y[above] - t)) / n - load
        step = excess * n / count
        t_new = t + step
        if abs(step) <= 4e-16 * max(abs(t), abs(load)) or t_new == t:
            t = t_new
            break
        t = t_new
    return np.maximum(y - t, 0.0), t


def _norm(v):
    """‖v‖₂ by einsum (BLAS's threaded dot costs more than it saves on two shared cores)."""
    return math.sqrt(float(np.einsum("i,i->", v, v)))


def _anderson(T, y0, tol_of, memory=_MEMORY, max_iterations=_MAX_ITERATIONS):
    """A fixed point of T by Anderson's mixing (type II) with the safeguard of Zhang et al.

    ``T(y)`` returns (T y, aux); ``tol_of(aux)`` the bound on ‖T y − y‖∞ that stops.  Returns
    (y, aux, evaluations, mixed steps kept, converged).

    The differences are kept as rows and their Gram matrix updated by one row per step; the
    sums are NumPy's (einsum, not BLAS: reproducible, and no threads fighting for the cores).
    """
    shape = y0.shape
    n = y0.size
    dy = np.zeros((memory, n))
    dg = np.zeros((memory, n))
    gram = np.zeros((memory, memory))
    ty, aux = T(y0)
    evals = 1
    y = y0.ravel().copy()
    g = ty.ravel() - y
    g0 = _norm(g)
    kept, count, head = 0, 0, 0
    while evals < max_iterations:
        if float(np.max(np.abs(g))) <= tol_of(aux):
            return y.reshape(shape), aux, evals, kept, True
        k = min(count, memory)
        if k:
            b = np.einsum("ij,j->i", dg[:k], g)
            gm = gram[:k, :k]
            ridge = 1e-12 * max(np.trace(gm) / k, 1e-300)
            try:
                gam = np.linalg.solve(gm + ridge * np.eye(k), b)
            except np.linalg.LinAlgError:
                gam = np.zeros(k)
            cand = y + g - np.einsum("i,ij->j", gam, dy[:k]) - np.einsum("i,ij->j", gam,
                                                                           dg[:k])
            tc, auxc = T(cand.reshape(shape))
            evals += 1
            gc = tc.ravel() - cand
            if _norm(gc) <= _SAFE_D * g0 * (kept + 1) ** (-1.0 - _SAFE_EPS):
                kept += 1
            else:                               # the plain step T y instead
                cand = y + g
                tc, auxc = T(cand.reshape(shape))
                evals += 1
                gc = tc.ravel() - cand
        else:
            cand = y + g
            tc, auxc = T(cand.reshape(shape))
            evals += 1
            gc = tc.ravel() - cand
        dy[head] = cand - y
        dg[head] = gc - g
        k = min(count + 1, memory)
        row = np.einsum("ij,j->i", dg[:k], dg[head])
        gram[head, :k] = row
        gram[:k, head] = row
        head = (head + 1) % memory
        count += 1
        y, g, aux = cand, gc, auxc
    return y.reshape(shape), aux, evals, kept, False


def _solve_level(grid, zt, control, value, start, tol):
    """The contact on one grid: σ, k u, k s, evaluations, mixed steps kept, converged.

    zt: k z̃ on the grid; value: p̃ (load) or k s (penetration); start: (σ, gap, s) of a
    coarser grid interpolated here, or None.
    """
    gamma = 1.0 / math.sqrt(grid.scales[0] * grid.scales[1])
    resolvent = 1.0 / (1.0 + gamma * grid.symbol)
    zh = gamma * grid.rfft(zt)
    npts = grid.nx * grid.ny
    if control == "penetration":
        zh[0, 0] -= gamma * value * npts      # the constant s of A(σ) = Cσ − z̃ + s
    state = {"t": 0.0}

    def T(y):
        if control == "load":
            sigma, state["t"] = _project(y, value, state["t"])
        else:
            sigma = np.maximum(y, 0.0)
        r = grid.irfft(resolvent * (grid.rfft(2.0 * sigma - y) + zh))
        return y + r - sigma, sigma

    if start is None:
        y0 = np.full((grid.nx, grid.ny), value if control == "load" else 0.0)
        if control == "penetration":
            y0 = gamma * np.maximum(zt - value, 0.0)   # the rigid overlap, pressed
    else:
        s0, g0, sep0 = start
        if control == "load":
            y0 = s0 - gamma * (g0 - sep0)
            state["t"] = gamma * sep0
        else:
            y0 = s0 - gamma * g0
    y, sigma, evals, kept, ok = _anderson(T, y0, lambda sig: tol * max(float(sig.max()),
                                                                          1e-300))
    if control == "load":
        sigma, t = _project(y, value, state["t"])
        s = t / gamma
    else:
        sigma = np.maximum(y, 0.0)
        s = value
    return sigma, grid.apply(sigma), s, evals, kept, ok


# --------------------------------------------------------------------------------------------
# Measurements on one grid
# --------------------------------------------------------------------------------------------
#: the fit window's half-width (points) and the quadratic's smallest number of points
_WINDOW = 4
_MIN_FIT = 9


def _square_fraction(a, b, d):
    """Area of {a u + b v ≤ d} in the unit square (arrays; a, b, d of one shape)."""
    d = d - np.where(a < 0.0, a, 0.0) - np.where(b < 0.0, b, 0.0)   # reflect u → 1 − u
    a, b = np.abs(a), np.abs(b)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    out = np.empty(a.shape)
    thin = lo <= 1e-7 * hi      # a line along a side: the mean of its clipped position
    with np.errstate(divide="ignore", invalid="ignore"):
        out[thin] = np.clip((d[thin] - 0.5 * lo[thin]) / hi[thin], 0.0, 1.0)
        F = lambda t: 0.5 * np.maximum(t, 0.0) ** 2
        w = ~thin
        aw, bw, dw = a[w], b[w], d[w]
        out[w] = (F(dw) - F(dw - aw) - F(dw - bw) + F(dw - aw - bw)) / (aw * bw)
    return np.clip(out, 0.0, 1.0)


def _contact_area(contact, gap, rho):
    """(refined area fraction, points of the edge band, points fitted) of one grid.

    rho = hy/hx, the panel's aspect; positions in units of hx.  See the module docstring.
    """
    nx, ny = contact.shape
    near = ndimage.maximum_filter(contact, size=3, mode="wrap")
    inner = ndimage.minimum_filter(contact, size=3, mode="wrap")
    band = near & ~inner
    far_gap = ~near
    frac = contact.astype(float)
    bi, bj = np.nonzero(band)
    if bi.size == 0:
        return float(frac.mean()), 0, 0
    r = np.arange(-_WINDOW, _WINDOW + 1)
    di, dj = np.meshgrid(r, r, indexing="ij")
    di, dj = di.ravel(), dj.ravel()
    ii = (bi[:, None] + di[None, :]) % nx
    jj = (bj[:, None] + dj[None, :]) % ny
    use = far_gap[ii, jj]
    phi = np.where(use, np.maximum(gap[ii, jj], 0.0), 0.0) ** (2.0 / 3.0)
    X, Y = di.astype(float), dj * rho
    basis = np.stack([np.ones_like(X), X, Y, X * X, X * Y, Y * Y], axis=1)   # (81, 6)
    wgt = use.astype(float)
    count = wgt.sum(axis=1)
    fitted = np.zeros(bi.size, dtype=bool)
    coef = np.zeros((bi.size, 3))
    for ncols, enough in ((6, count >= _MIN_FIT), (3, (count >= 4) & (count < _MIN_FIT))):
        if not np.any(enough):
            continue
        A = basis[:, :ncols]
        w = wgt[enough]
        ata = np.einsum("bk,ki,kj->bij", w, A, A)
        atb = np.einsum("bk,ki,bk->bi", w, A, phi[enough])
        # a singular window (points on a line) keeps the nodal value
        cond = np.linalg.cond(ata)
        good = np.isfinite(cond) & (cond < 1e10)
        sol = np.zeros((ata.shape[0], ncols))
        if np.any(good):
            sol[good] = np.linalg.solve(ata[good], atb[good][..., None])[..., 0]
        idx = np.flatnonzero(enough)[good]
        coef[idx] = sol[good][:, :3]
        fitted[idx] = True
    a0, a1, a2 = coef[:, 0], coef[:, 1], coef[:, 2]
    ok = fitted & ((a1 != 0.0) | (a2 != 0.0))
    # the cell [−½, ½] × [−ρ/2, ρ/2] as the unit square: u = X + ½, v = Y/ρ + ½
    part = _square_fraction(a1[ok], a2[ok] * rho, -(a0[ok] - 0.5 * a1[ok] - 0.5 * a2[ok] * rho))
    frac[bi[ok], bj[ok]] = part
    return float(frac.mean()), int(bi.size), int(np.count_nonzero(ok))


def _patches(contact):
    """(number of patches, points of the smallest): four-neighbour components, periodic."""
    labels, count = ndimage.label(contact)
    if count == 0:
        return 0, 0
    parent = list(range(count + 1))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in ((labels[:, -1], labels[:, 0]), (labels[-1, :], labels[0, :])):
        for p, q in zip(a[(a > 0) & (b > 0)], b[(a > 0) & (b > 0)]):
            rp, rq = root(int(p)), root(int(q))
            if rp != rq:
                parent[max(rp, rq)] = min(rp, rq)
    roots = np.array([root(i) for i in range(count + 1)])
    sizes = np.bincount(roots[labels[contact]], minlength=count + 1)
    sizes = sizes[sizes > 0]
    return int(sizes.size), int(sizes.min())


def _peak(sigma, rho):
    """The peak of σ: the nodal maximum, polished by the vertex of the quadratic fitted on its
    3 × 3 neighbourhood when that vertex is a maximum within one spacing."""
    nx, ny = sigma.shape
    i, j = np.unravel_index(np.argmax(sigma), sigma.shape)
    top = float(sigma[i, j])
    r = np.array([-1, 0, 1])
    di, dj = np.meshgrid(r, r, indexing="ij")
    vals = sigma[(i + di) % nx, (j + dj) % ny].ravel()
    X, Y = di.ravel().astype(float), dj.ravel() * rho
    A = np.stack([np.ones(9), X, Y, X * X, X * Y, Y * Y], axis=1)
    c = np.linalg.lstsq(A, vals, rcond=None)[0]
    hess = np.array([[2.0 * c[3], c[4]], [c[4], 2.0 * c[5]]])
    if np.all(np.linalg.eigvalsh(hess) < 0.0):
        v = np.linalg.solve(hess, -c[1:3])
        if abs(v[0]) <= 1.0 and abs(v[1]) <= rho:
            return max(top, float(c[0] + c[1] * v[0] + c[2] * v[1] + c[3] * v[0] ** 2
                                  + c[4] * v[0] * v[1] + c[5] * v[1] ** 2))
    return top


def _lowest(f):
    """The minimum of the trigonometric interpolant of the grid values f (at the threshold of
    full contact the load is minus the lowest oscillating pressure, which may fall between the
    points): Nelder–Mead from the lowest point, on the interpolant evaluated exactly."""
    nx, ny = f.shape
    spec = np.fft.fft2(f) / f.size
    mx, my = np.fft.fftfreq(nx, 1.0 / nx), np.fft.fftfreq(ny, 1.0 / ny)

    def basis(m, n, a):
        out = np.exp(2j * math.pi * m * a / n)
        if n % 2 == 0:
            out[n // 2] = math.cos(math.pi * a)   # the Nyquist mode as the cosine it holds
        return out

    value = lambda p: float((basis(mx, nx, p[0]) @ spec @ basis(my, ny, p[1])).real)
    i, j = np.unravel_index(np.argmin(f), f.shape)
    x0 = np.array([i, j], dtype=float)
    res = minimize(value, x0, method="Nelder-Mead",
                   options={"xatol": 1e-10, "fatol": 1e-16, "maxiter": 1000,
                            "initial_simplex": [x0, x0 + [0.5, 0.0], x0 + [0.0, 0.5]]})
    return min(float(f[i, j]), float(res.fun))


def _level_scalars(grid, sigma, gap, s, zk, h_ref, full):
    """The scalars and diagnostics of one solved grid (zk: k z on it; full: in full contact,
    where σ may touch 0 at a point, at the threshold)."""
    load = float(np.mean(sigma))
    tau = grid.spectral_sum(grid.dissipation, sigma)
    lat = grid.spectral_sum(grid.lateral, sigma)
    zh = grid.rfft(zk)
    slope = grid.irfft(grid.slope * zh)
    slope_lat = grid.irfft(grid.slope_lateral * zh)
    contact = np.full(sigma.shape, True) if full else sigma > 0.0
    rho = (grid.aspect / grid.ny) * grid.nx
    area, band, fitted = _contact_area(contact, gap, rho)
    n_patches, smallest = _patches(contact)
    scale = max(float(sigma.max()), 1e-300)
    return {
        "load": load,
        "penetration": 1.0 - s / h_ref,
        "tau_f": tau,
        "mu": tau / load if load > 0.0 else math.nan,
        "mu_lateral": lat / load if load > 0.0 else math.nan,
        "contact_fraction": 1.0 if contact.all() else area,
        "max_pressure": _peak(sigma, rho),
        "n_patches": n_patches,
        "full_contact": bool(contact.all()),
        "smallest_patch_points": smallest,
        "contact_fraction_nodal": float(np.mean(contact)),
        "mu_direct": -float(np.mean(sigma * slope)) / load if load > 0.0 else math.nan,
        "mu_lateral_direct": float(np.mean(sigma * slope_lat)) / load if load > 0.0
        else math.nan,
        "edge_points": band,
        "edge_points_fitted": fitted,
        "complementarity": max(float(np.max(np.abs(gap[contact]), initial=0.0)) / h_ref,
                               float(-gap.min()) / h_ref, float(-sigma.min()) / scale, 0.0),
    }


# --------------------------------------------------------------------------------------------
# Mesh refinement: Richardson's extrapolation and the error estimate
# --------------------------------------------------------------------------------------------
def _order(n1, n2, n3, d1, d2):
    """The order p with d1/d2 = (n1^−p − n2^−p)/(n2^−p − n3^−p) (NaN if none in [0.1, 10])."""
    ratio = d1 / d2
    if not ratio > 1.0:
        return math.nan
    f = lambda p: (n1 ** -p - n2 ** -p) / (n2 ** -p - n3 ** -p) - ratio
    try:
        return brentq(f, 0.1, 10.0, xtol=1e-12)
    except ValueError:
        return math.nan


def richardson(nodes, values):
    """Richardson's extrapolation from the last three grids, with its observed order.

    Parameters
    ----------
    nodes : sequence of int
        Panels along x of the grids, increasing.
    values : sequence of float
        One scalar on each grid.

    Returns
    -------
    value, estimate, order, extrapolated : float, float, float, bool
        With the differences d1, d2 of the last three grids of one sign and shrinking, the
        order p they show (`_order`; for grids doubling, log2(d1/d2)) in [0.5, 8] gives the
        finest grid's error c N3^−p = d2 N3^−p/(N2^−p − N3^−p), which is the estimate.  The
        extrapolated value (finest + that correction) is returned only when four grids or more
        show orders within 0.5 of each other over their last two triples; its estimate is then
        the larger of the correction and the change from the extrapolation one grid coarser.
        Otherwise (errors that change sign as an edge moves across the points, or a pre-
        asymptotic start) the finest value is returned with the larger of |d2| and
        |d1| (N2/N3) (what a first-order error of d1 leaves on the finest grid) as its
        estimate.  Two grids: the finest value and |d2|; one: NaN.
    """
    q = [float(v) for v in values]
    ns = [float(v) for v in nodes]
    if len(q) < 2:
        return q[-1], math.nan, math.nan, False
    d2 = q[-1] - q[-2]
    if len(q) < 3:
        return q[-1], abs(d2), math.nan, False
    plain_estimate = max(abs(d2), abs(q[-2] - q[-3]) * ns[-2] / ns[-1])
    if not all(math.isfinite(v) for v in q[-3:]):
        return q[-1], math.nan, math.nan, False
    if q[-1] == q[-2] == q[-3]:
        return q[-1], 0.0, math.nan, False

    def triple(k):
        n1, n2, n3 = ns[k - 3:k]
        a, b = q[k - 2] - q[k - 3], q[k - 1] - q[k - 2]
        if b == 0.0:
            return math.nan, math.nan
        p = _order(n1, n2, n3, a, b)
        if not 0.5 <= p <= 8.0:
            return p, math.nan
        return p, b * n3 ** -p / (n2 ** -p - n3 ** -p)

    order, corr = triple(len(q))
    if not math.isfinite(corr):
        return q[-1], plain_estimate, order, False
    if len(q) >= 4:
        order0, corr0 = triple(len(q) - 1)
        if math.isfinite(corr0) and abs(order - order0) <= 0.5:
            value = q[-1] + corr
            return value, max(abs(corr), abs(value - (q[-2] + corr0))), order, True
    return q[-1], abs(corr), order, False


# --------------------------------------------------------------------------------------------
# The result and the solver
# --------------------------------------------------------------------------------------------
#: the scalars of the surface conventions, in their order
SCALAR_KEYS = ("penetration", "mu", "mu_lateral", "contact_fraction", "n_patches",
               "max_pressure")
#: scalars combined over the grids: relative estimates, then absolute ones
_RELATIVE = ("load", "penetration", "tau_f", "mu", "max_pressure")
_ABSOLUTE = ("mu_lateral", "contact_fraction")
#: diagnostics averaged over a level's grids like the scalars
_DIAGNOSTIC = ("mu_direct", "mu_lateral_direct", "contact_fraction_nodal")
#: every level is solved on two grids, the surface moved by these fractions of a panel along
#: both axes, and averaged
SHIFTS = (0.0, 0.5)
#: added to every estimate (relative or absolute, as the estimate): what the grid differences
#: cannot see, the rounding of the iteration's stop
_FLOOR = 1e-13


@dataclass(frozen=True)
class SurfaceSolution:
    """One operating point of the surface reference (a SciPy-like result object).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (every grid converged, the scalars finite, a contact), 0 or
        1, what the solver says, caveats (tuple of str).
    control, asked
        ``"load"`` or ``"penetration"`` and the value asked for.
    load, speed, direction, aspect, material
        p̃ (E0/(1 − ν²); an output under penetration control), w = V τ k, θ in degrees,
        Ly/Lx, and the creep series as ``{"J0", "J", "tau"}``.
    h_ref
        k h_ref = k (max z − mean z).
    full_contact, contact_fraction, penetration, separation, tau_f, mu, mu_lateral,
    n_patches, max_pressure
        The scalars of the surface conventions: contact area over the cell's (refined), Δ/h_ref,
        s/h_ref = 1 − Δ/h_ref, τf(1 − ν²)/E0 (positive when it resists), τf/p̃, the lateral
        force along (−sin θ, cos θ) over the load, the patches (four-neighbour, periodic) and
        the peak σ(1 − ν²)/E0, all from the finest grid or extrapolated (see
        ``extrapolated``).
    error_estimate : dict
        Per scalar: relative for load, penetration, tau_f, mu, max_pressure; absolute for
        mu_lateral, contact_fraction; None for n_patches (an integer: ``warnings`` say when
        the grids disagree).  See `richardson`.
    observed_order, extrapolated : dict
        Per scalar: the order of the last three grids and whether the value is extrapolated.
    nodes : int
        Panels along x of the finest grid.
    grids : tuple of (int, int)
        (nx, ny) of every grid, coarse to fine.
    levels : tuple of dict
        Per level: ``nodes``, ``ny``, ``scalars`` (the average of its two grids, with the
        nodal contact fraction, the direct friction forms and the worse complementarity),
        ``shifted`` (each grid's own scalars, the surface moved by `SHIFTS` of a panel),
        ``evaluations`` of the iteration's map, ``mixed`` (Anderson steps kept), ``seconds``.
    diagnostics : dict
        The finest level's ``mu_direct``, ``mu_lateral_direct`` (the friction from the
        surface's slope), ``contact_fraction_nodal`` and ``complementarity`` (the worst of
        |gap| in the contact and −gap over h_ref, −σ over max σ).
    x, y, pressure, gap, displacement : ndarray
        The finest level's unshifted grid: panel centres (over Lx), σ(1 − ν²)/E0 of shape
        (len(x), len(y)), gap/h_ref and (u − mean u)/h_ref.
    elapsed : float
        Wall time, seconds.
    layer : dict or None
        None on the half-space; on a layer its description: ``thickness`` (k d),
        ``thickness_over_wavelength`` (d/Lx), ``foundation``, ``nu``, ``uniform_compliance``
        (C of the uniform mode).
    mean_displacement, approach : float or None
        On a layer (None on the half-space): v̄0/h_ref, the layer's uniform compression under
        the mean pressure (k v̄0 = C (k d) J0 p̃, J0 the relaxed compliance), and Δ/h_ref +
        v̄0/h_ref, the crest's approach from the undeformed top face (the BEM's
        ``diagnostics["layer"]``; also in ``diagnostics["layer"]`` here).  Their relative
        estimates are in ``error_estimate``.
    """

    success: bool
    status: int
    message: str
    control: str
    asked: float
    load: float
    speed: float
    direction: float
    aspect: float
    material: dict
    h_ref: float
    full_contact: bool
    contact_fraction: float
    penetration: float
    separation: float
    tau_f: float
    mu: float
    mu_lateral: float
    n_patches: int
    max_pressure: float
    error_estimate: dict
    observed_order: dict
    extrapolated: dict
    nodes: int
    grids: tuple
    levels: tuple = field(repr=False)
    diagnostics: dict = field(repr=False)
    x: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    elapsed: float = 0.0
    warnings: tuple = ()
    layer: dict | None = None
    mean_displacement: float | None = None
    approach: float | None = None

    def scalars(self):
        """The six scalars of the surface conventions, as a dict."""
        return {k: getattr(self, k) for k in SCALAR_KEYS}

    def as_dict(self):
        """Everything but the fields, as plain Python values (non-finite floats as None)."""
        out = {"solver": "surface_reference", "success": self.success, "status": self.status,
               "message": self.message, "warnings": list(self.warnings),
               "control": self.control, "asked": self.asked, "load": self.load,
               "speed": self.speed, "direction": self.direction, "aspect": self.aspect,
               "material": self.material, "h_ref": self.h_ref,
               "full_contact": self.full_contact, "separation": self.separation,
               "tau_f": self.tau_f}
        out.update(self.scalars())
        out.update({"error_estimate": self.error_estimate,
                    "observed_order": self.observed_order, "extrapolated": self.extrapolated,
                    "nodes": self.nodes, "grids": self.grids, "levels": self.levels,
                    "diagnostics": self.diagnostics, "elapsed": self.elapsed})
        if self.layer is not None:  # the half-space's record is unchanged
            out.update({"layer": self.layer, "mean_displacement": self.mean_displacement,
                        "approach": self.approach})
        return plain(out)


def _check_nodes(nodes, surf):
    """The grids (panels along x), increasing; a single N gives N/4, N/2, N."""
    allowed = (f"an even number of panels along x in [{MIN_NODES}, {MAX_NODES}], or an "
               "increasing sequence of them (three or more for Richardson's extrapolation); "
               "one N solves N/4, N/2 and N")
    if nodes is None:
        if surf.kind == "array":
            nx0 = surf.values.shape[0]
            if nx0 > MAX_NODES:
                raise bad("heights", surf.values.shape, f"an array of at most {MAX_NODES} "
                          "points along x")
            seq = [nx0 * f for f in (1, 2, 4) if nx0 * f <= MAX_NODES]
        else:
            seq = list(NODES)
    elif is_integer(nodes):
        n = int(nodes)
        if not (MIN_NODES <= n <= MAX_NODES and n % 2 == 0):
            raise bad("nodes", nodes, allowed)
        seq = [n // 4, n // 2, n] if n % 8 == 0 and n // 4 >= MIN_NODES else [n]
        if surf.kind == "array":
            seq = [v for v in seq if v % surf.values.shape[0] == 0] or [n]
    else:
        if isinstance(nodes, (str, bytes)):
            raise bad("nodes", nodes, allowed)
        try:
            seq = list(nodes)
        except TypeError:
            raise bad("nodes", nodes, allowed) from None
        if not seq or not all(is_integer(v) and MIN_NODES <= v <= MAX_NODES and v % 2 == 0
                              for v in seq) \
                or any(b <= a for a, b in zip(seq[:-1], seq[1:])):
            raise bad("nodes", nodes, allowed)
        seq = [int(v) for v in seq]
    surf.check_nodes(seq)
    for n in seq:
        nx, ny = surf.grid_for(n)
        if nx * ny > MAX_NODES ** 2:
            raise bad("nodes", nodes if nodes is not None else seq,
                      f"grids of at most {MAX_NODES}² points (nx = {nx} gives ny = {ny} for "
                      f"this cell)")
    return tuple(seq)


#: the keys of the ``layer`` mapping: one of the two thicknesses, the foundation and ν
LAYER_KEYS = ("thickness", "thickness_over_wavelength", "foundation", "nu")


def _check_layer(layer):
    """The ``layer`` argument as ``{"thickness": k d, "foundation", "nu"}`` (None: the half-space).

    A mapping with ``"foundation"``, ``"nu"`` and exactly one of ``"thickness"`` (k d, k =
    2π/Lx) and ``"thickness_over_wavelength"`` (d/Lx); the entries are checked by
    `analytic._layer.check_layer` (the Fourier reference's), the first bad one refused by
    name (``layer['nu']=…``).
    """
    if layer is None:
        return None
    what = ("None (the half-space) or a mapping {'thickness': k d > 0 (k = 2π/Lx) or "
            "'thickness_over_wavelength': d/Lx > 0, 'foundation': 'bonded' or 'frictionless', "
            "'nu': a Poisson ratio in (-1, 0.5]}")
    if not isinstance(layer, Mapping):
        raise bad("layer", layer, what)
    keys = set(layer)
    given = [k for k in ("thickness", "thickness_over_wavelength") if k in keys]
    missing = [k for k in ("foundation", "nu") if k not in keys]
    extra = sorted(map(repr, keys - set(LAYER_KEYS)))
    if len(given) != 1 or missing or extra:
        why = "; ".join(x for x in (
            "neither thickness nor thickness_over_wavelength" if not given else
            "both thickness and thickness_over_wavelength" if len(given) == 2 else "",
            f"missing {', '.join(missing)}" if missing else "",
            f"unknown {', '.join(extra)}" if extra else "") if x)
        raise bad("layer", dict(layer), "a mapping with the keys foundation, nu and one of "
                  f"thickness (k d) and thickness_over_wavelength (d/Lx) ({why})")
    if given[0] == "thickness":
        kd = layer["thickness"]
    else:
        dl = real("layer['thickness_over_wavelength']", layer["thickness_over_wavelength"],
                  "a finite thickness d/Lx > 0 (layer=None for the half-space)",
                  lambda v: v > 0.0 and math.isfinite(_TWO_PI * v), kind=True)
        kd = _TWO_PI * dl
    try:
        return check_layer({"thickness": kd, "foundation": layer["foundation"],
                            "nu": layer["nu"]})
    except ValueError as exc:
        if given[0] == "thickness":
            raise
        # the thickness was given over Lx: name it so
        raise ValueError(str(exc).replace(
            f"layer['thickness']={kd!r}",
            f"layer['thickness_over_wavelength']={layer['thickness_over_wavelength']!r} "
            f"(k d = {kd!r})")) from None


def _shortest_relaxation(material):
    """The shortest relaxation time of the creep series (0 for an elastic solid).

    The relaxation times are −1/s at the zeros of J(0+) + Σ J_i/(1 + s τ_i); the shortest is
    the zero left of the leftmost pole −1/τ_min (the sum falls from J(0+) at −∞ to −∞ there).
    """
    j0, jj, tt = material
    terms = [(a, t) for a, t in zip(jj, tt) if a > 0.0]
    if not terms:
        return 0.0
    jplus = j0 - math.fsum(jj)
    f = lambda s: jplus + math.fsum(a / (1.0 + s * t) for a, t in terms)
    pole = -1.0 / min(t for _, t in terms)
    hi = pole * (1.0 + 1e-12)
    while f(hi) >= 0.0 and hi != pole:          # a hair left of the pole, where f < 0
        hi = pole + 0.5 * (hi - pole)
    lo = 2.0 * pole
    while f(lo) <= 0.0:
        lo *= 2.0
    return -1.0 / brentq(f, lo, hi, xtol=1e-300, rtol=1e-14)


def _prolong(field_, nx, ny):
    """A coarse grid's field at the panel centres of nx × ny (periodic bilinear)."""
    cx, cy = field_.shape
    ii = np.arange(nx) * (cx / nx)
    jj = np.arange(ny) * (cy / ny)
    coords = np.meshgrid(ii, jj, indexing="ij")
    return ndimage.map_coordinates(field_, coords, order=1, mode="grid-wrap")


def _solve_grid(grid, zk, control, value, asked, start, tol, h_ref):
    """One grid: a dict of σ, gap, u (k units), s, scalars and the iteration's counts, or
    the message of a failure (str).  start: the coarser grid's (σ, gap, s) or None."""
    nx, ny = grid.nx, grid.ny
    zt = zk - zk.mean()
    # the pressure of full contact, σ̂_q = ẑ_q/Ĉ(q) (q ≠ 0): gap = 0 everywhere
    zh = grid.rfft(zt)
    osc_h = np.zeros_like(zh)
    nz = grid.symbol != 0.0
    osc_h[nz] = zh[nz] / grid.symbol[nz]
    osc = grid.irfft(osc_h)
    evals = kept = 0
    full = True
    if control == "load" and value + osc.min() >= 0.0:
        sigma, s, u = value + osc, 0.0, zt.copy()
    elif control == "penetration" and asked == 1.0:
        sigma, s, u = osc - _lowest(osc), 0.0, zt.copy()
    else:
        full = False
        if start is not None:
            start = (_prolong(start[0], nx, ny), _prolong(start[1], nx, ny), start[2])
        sigma, u, s, evals, kept, converged = _solve_level(grid, zt, control, value, start,
                                                           tol)
        if not converged:
            return (f"the iteration did not converge on the {nx} × {ny} grid ({evals} "
                    "evaluations of its map)")
    if not sigma.max() > 0.0:
        return f"no contact on the {nx} × {ny} grid (the surface does not reach s)"
    gap = s - zt + u
    return {"sigma": sigma, "gap": gap, "u": u, "s": s, "evaluations": evals, "mixed": kept,
            "scalars": _level_scalars(grid, sigma, gap, s, zk, h_ref, full)}


def solve(*, load=None, penetration=None, speed, heights, aspect=1.0, direction=0.0,
          ratio=None, material=None, nodes=None, tol=TOL, layer=None):
    """Steady sliding of a rigid periodic surface over a viscoelastic half-space.

    Parameters
    ----------
    load : float, optional
        Mean pressure over the cell p̃ = p∞(1 − ν²)/E0 > 0 (load control).
    penetration : float, optional
        Δ/h_ref in (0, 1] (penetration control; the load is an output; at 1 the smallest
        load of full contact).  Give exactly one of the two.
    speed : float
        w = V τ k ≥ 0 (V/V0; 0 is the relaxed elastic solid, J0).
    heights : callable, array or dict
        The surface as k·z (positive toward the body): a callable f(x, y) of positions over
        Lx (arrays of one shape, y in [−aspect/2, aspect/2)); a 2-D array of point values at
        the panel centres x_i = i/nx − ½, y_j = (j/ny − ½)·aspect (its trigonometric
        interpolant is solved on grids of multiples of nx); or harmonics ``{(m, n): c}``,
        k·z = Σ Re[c e^{2πi(m x + n y/aspect)}] (the bi-sinusoid hk[cos kx + cos ky] is
        ``{(1, 0): hk, (0, 1): hk}`` with aspect 1).
    aspect : float
        Ly/Lx in [1/64, 64] (default 1).
    direction : float
        θ, degrees from +x counter-clockwise (default 0).
    ratio : float, optional
        E∞/E0 of the standard linear solid (default 3).
    material : (J0, J, tau), optional
        A creep series instead of ``ratio``: J0 and J_i in (1 − ν²)/E0, τ_i in τ.
    nodes : int or sequence of int, optional
        Panels along x of the grids (ny = nx·aspect rounded to even, or in the array's
        proportion): one N solves N/4, N/2 and N; default (64, 128, 256), for an array
        (nx, 2nx, 4nx) up to `MAX_NODES`.
    tol : float
        Stop when the iteration's residual ‖T y − y‖∞ is below tol·max σ (default 1e-10).
    layer : mapping, optional
        A layer of thickness d on a rigid foundation in place of the half-space (None, the
        default: the half-space, solved exactly as without this argument):
        ``{"thickness": k d}`` (k = 2π/Lx) or ``{"thickness_over_wavelength": d/Lx}``, with
        ``"foundation"`` (``"bonded"`` or ``"frictionless"``) and ``"nu"`` (in (−1, 0.5]),
        as `analytic.fourier_solve` takes it.  Mode q of the operator is the half-space's times
        the layer factor S(|q| k d, ν) of `analytic._layer` (Navier's equations, one mode at a
        time); the scalars keep their meaning (Δ from the mean plane of the deformed surface)
        and the result adds ``layer``, ``mean_displacement`` v̄0/h_ref (the layer's uniform
        compression, k v̄0 = C (k d) J0 p̃, J0 the relaxed compliance, C of
        `analytic._layer.uniform_compliance`) and ``approach`` Δ/h_ref + v̄0/h_ref, as the
        BEM's ``diagnostics["layer"]``.  An approach that reaches the foundation (approach ·
        k h_ref ≥ k d) is not a success; under penetration control Δ/h_ref ≥ k d/(k h_ref) is
        refused.

    Returns
    -------
    SurfaceSolution

    Raises
    ------
    ValueError
        ``"name=value is not allowed: …"`` for any input outside what is accepted.

    References
    ----------
    Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014), eq. (2.5) (the
    operator, here per mode of the surface) and eq. (3.1) (the friction).
    """
    t0 = time.perf_counter()
    if load is not None and penetration is not None:
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
    if load is None and penetration is None:
        raise ValueError("load=None, penetration=None is not allowed: give exactly one of "
                         "load and penetration")
    vals = check_reals(ACCEPTED, (("load", load), ("penetration", penetration),
                                  ("speed", speed), ("direction", direction),
                                  ("aspect", aspect), ("tol", tol)), _TESTS)
    mat = _material(ratio, material)
    lay = _check_layer(layer)
    surf = _Surface(heights, vals["aspect"])
    levels = _check_nodes(nodes, surf)
    w, theta, tol = vals["speed"], vals["direction"], vals["tol"]
    control = "load" if load is not None else "penetration"
    asked = vals[control]

    fine_samples = surf.sample(*surf.grid_for(levels[-1]))
    h_ref = surf.extent(fine_samples)
    if not h_ref > 0.0:
        raise bad("heights", heights, surf.what + " (max z − mean z is not > 0)")
    if lay is not None and control == "penetration" and asked * h_ref >= lay["thickness"]:
        # the approach is at least Δ (C ≥ 0): the crest would reach the foundation
        raise bad("penetration", penetration, f"a penetration Δ/h_ref below k d/(k h_ref) = "
                  f"{lay['thickness'] / h_ref:.6g} on this layer (the approach Δ/h_ref + "
                  "v̄0/h_ref, at least Δ/h_ref, must not reach the foundation)")
    value = asked if control == "load" else h_ref * (1.0 - asked)
    warnings = []
    rows, failure = [], None
    starts = [None] * len(SHIFTS)
    for n in levels:
        t1 = time.perf_counter()
        nx, ny = surf.grid_for(n)
        grid = _Grid(nx, ny, vals["aspect"], theta, w, mat, lay)
        pair = []
        for k, shift in enumerate(SHIFTS):
            zk = fine_samples if (n, shift) == (levels[-1], 0.0) else surf.sample(nx, ny, shift)
            got = _solve_grid(grid, zk, control, value, asked, starts[k], tol, h_ref)
            if isinstance(got, str):
                failure = got
                break
            pair.append(got)
            starts[k] = (got["sigma"], got["gap"], got["s"])
        if failure is not None:
            break
        scalars = {key: 0.5 * (pair[0]["scalars"][key] + pair[1]["scalars"][key])
                   for key in _RELATIVE + _ABSOLUTE + _DIAGNOSTIC}
        for key in ("n_patches", "full_contact", "smallest_patch_points"):
            scalars[key] = pair[0]["scalars"][key]
        scalars["complementarity"] = max(p["scalars"]["complementarity"] for p in pair)
        rows.append({"nodes": nx, "ny": ny, "scalars": scalars,
                     "shifted": [p["scalars"] for p in pair],
                     "evaluations": sum(p["evaluations"] for p in pair),
                     "mixed": sum(p["mixed"] for p in pair),
                     "seconds": time.perf_counter() - t1})
    elapsed = time.perf_counter() - t0
    material_out = {"J0": mat[0], "J": list(mat[1]), "tau": list(mat[2])}
    if failure is None:
        last = pair[0]
        x = np.arange(nx) / nx - 0.5
        y = (np.arange(ny) / ny - 0.5) * vals["aspect"]
    common = dict(control=control, asked=asked, speed=w, direction=theta,
                  aspect=vals["aspect"], material=material_out, h_ref=h_ref,
                  grids=tuple((r["nodes"], r["ny"]) for r in rows), levels=tuple(rows),
                  nodes=rows[-1]["nodes"] if rows else 0, elapsed=elapsed)
    if lay is not None:
        common["layer"] = {"thickness": lay["thickness"],
                           "thickness_over_wavelength": lay["thickness"] / _TWO_PI,
                           "foundation": lay["foundation"], "nu": lay["nu"],
                           "uniform_compliance": uniform_compliance(lay["nu"],
                                                                    lay["foundation"])}
    if failure is not None:
        nan = math.nan
        empty = np.zeros((0, 0))
        return SurfaceSolution(success=False, status=1, message=failure, load=nan,
                               full_contact=False, contact_fraction=nan, penetration=nan,
                               separation=nan, tau_f=nan, mu=nan, mu_lateral=nan,
                               n_patches=0, max_pressure=nan, error_estimate={},
                               observed_order={}, extrapolated={}, diagnostics={},
                               warnings=tuple(warnings), x=np.zeros(0), y=np.zeros(0),
                               pressure=empty, gap=empty, displacement=empty, **common)
    common.update(x=x, y=y, pressure=last["sigma"], gap=last["gap"] / h_ref,
                  displacement=last["u"] / h_ref)

    ns = [r["nodes"] for r in rows]
    out, est, order, extra = {}, {}, {}, {}
    for key in _RELATIVE + _ABSOLUTE:
        v, e, p, x_ = richardson(ns, [r["scalars"][key] for r in rows])
        a_, b_ = (g[key] for g in rows[-1]["shifted"])
        # one grid's error oscillates with where the edges fall between the points: the
        # finest level's two grids sample it at two phases, so their spread joins the estimate
        e = max(e, abs(a_ - b_)) if math.isfinite(e) else abs(a_ - b_)
        if key in _RELATIVE:
            e = e / abs(v) if v != 0.0 else math.inf
        e = e + _FLOOR
        out[key], est[key], order[key], extra[key] = v, e, p, x_
    est["n_patches"] = None
    fine = rows[-1]["scalars"]
    if len({r["scalars"]["n_patches"] for r in rows}) > 1:
        warnings.append("the grids disagree on the number of patches: "
                        + ", ".join(str(r["scalars"]["n_patches"]) for r in rows))
    if not fine["full_contact"] and fine["smallest_patch_points"] < _MIN_PATCH_POINTS:
        warnings.append(f"a contact patch of {fine['smallest_patch_points']} points on the "
                        "finest grid: its edges are not resolved")
    memory = w * _shortest_relaxation(mat) / _TWO_PI
    if 0.0 < memory * nx < 4.0:
        warnings.append(f"the shortest memory length w θ/(2π) = {memory:.3g} Lx has fewer "
                        f"than 4 panels on the finest grid ({nx} along x)")
    if control == "penetration" and asked == 1.0:
        message = "the threshold of full contact (Δ/h_ref = 1), in closed form on each grid"
    elif fine["full_contact"]:
        message = "full contact, in closed form on each grid (σ̂_q = ẑ_q/Ĉ(q))"
    else:
        message = ("converged on grids " + ", ".join(f"{a} × {b}" for a, b in common["grids"])
                   + f" ({sum(r['evaluations'] for r in rows)} evaluations of the map)")
    finite = all(math.isfinite(out[k]) for k in ("load", "penetration", "mu", "mu_lateral",
                                                  "contact_fraction", "max_pressure"))
    success = finite and out["load"] > 0.0
    if not success:
        message = "non-finite or non-positive scalars; not a solution"
    diagnostics = {k: fine[k] for k in ("mu_direct", "mu_lateral_direct",
                                         "contact_fraction_nodal", "complementarity")}
    if lay is not None:
        load_out = out["load"] if control == "penetration" else asked
        # the uniform mode: k v̄0 = C (k d) J0 p̃ (static: the relaxed J0), over k h_ref
        mean = common["layer"]["uniform_compliance"] * lay["thickness"] * mat[0] * load_out \
            / h_ref
        approach = out["penetration"] + mean
        est["mean_displacement"] = est["load"]      # v̄0 ∝ p̃
        est["approach"] = ((est["penetration"] * abs(out["penetration"])
                            + est["load"] * abs(mean)) / abs(approach)
                           if approach != 0.0 else math.inf)
        common.update(mean_displacement=mean, approach=approach)
        diagnostics["layer"] = dict(common["layer"], mean_displacement=mean, approach=approach)
        if success and approach * h_ref >= lay["thickness"]:
            success = False
            message = (f"the crest's approach {approach:.6g} h_ref reaches the foundation at "
                       f"d = {lay['thickness'] / h_ref:.6g} h_ref (k d = "
                       f"{lay['thickness']:.6g}, k h_ref = {h_ref:.6g}): not a solution of "
                       "small strains")
        if lay["thickness"] * nx / _TWO_PI < 4.0:
            warnings.append(f"the layer's thickness d = {lay['thickness'] / _TWO_PI:.3g} Lx "
                            f"spans fewer than 4 panels on the finest grid ({nx} along x)")
    return SurfaceSolution(success=success, status=0 if success else 1, message=message,
                           load=out["load"] if control == "penetration" else asked,
                           full_contact=fine["full_contact"],
                           contact_fraction=out["contact_fraction"],
                           penetration=out["penetration"], separation=1.0 - out["penetration"],
                           tau_f=out["tau_f"], mu=out["mu"], mu_lateral=out["mu_lateral"],
                           n_patches=fine["n_patches"], max_pressure=out["max_pressure"],
                           error_estimate=est, observed_order=order, extrapolated=extra,
                           diagnostics=diagnostics, warnings=tuple(warnings), **common)
