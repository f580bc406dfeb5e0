"""The surface reference's operator on one grid: the wave vectors, the alias-averaged symbols
Ĉ(q) (times the layer factor on a layer) and the spectral sums of the dissipation and the
lateral force."""
from __future__ import annotations

import math

import numpy as np
from scipy import fft as sfft

from .._layer import layer_factor
from ._inputs import complex_compliance


class _Grid:
    """Wave vectors and the alias-averaged symbols of an nx × ny grid (rfft2 layout)."""

    def __init__(self, nx, ny, aspect, theta, speed, material, layer=None):
        self.nx, self.ny, self.aspect = nx, ny, aspect
        self.e = (math.cos(math.radians(theta)), math.sin(math.radians(theta)))
        self.speed, self.material = speed, material
        mx = np.fft.fftfreq(nx, 1.0 / nx)[:, None] * np.ones((1, ny // 2 + 1))
        ny_ = np.arange(ny // 2 + 1, dtype=float)[None, :] * np.ones((nx, 1))
        # the aliases of a Nyquist row (m = −nx/2 ~ +nx/2) or column (n = ny/2 ~ −ny/2)
        alt_m = np.where(np.abs(mx) * 2 == nx, -mx, mx) if nx % 2 == 0 else mx
        alt_n = np.where(ny_ * 2 == ny, -ny_, ny_) if ny % 2 == 0 else ny_
        self._pairs = [(a, b / aspect) for a in (mx, alt_m) for b in (ny_, alt_n)]
        # on a layer each alias's S(|q| k d, ν) (the half-space: None, its arithmetic unchanged)
        self._factors = [None] * 4 if layer is None else [
            layer_factor(np.hypot(qx, qy) * layer["thickness"], layer["nu"],
                         layer["foundation"]) for qx, qy in self._pairs]
        c = self.average(lambda qx, qy, f: self._compliance(qx, qy, f))
        self.symbol = c
        mag = np.abs(c)
        mag = mag[mag > 0.0]
        self.scales = (float(mag.min()), float(mag.max()))
        e, p = self.e, (-self.e[1], self.e[0])
        # (q·ê) Im Ĉ and (q·ê⊥) Im Ĉ: the dissipation and the lateral force per |σ̂_q|²
        self.dissipation = self.average(
            lambda qx, qy, f: (qx * e[0] + qy * e[1]) * self._compliance(qx, qy, f).imag)
        self.lateral = self.average(
            lambda qx, qy, f: -(qx * p[0] + qy * p[1]) * self._compliance(qx, qy, f).imag)
        self.slope = self.average(lambda qx, qy, f: 1j * (qx * e[0] + qy * e[1]))
        self.slope_lateral = self.average(lambda qx, qy, f: 1j * (qx * p[0] + qy * p[1]))
        # rfft2 holds the columns n = 1 … ny/2 − 1 once for the pair ±q: weight 2 in sums
        w = np.full(c.shape, 2.0)
        w[:, 0] = 1.0
        if ny % 2 == 0:
            w[:, -1] = 1.0
        self.weight = w

    def average(self, f):
        """f(qx, qy, S) on the rfft2 layout, averaged over the aliases of the Nyquist rows and
        columns (S: the alias's layer factor, None on the half-space)."""
        vals = [f(qx, qy, s) for (qx, qy), s in zip(self._pairs, self._factors)]
        return 0.25 * (vals[0] + vals[1] + vals[2] + vals[3])

    def _compliance(self, qx, qy, factor=None):
        q = np.hypot(qx, qy)
        j = complex_compliance(qx * self.e[0] + qy * self.e[1], self.speed, self.material)
        out = np.zeros(q.shape, dtype=complex)
        nz = q > 0.0
        if factor is None:
            out[nz] = 2.0 * j[nz] / q[nz]
        else:                                   # a layer: the mode's factor S(|q| k d, ν)
            out[nz] = 2.0 * j[nz] * factor[nz] / q[nz]
        return out

    def rfft(self, f):
        return sfft.rfft2(f)

    def irfft(self, f):
        return sfft.irfft2(f, (self.nx, self.ny))

    def apply(self, sigma):
        """k u = C σ (mode 0 of u is 0)."""
        return self.irfft(self.symbol * self.rfft(sigma))

    def spectral_sum(self, weights, sigma):
        """Σ_q weights(q) |σ̂_q|² over the whole spectrum (σ̂ normalised by the points)."""
        sh = self.rfft(sigma) / (self.nx * self.ny)
        return float(np.sum(self.weight * weights * (sh.real ** 2 + sh.imag ** 2)))
