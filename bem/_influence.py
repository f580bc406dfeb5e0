"""Real-space influence coefficients of the steady-sliding operator (eq. 2.4-2.5).

Element: piecewise-constant pressure on ``N`` equal panels of one period,
collocation at the panel centres ``X_j = j/N - 1/2``.  The operator is circulant,
``k v_i = sum_j C[(i - j) mod N] sigma_j``, and this module returns the first
column ``C_m`` (influence at ``X = m/N`` of the panel centred at 0).

Units: ``X = x/lambda``; ``k v``; pressure in ``E_ref/(1 - nu^2)``; compliances in
``1/E_ref``; times in ``tau_ref``; speed ``w = V tau_ref k``.

Elastic part (eq. 2.2 integrated over a panel, exact)::

    c(X) = (2/pi) [Cl2(2 pi (X + 1/(2N))) - Cl2(2 pi (X - 1/(2N)))]

Memory part of one Prony term ``J_i exp(-t/tau_i)`` (second term of eq. 2.5,
with ``y = V z`` and the memory length ``L_i = V tau_i / lambda = w tau_i/(2 pi)``)::

    M_m = (J_i/L_i) int_0^inf exp(-y/L_i) c(X_m + y) dy.

It is evaluated by the exact recursion ``E_m = S_m + exp(-h/L) E_(m+1)``
(h = 1/N, periodic in m) with ``S_m = int_0^h exp(-y/L) c(X_m + y) dy``: O(N) per
term after the N source integrals.  The two intervals that contain a kink of ``c`` (a
``y log y`` singularity of its derivative at a panel edge) get a graded composite rule.  On
every other interval every term of a Prony series shares the nodes
(:class:`MemorySources`): product rules on fixed Gauss-Legendre points, ``int_0^1 exp(-a t)
l_q(t) dt`` (a = h/L) for their Lagrange basis ``l_q``, exact for any speed, from ``L << h``
to ``L >> lambda``.  c is evaluated once per grid, not once per term: a rubber's 30-term
spectrum costs a few matrix-vector products more than one term.

Fourier check (mode ``n``, ``n != 0``): the symbol of the operator is
``(2/|n|) J*(n) sinc(pi n/N)`` (times 1/N per panel) with
``J*(n) = J(0+) + sum_i J_i / (1 - i n w tau_i)``, i.e. ``J*(-k_n V)`` of
``J*(omega) = J(0+) + int_0^inf J'(s) exp(-i omega s) ds``.
"""
from __future__ import annotations

import math
from functools import lru_cache

import numpy as np

from . import _kernels

#: the shared product rules of the source intervals but the two with a kink: (farthest
#: distance from a kink in panels, Legendre points).  On an interval m panels from a kink,
#: c(X_m + t h) is analytic in a Bernstein ellipse of parameter 2m + (4m^2 - 1)^(1/2), about
#: 4m, and interpolation at n Legendre points errs by about that to the power -n, of c: at
#: each band's nearest interval 3.7^-32 = 5e-19, 12^-16 = 6e-18, 132^-8 = 1e-17,
#: 1028^-6 = 8e-19, 32772^-4 = 9e-19
_SHARED_BANDS = ((2, 32), (32, 16), (256, 8), (8192, 6), (None, 4))
#: the farthest band from the elastic column, when given (MemorySources): c on the interval
#: [m, m + 1] panels by its interpolant through the panel centres m - 2 ... m + 3, which errs
#: by about max|prod_k (t - k)|/6! |c^(6)| = 3.5/720 (4h 5!/m^6) = 0.6 (4h)/m^6, 2e-24 (4h) at
#: m = 8193, below the 4-point rule's 9e-19 of c; no kernel values to make there (a 2^20
#: grid's shared sources in 0.014 s instead of 0.3 s)
_STENCIL = np.arange(-2, 4)
#: the sawtooth ratio sigma_i/sigma_(i+1) the collocation shift of a memory term allows
#: (see collocation_shift): a sawtooth left by the discretisation decays by this much per panel
SAWTOOTH_RATIO = 0.3
#: above this a = h/L the weight e^(-a t) is treated as e^(-a t) on [0, inf)
_A_LAGUERRE = 120.0
#: exp(-x) is exactly 0.0 in double precision for x above this (below the smallest subnormal)
_EXP_UNDERFLOW = 746.0


#: the two halves of an interval with a kink of c at its middle: (start, end, kink at the end)
_KINK_HALVES = ((0.0, 0.5, True), (0.5, 1.0, False))


def _kink_rule(lo: float, hi: float, kink_at_hi: bool, a: float):
    """Nodes t and weights (without the factor exp(-a t)) of the rule of :func:`_kink_integral`
    on one half: composite Gauss-Legendre (16 points) on subintervals graded geometrically
    (ratio 1/4) toward the kink, refined to width 2/a where the weight varies."""
    g, gw = _leggauss(16)
    length = hi - lo
    dist = length * 0.25 ** np.arange(0, 27)
    parts = [(hi - dist) if kink_at_hi else (lo + dist), np.array([lo, hi])]
    if a * length > 2.0:
        step = 2.0 / a
        jmax = int(min(length / step, 40))
        parts.append(lo + step * np.arange(1, jmax + 1))
    b = np.unique(np.concatenate(parts))
    b = b[(b >= lo) & (b <= hi)]
    half = 0.5 * np.diff(b)
    mid = 0.5 * (b[1:] + b[:-1])
    t = (mid[:, None] + half[:, None] * g[None, :]).ravel()
    return t, (half[:, None] * gw[None, :]).ravel()


def _kink_integral(m: int, nodes: int, a: float, cache: dict | None = None) -> float:
    """``int_0^1 exp(-a t) c(X_m + t h) dt`` for an interval with a kink at t = 1/2
    (:func:`_kink_rule` on each half).

    `cache` keeps, per grid, the nodes and kernel values of the halves whose rule does not
    depend on a (no refinement, a <= 4): the terms of a Prony series share them.
    """
    total = 0.0
    for k, (lo, hi, kink_at_hi) in enumerate(_KINK_HALVES):
        shared = not a * (hi - lo) > 2.0
        hit = cache.get((m, k)) if shared and cache is not None else None
        if hit is None:
            t, hw = _kink_rule(lo, hi, kink_at_hi, a)
            x = (m + t) / nodes
            vals = np.empty_like(x)
            _kernels.panel_values(x, nodes, vals)
            if shared and cache is not None:
                cache[(m, k)] = t, hw, vals
        else:
            t, hw, vals = hit
        w = hw * np.exp(-a * t)
        total += float(np.dot(w, vals))
    return total


def elastic_coefficients(nodes: int) -> np.ndarray:
    """Elastic panel coefficients ``c(X_m)`` for unit compliance (J = 1).

    Returns
    -------
    ndarray, shape (nodes,)
        ``c_m`` for m = 0..nodes-1 (m and m - nodes are the same offset).
    """
    m = np.arange(nodes)
    x = np.where(m <= nodes // 2, m, m - nodes) / nodes
    out = np.empty(nodes)
    _kernels.panel_values(x, nodes, out)
    return out


@lru_cache(maxsize=None)
def _leggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.legendre.leggauss(n)


@lru_cache(maxsize=None)
def _laggauss(n: int) -> tuple[np.ndarray, np.ndarray]:
    return np.polynomial.laguerre.laggauss(n)


@lru_cache(maxsize=None)
def _legendre01(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre nodes and barycentric weights on [0, 1]."""
    g, _ = _leggauss(n)
    t = 0.5 * (g + 1.0)
    bary = np.array([1.0 / np.prod(t[q] - np.delete(t, q)) for q in range(n)])
    return t, bary


def _lagrange_basis(x: np.ndarray, n: int) -> np.ndarray:
    """``l_q(x_r)`` for the Lagrange basis of the n Legendre points of [0, 1], shape (x.size, n)
    (barycentric form; a point of x on a Legendre point takes the exact row)."""
    t, bary = _legendre01(n)
    diff = x[:, None] - t[None, :]
    hit = diff == 0.0
    diff[hit] = 1.0
    basis = bary / diff
    basis /= basis.sum(axis=1, keepdims=True)
    rows = np.flatnonzero(hit.any(axis=1))
    basis[rows] = hit[rows]
    return basis


@lru_cache(maxsize=None)
def _composite_basis(pieces: int, n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A composite Gauss-Legendre rule on [0, 1] (`pieces` equal pieces of n + 12 points),
    its weights and the Lagrange basis of the n Legendre points on its nodes."""
    g, gw = _leggauss(n + 12)
    edges = np.linspace(0.0, 1.0, pieces + 1)
    half = 0.5 * np.diff(edges)
    mid = 0.5 * (edges[1:] + edges[:-1])
    x = (mid[:, None] + half[:, None] * g[None, :]).ravel()
    w = (half[:, None] * gw[None, :]).ravel()
    return x, w, _lagrange_basis(x, n)


@lru_cache(maxsize=4096)
def _product_weights(a: float, n: int) -> np.ndarray:
    """``w_q = int_0^1 exp(-a t) l_q(t) dt`` for the Lagrange basis ``l_q`` of the n Legendre
    points of [0, 1] (a product rule: exact for degree n - 1 with the weight, any a >= 0).

    For ``a >= 120`` the truncation at t = 1 is below 1e-50 relative and the scaled
    n-point Gauss-Laguerre rule (exact to degree 2n - 1 on [0, inf)) integrates each ``l_q``.
    Below, a composite Gauss-Legendre rule whose pieces (4 … 64, a power of two) keep the
    exponential's change on each below e^2 does, exactly to rounding: its n + 12 points per
    piece integrate a polynomial of degree n - 1 times the exponential's Taylor series to
    beyond degree 2n + 20.
    """
    if a >= _A_LAGUERRE:
        s, w = _laggauss(n)
        return (w / a) @ _lagrange_basis(s / a, n)
    pieces = 4
    while pieces < a / 2.0:
        pieces *= 2
    x, w, basis = _composite_basis(pieces, n)
    return (w * np.exp(-a * x)) @ basis


@lru_cache(maxsize=None)
def _stencil_basis() -> np.ndarray:
    """``l_k(t_q)``: the Lagrange basis of the nodes t = k in _STENCIL at the _STENCIL.size
    Legendre points of [0, 1], shape (points, nodes)."""
    t, _ = _legendre01(_STENCIL.size)
    ks = [float(k) for k in _STENCIL]
    return np.array([[math.prod((tq - j) / (k - j) for j in ks if j != k) for k in ks]
                     for tq in t])


class MemorySources:
    """The source integrals ``S_m = int_0^1 exp(-a t) c(X_m + t h) dt`` of the memory
    recursion, for the signed offsets `offsets` of a grid of `nodes` panels, for any decay
    ``a = h/L``: every Prony term of a grid calls the same instance.

    c is the elastic panel value (:func:`_kernels.panel_values`).  Its values at the shared
    Legendre points (:data:`_SHARED_BANDS`, more points nearer the kinks of c at ``X =
    +-h/2``) are made once, here; a term then costs one matrix-vector product per band.  The
    two intervals that contain a kink (offsets 0 and -1) take a graded composite rule.  Given
    ``elastic``, c at every offset of `offsets` (the whole grid's `elastic_coefficients`), the
    farthest band takes c from it instead (:data:`_STENCIL`): no kernel values to make there.
    """

    def __init__(self, nodes: int, offsets: np.ndarray, elastic: np.ndarray | None = None):
        self.nodes = nodes
        offsets = np.asarray(offsets, dtype=np.int64)
        self.size = offsets.size
        dist = np.where(offsets >= 0, offsets, -offsets - 1)
        self.kinks = [(int(i), int(offsets[i])) for i in np.flatnonzero(dist == 0)]
        self._kink_cache = {}
        self.bands = []
        self.elastic = elastic
        lo = 1
        for hi, points in _SHARED_BANDS:
            sel = np.flatnonzero((dist >= lo) & (dist <= (hi if hi is not None else dist.max())))
            if sel.size and hi is None and self._stencil_fits(sel, offsets):
                self.bands.append((slice(int(sel[0]), int(sel[-1]) + 1), None, None))
            elif sel.size:
                t, _ = _legendre01(points)
                x = (offsets[sel, None] + t[None, :]) / nodes
                vals = np.empty(x.size)
                _kernels.panel_values(x.ravel(), nodes, vals)
                if sel[-1] - sel[0] + 1 == sel.size:
                    sel = slice(int(sel[0]), int(sel[-1]) + 1)  # contiguous: no gather
                self.bands.append((sel, points, vals.reshape(-1, points)))
            if hi is None:
                break
            lo = hi + 1

    def _stencil_fits(self, sel, offsets) -> bool:
        """Whether the stencil's neighbours of the band `sel` are in ``elastic`` next to it:
        the band contiguous and inside the array, its offsets consecutive modulo nodes."""
        if self.elastic is None or self.elastic.size != self.size:
            return False
        first, last = int(sel[0]), int(sel[-1])
        lo, hi = first + int(_STENCIL[0]), last + int(_STENCIL[-1])
        return (last - first + 1 == sel.size and lo >= 0 and hi < self.size
                and bool(np.all(np.diff(offsets[lo:hi + 1]) % self.nodes == 1)))

    def __call__(self, a: float) -> np.ndarray:
        src = np.empty(self.size)
        for sel, points, vals in self.bands:
            if vals is None:  # the stencil on the elastic column
                w = _product_weights(a, _STENCIL.size) @ _stencil_basis()
                _kernels.stencil_sum(self.elastic, sel.start + int(_STENCIL[0]), w, src[sel])
                continue
            src[sel] = vals @ _product_weights(a, points)
        for i, m in self.kinks:
            src[i] = _kink_integral(m, self.nodes, a, self._kink_cache)
        return src


def _signed_offsets(nodes: int) -> np.ndarray:
    m = np.arange(nodes)
    return np.where(m <= nodes // 2, m, m - nodes)


def memory_coefficients(nodes: int, length: float,
                        sources: MemorySources | None = None) -> np.ndarray:
    """Memory coefficients of one Prony term per unit ``J_i`` (second term of eq. 2.5).

    Parameters
    ----------
    nodes : int
        Number of panels N.
    length : float
        Memory length ``L = V tau_i / lambda > 0`` in wavelengths.
    sources : MemorySources, optional
        The grid's shared source integrals (made here when not given).

    Returns
    -------
    ndarray, shape (nodes,)
        ``(1/L) int_0^inf exp(-y/L) c(X_m + y) dy`` for m = 0..nodes-1.
    """
    a = (1.0 / nodes) / length
    if sources is None:
        sources = MemorySources(nodes, _signed_offsets(nodes))
    src = sources(a)
    out = np.empty(nodes)
    _kernels.exponential_recursion(src, a, out)
    out *= a  # (1/L) * h * (1/h) E: the recursion ran on S_m / h
    return out


def _window_reach(nodes: int, first: int, count: int) -> int:
    """``D = max(|first|, |last|) + 1`` of a window, refused unless well inside one period."""
    last = first + count - 1
    d = max(abs(first), abs(last)) + 1
    if 2 * d + 4 > nodes:
        raise ValueError(f"count={count!r} is not allowed: a window well inside one period "
                         f"(offsets {first}..{last} on nodes={nodes})")
    return d


def window_sources(nodes: int, first: int, count: int) -> MemorySources:
    """The shared source integrals of a window (signed offsets ``-(D+1) .. D``)."""
    d = _window_reach(nodes, first, count)
    return MemorySources(nodes, np.arange(-(d + 1), d + 1))


def window_memory_coefficients(nodes: int, length: float, first: int, count: int,
                               sources: MemorySources | None = None) -> np.ndarray:
    """:func:`memory_coefficients` at the signed offsets ``first .. first + count - 1`` only,
    for a grid too fine to be made (a contact window of ``count`` panels of a grid of
    ``nodes`` panels per period; panel values are finite up to 2^52).

    The recursion ``E_m = S_m + q E_(m+1)`` (``q = exp(-h/L)``) runs down from ``D + 1``,
    ``D = max(|first|, |last|) + 1``, whose value is the whole integral beyond:
    ``E_(D+1) = P/(1 - q^N)`` over one period ``P``, split into the source intervals of the
    load's periodic image (signed offsets ``-(D+1) .. D``, the ones near the window, weight
    ``q^(N + m - D - 1)``) and the smooth rest, ``(1/h) int_(X0)^(1-X0) exp(-(X - X0)/L) c(X)
    dX`` with ``X0 = (D+1) h``, by Gauss-Legendre on intervals graded geometrically toward
    both ends (c ~ 4 h log|2 sin pi X| there) and no wider than 4 L where the weight decays.
    ``sources``: :func:`window_sources` of the window, when already made.
    """
    d = _window_reach(nodes, first, count)
    h = 1.0 / nodes
    a = h / length
    if sources is None:
        sources = window_sources(nodes, first, count)
    lo = -(d + 1)
    src = sources(a)  # signed offsets lo .. d
    if a * (nodes + lo - d - 1) > _EXP_UNDERFLOW:
        image = 0.0  # every weight q^(N + m - D - 1) underflows to 0: the same sum, unmade
    else:
        offs = np.arange(lo, d + 1, dtype=float)
        image = float(np.dot(np.exp(-a * (nodes + offs - d - 1)), src))
    x0 = (d + 1) * h
    smooth = _smooth_memory_integral(x0, 1.0 - x0, length, nodes) / h
    e = (smooth + image) / -math.expm1(-a * nodes)  # E_(d+1)
    out = np.empty(count)
    _kernels.exponential_recursion_down(src[first - lo:], a, e, count, out)
    return a * out


def _smooth_memory_integral(x0: float, x1: float, length: float, nodes: int) -> float:
    """``int_(x0)^(x1) exp(-(X - x0)/L) c(X) dX`` for c of a grid of `nodes` panels, where
    [x0, x1] keeps away from the panel at X = 0 and its image at 1 (c smooth, logarithmic
    toward both ends): 20-point Gauss-Legendre on intervals doubling away from each end, cut
    to at most 4 L where the weight decays, and ending where it has fallen below 1e-20."""
    mid = 0.5 * (x0 + x1)
    pts = {x0, x1, mid}
    w = x0
    while x0 + w < mid:
        pts.update((x0 + w, x1 - w))
        w *= 2.0
    end = min(x1, x0 + 46.0 * length)  # exp(-46) = 1e-20
    pts = sorted(p for p in pts if p < end) + [end]
    edges = [pts[0]]
    for p in pts[1:]:
        pieces = max(1, int(math.ceil((p - edges[-1]) / (4.0 * length))))
        edges.extend(edges[-1] + (p - edges[-1]) * np.arange(1, pieces + 1) / pieces)
    edges = np.asarray(edges)
    g, gw = _leggauss(20)
    half = 0.5 * np.diff(edges)
    centre = 0.5 * (edges[1:] + edges[:-1])
    x = (centre[:, None] + half[:, None] * g[None, :]).ravel()
    wts = (half[:, None] * gw[None, :]).ravel() * np.exp(-(x - x0) / length)
    vals = np.empty_like(x)
    _kernels.panel_values(x, nodes, vals)
    return float(np.dot(wts, vals))


def collocation_shift(h: float, length: float, j_local: float, j_i: float) -> float:
    """Upstream-fitted collocation shift ``delta`` of one memory term, in wavelengths.

    Where the memory length ``L`` spans a panel or more but the pressure relaxation layer
    (``L j_local/(j_local + J_i)``) is thinner than one, collocation at the panel centre
    treats the memory integral like the trapezoidal rule treats a stiff decay: a discrete
    pressure mode ``sigma_j ~ r^j`` with ``r`` near -1 (a sawtooth from the leading edge,
    growing with the stiffness E_inf/E0) then solves the homogeneous contact equations.
    Model: ``v = j_local sigma + (J_i/L) int_0^inf exp(-y/L) sigma(X + y) dy`` with
    piecewise-constant sigma, its memory part collocated ``delta`` downstream of the
    centre.  Differencing gives ``sigma_i/sigma_(i+1) = q - B sqrt(q)/A`` with ``q =
    exp(-h/L)``, ``A = j_local + J_i (1 - sqrt(q) E)``, ``B = J_i (1 - q) E``,
    ``E = exp(-delta/L)``.  The shift is zero where this ratio is already at least
    ``-SAWTOOTH_RATIO`` (resolved layers, short memories, E_inf/E0 <= 3); otherwise it is
    the smallest that brings the ratio up to ``-SAWTOOTH_RATIO`` = -k.  The ratio grows with
    delta, so the shift stays below ``h (1 - k)/(2 (1 + k))`` (0.27 h) and ``delta/L`` below
    ``ln((1 + k)/(2 sqrt(k)))`` (0.17).  ``j_local`` is J(0+) plus what the other terms add at
    once over half a panel.
    """
    if not length > 0.0 or j_i <= 0.0:
        return 0.0
    s = math.exp(-0.5 * h / length)
    ratio = s * s - j_i * (1.0 - s * s) * s / (j_local + j_i * (1.0 - s))
    if ratio >= -SAWTOOTH_RATIO:
        return 0.0
    k = SAWTOOTH_RATIO
    e = (s * s + k) * (j_local + j_i) / (j_i * s * (1.0 + k))
    return max(-length * math.log(e), 0.0)


def collocation_shifts(h: float, j_plus: float, terms, lengths) -> list[float]:
    """The collocation shift of every memory term of a series (wavelengths; see
    :func:`collocation_shift` for one term).

    Several terms whose memory spans about a panel form the sawtooth together even where none
    does alone: in the model of :func:`collocation_shift` with all terms, a sawtooth of ratio
    ``-1/r`` solves the homogeneous equations where ``F(r) = J(0+) + sum_i J_i (1 - sqrt(q_i)
    E_i + (1 - q_i) sqrt(q_i) E_i r/(1 - q_i r))`` vanishes; F increases with r < 0, so the
    ratio stays at least ``-SAWTOOTH_RATIO`` = -k exactly where ``F(-1/k) = J(0+) + sum_i J_i
    (1 - c_i E_i) >= 0``, ``c_i = sqrt(q_i) (1 + k)/(k + q_i)``, ``E_i = exp(-delta/L_i)``.
    Only the terms with ``c_i > 1`` (memory beyond 0.41 h) lower F, and they all take one shift
    ``delta``, the smallest that makes ``F(-1/k) >= 0`` (F grows with delta; at ``h (1 - k)/(2
    (1 + k))`` = 0.27 h every such term contributes ``>= 0``).  One shift for all: what costs
    accuracy is moving the memory relative to the instantaneous compliance (J(0+) and the
    memories within a panel), a phase error of about ``k delta J_inst/J``; a shift of some
    memory terms against the others would add theirs (measured on a 16-term spectrum at
    E_inf/E0 = 1000: 4e-7 of mu in full contact at N = 4096 with one shift, 5e-5 with the
    shifts that minimise ``sum J_i delta_i``).  For a single term this is
    :func:`collocation_shift`.
    """
    k = SAWTOOTH_RATIO
    base = j_plus
    bad = []  # (index, J_i, c_i, L_i, sqrt(q_i)) of the terms that lower F
    for i, ((j_i, _), length) in enumerate(zip(terms, lengths)):
        if j_i <= 0.0:
            continue
        if not length > 0.0:
            base += j_i
            continue
        s = math.exp(-0.5 * h / length)
        c = s * (1.0 + k) / (k + s * s)
        if c > 1.0:
            bad.append((i, j_i, c, length, s))
        else:
            base += j_i * (1.0 - c)
    out = [0.0] * len(terms)

    def f(delta):
        return base + sum(j * (1.0 - c * math.exp(-delta / ln)) for _, j, c, ln, _ in bad)

    if not bad or f(0.0) >= 0.0:
        return out
    if len(bad) == 1:  # one term against what acts at once: collocation_shift's closed form
        i, j, _, ln, _ = bad[0]
        out[i] = collocation_shift(h, ln, base, j)
        return out
    lo, hi = 0.0, h * (1.0 - k) / (2.0 * (1.0 + k))
    for _ in range(100):  # bisection to the last bits of delta (deterministic)
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        if f(mid) >= 0.0:
            hi = mid
        else:
            lo = mid
    for i, *_ in bad:
        out[i] = hi
    return out


def shifted_memory_coefficients(nodes: int, length: float, delta: float,
                                span: tuple[int, int] | None = None,
                                base: np.ndarray | None = None) -> np.ndarray:
    """Memory coefficients collocated ``delta`` downstream of the panel centres.

    ``(1/L) int_0^inf exp(-y/L) c(X_m - delta + y) dy = exp(-delta/L) M_m + (delta/L)
    int_0^1 exp(-(delta/L) t) c(X_m - delta + delta t) dt``, with ``M_m`` of
    :func:`memory_coefficients`.  With the shifts of :func:`collocation_shift` (``delta <=
    0.27 h``, ``delta/L <= 0.17``) the kinks of c at ``+-h/2`` stay at least 0.23 h from every
    interval of the second integral, whose length is at most 0.27 h: 16-point Gauss-Legendre
    with the weight folded in is exact to rounding.  ``span = (first, count)``: the signed
    offsets of a window only (:func:`window_memory_coefficients`).  ``base``: the unshifted
    coefficients, when already made.
    """
    if not 0.0 <= delta <= 0.3 / nodes:
        raise ValueError(f"delta={delta!r} is not allowed: a shift in [0, 0.3 h] "
                         "(collocation_shift gives at most 0.27 h)")
    if base is None:
        base = (memory_coefficients(nodes, length) if span is None
                else window_memory_coefficients(nodes, length, *span))
    if delta <= 0.0:
        return base
    a = delta / length
    return math.exp(-a) * base + a * _shifted_integral(nodes, delta, span, _joint_weights(a))


def influence_coefficients_nd(j_plus: float, terms: tuple[tuple[float, float], ...],
                              speed: float, nodes: int,
                              span: tuple[int, int] | None = None,
                              parts: dict | None = None) -> np.ndarray:
    """First column of the circulant operator for a Prony creep function.

    Parameters
    ----------
    j_plus : float
        Instantaneous compliance J(0+) in 1/E_ref.
    terms : tuple of (J_i, tau_i)
        Prony terms (J_i >= 0 in 1/E_ref, tau_i > 0 in tau_ref).
    speed : float
        ``w = V tau_ref k >= 0``; at 0 the memory terms take their relaxed limit.
    nodes : int
        Number of panels.
    span : (first, count), optional
        Only the signed offsets ``first .. first + count - 1``, without making the grid (the
        Toeplitz operator of a contact window of a grid too fine to be made).
    parts : dict, optional
        Filled with the pieces made on the way: ``"elastic"`` (unit compliance) and, keyed by
        its memory length, each Prony term's unshifted memory coefficients per unit J_i (what
        the window's friction needs).

    Returns
    -------
    ndarray, shape (nodes,) or (count,)
        ``C_m``: k v at X = m/N due to unit pressure on the panel centred at 0.
    """
    if span is None:
        base = elastic_coefficients(nodes)
    else:
        base = np.empty(span[1])
        _kernels.panel_values(np.arange(span[0], span[0] + span[1]) / nodes, nodes, base)
    if parts is not None:
        parts["elastic"] = base
    total = j_plus * base
    h = 1.0 / nodes
    lengths = [speed * tau_i / (2.0 * np.pi) for _, tau_i in terms]
    shifts = collocation_shifts(h, j_plus, terms, lengths)
    # several shifted terms share one shift (collocation_shifts): their second integrals take
    # c at the same points, so they are summed with the terms' weights combined (one set of
    # kernel values per grid, not one per term)
    joint = sum(1 for (j_i, _), d in zip(terms, shifts) if j_i != 0.0 and d > 0.0) > 1
    weights = None  # of the joint second integral, at its 16 points
    sources = None  # made at the first memory term, shared by the others
    for i, ((j_i, _), length) in enumerate(zip(terms, lengths)):
        if j_i == 0.0:
            continue
        if length == 0.0:
            total = total + j_i * base  # fully relaxed: J(0+) + J_i acts at once
            continue
        if sources is None:
            sources = (MemorySources(nodes, _signed_offsets(nodes), base) if span is None
                       else window_sources(nodes, *span))
        delta = shifts[i]
        unshifted = (memory_coefficients(nodes, length, sources) if span is None
                     else window_memory_coefficients(nodes, length, *span, sources))
        if parts is not None:
            parts[length] = unshifted
        if joint and delta > 0.0:
            a = delta / length
            total = total + (j_i * math.exp(-a)) * unshifted
            w = _joint_weights(a)
            weights = j_i * a * w if weights is None else weights + j_i * a * w
        else:
            total = total + j_i * shifted_memory_coefficients(nodes, length, delta, span,
                                                              unshifted)
    if weights is not None:
        total = total + _shifted_integral(nodes, max(shifts), span, weights)
    return total


def _joint_weights(a: float) -> np.ndarray:
    """Weights of ``int_0^1 exp(-a t) f(t) dt`` at the 16 Gauss-Legendre points on [0, 1]
    (those of :func:`shifted_memory_coefficients`)."""
    g, gw = _leggauss(16)
    t = 0.5 * (g + 1.0)
    return 0.5 * gw * np.exp(-a * t)


def _shifted_integral(nodes: int, delta: float, span, weights) -> np.ndarray:
    """``sum_q weights_q c(X_m - delta + delta t_q)`` over the offsets (all, or ``span``'s):
    the second integral of :func:`shifted_memory_coefficients`, for given weights."""
    offsets = _signed_offsets(nodes) if span is None else np.arange(span[0], span[0] + span[1])
    x0 = offsets / nodes - delta
    g, _ = _leggauss(16)
    acc = np.zeros(offsets.size)
    vals = np.empty(offsets.size)
    for tq, wq in zip(0.5 * (g + 1.0), weights):
        _kernels.panel_values(x0 + delta * tq, nodes, vals)
        acc += wq * vals
    return acc
