"""Helpers on sampled fields the comparison layer shares (verify's reading of another code's
fields, the Tamaas peer's measuring of its own, the suite's and verify's contact patches and
per-point errors), and the fields CSV: its writer (``point --fields``, ``sweep --fields``) and
its one reader (``verify --fields``), beside each other.  The roads keep their own: bem and
analytic share nothing but `viscosine`.
"""
from __future__ import annotations

import math
import os

import numpy as np

from viscosine import Fields
from viscosine.fields import UNIFORM_SPACING, WIDTH

from ._errors import bad_input
from ._io import read_text, temporary_name


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


# ------------------------------------------------------------------------------ the fields CSV
#: the fewest points of a fields file (and of the fields of a solver under test)
MIN_POINTS = 8

FIELDS_ALLOWED = ("a UTF-8 CSV: '#' lines, a header with x_over_lambda,pressure"
                  "[,displacement,gap][,width], one row per point over one period, uniform or "
                  "with cell widths (docs/conventions.md, 'Fields')")


def write_fields_csv(path, fields, header=()):
    """Write the fields (header ``#`` lines, the column line, one row per point) atomically.

    ``fields``: a `viscosine.Fields` (or its columns, as `Fields.as_dict` gives them).  The
    columns are ``x_over_lambda, pressure, displacement, gap`` and, on a non-uniform grid,
    ``width`` (each row's cell, x/λ; the cells consecutive in row order over one period, the
    first centred on its row: what `Fields.from_columns` reads back).  The file is written under
    a name unique to this process and moved into place, so a reader never sees half a file and
    two writers never share a temporary file.
    """
    f = fields if isinstance(fields, Fields) else Fields.from_columns(fields)
    data = f.as_dict()
    cols = list(data)
    if not f.uniform:  # the CSV gives widths only: its first cell must be centred on its row
        w0 = float(f.edges[1] - f.edges[0])
        if abs(f.edges[0] - (f.x_over_lambda[0] - 0.5 * w0)) > 1e-9 * w0:
            raise ValueError("the first cell is not centred on its point: its edges cannot be "
                             "written as widths")
    arrays = [np.asarray(data[c], dtype=float) for c in cols]
    tmp = temporary_name(os.path.abspath(path))
    try:
        with open(tmp, "w", encoding="ascii", newline="\n") as fh:
            for line in header:
                fh.write(f"# {line}\n")
            fh.write(",".join(cols) + "\n")
            for row in zip(*arrays):
                fh.write(",".join(repr(float(v)) for v in row) + "\n")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def read_fields_csv(path, option="--fields") -> dict:
    """The columns of one fields CSV file, checked (`parse_fields_csv`; `Fields.from_columns`
    makes them a `viscosine.Fields`).

    The format (what `write_fields_csv` writes, and what another code's fields must be for
    ``verify --fields``): a header line with the columns ``x_over_lambda, pressure`` and
    optionally ``displacement, gap`` (any order, other columns ignored), ``#`` comment lines
    allowed before it, one row per point of a uniform grid over one period (any offset,
    increasing x, the end point not repeated); or, with a ``width`` column, a non-uniform grid:
    each row's cell width (x/λ), the cells consecutive in row order over one period, the first
    centred on its row (the format ``python -m comparisons point --fields`` writes after a
    contact window).  Units of the conventions (pressure σ(1 − ν²)/E0, displacement v/h,
    gap/h); ``verify --units SI`` converts SI ones (Pa, m, m).

    Raises
    ------
    BadInput
        Naming ``option`` and the file: one that cannot be read as text (`read_text`), or whose
        content `parse_fields_csv` refuses.
    """
    return parse_fields_csv(read_text(option, path, FIELDS_ALLOWED), option, str(path))


def parse_fields_csv(text, option="--fields", name="<text>") -> dict:
    """The columns of a fields CSV (`read_fields_csv`) as float arrays, checked.

    Returns
    -------
    dict
        ``x_over_lambda``, ``pressure`` and, when present, ``displacement``, ``gap`` and
        ``width`` (the cells of a non-uniform grid).

    Raises
    ------
    BadInput
        Missing columns, non-numeric values, fewer than MIN_POINTS rows, a grid that is not
        uniform over one period (without widths) or whose cells do not make one period (with
        them).
    """
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise bad_input(option, name, "no header line (only comments)", FIELDS_ALLOWED)
    head = [h.strip().lower() for h in lines[0].split(",")]
    if "x_over_lambda" not in head or "pressure" not in head:
        raise bad_input(option, name, f"the columns x_over_lambda and pressure are required "
                        f"(found: {', '.join(head)})", FIELDS_ALLOWED)
    cols = {c: head.index(c) for c in ("x_over_lambda", "pressure", "displacement", "gap", WIDTH)
            if c in head}
    rows = []
    for i, ln in enumerate(lines[1:], 2):
        cells = [c.strip() for c in ln.split(",")]
        if len(cells) < len(head):
            raise bad_input(option, name, f"row {i - 1} has {len(cells)} fields, the header "
                            f"{len(head)}", FIELDS_ALLOWED)
        try:
            rows.append([float(cells[j]) for j in cols.values()])
        except ValueError:
            raise bad_input(option, name, f"row {i - 1}: not a number in {ln.strip()[:60]!r}",
                            FIELDS_ALLOWED) from None
    data = np.array(rows, dtype=float).reshape(-1, len(cols))
    if data.shape[0] < MIN_POINTS:
        raise bad_input(option, name, f"{data.shape[0]} rows", f"at least {MIN_POINTS} points")
    if not np.all(np.isfinite(data)):
        raise bad_input(option, name, "non-finite values (nan or inf)", "finite numbers")
    out = {c: data[:, k] for k, c in enumerate(cols)}
    check_grid(out["x_over_lambda"], option, name, out.get(WIDTH))
    return out


def check_grid(x, option="--fields", name="<fields>", widths=None):
    """BadInput unless x is increasing and uniform over exactly one period (end not repeated),
    or, with ``widths``, the cells they give make one period with each point in its own."""
    x = np.asarray(x, float)
    if widths is not None:
        z = np.zeros(x.size)
        try:
            Fields(x, z, z, z, widths=widths)
        except ValueError as exc:
            raise bad_input(option, name, f"the width column does not describe the grid ({exc})",
                            "cells consecutive in row order over one period, the first centred on "
                            "its row, each point in its cell") from None
        return
    m = x.size
    dx = np.diff(x)
    spread = float(np.max(np.abs(dx * m - 1.0))) if m > 1 else math.inf
    if abs(x[-1] - x[0] - 1.0) < 1e-9:
        raise bad_input(option, name, "the end point of the period is repeated",
                        "one period, x_last = x_first + 1 − 1/M (drop the last row)")
    if not spread < UNIFORM_SPACING:
        raise bad_input(option, name, f"x_over_lambda is not a uniform grid over one period "
                        f"(spacing × M − 1 reaches {spread:.2e})",
                        "x_j = x_0 + j/M, j = 0..M−1, increasing")


def count_patches(contact):
    """Contact patches of a surface's grid: points in contact connected through their four
    neighbours, the grid periodic (components that meet across the cell's edges are one patch).

    Parameters
    ----------
    contact : array_like of bool, shape (nx, ny)

    Returns
    -------
    int
        0 without contact, 1 in full contact.
    """
    from scipy import ndimage

    c = np.asarray(contact, dtype=bool)
    labels, n = ndimage.label(c)  # 4-connectivity: the default cross in 2-D
    parent = list(range(n + 1))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in ((labels[-1, :], labels[0, :]), (labels[:, -1], labels[:, 0])):
        both = (a > 0) & (b > 0)
        for la, lb in zip(a[both].tolist(), b[both].tolist()):
            ra, rb = root(la), root(lb)
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    return len({root(k) for k in range(1, n + 1)})
