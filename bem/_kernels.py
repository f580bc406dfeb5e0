"""Compiled kernels of the boundary-element road (numba, ``cache=True``, no fastmath).

Every function here takes arrays and floats, writes into caller-allocated output
arrays and returns nothing (scalar helpers return a float).  Validation,
allocation and orchestration live in the other private modules of :mod:`bem`.
Each kernel has a plain NumPy or dense twin in ``tests/bem/test_bem_kernels.py``.

Units (as everywhere in :mod:`bem`): positions ``X = x/lambda``; angles
``theta = 2 pi X``; heights and displacements ``k y``, ``k v``; pressure in units
of ``E_ref/(1 - nu^2)``; compliances in ``1/E_ref``.

References
----------
Eq. (2.2) of the paper: the periodic Green's function
``G(x) = -(2(1 - nu^2)/pi) log|2 sin(kx/2)|``, whose antiderivative is the
Clausen function ``Cl2(theta) = -int_0^theta log|2 sin(t/2)| dt``.
"""
from __future__ import annotations

from fractions import Fraction
from math import factorial

import numpy as np
from numba import njit


# --------------------------------------------------------------------------
# Tables, built once with exact rational arithmetic (deterministic).
# --------------------------------------------------------------------------
def _bernoulli_abs(count: int) -> list[Fraction]:
    """|B_2k| for k = 1..count (Akiyama-Tanigawa, exact)."""
    size = 2 * count + 1
    a = [Fraction(0)] * (size + 1)
    out = []
    bern = []
    for m in range(size + 1):
        a[m] = Fraction(1, m + 1)
        for j in range(m, 0, -1):
            a[j - 1] = j * (a[j - 1] - a[j])
        bern.append(a[0])  # B_m with B_1 = +1/2
    for k in range(1, count + 1):
        out.append(abs(bern[2 * k]))
    return out


def _cl2_series_table(count: int = 26) -> np.ndarray:
    """c_k = |B_2k| / (2k (2k+1)!), so Cl2(t) = t - t log t + t sum_k c_k t^(2k)."""
    b = _bernoulli_abs(count)
    return np.array([float(b[k - 1] / (2 * k * factorial(2 * k + 1)))
                     for k in range(1, count + 1)])


def _cot_derivative_table(count: int = 24) -> np.ndarray:
    """Q_j(x) coefficients / (2j+1)!, with d^(2j-1)/du^(2j-1) cot u = -Q_j(cot^2 u).

    Row j (1..count), column i: coefficient of x^i.  Built from
    P_1(c) = -(1 + c^2), P_{n+1}(c) = -(1 + c^2) P_n'(c) (P_n = cot^(n) in c).
    """
    table = np.zeros((count + 1, count + 1))
    poly = [-1, 0, -1]  # P_1, coefficients of c^0, c^1, c^2 (exact ints)
    n = 1
    while True:
        if n % 2 == 1:
            j = (n + 1) // 2
            if j > count:
                break
            den = factorial(2 * j + 1)
            for i in range(0, len(poly), 2):  # P_odd is even in c, all <= 0
                table[j, i // 2] = float(Fraction(-poly[i], den))
        # P_{n+1} = -(1 + c^2) P_n'
        der = [i * poly[i] for i in range(1, len(poly))]
        nxt = [0] * (len(der) + 2)
        for i, cf in enumerate(der):
            nxt[i] -= cf
            nxt[i + 2] -= cf
        poly = nxt
        n += 1
    return table


CL2_SERIES = _cl2_series_table()
COT_DERIV = _cot_derivative_table()

_TWO_PI = 2.0 * np.pi


# --------------------------------------------------------------------------
# Clausen function and the exact panel integral of the log kernel
# --------------------------------------------------------------------------
@njit(cache=True)
def cl2(theta: float) -> float:
    """Clausen function Cl2(theta) = sum_n sin(n theta)/n^2 (odd, period 2 pi).

    Bernoulli series on |t| <= pi: Cl2(t) = t - t log|t| + sum_k |B_2k| t^(2k+1)/(2k (2k+1)!).
    Absolute accuracy a few ulp of max|Cl2| ~ 1.01.
    """
    t = theta - _TWO_PI * np.floor(theta / _TWO_PI + 0.5)  # t in [-pi, pi)
    sign = 1.0
    if t < 0.0:
        t = -t
        sign = -1.0
    if t == 0.0:
        return 0.0
    t2 = t * t
    acc = 0.0
    for k in range(CL2_SERIES.shape[0] - 1, -1, -1):
        acc = acc * t2 + CL2_SERIES[k]
    return sign * (t - t * np.log(t) + t * t2 * acc)


@njit(cache=True)
def cl2_array(theta: np.ndarray, out: np.ndarray) -> None:
    """out[i] = Cl2(theta[i])."""
    for i in range(theta.shape[0]):
        out[i] = cl2(theta[i])


@njit(cache=True)
def cl2_difference(theta: float, delta: float) -> float:
    """Cl2(theta + delta) - Cl2(theta - delta), accurate to ~eps * delta.

    Differencing two O(1) Clausen values loses log10(1/delta) digits, so when the
    segment is at least 3 delta away from the singular points (multiples of 2 pi)
    the Taylor series about theta is used instead (u = theta/2, c = cot u):
        -2 delta log(2 sin u) + 4 eta sum_{j>=1} eta^(2j) Q_j(c^2)/(2j+1)!,
    eta = delta/2, whose terms are positive and fall like (delta/theta)^(2j).
    The function is even in theta.
    """
    t = theta - _TWO_PI * np.floor(theta / _TWO_PI + 0.5)
    if t < 0.0:
        t = -t
    if t < 3.0 * delta:
        # near the singular point both values are O(delta log delta): no harm
        return cl2(t + delta) - cl2(t - delta)
    u = 0.5 * t
    s = np.sin(u)
    c = np.cos(u) / s
    x = c * c
    eta = 0.5 * delta
    e2 = eta * eta
    total = -2.0 * delta * np.log(2.0 * s)
    scale = 4.0 * eta
    tiny = 1e-18 * (abs(total) + delta)
    # eta^(2j) Q_j(x) = sum_i c_ji z^i e2^(j-i) with z = e2 x = (eta cot u)^2 <= 1/9: neither
    # factor over- or underflows (eta^(2j) and x^j do on grids of 2^37 panels and more)
    z = e2 * x
    for j in range(1, COT_DERIV.shape[0]):
        q = 0.0
        p = 1.0
        for i in range(j, -1, -1):
            q = q * z + COT_DERIV[j, i] * p
            p *= e2
        term = scale * q
        total += term
        if term < tiny:
            break
    return total


@njit(cache=True)
def panel_values(x: np.ndarray, nodes: int, out: np.ndarray) -> None:
    """Elastic panel influence at positions x (in wavelengths), unit compliance.

    out[i] = (2/pi) [Cl2(2 pi (x + h/2)) - Cl2(2 pi (x - h/2))], h = 1/nodes:
    k v at x due to unit pressure (units E_ref/(1-nu^2)) on the panel [-h/2, h/2]
    with J = 1 (eq. 2.2 integrated exactly over the panel).
    """
    delta = np.pi / nodes
    for i in range(x.shape[0]):
        out[i] = (2.0 / np.pi) * cl2_difference(_TWO_PI * x[i], delta)


@njit(cache=True)
def stencil_sum(values: np.ndarray, first: int, weights: np.ndarray, out: np.ndarray) -> None:
    """out[j] = sum_k weights[k] values[first + j + k] for j < out.size: a short stencil run
    along `values` in one pass (the far memory sources from the elastic column)."""
    m = weights.shape[0]
    for j in range(out.shape[0]):
        acc = 0.0
        for k in range(m):
            acc += weights[k] * values[first + j + k]
        out[j] = acc


@njit(cache=True)
def exponential_recursion(source: np.ndarray, a: float, out: np.ndarray) -> None:
    """Periodic solution of E_m = S_m + exp(-a) E_(m+1), E_(m+N) = E_m.

    This is the exact exponential smoothing E_m = sum_(q>=0) e^(-a q) S_(m+q)
    (periodic in q), computed in O(N): E_0 by the geometrically weighted sum over one
    period (Horner's rule, the same recursion started from 0) divided by 1 - e^(-a N) (with
    expm1), then backwards.
    """
    n = source.shape[0]
    r = np.exp(-a)
    acc = 0.0
    for q in range(n - 1, -1, -1):
        acc = source[q] + r * acc
    e0 = acc / (-np.expm1(-a * n))
    out[0] = e0
    nxt = e0
    for m in range(n - 1, 0, -1):
        nxt = source[m] + r * nxt
        out[m] = nxt


@njit(cache=True)
def exponential_recursion_down(source: np.ndarray, a: float, start: float, count: int,
                               out: np.ndarray) -> None:
    """E_k = S_k + exp(-a) E_(k+1) down from E_K = start (K = source.size), for k = K-1 .. 0;
    out[k] = E_k for k < count (a window's recursion, started from the exact integral
    beyond it)."""
    r = np.exp(-a)
    e = start
    for k in range(source.shape[0] - 1, -1, -1):
        e = source[k] + r * e
        if k < count:
            out[k] = e


# --------------------------------------------------------------------------
# Contact loops
# --------------------------------------------------------------------------
@njit(cache=True)
def update_active_set(active: np.ndarray, pressure: np.ndarray,
                      gap: np.ndarray, out: np.ndarray, eps_p: float = 0.0,
                      eps_g: float = 0.0) -> int:
    """Primal-dual active-set rule; returns how many entries changed.

    On the active set the gap is zero and a panel leaves when its pressure is
    below -eps_p; off it the pressure is zero and a panel enters when its gap
    is below -eps_g (interpenetration).  The small allowances stop panels whose
    pressure and gap are both zero to round-off from flipping back and forth.
    """
    changed = 0
    for i in range(active.shape[0]):
        if active[i]:
            out[i] = pressure[i] >= -eps_p
        else:
            out[i] = gap[i] < -eps_g
        if out[i] != active[i]:
            changed += 1
    return changed


@njit(cache=True)
def contact_residuals(active: np.ndarray, pressure: np.ndarray,
                      gap: np.ndarray, out: np.ndarray) -> None:
    """out = [max |p g|, max |g| on the active set, max(0, -min g), max(0, -min p)]."""
    comp = 0.0
    gmax = 0.0
    pen = 0.0
    neg = 0.0
    for i in range(active.shape[0]):
        prod = abs(pressure[i] * gap[i])
        if prod > comp:
            comp = prod
        if active[i] and abs(gap[i]) > gmax:
            gmax = abs(gap[i])
        if -gap[i] > pen:
            pen = -gap[i]
        if -pressure[i] > neg:
            neg = -pressure[i]
    out[0] = comp
    out[1] = gmax
    out[2] = pen
    out[3] = neg
