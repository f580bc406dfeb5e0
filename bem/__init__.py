"""Periodic boundary-element solver for steady viscoelastic sliding (the BEM road).

A rigid periodic indenter slides at speed V toward +x over a linear viscoelastic
half-plane (plane strain, frictionless, adhesionless).  In the frame of the
indenter the steady surface displacement is ``v = Phi_V * sigma`` over one
period (eq. 2.4) with the kernel of eq. (2.5), discretised on N equal panels
(piecewise-constant pressure, collocation at the panel centres) and solved with a
primal-dual active-set method on FFT products.  Where memories of about a panel would let the
discrete pressure form a sawtooth (stiff materials, alone or as several Prony terms together),
their memory parts are collocated a fraction of a panel downstream, which keeps it free of the
sawtooth centre collocation would give there (see ``_influence.collocation_shifts``).  This
package never imports :mod:`analytic`.

Units (stated once): positions ``X = x/lambda`` with the crest of the sinusoid at
0; heights and displacements ``k y``, ``k v`` (k = 2 pi/lambda); pressures in
``E_ref/(1 - nu^2)``; compliances in ``1/E_ref``; times in ``tau_ref``; speed
``w = V tau_ref k``.  For the standard linear solid ``E_ref = E0`` and
``tau_ref = tau`` (the creep time), so ``load`` is the paper's p~ and ``speed``
its V/V0.  Signs: pressure positive in compression, displacement positive into
the body, the leading edge of a contact is its +x edge.

The public shape is the semi-analytic road's: ``solve`` returns a `BemResult` with the result
protocol (``scalars``, ``as_dict``, ``fields``, ``patches``, ``diagnostics``,
``error_estimate``); ``solve_meshes`` answers a mesh study (``solve`` on several fixed meshes,
their grids solved once); ``sweep`` tabulates a grid of points; ``solve_si`` takes SI data;
``ACCEPTED`` lists the range of every input and why, ``validate`` checks them (``solve`` calls
it first) and ``MAX_NODES`` is the largest mesh this machine's memory allows; ``TERM_MIN`` is
the smallest creep term over J(0+) a material may hold.  ``solve(...,
layer=Layer(thickness=k d, foundation=..., nu=...))`` puts a layer on a rigid foundation in place
of the half-space (``docs/layers.md``); a `Layer` checks its own inputs, and a thin one limits
the mesh (``_layer.finest_nodes``).

Surfaces (three-dimensional contact): ``solve_surface`` slides a rigid periodic surface z = h(x,
y) (`bisinusoid`, `self_affine`, `sampled_surface`, `read_surface`) in any direction over the
half-space or a layer (``solve_surface_meshes``: a grid study); each mode of the surface is the line contact's mode loaded at the
frequency q·V (``docs/surfaces.md``).  Lengths there are over the cell's side Lx, heights
``k z`` with k = 2 pi/Lx.
"""
from viscosine import Fields
from viscosine.checks import positive_int as _positive_int
from viscosine.checks import real as _real

from ._accepted import ACCEPTED, MAX_NODES, TERM_MIN, validate
from ._front import SurfaceSIResult, solve_si, solve_surface_si, sweep
from ._influence import influence_coefficients_nd as _coefficients
from ._inputs import Harmonics, Prony, SampledProfile, Sinusoid, read_profile, read_prony
from ._layer import Layer
from ._result import MESSAGES, BemResult, Patch
from ._solver import solve
from ._study import solve_meshes
from ._surface import Surface, bisinusoid, read_surface, sampled_surface, self_affine
from ._surface_result import SurfaceFields, SurfacePatch, SurfaceResult
from ._surface_solver import (max_surface_panels, solve_surface, solve_surface_meshes,
                              validate_surface)


def influence_coefficients(material, speed, nodes):
    """First column ``C_m`` of the steady-sliding operator (eq. 2.5) on N panels.

    ``k v_i = sum_j C[(i - j) mod N] sigma_j`` with panels centred at
    ``X_j = j/N - 1/2`` and ``C_m`` the response at the offset ``X = m/N``
    (m > N/2 meaning ``m/N - 1``).  Pressure in ``E_ref/(1 - nu^2)``.

    Parameters
    ----------
    material : Prony
    speed : float
        ``w = V tau_ref k >= 0``.
    nodes : int
        ``N >= 8``.

    Returns
    -------
    ndarray, shape (nodes,)
    """
    if not isinstance(material, Prony):
        raise ValueError(f"material={material!r} is not allowed: a bem.Prony creep function")
    speed = _real("speed", speed, "a finite speed >= 0", lambda v: v >= 0.0)
    nodes = _positive_int("nodes", nodes, 8)
    return _coefficients(material.j_plus, material.terms, speed, nodes)


__all__ = ["ACCEPTED", "BemResult", "Fields", "Harmonics", "Layer", "MAX_NODES", "MESSAGES",
           "Patch", "Prony", "SampledProfile", "Sinusoid", "Surface", "SurfaceFields",
           "SurfacePatch", "SurfaceResult", "SurfaceSIResult", "bisinusoid",
           "influence_coefficients", "max_surface_panels", "read_profile", "read_prony",
           "read_surface", "sampled_surface", "self_affine", "solve", "solve_meshes", "solve_si",
           "solve_surface", "solve_surface_meshes", "solve_surface_si", "sweep", "validate", "validate_surface", "TERM_MIN"]
