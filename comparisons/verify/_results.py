"""The results of the solver under test: from fields, from its own scalars, from a callable
(``--callable``) or from a third code (``--peer``).

- A callable (``--callable module:function`` or ``path/to/file.py:function``): called as
  ``function(point, nodes)`` for each ``--nodes`` with ``point`` the operating point (a dict:
  ``load`` or ``penetration``, ``speed``, and ``ratio``/``hk`` or absolute ``prony``/``profile``
  file paths, or for a suite case that names a material file of any form an absolute
  ``material`` path with its ``temperature`` and ``wlf`` when given, as
  :func:`comparisons._materials.read` takes them; for a case on a layer, ``layer``: a dict
  ``{"thickness_over_wavelength": d/λ, "foundation": "bonded" | "frictionless", "nu": ν}``, the
  layer of thickness d on a rigid foundation that replaces the half-plane, which the callable
  must solve: the half-plane's answer fails); it returns a :class:`viscosine.Fields` (its
  cells too, on a non-uniform grid), a dict of arrays keyed like the CSV columns, or an object
  with ``.fields`` (and optionally ``.scalars``, a dict).  Δ/h and the displacement are measured
  from the mean line of the deformed surface on a layer too (the layer's mean compression is
  not in them).
  :func:`viscosine_bem` is such a callable (viscosine's own BEM, the layer included).
- ``--peer tamaas``: :mod:`comparisons.peers.tamaas` (imported only when asked for): at each
  ``--nodes`` (default 256 512 1024) a dt study with dt = C·T/N for each ``--dt-cells`` C
  (default 4 2 1), extrapolated to dt → 0 by the peer's Richardson step (``extrapolate``, the
  one the report uses), fields included; the verdict is on the extrapolated values, each shown
  with its estimated error.  Progress goes to standard error, one line per run.
"""
from __future__ import annotations

import importlib
from dataclasses import dataclass

import numpy as np

from viscosine import Fields
from viscosine.fields import WIDTH

from .. import roads
from .. import suite as _suite
from .._errors import bad_input
from ..fields import MIN_POINTS, bem_fields, check_grid
from ..peers.tamaas import CELLS_PER_STEP as DEFAULT_DT_CELLS  # --peer tamaas: its dt ladder
from ._quantities import COMPARED_KEYS
from ._scalars import scalars_from_fields


@dataclass
class Result:
    """One result of the solver under test: its resolution, fields (dict or None) and scalars."""

    nodes: int | None
    fields: dict | None
    scalars: dict
    patches: list
    source: str   # "fields" or "solver"
    errors: dict | None = None  # the solver's own error estimates (absolute), when it gave some
    own: tuple = ()  # on a surface case, the scalars the solver gave itself (not from fields)


def as_fields(obj, option, label):
    """A dict of arrays from a Fields, a dict, or an object with .fields."""
    f = getattr(obj, "fields", obj)
    if callable(f) and not isinstance(f, dict):
        f = f()
    if isinstance(f, dict):
        d = {k: np.asarray(v, float) for k, v in f.items() if v is not None}
    elif isinstance(f, Fields):
        d = {k: np.asarray(v, float) for k, v in f.as_dict().items()}  # with its cells
    else:
        d = {}
        for k in ("x_over_lambda", "pressure", "displacement", "gap"):
            v = getattr(f, k, None)
            if v is not None:
                d[k] = np.asarray(v, float)
    if "x_over_lambda" not in d or "pressure" not in d:
        raise bad_input(option, label, "returned no x_over_lambda and pressure",
                        "a viscosine.Fields, a dict of arrays or an object with .fields")
    n = d["x_over_lambda"].size
    if any(a.shape != (n,) for a in d.values()) or n < MIN_POINTS:
        raise bad_input(option, label, "returned columns of different lengths or too few points",
                        f"1-D arrays of one length >= {MIN_POINTS}")
    check_grid(d["x_over_lambda"], option, label, d.get(WIDTH))
    return d


def results_from_fields(fields_list, shape, nodes=None, solver_scalars=None):
    """A `Result` per fields dict, its scalars derived from its fields (`scalars_from_fields`)
    or, where the solver gave them (``solver_scalars``), the solver's own; N = ``nodes`` or
    the number of points."""
    out = []
    for i, f in enumerate(fields_list):
        sc, patches = scalars_from_fields(f, shape)
        source = "fields"
        if solver_scalars and solver_scalars[i]:
            sc = {**sc, **{k: float(v) for k, v in solver_scalars[i].items()
                           if k in COMPARED_KEYS and v is not None}}
            source = "solver (fields for the rest)"
        out.append(Result(nodes[i] if nodes else f["x_over_lambda"].size, f, sc, patches, source))
    return out


def to_conventions(fields, E0, nu, amplitude):
    """SI fields (Pa, m, m) in the conventions' units (σ(1 − ν²)/E0, v/h, gap/h)."""
    scale = (1.0 - nu * nu) / E0
    out = dict(fields)
    out["pressure"] = np.asarray(fields["pressure"], float) * scale
    for k in ("displacement", "gap"):
        if k in fields:
            out[k] = np.asarray(fields[k], float) / amplitude
    return out


@dataclass
class SurfaceOutput:
    """What `viscosine_bem` returns on a surface case: the fields (the conventions' arrays
    ``x``, ``y``, ``pressure``, ``displacement``, ``gap``) and the solver's own scalars."""

    fields: dict
    scalars: dict


def viscosine_bem(point, nodes):
    """viscosine's own BEM as a ``--callable``: ``comparisons.verify:viscosine_bem``.

    Returns the BEM's fields at its panel centres (x/λ = j/N − ½) as a dict of arrays.  A
    point's ``layer`` goes to ``bem.solve`` (through `comparisons.roads.bem_solution`).  On a
    surface case (a point with ``surface``) the surface BEM on N × N panels (N × N Ly/Lx;
    `comparisons.roads.surface_solution`, the layer included): a `SurfaceOutput`.
    """
    if point.get("surface"):
        res = roads.surface_solution(point, int(nodes))
        if not res.success:
            raise RuntimeError(f"surface BEM not converged at N = {nodes}: "
                               f"{res.message.splitlines()[0]}")
        f = res.fields()
        return SurfaceOutput({"x": f.x, "y": f.y, "pressure": f.pressure,
                              "displacement": f.displacement, "gap": f.gap},
                             {k: float(getattr(res, k)) for k in
                              ("mu", "mu_lateral", "penetration", "contact_fraction")})
    res = _suite.bem_solution(point, int(nodes), base="/")
    if not res.success:
        raise RuntimeError(f"BEM not converged at N = {nodes}: {res.message.splitlines()[0]}")
    x, p, v, g = bem_fields(res)
    return {"x_over_lambda": x, "pressure": p, "displacement": v, "gap": g}


def tamaas_module():
    """:mod:`comparisons.peers.tamaas`, imported when asked for (BadInput without it)."""
    try:
        return importlib.import_module("comparisons.peers.tamaas")
    except ImportError as exc:
        raise bad_input("--peer", "tamaas", f"comparisons.peers.tamaas is not available ({exc})",
                        "a viscosine with the peers extra ('.[peers]')") from None


def peer_tamaas(point, nodes, dt=None, cells=None, progress=None):
    """Results of the third-party code Tamaas through :mod:`comparisons.peers.tamaas`.

    Imported only here, when ``--peer tamaas`` is asked for.  With ``dt`` (units of τ): one run,
    ``solve(*, load, speed, ratio, hk, nodes, dt)``.  Otherwise a dt study on this grid,
    ``dt_extrapolation(..., cells_per_step=cells)`` (default DEFAULT_DT_CELLS: T/N × 4, 2, 1),
    extrapolated to dt → 0 with the peer's own Richardson step (the one the report uses).
    Either returns an object with ``.fields`` (a viscosine.Fields) and ``.scalars``; the study
    also has ``.error`` (the estimated error of each extrapolated scalar).
    """
    peer = tamaas_module()
    kw = {"load": point.get("load"), "speed": point["speed"], "ratio": point["ratio"],
          "hk": point["hk"], "nodes": int(nodes)}
    if dt is not None:
        return peer.solve(**kw, dt=dt)
    return peer.dt_extrapolation(**kw, cells_per_step=tuple(cells or DEFAULT_DT_CELLS),
                                 progress=progress)

