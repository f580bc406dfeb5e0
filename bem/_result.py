"""Result objects of :func:`bem.solve` (frozen, SciPy-like)."""
from __future__ import annotations

import math

from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Mapping

import numpy as np


@dataclass(frozen=True)
class Patch:
    """One contact patch (positions in wavelengths, X = x/lambda, crest at 0).

    Attributes
    ----------
    trailing_edge, leading_edge : float
        Sub-panel estimates of the -x and +x edges (leading_edge > trailing_edge;
        the pair may straddle X = +-1/2).
    ka : float
        k a, with 2a the patch width.
    ke : float
        k e: offset of the patch centre from X = 0, positive toward +x (leading).
    ke_hat : float
        k e_hat: offset of the pressure centroid over the patch from X = 0.
    load : float
        The patch's share of the mean pressure (sum over the patch / N).
    panels : int
        Active panels in the patch.
    """

    trailing_edge: float
    leading_edge: float
    ka: float
    ke: float
    ke_hat: float
    load: float
    panels: int


def _frozen_array(a) -> np.ndarray:
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
        True when the active set converged and the last linear solve met ``tol``.
        When False, the scalars and fields are the last iterate and are not an
        answer; ``message`` gives the residuals.
    status : int
        0 converged; 1 outer iterations exhausted; 2 a Krylov solve failed;
        3 the active set cycled.
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
    ka: float
    ke: float | None
    ke_hat: float
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

    def __post_init__(self):
        for name in ("x_over_lambda", "pressure", "displacement", "gap"):
            object.__setattr__(self, name, _frozen_array(getattr(self, name)))
        object.__setattr__(self, "residuals", MappingProxyType(dict(self.residuals)))
        object.__setattr__(self, "inner_iterations", tuple(int(i) for i in self.inner_iterations))

    def scalars(self) -> dict:
        """The output keys of ``conventions.md`` as plain Python values."""
        return {
            "full_contact": bool(self.full_contact),
            "contact_fraction": float(self.contact_fraction),
            "ka": float(self.ka),
            "ke": None if self.ke is None else float(self.ke),
            "ke_hat": float(self.ke_hat),
            "penetration": float(self.penetration),
            "tau_f": float(self.tau_f),
            "mu": float(self.mu),
        }
