"""The surface of the surface reference: k·z given as a callable, point values or harmonics,
sampled on a level's grid (shifted if asked), and its reference height h_ref."""
from __future__ import annotations

import math
import numbers

import numpy as np
from scipy.optimize import minimize

from viscosine.checks import bad, is_integer

_TWO_PI = 2.0 * math.pi


class _Surface:
    """k·z as one of: a callable of (x/Lx, y/Lx), point values at the panel centres, harmonics.

    ``kind`` is "callable", "array" or "harmonics"; `sample` gives k z on a level's grid.
    """

    def __init__(self, heights, aspect):
        self.aspect = aspect
        what = ("a callable f(x, y) → k·z (x, y over Lx, arrays of one shape), a 2-D array of "
                "k·z at the panel centres x_i = i/nx − ½, y_j = (j/ny − ½)·aspect (nx, ny ≥ 2, "
                "finite, not flat), or a mapping {(m, n): c} of harmonics "
                "k·z = Σ Re[c e^{2πi(m x + n y/aspect)}] (integers m, n; complex c; not all "
                "zero)")
        self.what = what
        if callable(heights):
            self.kind, self.func = "callable", heights
            return
        if isinstance(heights, dict):
            modes = {}
            for key, c in heights.items():
                if not (isinstance(key, tuple) and len(key) == 2 and all(map(is_integer, key))
                        and isinstance(c, numbers.Complex) and not isinstance(c, bool)
                        and math.isfinite(abs(complex(c)))):
                    raise bad("heights", heights, what)
                m, n = int(key[0]), int(key[1])
                # (m, n) and (−m, −n) describe one real mode: fold onto one of them
                if (m, n) < (0, 0) and not (m == 0 and n == 0):
                    m, n, c = -m, -n, complex(c).conjugate()
                modes[(m, n)] = modes.get((m, n), 0.0) + complex(c)
            modes = {k: c for k, c in modes.items() if k != (0, 0) and c != 0.0}
            if not modes:
                raise bad("heights", heights, what)
            self.kind, self.modes = "harmonics", modes
            self.max_m = max(abs(m) for m, _ in modes)
            self.max_n = max(abs(n) for _, n in modes)
            return
        if isinstance(heights, (str, bytes)):
            raise bad("heights", heights, what)
        try:
            arr = np.asarray(heights)
        except (TypeError, ValueError):
            raise bad("heights", heights, what) from None
        if arr.ndim != 2 or arr.dtype.kind not in "iuf" or min(arr.shape) < 2 \
                or not np.all(np.isfinite(arr)) or np.ptp(arr) == 0.0:
            raise bad("heights", heights, what)
        self.kind, self.values = "array", arr.astype(float)

    def grid_for(self, nx):
        """(nx, ny) of the level with nx panels along x."""
        if self.kind == "array":
            nx0, ny0 = self.values.shape
            return nx, ny0 * nx // nx0
        return nx, max(2, 2 * int(round(0.5 * nx * self.aspect)))

    def check_nodes(self, levels):
        """Refuse grids on which this surface is not represented."""
        if self.kind == "array":
            nx0 = self.values.shape[0]
            if any(n % nx0 for n in levels):
                raise bad("nodes", list(levels), f"multiples of the array's {nx0} points along "
                          "x (each grid holds the array's interpolant)")
        if self.kind == "harmonics":
            n0 = levels[0]
            nx, ny = self.grid_for(n0)
            if 2 * self.max_m >= nx or 2 * self.max_n >= ny:
                raise bad("nodes", list(levels), f"grids whose Nyquist modes exceed the "
                          f"harmonics (|m| < nx/2, |n| < ny/2 with ny = nx·aspect rounded even): "
                          f"the coarsest has nx = {nx}, ny = {ny} for |m| ≤ {self.max_m}, "
                          f"|n| ≤ {self.max_n}")

    def sample(self, nx, ny, shift=0.0):
        """k z at the panel centres of the nx × ny grid (shape (nx, ny)), the surface moved by
        ``shift`` of a panel along both axes (z(x + shift/nx, y + shift·aspect/ny))."""
        x = (np.arange(nx) + shift) / nx - 0.5
        y = ((np.arange(ny) + shift) / ny - 0.5) * self.aspect
        if self.kind == "callable":
            xx, yy = np.meshgrid(x, y, indexing="ij")
            try:
                out = np.asarray(self.func(xx, yy), dtype=float)
            except Exception as exc:  # any failure of the user's function is a bad input
                raise bad("heights", self.func, self.what + f" (calling it raised {exc!r})") \
                    from None
            if out.shape == ():
                out = np.full((nx, ny), float(out))
            if out.shape != (nx, ny) or not np.all(np.isfinite(out)):
                raise bad("heights", self.func, self.what + f" (it returned shape {out.shape} "
                          f"or non-finite values for arrays of shape {(nx, ny)})")
            return out
        if self.kind == "harmonics":
            out = np.zeros((nx, ny))
            for (m, n), c in self.modes.items():
                ex = np.exp(1j * _TWO_PI * m * x)
                ey = np.exp(1j * _TWO_PI * n * y / self.aspect)
                out += (c * np.outer(ex, ey)).real
            return out
        return _interpolate(self.values, nx, ny, shift)

    def extent(self, fine):
        """k h_ref = max z − mean z, from the finest grid's samples ``fine``.

        The array's own samples define it; a callable's or the harmonics' maximum is polished
        from the best grid point by a local search (the crest may lie between points).
        """
        if self.kind == "array":
            return float(self.values.max() - self.values.mean())
        nx, ny = fine.shape
        i, j = np.unravel_index(np.argmax(fine), fine.shape)
        x0 = np.array([i / nx - 0.5, (j / ny - 0.5) * self.aspect])
        if self.kind == "harmonics":
            def neg(p):
                return -sum((c * np.exp(1j * _TWO_PI * (m * p[0] + n * p[1] / self.aspect))).real
                            for (m, n), c in self.modes.items())
        else:
            def neg(p):
                return -float(np.asarray(self.func(np.array([[p[0]]]), np.array([[p[1]]])),
                                         dtype=float).ravel()[0])
        step = np.array([1.0 / nx, self.aspect / ny])
        res = minimize(neg, x0, method="Nelder-Mead",
                       options={"xatol": 1e-12, "fatol": 1e-15, "maxiter": 2000,
                                "initial_simplex": [x0, x0 + [step[0], 0], x0 + [0, step[1]]]})
        top = max(float(fine.max()), -float(res.fun)) if np.isfinite(res.fun) else fine.max()
        if self.kind == "harmonics":
            return float(top)  # mean 0: mode (0, 0) is dropped
        return float(top - fine.mean())


def _interpolate(values, nx, ny, shift=0.0):
    """The trigonometric interpolant of ``values`` (panel centres) at the centres of nx × ny,
    moved by ``shift`` of a new panel along both axes.

    Zero padding of the spectrum, axis by axis; an even axis's Nyquist coefficient is split
    equally between +N/2 and −N/2 (the real interpolant of the cosine the samples hold); the
    shift is the phase e^{2πi m shift/N} of mode m.
    """
    out = values
    for axis, new in ((0, nx), (1, ny)):
        old = out.shape[axis]
        if new == old and shift == 0.0:
            continue
        # both grids start at −½: the phase (−1)^m of that offset is the same on both
        spec = np.fft.fft(out, axis=axis) / old
        pad = np.zeros(spec.shape[:axis] + (new,) + spec.shape[axis + 1:], dtype=complex)
        half = (old - 1) // 2
        sl = [slice(None)] * 2
        sl[axis] = slice(0, half + 1)
        pad[tuple(sl)] = spec[tuple(sl)]
        sl[axis] = slice(new - half, new)
        src = [slice(None)] * 2
        src[axis] = slice(old - half, old)
        if half:
            pad[tuple(sl)] = spec[tuple(src)]
        if old % 2 == 0:
            nyq = [slice(None)] * 2
            nyq[axis] = old // 2
            up, down = list(nyq), list(nyq)
            down[axis] = new - old // 2
            pad[tuple(up)] += 0.5 * spec[tuple(nyq)]
            pad[tuple(down)] += 0.5 * spec[tuple(nyq)]
        if shift != 0.0:
            phase = np.exp(1j * _TWO_PI * np.fft.fftfreq(new) * shift)
            pad *= phase.reshape((-1, 1) if axis == 0 else (1, -1))
        out = (np.fft.ifft(pad, axis=axis) * new).real
    return out
