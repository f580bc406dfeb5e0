"""Helpers on sampled fields the comparison layer shares (verify's reading of another code's
fields, the Tamaas peer's measuring of its own, the suite's and verify's contact patches and
per-point errors).  The roads keep their own: bem and analytic share nothing but `viscosine`.
"""
from __future__ import annotations

import math

import numpy as np

from viscosine import Fields
from viscosine._fields import WIDTH


def true_runs(mask) -> list:
    """The maximal runs of True in a periodic boolean array, as ``[(first index, length), ...]``.

    A run may wrap past the end of the array (its first index is then near the end); the whole
    array True is one run ``(0, n)``, none True is ``[]``.  Runs are listed from the one after
    the first False entry, in order around the period.
    """
    mask = np.asarray(mask, dtype=bool)
    n = mask.size
    if mask.all():
        return [(0, n)]
    if not mask.any():
        return []
    start = int(np.argmin(mask))  # the first False entry: no run wraps past it
    d = np.diff(np.concatenate(([0], np.roll(mask, -start).astype(np.int8), [0])))
    firsts, ends = np.flatnonzero(d == 1), np.flatnonzero(d == -1)
    return [((int(f) + start) % n, int(e - f)) for f, e in zip(firsts, ends)]


def neighbour_max(a):
    """The largest of each entry of a periodic array and its two neighbours."""
    return np.maximum(np.maximum(a, np.roll(a, 1)), np.roll(a, -1))


def bem_fields(res):
    """(x, pressure, displacement, gap) of a BEM result at its panel centres, on the uniform
    grid of a fixed mesh (ValueError for a non-uniform one, whose cells these columns lose)."""
    f = res.fields() if callable(getattr(res, "fields", None)) else res
    if not getattr(f, "uniform", True):
        raise ValueError("the BEM fields are on a non-uniform grid (a contact window): "
                         "solve on a fixed mesh (nodes=N) for panel centres j/N - 1/2")
    return (np.asarray(f.x_over_lambda, float), np.asarray(f.pressure, float),
            np.asarray(f.displacement, float), np.asarray(f.gap, float))


# ------------------------------------------------------------------------------ contact patches
#: what `patch_records` says of each patch (x/λ, its share of the load, radians)
PATCH_KEYS = ("summit", "trailing_edge", "leading_edge", "load", "ka", "ke", "ke_hat")


def wrap(x):
    """x taken into [−½, ½)."""
    return x - math.floor(x + 0.5)


def patch_records(res, shape):
    """The contact patches of a BEM result as dicts keyed by PATCH_KEYS.

    Edges are unwrapped so that the patch centre lies within ½ of its summit (the highest
    profile point inside the patch, ``shape.summit(trailing, leading)``: a
    `comparisons.suite_inputs.ProfileShape`); ka = π·width, ke = 2π(centre − summit),
    kê = 2π(centroid − summit) (for the sinusoid the summit is the crest at 0 and these are the
    conventions' ka, ke, kê).  Sorted by centre, taken in [−½, ½).
    """
    out = []
    for p in getattr(res, "patches", ()) or ():
        t, l = float(p.trailing_edge), float(p.leading_edge)
        centroid = getattr(p, "centroid", None)
        if centroid is None:  # older result objects: kê measured from X = 0
            centroid = float(p.ke_hat) / (2.0 * math.pi)
        summit = shape.summit(t, l)
        shift = -math.floor(0.5 * (t + l) - summit + 0.5)
        t, l = t + shift, l + shift
        centroid = float(centroid) - math.floor(float(centroid) - summit + 0.5)
        out.append({"summit": summit, "trailing_edge": t, "leading_edge": l,
                    "load": float(p.load), "ka": math.pi * (l - t),
                    "ke": math.pi * (t + l) - 2.0 * math.pi * summit,
                    "ke_hat": 2.0 * math.pi * (centroid - summit)})
    return sorted(out, key=lambda r: wrap(0.5 * (r["trailing_edge"] + r["leading_edge"])))


def match_patches(reference, patches):
    """For each patch of ``reference``, the patch of ``patches`` whose centre is nearest (modulo
    one period) if it is within half the reference patch's width and no other reference patch
    claims it; None otherwise (a patch that is missing or split on this mesh)."""
    if patches is None:
        return [None] * len(reference)
    centre = lambda r: 0.5 * (r["trailing_edge"] + r["leading_edge"])  # noqa: E731
    picks = []
    for r in reference:
        dist = [abs(wrap(centre(q) - centre(r))) for q in patches]
        j = int(np.argmin(dist)) if dist else -1
        ok = j >= 0 and dist[j] < 0.5 * (r["leading_edge"] - r["trailing_edge"])
        picks.append(j if ok else None)
    taken = [j for j in picks if j is not None]
    return [patches[j] if j is not None and taken.count(j) == 1 else None for j in picks]


def as_grid(columns) -> Fields:
    """The `viscosine.Fields` of a dict of columns keyed like the fields CSV, for its grid's
    quadrature (a ``width`` column makes it non-uniform); a field the dict lacks is zeros there,
    so only what the dict holds is ever read from it."""
    x = np.asarray(columns["x_over_lambda"], float)
    z = np.zeros(x.size)
    cols = [columns.get(c) for c in ("pressure", "displacement", "gap")]
    return Fields(x, *(z if a is None else a for a in cols), widths=columns.get(WIDTH))
