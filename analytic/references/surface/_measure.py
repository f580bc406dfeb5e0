"""Measurements on one solved grid of the surface reference: the friction and lateral force
as spectral sums and from the surface's slope, the refined contact area, the patches, the peak
pressure and the lowest pressure of full contact."""
from __future__ import annotations

import math

import numpy as np
from scipy import ndimage
from scipy.optimize import minimize

#: the fit window's half-width (points) and the quadratic's smallest number of points
_WINDOW = 4
_MIN_FIT = 9


def _square_fraction(a, b, d):
    """Area of {a u + b v ≤ d} in the unit square (arrays; a, b, d of one shape)."""
    d = d - np.where(a < 0.0, a, 0.0) - np.where(b < 0.0, b, 0.0)   # reflect u → 1 − u
    a, b = np.abs(a), np.abs(b)
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    out = np.empty(a.shape)
    thin = lo <= 1e-7 * hi      # a line along a side: the mean of its clipped position
    with np.errstate(divide="ignore", invalid="ignore"):
        out[thin] = np.clip((d[thin] - 0.5 * lo[thin]) / hi[thin], 0.0, 1.0)
        F = lambda t: 0.5 * np.maximum(t, 0.0) ** 2
        w = ~thin
        aw, bw, dw = a[w], b[w], d[w]
        out[w] = (F(dw) - F(dw - aw) - F(dw - bw) + F(dw - aw - bw)) / (aw * bw)
    return np.clip(out, 0.0, 1.0)


def _contact_area(contact, gap, rho):
    """(refined area fraction, points of the edge band, points fitted) of one grid.

    rho = hy/hx, the panel's aspect; positions in units of hx.  See the module docstring.
    """
    nx, ny = contact.shape
    near = ndimage.maximum_filter(contact, size=3, mode="wrap")
    inner = ndimage.minimum_filter(contact, size=3, mode="wrap")
    band = near & ~inner
    far_gap = ~near
    frac = contact.astype(float)
    bi, bj = np.nonzero(band)
    if bi.size == 0:
        return float(frac.mean()), 0, 0
    r = np.arange(-_WINDOW, _WINDOW + 1)
    di, dj = np.meshgrid(r, r, indexing="ij")
    di, dj = di.ravel(), dj.ravel()
    ii = (bi[:, None] + di[None, :]) % nx
    jj = (bj[:, None] + dj[None, :]) % ny
    use = far_gap[ii, jj]
    phi = np.where(use, np.maximum(gap[ii, jj], 0.0), 0.0) ** (2.0 / 3.0)
    X, Y = di.astype(float), dj * rho
    basis = np.stack([np.ones_like(X), X, Y, X * X, X * Y, Y * Y], axis=1)   # (81, 6)
    wgt = use.astype(float)
    count = wgt.sum(axis=1)
    fitted = np.zeros(bi.size, dtype=bool)
    coef = np.zeros((bi.size, 3))
    for ncols, enough in ((6, count >= _MIN_FIT), (3, (count >= 4) & (count < _MIN_FIT))):
        if not np.any(enough):
            continue
        A = basis[:, :ncols]
        w = wgt[enough]
        ata = np.einsum("bk,ki,kj->bij", w, A, A)
        atb = np.einsum("bk,ki,bk->bi", w, A, phi[enough])
        # a singular window (points on a line) keeps the nodal value
        cond = np.linalg.cond(ata)
        good = np.isfinite(cond) & (cond < 1e10)
        sol = np.zeros((ata.shape[0], ncols))
        if np.any(good):
            sol[good] = np.linalg.solve(ata[good], atb[good][..., None])[..., 0]
        idx = np.flatnonzero(enough)[good]
        coef[idx] = sol[good][:, :3]
        fitted[idx] = True
    a0, a1, a2 = coef[:, 0], coef[:, 1], coef[:, 2]
    ok = fitted & ((a1 != 0.0) | (a2 != 0.0))
    # the cell [−½, ½] × [−ρ/2, ρ/2] as the unit square: u = X + ½, v = Y/ρ + ½
    part = _square_fraction(a1[ok], a2[ok] * rho, -(a0[ok] - 0.5 * a1[ok] - 0.5 * a2[ok] * rho))
    frac[bi[ok], bj[ok]] = part
    return float(frac.mean()), int(bi.size), int(np.count_nonzero(ok))


def _patches(contact):
    """(number of patches, points of the smallest): four-neighbour components, periodic."""
    labels, count = ndimage.label(contact)
    if count == 0:
        return 0, 0
    parent = list(range(count + 1))

    def root(a):
        while parent[a] != a:
            parent[a] = parent[parent[a]]
            a = parent[a]
        return a

    for a, b in ((labels[:, -1], labels[:, 0]), (labels[-1, :], labels[0, :])):
        for p, q in zip(a[(a > 0) & (b > 0)], b[(a > 0) & (b > 0)]):
            rp, rq = root(int(p)), root(int(q))
            if rp != rq:
                parent[max(rp, rq)] = min(rp, rq)
    roots = np.array([root(i) for i in range(count + 1)])
    sizes = np.bincount(roots[labels[contact]], minlength=count + 1)
    sizes = sizes[sizes > 0]
    return int(sizes.size), int(sizes.min())


def _peak(sigma, rho):
    """The peak of σ: the nodal maximum, polished by the vertex of the quadratic fitted on its
    3 × 3 neighbourhood when that vertex is a maximum within one spacing."""
    nx, ny = sigma.shape
    i, j = np.unravel_index(np.argmax(sigma), sigma.shape)
    top = float(sigma[i, j])
    r = np.array([-1, 0, 1])
    di, dj = np.meshgrid(r, r, indexing="ij")
    vals = sigma[(i + di) % nx, (j + dj) % ny].ravel()
    X, Y = di.ravel().astype(float), dj.ravel() * rho
    A = np.stack([np.ones(9), X, Y, X * X, X * Y, Y * Y], axis=1)
    c = np.linalg.lstsq(A, vals, rcond=None)[0]
    hess = np.array([[2.0 * c[3], c[4]], [c[4], 2.0 * c[5]]])
    if np.all(np.linalg.eigvalsh(hess) < 0.0):
        v = np.linalg.solve(hess, -c[1:3])
        if abs(v[0]) <= 1.0 and abs(v[1]) <= rho:
            return max(top, float(c[0] + c[1] * v[0] + c[2] * v[1] + c[3] * v[0] ** 2
                                  + c[4] * v[0] * v[1] + c[5] * v[1] ** 2))
    return top


def _lowest(f):
    """The minimum of the trigonometric interpolant of the grid values f (at the threshold of
    full contact the load is minus the lowest oscillating pressure, which may fall between the
    points): Nelder–Mead from the lowest point, on the interpolant evaluated exactly."""
    nx, ny = f.shape
    spec = np.fft.fft2(f) / f.size
    mx, my = np.fft.fftfreq(nx, 1.0 / nx), np.fft.fftfreq(ny, 1.0 / ny)

    def basis(m, n, a):
        out = np.exp(2j * math.pi * m * a / n)
        if n % 2 == 0:
            out[n // 2] = math.cos(math.pi * a)   # the Nyquist mode as the cosine it holds
        return out

    value = lambda p: float((basis(mx, nx, p[0]) @ spec @ basis(my, ny, p[1])).real)
    i, j = np.unravel_index(np.argmin(f), f.shape)
    x0 = np.array([i, j], dtype=float)
    res = minimize(value, x0, method="Nelder-Mead",
                   options={"xatol": 1e-10, "fatol": 1e-16, "maxiter": 1000,
                            "initial_simplex": [x0, x0 + [0.5, 0.0], x0 + [0.0, 0.5]]})
    return min(float(f[i, j]), float(res.fun))


def _level_scalars(grid, sigma, gap, s, zk, h_ref, full):
    """The scalars and diagnostics of one solved grid (zk: k z on it; full: in full contact,
    where σ may touch 0 at a point, at the threshold)."""
    load = float(np.mean(sigma))
    tau = grid.spectral_sum(grid.dissipation, sigma)
    lat = grid.spectral_sum(grid.lateral, sigma)
    zh = grid.rfft(zk)
    slope = grid.irfft(grid.slope * zh)
    slope_lat = grid.irfft(grid.slope_lateral * zh)
    contact = np.full(sigma.shape, True) if full else sigma > 0.0
    rho = (grid.aspect / grid.ny) * grid.nx
    area, band, fitted = _contact_area(contact, gap, rho)
    n_patches, smallest = _patches(contact)
    scale = max(float(sigma.max()), 1e-300)
    return {
        "load": load,
        "penetration": 1.0 - s / h_ref,
        "tau_f": tau,
        "mu": tau / load if load > 0.0 else math.nan,
        "mu_lateral": lat / load if load > 0.0 else math.nan,
        "contact_fraction": 1.0 if contact.all() else area,
        "max_pressure": _peak(sigma, rho),
        "n_patches": n_patches,
        "full_contact": bool(contact.all()),
        "smallest_patch_points": smallest,
        "contact_fraction_nodal": float(np.mean(contact)),
        "mu_direct": -float(np.mean(sigma * slope)) / load if load > 0.0 else math.nan,
        "mu_lateral_direct": float(np.mean(sigma * slope_lat)) / load if load > 0.0
        else math.nan,
        "edge_points": band,
        "edge_points_fitted": fitted,
        "complementarity": max(float(np.max(np.abs(gap[contact]), initial=0.0)) / h_ref,
                               float(-gap.min()) / h_ref, float(-sigma.min()) / scale, 0.0),
    }
