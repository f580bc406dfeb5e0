"""A rigid periodic surface sliding over the half-space (the report's surface section).

Each figure draws numbers `comparisons.report_surfaces` reads from the results store
(nondimensional: positions over Lx, σ(1 − ν²)/E0, V/V0 = Vτk with k = 2π/Lx; `docs/surfaces.md`):

- `write_pressure_map`: σ on the cell with the contact outline and the sliding direction;
- `write_friction`: μ against V/V0 for several loads (bi-sinusoid);
- `write_direction`: μ and the lateral coefficient against the sliding direction θ
  (anisotropic bi-sinusoid);
- `write_persson`: μ and the contact fraction against V/V0 on self-affine surfaces, the BEM
  (mean and spread over seeds) beside Persson's theory.
"""
from __future__ import annotations

import math

import numpy as np

from . import kept_when_unchanged, pyplot, save


@kept_when_unchanged
def write_pressure_map(path, fields, direction, caption=""):
    """σ on the cell (colour), the contact outline (σ > 0, white) and an arrow along V."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.4, 4.6))
    x, y, p = fields["x"], fields["y"], fields["pressure"]
    dx, dy = x[1] - x[0], y[1] - y[0]
    ext = (x[0] - dx / 2, x[-1] + dx / 2, y[0] - dy / 2, y[-1] + dy / 2)
    im = ax.imshow(p.T, origin="lower", extent=ext, cmap="magma", aspect="equal")
    ax.contour(x, y, (p > 0).T.astype(float), levels=[0.5], colors="w", linewidths=0.8)
    t = math.radians(direction)
    ax.annotate("", xy=(0.3 * math.cos(t), 0.3 * math.sin(t)), xytext=(0.0, 0.0),
                arrowprops={"arrowstyle": "->", "color": "c", "lw": 2})
    ax.text(0.32 * math.cos(t), 0.32 * math.sin(t), "V", color="c")
    ax.set_xlabel("x / Lx")
    ax.set_ylabel("y / Lx")
    fig.colorbar(im, ax=ax, label="σ (1 − ν²)/E0")
    if caption:
        ax.set_title(caption, fontsize=8)
    return save(fig, path)


@kept_when_unchanged
def write_friction(path, curves):
    """μ against V/V0, one line per load: ``curves`` = [{"load", "speed", "mu"}, ...]."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    cols = plt.cm.viridis(np.linspace(0.0, 0.85, len(curves)))
    for c, col in zip(curves, cols):
        ax.plot(c["speed"], c["mu"], "o-", ms=3, lw=1.2, color=col, label=f"p̃∞ = {c['load']:g}")
    ax.set_xscale("log")
    ax.set_xlabel("V/V0")
    ax.set_ylabel("μ")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save(fig, path)


@kept_when_unchanged
def write_direction(path, data):
    """μ and the lateral coefficient against θ: ``data`` = {"direction", "mu", "mu_lateral"}."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(5.6, 3.8))
    ax.plot(data["direction"], data["mu"], "o-", ms=3, label="μ (along V)")
    ax.plot(data["direction"], data["mu_lateral"], "s-", ms=3, label="lateral (left of V)")
    ax.axhline(0.0, color="k", lw=0.6)
    ax.set_xlabel("θ [degrees]")
    ax.set_ylabel("force / load")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return save(fig, path)


@kept_when_unchanged
def write_persson(path, curves):
    """μ (left) and the contact fraction (right) against V/V0 per load: the BEM's mean over
    seeds with its spread (bars: min … max), Persson's theory as lines.  ``curves`` =
    [{"load", "speed", "mu_mean", "mu_min", "mu_max", "cf_mean", "cf_min", "cf_max",
    "persson_mu", "persson_cf"}, ...]."""
    plt = pyplot()
    fig, axes = plt.subplots(1, 2, figsize=(9.0, 3.8))
    cols = plt.cm.viridis(np.linspace(0.0, 0.85, len(curves)))
    for c, col in zip(curves, cols):
        s = np.asarray(c["speed"])
        for ax, key, pkey in ((axes[0], "mu", "persson_mu"), (axes[1], "cf", "persson_cf")):
            m = np.asarray(c[key + "_mean"])
            err = [m - np.asarray(c[key + "_min"]), np.asarray(c[key + "_max"]) - m]
            ax.errorbar(s, m, yerr=err, fmt="o", ms=3, color=col, capsize=2,
                        label=f"BEM, p̃∞ = {c['load']:g}")
            ax.plot(s, c[pkey], "-", color=col, lw=1.2, label=f"Persson, p̃∞ = {c['load']:g}")
    for ax, lab in zip(axes, ("μ", "contact fraction")):
        ax.set_xscale("log")
        ax.set_xlabel("V/V0")
        ax.set_ylabel(lab)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    return save(fig, path)
