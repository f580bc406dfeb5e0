"""Result objects of :func:`bem.solve_surface` (frozen, SciPy-like), with the result protocol of
the line contact (``success``, ``message``, ``scalars()``, ``as_dict()``, ``fields()``,
``error_estimate``).  Keys, units and signs as in ``docs/conventions.md`` ('Surfaces')."""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any, Mapping

import numpy as np

from viscosine.protocol import plain

#: the scalars of a surface point, in the order of the conventions
SURFACE_SCALAR_KEYS = ("full_contact", "contact_fraction", "penetration", "separation", "tau_f",
                       "mu", "mu_lateral", "n_patches", "max_pressure")


@dataclass(frozen=True)
class SurfacePatch:
    """One contact patch, connected across the periodic cell (4-neighbour panels).

    Positions over Lx, in the frame of the surface (crest of the bi-sinusoid at the origin).

    Attributes
    ----------
    area : float
        Its panels' area over the cell's (a count of panels: the result's contact fraction
        places the edges inside their panels, so the patches' areas add up to it only to
        within the panels along the edges).
    load : float
        Its share of the mean pressure p̃∞ (the patches' loads add up to p̃∞).
    panels : int
    summit : (float, float)
        The highest surface point among its panels.
    centroid, pressure_centroid : (float or None, float or None)
        Centroids of its panels and of its pressure, unwrapped about the summit; a coordinate
        is None where the patch spans the cell along that axis (it percolates: it wraps onto
        itself and has no centroid there).
    eccentricity, pressure_eccentricity : float or None
        (centroid − summit)·e and (pressure centroid − summit)·e over Lx, e the sliding
        direction: positive toward the leading side (where the material enters), as e and ê of
        the line contact; None where e has a component along an axis the patch spans.
    """

    area: float
    load: float
    panels: int
    summit: tuple
    centroid: tuple
    pressure_centroid: tuple
    eccentricity: float | None
    pressure_eccentricity: float | None


@dataclass(frozen=True)
class SurfaceFields:
    """The fields of a surface solve on its grid (``conventions.md``, 'Surfaces').

    Attributes
    ----------
    x, y : ndarray
        Panel centres over Lx: ``x_i = i/nx - 1/2``, ``y_j = (j/ny - 1/2) Ly/Lx``.
    pressure : ndarray, shape (nx, ny)
        σ (1 − ν²)/E_ref.
    displacement, gap : ndarray, shape (nx, ny)
        Over h_ref, the displacement from the mean plane of the deformed surface (positive into
        the body), the gap 0 in contact.
    """

    x: np.ndarray
    y: np.ndarray
    pressure: np.ndarray
    displacement: np.ndarray
    gap: np.ndarray
    load: float
    speed: float
    direction: float

    def save(self, path) -> Path:
        """Write the fields as ``.npz`` (the arrays and the scalars ``load``, ``speed``,
        ``direction``; read them with ``numpy.load``), through a temporary file renamed into
        place (an interrupted write leaves no half file)."""
        path = Path(path)
        tmp = path.with_name(path.name + ".part")
        with open(tmp, "wb") as fh:
            np.savez(fh, x=self.x, y=self.y, pressure=self.pressure,
                     displacement=self.displacement, gap=self.gap, load=self.load,
                     speed=self.speed, direction=self.direction)
        tmp.replace(path)
        return path


@dataclass(frozen=True)
class SurfaceResult:
    """Steady viscoelastic sliding of a rigid periodic surface, solved by the surface BEM.

    Units as in ``conventions.md`` ('Surfaces'): pressures in ``E_ref/(1 − ν²)``, heights,
    displacements and gaps over h_ref (the crest above the mean plane), positions over Lx.

    Attributes
    ----------
    success : bool
        True when the active set converged, every linear solve met ``tol``, the answer passed
        the validity gate (finite scalars, 0 < Δ/h_ref ≤ 1, μ ≥ 0, σ ≥ 0, gap ≥ 0, mean σ
        equal to the load) and, on the adaptive mesh, the estimated errors met ``rtol``.
    status : int
        As `bem.MESSAGES`.
    message : str
    nit : int
        Active-set iterations on the finest grid.
    nodes : int
        Panels along x of the finest grid (``shape[0]``).
    shape : (int, int)
        (nx, ny) of the finest grid.
    full_contact, contact_fraction, penetration, separation, tau_f, mu, mu_lateral
        The scalars: contact area over the cell's, Δ/h_ref, s/h_ref, τf (1 − ν²)/E_ref, μ
        (the force along V over the load, positive when it resists) and the force that the
        solid exerts on the surface to the left of V over the load.
    n_patches : int
    patches : tuple of SurfacePatch
    max_pressure : float
    at_max_pressure : (float, float)
        Where the pressure peaks (x, y over Lx).
    pressure_moments : mapping
        Of σ over the contact area: ``mean``, ``std``, ``skewness``, ``excess_kurtosis``.
    error_estimate : mapping or None
        Estimated discretisation error of each scalar: relative for ``penetration``,
        ``tau_f``, ``mu``, ``max_pressure`` and ``contact_fraction``; for ``mu_lateral``
        absolute, over |μ| (the lateral force can vanish).
    residuals, levels, diagnostics : mapping, tuple, mapping
        The residuals of the answer (complementarity, gaps, load balance, the Krylov
        residual, and ``friction_mismatch``: the dissipation and direct forms of μ, a
        discretisation indicator), the grids solved ((nx, ny, nit, status, FFT pairs: the
        transform pairs of the grid, its measurements included)), and what else the solver
        says (``memory_lengths``, a layer's ``layer``).
    """

    success: bool
    status: int
    message: str
    nit: int
    nodes: int
    shape: tuple
    control: str
    asked: float
    load: float
    speed: float
    direction: float
    full_contact: bool
    contact_fraction: float
    penetration: float
    separation: float
    tau_f: float
    mu: float
    mu_lateral: float
    n_patches: int
    patches: tuple
    max_pressure: float
    at_max_pressure: tuple
    pressure_moments: Mapping[str, float]
    error_estimate: Mapping[str, Any] | None
    residuals: Mapping[str, float]
    levels: tuple
    diagnostics: Mapping[str, Any]
    surface: Mapping[str, Any]
    material: Mapping[str, Any]
    warnings: tuple = ()
    pressure: np.ndarray = field(default=None, repr=False)
    displacement: np.ndarray = field(default=None, repr=False)
    gap: np.ndarray = field(default=None, repr=False)

    def scalars(self) -> dict:
        """The scalars of the conventions ('Surfaces') as a plain dict."""
        return {k: plain(getattr(self, k)) for k in SURFACE_SCALAR_KEYS}

    def fields(self) -> SurfaceFields:
        """The grid and the pressure, displacement and gap on it."""
        nx, ny = self.shape
        aspect = self.surface["aspect"]
        return SurfaceFields(x=np.arange(nx) / nx - 0.5, y=(np.arange(ny) / ny - 0.5) * aspect,
                             pressure=self.pressure, displacement=self.displacement,
                             gap=self.gap, load=self.load, speed=self.speed,
                             direction=self.direction)

    def as_dict(self) -> dict:
        """The JSON record (``allow_nan=False``-safe): inputs, scalars, estimate, patches."""
        import viscosine
        rec = {"solver": "bem", "version": viscosine.__version__, "geometry": "surface",
               "control": self.control,
               "load_asked": self.asked if self.control == "load" else None,
               "penetration_asked": self.asked if self.control == "penetration" else None,
               "load": self.load, "speed": self.speed, "direction": self.direction,
               "surface": dict(self.surface), "material": dict(self.material),
               "nodes": self.nodes, "shape": list(self.shape)}
        rec.update(self.scalars())
        rec.update({"success": self.success, "status": self.status, "message": self.message,
                    "warnings": list(self.warnings), "iterations": self.nit})
        ok = self.success
        rec.update({"at_max_pressure": list(self.at_max_pressure) if ok else None,
                    "pressure_moments": dict(self.pressure_moments) if ok else None,
                    "patches": [asdict(p) for p in self.patches] if ok else [],
                    "error_estimate": dict(self.error_estimate) if self.error_estimate else None,
                    "residuals": dict(self.residuals),
                    "levels": [list(lv) for lv in self.levels],
                    "diagnostics": dict(self.diagnostics)})
        return plain(rec)


def pressure_moments(sigma: np.ndarray, active: np.ndarray) -> dict:
    """Mean, standard deviation, skewness and excess kurtosis of σ over the contact panels."""
    s = sigma[active]
    if s.size == 0:
        return {"mean": math.nan, "std": math.nan, "skewness": math.nan,
                "excess_kurtosis": math.nan}
    mean = float(s.mean())
    d = s - mean
    var = float(np.mean(d * d))
    std = math.sqrt(var)
    if std == 0.0:
        return {"mean": mean, "std": 0.0, "skewness": 0.0, "excess_kurtosis": -3.0}
    return {"mean": mean, "std": std, "skewness": float(np.mean(d ** 3)) / std ** 3,
            "excess_kurtosis": float(np.mean(d ** 4)) / var ** 2 - 3.0}
