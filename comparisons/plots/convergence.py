"""The BEM's convergence by mesh refinement: its error against the semi-analytic solution
against N (panels per period), with the observed orders (`comparisons.report_numbers`)."""
from __future__ import annotations

import numpy as np

from . import kept_when_unchanged, pyplot, save


def plot_convergence(fig, conv):
    """One panel per convergence point: the BEM's errors against N on log–log axes, each
    labelled with its observed order, and the slopes N⁻¹ (dotted) and N⁻² (dashed).

    Parameters
    ----------
    fig : matplotlib Figure
    conv : list of dict
        `comparisons.report_numbers.convergence`'s output.

    Returns
    -------
    fig
    """
    axes = fig.subplots(1, len(conv))
    for ax, c in zip(np.atleast_1d(axes), conv):
        N = np.array(c["data"]["N"], float)
        for k, m in zip(("ka", "ke", "penetration", "mu", "pressure"), "os^dv"):
            e = np.array(c["data"][k], float)
            if np.all(~np.isfinite(e)) or not np.any(e > 0):
                continue
            lab = {"ka": "ka", "ke": "ke", "penetration": "Δ/h", "mu": "μ", "pressure": "σ (rel. L2)"}[k]
            ax.loglog(N, e, m + "-", ms=4, mfc="none", label=f"{lab}: p = {c['orders'][k]:.2f}")
        for p_, ls in ((1, ":"), (2, "--")):
            ax.loglog(N, (N / N[0]) ** (-p_) * 1e-2, "k" + ls, lw=0.6, alpha=0.5)
        ax.set_title(c["label"], fontsize=8)
        ax.set_xlabel("N (panels per period)")
        ax.set_ylabel("|BEM − semi-analytic|")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6)
    return fig


@kept_when_unchanged
def write_figure(path_png, conv):
    """`plot_convergence` on a figure 4.6 in wide per convergence point, written to
    ``path_png``."""
    fig = pyplot().figure(figsize=(4.6 * len(conv), 4.2))
    plot_convergence(fig, conv)
    return save(fig, path_png)
