"""The third code's figure: the error of Tamaas's μ against the semi-analytic road as its time
step is halved (`comparisons.peers.tamaas`; the report's Tamaas section)."""
from __future__ import annotations

import numpy as np

from . import kept_when_unchanged, pyplot, save


def plot_dt_convergence(ax, data):
    """Relative error of Tamaas's μ against the semi-analytic road, against dt/T.

    Parameters
    ----------
    ax : matplotlib Axes
    data : dict
        The output of `comparisons.peers.tamaas.third_code_table` (or the report's
        `tamaas_study`, of the same shape).

    Returns
    -------
    ax
        Markers: each dt; dashed: the Richardson value's error; dotted: slope 1.
    """
    for i, s in enumerate(data["summary"]):
        colour = f"C{i}"
        x = np.asarray(s["dt_over_period"])
        y = np.abs(np.asarray(s["mu_per_dt"]) / s["mu_analytic"] - 1.0)
        ax.loglog(x, y, "o-", color=colour, label=f"V/V0 = {s['speed']:.3g}")
        if s["relative_difference"] is not None:
            ax.axhline(abs(s["relative_difference"]), color=colour, ls="--", lw=0.8)
    first = data["summary"][0]
    x = np.asarray(first["dt_over_period"])
    y0 = abs(first["mu_per_dt"][0] / first["mu_analytic"] - 1.0)
    ax.loglog(x, 0.5 * y0 * x / x[0], ":", color="0.4", label="slope 1")
    inp = data["inputs"]
    ax.set_xlabel("dt / T (time step over the period transit time)")
    ax.set_ylabel("|μ_Tamaas / μ_analytic − 1|")
    ax.set_title(f"Tamaas (backward Euler) against the semi-analytic road\np̃∞ = "
                 f"{inp['load']:g}, E∞/E0 = {inp['ratio']:g}, hk = {inp['hk']:g}, "
                 f"N = {inp['nodes']}; dashed: Richardson", fontsize=9)
    ax.legend(fontsize=8)
    return ax


@kept_when_unchanged
def write_figure(path_png, data):
    """`plot_dt_convergence` written to ``path_png`` (6.4 × 4.4 in, 110 dpi); returns the path."""
    fig, ax = pyplot().subplots(figsize=(6.4, 4.4))
    plot_dt_convergence(ax, data)
    return save(fig, path_png)
