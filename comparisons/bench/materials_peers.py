"""viscosine's DMA fit against pyvisco's on pyvisco's own example master curves.

``python -m comparisons bench --materials-peers``: for each frequency-domain master curve that
NREL's pyvisco ships (``comparisons/data/materials_peers/``, BSD-3-Clause, its notice kept), the
Prony series of `viscosine.materials.fit_prony` with no options, pyvisco's two fits (its default
initial fit, one relaxation time per decade, and the fit its term minimisation suggests) and,
where pyvisco ships one, ANSYS APDL's fit of its verification folder are evaluated at the
measured frequencies (every row of the file, duplicates included, the same rows for every
fitter).  Our fit to E' alone (``loss_weight=0``) is shown beside the default: the peers'
objectives are of that kind.  Printed: terms, RMS and largest relative residual (model/datum - 1)
of E', E'' and tan delta, pyvisco's own figure of merit (its ``prony.ls_res``: the sum of squared
residuals of E' and E'' divided by its E_0, the storage modulus at the highest frequency), the
Kramers-Kronig figure of the data (`FitReport.kk_range`), and per decade the RMS residuals of
each fitter.  The time-domain sets (E(t) master curves) follow, from `materials_peers_time`.

pyvisco's tables were made once by pyvisco 2.1.3 in a separate environment (pyvisco is no
dependency of viscosine); each carries, in a ``# ls_res = ...`` line, pyvisco's own residual,
which `ls_res` here reproduces from the table read back (tests/validation/test_materials_peers.py).
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from viscosine.materials import fit_prony, read_dma

DATA = Path(__file__).resolve().parents[1] / "data" / "materials_peers"
#: the data sets: name, Poisson ratio for a shear-modulus file (None: tensile)
SETS = (("user-master", None), ("eplexor-master", None), ("eplexor-shear", 0.5),
        ("eplexor-raw-master", None))
#: the peers' tables, ``<set>.<peer>.csv`` (absent where the peer published none)
PEERS = ("pyvisco-initial", "pyvisco-opt", "ansys")
OURS = "viscosine"
#: our fit to E' alone (``loss_weight=0``): the like of the peers' objectives, where E'' counts
#: as (E''/E_0)^2, next to nothing
OURS_STORAGE = "viscosine, loss_weight 0"


@dataclass(frozen=True)
class PeerTable:
    """A normalised Prony series as pyvisco writes it: ``E(t) = E_0 [1 - sum alpha_i (1 -
    exp(-t/tau_i))]`` (``E_inf = E_0 (1 - sum alpha_i)``; tau_i in s; E_0 in the file's
    modulus unit), with the ``# key = value`` lines of its header."""

    path: Path
    E_0: float
    alpha: np.ndarray
    tau: np.ndarray
    header: dict

    @property
    def terms(self) -> int:
        return int(np.count_nonzero(self.alpha))

    def modulus(self, omega):
        """``E' + i E''`` at angular frequencies ``omega`` [rad/s] (pyvisco's E_freq_norm)."""
        x = np.outer(np.asarray(omega, float), self.tau)
        a = self.E_0 * self.alpha
        stor = self.E_0 * (1.0 - self.alpha.sum()) + (x * x / (1.0 + x * x)) @ a
        return stor + 1j * ((x / (1.0 + x * x)) @ a)


def read_peer_table(path) -> PeerTable:
    """Read a table ``i,tau_i,alpha_i[,E_0,E_i]`` under a row of units; ``#`` lines hold
    ``key = value`` pairs (``E_0`` when the table has no E_0 column, as ANSYS's card)."""
    path = Path(path)
    header, rows = {}, []
    for line in path.read_text(encoding="utf-8").splitlines():
        if line.startswith("#"):
            key, eq, rest = line[1:].partition("=")
            if eq and key.strip().isidentifier():
                header[key.strip()] = float(rest.split()[0])
        elif line.strip():
            rows.append(line.split(","))
    names, table = rows[0], np.array(rows[2:], dtype=float)   # rows[1]: the units
    col = {n: j for j, n in enumerate(names)}
    e0 = [n for n in names if n in ("E_0", "G_0")]
    E_0 = float(table[0, col[e0[0]]]) if e0 else header["E_0"]
    return PeerTable(path, E_0, table[:, col["alpha_i"]], table[:, col["tau_i"]], header)


def rows(name):
    """Every row of a data set as given: frequency [Hz], storage, loss (file's unit)."""
    d = np.loadtxt(DATA / f"{name}.csv", delimiter=",", comments="#", skiprows=4)
    return d[:, 0], d[:, 1], d[:, 2]


def ls_res(model, e1, e2, E_0):
    """pyvisco's figure of merit (``prony.ls_res``): sum of ((model - datum)/E_0)^2 over E'
    and E''."""
    return float(np.sum(((model.real - e1) / E_0) ** 2) + np.sum(((model.imag - e2) / E_0) ** 2))


def _stats(r):
    return float(np.sqrt(np.mean(r * r))), float(np.max(np.abs(r)))


def _measure(model, f, e1, e2, E_0):
    r = (model.real / e1 - 1.0, model.imag / e2 - 1.0,
         (model.imag / model.real) / (e2 / e1) - 1.0)
    dec = np.floor(np.log10(f) + 1e-12).astype(int)
    decades = {int(k): tuple(_stats(q[dec == k])[0] for q in r) for k in np.unique(dec)}
    return {"storage": _stats(r[0]), "loss": _stats(r[1]), "tan_delta": _stats(r[2]),
            "ls_res": ls_res(model, e1, e2, E_0), "decades": decades}


def compare(name, nu=None):
    """One data set: ``{"points", "kk_range", "fitters": {label: {terms, storage, loss,
    tan_delta (each (rms, max)), ls_res, decades {decade: (E', E'', tan d rms)}, seconds}}}``."""
    f, e1, e2 = rows(name)
    omega = 2.0 * math.pi * f
    peers = {p: read_peer_table(DATA / f"{name}.{p}.csv") for p in PEERS
             if (DATA / f"{name}.{p}.csv").exists()}
    E_0 = peers["pyvisco-initial"].E_0          # one figure of merit for every fitter
    t0 = time.perf_counter()
    ours = fit_prony(read_dma(DATA / f"{name}.csv", nu=nu))
    seconds = time.perf_counter() - t0
    scale = 1.0 if nu is None else 2.0 * (1.0 + nu)   # our fit is tensile; a shear file is G
    out = {OURS: dict(_measure(ours.modulus(omega) / scale, f, e1, e2, E_0),
                      terms=len(ours.E), seconds=seconds)}
    storage = fit_prony(read_dma(DATA / f"{name}.csv", nu=nu), loss_weight=0.0)
    out[OURS_STORAGE] = dict(_measure(storage.modulus(omega) / scale, f, e1, e2, E_0),
                             terms=len(storage.E), seconds=None)
    for label, t in peers.items():
        out[label] = dict(_measure(t.modulus(omega), f, e1, e2, E_0), terms=t.terms,
                          seconds=None)
    return {"points": f.size, "kk_range": ours.fit.kk_range, "fit": ours.fit, "fitters": out}


def _pct(v):
    return f"{100 * v:.2f}"


def table(results) -> list:
    """The summary table (markdown) of `compare` results keyed by set."""
    lines = ["| data set (points, KK range) | fitter | terms | E′ RMS/max % | E″ RMS/max % | "
             "tan δ RMS/max % | pyvisco's ls_res |",
             "| --- | --- | --- | --- | --- | --- | --- |"]
    for name, res in results.items():
        kk = res["kk_range"]
        kk_text = "n/a" if kk[0] is None else f"{kk[0]:.2f}–{kk[1]:.2f}"
        for j, (label, m) in enumerate(res["fitters"].items()):
            first = f"{name} ({res['points']}, {kk_text})" if j == 0 else ""
            lines.append(
                f"| {first} | {label} | {m['terms']} | {_pct(m['storage'][0])}/"
                f"{_pct(m['storage'][1])} | {_pct(m['loss'][0])}/{_pct(m['loss'][1])} | "
                f"{_pct(m['tan_delta'][0])}/{_pct(m['tan_delta'][1])} | {m['ls_res']:.4g} |")
    return lines


def decade_wins(res, peer):
    """Decades where our RMS residual is below the peer's, for E', E'', tan d: ``(wins,
    decades)`` each."""
    ours, theirs = res["fitters"][OURS]["decades"], res["fitters"][peer]["decades"]
    return tuple((sum(ours[k][q] < theirs[k][q] for k in ours), len(ours)) for q in range(3))


def decade_table(name, res) -> list:
    labels = list(res["fitters"])
    lines = [f"{name}: RMS relative residual per decade of frequency [Hz], % (E′ / E″)",
             "decade " + "".join(f"{lab:>26s}" for lab in labels)]
    for k in sorted(res["fitters"][OURS]["decades"]):
        cells = "".join(f"{_pct(res['fitters'][lab]['decades'][k][0]):>15s}/"
                        f"{_pct(res['fitters'][lab]['decades'][k][1]):<10s}" for lab in labels)
        lines.append(f"1e{k:+03d} {cells}")
    return lines


def run() -> int:
    results = {name: compare(name, nu) for name, nu in SETS}
    for line in table(results):
        print(line)
    print()
    print("| data set | against | decades where viscosine's RMS is lower: E′ | E″ | tan δ |")
    print("| --- | --- | --- | --- | --- |")
    for name, res in results.items():
        for peer in res["fitters"]:
            if peer not in (OURS, OURS_STORAGE):
                w = decade_wins(res, peer)
                print(f"| {name} | {peer} | " + " | ".join(f"{a}/{b}" for a, b in w) + " |")
    for name, res in results.items():
        print()
        for line in decade_table(name, res):
            print(line)
        print(f"viscosine: {res['fit'].summary()}; {res['fitters'][OURS]['seconds']:.2f} s")
    return 0
