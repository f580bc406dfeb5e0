"""A surface's 2-D fields in verify: read (``.npz``, a callable's output), checked, and the
scalars derived from them (documented, deterministic).

The fields are those of the conventions ('Surfaces'): ``x`` and ``y`` the panel centres over Lx
(x_i = i/nx − ½, y_j = (j/ny − ½) Ly/Lx), ``pressure`` σ(1 − ν²)/E0 of shape (nx, ny), and
optionally ``displacement`` and ``gap`` over h_ref; a file may also hold the scalars ``load``,
``speed``, ``direction`` (checked against the case) and the solver's own ``mu``,
``mu_lateral``, ``penetration``, ``contact_fraction`` (used in place of those derived).

From the fields, on the grid's own quadrature (the plain mean of the point values), with the
case's surface at the same points (`comparisons.roads.surface_on_grid`: its exact heights and
slopes):

- load p̃∞ = mean σ;
- μ = −mean(σ ∂z/∂ê)/p̃∞ and μ_lateral = mean(σ ∂z/∂ê⊥)/p̃∞, ê = (cos θ, sin θ), ê⊥ = (−sin θ,
  cos θ): the direct form of the force (docs/surfaces.md §2.1; on the contact ∂u = ∂z);
- Δ/h_ref = 1 − mean gap (the mean gap is the mean separation s: mean u = 0 and the surface's
  mean is 0); without a gap, s/h_ref = the mean over the contact points of z/h_ref − u;
- contact points σ > CONTACT · max σ; patches their 4-connected components on the periodic
  grid;
- contact fraction: along every row of points (and every column), each run of contact points
  reaches past each of its end points to an edge placed inside the next cell: the zero of the
  line through gap^(2/3) at the 2nd and 3rd free points beyond the end (gap^(2/3) falls
  linearly to an edge; the point next to it carries the grid's largest error), else (without
  a gap, or no such free points) through σ² at the end point and the one before it, else half
  a cell; a zero outside the cell is not trusted (half a cell).  The rows' lengths give the
  area along x, the columns' along y, and the two are averaged with the number of run ends
  each found as weights (a surface uniform in y is measured along x alone).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from .. import operating_point as op
from .. import roads
from .._errors import bad_input
from ..fields import MIN_POINTS, count_patches, true_runs

#: contact points: σ > CONTACT · max σ (as on the line)
CONTACT = 1e-9
#: the solver's own scalars a fields file or a callable may give (conventions' keys)
OWN_KEYS = ("mu", "mu_lateral", "penetration", "contact_fraction", "load")
#: the arrays of a surface's fields, the first three required
FIELD_ARRAYS = ("x", "y", "pressure", "displacement", "gap")
FIELDS_ALLOWED = ("an .npz of the conventions ('Surfaces'): 1-D x, y (panel centres x_i = i/nx "
                  "- 1/2, y_j = (j/ny - 1/2) Ly/Lx, at least 8 each), 2-D pressure[, "
                  "displacement, gap] of shape (len(x), len(y)), finite")


def read_npz(path, option="--fields"):
    """(fields dict, scalars the file holds) of a surface fields ``.npz`` (bad input named)."""
    if not Path(path).is_file():
        raise bad_input(option, path, "no such file", FIELDS_ALLOWED)
    try:
        with np.load(path, allow_pickle=False) as z:
            data = {k: np.asarray(z[k]) for k in z.files}
    except Exception as exc:  # any unreadable file is bad input, in one line
        raise bad_input(option, path, f"not a readable .npz ({type(exc).__name__})",
                        FIELDS_ALLOWED) from None
    fields = {k: data[k] for k in FIELD_ARRAYS if k in data}
    scalars = {}
    for k, v in data.items():
        if k in FIELD_ARRAYS:
            continue
        if v.shape == () and v.dtype.kind in "iuf" and math.isfinite(float(v)):
            scalars[k] = float(v)
    return fields, scalars


def check_fields(fields, option, name, aspect):
    """The fields as float arrays, checked against the conventions' grid (bad input named)."""
    missing = [k for k in ("x", "y", "pressure") if k not in fields]
    if missing:
        raise bad_input(option, name, f"no array {missing[0]}", FIELDS_ALLOWED)
    out = {}
    for k in FIELD_ARRAYS:
        if k in fields and fields[k] is not None:
            a = np.asarray(fields[k])
            if a.dtype.kind not in "iuf":
                raise bad_input(option, name, f"{k} is not numeric", FIELDS_ALLOWED)
            out[k] = a.astype(float)
    x, y = out["x"], out["y"]
    if x.ndim != 1 or y.ndim != 1 or x.size < MIN_POINTS or y.size < MIN_POINTS:
        raise bad_input(option, name, f"x and y of {x.size} and {y.size} points",
                        FIELDS_ALLOWED)
    for k in FIELD_ARRAYS[2:]:
        if k in out and out[k].shape != (x.size, y.size):
            raise bad_input(option, name, f"{k} of shape {out[k].shape}, not "
                            f"(len(x), len(y)) = {(x.size, y.size)}", FIELDS_ALLOWED)
    for k, a in out.items():
        if not np.all(np.isfinite(a)):
            raise bad_input(option, name, f"{k} is not finite everywhere", FIELDS_ALLOWED)
    nx, ny = x.size, y.size
    if not (np.allclose(x, np.arange(nx) / nx - 0.5, rtol=0.0, atol=1e-9 / nx)
            and np.allclose(y, (np.arange(ny) / ny - 0.5) * aspect, rtol=0.0,
                            atol=1e-9 * aspect / ny)):
        raise bad_input(option, name, f"x, y are not the panel centres of a {nx} x {ny} grid "
                        f"of the cell 1 x {aspect:g}", FIELDS_ALLOWED)
    return out


def as_surface_fields(obj, option, label, aspect):
    """(fields, the solver's own scalars) of a callable's output: an object with ``.fields``
    (a method or an attribute: an object with the arrays as attributes, or a dict) and
    optionally ``.scalars`` (a method or a dict), or a dict of the arrays."""
    f = getattr(obj, "fields", obj)
    if callable(f) and not isinstance(f, dict):
        f = f()
    if not isinstance(f, dict):
        f = {k: getattr(f, k, None) for k in FIELD_ARRAYS}
    sc = getattr(obj, "scalars", None)
    if callable(sc):
        sc = sc()
    own = {}
    for k, v in (sc or {}).items():
        if k in OWN_KEYS and isinstance(v, (int, float)) and not isinstance(v, bool) \
                and math.isfinite(v):
            own[k] = float(v)
    return check_fields({k: v for k, v in f.items() if v is not None}, option, label,
                        aspect), own


def surface_at(point, nx, ny, option, name):
    """The case's surface on the nx × ny grid (`roads.surface_on_grid`); bad input when the grid
    cannot hold its finest mode."""
    try:
        return roads.surface_on_grid(point["surface"], nx, ny)
    except ValueError as exc:
        raise bad_input(option, name, f"a {nx} x {ny} grid cannot hold the case's surface "
                        f"({str(exc).split(': ', 1)[-1]})") from None


def _edge_offset(line, end, step):
    """Cells from the point ``end`` of a run to its edge, the run continuing against ``step``
    (±1) in the periodic 1-D arrays ``line`` = (contact, σ², gap^(2/3) or None)."""
    contact, s2, g23 = line
    n = contact.size
    if g23 is not None:
        i2, i3 = (end + 2 * step) % n, (end + 3 * step) % n
        if not (contact[(end + step) % n] or contact[i2] or contact[i3]) and g23[i3] > g23[i2]:
            d0 = 2.0 - g23[i2] / (g23[i3] - g23[i2])
            if 0.0 <= d0 <= 1.0:
                return d0
    prev = (end - step) % n
    if contact[prev] and s2[prev] > s2[end]:
        d0 = s2[end] / (s2[prev] - s2[end])
        if 0.0 <= d0 <= 1.0:
            return d0
    return 0.5


def _area_along(contact, s2, g23, axis):
    """(contact fraction from the lines along ``axis``, run ends found)."""
    c, s, g = (np.moveaxis(a, axis, 0) if a is not None else None for a in (contact, s2, g23))
    n, lines = c.shape
    total, ends = 0.0, 0
    for j in range(lines):
        line = (c[:, j], s[:, j], None if g is None else g[:, j])
        for first, length in true_runs(c[:, j]):
            if length == n:
                total += n
                continue
            last = first + length - 1
            total += (length - 1) + _edge_offset(line, last % n, 1) + \
                _edge_offset(line, first, -1)
            ends += 2
    return total / (n * lines), ends


def contact_area(pressure, gap=None):
    """The contact fraction of fields on a uniform periodic grid (the module's docstring)."""
    p = np.asarray(pressure, float)
    pmax = float(np.max(p))
    contact = p > CONTACT * pmax if pmax > 0.0 else np.zeros(p.shape, bool)
    if contact.all() or not contact.any():
        return float(contact.all())
    s2 = np.where(contact, p, 0.0) ** 2
    g23 = None if gap is None else np.abs(np.asarray(gap, float)) ** (2.0 / 3.0)
    ax, ex = _area_along(contact, s2, g23, 0)
    ay, ey = _area_along(contact, s2, g23, 1)
    return (ax * ex + ay * ey) / (ex + ey) if ex + ey else 0.5 * (ax + ay)


def scalars_from_fields(fields, point, surf):
    """The scalars derived from a surface's fields (the module's docstring): a dict of ``load``,
    ``mu``, ``mu_lateral``, ``penetration`` (with a gap, or a displacement), ``contact_fraction``,
    ``n_patches`` and ``full_contact``.  ``surf``: the case's surface on the fields' grid
    (`surface_at`)."""
    p = fields["pressure"]
    load = float(np.mean(p))
    th = math.radians(op.direction_of(point))
    c, s = math.cos(th), math.sin(th)
    along = surf["slope_x"] * c + surf["slope_y"] * s
    across = -surf["slope_x"] * s + surf["slope_y"] * c
    out = {"load": load}
    if load > 0.0:
        out["mu"] = -float(np.mean(p * along)) / load
        out["mu_lateral"] = float(np.mean(p * across)) / load
    pmax = float(np.max(p))
    contact = p > CONTACT * pmax if pmax > 0.0 else np.zeros(p.shape, bool)
    if "gap" in fields:
        out["penetration"] = 1.0 - float(np.mean(fields["gap"]))
    elif "displacement" in fields and contact.any():
        z = (surf["heights"] - np.mean(surf["heights"])) / surf["amplitude"]
        out["penetration"] = 1.0 - float(np.mean((z - fields["displacement"])[contact]))
    out["contact_fraction"] = contact_area(p, fields.get("gap"))
    out["n_patches"] = count_patches(contact) if contact.any() else 0
    out["full_contact"] = bool(contact.all())
    return out
