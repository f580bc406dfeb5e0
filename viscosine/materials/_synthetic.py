"""Measured-looking data made from a known material: the test set of the readers and fits.

Each generator takes a known relaxation series (`Maxwell`, the truth) and returns what a lab
would write: raw isotherms at several temperatures shifted by a known WLF (`isotherm_rows`),
E(t) or J(t) samples (`time_rows`), with multiplicative scatter of a given relative size from a
seeded generator.  The tests, ``bench --materials-fits`` and the tutorial judge every recovered
quantity against the truth these were made from.
"""
from __future__ import annotations

import math

import numpy as np

from ._series import Maxwell
from ._temperature import WLF


def lognormal_series(E_r, ratio, *, centre=0.0, width=2.5, decades=14.0, per_decade=2.0):
    """A relaxation series of glassy/relaxed modulus ``ratio``: times log-spaced over
    ``decades`` around ``10**centre`` with log-normal amplitudes of ``width`` decades."""
    n = int(round(decades * per_decade)) + 1
    u = np.linspace(-0.5, 0.5, n) * decades
    theta = 10.0 ** (centre + u)
    w = np.exp(-0.5 * (u / width) ** 2)
    amps = w / w.sum() * E_r * (ratio - 1.0)
    return Maxwell(float(E_r), tuple(amps.tolist()), tuple(theta.tolist()))


def isotherm_rows(model: Maxwell, wlf: WLF, temperatures, frequencies_hz, *, noise=0.0,
                  seed=0, kelvin_offset=None):
    """Rows ``(T, f [Hz], E', E'')`` of raw sweeps of ``model`` (the master curve at
    ``wlf.T_ref``): at T the modulus is ``E*(2 pi f a_T)``, times ``1/b_T`` when
    ``kelvin_offset`` is given (``b_T = T0/T`` in kelvin, T + offset), each value times
    ``exp(noise N(0, 1))``."""
    rng = np.random.default_rng(seed)
    f = np.asarray(frequencies_hz, float)
    rows = []
    for T in temperatures:
        a = float(wlf.a_T(T))
        e = model.modulus(2.0 * math.pi * f * a)
        scale = 1.0
        if kelvin_offset is not None:
            scale = (T + kelvin_offset) / (wlf.T_ref + kelvin_offset)  # 1/b_T
        e1 = e.real * scale * np.exp(noise * rng.standard_normal(f.size))
        e2 = e.imag * scale * np.exp(noise * rng.standard_normal(f.size))
        rows += [(float(T), float(fi), float(a1), float(a2)) for fi, a1, a2 in zip(f, e1, e2)]
    return rows


def time_rows(model: Maxwell, times, *, kind="relaxation", noise=0.0, seed=0):
    """Rows ``(t, E(t))`` or ``(t, J(t))`` of ``model`` with multiplicative scatter."""
    rng = np.random.default_rng(seed)
    t = np.asarray(times, float)
    if kind == "relaxation":
        y = model.relaxation(t)
    else:
        c = model.creep()
        y = np.full(t.shape, c.J0)
        for j, tau in zip(c.J, c.tau):
            y = y - j * np.exp(-t / tau)
    y = y * np.exp(noise * rng.standard_normal(t.size))
    return [(float(a), float(b)) for a, b in zip(t, y)]
