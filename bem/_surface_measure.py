"""What one solved surface grid measures: contact area, patches, friction, the scalars.

Units of :mod:`bem`'s surface solver: positions over Lx, heights and gaps ``k z``, pressures in
``E_ref/(1 - nu^2)``; fields flattened in C order over the (nx, ny) grid.
"""
from __future__ import annotations

import math

import numpy as np
from scipy import ndimage

from ._surface_result import SurfacePatch


# --------------------------------------------------------------------------------------------
# Contact area with sub-panel edges
# --------------------------------------------------------------------------------------------
#: free panels (distances from the last contact panel) over which gap^(2/3) is fitted by a
#: quadratic: the panels next to an edge carry the largest discretisation error (on the
#: extruded sinusoid, elastic, N = 128 ... 1024, the edge from panels 2..6 is within 0.03
#: panel of the exact one, from panels 1..2 within 0.13, from the pressure side up to 0.2)
FIT_PANELS = (2, 3, 4, 5, 6)
_FIT = np.linalg.pinv(np.vander(np.array(FIT_PANELS, dtype=float), 3, increasing=True))


def _edge_offsets(gaps, free):
    """Where the contact edge lies beyond the last contact panel of a run (at 0), in panel
    widths along the run's direction: near an edge the gap grows like d^(3/2), so gap^(2/3)
    vanishes linearly there.  ``gaps[:, k - 1]``, ``free[:, k - 1]``: the gap and whether the
    panel k panels out is free, k = 1 … 6.  A quadratic through gap^(2/3) on FIT_PANELS gives
    the zero where those panels are all free; else the line through panels 1 and 2; else 1/2
    (the panel's edge: the count of contact panels).  A zero outside [−1, 2] is not trusted."""
    b = np.cbrt(gaps) ** 2
    t = np.full(b.shape[0], 0.5)
    # the line through panels 1 and 2
    with np.errstate(divide="ignore", invalid="ignore"):
        lin = 1.0 - b[:, 0] / (b[:, 1] - b[:, 0])
    ok = free[:, 0] & free[:, 1] & (b[:, 1] > b[:, 0]) & (lin >= -1.0) & (lin <= 2.0)
    t[ok] = lin[ok]
    full = free[:, :6].all(axis=1)
    if full.any():
        c = b[full][:, 1:6] @ _FIT.T  # c0 + c1 t + c2 t^2, least squares
        c0, c1, c2 = c[:, 0], c[:, 1], c[:, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            disc = np.sqrt(np.maximum(c1 * c1 - 4.0 * c2 * c0, 0.0))
            # the root of the rising branch, written without cancellation
            root = np.where(c1 > 0, -2.0 * c0 / (c1 + disc), (-c1 + disc) / (2.0 * c2))
            root = np.where(np.abs(c2) * 1e12 <= np.abs(c1), -c0 / c1, root)
        good = np.isfinite(root) & (root >= -1.0) & (root <= 2.0) & (c1 + 2 * c2 * 4.0 > 0)
        tf = t[full]
        tf[good] = root[good]
        t[full] = tf
    return t


def _row_lengths(active, gap, block=256):
    """Σ over the rows (axis 1 runs along the row, periodic) of the contact length in panel
    widths (each run of contact panels reaches past its end panels to the fitted edges), and
    the number of run ends.  Rows are taken ``block`` at a time (the shifted copies stay small at any grid size)."""
    length, ends = 0.0, 0
    for r0 in range(0, active.shape[0], block):
        on = active[r0:r0 + block]
        gp = gap[r0:r0 + block]
        length += float(np.count_nonzero(on))
        for d in (1, -1):  # d = 1: a run's +end; -1: its -end
            end = on & ~np.roll(on, -d, axis=1)
            if not end.any():
                continue
            gaps = np.stack([np.roll(gp, -k * d, axis=1)[end] for k in range(1, 7)], axis=1)
            free = np.stack([~np.roll(on, -k * d, axis=1)[end] for k in range(1, 7)], axis=1)
            t = _edge_offsets(gaps, free)
            length += float(np.sum(t)) - 0.5 * t.size
            ends += t.size
    return length, ends


def contact_area(active2, gap2) -> float:
    """The contact area over the cell's, from sub-panel edges.

    Along every row of panels (and, separately, every column) each run of contact panels
    reaches past its end panels to the edges fitted by `_edge_offsets`, and the rows' summed
    lengths give the area (the midpoint rule across rows).  A direction resolves the edges its
    rows cross; an edge parallel to its rows makes their lengths jump from row to row, and
    the midpoint rule is then first order there.  So the two directions' areas are weighted by
    how many run ends each found (a surface uniform in y: the rows along x alone).  This
    converges faster than the count of contact panels (an edge anywhere inside its panel:
    first order, with scatter).  Full contact gives 1 and no contact 0 exactly.
    """
    n = active2.size
    if active2.all() or not active2.any():
        return float(active2.all())
    along_y, ends_y = _row_lengths(active2, gap2)
    along_x, ends_x = _row_lengths(active2.T, gap2.T)
    area = (ends_x * along_x + ends_y * along_y) / (ends_x + ends_y) / n
    return min(1.0, max(0.0, area))
# --------------------------------------------------------------------------------------------
# What one solved grid measures
# --------------------------------------------------------------------------------------------
def _label_periodic(active2: np.ndarray):
    """Connected components of the contact (4-neighbours) on the periodic grid: (labels with
    0 off the contact and 1..count on it, count)."""
    lab, count = ndimage.label(active2)
    if count == 0:
        return lab, 0
    parent = np.arange(count + 1)

    def find(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a_edge, b_edge in ((lab[0, :], lab[-1, :]), (lab[:, 0], lab[:, -1])):
        both = (a_edge > 0) & (b_edge > 0)
        for a, b in zip(a_edge[both], b_edge[both]):
            ra, rb = find(int(a)), find(int(b))
            if ra != rb:
                parent[max(ra, rb)] = min(ra, rb)
    roots = np.array([find(i) for i in range(count + 1)])
    uniq, inv = np.unique(roots[1:], return_inverse=True)
    remap = np.concatenate(([0], inv + 1))
    return remap[lab], int(uniq.size)


def _patches(sigma2, active2, z2, aspect, direction, load):
    """The contact patches (`SurfacePatch`), largest load first."""
    nx, ny = active2.shape
    lab, count = _label_periodic(active2)
    if count == 0:
        return ()
    e = np.array([math.cos(direction), math.sin(direction)])
    xs = np.arange(nx) / nx - 0.5
    ys = (np.arange(ny) / ny - 0.5) * aspect
    total = sigma2.sum()
    out = []
    objs = ndimage.value_indices(lab, ignore_value=0)
    for k in range(1, count + 1):
        ii, jj = objs[k]
        s = sigma2[ii, jj]
        top = int(np.argmax(z2[ii, jj]))
        summit = np.array([xs[ii[top]], ys[jj[top]]])
        # positions unwrapped about the summit (the cell's periods 1 and aspect)
        dx = (xs[ii] - summit[0] + 0.5) % 1.0 - 0.5
        dy = (ys[jj] - summit[1] + 0.5 * aspect) % aspect - 0.5 * aspect
        # a patch that spans the cell along an axis wraps onto itself there (it percolates):
        # no centroid along that axis
        wraps = (np.unique(ii).size == nx, np.unique(jj).size == ny)
        c = np.array([dx.mean(), dy.mean()])
        pc = np.array([np.sum(dx * s), np.sum(dy * s)]) / s.sum() if s.sum() > 0 else c
        cen = tuple(None if w else float(v) for w, v in zip(wraps, summit + c))
        pcen = tuple(None if w else float(v) for w, v in zip(wraps, summit + pc))
        along = all(not w or abs(ei) < 1e-12 for w, ei in zip(wraps, e))
        ecc = float(np.dot(np.where(wraps, 0.0, c), e)) if along else None
        pecc = float(np.dot(np.where(wraps, 0.0, pc), e)) if along else None
        out.append(SurfacePatch(area=ii.size / (nx * ny),
                                load=float(load * s.sum() / total) if total > 0 else 0.0,
                                panels=int(ii.size), summit=tuple(float(v) for v in summit),
                                centroid=cen, pressure_centroid=pcen, eccentricity=ecc,
                                pressure_eccentricity=pecc))
    return tuple(sorted(out, key=lambda p: -p.load))


def _friction(grid, sigma, direction):
    """(τf, lateral force over the cell, direct τf): the frictional stresses (1 − ν²)/E_ref.

    With σ = Σ σ_q e^{i q·x} (q in k) and k u_q = Ĉ(q) σ_q, the mean of σ ∂u/∂d over the cell
    is −Σ_q (q·d) Im Ĉ(q) |σ_q|² (Parseval; the real parts cancel between q and −q): τf is
    minus that along e, the lateral force that along e⊥ = (−sin θ, cos θ), each a sum of what
    the modes dissipate, insensitive to phase errors.  The direct form −mean(σ ∂z/∂e) uses the
    surface's slope (u = z − s on the contact): the two agree to the discretisation error and
    their difference is the result's ``friction_mismatch``.
    """
    nx, ny = grid.shape
    spec = grid.op.spectrum(sigma)
    power = spec.real ** 2 + spec.imag ** 2
    del spec
    weight = np.full(ny // 2 + 1, 2.0)
    weight[0] = 1.0
    if ny % 2 == 0:
        weight[-1] = 1.0  # +ny/2 and -ny/2 share one discrete mode
    m = np.fft.fftfreq(nx, 1.0 / nx)[:, None]
    n = (np.arange(ny // 2 + 1) / grid.aspect)[None, :]
    # a Nyquist mode stands for wave vectors of both signs along its axis: its derivative
    # there is zero (their contributions cancel), as in spectral differentiation
    if nx % 2 == 0:
        m[nx // 2] = 0.0
    if ny % 2 == 0:
        n[0, -1] = 0.0
    c, s = math.cos(direction), math.sin(direction)
    im = grid.op.symbol.imag * power * weight[None, :]
    tau = float(np.sum(im * (m * c + n * s)))
    lateral = -float(np.sum(im * (-m * s + n * c)))
    return tau, lateral


def _direct_friction(surface, grid, sigma, direction):
    gx, gy = surface.gradient(*grid.shape)
    slope = gx.reshape(-1) * math.cos(direction) + gy.reshape(-1) * math.sin(direction)
    return -float(np.dot(sigma, slope)) / grid.n


def measure(res, grid, surface, direction, load_asked):
    """The scalars of one solved grid (a plain dict)."""
    sigma, active = res["sigma"], res["active"]
    amp = grid.amp
    load = float(sigma.mean()) if load_asked is None else load_asked
    tau, lateral = _friction(grid, sigma, direction)
    direct = _direct_friction(surface, grid, sigma, direction)
    nx, ny = grid.shape
    a2 = active.reshape(grid.shape)
    s2 = sigma.reshape(grid.shape)
    patches = _patches(s2, a2, (grid.y.reshape(grid.shape)), surface.aspect, direction, load)
    imax = int(np.argmax(sigma))
    i, j = divmod(imax, ny)
    sep = float(res["s"])
    return {
        "full_contact": bool(active.all()),
        "contact_fraction": contact_area(a2, res["gap"].reshape(grid.shape)),
        "contact_panels": float(np.count_nonzero(active)) / grid.n,
        "penetration": 1.0 - sep / amp,
        "separation": sep / amp,
        "tau_f": tau,
        "mu": tau / load,
        "mu_lateral": lateral / load,
        "tau_direct": direct,
        "n_patches": len(patches),
        "patches": patches,
        "max_pressure": float(sigma[imax]),
        "at_max_pressure": (i / nx - 0.5, (j / ny - 0.5) * surface.aspect),
        "load": load,
    }


