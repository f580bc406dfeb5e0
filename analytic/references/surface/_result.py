"""The surface reference's result object, `SurfaceSolution`."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from viscosine.protocol import plain

#: the scalars of the surface conventions, in their order
SCALAR_KEYS = ("penetration", "mu", "mu_lateral", "contact_fraction", "n_patches",
               "max_pressure")


@dataclass(frozen=True)
class SurfaceSolution:
    """One operating point of the surface reference (a SciPy-like result object).

    Attributes
    ----------
    success, status, message, warnings
        Whether this is an answer (every grid converged, the scalars finite, a contact), 0 or
        1, what the solver says, caveats (tuple of str).
    control, asked
        ``"load"`` or ``"penetration"`` and the value asked for.
    load, speed, direction, aspect, material
        p̃ (E0/(1 − ν²); an output under penetration control), w = V τ k, θ in degrees,
        Ly/Lx, and the creep series as ``{"J0", "J", "tau"}``.
    h_ref
        k h_ref = k (max z − mean z).
    full_contact, contact_fraction, penetration, separation, tau_f, mu, mu_lateral,
    n_patches, max_pressure
        The scalars of the surface conventions: contact area over the cell's (refined), Δ/h_ref,
        s/h_ref = 1 − Δ/h_ref, τf(1 − ν²)/E0 (positive when it resists), τf/p̃, the lateral
        force along (−sin θ, cos θ) over the load, the patches (four-neighbour, periodic) and
        the peak σ(1 − ν²)/E0, all from the finest grid or extrapolated (see
        ``extrapolated``).
    error_estimate : dict
        Per scalar: relative for load, penetration, tau_f, mu, max_pressure and
        contact_fraction (the output contract's meaning); absolute for mu_lateral (it can
        vanish); None for n_patches (an integer: ``warnings`` say when the grids disagree).
        See `richardson`.
    observed_order, extrapolated : dict
        Per scalar: the order of the last three grids and whether the value is extrapolated.
    nodes : int
        Panels along x of the finest grid.
    grids : tuple of (int, int)
        (nx, ny) of every grid, coarse to fine.
    levels : tuple of dict
        Per level: ``nodes``, ``ny``, ``scalars`` (the average of its two grids, with the
        nodal contact fraction, the direct friction forms and the worse complementarity),
        ``shifted`` (each grid's own scalars, the surface moved by `SHIFTS` of a panel),
        ``evaluations`` of the iteration's map, ``mixed`` (Anderson steps kept), ``seconds``.
    diagnostics : dict
        The finest level's ``mu_direct``, ``mu_lateral_direct`` (the friction from the
        surface's slope), ``contact_fraction_nodal`` and ``complementarity`` (the worst of
        |gap| in the contact and −gap over h_ref, −σ over max σ).
    x, y, pressure, gap, displacement : ndarray
        The finest level's unshifted grid: panel centres (over Lx), σ(1 − ν²)/E0 of shape
        (len(x), len(y)), gap/h_ref and (u − mean u)/h_ref.
    elapsed : float
        Wall time, seconds.
    layer : dict or None
        None on the half-space; on a layer its description: ``thickness`` (k d),
        ``thickness_over_wavelength`` (d/Lx), ``foundation``, ``nu``, ``uniform_compliance``
        (C of the uniform mode).
    mean_displacement, approach : float or None
        On a layer (None on the half-space): v̄0/h_ref, the layer's uniform compression under
        the mean pressure (k v̄0 = C (k d) J0 p̃, J0 the relaxed compliance), and Δ/h_ref +
        v̄0/h_ref, the crest's approach from the undeformed top face (the BEM's
        ``diagnostics["layer"]``; also in ``diagnostics["layer"]`` here).  Their relative
        estimates are in ``error_estimate``.
    """

    success: bool
    status: int
    message: str
    control: str
    asked: float
    load: float
    speed: float
    direction: float
    aspect: float
    material: dict
    h_ref: float
    full_contact: bool
    contact_fraction: float
    penetration: float
    separation: float
    tau_f: float
    mu: float
    mu_lateral: float
    n_patches: int
    max_pressure: float
    error_estimate: dict
    observed_order: dict
    extrapolated: dict
    nodes: int
    grids: tuple
    levels: tuple = field(repr=False)
    diagnostics: dict = field(repr=False)
    x: np.ndarray = field(repr=False)
    y: np.ndarray = field(repr=False)
    pressure: np.ndarray = field(repr=False)
    gap: np.ndarray = field(repr=False)
    displacement: np.ndarray = field(repr=False)
    elapsed: float = 0.0
    warnings: tuple = ()
    layer: dict | None = None
    mean_displacement: float | None = None
    approach: float | None = None

    def scalars(self):
        """The six scalars of the surface conventions, as a dict."""
        return {k: getattr(self, k) for k in SCALAR_KEYS}

    def as_dict(self):
        """Everything but the fields, as plain Python values (non-finite floats as None)."""
        out = {"solver": "surface_reference", "success": self.success, "status": self.status,
               "message": self.message, "warnings": list(self.warnings),
               "control": self.control, "asked": self.asked, "load": self.load,
               "speed": self.speed, "direction": self.direction, "aspect": self.aspect,
               "material": self.material, "h_ref": self.h_ref,
               "full_contact": self.full_contact, "separation": self.separation,
               "tau_f": self.tau_f}
        out.update(self.scalars())
        out.update({"error_estimate": self.error_estimate,
                    "observed_order": self.observed_order, "extrapolated": self.extrapolated,
                    "nodes": self.nodes, "grids": self.grids, "levels": self.levels,
                    "diagnostics": self.diagnostics, "elapsed": self.elapsed})
        if self.layer is not None:  # the half-space's record is unchanged
            out.update({"layer": self.layer, "mean_displacement": self.mean_displacement,
                        "approach": self.approach})
        return plain(out)
