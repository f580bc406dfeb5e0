"""The steady-sliding operator on a surface grid: a diagonal symbol on the cell's modes.

Transform convention
--------------------
* Panels (i, j) of an (nx, ny) grid are centred at ``x_i = i/nx - 1/2``, ``y_j = (j/ny - 1/2)
  aspect`` (lengths over Lx); fields are flattened in C order (index ``i ny + j``) for the
  active-set solver, which sees one vector of ``nx ny`` unknowns.
* ``k u = irfft2(Chat * rfft2(sigma))`` (``scipy.fft``: no factor forward, 1/(nx ny) inverse):
  the pressure is represented by its values at the panel centres and the displacement is
  collocated there (a spectral Galerkin-collocation scheme, Tamaas's and ContactMechanics'
  discretisation of the elastic half-space, here with the memory of the material).
* Mode (m, n) (``m`` from ``fftfreq`` along x, ``n = 0 .. ny/2`` along y) has the wave vector
  ``q = (m, n/aspect)`` in units of k = 2 pi/Lx and is loaded at the frequency ``q . e V``
  (e = (cos theta, sin theta) the sliding direction): its symbol is
  ``Chat = (2/|q|) J*(q . e) S(|q| k d)`` with the line contact's ``J*(n) = J(0+) + sum_i
  J_i/(1 - i n w tau_i)`` (eq. 2.5 in Fourier space, ``docs/surfaces.md``) and S the layer's
  factor (1 on the half-space).  The material streams toward -e, so the memory lies behind
  the load along -e.
* A Nyquist mode (m = -nx/2 or n = ny/2) is one discrete mode for two wave vectors of opposite
  sign: its symbol is the mean of theirs (real along the axes), which keeps the operator real
  and the grid's mirror and quarter-turn symmetries exact.
* Mode 0 carries nothing: displacements are measured from the mean plane of the deformed
  surface, and the pseudo-inverse maps the mean to 0.
"""
from __future__ import annotations

import math
import os

import numpy as np
import scipy.fft as sfft

#: FFT threads when VISCOSINE_FFT_THREADS is not set: both cores of the reference machine (the
#: transforms are most of the work; on two idle cores a 1024² pair takes 0.033 s, not 0.041 s)
WORKERS = 2
#: the environment variable that sets them: 1 where other processes already fill the cores
#: (the local process pools of viscosine's commands, the test processes), where a second
#: thread costs CPU (0.066 against 0.041 CPU s a 1024² pair) and gains no time
THREADS_VARIABLE = "VISCOSINE_FFT_THREADS"
#: rows of the symbol made at a time (its temporaries stay a few MB at any grid size)
_ROWS = 256


def fft_threads() -> int:
    """The FFT threads of a surface operator: ``$VISCOSINE_FFT_THREADS`` when it is a whole
    number >= 1, else `WORKERS`.  Read when an operator is made (a process pool's initializer
    sets it before any solve); the results are the same bit for bit on any number of threads.

    Raises
    ------
    ValueError
        ``VISCOSINE_FFT_THREADS`` set to anything but a whole number >= 1.
    """
    text = os.environ.get(THREADS_VARIABLE)
    if text is None:
        return WORKERS
    try:
        n = int(text)
    except ValueError:
        n = 0
    if n < 1:
        raise ValueError(f"{THREADS_VARIABLE}={text!r} is not allowed: a whole number >= 1")
    return n


def _wave_numbers(nx, ny, aspect):
    """(m along x as floats, n along y as floats over aspect) of the rfft2 half-spectrum."""
    m = np.fft.fftfreq(nx, 1.0 / nx)
    n = np.arange(ny // 2 + 1) / aspect
    return m, n


def surface_symbol(nx, ny, aspect, j_plus, terms, speed, direction, layer=None):
    """The symbol ``Chat`` of the steady-sliding operator on the (nx, ny) grid (module
    docstring), shape (nx, ny//2 + 1), complex; ``Chat[0, 0] = 0``.

    Parameters
    ----------
    nx, ny : int
        Panels along x and y (even, >= 4).
    aspect : float
        Ly/Lx.
    j_plus : float
        J(0+), in ``1/E_ref``.
    terms : tuple of (J_i, tau_i)
        The Prony terms (compliances in ``1/E_ref``, retardation times in ``tau_ref``).
    speed : float
        ``w = V tau_ref k``, >= 0.
    direction : float
        The sliding direction theta in radians.
    layer : bem.Layer, optional
        A layer on a rigid foundation (its factor S per mode); None for the half-space.
    """
    m, n = _wave_numbers(nx, ny, aspect)
    c, s = math.cos(direction), math.sin(direction)
    out = np.empty((nx, n.size), dtype=complex)

    def block(mm, nn):
        q = np.hypot(mm, nn)
        with np.errstate(divide="ignore", invalid="ignore"):
            inv = np.where(q > 0, 2.0 / np.where(q > 0, q, 1.0), 0.0)
        freq = (mm * c + nn * s) * speed
        js = np.full(freq.shape, j_plus, dtype=complex)
        for j_i, tau_i in terms:
            js += j_i / (1.0 - 1j * freq * tau_i)
        sym = inv * js
        if layer is not None:
            sym *= layer.factor(q)
        return sym

    for r0 in range(0, nx, _ROWS):
        mm = m[r0:r0 + _ROWS, None]
        out[r0:r0 + _ROWS] = block(mm, n[None, :])
    # Nyquist modes: the mean over the wave vectors of both signs
    if ny % 2 == 0:
        out[:, -1] = 0.5 * (block(m[:, None], n[None, -1:]) + block(m[:, None], -n[None, -1:]))[:, 0]
    if nx % 2 == 0:
        row = nx // 2
        mm = np.array([[m[row]], [-m[row]]])
        both = block(mm, n[None, :])
        if ny % 2 == 0:  # the corner: four wave vectors
            both[:, -1] = 0.5 * (block(mm, n[None, -1:]) + block(mm, -n[None, -1:]))[:, 0]
        out[row] = 0.5 * (both[0] + both[1])
    out[0, 0] = 0.0
    return out


class SpectralOperator:
    """``k u = C sigma`` and its pseudo-inverse on a surface grid, O(n log n) by rfft2.

    The interface of `bem._operator.CirculantOperator` on flattened fields (``apply``,
    ``pseudo_solve``, ``apply_on``, ``symbol``, ``max_inverse``, ``n``), so that one
    active-set solver (`bem._grid`) serves the line and the surface.
    """

    def __init__(self, symbol: np.ndarray, shape: tuple):
        self.shape = (int(shape[0]), int(shape[1]))
        self.n = self.shape[0] * self.shape[1]
        self.symbol = symbol
        mag = np.abs(symbol)
        mag[0, 0] = np.inf
        self.max_inverse = float(1.0 / np.min(mag))
        del mag
        self.transforms = 0  # rfft2 and irfft2 made (the cost the bench reports, in pairs)
        self.threads = fft_threads()

    def _through(self, f: np.ndarray, inverse: bool) -> np.ndarray:
        if inverse:
            f[0, 0] = 0.0
            f[1:, :] /= self.symbol[1:, :]
            f[0, 1:] /= self.symbol[0, 1:]
        else:
            f *= self.symbol
        out = sfft.irfft2(f, s=self.shape, axes=(0, 1), overwrite_x=True, workers=self.threads)
        self.transforms += 1
        return out.reshape(-1)

    def _forward(self, v: np.ndarray) -> np.ndarray:
        self.transforms += 1
        return sfft.rfft2(v.reshape(self.shape), axes=(0, 1), workers=self.threads)

    def apply(self, sigma: np.ndarray) -> np.ndarray:
        """k u = C sigma (flattened; mean of the result exactly 0)."""
        return self._through(self._forward(sigma), False)

    def pseudo_solve(self, v: np.ndarray) -> np.ndarray:
        """sigma with C sigma = v - mean(v) and mean(sigma) = 0."""
        return self._through(self._forward(v), True)

    def apply_on(self, idx: np.ndarray, values: np.ndarray, inverse: bool = False,
                 whole: bool = False):
        """``(C z)[idx]`` (or ``(C^+ z)[idx]``) for ``z`` equal to `values` on `idx` and zero
        elsewhere; ``whole``: on every panel (the caller gathers)."""
        z = np.zeros(self.n)
        z[idx] = values
        f = self._forward(z)
        del z
        out = self._through(f, inverse)
        del f
        return out if whole else out[idx]

    def spectrum(self, sigma: np.ndarray) -> np.ndarray:
        """rfft2 of a flattened field over the number of panels (the mode coefficients)."""
        return self._forward(sigma) / self.n
