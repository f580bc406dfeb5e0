"""The paper's figures 3–12 with both roads: semi-analytic lines, boundary-element markers.

Each ``fig…(ax, data)`` draws the numbers `comparisons.report_numbers` reads for that figure
(nondimensional: x/λ, v/h, p̃∞, Δ/h, V/V0, ka, ke, kê, μ; `docs/conventions.md`) and returns
``ax``; `write_figure` puts one on its own figure and writes it.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): figures 3–12.
"""
from __future__ import annotations

import math

import numpy as np

from . import kept_when_unchanged, pyplot, save


def _style(ax, xlabel, ylabel, title, logx=False):
    if logx:
        ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title, fontsize=10)
    ax.grid(True, alpha=0.3)
    return ax


def _colors(n):
    return pyplot().cm.viridis(np.linspace(0.0, 0.9, n))


def _profiles(ax, curves, title):
    for c, cur in zip(_colors(len(curves)), curves):
        ax.plot(cur["x"], cur["displacement"], color=c, lw=1.2, label=f"V/V0 = {cur['speed']:g}")
        bem = cur["bem"]
        if bem:
            step = max(1, len(bem["x"]) // 48)
            ax.plot(bem["x"][::step], bem["displacement"][::step], "o", ms=3, color=c, mfc="none")
    ax.invert_yaxis()  # displacement is positive into the body: draw the surface as seen
    _style(ax, "x/λ (crest at 0, sliding toward +x)", "v/h (into the body)", title)
    ax.legend(fontsize=7)
    return ax


def fig3a(ax, curves):
    """Deformed profile v/h for several V/V0 at p̃∞ = 0.3 (`report_numbers.profiles`)."""
    return _profiles(ax, curves, "Figure 3a: deformed profile at p̃∞ = 0.3")


def fig3b(ax, curves):
    """Deformed profile v/h for several V/V0 at Δ/h = 0.8 (`report_numbers.profiles`)."""
    return _profiles(ax, curves, "Figure 3b: deformed profile at Δ/h = 0.8")


def _load_sweep(ax, curves, ylabel, xlabel, title):
    for c, cur in zip(_colors(len(curves)), curves):
        ax.plot(cur["x"], cur["y"], color=c, lw=1.2, label=f"V/V0 = {cur['speed']:g}")
        ax.plot(cur["bem_x"], cur["bem_y"], "o", ms=4, color=c, mfc="none")
    _style(ax, xlabel, ylabel, title)
    ax.legend(fontsize=7)
    return ax


def fig4(ax, curves):
    """Δ/h against p̃∞ (`report_numbers.load_sweep`)."""
    return _load_sweep(ax, curves, "Δ/h", "p̃∞", "Figure 4: penetration against load")


def fig5(ax, curves):
    """ka against p̃∞ (`report_numbers.load_sweep`)."""
    return _load_sweep(ax, curves, "ka", "p̃∞", "Figure 5: contact half-width against load")


def fig6(ax, curves):
    """ka against Δ/h (`report_numbers.load_sweep`)."""
    return _load_sweep(ax, curves, "ka", "Δ/h", "Figure 6: contact half-width against penetration")


def fig7(ax, curves):
    """ka against V/V0 at fixed Δ/h (`report_numbers.ka_at_penetrations`)."""
    for c, cur in zip(_colors(len(curves)), curves):
        ax.plot(cur["speed"], cur["ka"], color=c, lw=1.2, label=f"Δ/h = {cur['penetration']:g}")
        ax.plot(cur["bem_speed"], cur["bem_ka"], "o", ms=4, color=c, mfc="none")
    _style(ax, "V/V0", "ka", "Figure 7: contact half-width against speed at fixed penetration",
           logx=True)
    ax.legend(fontsize=7)
    return ax


def fig8(ax, data):
    """The full-contact load p̃FC against V/V0 (`report_numbers.full_contact_loads`)."""
    ax.plot(data["speed"], data["load"], "k-", lw=1.2, label="semi-analytic |E(kV)| hk/(2E0)")
    ax.plot(data["bem_speed"], data["bem_load"], "o", ms=5, mfc="none", color="C3",
            label="BEM (p̃∞ − min σ at p̃∞ = 2)")
    for limit in data["limits"]:
        ax.axhline(limit, ls=":", color="0.5")
    _style(ax, "V/V0", "p̃FC", "Figure 8: full-contact load against speed", logx=True)
    ax.legend(fontsize=7)
    return ax


def _speed_sweep(ax, curves, ylabel, title):
    for c, cur in zip(_colors(len(curves)), curves):
        ax.plot(cur["speed"], cur["y"], color=c, lw=1.2, label=f"p̃∞ = {cur['load']:g}")
        ax.plot(cur["bem_speed"], cur["bem_y"], "o", ms=4, color=c, mfc="none")
    _style(ax, "V/V0", ylabel, title, logx=True)
    ax.legend(fontsize=7)
    return ax


def fig9(ax, curves):
    """ka against V/V0 across the transition (`report_numbers.speed_sweep`)."""
    return _speed_sweep(ax, curves, "ka", "Figure 9: contact half-width across the transition")


def _eccentricities(ax, data, title):
    ax.plot(data["speed"], data["ke"], "C0-", lw=1.2, label="ke")
    ax.plot(data["speed"], data["ke_hat"], "C3--", lw=1.2, label="kê")
    ax.plot(*data["bem_ke"], "o", ms=4, color="C0", mfc="none", label="BEM ke")
    ax.plot(*data["bem_ke_hat"], "s", ms=4, color="C3", mfc="none", label="BEM kê")
    if 0 < data["threshold"] < math.inf:
        ax.axvline(data["threshold"], ls=":", color="0.5")
    _style(ax, "V/V0", "ke, kê", title, logx=True)
    ax.legend(fontsize=7)
    return ax


def fig10(ax, data):
    """ke and kê against V/V0 at p̃∞ = 0.3 (`report_numbers.eccentricities`)."""
    return _eccentricities(ax, data, "Figure 10: eccentricities at p̃∞ = 0.3 (partial contact)")


def fig11(ax, data):
    """ke and kê against V/V0 at p̃∞ = 1.0 (`report_numbers.eccentricities`)."""
    return _eccentricities(ax, data, "Figure 11: eccentricities at p̃∞ = 1.0 (transition at the "
                                     "dotted line)")


def fig12(ax, curves):
    """μ against V/V0 (`report_numbers.speed_sweep`)."""
    return _speed_sweep(ax, curves, "μ", "Figure 12: friction coefficient against speed")


@kept_when_unchanged
def write_figure(path_png, draw, data):
    """``draw(ax, data)`` (one of the figures above) on a 6.4 × 4.4 in figure, written to
    ``path_png`` (110 dpi); returns the figure's title (the report's caption starts with it)."""
    fig, ax = pyplot().subplots(figsize=(6.4, 4.4))
    draw(ax, data)
    title = ax.get_title()
    save(fig, path_png, returned=title)  # kept in the PNG: a figure kept returns it too
    return title
