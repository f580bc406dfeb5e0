"""Rigid periodic surfaces z = h(x, y) for the surface solver (validated, nondimensional).

Units: lengths over the cell's x side Lx (the cell is 1 by ``aspect`` = Ly/Lx), heights ``k z``
with k = 2 pi/Lx, wave vectors q in units of k (mode (m, n) of the cell has q = (m, n/aspect)).
Heights are positive toward the body: the highest point is the deepest point of the indenter.
The reference height is h_ref = max h - mean h (the line contact's h), ``amplitude`` = k h_ref.

Every surface here is band-limited: a finite sum of the cell's Fourier modes, so it is sampled
exactly on any grid fine enough to hold its modes (``min_nodes``), and mesh refinement refines
the discretisation of one and the same surface.  Grids are ``(nx, ny)`` panels with centres
``x_i = i/nx - 1/2`` and ``y_j = (j/ny - 1/2) aspect`` (the crest of the bi-sinusoid at the
origin, index (nx/2, ny/2)); arrays are indexed ``[i, j]``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from viscosine.checks import bad, integer, real

from ._inputs import _numbers, _rows

_TWO_PI = 2.0 * math.pi


def _aspect(value) -> float:
    return real("aspect", value, "a finite cell ratio Ly/Lx in [1/64, 64]",
                lambda v: 1.0 / 64.0 <= v <= 64.0, kind=True)


class Surface:
    """A band-limited periodic surface: Fourier coefficients on the cell's modes.

    Attributes
    ----------
    aspect : float
        Ly/Lx.
    modes : ndarray, shape (K, 2), int
        (m, n) of the coefficients kept (one of each conjugate pair: the heights are
        ``sum Re(c (2 - [m = n = 0]) e^{2 pi i (m x + n y/aspect)})`` over the kept modes).
    coefficients : ndarray, shape (K,), complex
        ``c`` of each kept mode, heights in ``k z``.
    """

    def __init__(self, modes, coefficients, aspect=1.0, describe=None):
        m = np.asarray(modes, dtype=np.int64).reshape(-1, 2)
        c = np.asarray(coefficients, dtype=complex).reshape(-1)
        keep = (m[:, 0] != 0) | (m[:, 1] != 0)  # the mean plane carries no height
        self.modes = m[keep]
        self.coefficients = c[keep]
        self.aspect = _aspect(aspect)
        self._describe = describe or {"kind": "fourier", "modes": int(self.modes.shape[0])}
        if self.modes.shape[0] == 0 or not np.any(self.coefficients != 0):
            raise bad("surface", self._describe, "a surface with relief (every height is the "
                      "same: nothing touches but everything, and no contact problem is left)")
        self._amp = None

    # -- sampling -------------------------------------------------------------------------
    @property
    def band(self) -> tuple:
        """(max |m|, max |n|) of the kept modes."""
        return int(np.max(np.abs(self.modes[:, 0]))), int(np.max(np.abs(self.modes[:, 1])))

    def min_nodes(self) -> tuple:
        """The coarsest (nx, ny) that holds every mode below its Nyquist mode (exact samples)."""
        bm, bn = self.band
        return 2 * bm + 2, 2 * bn + 2

    def spectrum(self, nx: int, ny: int) -> np.ndarray:
        """The ``rfft2`` (axes 0, 1; no factor) of the heights sampled on the (nx, ny) grid."""
        bm, bn = self.band
        if nx < 2 * bm + 2 or ny < 2 * bn + 2:
            raise bad("nodes", (nx, ny), f"a grid of at least {2 * bm + 2} x {2 * bn + 2} panels "
                      "(the surface's finest mode must lie below the grid's Nyquist mode)")
        spec = np.zeros((nx, ny // 2 + 1), dtype=complex)
        m = self.modes[:, 0].copy()
        n = self.modes[:, 1].copy()
        c = self.coefficients.copy()
        flip = n < 0  # (m, n) and (-m, -n) carry conjugate coefficients: keep n >= 0
        m[flip], n[flip], c[flip] = -m[flip], -n[flip], np.conj(c[flip])
        # panel centres at i/nx - 1/2: the mode's phase at i = 0 is e^{-i pi (m + n)}
        phase = np.where((m + n) % 2 == 0, 1.0, -1.0)
        total = nx * ny
        for mm, nn, cc, ph in zip(m, n, c, phase):
            if nn == 0:
                # both c (at m) and conj(c) (at -m) live in the n = 0 column
                spec[mm % nx, 0] += total * cc * ph
                spec[(-mm) % nx, 0] += total * np.conj(cc) * ph
            else:
                spec[mm % nx, nn] += total * cc * ph
        return spec

    def sample(self, nx: int, ny: int) -> np.ndarray:
        """Heights ``k z`` at the panel centres of the (nx, ny) grid (exact: band-limited)."""
        return np.fft.irfft2(self.spectrum(nx, ny), s=(nx, ny), axes=(0, 1))

    def gradient(self, nx: int, ny: int) -> tuple:
        """(dz/dx, dz/dy) at the panel centres (exact; slopes are dimensionless)."""
        spec = self.spectrum(nx, ny)
        m = np.fft.fftfreq(nx, 1.0 / nx)[:, None]
        n = np.arange(ny // 2 + 1)[None, :]
        gx = np.fft.irfft2(spec * (1j * m), s=(nx, ny), axes=(0, 1))
        gy = np.fft.irfft2(spec * (1j * n / self.aspect), s=(nx, ny), axes=(0, 1))
        return gx, gy

    @property
    def amplitude(self) -> float:
        """k h_ref = k (max h - mean h), the crest above the mean plane."""
        if self._amp is None:
            self._amp = self._crest()
        return self._amp

    def _crest(self) -> float:
        # on a fine grid, then polished by Newton steps on the trigonometric sum from the best
        # sample (a max between samples: the crest of a random surface need not sit on a node)
        bm, bn = self.band
        nx = max(64, 8 * (2 * bm + 2))
        ny = max(64, 8 * (2 * bn + 2))
        while nx * ny > 2 ** 24:
            nx, ny = max(2 * bm + 2, nx // 2), max(2 * bn + 2, ny // 2)
        z = self.sample(nx, ny)
        i, j = np.unravel_index(int(np.argmax(z)), z.shape)
        p = np.array([i / nx - 0.5, (j / ny - 0.5) * self.aspect])
        best = float(z[i, j])
        for _ in range(20):
            val, g, hess = self._local(p)
            try:
                step = np.linalg.solve(hess, -g)
            except np.linalg.LinAlgError:
                break
            if not np.all(np.isfinite(step)) or np.linalg.norm(step) > 2.0 / min(nx, ny):
                break
            p = p + step
            best = max(best, self._local(p)[0])
            if np.linalg.norm(step) < 1e-14:
                break
        return best

    def _local(self, p):
        """(z, grad z, Hessian of z) at the point p = (x, y) over Lx."""
        m = self.modes[:, 0].astype(float)
        n = self.modes[:, 1].astype(float) / self.aspect
        w = np.where((self.modes[:, 0] == 0) & (self.modes[:, 1] == 0), 1.0, 2.0)
        ph = np.exp(1j * _TWO_PI * (m * p[0] + n * p[1]))
        a = w * self.coefficients * ph
        z = float(np.sum(a.real))
        gx = float(np.sum((a * 1j * _TWO_PI * m).real))
        gy = float(np.sum((a * 1j * _TWO_PI * n).real))
        hxx = float(np.sum((a * -(_TWO_PI * m) ** 2).real))
        hyy = float(np.sum((a * -(_TWO_PI * n) ** 2).real))
        hxy = float(np.sum((a * -(_TWO_PI ** 2) * m * n).real))
        return z, np.array([gx, gy]), np.array([[hxx, hxy], [hxy, hyy]])

    def rms(self) -> dict:
        """Root mean squares: ``height`` (k z_rms) and ``slope`` (sqrt <|grad z|^2>)."""
        q2 = self.modes[:, 0] ** 2 + (self.modes[:, 1] / self.aspect) ** 2
        p = 2.0 * np.abs(self.coefficients) ** 2  # each kept mode and its conjugate
        return {"height": float(np.sqrt(np.sum(p))), "slope": float(np.sqrt(np.sum(p * q2)))}

    def describe(self) -> dict:
        """The surface as plain data (for the result's record)."""
        return dict(self._describe, aspect=self.aspect, amplitude=self.amplitude)

    def rotated_quarter(self, turns: int = 1) -> "Surface":
        """The surface rotated by ``turns`` quarter turns counter-clockwise about the origin
        (the cell's sides swap for odd turns)."""
        m, n = self.modes[:, 0], self.modes[:, 1]
        for _ in range(turns % 4):
            m, n = -n, m
        aspect = self.aspect if turns % 2 == 0 else 1.0 / self.aspect
        # in units of the new Lx the heights and wave vectors rescale when the cell's sides swap
        scale = 1.0 if turns % 2 == 0 else aspect
        return Surface(np.column_stack([m, n]), self.coefficients * scale, aspect,
                       dict(self._describe, rotated_quarter_turns=turns % 4))


def bisinusoid(hk: float = 1.0, hk_y: float | None = None, aspect: float = 1.0) -> Surface:
    """z = h_x cos(k x) + h_y cos(2 pi y/Ly) on the cell Lx x Ly (crest at the origin).

    Parameters
    ----------
    hk : float
        k h_x, with k = 2 pi/Lx; > 0.
    hk_y : float, optional
        k h_y (the same k: heights are all in units of 1/k); default ``hk``, 0 for a surface
        uniform in y (the line contact's sinusoid extruded).
    aspect : float
        Ly/Lx (the wavelength along y over the wavelength along x).

    The conventions' bi-sinusoid is ``bisinusoid(hk)``: h_ref = 2 h.
    """
    hx = real("hk", hk, "a finite h k > 0", lambda v: v > 0.0, kind=True)
    hy = hx if hk_y is None else real("hk_y", hk_y, "a finite h_y k >= 0", lambda v: v >= 0.0,
                                      kind=True)
    modes, coeffs = [(1, 0)], [0.5 * hx]
    if hy > 0.0:
        modes.append((0, 1))
        coeffs.append(0.5 * hy)
    desc = {"kind": "bisinusoid", "hk": hx, "hk_y": hy}
    return Surface(modes, coeffs, aspect, desc)


def self_affine(*, hurst: float, rolloff: float, short_cutoff: float, long_cutoff: float = 1.0,
                rms_slope: float | None = None, rms_height: float | None = None, seed: int = 0,
                aspect: float = 1.0) -> Surface:
    """A random isotropic self-affine surface by Fourier synthesis with a seeded generator.

    Power spectrum (Persson's normalisation, <z^2> = integral of C(q) d^2q), q = |q| in units
    of k = 2 pi/Lx::

        C(q) = C0                          for long_cutoff <= q < rolloff
        C(q) = C0 (q/rolloff)^(-2(1 + H))  for rolloff <= q <= short_cutoff
        C(q) = 0                           elsewhere

    Every mode of the cell inside the band gets the amplitude sqrt(C(q)) (times the cell's mode
    spacing) and a uniformly random phase: the surface's discrete spectrum is the target exactly
    (no amplitude scatter), its heights are nearly Gaussian, and C0 is fixed by the rms slope or
    height of the kept modes (exactly one of the two).  The mode (m, n) and its conjugate are
    drawn once, in a fixed order, from ``numpy.random.default_rng(seed)``: the same seed gives
    the same surface on every machine and every grid.

    Parameters
    ----------
    hurst : float
        H in (0, 1).
    rolloff, short_cutoff, long_cutoff : float
        q_r, q_s, q_l in units of k: 1 <= q_l <= q_r <= q_s <= 512.
    rms_slope : float, optional
        sqrt(<|grad z|^2>), > 0.
    rms_height : float, optional
        k z_rms, > 0.
    seed : int
        >= 0.
    aspect : float
        Ly/Lx.
    """
    h = real("hurst", hurst, "a Hurst exponent in (0, 1)", lambda v: 0.0 < v < 1.0, kind=True)
    ql = real("long_cutoff", long_cutoff, "a finite q_l/k >= 1 (k = 2 pi/Lx: the cell's lowest "
              "wavenumber)", lambda v: v >= 1.0, kind=True)
    qr = real("rolloff", rolloff, f"a finite q_r/k in [long_cutoff, 512] = [{ql:g}, 512]",
              lambda v: ql <= v <= 512.0, kind=True)
    qs = real("short_cutoff", short_cutoff, f"a finite q_s/k in [rolloff, 512] = [{qr:g}, 512]",
              lambda v: qr <= v <= 512.0, kind=True)
    if (rms_slope is None) == (rms_height is None):
        raise bad("rms_slope", rms_slope, "exactly one of rms_slope and rms_height (got "
                  f"rms_slope={rms_slope!r}, rms_height={rms_height!r})")
    if rms_slope is not None:
        target = real("rms_slope", rms_slope, "a finite rms slope > 0", lambda v: v > 0.0,
                      kind=True)
    else:
        target = real("rms_height", rms_height, "a finite k z_rms > 0", lambda v: v > 0.0,
                      kind=True)
    sd = integer("seed", seed, "an integer >= 0", lambda v: v >= 0)
    asp = _aspect(aspect)
    mmax = int(math.floor(qs))
    nmax = int(math.floor(qs * asp))
    mm, nn = np.meshgrid(np.arange(-mmax, mmax + 1), np.arange(0, nmax + 1), indexing="ij")
    mm, nn = mm.ravel(), nn.ravel()
    half = (nn > 0) | (mm > 0)  # one of each conjugate pair
    mm, nn = mm[half], nn[half]
    q = np.hypot(mm, nn / asp)
    inside = (q >= ql) & (q <= qs)
    mm, nn, q = mm[inside], nn[inside], q[inside]
    if mm.size == 0:
        raise bad("short_cutoff", qs, f"a band [{ql:g}, {qs:g}] that holds at least one mode of "
                  f"the cell (aspect {asp:g})")
    c = np.where(q < qr, 1.0, (q / qr) ** (-2.0 * (1.0 + h)))
    rng = np.random.default_rng(sd)
    phase = rng.uniform(0.0, _TWO_PI, size=mm.size)
    coeff = np.sqrt(c) * np.exp(1j * phase)
    q2 = q ** 2 if rms_slope is not None else np.ones_like(q)
    norm = math.sqrt(float(np.sum(2.0 * np.abs(coeff) ** 2 * q2)))
    coeff *= target / norm
    desc = {"kind": "self_affine", "hurst": h, "rolloff": qr, "short_cutoff": qs,
            "long_cutoff": ql, "seed": sd,
            ("rms_slope" if rms_slope is not None else "rms_height"): target}
    return Surface(np.column_stack([mm, nn]), coeff, asp, desc)


def sampled_surface(heights, aspect: float = 1.0, name: str = "heights") -> Surface:
    """A surface given by its heights ``k z`` on an (nx, ny) grid of panel centres.

    The heights are taken as samples of a band-limited periodic surface (trigonometric
    interpolation: refinement samples the same surface).  The grid's Nyquist modes are dropped
    (a mode at the Nyquist frequency has no unique interpolant); the record says how much of the
    heights' variance that removed.
    """
    z = np.asarray(heights)
    if z.dtype.kind not in "iuf":
        raise bad(name, "an array of " + str(z.dtype), "real heights")
    z = z.astype(float)
    if z.ndim != 2 or z.shape[0] < 4 or z.shape[1] < 4:
        raise bad(name, f"an array of shape {z.shape}", "a rectangular grid of at least 4 x 4 "
                  "heights (rows along x, columns along y)")
    if not np.all(np.isfinite(z)):
        bad_at = np.argwhere(~np.isfinite(z))[0]
        raise bad(name, f"a non-finite height at row {bad_at[0]}, column {bad_at[1]}",
                  "finite heights everywhere (the surface is periodic: no missing data)")
    check_periodic_edges(z, name)
    nx, ny = z.shape
    spec = np.fft.rfft2(z, axes=(0, 1)) / (nx * ny)
    m = np.fft.fftfreq(nx, 1.0 / nx).astype(np.int64)
    n = np.arange(ny // 2 + 1)
    mm, nn = np.meshgrid(m, n, indexing="ij")
    keep = np.ones(spec.shape, dtype=bool)
    if nx % 2 == 0:
        keep[nx // 2, :] = False
    if ny % 2 == 0:
        keep[:, ny // 2] = False
    keep &= (nn > 0) | (mm > 0)  # one of each conjugate pair
    var = float(np.var(z))
    # undo the centres' phase e^{-i pi (m + n)}
    sign = np.where((mm + nn) % 2 == 0, 1.0, -1.0)
    coeff = (spec * sign)[keep]
    dropped = var - float(np.sum(2.0 * np.abs(coeff) ** 2))
    desc = {"kind": "sampled", "shape": [nx, ny],
            "nyquist_variance_dropped": max(dropped, 0.0) / var if var > 0 else 0.0}
    return Surface(np.column_stack([mm[keep], nn[keep]]), coeff, aspect, desc)


def check_periodic_edges(z, name="heights", value=None, tol=0.5):
    """Refuse heights whose opposite edges do not match as a periodic surface's would.

    The jump across each edge of the cell is compared with the typical jump between
    neighbouring rows (columns) inside: a surface that was cut out of a larger one without
    making it periodic jumps by far more at its edge.  ``tol``: how many times the largest
    inside jump (times 1 + tol) the edge jump may be.  ``value``: what the refusal shows as
    the input (a file's name; default a description of the array).
    """
    z = np.asarray(z, dtype=float)
    for axis, what in ((0, "x (first and last rows)"), (1, "y (first and last columns)")):
        inside = np.max(np.abs(np.diff(z, axis=axis)))
        edge = np.max(np.abs(np.take(z, 0, axis=axis) - np.take(z, -1, axis=axis)))
        if inside > 0 and edge > (1.0 + tol) * inside:
            shown = f"an array of shape {z.shape}" if value is None else value
            raise bad(name, shown, f"a periodic surface whose cell tiles the plane (the "
                      f"heights jump by {edge:.3g} across {what}): more than {1 + tol:g} x the "
                      f"largest jump inside ({inside:.3g})")


def read_surface(path, units: str = "conventions", length: float | None = None) -> Surface:
    """Heights on a grid from a text file (whitespace- or comma-separated, '#' comments).

    Layout: one row per x panel, one column per y panel (centres ``i/nx - 1/2`` and
    ``(j/ny - 1/2) aspect``).  A comment line ``# aspect: A`` sets Ly/Lx (default ny/nx:
    square panels).  ``units``: ``"conventions"`` for heights ``k z`` (k = 2 pi/Lx), ``"SI"``
    for heights in metres, with ``length`` Lx in metres.  The heights must tile the plane (the
    problem is periodic: `check_periodic_edges`).
    """
    opt = "surface"
    rows = _rows(path, opt)
    aspect = None
    for line in Path(path).read_text(encoding="utf-8").splitlines():
        key, sep, val = line.strip().lstrip("#").partition(":")
        if line.strip().startswith("#") and sep and key.strip().lower() == "aspect":
            try:
                aspect = float(val)
            except ValueError:
                raise bad(opt, str(path), f"an '# aspect: A' line with a number (not "
                          f"{val.strip()!r})") from None
    widths = sorted({len(r) for r in rows})
    if len(widths) != 1:
        raise bad(opt, str(path), "a rectangular grid of heights: every row as many values "
                  f"(rows have {widths} values)")
    z = np.array([_numbers(opt, path, r) for r in rows])
    if z.shape[0] < 4 or z.shape[1] < 4:
        raise bad(opt, str(path), f"a grid of at least 4 x 4 heights (it has {z.shape[0]} x "
                  f"{z.shape[1]})")
    if units == "SI":
        lx = real("length", length, "the cell's side Lx in metres, > 0", lambda v: v > 0.0)
        z = z * (_TWO_PI / lx)
    elif units != "conventions":
        raise bad("units", units, "'conventions' (heights k z) or 'SI' (metres, with length)")
    if aspect is None:
        aspect = z.shape[1] / z.shape[0]
    check_periodic_edges(z, opt, str(path))
    surf = sampled_surface(z, aspect, name=opt)
    surf._describe.update(file=str(path))
    return surf
