"""The Fourier reference's result object (`FourierResult`) and its assembly from the levels:
the extrapolated scalars with their estimates, the closed form of full contact, a failure, and
the layer's uniform mode."""
from __future__ import annotations

import dataclasses
import math
import time
from dataclasses import dataclass, field

import numpy as np

from ._closed_form import _mean_displacement
from ._levels import _FLOOR, _KEYS, _RELATIVE, richardson
from ._measure import _wrap

_TWO_PI = 2.0 * math.pi

#: a patch narrower than this many points of the finest grid is not an answer (the edge fit
#: and the shift average need points inside; measured at p̃ = 1e-6, 4 points: errors of 4e-6 in
#: ka and 8e-5 in Δ/h, still within the estimates), and under four times as many is warned of
_MIN_PATCH_POINTS = 4


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
