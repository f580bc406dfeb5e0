"""The DMA fit figure: measured E′, E″ and tan δ against ω with the fitted Prony series.

Inputs are a master curve and a relaxation-form series of :mod:`viscosine.materials` (the shared
package, not a road), in the units of the data: angular frequency in rad per time unit, moduli in
the file's unit.  E″ ≥ 0 (the strain lags the stress), tan δ = E″/E′.  The measured window is
shaded: outside it the curve is the fit's extrapolation, not data.
"""
from __future__ import annotations

import math

import numpy as np


def plot_dma_fit(curve, model, *, ax=None, title=None):
    """Data (markers) against fit (lines): E′, E″ on log axes, tan δ on a right axis.

    Parameters
    ----------
    curve : viscosine.materials.MasterCurve
        The data.
    model : viscosine.materials.Maxwell
        The series fitted to it (``fit_prony``); drawn a decade beyond the data on each side.
    ax : matplotlib Axes, optional
        Where E′ and E″ go (tan δ on ``ax.twinx()``); a new figure when None.
    title : str, optional
        Default: the data source and the fit report (terms, residuals), for provenance.

    Returns
    -------
    ax
    """
    if ax is None:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        _, ax = plt.subplots(figsize=(7.0, 4.6))
    w0, w1 = curve.window
    w = np.logspace(math.log10(w0) - 1.0, math.log10(w1) + 1.0, 600)
    fit = model.modulus(w)
    h = [ax.axvspan(w0, w1, color="0.93", zorder=0, label="measured window"),
         ax.loglog(curve.omega, curve.storage, "o", color="C0", ms=3.5, mfc="none",
                   label="E′ data")[0],
         ax.loglog(w, fit.real, "-", color="C0", lw=1.3, label="E′ fit")[0],
         ax.loglog(curve.omega, curve.loss, "s", color="C3", ms=3.5, mfc="none",
                   label="E″ data")[0],
         ax.loglog(w, fit.imag, "-", color="C3", lw=1.3, label="E″ fit")[0]]
    ax.set_xlabel("ω (rad per time unit of the data)")
    ax.set_ylabel("E′, E″ (modulus unit of the data)")
    ax.grid(True, which="both", alpha=0.25)
    tw = ax.twinx()
    h += [tw.loglog(curve.omega, curve.tan_delta, "^", color="C2", ms=3.0, mfc="none",
                    label="tan δ data (right)")[0],
          tw.loglog(w, fit.imag / fit.real, "--", color="C2", lw=1.1,
                    label="tan δ fit (right)")[0]]
    tw.set_ylabel("tan δ", color="C2")
    ax.legend(handles=h, fontsize=7, loc="upper left")
    if title is None:
        report = model.fit
        what = report.summary() if report is not None else f"{len(model.E)} terms"
        title = f"{curve.source or 'DMA data'}\nProny fit: {what}"
    ax.set_title(title, fontsize=8)
    return ax


def dma_fit_figure(path_png, curve, model, *, title=None):
    """Write `plot_dma_fit` to ``path_png`` (Agg backend, 110 dpi); returns the path."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    plot_dma_fit(curve, model, ax=ax, title=title)
    fig.tight_layout()
    fig.savefig(path_png, dpi=110)
    plt.close(fig)
    return path_png
