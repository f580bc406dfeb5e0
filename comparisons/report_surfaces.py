"""The report's section on surfaces: a rigid periodic surface z = h(x, y) sliding over the
half-space (three-dimensional contact), solved by the surface BEM (`bem.solve_surface`,
reached through `comparisons.roads`; `docs/surfaces.md`).

Its runs (`surface_runs`) are specs like every other of the report, one store entry each, so
an interrupted report keeps them; the section (`surfaces_section`) reads them back and writes
the checks against the line contact's roads and closed forms, the pressure map, μ against V/V0
for several loads, μ and the lateral coefficient against the sliding direction on an
anisotropic surface, and the BEM beside Persson's theory on self-affine surfaces.

Numbers are nondimensional (`docs/conventions.md`, 'Surfaces'): lengths over Lx, heights k z
with k = 2π/Lx, loads p̃∞ = p∞(1 − ν²)/E0, speeds V/V0 = Vτk, the standard linear solid with
E∞/E0 = 3.
"""
from __future__ import annotations

import math
import time

import numpy as np

from . import report_numbers as numbers
from . import operating_point as op
from . import roads
from .report_numbers import RATIO

#: the bi-sinusoid k z = hk (cos kx + cos ky) with hk = 1: p̃_FC is 1 at rest, 3 at high speed
BISINUSOID = {"kind": "bisinusoid", "hk": 1.0, "hk_y": None, "aspect": None}
#: the anisotropic one of the direction sweep: the ridges along y are twice as high
ANISOTROPIC = {"kind": "bisinusoid", "hk": 1.0, "hk_y": 0.5, "aspect": None}
#: the line contact's sinusoid extruded along y
EXTRUDED = {"kind": "bisinusoid", "hk": 1.0, "hk_y": 0.0, "aspect": None}
FRICTION_LOADS = (0.1, 0.3, 1.0)
DIRECTIONS = tuple(float(d) for d in range(0, 181, 15))
MAP_POINT = (0.3, 1.0, 30.0)  # load, speed, direction of the pressure map
#: Persson's comparison: self-affine surfaces (seeds 0, 1, 2) with these spectra, at two loads
SELF_AFFINE = {"kind": "self_affine", "hurst": 0.8, "rolloff": 2.0, "short_cutoff": 16.0,
               "long_cutoff": None, "rms_slope": 0.2, "rms_height": None, "aspect": None}
PERSSON_LOADS = (0.02, 0.1)
SEEDS = (0, 1, 2)


def _nodes(quick):
    """(grid of the sweeps, grid of the map and the extruded check) a side."""
    return (64, 128) if quick else (128, 512)


def _speeds(quick):
    return np.logspace(-2, 2, 5 if quick else 9)


def surface_spec(load, speed, nodes, surface, direction=None, penetration=None):
    """The spec of a surface run of the report (`comparisons.operating_point.at`: ``surface`` and
    ``direction`` beside the line's keys)."""
    return op.at("bem", float(speed), load=None if load is None else float(load),
                 penetration=None if penetration is None else float(penetration),
                 ratio=RATIO, nodes=int(nodes), surface=surface, direction=direction)


def _seeded(seed):
    return dict(SELF_AFFINE, seed=int(seed))


def surface_runs(quick):
    """Every run of the section: list of (spec, with_fields)."""
    n, fine = _nodes(quick)
    out = []
    for p in FRICTION_LOADS:
        out += [(surface_spec(p, s, n, BISINUSOID), False) for s in _speeds(quick)]
    out += [(surface_spec(0.3, 1.0, n, ANISOTROPIC, d), False) for d in DIRECTIONS]
    for p in PERSSON_LOADS:
        out += [(surface_spec(p, s, n, _seeded(k)), False) for s in _speeds(quick) for k in SEEDS]
    load, speed, theta = MAP_POINT
    out.append((surface_spec(load, speed, fine, BISINUSOID, theta), True))
    out += _check_runs(n, fine)
    return out


def _check_runs(n, fine):
    return [(surface_spec(0.3, 1.0, fine, EXTRUDED), False),              # the line contact
            (surface_spec(0.3, 5.0, n, EXTRUDED, 90.0), False),           # along the ridges
            (surface_spec(0.3, 2.0, n, EXTRUDED, 30.0), False),           # oblique law ...
            (surface_spec(0.3, 2.0 * math.cos(math.radians(30.0)), n, EXTRUDED), False),
            (surface_spec(4.0, 1.0, n, BISINUSOID), False)]               # full contact


def _record(store, spec):
    doc = store.get(spec)
    return doc["record"] if doc["ok"] else None


def _fmt(v, digits=4):
    return "—" if v is None else f"{v:.{digits}g}"


def surfaces_section(doc, folder, store, cfg, timings, png):
    """Write the section into ``doc`` (figures into ``folder`` through ``png(folder, name)``);
    ``timings`` gains the section's runs and its figures."""
    from .plots import surfaces as plots
    t0 = time.monotonic()
    n, fine = _nodes(cfg.quick)
    speeds = _speeds(cfg.quick)
    doc.p("A rigid periodic surface z = h(x, y) on a cell Lx × Ly slides at speed V in the "
          "direction θ over the same standard linear solid (E∞/E0 = 3), solved by the surface "
          "BEM alone (`bem.solve_surface`; `docs/surfaces.md`): the mode of wave vector q is the "
          "line contact's mode loaded at the frequency q·V, k u_q = (2/|q|) J*(q·ê) σ_q, on a "
          "grid of panels with the line's active set. Lengths are over Lx, heights k z with "
          "k = 2π/Lx, p̃∞ the mean pressure over the cell; the bi-sinusoid is k z = cos kx + "
          "cos ky (h_ref = 2h), whose full-contact load is 1 at rest and 3 at high speed.")
    doc.p("Checks (each a run of this report, the others' values beside it):")
    doc.table(["check", "what is compared", "surface BEM", "reference", "difference",
               "BEM's estimate"], _check_rows(store, n, fine))
    load, speed, theta = MAP_POINT
    spec = surface_spec(load, speed, fine, BISINUSOID, theta)
    got = store.get(spec, fields=True)
    if got["ok"]:
        rec = got["record"]
        plots.write_pressure_map(png(folder, "surface_pressure"), got["fields"], theta)
        doc.img("surface_pressure.png",
                f"Pressure σ(1 − ν²)/E0 on the bi-sinusoid's cell at p̃∞ = {load:g}, V/V0 = "
                f"{speed:g}, θ = {theta:g}° ({fine} × {fine} panels): white, the contact "
                f"outline; the arrow, the sliding direction. μ = {rec['mu']:.5f}, lateral "
                f"{rec['mu_lateral']:.2e}, contact fraction {rec['contact_fraction']:.4f}, "
                f"Δ/h_ref = {rec['penetration']:.5f}. The contact leads: it lies ahead of the "
                "crest along V, and the pressure more so (the line contact's e < ê).")
    curves = []
    for p in FRICTION_LOADS:
        recs = [_record(store, surface_spec(p, s, n, BISINUSOID)) for s in speeds]
        ok = [(s, r) for s, r in zip(speeds, recs) if r is not None]
        curves.append({"load": p, "speed": [s for s, _ in ok], "mu": [r["mu"] for _, r in ok],
                       "estimate": [(r["error_estimate"] or {}).get("mu") for _, r in ok]})
    plots.write_friction(png(folder, "surface_mu"), curves)
    worst = max((e for c in curves for e in c["estimate"] if e is not None), default=None)
    doc.img("surface_mu.png",
            f"Friction coefficient μ against V/V0 on the bi-sinusoid (θ = 0, {n} × {n} panels) "
            f"at p̃∞ = {', '.join(f'{p:g}' for p in FRICTION_LOADS)}; the BEM's estimated error "
            f"of μ at most {_fmt(worst, 2)} relative. Sliding along x, the modes (0, n) are never "
            "loaded in time (q·V = 0): they stay relaxed at any speed, so even at high speed "
            "the contact is not the glassy one.")
    doc.table(["p̃∞", "largest μ", "at V/V0", "μ at V/V0 = 0.01", "μ at V/V0 = 100"],
              [[f"{c['load']:g}", _fmt(max(c["mu"]), 5),
                _fmt(c["speed"][int(np.argmax(c["mu"]))], 3), _fmt(c["mu"][0], 4),
                _fmt(c["mu"][-1], 4)] for c in curves if c["mu"]])
    recs = [_record(store, surface_spec(0.3, 1.0, n, ANISOTROPIC, d)) for d in DIRECTIONS]
    ok = [(d, r) for d, r in zip(DIRECTIONS, recs) if r is not None]
    data = {"direction": [d for d, _ in ok], "mu": [r["mu"] for _, r in ok],
            "mu_lateral": [r["mu_lateral"] for _, r in ok]}
    plots.write_direction(png(folder, "surface_direction"), data)
    lat = max(data["mu_lateral"], key=abs) if ok else None
    doc.img("surface_direction.png",
            "μ (along V) and the lateral coefficient (the force to the left of V over the load) "
            "against the sliding direction θ on the anisotropic bi-sinusoid k z = cos kx + "
            f"0.5 cos ky at p̃∞ = 0.3, V/V0 = 1 ({n} × {n} panels). Along an axis (0°, 90°, "
            "180°) the surface is symmetric about V and the lateral force vanishes; obliquely "
            f"the higher ridges push the surface sideways (largest |lateral| "
            f"{_fmt(None if lat is None else abs(lat), 3)}); "
            "θ and 180° − θ mirror each other (the same μ, opposite lateral force).")
    _persson(doc, folder, store, n, speeds, plots, png)
    doc.p("The runs are in the results store like every other (one file each, written as it is "
          "done: an interrupted report keeps them and `--resume` does not repeat them).")
    timings["surface section: runs (sum over processes)"] = sum(
        store.get(spec).get("seconds") or 0.0 for spec, _ in surface_runs(cfg.quick))
    timings["surface section: figures and tables"] = time.monotonic() - t0


def _check_rows(store, n, fine):
    ext, ridge, obl, obl_ref, full = (_record(store, s) for s, _ in _check_runs(n, fine))
    rows = []
    if ext is not None:
        a = numbers.semi_analytic(0.3, 1.0)
        e = ext["error_estimate"] or {}
        for key, ref in (("mu", a.mu), ("penetration", a.penetration),
                         ("contact_fraction", a.contact_fraction)):
            diff = abs(ext[key] - ref) / abs(ref)  # relative, as the estimate beside it
            rows.append([f"surface uniform in y, along x ({fine}²)",
                         f"{key} against the semi-analytic line contact",
                         _fmt(ext[key], 8), _fmt(ref, 8), f"{diff:.1e} rel.",
                         _fmt(e.get(key), 2)])
    if ridge is not None:
        w = numbers.semi_analytic(0.3, 0.0)
        rows.append([f"the same along its ridges, V/V0 = 5 ({n}²)", "μ (q·V = 0 for every mode)",
                     f"{ridge['mu']:.1e}", "0", f"{abs(ridge['mu']):.1e}", "—"])
        rows.append(["", "Δ/h against Westergaard with E0",
                     _fmt(ridge["penetration"], 8), _fmt(w.penetration, 8),
                     f"{abs(ridge['penetration'] / w.penetration - 1):.1e} rel.",
                     _fmt((ridge["error_estimate"] or {}).get("penetration"), 2)])
    if obl is not None and obl_ref is not None:
        c, s = math.cos(math.radians(30.0)), math.sin(math.radians(30.0))
        rows.append([f"the same at θ = 30°, V/V0 = 2 ({n}²)",
                     "μ against cos θ μ(θ = 0, V cos θ)", _fmt(obl["mu"], 10),
                     _fmt(c * obl_ref["mu"], 10), f"{abs(obl['mu'] / (c * obl_ref['mu']) - 1):.1e} rel.",
                     "—"])
        rows.append(["", "lateral against sin θ μ(θ = 0, V cos θ)", _fmt(obl["mu_lateral"], 10),
                     _fmt(s * obl_ref["mu"], 10),
                     f"{abs(obl['mu_lateral'] / (s * obl_ref['mu']) - 1):.1e} rel.", "—"])
    if full is not None:
        a = numbers.semi_analytic(4.0, 1.0)
        rows.append([f"bi-sinusoid in full contact, p̃∞ = 4, V/V0 = 1 ({n}²)",
                     "μ against the line's Appendix B (only the mode (1, 0) dissipates)",
                     _fmt(full["mu"], 12), _fmt(a.mu, 12),
                     f"{abs(full['mu'] / a.mu - 1):.1e} rel.", "—"])
    return rows


def _persson(doc, folder, store, n, speeds, plots, png):
    """The BEM on self-affine surfaces (three seeds) beside Persson's theory."""
    curves, rows = [], []
    for p in PERSSON_LOADS:
        c = {"load": p, "speed": [], "persson_mu": [], "persson_cf": []}
        for key in ("mu", "cf"):
            for stat in ("mean", "min", "max"):
                c[f"{key}_{stat}"] = []
        for s in speeds:
            recs = [_record(store, surface_spec(p, s, n, _seeded(k))) for k in SEEDS]
            recs = [r for r in recs if r is not None]
            if not recs:
                continue
            th_mu, th_cf = roads.persson(p, float(s), SELF_AFFINE, RATIO)
            mu = np.array([r["mu"] for r in recs])
            cf = np.array([r["contact_fraction"] for r in recs])
            c["speed"].append(s)
            for key, v in (("mu", mu), ("cf", cf)):
                c[f"{key}_mean"].append(float(v.mean()))
                c[f"{key}_min"].append(float(v.min()))
                c[f"{key}_max"].append(float(v.max()))
            c["persson_mu"].append(th_mu)
            c["persson_cf"].append(th_cf)
            rows.append([f"{p:g}", f"{s:.3g}", _fmt(mu.mean(), 4), _fmt(th_mu, 4),
                         f"{th_mu / mu.mean():.2f}", _fmt(cf.mean(), 4), _fmt(th_cf, 4),
                         f"{th_cf / cf.mean():.2f}"])
        curves.append(c)
    plots.write_persson(png(folder, "surface_persson"), curves)
    doc.img("surface_persson.png",
            "Self-affine surfaces (H = 0.8, roll-off 2k, short cut-off 16k, rms slope 0.2; "
            f"seeds {', '.join(str(k) for k in SEEDS)}; {n} × {n} panels, "
            f"{n / SELF_AFFINE['short_cutoff']:g} panels along the shortest wavelength) at p̃∞ = "
            f"{', '.join(f'{p:g}' for p in PERSSON_LOADS)}: the BEM's μ and contact fraction "
            "(mean over the seeds; bars: their range) beside Persson's theory with the "
            "contact-area correction (analytic.references.persson, docs/persson.md), which "
            "sees the spectrum, not the realisation.")
    doc.table(["p̃∞", "V/V0", "μ, BEM (mean)", "μ, Persson", "Persson/BEM",
               "contact, BEM", "contact, Persson", "Persson/BEM"], rows)
    doc.p("Persson's theory is the field's standard approximation, not a truth: it is a "
          "mean-field theory of an infinite random surface, here compared with the exact "
          "steady state of a few periodic realisations. The table says where the two agree "
          "and by how much they part (ratios per point).")
