"""The benchmark suite exported as plain files, and its summary tables.

    python -m comparisons suite --export DIR [--cases NAME ...]
    python -m comparisons suite --list [--cases NAME ...]

`export` writes one folder per case (``inputs.json``, ``prony.txt``, ``profile.csv``,
``scalars.json``, ``scalars.csv``, ``fields.csv``, ``material.png`` for a Prony material and the
original material file) and ``README.md`` and ``index.json`` for the suite, from what
``suite.json`` certifies (:mod:`comparisons.suite`); it computes nothing.  `summary_table` is the
table of certified digits that ``--list`` prints and the README shows.
"""
from __future__ import annotations

import csv
import io
import json
import math
import shutil
from pathlib import Path

from . import operating_point as op
from . import roads as _roads
from ._io import write_text
from .fields import PATCH_KEYS
from .plots.materials import prony_numbers
from .plots.suite import material_png
from .suite import (FORM_NAMES, SURFACE_REFERENCES, SURFACE_RULE, case_material, is_surface,
                    load_suite, reference_of, select, surface_references, two_roads)
from .suite_inputs import DATA

#: the files an exported case folder writes itself (a copied material file never takes one)
EXPORT_FILES = ("inputs.json", "prony.txt", "profile.csv", "scalars.json", "scalars.csv",
                "fields.csv", "material.png")
#: the files of an exported surface case's folder
SURFACE_EXPORT_FILES = ("inputs.json", "prony.txt", "surface.csv", "scalars.json", "scalars.csv",
                        "fields.npz")


def _source_name(point) -> str:
    """The name under which an export copies a case's original material file."""
    name = Path(point["material"]).name
    return name if name not in EXPORT_FILES else "source-" + name


def _prony_text(point) -> str:
    if point.get("prony"):
        return (DATA / point["prony"]).read_text(encoding="utf-8")
    if point.get("material"):
        m = case_material(point)
        info, pr = m.info, m.prony
        name = Path(point["material"]).name
        copied = "copied alongside" + ("" if _source_name(point) == name
                                       else f" as {_source_name(point)}")
        lines = [f"# creep series converted from {name} ({copied}): a "
                 f"{FORM_NAMES[info['form']]}, sha256 {info['sha256']}",
                 "# converted by comparisons._materials.read (relaxation series: exactly; DMA "
                 "curve: its Prony fit, then exactly)"]
        if info.get("fit"):
            f = info["fit"]
            lines.append(f"# DMA fit: {f['per_decade']:g} relaxation times per decade, largest "
                         f"relative residual {f['max_residual']:.3g}"
                         + (f" (bound {f['bound']:g})" if f.get("bound") is not None else "")
                         + ", "
                         f"measured window {f['window'][0]:.4g}..{f['window'][1]:.4g} rad/s"
                         + (" (shifted to the temperature below)"
                            if info.get("temperature") is not None else ""))
        if info.get("temperature") is not None:
            sh = info["shift"]
            lines.append(f"# at temperature {info['temperature']:g} (WLF C1 = {sh['C1']:g}, "
                         f"C2 = {sh['C2']:g}, T_ref = {sh['T_ref']:g}: log10 a_T = "
                         f"{info['log10_aT']:.6g}; every time multiplied by a_T)")
        lines.append(f"# J(t) = J0 - sum_i J_i exp(-t/tau_i), {len(pr.J)} terms; compliances in "
                     f"1/E_ref, E_ref = {info['E_ref_is']} = {info['E_ref']!r}; retardation "
                     f"(creep) times in tau_ref, tau_ref = {info['tau_ref_is']}")
        lines.append(f"J0 {float(pr.J0)!r}")
        lines += [f"{float(j)!r} {float(t)!r}" for j, t in zip(pr.J, pr.tau)]
        return "\n".join(lines) + "\n"
    r = op.ratio_of(point)
    return ("# standard linear solid, E_inf/E0 = %r: J(t) = J0 - J1 exp(-t/tau)\n"
            "# compliances in 1/E0, times in the creep time tau\n"
            "J0 1.0\n%r 1.0\n" % (r, 1.0 - 1.0 / r))


def _profile_text(point) -> str:
    if point.get("profile"):
        return (DATA / point["profile"]).read_text(encoding="utf-8")
    hk = op.hk_of(point)
    m = 64  # the trigonometric interpolant of 64 samples is exactly hk cos(2 pi x)
    lines = [f"# sinusoid k*y = {hk!r} cos(2 pi x/lambda), sampled at x/lambda = j/{m} - 1/2",
             "x_over_lambda,ky"]
    lines += [f"{j / m - 0.5!r},{hk * math.cos(2 * math.pi * (j / m - 0.5))!r}" for j in range(m)]
    return "\n".join(lines) + "\n"


def _inputs(case, suite) -> dict:
    p = case["point"]
    d = {"name": case["name"], "title": case["title"], "suite_version": suite["version"],
         "control": "load" if p.get("load") is not None else "penetration"}
    d.update(_roads.point_controls(p))
    d["speed"] = float(p["speed"])
    if p.get("profile"):
        text = (DATA / p["profile"]).read_text(encoding="utf-8")
        about = " ".join(ln.lstrip("# ").strip() for ln in text.splitlines() if ln.startswith("#"))
        d["profile"] = {"kind": "samples (trigonometric interpolant)", "file": "profile.csv",
                        "description": about}
    else:
        d["profile"] = {"kind": "sinusoid", "hk": op.hk_of(p), "file": "profile.csv"}
    units = ("load = p (1 - nu^2)/E_ref; speed = V tau_ref k; lengths in wavelengths "
             "(x/lambda, crest at 0, sliding toward +x), heights k*y; compliances in "
             "1/E_ref, times in tau_ref")
    if p.get("prony"):
        d["material"] = {"kind": "prony", "file": "prony.txt", "figure": "material.png"}
    elif p.get("material"):
        info = case_material(p).info
        d["material"] = {"kind": FORM_NAMES[info["form"]],
                         "file": "prony.txt",
                         "file_is": "the creep series the BEM solves, converted from source_file",
                         "source_file": _source_name(p), "source_sha256": info["sha256"],
                         "E_ref": info["E_ref"], "E_ref_is": info["E_ref_is"],
                         "tau_ref_is": info["tau_ref_is"],
                         "terms": info["terms"], "temperature": info["temperature"],
                         "shift": info["shift"], "log10_aT": info["log10_aT"],
                         "fit": info["fit"], "figure": "material.png"}
        units += f" (E_ref = {info['E_ref_is']}; tau_ref = {info['tau_ref_is']})"
    else:
        d["material"] = {"kind": "standard linear solid", "ratio": op.ratio_of(p),
                         "file": "prony.txt"}
    if not p.get("material"):
        units += " (E_ref = E0, tau_ref = tau: the creep time)"
    if p.get("layer"):
        units += ("; on a layer, approach and mean_displacement over h, the layer's thickness "
                  "as d/lambda and k d (k = 2 pi/lambda)")
    d["units"] = units
    if p.get("layer"):
        d["layer"] = layer_inputs(case)
    if two_roads(p):
        d["reference_road"] = "semi-analytic (two roads agree)"
    elif reference_of(case) == "fourier":
        d["reference_road"] = ("BEM (convergence study), checked against the independent "
                               "Fourier-collocation reference analytic.fourier_solve (the digits "
                               "both agree on)" + (", solved on the same layer"
                                                   if p.get("layer") else ""))
    else:
        d["reference_road"] = "BEM (convergence study)"
    return d


#: what a case's layer is, its surface compliance and the approach (inputs.json, README.md)
LAYER_DEFINITION = (
    "a layer of thickness d in place of the half-plane, its top face under the indenter (the "
    "contact pressure, no shear) and its lower face on a rigid foundation: bonded "
    "(u_x = u_z = 0 there) or frictionless (u_z = 0 and no shear there); plane strain, Poisson "
    "ratio nu constant in time (only E depends on the frequency). Mode n of the surface "
    "compliance is the half-space's times the layer factor S(|n| k d, nu): with q = exp(-2t), "
    "kappa = 3 - 4 nu, bonded S = [kappa (1 - q^2) - 4 t q] / [kappa (1 + q^2) + "
    "(1 + kappa^2 + 4 t^2) q], frictionless S = (1 - q)^2 / [(1 - q^2) + 4 t q] (docs/layers.md "
    "of viscosine)")
APPROACH_DEFINITION = (
    "Delta is measured from the mean line of the deformed surface, as on the half-space "
    "(penetration = Delta/h = 1 - s/h, s the mean gap). The layer also compresses as a whole "
    "under the mean pressure: its mean line sinks by v0/h = C (k d) J0 p/hk (mean_displacement; "
    "J0 the relaxed compliance J(t -> inf) in 1/E_ref, the mean pressure being static in the "
    "frame of the indenter; C = (1 - 2 nu)/(1 - nu)^2 bonded, C = 1 frictionless with the "
    "layer's ends free). approach = Delta/h + v0/h is the indenter crest's depth below the "
    "undeformed top face, over h; it stays below d/h = k d/hk (the cases are well clear of it)")


def layer_inputs(case) -> dict:
    """The layer block of a case's ``inputs.json``: d/λ and k d (and over h), the foundation,
    ν, the uniform compliance C, the layer factor of mode 1, the definitions a third code needs
    (`LAYER_DEFINITION`, `APPROACH_DEFINITION`) and, under load control, the exact mean
    compression (as ``scalars.json`` lists it)."""
    p = case["point"]
    lay = _roads.layer(p["layer"])
    out = {"thickness_over_wavelength": float(lay.thickness_over_wavelength),
           "thickness_kd": float(lay.thickness),
           "foundation": lay.foundation, "nu": float(lay.nu),
           "uniform_compliance_C": float(lay.uniform),
           "layer_factor_mode_1": float(lay.factor([1.0])[0]),
           "definition": LAYER_DEFINITION, "approach": APPROACH_DEFINITION}
    if not p.get("profile"):
        out["thickness_over_h"] = float(lay.thickness) / op.hk_of(p)
    mean = case["certified"]["exact"].get("mean_displacement")
    if mean is not None:
        out["mean_displacement"] = mean
    return out


def layer_text(point) -> str:
    """A case's layer in a few words (``--list``, README.md): ``half-plane`` without one (a
    surface case's: ``half-space``, its thickness over Lx)."""
    surface = is_surface(point)
    if not point.get("layer"):
        return "half-space" if surface else "half-plane"
    lay = _roads.layer(point["layer"])
    return (f"layer d/{'Lx' if surface else 'λ'} = {lay.thickness_over_wavelength:g} "
            f"(kd = {lay.thickness:.4g}), {lay.foundation}, ν = {lay.nu:g}")


def _scalar_rows(cert):
    rows = []
    for k, r in cert["scalars"].items():
        rows.append(["", k, r["value"], r["digits"], r["rounded"], r["error"], r["method"]])
    for k, v in cert["exact"].items():
        rows.append(["", k, v, "exact", "" if v is None else repr(v), 0.0, "exact"])
    for j, p in enumerate(cert["patches"], 1):
        for k in PATCH_KEYS:
            r = p[k]
            rows.append([j, k, r["value"], r["digits"], r["rounded"], r["error"], r["method"]])
    return rows


def export(folder, names=(), suite=None):
    """Write the suite as plain CSV/JSON, one folder per case plus ``README.md`` and ``index.json``.

    Returns the list of case folders written.
    """
    suite = suite or load_suite()
    cases = select(suite, names)
    folder = Path(folder)
    written = []
    for case in cases:
        d = folder / case["name"]
        cert = case["certified"]
        if is_surface(case):
            _export_surface(d, case, suite)
            written.append(d)
            continue
        write_text(d / "inputs.json", json.dumps(_inputs(case, suite), indent=1,
                                                    ensure_ascii=False) + "\n")
        write_text(d / "prony.txt", _prony_text(case["point"]))
        if case["point"].get("material"):  # the file as the user would hold it
            shutil.copyfile(DATA / case["point"]["material"], d / _source_name(case["point"]))
        if case["point"].get("prony") or case["point"].get("material"):
            _material_png(d / "material.png", case)
        write_text(d / "profile.csv", _profile_text(case["point"]))
        sc = {"case": case["name"], "status": cert["status"], "notes": cert["notes"],
              "method": cert["method"],
              "scalars": {k: {kk: r[kk] for kk in ("value", "digits", "rounded", "error", "method")}
                          for k, r in cert["scalars"].items()},
              "exact": cert["exact"],
              "patches": [{k: {kk: p[k][kk] for kk in ("value", "digits", "rounded", "error")}
                           for k in PATCH_KEYS} for p in cert["patches"]],
              "fields": {"file": "fields.csv", "grid": cert["fields"]["grid"],
                         "max_error": cert["fields"]["max_error"]}}
        write_text(d / "scalars.json", json.dumps(sc, indent=1, ensure_ascii=False) + "\n")
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["patch", "quantity", "value", "certified_digits", "rounded", "error_bound",
                    "method"])
        for row in _scalar_rows(cert):
            w.writerow(["" if v is None else (repr(v) if isinstance(v, float) else v) for v in row])
        write_text(d / "scalars.csv", buf.getvalue())
        shutil.copyfile(DATA / cert["fields"]["file"], d / "fields.csv")
        written.append(d)
    index = {"suite_version": suite["version"], "description": suite["description"],
             "rule": suite["rule"], "cases": [c["name"] for c in cases]}
    write_text(folder / "index.json", json.dumps(index, indent=1, ensure_ascii=False) + "\n")
    write_text(folder / "README.md", _index_readme(suite, cases))
    return written


def _surface_text(point) -> str:
    """``surface.csv``: the surface's harmonics, exactly (every surface of the suite is
    band-limited; a self-affine one is its seeded synthesis)."""
    heights, aspect = _roads.surface_harmonics(point["surface"])
    amp = float(_roads.surface(point["surface"]).amplitude)
    desc = ", ".join(f"{k} = {v!r}" for k, v in point["surface"].items() if v is not None)
    lines = [f"# surface: {desc}",
             "# k z(x, y) = sum over the rows of Re[c exp(2 pi i (m x + n y/aspect))], c = re + "
             "i im; x, y over Lx (the crest of the bi-sinusoid at the origin), k = 2 pi/Lx",
             f"# aspect Ly/Lx = {aspect!r}; k h_ref = max k z - mean k z = {amp!r}",
             "m,n,re,im"]
    lines += [f"{m},{n},{c.real!r},{c.imag!r}" for (m, n), c in sorted(heights.items())]
    return "\n".join(lines) + "\n"


def _surface_inputs(case, suite) -> dict:
    """A surface case's ``inputs.json``: the operating point, the surface, the material, the
    layer, the units and the second opinions that certify it."""
    p = case["point"]
    d = {"name": case["name"], "title": case["title"], "suite_version": suite["version"],
         "geometry": "surface", "control": "load" if p.get("load") is not None else "penetration"}
    d.update(_roads.point_controls(p))
    d["speed"] = float(p["speed"])
    d["direction"] = op.direction_of(p)
    d["surface"] = dict({k: v for k, v in p["surface"].items() if v is not None},
                        file="surface.csv",
                        amplitude_k_h_ref=float(_roads.surface(p["surface"]).amplitude))
    d["material"] = {"kind": "standard linear solid", "ratio": op.ratio_of(p),
                     "file": "prony.txt"}
    d["units"] = ("load = p (1 - nu^2)/E0, the mean pressure over the cell; speed = V tau k, "
                  "k = 2 pi/Lx; direction theta in degrees from +x, counter-clockwise; "
                  "positions over Lx, heights k z; penetration = Delta/h_ref, h_ref = max z - "
                  "mean z; mu along V, mu_lateral the force the solid exerts on the surface "
                  "along (-sin theta, cos theta) over the load; pressure sigma (1 - nu^2)/E0; "
                  "displacement and gap over h_ref (E_ref = E0, tau_ref = tau: the creep time)")
    if p.get("layer"):
        lay = _roads.layer(p["layer"])
        d["layer"] = {"thickness_over_Lx": float(lay.thickness_over_wavelength),
                      "thickness_kd": float(lay.thickness), "foundation": lay.foundation,
                      "nu": float(lay.nu), "uniform_compliance_C": float(lay.uniform),
                      "definition": SURFACE_LAYER_DEFINITION}
    refs = surface_references(case)
    d["reference_road"] = ("; ".join(SURFACE_REFERENCES[r] for r in refs) if refs else
                           "none independent: the surface BEM's convergence study alone")
    return d


#: what a surface case's layer is (its inputs.json)
SURFACE_LAYER_DEFINITION = (
    "a layer of thickness d in place of the half-space, its top face under the surface (the "
    "contact pressure, no shear), its lower face on a rigid foundation, bonded or frictionless; "
    "Poisson ratio nu constant in time. A pressure mode of wave vector q (|q| in k = 2 pi/Lx) "
    "is the layer's plane-strain mode along q: its compliance is the half-space's times the "
    "line's layer factor S(|q| k d, nu) (docs/layers.md and docs/surfaces.md §1.2 of "
    "viscosine). The penetration and the displacement are measured from the mean plane of the "
    "deformed surface, as on the half-space")


def _export_surface(d, case, suite):
    """One surface case's folder (SURFACE_EXPORT_FILES) from what ``suite.json`` certifies."""
    cert = case["certified"]
    write_text(d / "inputs.json", json.dumps(_surface_inputs(case, suite), indent=1,
                                             ensure_ascii=False) + "\n")
    write_text(d / "prony.txt", _prony_text(case["point"]))
    write_text(d / "surface.csv", _surface_text(case["point"]))
    sc = {"case": case["name"], "status": cert["status"], "notes": cert["notes"],
          "method": cert["method"],
          "scalars": {k: {kk: r[kk] for kk in ("value", "digits", "rounded", "error", "method")}
                      for k, r in cert["scalars"].items()},
          "exact": cert["exact"],
          "fields": {"file": "fields.npz", "grid": cert["fields"]["grid"],
                     "max_error": cert["fields"]["max_error"]}}
    write_text(d / "scalars.json", json.dumps(sc, indent=1, ensure_ascii=False) + "\n")
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["quantity", "value", "certified_digits", "rounded", "error_bound", "method"])
    for k, r in cert["scalars"].items():
        w.writerow([k, repr(r["value"]), r["digits"], r["rounded"], r["error"], r["method"]])
    for k, v in cert["exact"].items():
        w.writerow([k, repr(v), "exact", repr(v), 0.0, "exact"])
    write_text(d / "scalars.csv", buf.getvalue())
    shutil.copyfile(DATA / cert["fields"]["file"], d / "fields.npz")


def _material_png(path, case):
    """The material figure of a case with a Prony material: its creep series as the BEM solves
    it, drawn by `comparisons.plots.suite.material_png`."""
    point = case["point"]
    if point.get("prony"):
        j0, terms = prony_numbers(DATA / point["prony"])
        source = Path(point["prony"]).name
    else:  # the creep series converted from the material file, as the BEM solves it
        pr = case_material(point).prony
        j0, terms = float(pr.J0), [(float(j), float(t)) for j, t in zip(pr.J, pr.tau)]
        source = Path(point["material"]).name + (f" at T = {point['temperature']:g}"
                                                  if point.get("temperature") is not None else "")
    material_png(path, case["name"], source, j0, terms, float(point["speed"]))


def summary_table(cases) -> str:
    """The Markdown table of `summary_rows` (`suite --list`, the exported README)."""
    from ._html import table
    return table(["case", "title", "body", "μ digits", "Δ/h digits", "certified by"],
                 summary_rows(cases))


def summary_rows(cases):
    """(case, title, body: the half-plane or the layer, μ digits, Δ/h or load digits, how) for
    each case."""
    rows = []
    for c in cases:
        cert = c["certified"]
        sc = cert["scalars"]
        if "penetration" in sc:
            second = str(sc["penetration"]["digits"])
        elif "load" in sc:  # penetration control: Δ/h is the input, the load is certified
            second = f"input ({sc['load']['digits']} in the load)"
        else:
            second = "exact (full contact)"
        rows.append([c["name"], c["title"], layer_text(c["point"]), str(sc["mu"]["digits"]),
                     second,
                     cert["method"] + ("" if cert["status"] == "complete"
                                       else f" — {cert['status']}")])
    return rows


def _index_readme(suite, cases) -> str:
    out = [f"# viscosine benchmark suite, version {suite['version']}", "",
           suite["description"], "",
           "Each folder is one case:", "",
           "- `inputs.json`: the operating point (load or penetration control, speed) and what "
           "the indenter and the material are, in the units stated there (and, for a case on a "
           "layer, `layer`: its thickness as d/λ and k d, its foundation, ν and the definitions "
           "below);",
           "- `profile.csv`: the indenter, k·y at x/λ = j/M − 1/2 (columns `x_over_lambda,ky`; "
           "the profile is the trigonometric interpolant of the samples);",
           "- `prony.txt`: the creep function, a line `J0 value` then one line `J_i tau_i` per "
           "term, J(t) = J0 − Σ J_i exp(−t/τ_i), compliances in 1/E_ref, retardation (creep) "
           "times in τ_ref; a case whose material is a relaxation series or a DMA master curve "
           "(`inputs.json` says which, at which temperature) gets the creep series it was "
           "converted to, its header naming the original file (copied alongside) and its "
           "SHA-256;",
           "- `scalars.json` and `scalars.csv`: every certified value with its certified "
           "significant digits, the value rounded to them, and the error bound behind them;",
           "- `fields.csv`: pressure, displacement and gap on a stated grid, each with its "
           "certified absolute error (`<column>_err`);",
           "- `material.png` (cases with a Prony material): the storage and loss moduli E′, E″ "
           "and the loss tangent of `prony.txt` against frequency, with the case's sliding "
           "frequency ω = kV (ωτ_ref = V/V0) marked.", "",
           "Quantities (keys of `scalars.json`): `mu` (μ = τf/p∞), `tau_f` (τf(1 − ν²)/E0), "
           "`penetration` (Δ/h), `separation` (s/h = 1 − Δ/h, the mean gap), `load` (p̃∞, "
           "certified under penetration control), `contact_fraction` (2a/λ), `ka`, `ke`, "
           "`ke_hat` (one patch or full contact); with several patches, per patch: `summit` "
           "(x/λ of the highest profile point in the patch), `trailing_edge`, `leading_edge` "
           "(x/λ), `load` (its share of p̃∞), `ka`, `ke`, `ke_hat`; on a layer also `approach` "
           "and, under penetration control, `mean_displacement` (below). `exact` lists what "
           "holds by construction (full contact: ka = π, Δ/h = 1, s = 0; the input Δ/h; on a "
           "layer under load control its `mean_displacement`, and in full contact the "
           "`approach`).", "",
           "Units and signs: pressure σ(1 − ν²)/E0 (positive in compression), displacement v/h "
           "(positive into the body, from the mean line of the deformed surface), gap/h; "
           "x/λ with the crest at 0 and the indenter sliding toward +x; μ = τf/p∞ with τf "
           "positive when it resists; ka, ke, kê in radians (per patch measured from the "
           "patch's summit).", "",
           *_layers_section(cases),
           "## How the digits are certified", "", suite["rule"], "",
           *_surfaces_section(suite, cases),
           "## Cases", "",
           summary_table(cases),
           *_materials_list(cases),
           "Cite: Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (the "
           "problem and the semi-analytic method).", ""]
    return "\n".join(out)


def _surfaces_section(suite, cases):
    """README lines on the surface cases (none without one): their files and how they are
    certified."""
    if not any(is_surface(c) for c in cases):
        return []
    return ["## Surfaces", "",
            "A case whose `inputs.json` says `\"geometry\": \"surface\"` is a rigid periodic "
            "surface z(x, y) sliding at the speed V in the direction θ over the half-space (or a "
            "layer): three-dimensional contact. Its folder holds `inputs.json`, `prony.txt`, "
            "`surface.csv` (the surface's harmonics, exactly), `scalars.json`, `scalars.csv` "
            "(mu, mu_lateral, penetration = Δ/h_ref, contact_fraction, and what is exact) and "
            "`fields.npz` (the arrays `x`, `y`, `pressure`, `displacement`, `gap` of the "
            "conventions, each with `<column>_err`, its certified absolute error, and the "
            "scalars `load`, `speed`, `direction`; read it with `numpy.load`).", "",
            suite.get("surface_rule", SURFACE_RULE), ""]


def _layers_section(cases):
    """README lines on the layer cases (none without one): what a layer is, how Δ/h and the
    approach are measured, and each case's layer."""
    layered = [c for c in cases if c["point"].get("layer")]
    if not layered:
        return []
    out = ["## Layers", "",
           "A case with `layer` in its `inputs.json` solves " + LAYER_DEFINITION + ".", "",
           "The scalars keep their meaning on a layer: " + APPROACH_DEFINITION + ".", ""]
    for c in layered:
        lay = layer_inputs(c)
        mean = lay.get("mean_displacement")
        out.append(f"- {c['name']}: d/λ = {lay['thickness_over_wavelength']:g}, "
                   f"k d = {lay['thickness_kd']!r}, {lay['foundation']}, "
                   f"ν = {lay['nu']:g}, C = {lay['uniform_compliance_C']:.6g}, "
                   f"S(k d) = {lay['layer_factor_mode_1']:.6g}"
                   + ("" if mean is None else f", mean_displacement = {mean!r} (exact)"))
    return out + [""]


def _materials_list(cases):
    """README lines linking the material figure of each Prony case (none without one)."""
    prony = [c for c in cases if c["point"].get("prony") or c["point"].get("material")]
    if not prony:
        return []
    return (["Prony materials (creep functions, creep times; `docs/conventions.md` of "
             "viscosine, 'Creep times, not relaxation times'):", ""]
            + [f"- {c['name']}: [{c['name']}/material.png]({c['name']}/material.png) "
               f"({Path(c['point'].get('prony') or c['point']['material']).name}"
               + (f" at T = {c['point']['temperature']:g}"
                  if c["point"].get("temperature") is not None else "")
               + f", V/V0 = {c['point']['speed']:g})"
               for c in prony] + [""])
