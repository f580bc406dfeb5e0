"""The semi-analytic solver: load or penetration control, partial and full contact.

Partial contact reduces, for a given contact half-angle A = ka, to closed forms for ke, the load
and the penetration (`_closure.py`); the half-angle is then found by Brent's method on
y = log tan(A/2), which keeps relative precision both for vanishing contacts (A ≈ 2eʸ) and at the
transition to full contact (π − A ≈ 2e⁻ʸ), so the root is not lost as ka → π.

References: eqs (2.7)–(2.15), (3.1), Appendix A (elastic arc solution) and Appendix B (full
contact) of the paper; the derivation of the closure is in `analytic/DERIVATION.md`.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from . import _kernels as K
from ._closure import Integrals, State, log_sin_half, state
from .full_contact import friction_stress, modulus
from viscosine import Fields

#: speeds outside this range are refused: beyond it the viscoelastic corrections (O(w), O(1/w))
#: are below double precision and the quadrature would need thousands of panels
SPEED_RANGE = (1e-30, 1e30)
_Y_MAX = 40.0  # |log tan(A/2)| ≤ 40: ka from 8e-18 to π − 8e-18
_CONVERGED = 1e-8  # a residual above this marks the solution as failed


def _check_finite(name, value, allowed):
    if not isinstance(value, (int, float, np.floating, np.integer)) or isinstance(value, bool):
        raise ValueError(f"{name} = {value!r}: must be a real number {allowed}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} = {value!r}: must be finite and {allowed}")
    return value


_ALLOWED = {  # parameter: (what is allowed, test)
    "load": ("> 0", lambda v: v > 0.0),
    "speed": ("≥ 0", lambda v: v >= 0.0),
    "ratio": ("> 1 (E∞ > E0)", lambda v: v > 1.0),
    "hk": ("> 0", lambda v: v > 0.0),
    "penetration": ("in (0, 1] (Δ/h)", lambda v: 0.0 < v <= 1.0),
}


def validate(load=None, speed=None, ratio=None, hk=None, penetration=None):
    """Check the dimensionless inputs; raise ValueError naming the parameter, value and range."""
    given = {"load": load, "speed": speed, "ratio": ratio, "hk": hk, "penetration": penetration}
    out = {}
    for name, value in given.items():
        if value is None:
            continue
        allowed, ok = _ALLOWED[name]
        v = _check_finite(name, value, allowed)
        if not ok(v):
            raise ValueError(f"{name} = {v!r}: must be {allowed}")
        out[name] = v
    v = out.get("speed", 0.0)
    if v != 0.0 and not SPEED_RANGE[0] <= v <= SPEED_RANGE[1]:
        raise ValueError(f"speed = {v!r}: must be 0 or within [{SPEED_RANGE[0]:g}, {SPEED_RANGE[1]:g}]"
                         " (beyond, the viscoelastic correction is below double precision)")
    return out


@dataclass(frozen=True)
class Solution:
    """One operating point of the semi-analytic solver (SciPy-like result object).

    Scalars follow `conventions.md`; `residuals` holds the closure residuals evaluated with the
    full singular integrands of (2.14)–(2.15) on a quadrature independent of the one the
    closure was solved with, σ at the trailing edge and the jump of v at the leading edge.
    """

    success: bool
    status: int
    message: str
    nit: int
    nfev: int
    load: float
    speed: float
    ratio: float
    hk: float
    full_contact: bool
    contact_fraction: float
    ka: float
    ke: float | None
    ke_hat: float
    penetration: float
    separation: float
    tau_f: float
    mu: float
    residuals: dict = field(default_factory=dict)
    _state: State | None = field(default=None, repr=False)

    def as_dict(self):
        """Inputs and the output keys of `conventions.md` (JSON-ready)."""
        return {"solver": "analytic", "load": self.load, "speed": self.speed, "ratio": self.ratio,
                "hk": self.hk, "full_contact": self.full_contact,
                "contact_fraction": self.contact_fraction, "ka": self.ka, "ke": self.ke,
                "ke_hat": self.ke_hat, "penetration": self.penetration, "tau_f": self.tau_f,
                "mu": self.mu}

    def fields(self, x_over_lambda=None):
        """Pressure, displacement and gap at x/λ (crest frame; default x/λ = j/1024 − ½)."""
        X = (np.arange(1024) / 1024 - 0.5 if x_over_lambda is None
             else np.asarray(x_over_lambda, float))
        hk = self.hk
        if self.full_contact:
            mag, delta = modulus(self.speed, self.ratio)
            p = self.load + 0.5 * hk * mag * np.cos(2 * np.pi * X - delta)
            return Fields(X, p, np.cos(2 * np.pi * X), np.zeros_like(X))
        st = self._state
        A, G = st.A, st.G
        theta = 2.0 * np.pi * X - st.ke                      # contact-centred angle
        theta = np.mod(theta + A, 2.0 * np.pi) - A           # into [−A, 2π − A)
        inside = theta <= A
        p = np.zeros_like(X)
        u = np.zeros_like(X)
        if self.speed == 0.0:  # Westergaard: P = P_W, u = D (u − w u' = D at w = 0)
            th = theta[inside]
            p[inside] = [K.contact_density(A + t, A - t, G, 1.0, 0.0, 0.0) for t in th]
            sA = math.sin(0.5 * A)
            u[~inside] = [K.gap_density(t - A, 2.0 * math.pi - A - t, sA, 1.0, 0.0, 0.0)
                          for t in theta[~inside]]
        else:
            th = np.ascontiguousarray(theta[inside])
            out = np.empty_like(th)
            K.contact_pressure_many(th, A, G, st.rho / st.w, st.Hc, st.Hs, st.kappa, out)
            p[inside] = out
            th = np.ascontiguousarray(theta[~inside])
            out = np.empty_like(th)
            K.gap_function_many(th, A, G, st.w, st.Hc, st.Hs, st.kappa, out)
            u[~inside] = out
        pressure = 0.5 * hk * p
        displacement = np.cos(2.0 * np.pi * X) - st.sep + u
        return Fields(X, pressure, displacement, u)

    def check(self):
        """Consistency of the solved fields (paper-notes, last paragraph), with graded quadrature.

        Returns a dict: min_pressure_over_load (σ ≥ 0 in the contact), min_gap (over h, ≥ 0
        outside), mean_pressure_error (|mean σ − p∞|/p∞), mean_displacement (mean v over h, 0),
        separation_error (mean gap − s, over h), pressure_at_edges (σ(±a)/p∞) and
        gap_at_edges (v jump at ±a, over h).  All vanish, up to round-off, for a correct solution.
        """
        if self.full_contact:
            mag, _ = modulus(self.speed, self.ratio)
            return {"min_pressure_over_load": 1.0 - 0.5 * self.hk * mag / self.load,
                    "min_gap": 0.0, "mean_pressure_error": 0.0, "mean_displacement": 0.0,
                    "separation_error": 0.0, "pressure_at_edges": 0.0, "gap_at_edges": 0.0}
        st = self._state
        A, G = st.A, st.G
        moving = st.w > 0.0
        # contact rule refined to the pressure memory layer ε = w/ρ at the edges, gap rule to w
        layer_c = st.w / st.rho if moving else math.inf
        layer_g = st.w if moving else math.inf
        tL, _, wc = K.graded_nodes(2.0 * A, 0.25 * min(layer_c, 2.0 * G, 2.0 * A),
                                   0.25 * min(layer_c, 2.0 * G, 2.0 * A))
        uL, _, wg = K.graded_nodes(2.0 * G, 0.25 * min(layer_g, 2.0 * A, 2.0 * G),
                                   0.25 * min(layer_g, 2.0 * A, 2.0 * G))
        fc = self.fields((tL - A + st.ke) / (2.0 * math.pi))
        fg = self.fields((A + uL + st.ke) / (2.0 * math.pi))
        mean_p = np.dot(wc, fc.pressure) / (2.0 * math.pi)
        mean_v = (np.dot(wc, fc.displacement) + np.dot(wg, fg.displacement)) / (2.0 * math.pi)
        mean_gap = np.dot(wg, fg.gap) / (2.0 * math.pi)
        if moving:
            beta = st.rho / st.w
            sig_edges = [K.contact_pressure(e, A, G, beta, st.Hc, st.Hs, st.kappa) for e in (-A, A)]
            gap_edges = [K.gap_function(e, A, G, st.w, st.Hc, st.Hs, st.kappa)
                         for e in (A, 2.0 * math.pi - A)]
        else:  # Westergaard: both vanish identically
            sig_edges = gap_edges = [0.0]
        return {"min_pressure_over_load": float(fc.pressure.min() / self.load),
                "min_gap": float(fg.gap.min()),
                "mean_pressure_error": float(abs(mean_p / self.load - 1.0)),
                "mean_displacement": float(abs(mean_v)),
                "separation_error": float(abs(mean_gap - st.sep)),
                "pressure_at_edges": float(np.max(np.abs(sig_edges)) * 0.5 * self.hk / self.load),
                "gap_at_edges": float(np.max(np.abs(gap_edges)))}


def _angles(y):
    """A = ka and G = π − A from y = log tan(A/2), each without cancellation."""
    return 2.0 * math.atan(math.exp(y)), 2.0 * math.atan(math.exp(-y))


def _y_of_sin2(s):
    s = min(max(s, 1e-300), 1.0 - 1e-16)
    return 0.5 * (math.log(s) - math.log1p(-s))


def _elastic_state(A, G):
    """Speed exactly 0: Westergaard's solution with E0 (Hc = 1, κ = 0, e = 0)."""
    sA2 = math.sin(0.5 * A) ** 2
    pen = sA2 * (1.0 - 2.0 * log_sin_half(A, G))
    nan = float("nan")
    return State(A, G, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, sA2, 1.0 - pen, pen, 0.0, 0.0,
                 Integrals(nan, nan, nan, nan, nan, nan))


def _closure_residuals(st):
    """Residuals of (2.14), (2.15), σ(−a)/p∞ and the gap at +a (over h); see `Solution`."""
    r214, r215 = K.paper_closures(st.A, st.G, st.w, st.rho, st.ke, st.Hc, st.Hs, st.kappa)
    s_trail = K.contact_pressure(-st.A, st.A, st.G, st.rho / st.w, st.Hc, st.Hs, st.kappa)
    g_lead = K.gap_function(st.A, st.A, st.G, st.w, st.Hc, st.Hs, st.kappa)
    return {"closure_2_14": r214, "closure_2_15": r215,
            "sigma_trailing_edge": abs(s_trail) / st.Pbar, "gap_leading_edge": abs(g_lead)}


def _make_partial(st, load, speed, ratio, hk, nit, nfev, target_residual, converged, message):
    res = {"target": target_residual}
    if speed > 0.0:
        res.update(_closure_residuals(st))
    worst = max(res.values())
    ok = converged and worst < _CONVERGED
    if converged and not ok:
        message = f"closure residuals too large ({worst:.2e} ≥ {_CONVERGED:g}); not a solution"
    load_out = 0.5 * hk * st.Pbar if load is None else load
    tau = hk * hk * st.tau_hat
    return Solution(success=ok, status=0 if ok else 1, message=message, nit=nit, nfev=nfev,
                    load=load_out, speed=speed, ratio=ratio, hk=hk, full_contact=False,
                    contact_fraction=st.A / math.pi, ka=st.A, ke=st.ke, ke_hat=st.ke_hat,
                    penetration=st.pen, separation=st.sep, tau_f=tau, mu=tau / load_out,
                    residuals=res, _state=st)


def _full(load, speed, ratio, hk, message="full contact"):
    _, delta = modulus(speed, ratio)
    tau = friction_stress(speed, ratio, hk)
    return Solution(success=True, status=0, message=message, nit=0, nfev=0, load=load,
                    speed=speed, ratio=ratio, hk=hk, full_contact=True, contact_fraction=1.0,
                    ka=math.pi, ke=None, ke_hat=delta, penetration=1.0, separation=0.0,
                    tau_f=tau, mu=tau / load, residuals={})


def _state_at(y, speed, ratio):
    A, G = _angles(y)
    if speed == 0.0:
        return _elastic_state(A, G)
    return state(A, G, speed, ratio)


def _find_half_angle(fun, y_lo, y_hi):
    """Root of the increasing function fun(y) of y = log tan(A/2), bracketed from [y_lo, y_hi].

    Returns (y, converged, iterations, message); when no bracket exists within |y| ≤ 40 the
    message says so and y is the last end tried.
    """
    lo, hi = y_lo, max(y_hi, y_lo + 1e-3)
    flo, fhi = fun(lo), fun(hi)
    while flo > 0.0 and lo > -_Y_MAX:
        hi, fhi = lo, flo
        lo = max(lo - 2.0, -_Y_MAX)
        flo = fun(lo)
    while fhi < 0.0 and hi < _Y_MAX:
        lo, flo = hi, fhi
        hi = min(hi + 2.0, _Y_MAX)
        fhi = fun(hi)
    if flo > 0.0 or fhi < 0.0:
        return hi, False, 0, (f"could not bracket the contact half-width (residuals "
                              f"{flo:.2e} at ka = {_angles(lo)[0]:.3e}, {fhi:.2e} at ka = {_angles(hi)[0]:.17g})")
    y, info = brentq(fun, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200,
                     full_output=True, disp=False)
    msg = "partial contact" if info.converged else f"root search did not converge ({info.flag})"
    return y, info.converged, info.iterations, msg


def solve(*, load=None, penetration=None, speed, ratio=3.0, hk=1.0):
    """Solve the steady sliding problem under load or penetration control.

    Parameters
    ----------
    load : float, optional
        p̃∞ = p∞(1 − ν²)/E0 > 0 (load control).
    penetration : float, optional
        Δ/h in (0, 1] (penetration control; the load is an output).  Give exactly one of the two.
    speed : float
        V/V0 = V τ k ≥ 0 (τ the creep time of eq. 2.3).
    ratio : float
        E∞/E0 > 1.
    hk : float
        Amplitude times wavenumber, > 0.

    Returns
    -------
    Solution
        `success` is False, with the residuals, when the root search or the closure failed.

    References
    ----------
    Eqs (2.7)–(2.15), (3.1) and Appendices A–B of the paper.
    """
    if (load is None) == (penetration is None):
        raise ValueError(f"load = {load!r}, penetration = {penetration!r}: give exactly one of "
                         "load and penetration")
    if load is not None:
        return _solve_load(load, speed, ratio, hk)
    return _solve_penetration(penetration, speed, ratio, hk)


def _solve_load(load, speed, ratio=3.0, hk=1.0):
    """Solve the steady sliding problem at given mean pressure (load control).

    Parameters
    ----------
    load : float
        p̃∞ = p∞(1 − ν²)/E0 > 0.
    speed : float
        V/V0 = V τ k ≥ 0 (τ the creep time of eq. 2.3).
    ratio : float
        E∞/E0 > 1.
    hk : float
        Amplitude times wavenumber, > 0.

    Returns
    -------
    Solution
        `success` is False, with the residuals, when the root search or the closure failed.

    References
    ----------
    Eqs (2.7)–(2.15), (3.1) and Appendices A–B of the paper.
    """
    v = validate(load=load, speed=speed, ratio=ratio, hk=hk)
    load, speed, ratio, hk = v["load"], v["speed"], v["ratio"], v["hk"]
    target = 2.0 * load / hk
    if target >= modulus(speed, ratio)[0]:
        return _full(load, speed, ratio, hk)
    nfev = [0]
    logt = math.log(target)

    def fun(y):
        nfev[0] += 1
        return math.log(_state_at(y, speed, ratio).Pbar) - logt

    # the effective modulus lies between E0 and E∞: Westergaard bounds the contact
    y, ok, nit, msg = _find_half_angle(fun, _y_of_sin2(0.5 * target / ratio),
                                       _y_of_sin2(min(2.0 * target, 0.999)))
    st = _state_at(y, speed, ratio)
    if not ok and y >= _Y_MAX and st.Pbar < target:
        # within rounding of p̃FC: ka = π to double precision, the transition itself
        return _full(load, speed, ratio, hk, "load within rounding of the full-contact load")
    return _make_partial(st, load, speed, ratio, hk, nit, nfev[0], abs(st.Pbar / target - 1.0), ok, msg)


def _solve_penetration(penetration, speed, ratio=3.0, hk=1.0):
    """Solve at given penetration Δ/h in (0, 1] (figures 3b, 6, 7); the load is an output.

    Δ/h = 1 is the transition itself: full contact at the smallest load that keeps it.
    """
    v = validate(penetration=penetration, speed=speed, ratio=ratio, hk=hk)
    pen, speed, ratio, hk = v["penetration"], v["speed"], v["ratio"], v["hk"]
    if pen == 1.0:
        fc = 1.0 if speed == 0.0 else modulus(speed, ratio)[0]
        return _full(0.5 * hk * fc, speed, ratio, hk, "full contact at the transition load")
    nfev = [0]
    logt = math.log(pen)

    def fun(y):
        nfev[0] += 1
        return math.log(_state_at(y, speed, ratio).pen) - logt

    # Westergaard's Δ/h = s(1 − ln s), s = sin²(A/2), holds at both speed limits
    s0 = pen
    for _ in range(60):  # invert s(1 − ln s) = Δ/h by fixed point, enough for a bracket
        s0 = pen / (1.0 - math.log(s0))
    y, ok, nit, msg = _find_half_angle(fun, _y_of_sin2(0.5 * s0), _y_of_sin2(min(2.0 * s0, 0.999)))
    st = _state_at(y, speed, ratio)
    return _make_partial(st, None, speed, ratio, hk, nit, nfev[0], abs(st.pen / pen - 1.0), ok, msg)
