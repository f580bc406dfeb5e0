"""The benchmark suite's figure: the material of a case, as its export shows it."""
from __future__ import annotations

import os

from .materials import material_figure


def material_png(path, name, source, J0, terms, speed):
    """Write E′, E″ and tan δ of a case's Prony material to ``path``, its sliding frequency marked.

    Parameters
    ----------
    path : pathlib.Path
        The PNG to write (through ``<stem>.part.png`` beside it, renamed over it when complete).
    name, source : str
        The case's name and what its creep series is (a file name, with a temperature), for the
        title.
    J0 : float
        Relaxed compliance, in 1/E_ref.
    terms : sequence of (float, float)
        (J_i, τ_i), compliances in 1/E_ref and creep (retardation) times in τ_ref.
    speed : float
        The sliding speed V/V0 = ωτ_ref of the mode kV.
    """
    if len(terms) <= 4:
        series = "(J_i, τ_i) = " + ", ".join(f"({j:g}, {t:g})" for j, t in terms)
    else:  # a broad spectrum: its extent, not every term, fits in a title
        taus = [t for _, t in terms]
        series = f"{len(terms)} terms, τ_i = {min(taus):.3g} … {max(taus):.3g}"
    tmp = path.with_name(path.stem + ".part.png")
    material_figure(tmp, J0, terms, speeds=[speed],
                    speeds_label=f"sliding frequency kV: ωτ_ref = V/V0 = {speed:g}",
                    title=f"{name} ({source}): J0 = {J0:g}, {series}"
                          + f"; E∞/E0 = {J0 / (J0 - sum(j for j, _ in terms)):.4g}")
    os.replace(tmp, path)
