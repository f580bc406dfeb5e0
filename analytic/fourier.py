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

S the layer factor of `analytic._layer` (solved there from Navier's equations), and the
dissipation weighs mode n by S as well.  Δ/h keeps its meaning (from the mean line of the
deformed surface); the uniform mode, finite on a layer, gives the mean displacement
k v̄_0 = C (k d) J0 p̃ (relaxed J0: the mean pressure is static) and the approach of the
indenter from the undeformed top face, Δ/h + v̄_0/h.  d is a length of the solution (the
pressure varies over d at the edges of a thin layer's contact) that the grids must resolve
like a memory layer (`thickness_resolution`).

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014: eqs (2.2)–(2.5) (the
steady-sliding displacement), (3.1) (friction), Appendix A (the elastic limits) and Appendix B
(full contact).  The layer: Menga, Afferrante & Carbone, J. Mech. Phys. Solids 95 (2016)
517–529.
"""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg
from scipy.optimize import brentq, minimize_scalar
from scipy.special import dawsn

from viscosine.checks import bad, integer, is_integer, real, series

from ._layer import check_layer, describe, layer_factor, uniform_compliance

_TWO_PI = 2.0 * math.pi

#: default levels (points per period) and shifts per level
NODES = (1024, 2048, 4096, 8192)
SHIFTS = 16
#: the largest grid: the restricted matrix of a near-full contact is then ~0.5 GB in LU form
MAX_NODES = 8192
MIN_NODES = 64
#: points per shortest memory layer below which a grid does not resolve it (measured: the
#: standard linear solid with E∞/E0 = 100 meets the estimates at 3.9 points, not at 1.3)
MIN_LAYER_POINTS = 4.0
#: points of the finest grid per thickness d of a layer below which d is not resolved
#: (`thickness_resolution`).  Measured against the BEM (rtol 1e-7 or 1e-8) over k d = 0.005 …
#: 0.5, both foundations, V/V0 = 0.1, 1, 10, contacts of 4 % to 68 % of the period (414
#: solves): with the default levels the true errors exceeded the estimates in 2 of 18 solves
#: under 32 points per d (1.2 and 1.3 times, at 13 and 26 points), in none of 72 from 32 on;
#: three levels (8 or 16 shifts) exceeded them in 5 of 126 under 32, 2 of 198 from 32 on (up to
#: 2.3 times both)
MIN_THICKNESS_POINTS = 32.0
#: a patch narrower than this many points of the finest grid is not an answer (the edge fit
#: and the shift average need points inside; measured at p̃ = 1e-6, 4 points: errors of 4e-6 in
#: ka and 8e-5 in Δ/h, still within the estimates), and under four times as many is warned of
_MIN_PATCH_POINTS = 4
#: the grid from which the first level is started
_START_NODES = 256
#: an active-set step drops σ_j < −_TOL·max σ and adds gap_j < −_TOL·hk: the error of the
#: restricted solve (its residual is held below 1e-12) must not make the iteration cycle at a
#: point that sits on an edge
_TOL = 1e-11
_MAX_ACTIVE_SET = 100
#: powers of d in the gap fit near an edge; its window is _FIT_WINDOW of the shorter of the
#: contact and the gap region (the expansion about one edge converges up to the other edges;
#: measured on the exact gap: edges to ~1e-9 λ at a quarter), and no fewer points than
#: _FIT_MIN_POINTS (the fit averages the O(h²) errors of the gap over them)
_FIT_POWERS = (1.5, 2.5, 3.5, 4.5, 5.5, 6.5)
_FIT_WINDOW = 0.25
_FIT_MIN_POINTS = 24
#: on a layer the fit window is also at most this many thicknesses d: the layer's kernel
#: differs from the half-space's by a part analytic in a strip of half-width 2d only (S − 1
#: ~ e^{−2|n|kd}), which bounds the expansion about an edge as the other edges do; a quarter
#: of that radius, as _FIT_WINDOW (measured: at k d = 0.2 the uncapped window, ~1.2 d, left
#: errors of 1e-6 in ka that did not fall with N and exceeded the estimates 2-4 times)
_FIT_LAYER = 0.5


# --------------------------------------------------------------------------------------------
# Material
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Material:
    """A Prony series in one of its two forms, as plain numbers (made by `material`).

    Attributes
    ----------
    form : str
        ``"creep"`` (base J0, amplitudes J_i, times τ_i) or ``"relaxation"`` (base E_r,
        amplitudes E_i, times θ_i).
    base : float
    amps, times : tuple of float
    """

    form: str            # "creep" or "relaxation"
    base: float          # J0 or E_r
    amps: tuple          # J_i or E_i
    times: tuple         # τ_i or θ_i

    def jstar(self, n, w):
        """J*(n) at speed w (array n)."""
        n = np.asarray(n, dtype=float)
        if self.form == "creep":
            out = np.full(n.shape, self.base - math.fsum(self.amps), dtype=complex)
            for a, t in zip(self.amps, self.times):
                out += a / (1.0 - 1j * (n * (w * t)))
            return out
        return 1.0 / self.estar(n, w)

    def estar(self, n, w):
        """E*(n) at speed w (array n)."""
        n = np.asarray(n, dtype=float)
        if self.form == "relaxation":
            out = np.full(n.shape, self.base, dtype=complex)
            for a, t in zip(self.amps, self.times):
                x = n * (w * t)
                out += a * (-1j * x) / (1.0 - 1j * x)
            return out
        return 1.0 / self.jstar(n, w)

    def as_dict(self):
        return {"form": self.form, "base": self.base, "amplitudes": list(self.amps),
                "times": list(self.times)}

    def creep_terms(self):
        """(J(0+), ((J_i, τ_i), ...)): the creep form (for a relaxation series, J(s) = 1/E(s)
        by partial fractions at the zeros of E(s), s the Laplace variable)."""
        if self.form == "creep":
            return self.base - math.fsum(self.amps), _merged(self.amps, self.times)
        terms = _merged(self.amps, self.times)
        e_inf = self.base + math.fsum(a for a, _ in terms)
        e_of = lambda s: e_inf - math.fsum(a / (1.0 + s * t) for a, t in terms)
        de = lambda s: math.fsum(a * t / (1.0 + s * t) ** 2 for a, t in terms)
        # E(s) increases between its poles −1/θ_i from −∞ to +∞, and from −∞ to E_r > 0 on
        # (−1/θ_max, 0): one zero s_j = −1/τ_j in each of those intervals
        poles = sorted(-1.0 / t for _, t in terms)
        out = []
        for lo, hi in zip(poles, poles[1:] + [0.0]):
            s = _zero_between(e_of, lo, hi, rising=True)
            out.append((-1.0 / s / de(s), -1.0 / s))   # J_j = τ_j / E'(s_j)
        return 1.0 / e_inf, tuple(out)

    def relaxation_times(self):
        """θ_k of the relaxation form (given, or −1/s at the zeros of J(s))."""
        if self.form == "relaxation":
            return tuple(sorted(t for _, t in _merged(self.amps, self.times)))
        jplus, terms = self.creep_terms()
        j_of = lambda s: jplus + math.fsum(a / (1.0 + s * t) for a, t in terms)
        # J(s) decreases between its poles −1/τ_i from +∞ to −∞, and from J(0+) > 0 to −∞ left of
        # the leftmost one: one zero in each of those intervals
        poles = sorted(-1.0 / t for _, t in terms)
        out = []
        for lo, hi in zip([None] + poles[:-1], poles):
            out.append(-1.0 / _zero_between(j_of, lo, hi, rising=False))
        return tuple(sorted(out))


def _merged(amps, times):
    """((a, t), ...) with equal times summed and zero amplitudes dropped (sorted by t)."""
    acc = {}
    for a, t in zip(amps, times):
        if a > 0.0:
            acc[t] = acc.get(t, 0.0) + a
    return tuple((a, t) for t, a in sorted(acc.items()))


def _zero_between(f, lo, hi, rising):
    """The zero of f, monotone between its poles lo < hi (lo None: −∞), by Brent's method."""
    sign = 1.0 if rising else -1.0
    if lo is None:          # step out to the left until f has the sign it has at −∞
        lo = 2.0 * hi
        while sign * f(lo) >= 0.0:
            lo *= 2.0
        a = lo
    else:
        d = 0.5 * (hi - lo)
        while sign * f(lo + d) >= 0.0 and lo + d != lo:
            d *= 0.5
        a = lo + d
    d = 0.5 * (hi - a)
    while sign * f(hi - d) <= 0.0 and hi - d != hi:
        d *= 0.5
    return brentq(f, a, hi - d, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=500)


def material(*, ratio=None, creep=None, relaxation=None):
    """The material of `fourier_solve`, validated (exactly one form; none: ratio 3).

    Parameters
    ----------
    ratio : float, optional
        E∞/E0 ≥ 1 of the standard linear solid (creep form J0 = 1, J_1 = 1 − 1/ratio, τ_1 = 1,
        units E0 and τ).
    creep : (J0, J_i, tau_i), optional
        Creep form J(t) = J0 − Σ J_i e^{−t/τ_i}: J0 and J_i in (1 − ν²)/E_ref, J_i ≥ 0,
        τ_i > 0 in τ_ref, J(0+) = J0 − Σ J_i > 0.
    relaxation : (E_r, E_i, theta_i), optional
        Relaxation form E(t) = E_r + Σ E_i e^{−t/θ_i}: E_r > 0 and E_i ≥ 0 in
        E_ref/(1 − ν²), θ_i > 0 in τ_ref.

    Returns
    -------
    Material
    """
    given = {k: v for k, v in (("ratio", ratio), ("creep", creep), ("relaxation", relaxation))
             if v is not None}
    if len(given) > 1:
        name = list(given)[1]
        raise bad(name, given[name], f"one material only (got {' and '.join(given)}): "
                  "ratio, creep or relaxation")
    if ratio is None and creep is None and relaxation is None:
        ratio = 3.0
    if ratio is not None:
        r = real("ratio", ratio, "a finite E∞/E0 ≥ 1 (1 is elastic)", lambda v: v >= 1.0)
        return Material("creep", 1.0, ((r - 1.0) / r,), (1.0,))
    form, value = ("creep", creep) if creep is not None else ("relaxation", relaxation)
    what = ("a triple (J0, J_i, tau_i) of J(t) = J0 − Σ J_i exp(−t/τ_i)" if form == "creep" else
            "a triple (E_r, E_i, theta_i) of E(t) = E_r + Σ E_i exp(−t/θ_i)")
    try:
        base, amps, times = value
    except (TypeError, ValueError):
        raise bad(form, value, what) from None
    try:  # a bad part is refused as the whole triple, named by its form
        base = real(form, base, "", lambda v: v > 0.0)
    except ValueError:
        raise bad(form, value, what + " with a finite base value > 0") from None
    try:
        amps = series(form, amps, "", lambda v: v >= 0.0)
        times = series(form, times, "", lambda v: v > 0.0)
    except ValueError:
        raise bad(form, value, what + " with finite amplitudes ≥ 0 and times > 0") from None
    if len(amps) != len(times):
        raise bad(form, value, f"{what} with one time per amplitude (got {len(amps)} "
                  f"amplitudes and {len(times)} times)")
    if form == "creep" and not base - math.fsum(amps) > 0.0:
        raise bad(form, value, f"{what} with J(0+) = J0 − Σ J_i > 0 (got "
                  f"{base - math.fsum(amps)!r})")
    return Material(form, base, amps, times)


def complex_compliance(modes, speed, **material_kw):
    """J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i) (or 1/E*(n) for a relaxation series).

    Parameters
    ----------
    modes : array_like
        Mode numbers n (X-frequencies).
    speed : float
        w = V τ_ref k ≥ 0.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    ndarray of complex, in (1 − ν²)/E_ref.
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    return material(**material_kw).jstar(modes, w)


def complex_modulus(modes, speed, **material_kw):
    """E*(n) = E_r + Σ E_i (−i n w θ_i)/(1 − i n w θ_i) (or 1/J*(n) for a creep series).

    Same parameters as `complex_compliance`; returns E_ref/(1 − ν²) units.
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    return material(**material_kw).estar(modes, w)


# --------------------------------------------------------------------------------------------
# Full contact in closed form (Appendix B)
# --------------------------------------------------------------------------------------------
def full_contact(speed, *, hk=1.0, load=None, layer=None, **material_kw):
    """Full contact of the sinusoid, for any material (Appendix B, one harmonic), on the
    half-space or on a layer.

    With v = y − s on the whole period, k v̂_1 = hk/2 and s = 0.  On a layer mode 1 of the
    operator is 2 S J*(1), S = S(k d, ν) the layer factor (`layer_factor`), so
    σ̂_1 = (hk/4) E*(1)/S (S = 1 on the half-space) and

        σ = p̃ + (hk/2)|E*(1)|/S cos(2πX + arg E*(1)),
        p̃FC = (hk/2)|E*(1)|/S                 (full contact iff p̃ ≥ p̃FC),
        τ̃f = 4 S Im J*(1) |σ̂_1|² = −(hk)²/(4S) Im E*(1)   (Im J* |E*|² = −Im E*),
        kê = −arg E*(1)                       (the pressure maximum leads the crest; S is
                                               real, so the phase is the half-space's).

    The dissipation of mode 1 carries one S (its displacement) and |σ̂_1|² two 1/S: a layer
    stiffens the contact and raises the friction stress by 1/S, μ = τ̃f/p̃ at a given p̃.  The
    mean displacement of the layer (its uniform mode, relaxed compliance J0 since the mean
    pressure is static) is k v̄_0 = C (k d) J0 p̃ (`analytic._layer.uniform_compliance`), and
    the approach of the crest from the undeformed top face is Δ/h + v̄_0/h = 1 + v̄_0/h.

    Parameters
    ----------
    speed : float
        w = V τ_ref k ≥ 0.
    hk : float
        Amplitude h k > 0.
    load : float, optional
        p̃ (E_ref/(1 − ν²)); with it, ``mu`` = τ̃f/p̃ and whether the contact is full.
    layer : mapping, optional
        ``{"thickness": k d > 0, "foundation": "bonded" | "frictionless", "nu": ν}`` (see
        `fourier_solve`); None (default) is the half-space.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    dict
        ``load_threshold`` p̃FC, ``modulus`` E*(1) of the material (complex), ``tau_f``,
        ``ke_hat``; with ``load``: ``full_contact`` (p̃ ≥ p̃FC) and ``mu``.  With a layer also
        ``layer_factor`` S(k d) and, with ``load``, ``mean_displacement`` v̄_0/h and
        ``approach`` 1 + v̄_0/h.

    References
    ----------
    Appendix B (eqs B1–B8) of the paper; the layer factor: Menga, Afferrante & Carbone (2016).
    """
    w = real("speed", speed, "a finite speed V τ_ref k ≥ 0", lambda v: v >= 0.0)
    hk = real("hk", hk, "a finite amplitude hk > 0", lambda v: v > 0.0)
    mat = material(**material_kw)
    lay = check_layer(layer)
    e1 = complex(mat.estar(np.array([1.0]), w)[0])
    out = {"load_threshold": 0.5 * hk * abs(e1), "modulus": e1,
           "tau_f": -0.25 * hk * hk * e1.imag, "ke_hat": -math.atan2(e1.imag, e1.real)}
    if lay is not None:
        s1 = layer_factor(lay["thickness"], lay["nu"], lay["foundation"])
        out["layer_factor"] = s1
        out["load_threshold"] /= s1
        out["tau_f"] /= s1
    if load is not None:
        p = real("load", load, "a finite mean pressure > 0", lambda v: v > 0.0)
        out["full_contact"] = p >= out["load_threshold"]
        out["mu"] = out["tau_f"] / p
        if lay is not None:
            out["mean_displacement"] = _mean_displacement(lay, mat, p, hk)
            out["approach"] = 1.0 + out["mean_displacement"]
    return out


def _relaxed_compliance(mat):
    """J0 = J(t → ∞) (the creep form's base, or 1/E_r)."""
    return mat.base if mat.form == "creep" else 1.0 / mat.base


def _mean_displacement(lay, mat, p, hk):
    """v̄_0/h: k v̄_0 = C (k d) J0 p̃ over hk (C of `uniform_compliance`, relaxed J0)."""
    return uniform_compliance(lay["nu"], lay["foundation"]) * lay["thickness"] \
        * _relaxed_compliance(mat) * p / hk


# --------------------------------------------------------------------------------------------
# One grid
# --------------------------------------------------------------------------------------------
def _runs(active):
    """(start, length) of the circular runs of True, in order of start."""
    n = active.size
    if active.all():
        return [(0, n)]
    if not active.any():
        return []
    a = active.astype(np.int8)
    up = np.flatnonzero(np.diff(np.concatenate([a[-1:], a])) == 1)
    down = np.flatnonzero(np.diff(np.concatenate([a[-1:], a])) == -1)
    out = []
    for s0 in up:
        later = down[down > s0]
        end = later[0] if later.size else down[0] + n
        out.append((int(s0), int(end - s0)))
    return out


def _circulant_product(colhat, x, n):
    return np.fft.irfft(np.fft.rfft(x, axis=0) * (colhat if x.ndim == 1 else colhat[:, None]),
                        n, axis=0)


def _toeplitz_product(c, r, z):
    """T z for the Toeplitz T with first column c and first row r (FFT, any number of columns)."""
    L = c.size
    m = 1 << int(math.ceil(math.log2(2 * L)))
    gen = np.zeros(m)
    gen[:L] = c
    gen[m - L + 1:] = r[1:][::-1]
    padded = np.concatenate([z, np.zeros((m - L,) + z.shape[1:])])
    return _circulant_product(np.fft.rfft(gen), padded, m)[:L]


def _restricted_solve(col, runs, idx, rhs):
    """Solve C_AA z = rhs on the active points idx (rhs of shape (|A|, k)).

    One patch: C_AA is Toeplitz (Levinson, O(|A|²)), with refinement steps by FFT products
    until the residual meets its bound; otherwise (or if it is not met) dense LU.
    """
    n = col.size
    if len(runs) == 1:
        s0, L = runs[0]
        order = (s0 + np.arange(L)) % n     # the run in order along x
        loc = np.empty(n, dtype=np.intp)
        loc[idx] = np.arange(idx.size)
        b = rhs[loc[order]]
        c = col[:L]
        r = col[(-np.arange(L)) % n]
        # Levinson's recursion leaves residuals of ~1e-13 here (LU ~1e-15): a refinement step
        # only where they exceed 1e-12, far below the discretisation errors
        bound = 1e-12 * max(np.max(np.abs(b)), 1e-300)
        try:
            z = linalg.solve_toeplitz((c, r), b, check_finite=False)
            for _ in range(3):
                res = b - _toeplitz_product(c, r, z)
                if np.max(np.abs(res)) <= bound:
                    out = np.empty_like(z)
                    out[loc[order]] = z
                    return out
                z = z + linalg.solve_toeplitz((c, r), res, check_finite=False)
        except linalg.LinAlgError:  # a singular leading minor: LU pivots past it
            pass
    dense = np.empty((idx.size, idx.size))
    for i0 in range(0, idx.size, 1024):  # row blocks: no |A|² index array at once
        rows = idx[i0:i0 + 1024]
        dense[i0:i0 + rows.size] = col[(rows[:, None] - idx[None, :]) % n]
    return linalg.solve(dense, rhs, check_finite=False)


@dataclass
class _Grid:
    n: int
    phi: float
    x: np.ndarray
    sigma: np.ndarray
    gap: np.ndarray
    s: float
    active: np.ndarray
    nit: int
    converged: bool
    complementarity: float


def _solve_grid(n, phi, mat, w, hk, control, value, patches, factor=None):
    """Active-set solve on one shifted grid, started from the patches [(x_t, x_l), ...].

    ``factor``: the layer factor S of the modes 0 … N/2 (None: the half-space)."""
    x = -0.5 + (np.arange(n) + phi) / n
    y = hk * np.cos(_TWO_PI * x)
    modes = np.arange(n // 2 + 1, dtype=float)
    sym = np.zeros(modes.size, dtype=complex)
    sym[1:] = (2.0 / modes[1:]) * mat.jstar(modes[1:], w)
    if factor is not None:
        sym[1:] *= factor[1:]
    # C has no mode 0 (v from its mean line), so it is singular and its restriction to a
    # near-full contact nearly so.  The solves use C' = C + c0·mean, mode 0 given the symbol
    # c0 = 2 Re J*(1) (times S(kd) on a layer) of the scale of mode 1: C'σ = Cσ + c0 mean(σ),
    # which only moves s.
    c0 = float(sym[1].real)
    sym[0] = c0
    col = np.fft.irfft(sym, n)        # C'[i, j] = col[(i − j) mod n]; Nyquist: its real part
    colhat = np.fft.rfft(col)
    active = np.zeros(n, dtype=bool)
    for xt, xl in patches:
        # positions of the points relative to the trailing edge, unwrapped into [0, 1)
        active |= np.mod(x - xt, 1.0) <= (xl - xt)
    if control == "penetration" and not np.any(y > value):
        # no point of this grid reaches the body: no contact to solve for
        zero = np.zeros(n)
        return _Grid(n, phi, x, zero, value - y, value, zero.astype(bool), 0, True, 0.0)
    if not active.any():
        active[np.argmax(y)] = True
    seen = set()
    converged = False
    sigma = np.zeros(n)
    for it in range(1, _MAX_ACTIVE_SET + 1):
        idx = np.flatnonzero(active)
        runs = _runs(active)
        z = _restricted_solve(col, runs, idx, np.stack([y[idx], np.ones(idx.size)], axis=1))
        # on the contact C'σ + t = y with t = s − c0 mean(σ), so σ = z1 − t z2
        m1, m2 = z[:, 0].sum() / n, z[:, 1].sum() / n
        if control == "load":
            t = (m1 - value) / m2
            s = t + c0 * value
        else:
            s = value
            t = (s - c0 * m1) / (1.0 - c0 * m2)
        sa = z[:, 0] - t * z[:, 1]
        sigma = np.zeros(n)
        sigma[idx] = sa
        gap = _circulant_product(colhat, sigma, n) - y + t
        gap[idx] = 0.0
        new = active.copy()
        new[idx[sa < -_TOL * max(sa.max(), 0.0)]] = False
        new[~active & (gap < -_TOL * hk)] = True
        if np.array_equal(new, active):
            converged = True
            break
        key = new.tobytes()
        if key in seen:
            break
        seen.add(key)
        active = new
    scale = max(sigma.max(), 1e-300)
    compl = max(float(-sigma.min()) / scale, float(-gap.min()) / hk, 0.0)
    return _Grid(n, phi, x, sigma, gap, s, active, it, converged, compl)


# --------------------------------------------------------------------------------------------
# Scalars of one grid
# --------------------------------------------------------------------------------------------
def _wrap(x):
    """x/λ into [−½, ½)."""
    return (x + 0.5) % 1.0 - 0.5


def _recovery(powers, z):
    """R_p(z) = Φ_p(z)/z^p with Φ_p(z) = ∫_0^z e^{−(z−u)} u^p du, for each p (rows) and z ≥ 0.

    Series z Σ_k (−z)^k / ((p+1)…(p+1+k)) below z = max p + 8 (it loses at most ~3 digits
    there); above, the upward recurrence R_p = 1 − (p/z) R_{p−1} from R_{−1/2} = 2√z F(√z)
    (F Dawson's integral), stable once z exceeds p.  R_p(0) = 0, R_p(∞) = 1.
    """
    z = np.asarray(z, dtype=float)
    out = np.empty((len(powers), z.size))
    big = z > max(powers) + 8.0
    if np.any(big):
        zb = z[big]
        r = 2.0 * np.sqrt(zb) * dawsn(np.sqrt(zb))
        p = -0.5
        table = {}
        while p < max(powers):
            p += 1.0
            r = 1.0 - (p / zb) * r
            table[p] = r
        for k, q in enumerate(powers):
            out[k, big] = table[q]
    small = ~big
    if np.any(small):
        zs = z[small]
        # the alternating terms fall below 1e-17 of the sum within 3 max z + 40 of them (z < 15)
        nterms = int(3.0 * zs.max()) + 40
        for k, q in enumerate(powers):
            term = np.full(zs.size, 1.0 / (q + 1.0))
            total = term.copy()
            for j in range(1, nterms):
                term *= -zs / (q + 1.0 + j)
                total += term
            out[k, small] = zs * total
    return out


def _edge_basis(d, powers, trailing, creep):
    """Columns of the gap model at distances d ≥ 0 from an edge.

    Leading edge: d^p, p = 3/2, 5/2, … (the memory there reaches only ahead of the contact and
    adds half-integer powers).  Trailing edge: the creep operator applied to (−x)_+^p,

        ψ_p(d) = J(0+) d^p + Σ_i J_i L_i^p Φ_p(d/L_i),   L_i = w τ_i/(2π) in x/λ,

    the recovery of the surface behind the contact, which on a length L_i turns J(0+) d^p into
    J0 d^p and which no power series in d reproduces on a window wider than L_i.
    """
    cols = d[:, None] ** powers[None, :]
    if not trailing or not creep[1]:
        return cols
    jplus, terms = creep
    factor = np.full((d.size, powers.size), jplus)
    for j_i, length in terms:
        if length == 0.0:
            factor += j_i
        else:
            factor += j_i * _recovery(list(powers), d / length).T
    return cols * factor


def _fit_edge(xs, g, lo, hi, side, trailing, creep, nbasis):
    """The edge x_e in [lo, hi] whose gap model (`_edge_basis`) fits g best.

    Variable projection: the coefficients by linear least squares for each x_e, x_e by Brent's
    method on the misfit (columns scaled to unit maximum).
    """
    powers = np.asarray(_FIT_POWERS[:nbasis])

    def misfit(xe):
        d = np.maximum(side * (xs - xe), 0.0)
        a = _edge_basis(d, powers, trailing, creep)
        a = a / np.maximum(np.max(np.abs(a), axis=0), 1e-300)
        coef, *_ = np.linalg.lstsq(a, g, rcond=None)
        return float(np.sum((a @ coef - g) ** 2))

    res = minimize_scalar(misfit, bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-15, "maxiter": 500})
    return float(res.x)


def _edges(grid, s0, length, gap_before, gap_after, creep, reach=None):
    """Trailing and leading edges (unwrapped x/λ) of the run of `length` points from s0.

    gap_before/gap_after: the gap points between this run and its neighbours (the run's own
    other end for a single patch).  The fit window is a quarter of the shorter of the contact
    and the gap region (the distance to the nearest other edge, which bounds the expansion),
    and no more than ``reach`` points on a layer (its expansion converges within about 2d
    there, `_FIT_LAYER`), at least _FIT_MIN_POINTS points, skipping the first gap point (the
    discretisation error is largest there).  Returns (x_t, x_l, fitted).
    """
    n = grid.n
    h = 1.0 / n
    x0 = grid.x[s0]
    x_last = x0 + (length - 1) * h      # last contact point, unwrapped
    fitted = True
    out = []
    for side, room in ((-1, gap_before), (+1, gap_after)):
        k = _FIT_WINDOW * min(length, room)
        if reach is not None:
            k = min(k, reach)
        k = max(_FIT_MIN_POINTS, int(round(k)))
        k = min(k, (room - 1) // 2)
        m = np.arange(2, k + 2)
        if side > 0:
            xs, g = x_last + m * h, grid.gap[(s0 + length - 1 + m) % n]
            lo, hi = x_last - h, x_last + 2 * h
        else:
            xs, g = x0 - m * h, grid.gap[(s0 - m) % n]
            lo, hi = x0 - 2 * h, x0 + h
        if k >= 8:
            nb = len(_FIT_POWERS) if k >= 24 else 4
            out.append(_fit_edge(xs, g, lo, hi, side, side < 0, creep, nb))
            continue
        # too few gap points for the fit: the zero of gap^(2/3), linear through two points
        fitted = False
        first = x_last + h if side > 0 else x0 - h
        idx = (s0 + length - 1 + np.array([1, 2])) % n if side > 0 else (s0 - np.array([1, 2])) % n
        gi = np.maximum(grid.gap[idx], 0.0) ** (2.0 / 3.0)
        den = gi[1] - gi[0]
        out.append(first - side * h * gi[0] / den if den > 0.0 else first - side * 0.5 * h)
    return out[0], out[1], fitted


def _grid_scalars(grid, mat, w, hk, creep, factor=None, reach=None):
    """The scalars of one grid, and its patches [(x_t, x_l, load, centroid)].

    ``factor``: the layer factor of the modes 0 … N/2 and ``reach`` the widest edge fit in
    points (None, None: the half-space)."""
    n = grid.n
    sig = grid.sigma
    shat = np.fft.rfft(sig) / n
    modes = np.arange(shat.size, dtype=float)
    weight = np.ones(modes.size)
    weight[0] = 0.0
    if n % 2 == 0:
        weight[-1] = 0.0   # the Nyquist mode is real in C: it dissipates nothing
    if factor is not None:
        weight = weight * factor   # a mode's displacement, so its dissipation, carries S
    tau = float(np.sum(weight * 4.0 * mat.jstar(modes, w).imag * np.abs(shat) ** 2))
    load = float(np.mean(sig))
    out = {"load": load, "penetration": 1.0 - grid.s / hk, "tau_f": tau,
           "mu": tau / load if load > 0.0 else math.nan}
    runs = _runs(grid.active)
    patches = []
    fitted = True
    if len(runs) == 1 and runs[0][1] == n:
        s1 = np.sum(sig * np.exp(-1j * _TWO_PI * grid.x)) / n  # σ̂_1 with its true phase
        out.update(full_contact=True, contact_fraction=1.0, ka=math.pi, ke=None,
                   ke_hat=-math.atan2(s1.imag, s1.real))
        return out, [(-0.5, 0.5, load, _wrap(out["ke_hat"] / _TWO_PI))], True
    for i, (s0, length) in enumerate(runs):
        prev_end = runs[i - 1][0] + runs[i - 1][1]
        nxt = runs[(i + 1) % len(runs)][0]
        before = (s0 - prev_end) % n
        after = (nxt - (s0 + length)) % n
        xt, xl, ok = _edges(grid, s0, length, before, after, creep, reach)
        fitted &= ok
        pts = (s0 + np.arange(length)) % n
        xr = grid.x[s0] + np.arange(length) / n
        share = float(np.sum(sig[pts])) / n
        # a patch that carries nothing (a point held at σ = 0 by the tolerance): its centre
        centroid = (float(np.sum(xr * sig[pts]) / np.sum(sig[pts])) if share > 0.0
                    else 0.5 * (xt + xl))
        shift = _wrap(0.5 * (xt + xl)) - 0.5 * (xt + xl)  # wrap by the centre, keep the pair
        patches.append((xt + shift, xl + shift, share, centroid + shift))
    patches.sort(key=lambda p: p[3])
    out["full_contact"] = False
    out["contact_fraction"] = float(sum(p[1] - p[0] for p in patches))
    if len(patches) == 1:
        xt, xl, _, cen = patches[0]
        out.update(ka=math.pi * (xl - xt), ke=_TWO_PI * 0.5 * (xt + xl), ke_hat=_TWO_PI * cen)
    else:
        out.update(ka=None, ke=None, ke_hat=None)
    return out, patches, fitted


# --------------------------------------------------------------------------------------------
# Levels, shifts and Richardson's extrapolation
# --------------------------------------------------------------------------------------------
#: scalars averaged and extrapolated; the first four have relative error estimates
_RELATIVE = ("penetration", "tau_f", "mu", "contact_fraction")
_ABSOLUTE = ("ka", "ke", "ke_hat")
_KEYS = ("load",) + _RELATIVE + _ABSOLUTE
#: added to every estimate (in the scalar's own units, before the relative ones are divided by
#: the value): what the level and shift differences cannot see.  The edge fit has a model
#: error that does not shrink with h (its window is a fixed fraction of the contact): measured
#: on the exact gap of the semi-analytic solution, up to 2e-9 λ per edge, so 4e-9 in the
#: contact fraction and ~1e-8 in ka and ke; the others, rounding of their scale
_FLOOR = {"load": 1e-13, "penetration": 1e-13, "tau_f": 1e-13, "mu": 1e-13,
          "contact_fraction": 4e-9, "ka": 1e-8, "ke": 1e-8, "ke_hat": 1e-12}


def _level(n, shifts, mat, w, hk, control, value, patches, factor=None, thickness=None):
    """One level: the same N on `shifts` shifted grids, averaged (trapezoidal rule in φ).

    ``factor``: the layer factor S of the modes 0, 1, … (at least N/2 + 1 of them) and
    ``thickness`` d/λ of the layer (None, None: the half-space)."""
    reach = None
    if factor is not None:
        factor = factor[:n // 2 + 1]
        reach = _FIT_LAYER * thickness * n
    rows, pats, grids = [], [], []
    fitted = True
    jplus, terms = mat.creep_terms()
    creep = (jplus, tuple((j, w * t / _TWO_PI) for j, t in terms))  # lengths L_i in x/λ
    for k in range(shifts):
        grid = _solve_grid(n, k / shifts, mat, w, hk, control, value, patches, factor)
        grids.append(grid)
        if not grid.converged:
            break
        sc, pt, ok = _grid_scalars(grid, mat, w, hk, creep, factor, reach)
        fitted &= ok
        rows.append(sc)
        pats.append(pt)
        if pt:
            patches = [(p[0], p[1]) for p in pt]   # starts the next shift
    out = {"nodes": n, "nit": sum(g.nit for g in grids),
           "converged": all(g.converged for g in grids),
           "complementarity": max(g.complementarity for g in grids),
           "fitted": fitted, "grid": grids[0], "patches": patches, "message": ""}
    if not out["converged"]:
        out["message"] = (f"the active set did not converge on a grid of {n} points (shift "
                          f"{grids[-1].phi:g}) after {grids[-1].nit} steps")
        return out
    counts = {len(p) for p in pats}
    full = {r["full_contact"] for r in rows}
    if counts == {0}:
        out["message"] = f"no contact on the grids of {n} points (penetration below their reach)"
        return out
    if len(counts) > 1 or len(full) > 1:
        out["message"] = (f"the shifted grids of {n} points disagree on the contact "
                          f"({sorted(counts)} patches, full contact {sorted(full)}): a contact "
                          "or a gap narrower than a few spacings, or a point within a spacing "
                          "of a change in the number of patches")
        return out
    avg, half = {}, {}
    for key in _KEYS:
        vals = [r[key] for r in rows]
        if any(v is None for v in vals):
            avg[key] = half[key] = None
            continue
        avg[key] = math.fsum(vals) / len(vals)
        even = vals[::2]
        half[key] = math.fsum(even) / len(even)
    avg["full_contact"] = rows[0]["full_contact"]
    # patches averaged over the shifts (they are sorted by centroid on every grid)
    npat = len(pats[0])
    out["avg_patches"] = [tuple(math.fsum(p[i][j] for p in pats) / len(pats) for j in range(4))
                          for i in range(npat)]
    out["scalars"], out["half"] = avg, half
    return out


def richardson(nodes, values):
    """Richardson's extrapolation of a sequence of levels, with its observed order.

    Parameters
    ----------
    nodes : sequence of int
        Points per period, increasing.
    values : sequence of float
        The scalar on each level.

    Returns
    -------
    value, estimate, order, extrapolated : float, float, float, bool
        ``order`` is the order p = log(d₁/d₂)/log(N₃/N₂) shown by the last three levels (d₁,
        d₂ their differences; NaN when undefined).  The extrapolation q₃ + d₂/((N₃/N₂)^p − 1)
        is returned only when it is trustworthy: four levels or more, the last three
        differences of one sign and shrinking, and the orders of the last two triples within
        0.5 of each other, in [0.5, 8].  Its estimate is then the larger of the correction and
        the change from the extrapolation one level coarser.  Otherwise the finest value is
        returned, ``extrapolated`` False, with the larger of the last difference and the one
        before it over (N₃/N₂)² as its estimate.
    """
    q = [float(v) for v in values]
    ns = [float(v) for v in nodes]
    if len(q) < 2:
        return q[-1], math.nan, math.nan, False
    d2 = q[-1] - q[-2]
    if len(q) < 3:
        return q[-1], abs(d2), math.nan, False

    def triple(a, b, c, nb, nc):
        e1, e2 = b - a, c - b
        if e1 == 0.0 or e2 == 0.0:
            return math.nan, math.nan
        p = math.log(abs(e1 / e2)) / math.log(nc / nb)
        if e1 / e2 <= 1.0:
            return p, math.nan
        return p, c + e2 / ((nc / nb) ** p - 1.0)

    order, value = triple(*q[-3:], *ns[-2:])
    # without a trustworthy order: the last difference, or the one before it over
    # (N₃/N₂)² (the error it implies for the finest level at second order) if larger,
    # which covers a last difference that is small by chance (errors that oscillate)
    plain = max(abs(d2), abs(q[-2] - q[-3]) / (ns[-1] / ns[-2]) ** 2)
    if len(q) < 4 or not math.isfinite(value):
        return q[-1], plain, order, False
    order0, value0 = triple(*q[-4:-1], *ns[-3:-1])
    if not (math.isfinite(value0) and 0.5 <= order <= 8.0 and 0.5 <= order0 <= 8.0
            and abs(order - order0) <= 0.5):
        return q[-1], plain, order, False
    return value, max(abs(value - q[-1]), abs(value - value0)), order, True


# --------------------------------------------------------------------------------------------
# The result and the solver
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class FourierResult:
    """One operating point of the Fourier reference (a SciPy-like result object).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (every grid converged, the grids agree on the contact, the
        scalars are finite), 0 or 1, what the solver says, caveats (tuple of str).
    control, asked
        ``"load"`` or ``"penetration"`` and the value asked for.
    load, speed, hk, material
        p̃ (E_ref/(1 − ν²); an output under penetration control), w = V τ_ref k, hk, and the
        material as plain numbers (``form``, ``base``, ``amplitudes``, ``times``).
    full_contact, contact_fraction, ka, ke, ke_hat, penetration, separation, tau_f, mu
        The scalars of the conventions (``ke`` None in full contact; ``ka``, ``ke``, ``ke_hat``
        None with several patches); separation s/h = 1 − Δ/h.
    error_estimate : dict
        Estimated error of each scalar: relative for penetration, tau_f, mu, contact_fraction;
        absolute for ka, ke, ke_hat.  The larger of the Richardson estimate (see `richardson`)
        and the change of the finest level's average when half of its shifts are dropped.
    observed_order, extrapolated : dict
        Per scalar: the order shown by the last three levels and whether the extrapolated value
        is the one reported (else the finest level's average).
    levels : tuple of dict
        Per level: ``nodes``, the shift-averaged ``scalars``, ``nit`` (active-set steps over
        all shifts), ``complementarity`` (worst of −min σ/max σ and −min gap/hk).
    nodes, shifts : tuple of int, int
        The levels asked for and the grids per level.
    patches : tuple of dict
        Per patch (finest level, shift-averaged): ``trailing_edge``, ``leading_edge``,
        ``width`` (x/λ), ``load`` (its share of p̃), ``centroid`` (x/λ).
    x_over_lambda, pressure, gap, displacement : ndarray
        Fields of the finest level's unshifted grid: σ (E_ref/(1 − ν²)), gap/h and v/h (from the
        mean line of the deformed surface); in full contact the closed form on 1024 points.
    elapsed : float
        Wall time of the solve, seconds.
    layer : dict or None
        None on the half-space; on a layer its description: ``thickness`` (k d),
        ``thickness_over_wavelength`` (d/λ), ``foundation``, ``nu``, ``uniform_compliance`` (C
        of the uniform mode) and ``factor_mode_1`` (S(k d)).
    mean_displacement, approach : float or None
        On a layer (None on the half-space): v̄_0/h, the mean displacement of the top face
        under the mean pressure (k v̄_0 = C (k d) J0 p̃, relaxed J0), and Δ/h + v̄_0/h, the
        indenter's approach from the undeformed top face over h (the BEM's
        ``diagnostics["layer"]``).  Their relative estimates are in ``error_estimate``.
    """

    success: bool
    status: int
    message: str
    control: str
    asked: float
    load: float
    speed: float
    hk: float
    material: dict
    full_contact: bool
    contact_fraction: float
    ka: float | None
    ke: float | None
    ke_hat: float | None
    penetration: float
    separation: float
    tau_f: float
    mu: float
    error_estimate: dict
    observed_order: dict
    extrapolated: dict
    levels: tuple
    nodes: tuple
    shifts: int
    patches: tuple
    x_over_lambda: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    elapsed: float = 0.0
    warnings: tuple = ()
    layer: dict | None = None
    mean_displacement: float | None = None
    approach: float | None = None

    def scalars(self):
        """The eight scalars of the conventions, as a dict."""
        return {"full_contact": self.full_contact, "contact_fraction": self.contact_fraction,
                "ka": self.ka, "ke": self.ke, "ke_hat": self.ke_hat,
                "penetration": self.penetration, "tau_f": self.tau_f, "mu": self.mu}

    def as_dict(self):
        """Everything but the fields, as plain Python values (non-finite floats as None)."""
        def plain(v):
            if isinstance(v, dict):
                return {str(k): plain(x) for k, x in v.items()}
            if isinstance(v, (list, tuple)):
                return [plain(x) for x in v]
            if isinstance(v, (bool, np.bool_)):
                return bool(v)
            if isinstance(v, (int, np.integer)):
                return int(v)
            if isinstance(v, (float, np.floating)):
                return float(v) if math.isfinite(v) else None
            return v
        out = {"solver": "fourier", "success": self.success, "status": self.status,
               "message": self.message, "warnings": list(self.warnings),
               "control": self.control, "asked": self.asked, "load": self.load,
               "speed": self.speed, "hk": self.hk, "material": self.material,
               "separation": self.separation}
        out.update(self.scalars())
        out.update({"error_estimate": self.error_estimate, "observed_order": self.observed_order,
                    "extrapolated": self.extrapolated, "nodes": self.nodes,
                    "shifts": self.shifts, "patches": self.patches, "elapsed": self.elapsed,
                    "levels": [{k: v for k, v in lv.items()} for lv in self.levels]})
        if self.layer is not None:  # the half-space's record is unchanged
            out.update({"layer": self.layer, "mean_displacement": self.mean_displacement,
                        "approach": self.approach})
        return plain(out)


def _check_nodes(nodes):
    seq = [nodes] if is_integer(nodes) else nodes
    allowed = (f"an even number of points per period in [{MIN_NODES}, {MAX_NODES}], or an "
               "increasing sequence of them (three or more for Richardson's extrapolation)")
    try:
        seq = list(seq)
    except TypeError:
        raise bad("nodes", nodes, allowed) from None
    if not seq or not all(is_integer(v) and MIN_NODES <= v <= MAX_NODES and v % 2 == 0
                          for v in seq):
        raise bad("nodes", nodes, allowed)
    if any(b <= a for a, b in zip(seq[:-1], seq[1:])):
        raise bad("nodes", nodes, allowed)
    return tuple(int(v) for v in seq)


def _westergaard_start(control, value, hk, e1):
    """Patches [(x_t, x_l)] of Westergaard's solution with the modulus |E*(1)| (a start only)."""
    if control == "load":
        s = min(value / (0.5 * hk * abs(e1)), 0.999)
    else:
        s = value                       # invert Δ/h = s(1 − ln s) by fixed point
        for _ in range(60):
            s = min(value / (1.0 - math.log(max(s, 1e-300))), 0.999)
    half = 2.0 * math.asin(math.sqrt(s)) / _TWO_PI
    return [(-half, half)]


def memory_resolution(speed, nodes, **material_kw):
    """Shortest memory layer of the material and whether `nodes` points per period resolve it.

    Behind the leading edge the pressure relaxes over L = w θ/(2π) wavelengths for each
    relaxation time θ of the series (θ = τ E0/E∞ for the standard linear solid).  A grid with
    fewer than `MIN_LAYER_POINTS` points across the shortest such layer leaves a sawtooth in the
    pressure there, misses part of the dissipation (the modes beyond N/2 with Im J* ∝ n w) and
    moves the contact edges by a fraction of L; the measured errors then exceed the estimates.

    Parameters
    ----------
    speed : float
        w = V τ_ref k ≥ 0.
    nodes : int
        Points per period of the finest grid.
    **material_kw
        ratio, creep or relaxation, as in `material`.

    Returns
    -------
    length, resolved : float, bool
        The shortest layer w θ_min/(2π) (x/λ; inf without memory or at rest) and whether
        ``length * nodes >= MIN_LAYER_POINTS``.
    """
    w = real("speed", speed, "a finite speed w = V τ_ref k ≥ 0", lambda v: v >= 0.0)
    thetas = material(**material_kw).relaxation_times()
    if w == 0.0 or not thetas:
        return math.inf, True
    length = w * min(thetas) / _TWO_PI
    return length, length * nodes >= MIN_LAYER_POINTS


def thickness_resolution(thickness, nodes):
    """The thickness d/λ of a layer and whether `nodes` points per period resolve it.

    d is a length of the solution: the layer's kernel differs from the half-space's by a part
    that is smooth over d only (S − 1 decays like e^{−2|n|kd}), so the pressure of a thin
    layer's contact changes its form over d at the edges (from the half-space's square root
    to the thin layer's own), and the edge fit, whose expansion about an edge converges
    within about 2d, is narrowed to d/2 (`_FIT_LAYER`) once the grid has the points.  A grid
    with fewer than `MIN_THICKNESS_POINTS` points across d is not trusted (measured against
    the BEM: see the constant).

    Parameters
    ----------
    thickness : float
        k d > 0.
    nodes : int
        Points per period of the finest grid.

    Returns
    -------
    length, resolved : float, bool
        d/λ and whether ``length * nodes >= MIN_THICKNESS_POINTS``.
    """
    kd = real("thickness", thickness, "a finite thickness k d > 0", lambda v: v > 0.0,
              kind=True)
    length = kd / _TWO_PI
    return length, length * nodes >= MIN_THICKNESS_POINTS


def fourier_solve(*, load=None, penetration=None, speed, ratio=None, creep=None,
                  relaxation=None, hk=1.0, nodes=NODES, shifts=SHIFTS, require_resolved=True,
                  layer=None):
    """Steady sliding of the sinusoid over any Prony-series material, by Fourier collocation.

    Parameters
    ----------
    load : float, optional
        Mean pressure p̃ = p∞(1 − ν²)/E_ref > 0 (load control).
    penetration : float, optional
        Δ/h in (0, 1] (penetration control; the load is an output; at 1 the smallest load of
        full contact).  Give exactly one of the two.
    speed : float
        w = V τ_ref k ≥ 0 (V/V0 for the standard linear solid; 0 is the relaxed elastic solid).
    ratio, creep, relaxation
        The material, at most one (default ratio 3): see `material`.
    hk : float
        Amplitude h k > 0 of k y = hk cos(2πX).
    nodes : int or sequence of int
        Points per period of the levels (even, 64 … 8192, increasing); default
        (1024, 2048, 4096, 8192).
    shifts : int
        Grids per level, shifted by 1/shifts of a spacing and averaged (1 … 64); default 16.
    require_resolved : bool
        True (default): a point whose shortest memory layer (`memory_resolution`) or whose
        layer thickness (`thickness_resolution`) the finest grid does not resolve is not
        solved and the result is not a success.  False solves it anyway, with a warning: its
        errors may then exceed the estimates.  Full contact (closed form) is exempt.
    layer : mapping, optional
        A layer of thickness d on a rigid foundation in place of the half-space:
        ``{"thickness": k d (finite, > 0), "foundation": "bonded" (u_x = u_z = 0 at the
        bottom) or "frictionless" (u_z = 0 and no shear there), "nu": ν in (−1, 0.5]}``.
        Mode n of the operator is the half-space's times S(|n| k d, ν) (`layer_factor`); the
        scalars keep their meaning and the result adds ``layer``, ``mean_displacement`` and
        ``approach``.  None (default): the half-space, answered exactly as without it.

    Returns
    -------
    FourierResult
        ``success`` False, with the reason in ``message``, when the memory or the layer is not
        resolved, a grid did not converge or the grids disagree on the contact (a point within
        a grid spacing of a transition); never raises for valid input.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: ..."`` for the first bad input.

    References
    ----------
    Eqs (2.2)–(2.5), (3.1) and Appendix B of Menga, Putignano, Carbone & Demelio, Proc. R.
    Soc. A 470, 20140392, 2014; the layer: Menga, Afferrante & Carbone, J. Mech. Phys. Solids
    95 (2016) 517–529.
    """
    t0 = time.perf_counter()
    if (load is None) == (penetration is None):
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
    if load is not None:
        control = "load"
        value = real("load", load, "a finite mean pressure p̃ > 0", lambda v: v > 0.0)
    else:
        control = "penetration"
        value = real("penetration", penetration, "a finite penetration Δ/h in (0, 1]",
                      lambda v: 0.0 < v <= 1.0)
    w = real("speed", speed, "a finite speed w = V τ_ref k ≥ 0", lambda v: v >= 0.0)
    hk = real("hk", hk, "a finite amplitude hk > 0", lambda v: v > 0.0)
    mat = material(ratio=ratio, creep=creep, relaxation=relaxation)
    levels_n = _check_nodes(nodes)
    shifts = integer("shifts", shifts, "an integer number of shifted grids per level in [1, 64]",
                     lambda v: 1 <= v <= 64)
    if not isinstance(require_resolved, bool):
        raise bad("require_resolved", require_resolved, "True or False")
    lay = check_layer(layer)
    kw = _material_kw(mat)
    fc = full_contact(w, hk=hk, layer=lay, **kw)
    common = {"control": control, "asked": value, "speed": w, "hk": hk,
              "material": mat.as_dict(), "nodes": levels_n, "shifts": shifts}
    if lay is not None:
        common["layer"] = describe(lay)
    if control == "load" and value >= fc["load_threshold"]:
        return _on_layer(_full_result(value, fc, common, t0), lay, mat)
    if control == "penetration" and value == 1.0:
        return _on_layer(_full_result(fc["load_threshold"], fc, common, t0), lay, mat)
    warnings = []
    length, resolved = memory_resolution(w, levels_n[-1], **kw)
    unresolved = []
    if not resolved:
        unresolved.append(f"the shortest memory layer, w θ_min/(2π) = {length:.3g} λ, spans "
                          f"{length * levels_n[-1]:.3g} points of the finest grid "
                          f"({levels_n[-1]}), under the {MIN_LAYER_POINTS} that resolve it")
    factor = thickness = None
    if lay is not None:
        d, resolved = thickness_resolution(lay["thickness"], levels_n[-1])
        if not resolved:
            unresolved.append(f"the layer's thickness, d = {d:.3g} λ, spans "
                              f"{d * levels_n[-1]:.3g} points of the finest grid "
                              f"({levels_n[-1]}), under the {MIN_THICKNESS_POINTS} that "
                              "resolve it")
        thickness = d
        top = max(levels_n[-1], _START_NODES) // 2
        factor = layer_factor(np.arange(top + 1) * lay["thickness"], lay["nu"],
                              lay["foundation"])
    for text in unresolved:
        if require_resolved:
            return _on_layer(_failed(common, text + "; not solved (require_resolved=False "
                                     "solves it, with errors that may exceed the estimates)",
                                     [], t0), lay, mat)
        warnings.append(text + ": errors may exceed the estimates")
    # the start: Westergaard's contact with mode 1's modulus (the layer's, |E*(1)|/S(kd))
    e1 = fc["modulus"] if lay is None else fc["modulus"] / fc["layer_factor"]
    patches = _westergaard_start(control, value, hk, e1)
    target = value if control == "load" else hk * (1.0 - value)   # the load, or s in 1/k
    if levels_n[0] > _START_NODES:
        start = _level(_START_NODES, 1, mat, w, hk, control, target, patches, factor,
                       thickness)
        if start["patches"]:
            patches = start["patches"]
    levels = []
    for n in levels_n:
        lv = _level(n, shifts, mat, w, hk, control, target, patches, factor, thickness)
        levels.append(lv)
        if lv["message"]:
            return _on_layer(_failed(common, lv["message"], levels, t0), lay, mat)
        patches = [(p[0], p[1]) for p in lv["avg_patches"]]
    return _on_layer(_partial_result(levels, common, warnings, t0), lay, mat)


def _on_layer(res, lay, mat):
    """The result with the layer's uniform mode: ``mean_displacement`` v̄_0/h (k v̄_0 =
    C (k d) J0 p̃) and ``approach`` Δ/h + v̄_0/h, with their relative estimates (v̄_0 ∝ p̃, so
    the load's; the approach's from the two absolute errors).  The half-space: unchanged."""
    if lay is None:
        return res
    mean = _mean_displacement(lay, mat, res.load, res.hk)
    approach = res.penetration + mean
    est = dict(res.error_estimate)
    if "penetration" in est:   # a solved point (full contact: exact, the load's estimate 0)
        est.setdefault("load", 0.0)
        est["mean_displacement"] = est["load"]
        est["approach"] = ((est["penetration"] * abs(res.penetration) + est["load"] * abs(mean))
                           / abs(approach) if approach != 0.0 else math.inf)
    warnings = res.warnings
    if approach * res.hk >= lay["thickness"]:
        # linear theory has no such limit (the answer stands), the body has
        warnings += (f"the indenter's approach {approach:.4g} h reaches the foundation at "
                     f"d = {lay['thickness'] / res.hk:.4g} h (k d = {lay['thickness']:g}, "
                     f"hk = {res.hk:g}): small strains no longer hold",)
    return dataclasses.replace(res, mean_displacement=mean, approach=approach,
                               error_estimate=est, warnings=warnings)


def _material_kw(mat):
    key = "creep" if mat.form == "creep" else "relaxation"
    return {key: (mat.base, mat.amps, mat.times)}


def _level_summary(lv):
    return {"nodes": lv["nodes"], "scalars": lv.get("scalars"), "nit": lv["nit"],
            "complementarity": lv["complementarity"], "converged": lv["converged"]}


def _fields(grid, hk):
    disp = (grid.gap + hk * np.cos(_TWO_PI * grid.x) - grid.s) / hk   # v = gap + y − s
    return {"x_over_lambda": grid.x.copy(), "pressure": grid.sigma.copy(),
            "gap": grid.gap / hk, "displacement": disp}


def _failed(common, message, levels, t0):
    nan = math.nan
    grid = levels[-1]["grid"] if levels else None
    fields = _fields(grid, common["hk"]) if grid is not None else \
        {k: np.zeros(0) for k in ("x_over_lambda", "pressure", "gap", "displacement")}
    return FourierResult(success=False, status=1, message=message,
                         load=common["asked"] if common["control"] == "load" else nan,
                         full_contact=False, contact_fraction=nan, ka=nan, ke=nan, ke_hat=nan,
                         penetration=nan, separation=nan, tau_f=nan, mu=nan, error_estimate={},
                         observed_order={}, extrapolated={},
                         levels=tuple(_level_summary(lv) for lv in levels), patches=(),
                         elapsed=time.perf_counter() - t0, **fields, **common)


def _full_result(p, fc, common, t0):
    """Appendix B in closed form: exact, so every estimate is zero."""
    hk = common["hk"]
    x = np.arange(1024) / 1024 - 0.5
    e1 = fc["modulus"]
    amplitude = 0.5 * hk * abs(e1)
    if "layer_factor" in fc:
        amplitude = amplitude / fc["layer_factor"]   # σ̂_1 = (hk/4) E*(1)/S
    sigma = p + amplitude * np.cos(_TWO_PI * x + math.atan2(e1.imag, e1.real))
    zero = {k: 0.0 for k in _RELATIVE + ("ka", "ke_hat")}
    centroid = _wrap(fc["ke_hat"] / _TWO_PI)
    patch = {"trailing_edge": centroid - 0.5, "leading_edge": centroid + 0.5, "width": 1.0,
             "load": p, "centroid": centroid}
    return FourierResult(success=True, status=0, message="full contact (closed form)",
                         load=p, full_contact=True, contact_fraction=1.0, ka=math.pi, ke=None,
                         ke_hat=fc["ke_hat"], penetration=1.0, separation=0.0,
                         tau_f=fc["tau_f"], mu=fc["tau_f"] / p, error_estimate=zero,
                         observed_order={}, extrapolated={}, levels=(), patches=(patch,),
                         x_over_lambda=x, pressure=sigma, gap=np.zeros_like(x),
                         displacement=np.cos(_TWO_PI * x), elapsed=time.perf_counter() - t0,
                         **common)


def _partial_result(levels, common, warnings, t0):
    ns = [lv["nodes"] for lv in levels]
    fin = levels[-1]
    sc = fin["scalars"]
    hk = common["hk"]
    values, est, order, extra = {}, {}, {}, {}
    keys = _KEYS if common["control"] == "penetration" else _KEYS[1:]
    for key in keys:
        seq = [lv["scalars"][key] for lv in levels]
        if any(v is None for v in seq):
            values[key] = None
            continue
        v, e, p, x = richardson(ns, seq)
        # plus the change of the finest average when every other shift is dropped (the
        # trapezoidal rule over the shift, whose error the level differences also carry)
        e = (e if math.isfinite(e) else 0.0) + abs(sc[key] - fin["half"][key]) + _FLOOR[key]
        if key in _RELATIVE or key == "load":
            e = e / abs(v) if v != 0.0 else math.inf
        values[key], est[key], order[key], extra[key] = v, e, p, x
    # the control is exact
    exact = "load" if common["control"] == "load" else "penetration"
    values[exact], est[exact], extra[exact] = common["asked"], 0.0, False
    ok = all(lv["converged"] for lv in levels)
    worst = max(lv["complementarity"] for lv in levels)
    message = "partial contact"
    narrowest = min(p[1] - p[0] for p in fin["avg_patches"]) * ns[-1]
    if not ok:
        message = "the active set did not converge on some grid; not an answer"
    elif not all(math.isfinite(values[k]) for k in values if values[k] is not None):
        ok, message = False, "non-finite scalars; not an answer"
    elif narrowest < _MIN_PATCH_POINTS:
        ok, message = False, (f"a contact patch spans {narrowest:.3g} points of the finest grid "
                              f"({ns[-1]}), under {_MIN_PATCH_POINTS}: not an answer")
    elif narrowest < 4 * _MIN_PATCH_POINTS:
        warnings.append(f"a contact patch spans only {narrowest:.3g} points of the finest grid: "
                        "its edges and the scalars carry large errors (see error_estimate)")
    if worst > 1e-9:
        warnings.append(f"complementarity residual {worst:.1e} on some grid")
    if not all(lv["fitted"] for lv in levels):
        warnings.append("a gap region too narrow for the edge fit: edges from two points "
                        "(first order)")
    patches = tuple({"trailing_edge": _wrap(p[0]), "leading_edge": _wrap(p[0]) + (p[1] - p[0]),
                     "width": p[1] - p[0], "load": p[2], "centroid": _wrap(p[3])}
                    for p in fin["avg_patches"])
    if len(patches) > 1:
        warnings.append(f"{len(patches)} contact patches: ka, ke, ke_hat are None")
    pen = values["penetration"]
    return FourierResult(success=ok, status=0 if ok else 1, message=message,
                         load=values["load"], full_contact=False,
                         contact_fraction=values["contact_fraction"], ka=values.get("ka"),
                         ke=values.get("ke"), ke_hat=values.get("ke_hat"), penetration=pen,
                         separation=1.0 - pen, tau_f=values["tau_f"], mu=values["mu"],
                         error_estimate=est, observed_order=order, extrapolated=extra,
                         levels=tuple(_level_summary(lv) for lv in levels), patches=patches,
                         elapsed=time.perf_counter() - t0, warnings=tuple(warnings),
                         **_fields(fin["grid"], hk), **common)
