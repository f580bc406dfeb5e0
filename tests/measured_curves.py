"""Realistic measured DMA master curves built from a known Prony material (the test set of
tests/viscosine/test_materials_measured.py).

A master curve is measured as frequency sweeps at several temperatures, each shifted by its a_T
onto the reference temperature.  Every sweep here covers `SWEEP_DECADES` decades, consecutive
sweeps overlap by `OVERLAP` decades, and each carries its own multiplicative error (the sample's
clamping, thermal drift: ``bias`` on E' and E'') on top of point-to-point scatter (``noise``).
Where two sweeps overlap, E' therefore drops between neighbouring points by up to about twice the
bias, and some frequencies are measured twice.  The truth each curve was built from is returned
with it, so that a fit can be judged against the material rather than against the data.
"""
from __future__ import annotations

import math

import numpy as np

from viscosine.materials import Maxwell

SWEEP_DECADES = 2.0
OVERLAP = 0.5
POINTS_PER_DECADE = 6


def rubber(E_r=3.0, glassy=3000.0, centre=-5.0, width=2.2, per_decade=2.0, span=(-11.0, 3.0)):
    """A filled-rubber-like relaxation series [MPa, s]: amplitudes a log-normal bump in the
    relaxation time around 10**centre s, summing to ``glassy - E_r``."""
    logt = np.arange(span[0], span[1] + 1e-9, 1.0 / per_decade)
    amp = np.exp(-0.5 * ((logt - centre) / width) ** 2)
    amp *= (glassy - E_r) / amp.sum()
    return Maxwell(E_r, tuple(amp.tolist()), tuple((10.0 ** logt).tolist()))


def sweeps(decades=(-3.0, 7.0)):
    """Frequencies [Hz] of the shifted sweeps covering ``decades`` (log10 Hz), with the sweep
    each belongs to; consecutive sweeps overlap by `OVERLAP` decades."""
    lo, hi = decades
    # a_T are not multiples of the sweep's step: overlapping sweeps interleave
    starts = lo + np.arange(0, hi - lo - SWEEP_DECADES + 1e-9, SWEEP_DECADES - OVERLAP + 0.029)
    if starts[-1] + SWEEP_DECADES < hi:
        starts = np.append(starts, hi - SWEEP_DECADES)
    f, which = [], []
    for k, s in enumerate(starts):
        n = int(round(SWEEP_DECADES * POINTS_PER_DECADE)) + 1
        f.append(np.logspace(s, s + SWEEP_DECADES, n))
        which.append(np.full(n, k))
    return np.concatenate(f), np.concatenate(which)


def measure(truth, *, seed=0, noise=0.005, bias=0.02, decades=(-3.0, 7.0), loss_factor=None,
            duplicates=0, duplicate_spread=0.05):
    """A measured master curve of ``truth``: ``(f [Hz], E' , E'')`` in the truth's unit.

    Parameters
    ----------
    noise : float
        Relative point-to-point scatter (normal, on E' and E'' independently).
    bias : float
        Each sweep's E' and E'' multiplied by ``1 + b`` with b uniform in [-bias, bias].
    loss_factor : callable, optional
        ``g(f)``: the measured E'' is ``g(f)`` times the material's (data that are not
        Kramers-Kronig consistent).
    duplicates : int
        Frequencies measured again by the neighbouring sweep at the same frequency (ratio
        ``1 + 4e-15``), E' and E'' ``duplicate_spread`` apart.
    """
    rng = np.random.default_rng(seed)
    f, which = sweeps(decades)
    e = truth.modulus(2.0 * math.pi * f)
    b = rng.uniform(-bias, bias, which.max() + 1)[which]
    e1 = e.real * (1.0 + b) * (1.0 + noise * rng.standard_normal(f.size))
    e2 = e.imag * (1.0 + b) * (1.0 + noise * rng.standard_normal(f.size))
    if loss_factor is not None:
        e2 = e2 * loss_factor(f)
    if duplicates:
        pick = rng.choice(np.arange(2, f.size - 2), duplicates, replace=False)
        f = np.concatenate([f, f[pick] * (1.0 + 4e-15)])
        e1 = np.concatenate([e1, e1[pick] * (1.0 + duplicate_spread)])
        e2 = np.concatenate([e2, e2[pick] * (1.0 + duplicate_spread)])
    return f, e1, e2


def write(path, f, e1, e2, *, layout="lab", order="decreasing"):
    """Write a curve as a lab would: ``layout`` "lab" (two header rows, names then units, ';'
    separators, decimal commas, MPa and Hz), "tab" (E_stor/E_loss [MPa] in brackets, tabs),
    "plain" (comma separated, one header row) or "shear-kpa" (G', G'' in kPa, blanks)."""
    order_idx = np.argsort(f)
    if order == "decreasing":
        order_idx = order_idx[::-1]
    elif order == "shuffled":
        order_idx = np.random.default_rng(1).permutation(f.size)
    rows = [(f[j], e1[j], e2[j]) for j in order_idx]
    if layout == "lab":
        head = "Frequency;E';E'';tan delta\nHz;MPa;MPa;-\n"
        body = "".join(f"{a:.6e};{b:.6e};{c:.6e};{c / b:.5f}\n".replace(".", ",")
                       for a, b, c in rows)
    elif layout == "tab":
        head = "# exported master curve, T_ref = 20 °C\nf [Hz]\tE_stor [MPa]\tE_loss [MPa]\n"
        body = "".join(f"{a:.6e}\t{b:.6e}\t{c:.6e}\n" for a, b, c in rows)
    elif layout == "plain":
        head = "frequency [Hz],storage [MPa],loss [MPa]\n"
        body = "".join(f"{float(a)!r},{float(b)!r},{float(c)!r}\n" for a, b, c in rows)
    elif layout == "shear-kpa":        # tensile data written as shear moduli with nu = 0.5
        head = "omega G' G''\nrad/s kPa kPa\n"
        body = "".join(f"{2 * math.pi * a:.8e} {b * 1e3 / 3:.8e} {c * 1e3 / 3:.8e}\n"
                       for a, b, c in rows)
    else:
        raise ValueError(layout)
    pathlib_write(path, head + body)
    return path


def pathlib_write(path, text):
    with open(path, "w", encoding="utf-8", newline="\n") as fh:
        fh.write(text)


def transition_and_tail(f, *, transition=1.3, tail=6.0, f_tail=1.0):
    """A loss factor for inconsistent data: ``transition`` in the glass transition, rising to
    ``tail`` in the low-frequency tail below ``f_tail`` Hz (the shape the measured curves of the
    user report show: E'' 1.15-1.5 x in the transition, 3-17 x in the tail)."""
    x = np.clip(np.log10(f_tail / np.asarray(f)), 0.0, None)
    return transition + (tail - transition) * (1.0 - np.exp(-x))
