"""Figures of ``python -m comparisons verify`` (plain numbers in, Axes or a PNG out): a result's
fields against the reference's, and the differences of its convergence study against N."""
from __future__ import annotations

import numpy as np

from . import pyplot


def plot_fields(axes, xs, ref, got, *, label, road, title):
    """σ (and v) of a result (markers) against the reference (lines), then their differences.

    Parameters
    ----------
    axes : sequence of matplotlib Axes
        Three with ``displacement`` in ``got`` (σ, v, the differences), else two.
    xs : ndarray
        x/λ, increasing.
    ref, got : dict
        The reference's and the result's ``pressure`` (σ(1 − ν²)/E0) at ``xs`` and, in ``got``
        when the result has it (and then in ``ref``), ``displacement`` (v/h).
    label, road, title : str
        The result's legend entry, the reference's road and the title.

    Returns
    -------
    axes
    """
    step = max(1, xs.size // 128)
    ax = axes[0]
    ax.plot(xs, ref["pressure"], "k-", lw=1.0, label=f"reference ({road})")
    ax.plot(xs[::step], got["pressure"][::step], "o", ms=3, mfc="none", color="C3",
            label=label)
    ax.set_ylabel("σ(1 − ν²)/E0")
    ax.legend(fontsize=7)
    if "displacement" in got:
        ax = axes[1]
        ax.plot(xs, ref["displacement"], "k-", lw=1.0, label="reference")
        ax.plot(xs[::step], got["displacement"][::step], "s", ms=2.5, mfc="none",
                color="C0", label=label)
        ax.set_ylabel("v/h")
        ax.legend(fontsize=7)
    ax = axes[-1]
    pm = float(np.max(np.abs(ref["pressure"])))
    ax.plot(xs, (got["pressure"] - ref["pressure"]) / pm, "C3-", lw=0.8,
            label="(σ − σ_ref)/max σ_ref")
    if "displacement" in got:
        ax.plot(xs, got["displacement"] - ref["displacement"], "C0-", lw=0.8,
                label="(v − v_ref)/h")
    ax.set_ylabel("difference")
    ax.set_xlabel("x/λ (crest at 0, sliding toward +x)")
    ax.legend(fontsize=7)
    for a in axes:
        a.grid(True, alpha=0.3)
    axes[0].set_title(title, fontsize=9)
    return axes


def fields_figure(path, xs, ref, got, *, label, road, title):
    """Write `plot_fields` to ``path`` (100 dpi)."""
    plt = pyplot()
    rows = 3 if "displacement" in got else 2
    fig, axes = plt.subplots(rows, 1, figsize=(7.5, 2.6 * rows), sharex=True)
    plot_fields(axes, xs, ref, got, label=label, road=road, title=title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path


def plot_convergence(ax, nodes, curves, *, floor, title):
    """The differences of each quantity from the reference against N, log–log.

    Parameters
    ----------
    ax : matplotlib Axes
    nodes : sequence of int
        The resolutions N of the results.
    curves : sequence of (str, sequence of float or None)
        Per quantity its legend entry and its differences at ``nodes`` (None where missing);
        each keeps its marker and colour by its place here.
    floor : float
        A curve with no difference above it (round-off only, such as a load the solver imposes
        exactly) is left out.
    title : str

    Returns
    -------
    ax
    """
    n = np.array(nodes, float)
    colours = pyplot().cm.tab20(np.linspace(0.0, 1.0, 20))
    for i, (label, errors) in enumerate(curves):
        e = np.array([np.nan if v is None else v for v in errors], float)
        if not np.any(e > floor):
            continue
        ax.loglog(n, e, "os^dv<>ph*"[i % 10] + "-", ms=4, mfc="none",
                  color=colours[(3 * i) % 20], label=label)
    ax.set_xlabel("N (resolution of the solver under test)")
    ax.set_ylabel("difference from the reference")
    ax.set_title(title, fontsize=9)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=6, ncol=2)
    return ax


def convergence_figure(path, nodes, curves, *, floor, title):
    """Write `plot_convergence` to ``path`` (100 dpi)."""
    plt = pyplot()
    fig, ax = plt.subplots(figsize=(7.0, 4.6))
    plot_convergence(ax, nodes, curves, floor=floor, title=title)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    return path
