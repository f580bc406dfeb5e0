"""The material figures: the complex modulus of a Prony series, and a DMA curve against its fit.

The material figure (shared by the report, ``verify`` and the suite export; plain numbers in, an
Axes out): the complex modulus E*(ω) = E′ + iE″ of a Prony creep function and its loss
tangent against frequency.  Its inputs are the numbers of a Prony file (docs/conventions.md,
'Input files of the boundary-element road'), not a solver object, so that plotting a material
needs neither road.

Conventions (docs/conventions.md, 'Creep times, not relaxation times'): the creep function is
J(t) = J0 − Σ_i J_i e^(−t/τ_i) for t > 0, with τ_i creep (retardation) times; compliances in
1/E_ref, times in τ_ref.  A harmonic stress σ0 e^(iωt) gives the strain J*(ω) σ0 e^(iωt) with

    J*(ω) = J0 − Σ_i J_i iωτ_i/(1 + iωτ_i) = J(0+) + Σ_i J_i/(1 + iωτ_i) = J′ − iJ″,
    J′ = J(0+) + Σ_i J_i/(1 + ω²τ_i²),     J″ = Σ_i J_i ωτ_i/(1 + ω²τ_i²) ≥ 0,

J(0+) = J0 − Σ_i J_i, and E*(ω) = 1/J*(ω): E′ = J′/|J*|², E″ = J″/|J*|² ≥ 0 (the strain lags the
stress), tan δ = E″/E′ = J″/J′.  E′ rises from 1/J0 (E0, relaxed) at ω → 0 to 1/J(0+) (E∞,
glassy) at ω → ∞.  For the standard linear solid (J0 = 1/E0, J1 = 1/E0 − 1/E∞, τ1 = τ) this is
E*/E0 = (1 + iωτ)/(1 + iωτ/ρ), ρ = E∞/E0, the modulus E(kV) of the paper at ω = kV; tan δ peaks
at ωτ = √ρ with the value (ρ − 1)/(2√ρ), and E″ at ωτ = ρ (the inverse relaxation time).
A mode e^(ikx) of the steady sliding field is seen by the material at the frequency kV, i.e.
ωτ_ref = V τ_ref k = V/V0: the sliding frequency in units of 1/τ_ref is the speed input itself.

J′ and J″ are sums of positive terms (J(0+) is formed once), so nothing cancels, even for
E∞/E0 = 1e4.

The DMA fit figure (`plot_dma_fit`): measured E′, E″ and tan δ against ω with the fitted Prony
series.  Its inputs are a master curve and a relaxation-form series of
:mod:`viscosine.materials` (the shared package, not a road), in the units of the data: angular
frequency in rad per time unit, moduli in the file's unit.  E″ ≥ 0 (the strain lags the stress), tan δ = E″/E′.  The measured window is
shaded: outside it the curve is the fit's extrapolation, not data.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014: eq. (2.3) (the
creep function of the standard linear solid) and eqs (2.7)–(2.8) (the modulus E(kV) at the
sliding frequency).
"""
from __future__ import annotations

import dataclasses
import math
import os

import numpy as np

from viscosine.checks import bad, real, reals

from .. import roads
from .._errors import Failed
from .._io import stderr
from . import kept_when_unchanged, pyplot, save


def _terms(J0, terms):
    j0 = real("J0", J0, "a finite compliance > 0", lambda v: v > 0.0)
    allowed = "pairs (J_i >= 0, tau_i > 0)"
    arr = reals("terms", terms, allowed)
    if arr.size and (arr.ndim != 2 or arr.shape[1] != 2):
        raise bad("terms", terms, allowed)
    tt = [(j, t) for j, t in arr.reshape(-1, 2).tolist()]
    for j, t in tt:
        if not (math.isfinite(j) and j >= 0.0 and math.isfinite(t) and t > 0.0):
            raise bad("terms", terms, allowed)
    jplus = j0 - sum(j for j, _ in tt)
    if not jplus > 0.0:
        raise bad("terms", terms, f"J(0+) = J0 - sum J_i = {jplus!r} must be > 0")
    return j0, tt, jplus


def complex_modulus(omega, J0, terms):
    """E′(ω), E″(ω) and tan δ(ω) of a Prony creep function.

    Parameters
    ----------
    omega : array_like
        Angular frequencies ω, in 1/τ_ref (ω τ_ref = V/V0 for the mode k at speed V).
    J0 : float
        Relaxed (long-time) compliance, in 1/E_ref.
    terms : sequence of (float, float)
        (J_i, τ_i): compliances in 1/E_ref and creep (retardation) times in τ_ref.

    Returns
    -------
    (ndarray, ndarray, ndarray)
        E′ and E″ in E_ref, and tan δ = E″/E′, at each ω (see the module docstring for the sign
        convention: E″ ≥ 0).

    Raises
    ------
    ValueError
        J0 ≤ 0, a term with J_i < 0 or τ_i ≤ 0, or J(0+) = J0 − Σ J_i ≤ 0.

    References
    ----------
    Eq. (2.3) of the paper (the standard linear solid, one term).
    """
    _, tt, jplus = _terms(J0, terms)
    w = np.asarray(omega, dtype=float)
    j1 = np.full(w.shape, jplus)
    j2 = np.zeros(w.shape)
    for j, t in tt:
        x = w * t
        d = 1.0 + x * x
        j1 = j1 + j / d
        j2 = j2 + j * x / d
    mod2 = j1 * j1 + j2 * j2
    return j1 / mod2, j2 / mod2, j2 / j1


def plot_material(ax, J0, terms, *, speeds=(), speeds_label="sliding frequencies kV",
                  title=None):
    """E′, E″ (left axis) and tan δ (right axis) against ω τ_ref, log axes.

    Parameters
    ----------
    ax : matplotlib Axes
        Where E′ and E″ are drawn; tan δ goes on ``ax.twinx()``.
    J0, terms
        The Prony creep function, as in `complex_modulus`.
    speeds : sequence of float
        Speeds V/V0 (= V τ_ref k) whose sliding frequencies ω = kV are marked by vertical lines.
    speeds_label : str
        Legend entry of those lines.
    title : str, optional
        Default: the creep function's numbers (J0, then (J_i, τ_i)) and E∞/E0.

    Returns
    -------
    ax
    """
    j0, tt, jplus = _terms(J0, terms)
    taus = [t for _, t in tt] or [1.0]
    lo, hi = 1e-2 / max(taus), 1e2 / min(taus)
    sp = [float(s) for s in speeds if float(s) > 0.0]
    if sp:  # the marked frequencies stay inside the plot
        lo, hi = min(lo, min(sp) / 3.0), max(hi, max(sp) * 3.0)
    w = np.logspace(math.log10(lo), math.log10(hi), 400)
    e1, e2, tan = complex_modulus(w, j0, tt)
    h1, = ax.loglog(w, e1, "C0-", lw=1.4, label="E′ (storage)")
    h2, = ax.loglog(w, e2, "C3-", lw=1.4, label="E″ (loss)")
    ax.axhline(1.0 / j0, color="C0", ls=":", lw=0.8)
    ax.axhline(1.0 / jplus, color="C0", ls=":", lw=0.8)
    ax.set_xlabel("ω τ_ref (frequency in 1/τ_ref; sliding: ω = kV, ω τ_ref = V/V0)")
    ax.set_ylabel("E′, E″ (units of E_ref)")
    ax.set_ylim(max(float(np.min(e2)), 1e-3 / j0) / 2.0, 2.0 / jplus)
    tw = ax.twinx()
    h3, = tw.loglog(w, tan, "C2--", lw=1.2, label="tan δ = E″/E′ (right axis)")
    tw.set_ylabel("tan δ", color="C2")
    tw.set_ylim(max(float(np.min(tan)), 1e-4 * float(np.max(tan))) / 2.0,
                2.0 * float(np.max(tan)))
    handles = [h1, h2, h3]
    for i, s in enumerate(sp):
        h = ax.axvline(s, color="0.45", ls="-", lw=0.6, alpha=0.7,
                       label=speeds_label if i == 0 else None)
        if i == 0:
            handles.append(h)
    ax.legend(handles=handles, fontsize=7, loc="upper left")
    ax.grid(True, which="both", alpha=0.25)
    if title is None:
        series = ", ".join(f"({j:.4g}, {t:.4g})" for j, t in tt) or "none"
        title = (f"Prony creep function J0 = {j0:.4g}, (J_i, τ_i) = {series}; "
                 f"E∞/E0 = J0/J(0+) = {j0 / jplus:.4g}")
    ax.set_title(title, fontsize=9)
    return ax


def prony_numbers(path):
    """(J0, [(J_i, τ_i), ...]) of a Prony file, read by the BEM road's own reader
    (:func:`bem.read_prony`, through `comparisons.roads`: the one definition of the format) and
    passed on as plain numbers."""
    p = roads.read_prony(path)
    return float(p.J0), [(float(j), float(t)) for j, t in zip(p.J, p.tau)]


@kept_when_unchanged
def material_figure(path_png, J0, terms, *, speeds=(), speeds_label="sliding frequency kV",
                    title=None):
    """Write the material figure to ``path_png`` (Agg backend, 110 dpi)."""
    fig, ax = pyplot().subplots(figsize=(6.6, 4.4))
    plot_material(ax, J0, terms, speeds=speeds, speeds_label=speeds_label, title=title)
    return save(fig, path_png)


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
        _, ax = pyplot().subplots(figsize=(7.0, 4.6))
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
        what = report.summary().replace("; ", "\n") if report is not None \
            else f"{len(model.E)} terms"
        title = f"{curve.source or 'DMA data'}\nProny fit: {what}"
    ax.set_title(title, fontsize=8)
    return ax


def plot_dma_residuals(curve, model, *, ax):
    """Relative residuals (model/datum − 1, %) of E′ and E″ at the data, with the fit report's
    estimated scatter of the data as a band (±1 σ of E′ and E″)."""
    fit = model.modulus(curve.omega)
    r1 = 100.0 * (fit.real / curve.storage - 1.0)
    r2 = 100.0 * (fit.imag / curve.loss - 1.0)
    ax.axhline(0.0, color="0.5", lw=0.8)
    report = model.fit
    if report is not None:
        for s, color in zip(report.scatter, ("C0", "C3")):
            if s is not None:
                ax.axhspan(-100 * s, 100 * s, color=color, alpha=0.08, zorder=0)
    ax.semilogx(curve.omega, r1, "o", color="C0", ms=3.0, mfc="none", label="E′")
    ax.semilogx(curve.omega, r2, "s", color="C3", ms=3.0, mfc="none", label="E″")
    ax.set_xlabel("ω (rad per time unit of the data)")
    ax.set_ylabel("fit/data − 1 (%)")
    ax.grid(True, which="both", alpha=0.25)
    ax.legend(fontsize=7, loc="best")
    return ax


def material_fit_figure(material, folder="."):
    """The fit figure of a command line's DMA material (a `comparisons._materials.Material`
    with its ``curve``), written to ``<folder>/<data file stem>_fit.png``; returns the path, or
    None for a series file (nothing fitted).  A material moved to a temperature is drawn there:
    the data's frequencies are shifted with the model's times."""
    curve = getattr(material, "curve", None)
    if curve is None:
        return None
    stem = os.path.splitext(os.path.basename(material.info.get("path") or "dma"))[0]
    log_a = material.info.get("log10_aT") or 0.0
    if log_a:
        curve = dataclasses.replace(curve, omega=curve.omega / 10.0 ** log_a)
    return dma_fit_figure(os.path.join(folder, f"{stem}_fit.png"), curve, material.model)


def report_fit(material, folder, command):
    """What every command that fits a DMA curve (point, sweep, mastercurve) does with the fit:
    its figure `material_fit_figure` written into ``folder``, said on standard error with the
    fit's summary and warnings (``<command>: DMA fit of FILE: ...; wrote PATH``).  Returns the
    path, or None when nothing was fitted (a series file, no material).

    Raises
    ------
    comparisons._errors.Failed
        The figure cannot be written.
    """
    try:
        path = material_fit_figure(material, folder)
    except OSError as exc:
        raise Failed(f"cannot write the DMA fit figure ({exc.strerror or exc})") from None
    if path is not None:
        report = material.model.fit
        stderr(f"{command}: DMA fit of {material.info['path']}: {report.summary()}; wrote {path}")
        for w in report.warnings:
            stderr(f"{command}: DMA fit: {w}")
    return path


@kept_when_unchanged
def dma_fit_figure(path_png, curve, model, *, title=None):
    """Write `plot_dma_fit` above `plot_dma_residuals` to ``path_png`` (Agg backend, 110 dpi);
    returns the path."""
    fig, (ax, rax) = pyplot().subplots(2, 1, figsize=(7.0, 6.6), sharex=True,
                                       gridspec_kw={"height_ratios": [2.2, 1.0]})
    plot_dma_fit(curve, model, ax=ax, title=title)
    ax.set_xlabel("")
    plot_dma_residuals(curve, model, ax=rax)
    return save(fig, path_png)
