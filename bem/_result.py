"""Result objects of :func:`bem.solve` (frozen, SciPy-like), with the result protocol of the
semi-analytic road (`scalars`, `as_dict`, `fields`, patches, diagnostics)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np

from viscosine import Fields, protocol
from viscosine.protocol import SCALAR_KEYS, plain

#: BemResult.status: one name per outcome (as scipy.optimize's status codes), and MESSAGES says
#: what each means.  The solver's messages add the particulars (residuals, grids, estimates).
CONVERGED = 0
OUTER_EXHAUSTED = 1
KRYLOV_FAILED = 2
CYCLED = 3
STATUS_INVALID = 4
STATUS_TARGET = 5
MESSAGES = MappingProxyType({
    CONVERGED: "converged",
    OUTER_EXHAUSTED: "the active-set (outer) iterations were exhausted",
    KRYLOV_FAILED: "a Krylov solve did not reach tol",
    CYCLED: "the active set cycled",
    STATUS_INVALID: "converged, but the answer failed the validity gate",
    STATUS_TARGET: "the adaptive mesh stopped before its estimated errors met rtol",
})
#: status of a contact-window grid whose contact reaches the window's ends: never on a result
#: (the adaptive mesh then answers from its periodic grids), hence not in MESSAGES
WINDOW_FAILED = 6


@dataclass(frozen=True)
class Patch(protocol.Patch):
    """One contact patch (positions x/λ, crest at 0): the protocol's patch plus its panels.

    Attributes
    ----------
    trailing_edge, leading_edge : float
        Sub-panel estimates of the −x and +x edges (leading > trailing; the pair may straddle
        ±½); in full contact −½ and ½.
    width : float
        leading − trailing (2a/λ).
    load : float
        The patch's share of the mean pressure (its panels' sum over N).
    centroid : float
        x/λ of the pressure centroid over its panels (full contact: summit + kê/2π).
    summit : float
        x/λ of the highest profile point inside the patch (0, the crest, for the sinusoid),
        unwrapped like the edges.
    ka, ke, ke_hat : float
        π·width, 2π(centre − summit) (None in full contact), 2π(centroid − summit).
    panels : int
        Active panels in the patch.
    """

    panels: int = 0


def _frozen_array(a) -> np.ndarray:
    # a float array that owns its data (the solver's fresh output) is frozen in place rather
    # than copied: at N = 2^20 the four fields are 32 bytes per panel
    if isinstance(a, np.ndarray) and a.dtype == np.float64 and a.base is None and a.flags.owndata:
        arr = a
    else:
        arr = np.array(a, dtype=float, copy=True)
    arr.flags.writeable = False
    return arr


@dataclass(frozen=True)
class BemResult:
    """Steady viscoelastic sliding of a rigid periodic indenter, solved by the BEM.

    Units as in ``conventions.md``: pressures in ``E_ref/(1 - nu^2)`` (``E0`` for the
    standard linear solid), displacements and gaps over the amplitude ``h``,
    positions in wavelengths with the crest at 0.

    Attributes
    ----------
    success : bool
        True when the active set converged, the last linear solve met ``tol`` and the answer
        passed the validity gate (every scalar finite, 0 < Δ/h ≤ 1, 0 < ka ≤ π, τf, μ ≥ 0,
        σ ≥ 0, gap ≥ 0, mean σ = load).  When False, the scalars and fields are the last
        iterate and are not an answer; ``message`` says why (with the residuals).
    status : int
        0 converged; 1 outer iterations exhausted; 2 a Krylov solve failed;
        3 the active set cycled; 4 converged but physically invalid; 5 the adaptive mesh
        stopped (at ``max_nodes``, or on grids that did not converge) before its estimated
        errors met ``rtol``.  ``bem.MESSAGES`` maps each code to its meaning.
    message : str
    nit : int
        Active-set (outer) iterations on the finest grid.
    inner_iterations : tuple of int
        Krylov iterations of each outer step on the finest grid (0 for a direct
        full-contact solve).
    residuals : mapping
        ``complementarity`` max |sigma gap| (sigma in E*, gap over h);
        ``contact_gap`` max |gap|/h on the active set; ``interpenetration``
        max(0, -min gap)/h; ``negative_pressure`` max(0, -min sigma)/max sigma;
        ``load_balance`` |mean sigma - load|/load; ``krylov`` 2-norm of the residual of
        the last linear solve over h k; ``friction_mismatch`` relative difference between
        the two estimates of tau_f (dissipation and direct), a discretisation
        indicator, not a convergence residual.
    levels : tuple of (nodes, nit, inner iterations)
        The nested-iteration history, coarse to fine.
    memory_layer_panels : float
        Panels across the thinnest pressure memory layer, speed × (shortest relaxation time)
        (`Prony.relaxation_times`); inf at speed 0.  Below about 3 the contact edges carry an
        error of the order of the layer: e.g. at V/V0 = 1e-6 the true half-width is
        ka_W − (1 − 1/ρ)(V/V0)/2, a shift no N ≤ 2^20 resolves; the message says so below 1.
    full_contact, contact_fraction, ka, ke, ke_hat, penetration, separation, tau_f, mu
        The scalars of the conventions.  ka, ke, kê are those of the single patch, measured
        from its summit; with several patches they are None (no single patch describes the
        contact; see ``patches``); ke is None in full contact.
    patches : tuple of Patch
        One per contact patch (full contact: one spanning the period).
    control, asked
        ``"load"`` or ``"penetration"`` and the value asked for.
    ratio, hk
        E∞/E0 as given for the standard linear solid (None for any other Prony series) and hk
        of the sinusoid (None for any other profile).
    warnings : tuple of str
        Caveats (a patch spanning few panels, an unresolved memory layer).
    error_estimate : mapping or None
        The solver's estimate of the discretisation error of each scalar, from its last three
        or four grids (N/8,) N/4, N/2, N (absolute for ka, ke, kê; relative, over the scalar's
        magnitude, for penetration, tau_f, mu, contact_fraction, and under penetration control
        the load, an output there; a key is None where its scalar is), None when the grids
        cannot support one
        (fewer than three converged, a patch under 8 panels, a patch count changing with N).
    rtol : float or None
        The accuracy target of an adaptive mesh; None when ``nodes`` fixed the mesh.
    extra_diagnostics : mapping
        Anything else the solver reports; part of ``diagnostics``.
    edges : ndarray or None
        The cell edges (x/λ) of the fields' grid when it is not uniform (after a contact
        window: the window's panels and the coarse periodic panels, see `fields`); None for the
        uniform grid of ``nodes`` panels.
    """

    success: bool
    status: int
    message: str
    nit: int
    inner_iterations: tuple
    residuals: Mapping[str, float]
    nodes: int
    speed: float
    material: Any
    profile: Any
    load: float
    full_contact: bool
    contact_fraction: float
    ka: float | None
    ke: float | None
    ke_hat: float | None
    penetration: float
    tau_f: float
    mu: float
    separation: float
    x_over_lambda: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    patches: tuple = ()
    levels: tuple = ()
    memory_layer_panels: float = math.inf
    control: str = "load"
    asked: float | None = None
    ratio: float | None = None
    hk: float | None = None
    warnings: tuple = ()
    error_estimate: Mapping | None = None
    rtol: float | None = None
    extra_diagnostics: Mapping = field(default_factory=dict, repr=False)
    edges: np.ndarray | None = field(default=None, repr=False)

    def __post_init__(self):
        for name in ("x_over_lambda", "pressure", "displacement", "gap"):
            object.__setattr__(self, name, _frozen_array(getattr(self, name)))
        if self.edges is not None:
            object.__setattr__(self, "edges", _frozen_array(self.edges))
        object.__setattr__(self, "residuals", MappingProxyType(dict(self.residuals)))
        object.__setattr__(self, "inner_iterations", tuple(int(i) for i in self.inner_iterations))
        object.__setattr__(self, "warnings", tuple(str(w) for w in self.warnings))
        object.__setattr__(self, "patches", tuple(self.patches))
        object.__setattr__(self, "extra_diagnostics",
                           MappingProxyType(dict(self.extra_diagnostics or {})))
        if self.error_estimate is not None:
            object.__setattr__(self, "error_estimate",
                               MappingProxyType(dict(self.error_estimate)))

    # ------------------------------------------------------------------ protocol
    @property
    def n_patches(self) -> int:
        """Number of contact patches per period (1 in full contact)."""
        return len(self.patches)

    @property
    def max_pressure(self) -> float:
        """Largest panel pressure σ(1 − ν²)/E_ref (a collocation value, not interpolated)."""
        return float(self.pressure.max()) if self.pressure.size else math.nan

    @property
    def x_max_pressure(self) -> float:
        """x/λ of the panel centre carrying `max_pressure`."""
        return float(self.x_over_lambda[int(np.argmax(self.pressure))]) \
            if self.pressure.size else math.nan

    @property
    def diagnostics(self) -> dict:
        """Iterations, residuals and resolution figures of the solve (plain dict)."""
        d = {"nit": self.nit, "inner_iterations": list(self.inner_iterations),
             "residuals": dict(self.residuals), "levels": [list(lv) for lv in self.levels],
             "memory_layer_panels": self.memory_layer_panels}
        d.update(self.extra_diagnostics)
        return d

    def as_dict(self) -> dict:
        """The JSON record (serialisable with ``allow_nan=False``; non-finite values are None).

        The keys of the semi-analytic road's record plus ``nodes``, on an adaptive mesh
        ``rtol`` and, on a layer, ``layer``: its thickness (k d and d/λ), foundation, ν, uniform
        compliance, ``mean_displacement`` and the indenter's ``approach`` (over h; see
        ``diagnostics["layer"]``, which the record carries here instead).
        """
        inputs = {"nodes": self.nodes}
        if self.rtol is not None:
            inputs["rtol"] = self.rtol
        layer = self.extra_diagnostics.get("layer")
        if layer is not None:
            inputs["layer"] = dict(layer)
        rec = protocol.record(self, "bem", inputs=inputs,
                              error_estimate=None if self.error_estimate is None
                              else dict(self.error_estimate))
        rec["diagnostics"].pop("layer", None)
        return rec

    def fields(self, x_over_lambda=None) -> Fields:
        """Pressure, displacement and gap over one period.

        Parameters
        ----------
        x_over_lambda : array_like, optional
            Positions x/λ (any real values: the fields are periodic).  Default: the panel
            centres ``j/N − ½``, where the values are the solver's own (after a contact window:
            the window's panels, a margin of its grid beyond each end, and outside that the
            panels of its coarse periodic grid, whose displacement is that of the window's
            pressure gathered onto them; a non-uniform grid, whose Fields carry its cells, so
            that `Fields.mean` and the other quadratures weigh each panel by its width).
            Elsewhere the four fields are interpolated linearly between panel centres,
            periodically (which keeps σ ≥ 0 and gap ≥ 0), and the Fields are point values
            (uniform cells if the positions are a uniform grid of one period).

        Returns
        -------
        viscosine.Fields
            σ(1 − ν²)/E_ref, v/h (from the mean line of the deformed surface) and gap/h.
        """
        if x_over_lambda is None:
            return Fields(self.x_over_lambda, self.pressure, self.displacement, self.gap,
                          edges=self.edges)
        X = np.atleast_1d(np.asarray(x_over_lambda, dtype=float))
        if X.ndim != 1 or not np.all(np.isfinite(X)):
            raise ValueError(f"x_over_lambda={x_over_lambda!r} is not allowed: a 1-D array of "
                             "finite positions x/λ")
        def interp(a):
            return np.interp(X, self.x_over_lambda, a, period=1.0)

        return Fields(X, interp(self.pressure), interp(self.displacement), interp(self.gap))

    def scalars(self) -> dict:
        """The eight scalars of the conventions (plain Python types, None where null)."""
        return {k: plain(getattr(self, k)) for k in SCALAR_KEYS}
