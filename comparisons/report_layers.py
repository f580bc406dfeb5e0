"""The report's layer section: μ and the contact against V/V0 per thickness and foundation, and
the full-contact load against d/λ (`layers_section`, on the numbers of
`comparisons.report_numbers`: `layer_sweeps`, `layer_full_contact`, `layer_findings`).  Part of
`comparisons.report`, which re-exports it.
"""
from __future__ import annotations

import math
import time

from . import report_numbers as numbers
from .report_doc import _fmt, _png, _reldiff
from .report_numbers import HK, RATIO

def _worst(values):
    """The largest of the finite numbers among ``values`` (None when there is none)."""
    v = [abs(x) for x in values if x is not None and math.isfinite(x)]
    return max(v) if v else None


def layers_section(doc, folder, store, cfg, timings):
    """The viscoelastic layer of thickness d on a rigid foundation (`bem.solve(layer=...)`):
    μ and 2a/λ against V/V0 per thickness and foundation, and the full-contact load against d/λ,
    closed form and BEM; ``timings`` gains the section's runs and its figures and tables."""
    from .plots import layers
    t0 = time.monotonic()
    sweeps = numbers.layer_sweeps(store, cfg)
    fc = numbers.layer_full_contact(store, cfg)
    curves = sweeps["curves"]
    every = [c for f in curves for c in curves[f]]
    mu_err = _worst(e for c in every for e in c["mu_error"])
    cf_err = _worst(e for c in every for e in c["contact_fraction_error"])
    no_est = sum(e is None for c in every for e in c["mu_error"])
    failed = sum(len(c["failed"]) for c in every)
    nu, load = sweeps["nu"], sweeps["load"]
    half = next(c for c in curves["bonded"] if c["d_over_lambda"] is None)
    thick = {f: next(c for c in curves[f] if c["d_over_lambda"] == 1.0) for f in curves}
    half_mu = dict(zip(half["speed"], half["mu"]))
    thick_diff = {f: _worst(m / half_mu[s] - 1.0 for s, m in zip(thick[f]["speed"], thick[f]["mu"])
                            if s in half_mu) for f in thick}
    s_of = {f: {q["d_over_lambda"]: fc["curves"][f][0]["half_space"] / q["closed_form"]
                for q in fc["curves"][f][0]["markers"]} for f in fc["curves"]}
    doc.p(f"A layer of thickness d of the same standard linear solid (E∞/E0 = {RATIO:g}) lies on "
          "a rigid foundation, either bonded to it or sliding on it without friction; the "
          f"sinusoid (hk = {HK:g}) slides over its top face at p̃∞ = {load:g}, the load of figure "
          "12's middle curve. Only the BEM road solves it (`bem.solve(layer=bem.Layer(...))`, "
          "reached through `comparisons.roads`): mode n of its operator is the half-space's times "
          "the layer factor S(|n|kd, ν) of `docs/layers.md`, S → 1 as kd → ∞ and, for a thin "
          "layer, S_B ≈ (2/3)(kd)³ (bonded, ν = ½: the squeezed film) and S_F ≈ kd/2 "
          f"(frictionless). Bonded layers have ν = {nu:g}. A frictionless layer's answer does not "
          "depend on ν in these units (p̃ = p(1 − ν²)/E0): S_F does not, nor its uniform "
          "compression under the mean pressure (free ends, C = 1); it is run at "
          f"ν = {nu:g} too. The panels start at different thicknesses: at p̃∞ = {load:g} a "
          "frictionless layer is also compressed as a whole, by the strain p̃∞, and below "
          "d/λ ≈ 0.15 the indenter's crest would then reach the foundation at low speeds (the "
          "BEM refuses such an answer: approach·h ≥ d).")
    layers.write_friction(_png(folder, "layers_mu"), sweeps)
    est = ("" if mu_err is None else
           f"; the BEM's estimated error of μ, at most {mu_err:.1e} relative over every point")
    doc.img("layers_mu.png",
            f"Friction coefficient μ against V/V0 at p̃∞ = {load:g} on layers of thickness d "
            f"(E∞/E0 = {RATIO:g}, hk = {HK:g}); BEM on a fixed mesh of N = {cfg.nodes} panels, "
            f"{len(cfg.layer_speeds)} speeds{est}. Black: the half-space, the report's own runs "
            "and figure 12's semi-analytic curve.")
    layers.write_contact(_png(folder, "layers_contact"), sweeps)
    est = ("" if cf_err is None else
           f"; the BEM's estimated error of 2a/λ, at most {cf_err:.1e} (relative)")
    doc.img("layers_contact.png",
            f"Contact fraction 2a/λ against V/V0 at p̃∞ = {load:g}, the same runs{est}. Black: "
            "the half-space (semi-analytic line: ka/π).")
    doc.p("The half-space curve is the report's own: its BEM circles are the same runs (the same "
          f"specs, the same stored results) as figure 12's markers at p̃∞ = {load:g}, with "
          f"{len(cfg.layer_speeds) - len(cfg.speeds_bem)} more speeds between them on the same "
          f"mesh, and its line is figure 12's semi-analytic curve, from which the BEM's μ differs "
          f"by at most {_fmt(sweeps['half_space_mu'], 2)} relative. The thickest layers, "
          f"d/λ = 1 (kd = 2π, S = {_fmt(s_of['bonded'][1.0], 7)} bonded and "
          f"{_fmt(s_of['frictionless'][1.0], 7)} frictionless), differ from the half-space's μ by "
          f"at most {_fmt(thick_diff['bonded'], 2)} (bonded) and "
          f"{_fmt(thick_diff['frictionless'], 2)} (frictionless) relative; from kd = 25 on the "
          "BEM's answer is the half-space's bit for bit (`tests/comparisons/test_report_layers.py` runs "
          "such a spec through this section's route)."
          + (f" {no_est} points have no error estimate (a layer thinner than the estimate "
             "trusts on this mesh)." if no_est else "")
          + (f" {failed} runs failed and are missing." if failed else ""))
    peak_a = sweeps["analytic"]["peak"]
    doc.table(["foundation", "d/λ", "S(kd) = p̃FC,half/p̃FC", "largest μ", "at V/V0",
               "μ at V/V0 = 0.01", "μ at V/V0 = 1", "μ at V/V0 = 100", "2a/λ at V/V0 = 0.01",
               "2a/λ at V/V0 = 1", "2a/λ at V/V0 = 100"],
              _layer_rows(curves, s_of) + [
                  ["half-space", "semi-analytic", "1", _fmt(peak_a[1], 5), _fmt(peak_a[0], 4)]
                  + [_fmt(numbers.semi_analytic(load, v).mu, 5) for v in (0.01, 1.0, 100.0)]
                  + [_fmt(numbers.semi_analytic(load, v).ka / math.pi, 4)
                     for v in (0.01, 1.0, 100.0)]])
    doc.p("The largest μ and its speed are the vertex of the parabola in (log V, log μ) through "
          f"the largest sampled μ and its two neighbours ({len(cfg.layer_speeds)} speeds over "
          "four decades); on the half-space the BEM's is off the semi-analytic road's peak (last "
          f"row) by {_reldiff(half['peak'][1], peak_a[1])} in μ and "
          f"{_reldiff(half['peak'][0], peak_a[0])} in V/V0 (relative).")
    layers.write_full_contact(_png(folder, "layers_full_contact"), fc)
    rel = [q["bem"] / q["closed_form"] - 1.0 for f in fc["curves"] for c in fc["curves"][f]
           for q in c["markers"] if q["bem"] is not None]
    rel1 = [q["bem_hk1"] / q["closed_form"] - 1.0 for f in fc["curves"]
            for c in fc["curves"][f] for q in c["markers"] if q["bem_hk1"] is not None]
    doc.img("layers_full_contact.png",
            "Full-contact load p̃FC against d/λ at V/V0 = "
            f"{', '.join(f'{s:g}' for s in numbers.LAYER_FC_SPEEDS)}: lines, the closed form "
            "(Appendix B, mode 1 carrying 1/S(kd)); dashed, the half-space's p̃FC. Crosses: the "
            f"BEM's load at Δ/h = 1 (N = {cfg.nodes}) at hk = {numbers.LAYER_FC_HK:g}, times "
            f"{HK / numbers.LAYER_FC_HK:g} (full contact is linear in the amplitude); circles: "
            f"at hk = {HK:g}. They differ from the closed form by at most "
            f"{_fmt(_worst(rel + rel1), 2)} relative. Dotted: where, at hk = {HK:g}, the "
            "indenter's crest would reach the foundation in full contact (approach·h ≥ d: a "
            "bonded incompressible layer thinner than h = λ/2π, a frictionless one where "
            "kd(1 − p̃FC) ≤ hk); linear theory goes on, the body does not.")
    doc.table(["foundation", "d/λ", "p̃FC at V/V0 = 1, closed form", "BEM (hk scaled)",
               "BEM − closed form (rel.)", f"BEM at hk = {HK:g}", f"full contact at hk = {HK:g}"],
              _full_contact_rows(fc))
    find = numbers.layer_findings(sweeps, fc)
    doc.p(_findings_text(find, load))
    doc.p("The runs are in the results store like every other (one file each, written as it is "
          "done: an interrupted report keeps them and `--resume` does not repeat them).")
    seconds = sum(store.get(spec).get("seconds") or 0.0
                  for spec, _ in numbers.layer_runs(cfg.nodes, cfg.layer_speeds))
    timings["layer section: runs (sum over processes)"] = seconds
    timings["layer section: figures and tables"] = time.monotonic() - t0


def _findings_text(find, load):
    """The layer section's reading of its own numbers (`report_numbers.layer_findings`)."""
    parts = []
    for f, t in find["thinnest"].items():
        (vt, mt), (vh, mh) = t["peak"], t["half_space_peak"]
        lo, hi = t["contact_ratio"]
        cross = ("" if t["crossing"] is None else
                 f"; below V/V0 ≈ {t['crossing']:.2g} its μ is the larger ({t['mu_ratio_low']:.3g} "
                 f"times the half-space's at the lowest speed), above it the smaller "
                 f"({t['mu_ratio_high']:.3g} times at the highest)")
        parts.append(f"the thinnest {f} layer (d/λ = {t['d_over_lambda']:g}) peaks at μ = "
                     f"{mt:.3g} at V/V0 = {vt:.3g}, the half-space at μ = {mh:.3g} at V/V0 = "
                     f"{vh:.3g}{cross}; its contact is {lo:.2f}–{hi:.2f} times the "
                     "half-space's")
    ex = find["exponent"]
    return (f"Read from these numbers (p̃∞ = {load:g}): a layer is stiffer than the half-space on "
            "every mode (S < 1), the more so the thinner it is and the bonded incompressible one "
            "most, so that at a fixed load its contact is narrower, its friction peak lower and "
            "at a lower speed (as if the frequency that matters were V/a: a narrower contact "
            "reaches it at a lower speed). " + "; ".join(parts)[0].upper()
            + "; ".join(parts)[1:] + ". At the same thickness the frictionless layer is softer "
            "than the bonded one (S_F > S_B) and stays closer to the half-space. The full-contact "
            "load is the half-space's divided by S(kd) at every speed (the BEM's, over the "
            "half-space's, varies with the speed by at most "
            f"{max(find['speed_spread'].values()):.1e} relative at one thickness: mode 1 alone "
            "carries full contact), so it "
            f"rises as the layer thins like d^−{ex['bonded']:.2f} for the bonded layer between "
            "the two thinnest markers (the squeezed film's S_B ≈ (2/3)(kd)³) and like "
            f"d^−{ex['frictionless']:.2f} for the frictionless one (S_F ≈ kd/2).")


def _layer_rows(curves, s_of):
    """Per foundation and thickness (the half-space once, the BEM's): S(kd), the friction peak,
    and μ and 2a/λ at V/V0 = 0.01, 1 and 100."""
    rows = []
    for f, cs in curves.items():
        for c in cs:
            d = c["d_over_lambda"]
            if d is None and f != "bonded":
                continue  # the same runs in every panel
            at = dict(zip(c["speed"], zip(c["mu"], c["contact_fraction"])))
            pts = [at.get(v) for v in (0.01, 1.0, 100.0)]
            rows.append([f if d is not None else "half-space", "BEM" if d is None else f"{d:g}",
                         "1" if d is None else _fmt(s_of[f].get(d), 5),
                         _fmt(c["peak"][1], 5), _fmt(c["peak"][0], 4)]
                        + ["—" if p is None else _fmt(p[0], 5) for p in pts]
                        + ["—" if p is None else _fmt(p[1], 4) for p in pts])
    return rows


def _full_contact_rows(fc):
    """Per foundation and marker thickness: p̃FC at V/V0 = 1, closed form and BEM."""
    rows = []
    for f, cs in fc["curves"].items():
        c = next(c for c in cs if c["speed"] == 1.0)
        for q in c["markers"]:
            clears = numbers.full_contact_clears(q["d_over_lambda"], f, q["closed_form"])
            rows.append([f, f"{q['d_over_lambda']:g}", _fmt(q["closed_form"], 8),
                         _fmt(q["bem"], 8), _reldiff(q["bem"], q["closed_form"]),
                         _fmt(q["bem_hk1"], 8),
                         "yes" if clears else "no: the crest would reach the foundation"])
    return rows
