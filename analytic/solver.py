"""The semi-analytic solver: load or penetration control, partial and full contact.

Partial contact reduces, for a given contact half-angle A = ka, to closed forms for ke, the load
and the penetration (`_closure.py`); the half-angle is then found by Brent's method on
y = log tan(A/2), which keeps relative precision both for vanishing contacts (A ≈ 2eʸ) and at the
transition to full contact (π − A ≈ 2e⁻ʸ), so the root is not lost as ka → π.

References: eqs (2.7)–(2.15), (3.1), Appendix A (elastic arc solution) and Appendix B (full
contact) of Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014; the
derivation of the closure is in `analytic/DERIVATION.md`.
"""
from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

from viscosine import table

from . import _kernels as K
from ._accepted import ACCEPTED, validate
from ._closure import Integrals, State, log_sin_half, state, westergaard_separation
from ._result import Solution
from .full_contact import friction_stress, modulus

# y = log tan(A/2) is searched in [_Y_MIN, _Y_MAX]: ka from 2e-65 (far below the smallest
# contact of the accepted loads, ~1e-23) to π − 8e-18 (p̃FC − p̃∞ ~ 1e-34 p̃FC: below rounding)
_Y_MIN, _Y_MAX = -150.0, 40.0
_CONVERGED = 1e-8  # a residual above this marks the solution as failed
#: two residuals are differences of terms about ρ times larger than their result, so their own
#: round-off is about ρ ε: the check of (2.14), which sums the contact density within the memory
#: layer 1/β = V/V0/ρ of the trailing edge (measured 2.2 ρ ε at ρ = 1e8 just below the
#: transition, 1.5e-10 at ρ = 1e6), and the root search's target under penetration control at
#: high speed (3.0 ρ ε at ρ = 1e8, V/V0 = 1e30).  Their gate is this many ρ ε where that exceeds
#: _CONVERGED (from ρ ≈ 2e6 up; 4.4e-7 at the largest accepted ρ, 1e8)
_ROUNDOFF_RHO = 20.0
_RHO_BOUND = ("closure_2_14", "target")


def _angles(y):
    """A = ka and G = π − A from y = log tan(A/2), each without cancellation."""
    return 2.0 * math.atan(math.exp(y)), 2.0 * math.atan(math.exp(-y))


def _y_of_sin2(s):
    s = min(max(s, 1e-300), 1.0 - 1e-16)
    return 0.5 * (math.log(s) - math.log1p(-s))


def _elastic_state(A, G):
    """Speed exactly 0: Westergaard's solution with E0 (Hc = 1, κ = 0, e = 0)."""
    sA2 = math.sin(0.5 * A) ** 2
    if sA2 <= 0.5:  # each of Δ/h and s/h where it is the small one (see _closure.state)
        pen = sA2 * (1.0 - 2.0 * log_sin_half(A, G))
        sep = 1.0 - pen
    else:
        sep = westergaard_separation(math.sin(0.5 * G) ** 2)
        pen = 1.0 - sep
    nan = float("nan")
    return State(A, G, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, sA2, sep, pen, 0.0, 0.0,
                 Integrals(nan, nan, nan, nan, nan, nan))


def _closure_residuals(st):
    """Residuals of (2.14), (2.15), σ(−a) over the mean contact pressure and the gap at +a."""
    r214, r215 = K.paper_closures(st.A, st.G, st.w, st.rho, st.ke, st.Hc, st.Hs, st.kappa)
    s_trail = K.contact_pressure(-st.A, st.A, st.G, st.rho / st.w, st.Hc, st.Hs, st.kappa)
    g_lead = K.gap_function(st.A, st.A, st.G, st.w, st.Hc, st.Hs, st.kappa)
    # σ − εσ' = p resolves σ to rounding of its own scale, the contact pressure P̄π/A, not of
    # the mean over the period (smaller by a/λ)
    return {"closure_2_14": r214, "closure_2_15": r215,
            "sigma_trailing_edge": abs(s_trail) * st.A / (math.pi * st.Pbar),
            "gap_leading_edge": abs(g_lead)}


def _invalid(values):
    """The first violated physical constraint of a partial-contact result, or None."""
    for name, v in values.items():
        if not (isinstance(v, float) and math.isfinite(v)):
            return f"{name} = {v!r} is not finite"
    if not 0.0 < values["ka"] < math.pi:
        return f"ka = {values['ka']!r} outside (0, π)"
    if not 0.0 < values["penetration"] <= 1.0 or values["separation"] < 0.0:
        return f"Δ/h = {values['penetration']!r} outside (0, 1]"
    if values["load"] <= 0.0:
        return f"load = {values['load']!r} ≤ 0"
    if values["tau_f"] < 0.0 or values["mu"] < 0.0:
        return f"μ = {values['mu']!r} < 0"
    if values["speed"] > 0.0 and values["mu"] <= 0.0:
        return f"μ = {values['mu']!r}: friction underflowed at speed {values['speed']!r}"
    return None


def _make_partial(st, inputs, nit, nfev, target_residual, converged, message):
    speed, hk = inputs["speed"], inputs["hk"]
    res = {"target": target_residual}
    if speed > 0.0:
        res.update(_closure_residuals(st))
    floor = max(_CONVERGED, _ROUNDOFF_RHO * 2.220446049250313e-16 * st.rho)
    gate = {key: floor for key in _RHO_BOUND}
    over = {k: v / gate.get(k, _CONVERGED) for k, v in res.items()}
    worst_key = max(over, key=lambda k: over[k])
    worst, limit = res[worst_key], gate.get(worst_key, _CONVERGED)
    ok = converged and all(v < 1.0 for v in over.values())  # NaN residuals fail here too
    if converged and not ok:
        message = f"closure residuals too large ({worst:.2e} ≥ {limit:g}); not a solution"
    load = 0.5 * hk * st.Pbar if inputs["control"] == "penetration" else inputs["asked"]
    tau = hk * hk * st.tau_hat
    values = {"load": load, "speed": speed, "ka": st.A, "ke": st.ke, "ke_hat": st.ke_hat,
              "penetration": st.pen, "separation": st.sep, "tau_f": tau, "mu": tau / load}
    if ok:
        bad = _invalid(values)
        if bad is not None:
            ok, message = False, f"physically invalid result ({bad}); not a solution"
    return Solution(success=ok, status=0 if ok else 1, message=message, nit=nit, nfev=nfev,
                    load=load, speed=speed, ratio=inputs["ratio"], hk=hk, full_contact=False,
                    contact_fraction=st.A / math.pi, ka=st.A, ke=st.ke, ke_hat=st.ke_hat,
                    penetration=st.pen, separation=st.sep, tau_f=tau, mu=tau / load,
                    residuals=res, control=inputs["control"], asked=inputs["asked"], _state=st)


def _full(load, inputs, message="full contact"):
    """Appendix B in closed form: Δ/h = 1, ka = π and s = 0 by construction."""
    speed, ratio, hk = inputs["speed"], inputs["ratio"], inputs["hk"]
    _, delta = modulus(speed, ratio)
    tau = friction_stress(speed, ratio, hk)
    return Solution(success=True, status=0, message=message, nit=0, nfev=0, load=load,
                    speed=speed, ratio=ratio, hk=hk, full_contact=True, contact_fraction=1.0,
                    ka=math.pi, ke=None, ke_hat=delta, penetration=1.0, separation=0.0,
                    tau_f=tau, mu=tau / load, residuals={}, control=inputs["control"],
                    asked=inputs["asked"])


def _failed(inputs, message, nit=0, nfev=0):
    nan = math.nan
    load = inputs["asked"] if inputs["control"] == "load" else nan
    return Solution(success=False, status=1, message=message, nit=nit, nfev=nfev, load=load,
                    speed=inputs["speed"], ratio=inputs["ratio"], hk=inputs["hk"],
                    full_contact=False, contact_fraction=nan, ka=nan, ke=nan, ke_hat=nan,
                    penetration=nan, separation=nan, tau_f=nan, mu=nan, residuals={},
                    control=inputs["control"], asked=inputs["asked"])


def _state_at(y, speed, ratio):
    A, G = _angles(y)
    if speed == 0.0:
        return _elastic_state(A, G)
    return state(A, G, speed, ratio)


def _find_half_angle(fun, y_lo, y_hi):
    """Root of the increasing function fun(y) of y = log tan(A/2), bracketed from [y_lo, y_hi].

    Returns (y, converged, iterations, message); when no bracket exists within
    [_Y_MIN, _Y_MAX] the message says so and y is the last end tried.
    """
    lo = min(max(y_lo, _Y_MIN), _Y_MAX)
    hi = min(max(y_hi, lo + 1e-3), _Y_MAX)
    flo, fhi = fun(lo), fun(hi)
    while flo > 0.0 and lo > _Y_MIN:
        hi, fhi = lo, flo
        lo = max(lo - 2.0, _Y_MIN)
        flo = fun(lo)
    while fhi < 0.0 and hi < _Y_MAX:
        lo, flo = hi, fhi
        hi = min(hi + 2.0, _Y_MAX)
        fhi = fun(hi)
    if not (flo <= 0.0 <= fhi):
        return hi, False, 0, (f"could not bracket the contact half-width (residuals "
                              f"{flo:.2e} at ka = {_angles(lo)[0]:.3e}, {fhi:.2e} at ka = "
                              f"{_angles(hi)[0]:.17g})")
    y, info = brentq(fun, lo, hi, xtol=1e-14, rtol=4 * np.finfo(float).eps, maxiter=200,
                     full_output=True, disp=False)
    msg = "partial contact" if info.converged else f"root search did not converge ({info.flag})"
    return y, info.converged, info.iterations, msg


def _log_or_floor(v):
    # a non-positive iterate can only come from rounding at the far end of the search: treat it
    # as "far below" so that Brent keeps bisecting toward the root
    return math.log(v) if v > 0.0 else -1e300


def solve(*, load=None, penetration=None, speed, ratio=3.0, hk=1.0):
    """Solve the steady sliding problem under load or penetration control.

    Parameters
    ----------
    load : float, optional
        p̃∞ = p∞(1 − ν²)/E0 (load control), in the range of `analytic.ACCEPTED`.
    penetration : float, optional
        Δ/h in (0, 1] (penetration control; the load is an output).  Give exactly one of the two.
    speed : float
        V/V0 = V τ k ≥ 0 (τ the creep time of eq. 2.3); 0 is Westergaard's solution with E0.
    ratio : float
        E∞/E0 > 1.
    hk : float
        Amplitude times wavenumber, > 0.

    Returns
    -------
    Solution
        `success` is False, with the residuals and a message, when the root search or the
        closure failed or the result is not physically valid; it never raises for accepted
        input.

    Raises
    ------
    ValueError
        Input outside `analytic.ACCEPTED`, naming the parameter, its value and what is allowed.

    References
    ----------
    Eqs (2.7)–(2.15), (3.1) and Appendices A–B of the paper.
    """
    if (load is None) == (penetration is None):
        raise ValueError(f"load={load!r}, penetration={penetration!r} is not allowed: give "
                         "exactly one of load and penetration")
    for name, value in (("speed", speed), ("ratio", ratio), ("hk", hk)):
        if value is None:
            raise ValueError(f"{name}=None is not allowed: {ACCEPTED[name][2]}")
    v = validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk)
    control = "load" if load is not None else "penetration"
    inputs = {"control": control, "asked": v[control], "speed": v["speed"], "ratio": v["ratio"],
              "hk": v["hk"]}
    try:
        if control == "load":
            return _solve_load(inputs)
        return _solve_penetration(inputs)
    except (ArithmeticError, ValueError) as exc:  # never a traceback for accepted input
        return _failed(inputs, f"numerical failure: {type(exc).__name__}: {exc}")


def _solve_load(inputs):
    load, speed, ratio, hk = inputs["asked"], inputs["speed"], inputs["ratio"], inputs["hk"]
    target = 2.0 * load / hk
    if target >= modulus(speed, ratio)[0]:
        return _full(load, inputs)
    nfev = [0]
    logt = math.log(target)

    def fun(y):
        nfev[0] += 1
        return _log_or_floor(_state_at(y, speed, ratio).Pbar) - logt

    # the effective modulus lies between E0 and E∞: Westergaard bounds the contact
    y, ok, nit, msg = _find_half_angle(fun, _y_of_sin2(0.5 * target / ratio),
                                       _y_of_sin2(min(2.0 * target, 0.999)))
    st = _state_at(y, speed, ratio)
    if not ok and y >= _Y_MAX and st.Pbar < target:
        # P̄(π − 8e-18) < p̄ < |E|: p̃∞ equals p̃FC to rounding, the transition itself
        return _full(load, inputs, "load within rounding of the full-contact load")
    return _make_partial(st, inputs, nit, nfev[0], abs(st.Pbar / target - 1.0), ok, msg)


def _solve_penetration(inputs):
    """Δ/h = 1 is the transition itself: full contact at the smallest load that keeps it."""
    pen, speed, ratio, hk = inputs["asked"], inputs["speed"], inputs["ratio"], inputs["hk"]
    if pen == 1.0:
        fc = 1.0 if speed == 0.0 else modulus(speed, ratio)[0]
        return _full(0.5 * hk * fc, inputs, "full contact at the transition load")
    nfev = [0]
    logt = math.log(pen)

    def fun(y):
        nfev[0] += 1
        return _log_or_floor(_state_at(y, speed, ratio).pen) - logt

    # Westergaard's Δ/h = s(1 − ln s), s = sin²(A/2), holds at both speed limits
    s0 = pen
    for _ in range(60):  # invert s(1 − ln s) = Δ/h by fixed point, enough for a bracket
        s0 = pen / (1.0 - math.log(s0))
    y, ok, nit, msg = _find_half_angle(fun, _y_of_sin2(0.5 * s0), _y_of_sin2(min(2.0 * s0, 0.999)))
    st = _state_at(y, speed, ratio)
    return _make_partial(st, inputs, nit, nfev[0], abs(st.pen / pen - 1.0), ok, msg)


def sweep(*, load=None, penetration=None, speed, ratio=3.0, hk=1.0):
    """Solve every (load or penetration, speed) pair: loads outer, speeds inner.

    Parameters
    ----------
    load, penetration : sequence of float
        Exactly one: the controls (outer loop).
    speed : sequence of float
        V/V0 (inner loop).
    ratio, hk : float
        As in `solve`.

    Returns
    -------
    dict of ndarray
        The table of `viscosine.table.sweep`: inputs, ``success``, the eight scalars (NaN where
        null), separation, max_pressure, x_max_pressure, n_patches and ``message``.  Bad input
        raises ValueError before any point is solved; a failing point is a row with success False.
    """
    return table.sweep(solve, validate, load=load, penetration=penetration, speed=speed,
                        ratio=ratio, hk=hk)
