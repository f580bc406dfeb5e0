"""A viscoelastic layer of finite thickness on a rigid foundation (the report's layer section).

Each figure draws the numbers `comparisons.report_numbers` reads for it (nondimensional:
V/V0, μ, 2a/λ, d/λ, p̃FC; `docs/conventions.md`, `docs/layers.md`) with one panel per foundation
(bonded, frictionless), and is written by its ``write_…`` function:

- `write_friction`: μ against V/V0 per thickness (`report_numbers.layer_sweeps`);
- `write_contact`: the contact fraction 2a/λ against V/V0, the same runs;
- `write_full_contact`: the full-contact load p̃FC against d/λ per speed, closed form and BEM
  (`report_numbers.layer_full_contact`).
"""
from __future__ import annotations

import numpy as np

from . import kept_when_unchanged, pyplot, save

FOUNDATIONS = ("bonded", "frictionless")


def _label(d):
    return "half-space" if d is None else f"d/λ = {d:g}"


def _colors(n):
    return pyplot().cm.viridis(np.linspace(0.0, 0.85, n))


def _sweep_panel(ax, data, foundation, key, ylabel):
    """One foundation's curves of ``key`` (``"mu"`` or ``"contact_fraction"``) against V/V0:
    the layers as lines through the BEM's points, the half-space as the BEM's circles on the
    semi-analytic line."""
    layers = [c for c in data["curves"][foundation] if c["d_over_lambda"] is not None]
    for col, c in zip(_colors(len(layers)), layers):
        ax.plot(c["speed"], c[key], "-", marker=".", ms=3, lw=1.2, color=col,
                label=_label(c["d_over_lambda"]))
    half = next(c for c in data["curves"][foundation] if c["d_over_lambda"] is None)
    ax.plot(data["analytic"]["speed"], data["analytic"][key], "k-", lw=0.8,
            label="half-space, semi-analytic")
    ax.plot(half["speed"], half[key], "o", ms=4, mfc="none", color="k",
            label="half-space, BEM")
    ax.set_xscale("log")
    ax.set_xlabel("V/V0")
    ax.set_ylabel(ylabel)
    nu = (f"ν = {data['nu']:g}" if foundation == "bonded" else
          f"ν = {data['nu']:g} (any ν: the same answer)")
    ax.set_title(f"{foundation} foundation, {nu}", fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def plot_friction(fig, data):
    """μ against V/V0 at p̃∞ = ``data["load"]``, one panel per foundation."""
    axes = fig.subplots(1, 2, sharey=True)
    for ax, f in zip(axes, FOUNDATIONS):
        _sweep_panel(ax, data, f, "mu", "μ")
    fig.suptitle(f"Friction on a layer of thickness d, p̃∞ = {data['load']:g}", fontsize=10)
    return fig


def plot_contact(fig, data):
    """The contact fraction 2a/λ against V/V0 at p̃∞ = ``data["load"]``, one panel per
    foundation."""
    axes = fig.subplots(1, 2, sharey=True)
    for ax, f in zip(axes, FOUNDATIONS):
        _sweep_panel(ax, data, f, "contact_fraction", "2a/λ")
    fig.suptitle(f"Contact fraction on a layer of thickness d, p̃∞ = {data['load']:g}",
                 fontsize=10)
    return fig


def plot_full_contact(fig, data):
    """p̃FC against d/λ, one curve per speed (solid where at the report's hk the indenter's crest
    clears the foundation in full contact, dotted where it would reach it), the half-space's value
    dashed; BEM markers: crosses at the small amplitude scaled to hk, circles at the report's
    hk."""
    axes = fig.subplots(1, 2, sharey=True)
    x = np.asarray(data["d_over_lambda"], float)
    for ax, f in zip(axes, FOUNDATIONS):
        curves = data["curves"][f]
        for col, c in zip(_colors(len(curves)), curves):
            y = np.asarray(c["load"], float)
            ok = np.asarray(c["clears"], bool)
            ax.plot(x, np.where(ok, y, np.nan), "-", color=col, lw=1.3,
                    label=f"V/V0 = {c['speed']:g}")
            ax.plot(x, np.where(ok, np.nan, y), ":", color=col, lw=1.3)
            ax.axhline(c["half_space"], ls="--", lw=0.7, color=col)
            m = [q for q in c["markers"] if q["bem"] is not None]
            ax.plot([q["d_over_lambda"] for q in m], [q["bem"] for q in m], "x", ms=6,
                    color=col)
            m1 = [q for q in c["markers"] if q["bem_hk1"] is not None]
            ax.plot([q["d_over_lambda"] for q in m1], [q["bem_hk1"] for q in m1], "o", ms=8,
                    mfc="none", color=col)
        ax.plot([], [], "kx", label="BEM, Δ/h = 1 at small hk, scaled")
        if any(q["bem_hk1"] is not None for c in curves for q in c["markers"]):
            ax.plot([], [], "ko", mfc="none", label="BEM, Δ/h = 1 at hk = 1")
        ax.plot([], [], "k:", label="at hk = 1 the crest would reach the foundation")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("d/λ")
        ax.set_ylabel("p̃FC/hk (= p̃FC at hk = 1)")
        ax.set_title(f"{f} foundation", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle("Full-contact load against thickness (dashed: the half-space)", fontsize=10)
    return fig


def _write(path_png, draw, data):
    fig = pyplot().figure(figsize=(11.0, 4.4))
    draw(fig, data)
    return save(fig, path_png)


@kept_when_unchanged
def write_friction(path_png, data):
    """`plot_friction` on an 11 × 4.4 in figure, written to ``path_png``."""
    return _write(path_png, plot_friction, data)


@kept_when_unchanged
def write_contact(path_png, data):
    """`plot_contact` on an 11 × 4.4 in figure, written to ``path_png``."""
    return _write(path_png, plot_contact, data)


@kept_when_unchanged
def write_full_contact(path_png, data):
    """`plot_full_contact` on an 11 × 4.4 in figure, written to ``path_png``."""
    return _write(path_png, plot_full_contact, data)
