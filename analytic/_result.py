"""The result of one operating point of the semi-analytic road (the result protocol).

Units as in `analytic/__init__.py`; positions x/λ in the crest frame (material streaming toward
−x, the leading edge of a contact is its +x edge); scalars, units and signs as in
`docs/conventions.md` ('Outputs: the scalars of one operating point').
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.optimize import brentq

from viscosine import Fields
from viscosine.protocol import SCALAR_KEYS, Patch, plain, record

from . import _kernels as K
from ._closure import State
from .full_contact import modulus

_TWO_PI = 2.0 * math.pi


def _wrap(x):
    """x/λ into [−½, ½) without touching values already there (keeps tiny positions exact)."""
    return x if -0.5 <= x < 0.5 else (x + 0.5) % 1.0 - 0.5


@dataclass(frozen=True)
class Solution:
    """One operating point of the semi-analytic solver (a SciPy-like result object).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (finite, converged, physically valid), 0 or 1, what the
        solver says, and any caveats (tuple of str).
    nit, nfev
        Root-search iterations and closure evaluations.
    load, speed, ratio, hk
        p̃∞ (achieved; the input under load control), V/V0, E∞/E0, hk.
    control, asked
        ``"load"`` or ``"penetration"`` and the value asked for.
    full_contact, contact_fraction, ka, ke, ke_hat, penetration, separation, tau_f, mu
        The scalars (ke None in full contact); separation s/h = 1 − Δ/h.
    residuals
        The road's convergence evidence: the root-search target, the closure (2.14)–(2.15)
        evaluated with the full singular integrands on a quadrature independent of the one the
        closure was solved with, σ at the trailing edge (over the mean contact pressure
        p∞λ/(2a)) and the jump of v at the leading edge (over h).  Empty in full contact (closed
        form).

    Notes
    -----
    ``max_pressure``, ``x_max_pressure``, ``patches`` and ``n_patches`` are computed on first
    use (the peak by Brent's method on σ − p = εσ′, eq. 2.8); ``check()`` evaluates the
    consistency of the fields by graded quadrature (a few ms, so not part of ``as_dict``).
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
    warnings: tuple = ()
    control: str = "load"
    asked: float | None = None
    _state: State | None = field(default=None, repr=False)
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    # ------------------------------------------------------------------ protocol
    error_estimate = None  # the semi-analytic road is exact up to its residuals

    @property
    def n_patches(self):
        return 1

    @property
    def patches(self):
        """(Patch,): one per period (full contact: spanning it)."""
        if "patches" not in self._cache:
            if self.full_contact:
                d = self.ke_hat
                p = Patch(-0.5, 0.5, 1.0, self.load, d / _TWO_PI, 0.0, math.pi, None, d)
            else:
                A, ke = self.ka, self.ke
                p = Patch((ke - A) / _TWO_PI, (ke + A) / _TWO_PI, A / math.pi, self.load,
                          self.ke_hat / _TWO_PI, 0.0, A, ke, self.ke_hat)
            self._cache["patches"] = (p,)
        return self._cache["patches"]

    @property
    def max_pressure(self):
        """Peak of σ(1 − ν²)/E0 over the period."""
        return self._peak()[0]

    @property
    def x_max_pressure(self):
        """x/λ of the peak of σ."""
        return self._peak()[1]

    @property
    def diagnostics(self):
        return {"nit": self.nit, "nfev": self.nfev, "residuals": dict(self.residuals)}

    def scalars(self):
        """The eight scalars of the conventions (plain Python types, None where null)."""
        return {k: plain(getattr(self, k)) for k in SCALAR_KEYS}

    def as_dict(self):
        """The JSON record (serialisable with ``allow_nan=False``; non-finite values are None)."""
        return record(self, "analytic")

    # ------------------------------------------------------------------ fields
    def _sigma(self, theta):
        """Σ = 2σ/(E*hk) at contact-centred angles θ in [−A, A] (array)."""
        st = self._state
        theta = np.ascontiguousarray(theta, dtype=float)
        out = np.empty_like(theta)
        if self.speed == 0.0:  # Westergaard: Σ = P_W = 2 cos(θ/2) r, r² = sin((A+θ)/2) sin((A−θ)/2)
            r2 = np.sin(0.5 * (st.A + theta)) * np.sin(0.5 * (st.A - theta))
            out[:] = 2.0 * np.cos(0.5 * theta) * np.sqrt(np.maximum(r2, 0.0))
        else:
            K.contact_pressure_many(theta, st.A, st.G, st.rho / st.w, st.Hc, st.Hs, st.kappa, out)
        return out

    def fields(self, x_over_lambda=None):
        """Pressure, displacement and gap over one period.

        Parameters
        ----------
        x_over_lambda : array_like, optional
            Positions x/λ in the crest frame (any real values: the fields are periodic);
            default j/1024 − ½, j = 0 … 1023.

        Returns
        -------
        viscosine.Fields
            σ(1 − ν²)/E0, v/h (from the mean line of the deformed surface) and gap/h.
        """
        X = (np.arange(1024) / 1024 - 0.5 if x_over_lambda is None
             else np.atleast_1d(np.asarray(x_over_lambda, dtype=float)))
        if X.ndim != 1 or not np.all(np.isfinite(X)):
            raise ValueError(f"x_over_lambda={x_over_lambda!r} is not allowed: a 1-D array of "
                             "finite positions x/λ")
        if not self.success:
            raise RuntimeError(f"no fields: the solve failed ({self.message})")
        hk = self.hk
        if self.full_contact:
            mag, delta = modulus(self.speed, self.ratio)
            pfc = 0.5 * hk * mag
            # σ = (p̃∞ − p̃FC) + hk|E| cos²((kx − δ)/2): ≥ 0 term by term (eq. B6)
            excess = max(self.load - pfc, 0.0)  # < 0 only by rounding of p̃FC (see solver)
            p = excess + hk * mag * np.cos(0.5 * (_TWO_PI * X - delta)) ** 2
            return Fields(X, p, np.cos(_TWO_PI * X), np.zeros_like(X))
        st = self._state
        A, G = st.A, st.G
        theta = _TWO_PI * X - st.ke                      # contact-centred angle
        theta = np.mod(theta + A, _TWO_PI) - A           # into [−A, 2π − A)
        inside = theta <= A
        p = np.zeros_like(X)
        u = np.zeros_like(X)
        p[inside] = self._sigma(theta[inside])
        if self.speed == 0.0:  # Westergaard: u = D (u − w u' = D at w = 0)
            sA = math.sin(0.5 * A)
            u[~inside] = [K.gap_density(t - A, _TWO_PI - A - t, sA, 1.0, 0.0, 0.0)
                          for t in theta[~inside]]
        else:
            th = np.ascontiguousarray(theta[~inside])
            out = np.empty_like(th)
            K.gap_function_many(th, A, G, st.w, st.Hc, st.Hs, st.kappa, out)
            u[~inside] = out
        pressure = 0.5 * hk * p
        displacement = np.cos(_TWO_PI * X) - st.sep + u
        return Fields(X, pressure, displacement, u)

    def _peak(self):
        """(max σ(1 − ν²)/E0, its x/λ): closed form in full contact and at speed 0; otherwise
        the root of Σ − P = εΣ′ (eq. 2.8) bracketed from a scan of the contact."""
        if "peak" in self._cache:
            return self._cache["peak"]
        if not self.success:
            peak = (math.nan, math.nan)
        elif self.full_contact:
            mag, delta = modulus(self.speed, self.ratio)
            peak = (self.load + 0.5 * self.hk * mag, delta / _TWO_PI)
        elif self.speed == 0.0:  # Westergaard: 2 cos(θ/2) r, largest at θ = 0, value 2 sin(A/2)
            peak = (self.hk * math.sin(0.5 * self.ka), 0.0)
        else:
            peak = self._peak_partial()
        self._cache["peak"] = peak
        return peak

    def _peak_partial(self):
        st = self._state
        A, G = st.A, st.G
        beta = st.rho / st.w

        def sigma(t):
            return K.contact_pressure(t, A, G, beta, st.Hc, st.Hs, st.kappa)

        def density(t):  # P(θ) from the distances to both edges
            return K.contact_density(A + t, A - t, G, st.Hc, st.Hs, st.kappa)

        # scan on Chebyshev points (dense near both edges, where the memory layer sits)
        n = 48
        t = -A * np.cos(np.pi * (np.arange(1, n) / n))
        s = self._sigma(t)
        j = int(np.argmax(s))
        lo = t[j - 1] if j > 0 else -A
        hi = t[j + 1] if j < n - 2 else A
        best_t, best = float(t[j]), float(s[j])
        g = lambda x: sigma(x) - density(x)  # = εΣ′: > 0 rising, < 0 falling
        a, b = (lo, float(t[j])) if g(float(t[j])) < 0.0 else (float(t[j]), hi)
        try:
            if g(a) > 0.0 > g(b):
                r = brentq(g, a, b, xtol=1e-15 * A, rtol=4 * np.finfo(float).eps, maxiter=200)
                val = sigma(r)
                if val >= best:
                    best_t, best = r, val
        except (ValueError, ArithmeticError):
            pass  # keep the scan's best point
        x = _wrap((best_t + st.ke) / _TWO_PI)
        return 0.5 * self.hk * best, x

    # ------------------------------------------------------------------ consistency
    def check(self):
        """Consistency of the solved fields (eqs 2.12–2.15 and the load), by graded quadrature.

        Returns
        -------
        dict
            ``min_pressure`` (min σ in the contact over the mean contact pressure p∞λ/(2a), ≥ 0),
            ``min_gap`` (over h, ≥ 0 outside), ``mean_pressure_error`` (|mean σ − p∞|/p∞),
            ``mean_displacement`` (mean v over h, 0), ``separation_error`` (mean gap − s, over
            h), ``pressure_at_edges`` (σ(±a) over p∞λ/(2a)), ``gap_at_edges`` (v jump at ±a,
            over h) and ``friction_error`` (the closed-form τ̃f against the quadrature of
            (1/λ)∫σ ∂v/∂x, over the quadrature of its absolute value).  All vanish, up to
            round-off, for a correct solution.
        """
        if not self.success:
            raise RuntimeError(f"nothing to check: the solve failed ({self.message})")
        if self.full_contact:
            mag, _ = modulus(self.speed, self.ratio)
            return {"min_pressure": max(self.load - 0.5 * self.hk * mag, 0.0) / self.load,
                    "min_gap": 0.0, "mean_pressure_error": 0.0, "mean_displacement": 0.0,
                    "separation_error": 0.0, "pressure_at_edges": 0.0, "gap_at_edges": 0.0,
                    "friction_error": 0.0}
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
        sig = 0.5 * self.hk * self._sigma(tL - A)
        fg = self.fields((A + uL + st.ke) / _TWO_PI)
        xc = (tL - A + st.ke) / _TWO_PI
        v_contact = np.cos(_TWO_PI * xc) - st.sep
        contact_mean = self.load * math.pi / A   # p∞ λ/(2a)
        mean_p = np.dot(wc, sig) / _TWO_PI
        mean_v = (np.dot(wc, v_contact) + np.dot(wg, fg.displacement)) / _TWO_PI
        mean_gap = np.dot(wg, fg.gap) / _TWO_PI
        # τ̃f = (1/λ)∫σ ∂v/∂x dx, ∂v/∂x = −hk sin(kx) in the contact; resisting > 0
        slope = np.sin(tL - A + st.ke)
        fr = self.hk * np.dot(wc, sig * slope) / _TWO_PI
        fr_abs = self.hk * np.dot(wc, np.abs(sig * slope)) / _TWO_PI
        if moving:
            beta = st.rho / st.w
            sig_edges = [K.contact_pressure(e, A, G, beta, st.Hc, st.Hs, st.kappa) for e in (-A, A)]
            gap_edges = [K.gap_function(e, A, G, st.w, st.Hc, st.Hs, st.kappa)
                         for e in (A, _TWO_PI - A)]
        else:  # Westergaard: both vanish identically
            sig_edges = gap_edges = [0.0]
        return {"min_pressure": float(sig.min() / contact_mean),
                "min_gap": float(fg.gap.min()),
                "mean_pressure_error": float(abs(mean_p / self.load - 1.0)),
                "mean_displacement": float(abs(mean_v)),
                "separation_error": float(abs(mean_gap - st.sep)),
                "pressure_at_edges": float(np.max(np.abs(sig_edges)) * 0.5 * self.hk / contact_mean),
                "gap_at_edges": float(np.max(np.abs(gap_edges))),
                "friction_error": float(abs(fr - self.tau_f) / fr_abs) if fr_abs > 0 else 0.0}
