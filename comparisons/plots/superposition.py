"""The shift figure of raw isotherms: log10 a_T against T with the fitted WLF, and the WLF residual.

Inputs are the record's ``superposition`` (`viscosine.materials.Superposition.as_dict`): the
shift of each isotherm with its standard error, the WLF constants and the range where they hold
(shaded), Arrhenius below when fitted.  a_T multiplies times: a_T < 1 above T_ref.
"""
from __future__ import annotations

import math

import numpy as np

from . import kept_when_unchanged, pyplot, save


def plot_shifts(sp, ax=None):
    """log10 a_T (points with 2-sigma bars) and WLF (line) against T; returns ax."""
    if ax is None:
        ax = pyplot().subplots()[1]
    t = np.array([s["temperature"] for s in sp["shifts"]])
    y = np.array([s["log10_aT"] for s in sp["shifts"]])
    e = np.array([s["log10_aT_error"] for s in sp["shifts"]])
    w = sp["wlf"]
    tt = np.linspace(max(t.min(), w["T_ref"] - w["C2"] + 1e-6 * w["C2"]), t.max(), 200)
    dt = tt - w["T_ref"]
    ax.errorbar(t, y, yerr=2 * e, fmt="o", ms=4, capsize=2, label="shifts from the data (±2σ)")
    ax.plot(tt, -w["C1"] * dt / (w["C2"] + dt), "-",
            label=f"WLF C1 = {w['C1']:.3g}, C2 = {w['C2']:.3g}, T_ref = {w['T_ref']:g}")
    ax.axvspan(w["holds"][0], w["holds"][1], color="0.9", zorder=0, label="WLF holds")
    a = sp.get("arrhenius")
    if a is not None:
        u = sp.get("temperature_unit") or ""
        off = {"degC": 273.15, "K": 0.0}.get(u)
        if off is not None:
            ta = np.linspace(a["range"][0], a["range"][1], 50)
            ax.plot(ta, a["A"] + a["B"] / (ta + off), "--",
                    label=f"Arrhenius Ea = {a['activation_energy'] / 1e3:.3g} kJ/mol")
    u = sp.get("temperature_unit") or ""
    ax.set_xlabel(f"T [{u}]" if u else "T")
    ax.set_ylabel("log10 a_T")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return ax


def plot_wlf_residual(sp, ax=None):
    """The shifts minus WLF, with the 3-sigma band of each shift; returns ax."""
    if ax is None:
        ax = pyplot().subplots()[1]
    t = np.array([s["temperature"] for s in sp["shifts"]])
    e = np.array([s["log10_aT_error"] for s in sp["shifts"]])
    r = np.array([math.nan if v is None else v for v in sp["wlf"]["residuals"]], dtype=float)
    ax.fill_between(t, -3 * e, 3 * e, color="0.85", label="±3σ of the shift")
    ax.plot(t, r, "o-", ms=3, label="shift − WLF")
    ax.axhline(0.0, color="k", lw=0.5)
    ax.set_xlabel("T")
    ax.set_ylabel("decades")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return ax


@kept_when_unchanged
def shifts_figure(path_png, sp, *, title=None):
    """`plot_shifts` above `plot_wlf_residual`, written to ``path_png``; returns the path."""
    fig, (ax, rax) = pyplot().subplots(2, 1, figsize=(6.5, 6.0), sharex=True,
                                       gridspec_kw={"height_ratios": [2.2, 1.0]})
    plot_shifts(sp, ax=ax)
    if title:
        ax.set_title(title, fontsize=9)
    plot_wlf_residual(sp, ax=rax)
    return save(fig, path_png)
