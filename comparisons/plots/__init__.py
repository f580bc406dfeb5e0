"""Figures: the only part of viscosine that imports matplotlib.

Every figure function takes plain numbers (or a record, a store, a material of `viscosine`) and
draws on an Axes or writes a PNG; none solves anything.  matplotlib is imported on first use, on
the file-only Agg backend, so that importing the comparison layer stays cheap and never opens a
window.

* `paper`: the paper's figures 3–12 with both roads (the report);
* `fields`: σ(x) and v(x) of both roads and their difference (the report);
* `convergence`: the BEM's error against N with its observed orders (the report);
* `peers`: Tamaas's error as its time step is halved (the report);
* `materials`: E′, E″ and tan δ of a Prony series (the report, ``verify``, the suite export)
  and a DMA curve against its Prony fit;
* `mastercurve`: the friction master curve μ(V, T) (``python -m comparisons mastercurve``);
* `sweep`: μ against the speed, one curve per load (``python -m comparisons sweep --plot``);
* `layers`: μ, 2a/λ and p̃FC on a layer of finite thickness, bonded or frictionless (the report).

The report's numbers come from `comparisons.report_numbers`; here they are only drawn.
"""
from __future__ import annotations


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend (figures are written to files, never shown)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path_png):
    """Write a finished figure to ``path_png`` (tight layout, 110 dpi) and close it; returns the
    path."""
    fig.tight_layout()
    fig.savefig(path_png, dpi=110)
    pyplot().close(fig)
    return path_png
