"""The benchmark suite's inputs: the folder they are in, a case's indenter evaluated anywhere, and
the generators of the synthetic profiles and materials the suite ships.

Heights are k·y at x/λ (units of :mod:`bem`); compliances in 1/E_ref, times in τ_ref (creep
series, the format of :func:`bem.read_prony`) or moduli in E_ref and relaxation times
(relaxation series, :func:`viscosine.materials.read_relaxation`).  The shipped files under
``DATA`` name the generator and arguments that made them (``comparisons.suite`` exposes the
generators under the names those files give).
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from . import operating_point as op
from . import roads as _roads

#: the suite's data: ``suite.json``, ``profiles/``, ``materials/``, ``fields/``
DATA = Path(__file__).resolve().parent / "data" / "suite"


# ------------------------------------------------------------------------------ a case's indenter
class ProfileShape:
    """k·y of the indenter as a trigonometric series, evaluated anywhere (units of :mod:`bem`).

    Built from the operating point: ``hk`` (sinusoid) or the samples of a profile file (their
    trigonometric interpolant, as :class:`bem.SampledProfile`).  Used for the summit of each
    contact patch and, in :mod:`comparisons.verify`, for the slope in the friction integral.
    """

    def __init__(self, point, base=DATA):
        if point.get("profile"):
            prof = _roads.read_profile(Path(base) / point["profile"])
            y = np.asarray(prof.heights, float)
            m = y.size
            f = np.fft.rfft(y) / m
            c = 2.0 * f[1:]
            if m % 2 == 0:
                c[-1] = f[-1]
            self.n = np.arange(1, f.size, dtype=float)
            self.c = c * np.exp(1j * np.pi * self.n)  # samples start at X = −1/2
            self.sinusoid = False
        else:
            self.n = np.array([1.0])
            self.c = np.array([op.hk_of(point) + 0j])
            self.sinusoid = True
        self.amplitude = float(self.max_value())

    def __call__(self, x, der=0):
        """d^der(k y)/dX^der at X = x (X = x/λ, crest of the sinusoid at 0; mean removed)."""
        x = np.atleast_1d(np.asarray(x, float))
        out = np.zeros(x.shape)
        for lo in range(0, self.n.size, 64):  # blocks keep the phase matrix small
            n = self.n[lo:lo + 64]
            c = self.c[lo:lo + 64] * (2j * np.pi * n) ** der
            out += (np.exp(2j * np.pi * np.outer(x, n)) @ c).real
        return out

    def _newton_max(self, x, lo=-math.inf, hi=math.inf):
        for _ in range(60):
            d1, d2 = float(self(x, 1)[0]), float(self(x, 2)[0])
            if d2 >= 0.0:
                break
            step = -d1 / d2
            x = min(max(x + step, lo), hi)
            if abs(step) < 1e-15:
                break
        return x

    def max_value(self):
        xs = np.arange(4096) / 4096 - 0.5
        ys = self(xs)
        j = int(np.argmax(ys))
        return float(self(self._newton_max(float(xs[j])))[0])

    def summit(self, trailing, leading):
        """X of the highest profile point in [trailing, leading] (sub-1e-13 by Newton)."""
        if self.sinusoid:
            return float(round((0.5 * (trailing + leading))))  # the crest at an integer X
        xs = np.linspace(trailing, leading, 2049)
        j = int(np.argmax(self(xs)))
        return self._newton_max(float(xs[j]), trailing, leading)


# ------------------------------------------------------------------------------ generated inputs
SELF_AFFINE = {"seed": 20140392, "samples": 256, "modes": 16, "hurst": 0.8}


def self_affine_heights(seed=20140392, samples=256, modes=16, hurst=0.8):
    """A self-affine periodic profile k·y at x/λ = j/samples − 1/2 (deterministic).

    Modes n = 1..modes with amplitudes n^−(1+H) (power spectrum ∝ q^−2(1+H), Hurst exponent H)
    and phases uniform in [0, 2π) from ``numpy.random.default_rng(seed)``; scaled so that the
    highest of 2^16 evenly spaced points of the series is 1 above its mean.  ``samples`` > 2 modes,
    so the samples' trigonometric interpolant is the series itself.
    """
    rng = np.random.default_rng(seed)
    n = np.arange(1, modes + 1, dtype=float)
    amp = n ** -(1.0 + hurst)
    phase = rng.uniform(0.0, 2.0 * np.pi, modes)

    def series(x):
        return np.cos(2.0 * np.pi * np.outer(x, n) + phase) @ amp

    scale = float(np.max(series(np.arange(1 << 16) / (1 << 16) - 0.5)))
    return series(np.arange(samples) / samples - 0.5) / scale


def harmonic_heights(amplitudes, phases, samples=64):
    """k·y = Σ a_n cos(2π n x/λ + φ_n) at x/λ = j/samples − 1/2 (exact for n < samples/2)."""
    x = np.arange(samples) / samples - 0.5
    n = np.arange(1, len(amplitudes) + 1, dtype=float)
    phase = np.asarray(phases, float)
    return np.cos(2.0 * np.pi * np.outer(x, n) + phase) @ np.asarray(amplitudes, float)


#: the generated broad spectra of the suite's Fourier-referenced cases (materials/*.txt): decades
#: are (log10 of the shortest, of the longest) time, ratio is E∞/E0 = J0/J(0+) = E(0+)/E_r
BROAD24 = {"terms": 24, "decades": (-6.0, 6.0), "ratio": 1000.0}
LOGNORMAL32 = {"terms": 32, "decades": (-5.0, 5.0), "ratio": 100.0, "width": 2.0}
RELAX16 = {"terms": 16, "decades": (-4.0, 4.0), "ratio": 300.0}


def creep_spectrum(terms, decades, ratio, width=None):
    """A creep series (J0 = 1, J_i, τ_i) of E∞/E0 = ``ratio`` (deterministic).

    ``terms`` retardation times ``τ_i = 10**linspace(decades[0], decades[1], terms)``; amplitudes
    equal (a box spectrum, ``width`` None) or log-normal in τ (weights
    ``exp(−½ ((log10 τ_i − centre)/width)²)``, centre the middle decade), scaled so that
    ``Σ J_i = 1 − 1/ratio`` (J(0+) = 1/ratio).
    """
    lo, hi = decades
    tau = 10.0 ** np.linspace(lo, hi, terms)
    if width is None:
        wgt = np.ones(terms)
    else:
        wgt = np.exp(-0.5 * ((np.log10(tau) - 0.5 * (lo + hi)) / width) ** 2)
    amps = wgt / wgt.sum() * (1.0 - 1.0 / ratio)
    return 1.0, tuple(float(a) for a in amps), tuple(float(t) for t in tau)


def relaxation_spectrum(terms, decades, ratio):
    """A relaxation series (E_r = 1, E_i, θ_i) of E∞/E0 = ``ratio``: ``terms`` equal moduli
    ``E_i = (ratio − 1)/terms`` at relaxation times ``θ_i = 10**linspace(*decades, terms)``."""
    theta = 10.0 ** np.linspace(decades[0], decades[1], terms)
    return 1.0, tuple((ratio - 1.0) / terms for _ in theta), tuple(float(t) for t in theta)
