"""A sweep's friction curve: μ against the speed (log axis), one curve per load or penetration
(``python -m comparisons sweep --plot FILE``)."""
from __future__ import annotations

import os

from . import pyplot

#: the figure formats ``--plot`` writes, by the file's extension
FORMATS = (".png", ".pdf", ".svg")


def plot(curves, *, xlabel, title, ax=None):
    """Draw μ against speed, one line with markers per curve.

    Parameters
    ----------
    curves : list of (label, speeds, mus)
        One curve per load (or penetration), its points in the sweep's order.
    xlabel, title : str
        The speed's name with its unit; the parameters that produced the curves.
    ax : Axes, optional
        Where to draw; a new figure when None.

    Returns
    -------
    Axes
    """
    if ax is None:
        _, ax = pyplot().subplots(figsize=(6.4, 4.4))
    for i, (label, speeds, mus) in enumerate(curves):
        ax.plot(speeds, mus, "o-", color=f"C{i % 10}", lw=1.2, ms=3.5, label=label)
    ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("μ = τf/p∞")
    ax.grid(True, which="both", alpha=0.25)
    if curves:
        ax.legend(fontsize=7)
    ax.set_title(title, fontsize=8)
    return ax


def write_figure(path, curves, *, xlabel, title):
    """`plot` written to ``path`` (its extension, one of `FORMATS`, picks the format), whole or
    not at all (a temporary file renamed)."""
    fig, ax = pyplot().subplots(figsize=(6.4, 4.4))
    plot(curves, xlabel=xlabel, title=title, ax=ax)
    fig.tight_layout()
    part = f"{path}.part"
    try:
        fig.savefig(part, dpi=110, format=os.path.splitext(path)[1][1:].lower())
        os.replace(part, path)
    finally:
        pyplot().close(fig)
        if os.path.exists(part):
            os.remove(part)
    return path
