"""Tamaas as a third code: the result of a run in the project's conventions (`TamaasResult`)
and how its fields are measured (`_measure`: contact edges, patches, scalars; `_stepping`: the
time step snapped to whole cells).  Part of `comparisons.peers.tamaas`, which re-exports it.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

import viscosine
from viscosine import Fields
from viscosine.protocol import SCALAR_KEYS, Patch, plain

from ..fields import true_runs

_TWO_PI = 2.0 * math.pi


# ----------------------------------------------------------------------------- results
@dataclass(frozen=True)
class TamaasResult:
    """One operating point run by Tamaas to steady sliding (the project's result protocol).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (steady, every step of the last period converged), 0 or 1,
        what the run says, caveats.
    nit
        Time steps taken.
    load, speed, ratio, hk, nodes, dt
        Achieved p̃∞ (mean of σ̃ over the grid), V/V0, E∞/E0, hk, N and the time step used
        (units of τ, after snapping).
    full_contact, contact_fraction, ka, ke, ke_hat, penetration, separation, tau_f, mu
        The scalars of the conventions at the last period end (ka, ke, kê None with several
        patches; ke None in full contact); separation s/h = 1 − Δ/h.
    max_pressure, x_max_pressure
        Largest nodal σ̃ and its x/λ.
    n_patches, patches
        Contact patches (`Patch`).
    diagnostics
        steps, periods, dt_over_tau, dt_over_period, cells_per_step, steps_per_cell,
        steady_residual (largest relative change over the last period), steady_tail (its
        geometric tail, the estimated distance to the steady state), steady_history,
        solver_error (worst Tamaas error over the last period), tolerance,
        complementarity (largest |gap|/h where σ > 0, before it is set to 0),
        load_error (|mean σ̃ − p̃∞|/p̃∞), wall_time (s), tamaas_version.
    error_estimate
        None (one run has no error estimate; see `dt_study`).
    """

    success: bool
    status: int
    message: str
    warnings: tuple
    nit: int
    load: float
    speed: float
    ratio: float
    hk: float
    nodes: int
    dt: float
    full_contact: bool
    contact_fraction: float
    ka: float | None
    ke: float | None
    ke_hat: float | None
    penetration: float
    separation: float
    tau_f: float
    mu: float
    max_pressure: float
    x_max_pressure: float
    n_patches: int
    patches: tuple
    diagnostics: dict
    load_asked: float = math.nan
    error_estimate = None
    _fields: Fields | None = field(default=None, repr=False, compare=False)

    def scalars(self):
        """The eight scalars of the conventions (plain Python types, None where null)."""
        return {k: plain(getattr(self, k)) for k in SCALAR_KEYS}

    def as_dict(self):
        """The JSON record (serialisable with ``allow_nan=False``)."""
        rec = {"solver": "tamaas", "version": viscosine.__version__, "control": "load",
               "load_asked": self.load_asked, "speed": self.speed, "ratio": self.ratio,
               "hk": self.hk, "nodes": self.nodes, "dt": self.dt, "load": self.load}
        rec.update(self.scalars())
        rec.update({"separation": self.separation, "success": self.success,
                    "message": self.message, "warnings": list(self.warnings),
                    "max_pressure": self.max_pressure, "x_max_pressure": self.x_max_pressure,
                    "n_patches": self.n_patches, "patches": [asdict(p) for p in self.patches],
                    "diagnostics": self.diagnostics, "error_estimate": None})
        return plain(rec)

    def fields(self, x_over_lambda=None):
        """Pressure, displacement and gap at the last period end.

        Parameters
        ----------
        x_over_lambda : array_like, optional
            Positions x/λ in the crest frame; default Tamaas's grid j/N − ½, j = 0 … N − 1
            (the crest on node N/2).  Elsewhere the nodal values are interpolated linearly and
            periodically.

        Returns
        -------
        viscosine.Fields
            σ(1 − ν²)/E0, v/h and gap/h (conventions units).
        """
        f = self._fields
        if f is None:
            raise RuntimeError(f"no fields: the run failed ({self.message})")
        if x_over_lambda is None:
            return f
        X = np.atleast_1d(np.asarray(x_over_lambda, dtype=float))
        if X.ndim != 1 or not np.all(np.isfinite(X)):
            raise ValueError(f"x_over_lambda={x_over_lambda!r} is not allowed: a 1-D array of "
                             "finite positions x/λ")
        xp = f.x_over_lambda
        return Fields(X, *(np.interp(X, xp, a, period=1.0)
                           for a in (f.pressure, f.displacement, f.gap)))


# ----------------------------------------------------------------------------- measuring
def _edge_cells(g_near, g_far, s_in, s_next):
    """Where a contact edge lies between the last gap node and the first contact node.

    Returns the distance from the last gap node toward the contact, in cells (0 to 1).  Just
    outside an edge the gap grows like distance^(3/2), so gap^(2/3) is linear: it is
    extrapolated to zero from the two nearest gap nodes (measured on Westergaard's solution:
    edges within 0.15 cell at N = 256, 0.06 cell at N ≥ 512, against 0.3–0.7 cell for the
    nearest node).  With a single gap node, σ² (linear near the edge, σ ~ √distance) is
    extrapolated from the first two contact nodes instead.
    """
    if g_far is not None and g_far > g_near > 0.0:
        a, b = g_near ** (2.0 / 3.0), g_far ** (2.0 / 3.0)
        return min(a / (b - a), 1.0)
    if s_next is not None and s_next > s_in > 0.0:
        a, b = s_in * s_in, s_next * s_next
        return max(1.0 - a / (b - a), 0.0)
    return 0.5


def _measure(sigma, u, gap, h, load):
    """The scalars of one snapshot in the crest frame (arrays on x_j = j/N − ½).

    Returns a dict with the eight scalars, separation, max pressure and the patches.
    """
    n = sigma.size
    dx = 1.0 / n
    x = np.arange(n) * dx - 0.5
    # τ̃f = −(1/λ)∫σ̃ ∂u/∂x dx with a spectral derivative (u and x in λ): resisting > 0
    q = _TWO_PI * np.fft.rfftfreq(n, dx)
    uh = np.fft.rfft(u)
    uh[-1] = 0.0  # the Nyquist mode has no derivative on the grid
    slope = np.fft.irfft(1j * q * uh, n)
    tau_f = -float(np.mean(sigma * slope))
    tau_abs = float(np.mean(np.abs(sigma * slope)))
    s = float(np.mean(u))  # the mean gap: mean(u) − mean(profile), and the profile's mean is 0
    contact = sigma > 0.0
    jmax = int(np.argmax(sigma))
    out = {"tau_f": tau_f, "tau_abs": tau_abs, "mu": tau_f / load, "separation": s / h,
           "penetration": 1.0 - s / h, "max_pressure": float(sigma[jmax]),
           "x_max_pressure": float(x[jmax]), "load": float(np.mean(sigma))}
    runs = true_runs(contact)
    if len(runs) == 1 and runs[0][1] == n:  # full contact: σ̃ is p̃∞ + A cos(kx − δ) exactly
        delta = -float(np.angle(np.sum(sigma * np.exp(-1j * _TWO_PI * x))))
        patch = Patch(-0.5, 0.5, 1.0, out["load"], delta / _TWO_PI, 0.0, math.pi, None, delta)
        out.update(full_contact=True, contact_fraction=1.0, ka=math.pi, ke=None, ke_hat=delta,
                   patches=(patch,))
        return out
    def outside(i):  # the gap at node i, or None when i is in contact
        i %= n
        return None if contact[i] else float(gap[i])

    patches = []
    for first, length in runs:
        idx = (first + np.arange(length)) % n
        xs = x[first] + dx * np.arange(length)  # continuous across ±½
        sg = sigma[idx]
        nxt, prv = (float(sg[1]), float(sg[-2])) if length >= 2 else (None, None)
        trailing = xs[0] - dx * (1.0 - _edge_cells(outside(first - 1), outside(first - 2),
                                                   float(sg[0]), nxt))
        leading = xs[-1] + dx * (1.0 - _edge_cells(outside(first + length),
                                                   outside(first + length + 1), float(sg[-1]), prv))
        trailing, leading = float(trailing), float(leading)
        width = leading - trailing
        centroid = float(np.dot(xs, sg) / np.sum(sg))
        centre = 0.5 * (trailing + leading)
        wrap = math.floor(centre + 0.5)  # the crest nearest the patch; positions around it
        summit = float(min(max(wrap, trailing), leading))  # highest profile point in the patch
        patches.append(Patch(trailing - wrap, leading - wrap, width, float(np.sum(sg)) / n,
                             centroid - wrap, summit - wrap, math.pi * width,
                             _TWO_PI * (centre - summit), _TWO_PI * (centroid - summit)))
    width = sum(p.width for p in patches)
    one = patches[0] if len(patches) == 1 else None
    out.update(full_contact=False, contact_fraction=width,
               ka=None if one is None else one.ka, ke=None if one is None else one.ke,
               ke_hat=None if one is None else one.ke_hat, patches=tuple(patches))
    return out


def _stepping(dt, speed, nodes):
    """(cells per step, steps per cell, snapped dt) nearest the requested dt (geometrically).

    The indenter must come back onto grid node 0 after each period: so a step is a whole number
    of cells that divides N, or a cell is a whole number of steps.
    """
    t_cell = _TWO_PI / (speed * nodes)  # time to cross one cell, units of τ
    if dt is None:
        return 1, 1, t_cell
    r = dt / t_cell
    if r >= 1.0:
        divisors = [d for d in range(1, nodes + 1) if nodes % d == 0]
        m = min(divisors, key=lambda d: abs(math.log(d / r)))
        return m, 1, m * t_cell
    lo = max(1, math.floor(1.0 / r))
    s = min((lo, lo + 1), key=lambda k: abs(math.log(k * r)))
    return 1, s, t_cell / s
