"""Persson's theory of rubber friction for a rigid, isotropic, self-affine rough surface sliding
steadily over a linear viscoelastic half-space.

The theory (Persson, J. Chem. Phys. 115, 3840, 2001) gives the friction coefficient from the
power spectrum C(q) of the surface and the complex modulus E(ω) of the solid, through the
fraction P(q) of the nominal area that is in contact when the surface is seen with its
roughness cut off above the wavenumber q; the contact-area correction S(q) = γ + (1 − γ)P(q)²
(Persson, J. Phys.: Condens. Matter 18, 7789, 2006) is applied by default with γ = `GAMMA`.
The formulas, the choices made and the limits of the theory are in ``docs/persson.md``.

Units, stated once (the project's, for surfaces): lengths over the cell length Lx,
wavenumbers in k = 2π/Lx (the cell's lowest wavenumber is 1), heights as k·z, pressures and
moduli in E0/(1 − ν²) (E0 the relaxed modulus), times in τ_ref (the creep time of the standard
linear solid).  Inputs: load p̃ = p∞(1 − ν²)/E0 (mean pressure over the cell), speed
w = V τ_ref k, ratio E∞/E0 or a creep series ``material = (J0, J, tau)`` (compliances in
(1 − ν²)/E0, times in τ_ref).  `ACCEPTED` lists the range of every input and why.

Sign convention, where it bites: the project's compliance of a mode loaded at the signed
frequency-variable n (n = q·ê for a wave vector q sliding along ê) is
J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i), with Im J* > 0 for n > 0.  Persson writes the modulus
with the engineering sign, Im E(ω) > 0 for ω > 0; the two are related by
E(ω = n w)/(1 − ν²) = 1/conj(J*(n)).  Taken without the conjugate, 1/J* would give a friction
of the wrong sign; with it, μ > 0 (it resists the motion).

The angular averages of the modulus over the sliding direction are done in closed form from the
relaxation (generalised Maxwell) form of the material (`angular_averages`); the integrals over
|q| by composite Gauss–Legendre quadrature in ln q, with the cumulative integral G(q) on the same
nodes (a spectral integration matrix) and panels refined geometrically at the start of each
smooth piece of C(q), where P(q) falls from 1 (`solve`).

This module never imports `bem` (the two roads are independent).

References
----------
B. N. J. Persson, J. Chem. Phys. 115, 3840 (2001): eqs for μ, P(q) = erf(1/(2√G)) and G(q).
B. N. J. Persson, J. Phys.: Condens. Matter 18, 7789 (2006): the correction factor S(q).
M. Scaraggi & B. N. J. Persson, J. Chem. Phys. 143, 224111 (2015): the theory restated, with S(q).
B. N. J. Persson, O. Albohr, U. Tartaglino, A. I. Volokitin & E. Tosatti, J. Phys.: Condens.
Matter 17, R1 (2005): the normalisation ⟨h²⟩ = ∫ d²q C(q) and self-affine spectra.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from numpy.polynomial import legendre
from scipy.special import erf

import viscosine
from viscosine.checks import bad, check_reals, is_integer, is_real, real, series
from viscosine.materials import Maxwell
from viscosine.protocol import plain

#: γ of the area correction S(q) = γ + (1 − γ)P(q)² (area_correction=True)
GAMMA = 0.45
#: the largest wavenumber accepted (in k = 2π/Lx): 12 decades of roughness
Q_MAX = 1e12
#: loads outside [LOAD_MIN, LOAD_MAX] are refused
LOAD_MIN, LOAD_MAX = 1e-12, 1e12
#: nonzero speeds outside [SPEED_MIN, SPEED_MAX] are refused (0 is the elastic limit with E0)
SPEED_MIN, SPEED_MAX = 1e-30, 1e30
RATIO_MAX = 1e4
#: bounds of rms_slope and rms_height
RMS_MIN, RMS_MAX = 1e-12, 1e6
#: default quadrature: Gauss–Legendre nodes per panel and the widest panel in ln q
NODES, WIDTH = 20, 0.5
#: a result whose estimated quadrature error (relative for μ, absolute for A/A0) exceeds this
#: is not an answer
TOLERANCE = 1e-8

#: name -> (low, high, what is allowed and why); inclusive unless a test in `_TESTS` says not
ACCEPTED = {
    "load": (LOAD_MIN, LOAD_MAX,
             f"a mean pressure p̃ = p∞(1 − ν²)/E0 in [{LOAD_MIN:g}, {LOAD_MAX:g}]: the range the "
             "quadrature is tested on, from A/A0 ~ 1e-12 to full contact"),
    "speed": (0.0, SPEED_MAX,
              f"w = Vτk equal to 0 (elastic, E0) or in [{SPEED_MIN:g}, {SPEED_MAX:g}]: beyond, "
              "every accepted wavenumber sees the relaxed (or glassy) modulus to rounding"),
    "hurst": (0.0, 1.0, "a Hurst exponent H with 0 < H < 1 (a self-affine surface)"),
    "long_cutoff": (1.0, Q_MAX,
                    f"a long-wavelength cut-off q_l in [1, {Q_MAX:g}] (in k = 2π/Lx: the cell's "
                    "lowest wavenumber is 1)"),
    "rolloff": (1.0, Q_MAX, f"a roll-off wavenumber q_r with long_cutoff ≤ q_r ≤ {Q_MAX:g}"),
    "short_cutoff": (1.0, Q_MAX,
                     f"a short-wavelength cut-off q_s with q_s ≥ rolloff, q_s > long_cutoff and "
                     f"q_s ≤ {Q_MAX:g}"),
    "rms_slope": (RMS_MIN, RMS_MAX,
                  f"an rms slope sqrt(∫ d²q q² C) in [{RMS_MIN:g}, {RMS_MAX:g}] (the theory "
                  "itself assumes it small)"),
    "rms_height": (RMS_MIN, RMS_MAX,
                   f"an rms height k·z_rms in [{RMS_MIN:g}, {RMS_MAX:g}]"),
    "ratio": (1.0, RATIO_MAX,
              f"E∞/E0 > 1 and ≤ {RATIO_MAX:g} (the standard linear solid; 1 would be elastic)"),
}
_TESTS = {"speed": lambda v: v == 0.0 or SPEED_MIN <= v <= SPEED_MAX,
          "hurst": lambda v: 0.0 < v < 1.0,
          "ratio": lambda v: 1.0 < v <= RATIO_MAX}


# --------------------------------------------------------------------------
# The surface: an isotropic self-affine power spectrum
# --------------------------------------------------------------------------
def _grow(e, span):
    """(exp(e·span) − 1)/e, and span when e = 0: ∫_0^span exp(e t) dt without cancellation."""
    return span if e == 0.0 else math.expm1(e * span) / e


@dataclass(frozen=True)
class Spectrum:
    """An isotropic self-affine power spectrum C(q), normalised as ⟨z²⟩ = ∫ d²q C(q).

    C(q) = c0 for q_l ≤ q < q_r, c0 (q/q_r)^(−2(1+H)) for q_r ≤ q ≤ q_s, and 0 elsewhere
    (wavenumbers in k = 2π/Lx and heights as k·z, so that C here is k⁴ times the dimensional
    spectrum).
    Build it with `spectrum`, which validates and normalises.

    Attributes
    ----------
    hurst : float
        H in (0, 1).
    long_cutoff, rolloff, short_cutoff : float
        q_l ≤ q_r ≤ q_s, with q_l < q_s.
    c0 : float
        The plateau C(q_l ≤ q < q_r) (and C(q_r)).
    """

    hurst: float
    long_cutoff: float
    rolloff: float
    short_cutoff: float
    c0: float

    def __call__(self, q):
        """C(q) at wavenumbers q (array_like, in k); 0 outside [q_l, q_s]."""
        q = np.asarray(q, dtype=float)
        out = np.zeros(q.shape)
        flat = (q >= self.long_cutoff) & (q < self.rolloff)
        power = (q >= self.rolloff) & (q <= self.short_cutoff)
        out[flat] = self.c0
        out[power] = self.c0 * (q[power] / self.rolloff) ** (-2.0 * (1.0 + self.hurst))
        return out

    def moment(self, order):
        """∫ d²q q^order C(q) = 2π ∫ q^(order+1) C(q) dq, in closed form.

        ``order`` 0 gives ⟨(kz)²⟩, 2 the mean square slope ⟨|∇z|²⟩ and 4 the mean square
        Laplacian ⟨(∇²z)²⟩ (lengths over 1/k).
        """
        a = float(order) + 2.0
        ql, qr, qs = self.long_cutoff, self.rolloff, self.short_cutoff
        flat = ql ** a * _grow(a, math.log(qr / ql))       # ∫_{q_l}^{q_r} q^(order+1) dq
        power = qr ** a * _grow(a - 2.0 - 2.0 * self.hurst, math.log(qs / qr))
        return 2.0 * math.pi * self.c0 * (flat + power)

    @property
    def rms_height(self):
        """k·z_rms = sqrt(∫ d²q C)."""
        return math.sqrt(self.moment(0))

    @property
    def rms_slope(self):
        """sqrt⟨|∇z|²⟩ = sqrt(∫ d²q q² C) (dimensionless)."""
        return math.sqrt(self.moment(2))

    @property
    def rms_curvature(self):
        """sqrt⟨(∇²z)²⟩ = sqrt(∫ d²q q⁴ C), in k: the rms Laplacian (twice the rms mean
        curvature; the rms of one directional second derivative is sqrt(3/8) of it)."""
        return math.sqrt(self.moment(4))


def spectrum(*, hurst, rolloff, short_cutoff, long_cutoff=1.0, rms_slope=None, rms_height=None):
    """The validated, normalised `Spectrum`.

    Parameters
    ----------
    hurst : float
        H in (0, 1).
    rolloff, short_cutoff, long_cutoff : float
        q_r, q_s and q_l in k = 2π/Lx: 1 ≤ q_l ≤ q_r ≤ q_s ≤ `Q_MAX`, q_l < q_s.
    rms_slope, rms_height : float
        Exactly one: sqrt(∫ d²q q² C) (dimensionless) or k·z_rms.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: ..."`` for the first bad input.
    """
    if (rms_slope is None) == (rms_height is None):
        raise ValueError(f"rms_slope={rms_slope!r}, rms_height={rms_height!r} is not allowed: "
                         "give exactly one of rms_slope and rms_height")
    v = check_reals(ACCEPTED, (("hurst", hurst), ("long_cutoff", long_cutoff),
                               ("rolloff", rolloff), ("short_cutoff", short_cutoff),
                               ("rms_slope", rms_slope), ("rms_height", rms_height)), _TESTS)
    ql, qr, qs = v["long_cutoff"], v["rolloff"], v["short_cutoff"]
    if qr < ql:
        raise bad("rolloff", qr, f"q_r ≥ long_cutoff = {ql!r} (and ≤ {Q_MAX:g})")
    if qs < qr or qs <= ql:
        raise bad("short_cutoff", qs, f"q_s ≥ rolloff = {qr!r} and > long_cutoff = {ql!r} "
                  f"(and ≤ {Q_MAX:g}): the spectrum must not be empty")
    unit = Spectrum(v["hurst"], ql, qr, qs, 1.0)
    if rms_slope is not None:
        c0 = v["rms_slope"] ** 2 / unit.moment(2)
    else:
        c0 = v["rms_height"] ** 2 / unit.moment(0)
    return Spectrum(v["hurst"], ql, qr, qs, c0)


def psd(q, *, hurst, rolloff, short_cutoff, long_cutoff=1.0, rms_slope=None, rms_height=None):
    """C(q) of the self-affine spectrum at wavenumbers q (see `spectrum` for the parameters)."""
    return spectrum(hurst=hurst, rolloff=rolloff, short_cutoff=short_cutoff,
                    long_cutoff=long_cutoff, rms_slope=rms_slope, rms_height=rms_height)(q)


# --------------------------------------------------------------------------
# The material: creep series in, relaxation form for the closed-form averages
# --------------------------------------------------------------------------
def _creep(ratio, material):
    """(J0, J, tau, ratio or None) from exactly one of ``ratio`` (default 3) and ``material``."""
    if material is None:
        r = 3.0 if ratio is None else check_reals(ACCEPTED, (("ratio", ratio),), _TESTS)["ratio"]
        return 1.0, (1.0 - 1.0 / r,), (1.0,), r
    if ratio is not None:
        raise ValueError(f"ratio={ratio!r}, material={material!r} is not allowed: give at most "
                         "one of ratio and material")
    what = ("a creep series (J0, J, tau): J0 > 0, amplitudes J_i ≥ 0 and times tau_i > 0 of "
            "equal lengths, J(0+) = J0 − ΣJ_i > 0 (compliances in (1 − ν²)/E0, times in τ_ref)")
    if isinstance(material, (str, bytes)) or not hasattr(material, "__len__") \
            or len(material) != 3:
        raise bad("material", material, what)
    j0, jj, tt = material
    j0 = real("material", j0, what, lambda x: x > 0.0)
    jj = series("material", jj, what, lambda x: x >= 0.0)
    tt = series("material", tt, what, lambda x: x > 0.0)
    if len(jj) != len(tt) or not j0 - math.fsum(jj) > 0.0:
        raise bad("material", material, what)
    return j0, jj, tt, None


def _relaxation(j0, jj, tt):
    """(E_r, E_m, θ_m) as arrays: E(ω) = E_r + Σ E_m iωθ_m/(1 + iωθ_m), the same material."""
    m = Maxwell.from_creep(j0, jj, tt)
    return m.E_r, np.asarray(m.E, dtype=float), np.asarray(m.theta, dtype=float)


def modulus(omega, *, ratio=None, material=None):
    """Persson's plane-strain modulus E(ω)/(1 − ν²), in E0/(1 − ν²), from the creep series.

    Parameters
    ----------
    omega : array_like
        ω τ_ref = n·w, n = q·ê the signed frequency-variable of a mode and w the speed.
    ratio, material
        As in `solve`.

    Returns
    -------
    ndarray of complex
        1/conj(J*(n)) = 1/(J(0+) + Σ J_i/(1 + i ω τ_i)): the engineering sign, Im E > 0 for
        ω > 0 (the project's J* has the opposite sign of i; see the module docstring).
    """
    j0, jj, tt, _ = _creep(ratio, material)
    w = np.asarray(omega, dtype=float)
    comp = np.full(w.shape, j0 - math.fsum(jj), dtype=complex)
    for j, tau in zip(jj, tt):
        comp += j / (1.0 + 1j * w * tau)
    return 1.0 / comp


def _averages(a, e_r, e, theta):
    """Closed-form means over φ of |E(a cos φ)|² and of cos φ Im E(a cos φ) (see
    `angular_averages`); every term is non-negative, so nothing cancels at any a."""
    a = np.asarray(a, dtype=float)
    b = a[..., None] * theta                       # b_m = a θ_m
    s = np.hypot(1.0, b)
    beta = b * b / (s * (1.0 + s))                 # ⟨b²c²/(1 + b²c²)⟩ = 1 − 1/s
    loss = (e * b / (s * (1.0 + s))).sum(-1)       # ⟨c · b c/(1 + b²c²)⟩ = β/b
    # ⟨|E|²⟩ = E_r² + 2 Σ_m E_m β_m [E_r + Σ_n E_n θ_n/(θ_m + θ_n)]  (partial fractions in c²)
    cross = e_r + (e * theta / (theta[:, None] + theta)).sum(-1)
    square = e_r * e_r + 2.0 * (e * beta * cross).sum(-1)
    return square, loss


def angular_averages(a, *, ratio=None, material=None):
    """The means over the sliding direction that Persson's integrals need, in closed form.

    Parameters
    ----------
    a : array_like
        |q| w ≥ 0: the mode of wavenumber |q| at angle φ to the sliding direction is loaded at
        ω τ_ref = a cos φ.
    ratio, material
        As in `solve`.

    Returns
    -------
    square, loss : ndarray
        (1/2π)∫ dφ |E(a cos φ)|² and (1/2π)∫ dφ cos φ Im E(a cos φ), with E = `modulus`
        (in E0/(1 − ν²) and its square).  With E = E_r + Σ E_m iωθ_m/(1 + iωθ_m),
        b_m = a θ_m, s_m = sqrt(1 + b_m²), β_m = 1 − 1/s_m:
        loss = Σ E_m β_m/b_m and square = E_r² + 2 Σ_m E_m β_m [E_r + Σ_n E_n θ_n/(θ_m + θ_n)],
        from (1/2π)∫ dφ/(1 + b² cos²φ) = 1/s.
    """
    j0, jj, tt, _ = _creep(ratio, material)
    return _averages(a, *_relaxation(j0, jj, tt))


# --------------------------------------------------------------------------
# Quadrature in ln q
# --------------------------------------------------------------------------
def _gauss(n):
    """Gauss–Legendre nodes x, weights w on [−1, 1] and the integration matrix
    Q[i, j] = ∫_{−1}^{x_i} ℓ_j(t) dt (ℓ_j the Lagrange basis on the nodes)."""
    x, w = legendre.leggauss(n)
    v = legendre.legvander(x, n)                   # P_0 … P_n at the nodes
    ip = np.empty((n, n))                          # ∫_{−1}^{x_i} P_k
    ip[:, 0] = x + 1.0
    for k in range(1, n):
        ip[:, k] = (v[:, k + 1] - v[:, k - 1]) / (2 * k + 1)
    # ℓ_j = w_j Σ_k (k + ½) P_k(x_j) P_k: exact, the Gauss rule integrates P_k P_k' (k, k' < n)
    q = (ip * (np.arange(n) + 0.5)) @ (v[:, :n].T * w)
    return x, w, q


def _edges(span, width, delta):
    """Panel edges on [0, span]: halving toward 0 down to ``delta`` (where P(q) may fall
    faster than any fixed panel resolves), then panels no wider than ``width``."""
    first = min(width, span)
    k = 0 if delta >= first else min(int(math.ceil(math.log2(first / delta))), 1000)
    graded = [first * 2.0 ** -i for i in range(k, -1, -1)]
    rest = np.linspace(first, span, max(int(math.ceil((span - first) / width)), 0) + 1)[1:]
    return np.concatenate(([0.0], graded, rest))


def _integrate(spec, relax, load, speed, gamma, nodes, width):
    """μ, G(q_s) and the number of panels, by Gauss–Legendre panels in t = ln(q/q_start).

    dG/dt = (π/(4p̃²)) q⁴C ⟨|E|²⟩ and dμ/dt = (π/p̃) q⁴C S(P) P ⟨cos φ Im E⟩, with
    P = erf(1/(2√G)); G at every node from the integration matrix, so P is as accurate as G.
    """
    x, w, qmat = _gauss(nodes)
    e_r, e, theta = relax
    # the plateau, then the power law (q_r included); q⁴C written to stay finite at Q_MAX
    pieces = [(spec.long_cutoff, spec.rolloff, 4.0),
              (spec.rolloff, spec.short_cutoff, 2.0 - 2.0 * spec.hurst)]
    g_total, mu, panels = 0.0, 0.0, 0
    kg, kf = math.pi / (4.0 * load * load), math.pi / load
    for q0, q1, power in pieces:
        span = math.log(q1 / q0)
        if span <= 0.0:
            continue
        # dG/dt at the start sets how fast P can fall from its value there
        sq0 = float(_averages(np.array([q0 * speed]), e_r, e, theta)[0][0])
        g0 = kg * spec.c0 * q0 ** 4 * sq0
        edges = _edges(span, width, max(g_total, 1e-6) / g0)
        lo, hi = edges[:-1], edges[1:]
        half = 0.5 * (hi - lo)
        t = lo[:, None] + half[:, None] * (x + 1.0)
        q = q0 * np.exp(t)
        q4c = spec.c0 * q0 ** 4 * np.exp(power * t)
        sq, loss = _averages(q * speed, e_r, e, theta)
        g = kg * q4c * sq
        steps = half * (g @ w)
        starts = g_total + np.concatenate(([0.0], np.cumsum(steps)[:-1]))
        big_g = starts[:, None] + half[:, None] * (g @ qmat.T)
        with np.errstate(divide="ignore"):
            p = np.where(big_g > 0.0, erf(0.5 / np.sqrt(big_g)), 1.0)
        s = gamma + (1.0 - gamma) * p * p
        f = kf * q4c * loss * s * p
        mu += float((half * (f @ w)).sum())
        g_total += float(steps.sum())
        panels += len(lo)
    return mu, g_total, panels


def _quadrature(value):
    what = (f"(nodes, width): Gauss–Legendre nodes per panel, an integer in [8, 64], and the "
            f"widest panel in ln q, in (0, 2] (default ({NODES}, {WIDTH}))")
    if isinstance(value, (str, bytes)) or not hasattr(value, "__len__") or len(value) != 2:
        raise bad("quadrature", value, what)
    n, h = value
    if not is_integer(n) or not 8 <= n <= 64 or not is_real(h) or not 0.0 < h <= 2.0:
        raise bad("quadrature", value, what)
    return int(n), float(h)


def _gamma(area_correction):
    what = (f"True (S = γ + (1 − γ)P² with γ = {GAMMA}), False (S = 1, Persson 2001) or a "
            "γ in [0, 1]")
    if isinstance(area_correction, (bool, np.bool_)):
        return GAMMA if area_correction else 1.0
    if is_real(area_correction):
        return real("area_correction", area_correction, what, lambda v: 0.0 <= v <= 1.0)
    raise bad("area_correction", area_correction, what)


# --------------------------------------------------------------------------
# The result and the solve
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Result:
    """One operating point of Persson's theory (a SciPy-like result object).

    Attributes
    ----------
    success, status, message
        Whether this is an answer (finite, estimated quadrature error within `TOLERANCE`),
        0 or 1, and what the solver says.
    mu : float
        Friction coefficient, positive when it resists the motion.
    contact_fraction : float
        A/A0 = P(q_s).
    tau_f : float
        μ p̃, the mean frictional stress in E0/(1 − ν²).
    g_total : float
        G(q_s) (P(q_s) = erf(1/(2√G(q_s)))).
    load, speed, hurst, long_cutoff, rolloff, short_cutoff : float
        The inputs.
    rms_slope, rms_height, rms_curvature : float
        Those of the spectrum (the one given, the others from the closed forms).
    c0 : float
        The spectrum's plateau C(q_l).
    ratio : float or None
        E∞/E0 of the standard linear solid (None when ``material`` was given).
    material : tuple
        The creep series (J0, J, tau) used.
    gamma : float
        γ of S(q) = γ + (1 − γ)P² (1 without the area correction).
    error_estimate : dict
        Estimated quadrature errors, relative for ``mu`` and ``contact_fraction`` (the
        output contract's meaning): the difference from a rule with two thirds of the nodes
        per panel, an upper bound in practice (see ``docs/persson.md``).  ``success`` asks
        the relative one of μ and the absolute one of A/A0 to be at most `TOLERANCE`.
    nodes, width, panels : int, float, int
        The quadrature: nodes per panel, widest panel in ln q, and panels used.
    """

    success: bool
    status: int
    message: str
    mu: float
    contact_fraction: float
    tau_f: float
    g_total: float
    load: float
    speed: float
    hurst: float
    long_cutoff: float
    rolloff: float
    short_cutoff: float
    rms_slope: float
    rms_height: float
    rms_curvature: float
    c0: float
    ratio: float | None
    material: tuple
    gamma: float
    error_estimate: dict = field(default_factory=dict)
    nodes: int = NODES
    width: float = WIDTH
    panels: int = 0

    def scalars(self):
        """{"mu", "contact_fraction", "tau_f"} as plain Python floats."""
        return plain({"mu": self.mu, "contact_fraction": self.contact_fraction,
                      "tau_f": self.tau_f})

    def as_dict(self):
        """The JSON record: inputs, scalars, success, message, error_estimate, diagnostics
        (serialisable with ``allow_nan=False``; non-finite values are None)."""
        j0, jj, tt = self.material
        rec = {"solver": "persson", "version": viscosine.__version__, "load": self.load,
               "speed": self.speed, "hurst": self.hurst, "long_cutoff": self.long_cutoff,
               "rolloff": self.rolloff, "short_cutoff": self.short_cutoff,
               "rms_slope": self.rms_slope, "rms_height": self.rms_height,
               "rms_curvature": self.rms_curvature, "c0": self.c0, "ratio": self.ratio,
               "material": {"J0": j0, "J": list(jj), "tau": list(tt)}, "gamma": self.gamma}
        rec.update(self.scalars())
        rec.update({"g_total": self.g_total, "success": self.success, "status": self.status,
                    "message": self.message, "error_estimate": dict(self.error_estimate),
                    "diagnostics": {"nodes": self.nodes, "width": self.width,
                                    "panels": self.panels}})
        return plain(rec)


def _solve(spec, creep, ratio, load, speed, gamma, nodes, width):
    """One point on validated inputs (`solve` and `sweep` share it)."""
    relax = _relaxation(*creep)
    mu, g_s, panels = _integrate(spec, relax, load, speed, gamma, nodes, width)
    mu_c, g_c, _ = _integrate(spec, relax, load, speed, gamma, (2 * nodes) // 3, width)
    p_s, p_c = (float(erf(0.5 / math.sqrt(v))) if v > 0.0 else 1.0 for v in (g_s, g_c))
    err_mu = abs(mu - mu_c) / abs(mu) if mu != 0.0 else abs(mu - mu_c)
    err_area = abs(p_s - p_c)  # absolute: the bound of success, as it always was
    # the output contract's estimate of a contact fraction is relative
    err = {"mu": err_mu, "contact_fraction": err_area / p_s if p_s > 0.0 else
           (0.0 if err_area == 0.0 else math.inf)}
    finite = all(math.isfinite(v) for v in (mu, g_s, p_s, err_mu))
    ok = finite and max(err_mu, err_area) <= TOLERANCE
    said = (f"estimated quadrature error {err_mu:.1e} (mu, relative), {err_area:.1e} "
            f"(contact_fraction, absolute; {err['contact_fraction']:.1e} relative)")
    if ok:
        message = f"converged: {said}"
    elif not finite:
        message = "failed: a non-finite result (mu, G or P)"
    else:
        message = (f"failed: {said}, above {TOLERANCE:g}; ask for more nodes or narrower "
                   "panels (quadrature=)")
    return Result(success=ok, status=0 if ok else 1, message=message, mu=mu,
                  contact_fraction=p_s, tau_f=mu * load, g_total=g_s, load=load, speed=speed,
                  hurst=spec.hurst, long_cutoff=spec.long_cutoff, rolloff=spec.rolloff,
                  short_cutoff=spec.short_cutoff, rms_slope=spec.rms_slope,
                  rms_height=spec.rms_height, rms_curvature=spec.rms_curvature, c0=spec.c0,
                  ratio=ratio, material=creep, gamma=gamma, error_estimate=err, nodes=nodes,
                  width=width, panels=panels)


def _inputs(hurst, rolloff, short_cutoff, long_cutoff, rms_slope, rms_height, ratio, material,
            area_correction, quadrature):
    spec = spectrum(hurst=hurst, rolloff=rolloff, short_cutoff=short_cutoff,
                    long_cutoff=long_cutoff, rms_slope=rms_slope, rms_height=rms_height)
    j0, jj, tt, r = _creep(ratio, material)
    return spec, (j0, jj, tt), r, _gamma(area_correction), _quadrature(quadrature)


def solve(*, load, speed, hurst, rolloff, short_cutoff, long_cutoff=1.0, rms_slope=None,
          rms_height=None, ratio=None, material=None, area_correction=True,
          quadrature=(NODES, WIDTH)):
    """Persson's friction coefficient and contact area for one operating point.

    Parameters
    ----------
    load : float
        p̃ = p∞(1 − ν²)/E0, the mean pressure over the cell.
    speed : float
        w = V τ_ref k (0: elastic, relaxed modulus).
    hurst, rolloff, short_cutoff, long_cutoff, rms_slope, rms_height
        The self-affine spectrum (`spectrum`): exactly one of rms_slope and rms_height.
    ratio : float, optional
        E∞/E0 of the standard linear solid J0 = 1, J_1 = 1 − 1/ratio, τ_1 = 1 (3 when neither
        ratio nor material is given).
    material : (J0, J, tau), optional
        A creep series J(t) = J0 − Σ J_i exp(−t/τ_i) instead of ``ratio``: compliances in
        (1 − ν²)/E0, times in τ_ref.
    area_correction : bool or float
        True: S(q) = γ + (1 − γ)P(q)² with γ = `GAMMA`; False: S = 1 (Persson 2001); a number
        in [0, 1]: that γ.
    quadrature : (int, float)
        Gauss–Legendre nodes per panel and the widest panel in ln q.

    Returns
    -------
    Result

    Raises
    ------
    ValueError
        ``"name=value is not allowed: ..."`` for the first bad input, before any work.
    """
    v = check_reals(ACCEPTED, (("load", load), ("speed", speed)), _TESTS)
    spec, creep, r, gamma, (n, h) = _inputs(hurst, rolloff, short_cutoff, long_cutoff,
                                            rms_slope, rms_height, ratio, material,
                                            area_correction, quadrature)
    return _solve(spec, creep, r, v["load"], v["speed"], gamma, n, h)


def sweep(*, load, speed, hurst, rolloff, short_cutoff, long_cutoff=1.0, rms_slope=None,
          rms_height=None, ratio=None, material=None, area_correction=True,
          quadrature=(NODES, WIDTH)):
    """`solve` at every (load, speed) pair, loads outer and speeds inner.

    ``load`` and ``speed`` are each a number or a 1-D sequence; the other parameters are as in
    `solve`.  Every input is checked before any point is solved.

    Returns
    -------
    list of Result
        ``[r.mu for r in sweep(load=0.1, speed=speeds, ...)]`` is a friction curve μ(w).
    """
    loads = series("load", load, ACCEPTED["load"][2])
    speeds = series("speed", speed, ACCEPTED["speed"][2])
    for ld in loads:
        check_reals(ACCEPTED, (("load", ld),), _TESTS)
    for sp in speeds:
        check_reals(ACCEPTED, (("speed", sp),), _TESTS)
    spec, creep, r, gamma, (n, h) = _inputs(hurst, rolloff, short_cutoff, long_cutoff,
                                            rms_slope, rms_height, ratio, material,
                                            area_correction, quadrature)
    return [_solve(spec, creep, r, ld, sp, gamma, n, h) for ld in loads for sp in speeds]


__all__ = ["ACCEPTED", "GAMMA", "Result", "Spectrum", "angular_averages", "modulus", "psd",
           "solve", "spectrum", "sweep"]
