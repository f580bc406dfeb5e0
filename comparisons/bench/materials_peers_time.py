"""viscosine's E(t) fit against pyvisco's and ANSYS's on pyvisco's time-domain master curve.

Part of ``python -m comparisons bench --materials-peers`` (`materials_peers.run` prints it after
the frequency-domain table).  For each relaxation master curve E(t) that NREL's pyvisco ships
(``comparisons/data/materials_peers/``, BSD-3-Clause, its notice kept):
`viscosine.materials.fit_time_data` with no options, pyvisco's two time-domain fits (its default
initial fit, one relaxation time per decade, and the fit its term minimisation suggests) and
ANSYS APDL's fit from pyvisco's verification folder are

* evaluated at every row of the file: RMS and largest relative residual of E(t) (model/datum -
  1) and pyvisco's own figure of merit in the time domain (``prony.ls_res(E_relax_norm)``: the
  sum of squared residuals of E(t) divided by its E_0, the first datum);
* turned into E', E'' and tan delta over the data's frequency window ``1/t_max .. 1/t_min``
  (rad/s), exactly, term by term.  Time data hold no measured E'': what can be judged is how
  far fits that all meet E(t) disagree on it, each against ours (RMS and largest relative
  difference), over the whole window and over its interior (a decade in from each end, where
  terms beyond the data no longer weigh).  Our own fits at other densities (`SCATTER` times a
  decade), which meet E(t) about as well, show how much of E'' the data leave open.

pyvisco's tables were made once by pyvisco 2.1.3 in a separate environment (no dependency of
viscosine); each carries its own residual in a ``# ls_res = ...`` line, which `ls_res_time`
reproduces from the table read back (tests/validation/test_materials_peers.py).
"""
from __future__ import annotations

import math

import numpy as np

from viscosine.materials import fit_time_data, read_time_data

from .materials_peers import DATA, OURS, read_peer_table

#: the time-domain data sets (tensile relaxation moduli E(t))
TIME_SETS = ("time-user-master",)
PEERS = ("pyvisco-initial", "pyvisco-opt", "ansys")
#: points per decade of the frequency grid on which the fits' E', E'' are compared
PER_DECADE = 10
#: other densities of our own fit (times a decade): fits that meet E(t) about as well as the
#: default, whose spread in E'' is the part of E'' the data leave open
SCATTER = (1.5, 3.0, 4.0, 6.0, 10.0)
OWN_SCATTER = "viscosine, other densities"


def time_rows(name):
    """Every row of a time-domain set as given: time [s], E(t) (file's unit)."""
    d = np.loadtxt(DATA / f"{name}.csv", delimiter=",", comments="#", skiprows=4)
    return d[:, 0], d[:, 1]


def relaxation(table, t):
    """``E(t) = E_0 [1 - sum alpha_i (1 - exp(-t/tau_i))]`` of a peer table (pyvisco's
    E_relax_norm times E_0)."""
    decay = np.exp(-np.outer(np.asarray(t, float), 1.0 / table.tau))
    return table.E_0 * (1.0 - table.alpha.sum() + decay @ table.alpha)


def ls_res_time(model, e, E_0):
    """pyvisco's time-domain figure of merit: sum of ((model - datum)/E_0)^2 over the rows."""
    return float(np.sum(((np.asarray(model) - e) / E_0) ** 2))


def _stats(r):
    return float(np.sqrt(np.mean(r * r))), float(np.max(np.abs(r)))


def window_grid(t):
    """Angular frequencies [rad/s] from ``1/t_max`` to ``1/t_min``, PER_DECADE a decade."""
    lo, hi = -math.log10(t[-1]), -math.log10(t[0])
    return np.logspace(lo, hi, int(math.ceil((hi - lo) * PER_DECADE)) + 1)


def _spectra(star):
    return {"storage": star.real, "loss": star.imag, "tan_delta": star.imag / star.real}


def _against(spec, ref, inner):
    """RMS/max relative difference of each of E', E'', tan d from the reference, over the
    whole window and its interior."""
    out = {}
    for q in ("storage", "loss", "tan_delta"):
        r = spec[q] / ref[q] - 1.0
        out[q] = (_stats(r), _stats(r[inner]))
    return out


def compare_time(name):
    """One data set: ``{"points", "window", "omega", "fit", "fitters": {label: {terms, relax
    (rms, max), ls_res, seconds, spectra {quantity: array over omega}, against_ours {quantity:
    ((rms, max) whole, (rms, max) interior)}}}, "scatter": `own_scatter`}``."""
    t, e = time_rows(name)
    peers = {p: read_peer_table(DATA / f"{name}.{p}.csv") for p in PEERS
             if (DATA / f"{name}.{p}.csv").exists()}
    E_0 = peers["pyvisco-initial"].E_0              # one figure of merit for every fitter
    data = read_time_data(DATA / f"{name}.csv")
    ours = fit_time_data(data)
    omega = window_grid(t)
    inner = (omega >= 10.0 * omega[0]) & (omega <= omega[-1] / 10.0)
    fitters = {OURS: (ours.relaxation(t), ours.modulus(omega), len(ours.E), ours.fit.seconds)}
    for label, tab in peers.items():
        fitters[label] = (relaxation(tab, t), tab.modulus(omega), tab.terms,
                          tab.header.get("seconds"))
    ref = _spectra(fitters[OURS][1])
    out = {}
    for label, (model, star, terms, secs) in fitters.items():
        spec = _spectra(star)
        out[label] = {"terms": terms, "relax": _stats(model / e - 1.0),
                      "ls_res": ls_res_time(model, e, E_0), "seconds": secs,
                      "spectra": spec, "against_ours": _against(spec, ref, inner)}
    return {"points": t.size, "window": (float(omega[0]), float(omega[-1])), "omega": omega,
            "fit": ours.fit, "fitters": out, "scatter": own_scatter(data, t, e, omega, inner, ref)}


def own_scatter(data, t, e, omega, inner, ref):
    """Our fits at the SCATTER densities against the default: ``{"relax": (smallest, largest)
    E(t) RMS, "terms": (fewest, most), quantity: ((rms, max) whole, (rms, max) interior), each
    the largest over the densities}``."""
    fits = [fit_time_data(data, per_decade=k) for k in SCATTER]
    rms = [_stats(f.relaxation(t) / e - 1.0)[0] for f in fits]
    diffs = [_against(_spectra(f.modulus(omega)), ref, inner) for f in fits]
    out = {"relax": (min(rms), max(rms)), "terms": (min(len(f.E) for f in fits),
                                                    max(len(f.E) for f in fits))}
    for q in ("storage", "loss", "tan_delta"):
        out[q] = tuple(tuple(max(d[q][w][k] for d in diffs) for k in (0, 1)) for w in (0, 1))
    return out


def _pct(v):
    return f"{100 * v:.2f}"


def _secs(v):
    return "–" if v is None else f"{v:.3g}"


def table(results) -> list:
    """The summary table (markdown) of `compare_time` results keyed by set."""
    lines = ["| data set (points, window rad/s) | fitter | terms | E(t) RMS/max % | "
             "pyvisco's ls_res | s per fit |",
             "| --- | --- | --- | --- | --- | --- |"]
    for name, res in results.items():
        lo, hi = res["window"]
        for j, (label, m) in enumerate(res["fitters"].items()):
            first = f"{name} ({res['points']}, {lo:.1e}–{hi:.1e})" if j == 0 else ""
            lines.append(f"| {first} | {label} | {m['terms']} | {_pct(m['relax'][0])}/"
                         f"{_pct(m['relax'][1])} | {m['ls_res']:.4g} | {_secs(m['seconds'])} |")
    return lines


def spread_table(results) -> list:
    """How far each peer's E', E'', tan d lie from ours over the window (RMS/max %)."""
    lines = ["| data set | fitter vs viscosine | E′ RMS/max % (interior) | "
             "E″ RMS/max % (interior) | tan δ RMS/max % (interior) |",
             "| --- | --- | --- | --- | --- |"]
    for name, res in results.items():
        for label, m in res["fitters"].items():
            if label == OURS:
                continue
            cells = []
            for q in ("storage", "loss", "tan_delta"):
                (wr, wm), (ir, im) = m["against_ours"][q]
                cells.append(f"{_pct(wr)}/{_pct(wm)} ({_pct(ir)}/{_pct(im)})")
            lines.append(f"| {name} | {label} | " + " | ".join(cells) + " |")
        sc = res["scatter"]
        cells = [f"{_pct(sc[q][0][0])}/{_pct(sc[q][0][1])} ({_pct(sc[q][1][0])}/"
                 f"{_pct(sc[q][1][1])})" for q in ("storage", "loss", "tan_delta")]
        lines.append(f"| {name} | {OWN_SCATTER} ({sc['terms'][0]}-{sc['terms'][1]} terms, E(t) "
                     f"RMS {_pct(sc['relax'][0])}-{_pct(sc['relax'][1])} %; largest) | "
                     + " | ".join(cells) + " |")
    return lines


def run() -> None:
    results = {name: compare_time(name) for name in TIME_SETS}
    print("Time domain: E(t) master curves, fits at the data's rows")
    for line in table(results):
        print(line)
    print()
    print("Time domain: E′, E″, tan δ of each fit against viscosine's over the window "
          "1/t_max..1/t_min (interior: a decade in from each end)")
    for line in spread_table(results):
        print(line)
    for name, res in results.items():
        print(f"{name}: viscosine: {res['fit'].summary()}")
