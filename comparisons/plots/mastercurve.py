"""The friction master curve's figure: μ against V, one curve per temperature, and against the
reduced speed a_T V (`comparisons.mastercurve`; hollow markers: the modulus was extrapolated
beyond the DMA window)."""
from __future__ import annotations

import os

from . import kept_when_unchanged, pyplot, save


def plot(table, *, axes=None, title=None):
    """μ against V (one curve per temperature) and against the reduced speed a_T V.

    Parameters
    ----------
    table : comparisons.mastercurve.FrictionMasterCurve
    axes : (Axes, Axes), optional
        Where to draw; a new figure when None.

    Returns
    -------
    (ax_speed, ax_reduced)
    """
    if axes is None:
        _, axes = pyplot().subplots(1, 2, figsize=(11.0, 4.4), sharey=True)
    ax, axr = axes
    temps = list(dict.fromkeys(table.temperature.tolist()))
    for i, T in enumerate(temps):
        sel = (table.temperature == T) & table.success
        color = f"C{i % 10}"
        for a, x in ((ax, table.speed), (axr, table.reduced_speed)):
            a.plot(x[sel], table.mu[sel], "-", color=color, lw=1.2, label=f"T = {T:g}")
            inside = sel & ~table.extrapolated
            out = sel & table.extrapolated
            a.plot(x[inside], table.mu[inside], "o", color=color, ms=3.5)
            a.plot(x[out], table.mu[out], "o", color=color, ms=4.0, mfc="none")
    for a, label in ((ax, "V (m/s)"), (axr, "a_T V (m/s), the speed at T_ref")):
        a.set_xscale("log")
        a.set_xlabel(label)
        a.grid(True, which="both", alpha=0.25)
    ax.set_ylabel("μ = τf/p∞")
    ax.legend(fontsize=7, title="hollow: modulus extrapolated", title_fontsize=7)
    if title is None:
        p = table.parameters
        m = p["material"]
        fit = m.get("fit") or {}
        title = (f"{os.path.basename(m.get('path') or 'material')} ({m['form']}"
                 + (f", fit max residual {100 * fit['max_residual']:.2g} %" if fit else "")
                 + f"); p∞ = {p['mean_pressure']:g} Pa, λ = {p['wavelength']:g} m, "
                 f"h = {p['amplitude']:g} m, ν = {p['nu']:g}; "
                 + (f"N = {p['nodes']}" if p["nodes"] else f"rtol = {p['rtol']:g}"))
    ax.figure.suptitle(title, fontsize=8)
    return ax, axr


@kept_when_unchanged
def write_figure(path_png, table):
    """`plot` written to ``path_png`` (Agg, 110 dpi)."""
    fig, axes = pyplot().subplots(1, 2, figsize=(11.0, 4.4), sharey=True)
    plot(table, axes=axes)
    return save(fig, path_png)
