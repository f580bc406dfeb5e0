"""Material inputs of the command line: a creep-series, relaxation-series or DMA file, moved to a
temperature, turned into the BEM road's creep series, and described in every record.

A material file is one of `viscosine.materials.FORMS`, told apart by its first line
(`viscosine.materials.material_form`):

* ``creep``: ``J0 <value>`` then ``J_i tau_i`` (`bem.read_prony`; creep, i.e. retardation, times);
* ``relaxation``: ``E_r <value>`` then ``E_i theta_i`` (`viscosine.materials.read_relaxation`;
  relaxation times), converted exactly (`Maxwell.creep`);
* ``dma``: a master curve table (`viscosine.materials.read_dma`), fitted with
  `viscosine.materials.fit_prony` and reported (residuals per decade, scatter, Kramers-Kronig
  figure: the record's ``material.fit``); refused only with ``--max-residual`` when missed.

The file is read once (its bytes give the SHA-256, its form and its contents).

Reference units (what the dimensionless groups are measured in; every record states them):

* a creep or relaxation file: its own units.  E_ref is its modulus unit (``load`` is
  p∞(1 − ν²)/E_ref) and τ_ref its time unit (``speed`` is V τ_ref k), so the two forms of one
  material written in one set of units give the same point;
* a DMA curve: E_ref is the relaxed modulus E_r of the fit (the paper's E0, in the data's unit),
  τ_ref is 1 s (the data's frequencies are in rad/s or Hz): ``speed`` is V k × 1 s;
* the standard linear solid (no file): E_ref = E0 and τ_ref = τ, its **creep** time (eq. 2.3);
  its relaxation time is τ E0/E∞;
* with ``--units SI`` every file material is in units of its relaxed modulus E_r [Pa] and 1 s
  (series files in Pa and s; a DMA curve in the modulus unit its header names).

A temperature (``--temperature T`` with ``--wlf C1 C2 TREF`` or ``--shift-table FILE``) multiplies
every time of the material by a_T (thermorheologically simple): the file is the material at the
shift's reference temperature.  τ_ref is not shifted, so a point at T equals the point at T_ref
at the speed multiplied by a_T.

Extrapolation: a DMA fit is trusted inside the measured window only.  A point probes the
frequencies ω_n = k_n V = n k V of the harmonics that carry the contact, n = 1 … ⌈λ/2a⌉ (a
contact of width 2a is built from harmonics up to wavelengths of about its width; in full
contact of the sinusoid only n = 1); when ω_1 … ω_top leaves the window (shifted to T), the record
carries a warning (`viscosine.materials.Maxwell.extrapolation_warning`).
"""
from __future__ import annotations

import hashlib
import math
import os
from typing import NamedTuple

from . import roads
from ._errors import one_line, reason
from ._material_options import (  # noqa: F401 (the tables, re-exported for the callers)
    APPLIES, DATA_OPTIONS, FLAG_OF, FLAGS, NO_FLAG, _checked_nu, _flag_refusal,
    _nu_reason, _refuse_inapplicable)
from ._io import file_bytes

TIME_UNIT_SLS = ("speed = V tau_ref k with tau_ref = tau, the creep (retardation) time of the "
                 "standard linear solid (eq. 2.3); its relaxation time is tau E0/Einf = "
                 "tau/ratio")


class Material(NamedTuple):
    """A material read for the BEM road."""

    info: dict      # JSON-ready description (goes into the spec and every record)
    prony: object   # bem.Prony: the creep series in E_ref and tau_ref
    model: object   # viscosine.materials.Maxwell at the temperature (None for a creep file)
    curve: object = None  # viscosine.materials.MasterCurve a DMA fit was made to
    #: measured frequencies (rad per tau_ref, at the material's temperature), or None
    window: tuple | None = None


def sls_description(ratio, si=None) -> dict:
    """The record's ``material`` of the standard linear solid of E∞/E0 = ratio; with ``si``
    (``--units SI``: the point's scales, `viscosine.si.SIScales.describe`) the solid the user
    gave, in Pa and s: E0, Einf, both times and which was given, E_ref = E0 and tau_ref = the
    creep time (the units the groups are measured in; the record's ``si_scales`` the same)."""
    if si is not None:
        e0, tau = si["E_ref"], si["tau_creep"]
        out = {"form": "standard_linear_solid", "path": None, "sha256": None, "terms": 1,
               "ratio": ratio, "E0": e0, "Einf": e0 * ratio, "tau_creep": tau,
               "tau_relax": si["tau_relax"], "time_given": si["time_given"],
               "E_ref": e0, "E_ref_is": "E0, the relaxed modulus of the solid [Pa]",
               "tau_ref": tau, "tau_ref_is": "tau_creep, the creep (retardation) time of the "
                                             "solid (eq. 2.3) [s]",
               "time_unit": TIME_UNIT_SLS, "units": "SI"}
        return out
    return {"form": "standard_linear_solid", "path": None, "sha256": None, "terms": 1,
            "ratio": ratio,
            "E_ref": 1.0, "E_ref_is": "E0, the relaxed modulus of the solid",
            "tau_ref": 1.0, "tau_ref_is": "tau, the creep (retardation) time of the solid "
                                           "(eq. 2.3); its relaxation time is tau/ratio",
            "time_unit": TIME_UNIT_SLS}


def _sha256(data: bytes) -> str:
    return hashlib.sha256(data).hexdigest()


def shift_from_options(wlf=None, shift_table=None):
    """The shift of ``--wlf C1 C2 TREF`` or ``--shift-table FILE``: (a `viscosine.materials.WLF`
    or `ShiftTable`, its JSON description), or (None, None); ValueError naming the option."""
    from viscosine import materials as vm
    if wlf is not None:
        c1, c2, t_ref = wlf
        try:
            s = vm.WLF(c1, c2, t_ref)
        except ValueError as exc:
            raise ValueError(f"--wlf {c1!r} {c2!r} {t_ref!r} is not allowed: {one_line(exc)}") from None
        return s, {"kind": "WLF", "C1": s.C1, "C2": s.C2, "T_ref": s.T_ref}
    if shift_table is not None:
        data = file_bytes("--shift-table", shift_table)
        try:
            s = vm.read_shift_table(shift_table)
        except ValueError as exc:
            raise ValueError(f"--shift-table {shift_table}: {one_line(exc)}") from None
        return s, {"kind": "table", "path": os.path.abspath(shift_table),
                   "sha256": _sha256(data), "T": [s.T[0], s.T[-1]]}
    return None, None


def read(path, *, temperature=None, wlf=None, shift_table=None, max_residual=None,
         per_decade=None, loss_weight=None, nu=None, si=False, option="--material",
         reference_temperature=None, kind=None, frequency_unit=None, extend=None,
         vertical=None, method=None) -> Material:
    """Read a material file of any accepted form, at a temperature, for the BEM road.

    Parameters
    ----------
    path : str
        The file.
    temperature : float, optional
        With exactly one of ``wlf`` ((C1, C2, T_ref)) and ``shift_table`` (a file).
    max_residual, per_decade, loss_weight : float, optional
        The DMA fit's bound on its largest relative residual, its relaxation times per decade
        and the weight of E'' against E' (None: the defaults of
        `viscosine.materials.fit_prony`: no bound, times chosen by held-out residual, equal
        weights); refused for a series file.
    nu : float, optional
        The Poisson ratio that turns a DMA curve of shear moduli (G', G'') into tensile ones,
        E = 2 (1 + ν) G (`viscosine.materials.read_dma`); required for such a curve, unused by
        every other file (the description's ``shear_nu`` says when it was used).
    si : bool
        Units of the file: SI (series in Pa and s; a DMA curve in the unit its header names),
        reference modulus E_r [Pa] and 1 s; else the file's own units (module docstring).
    kind, frequency_unit, extend, vertical, method : optional
        The readers' and fits' other keywords (`DATA_OPTIONS`; `FLAGS` gives each its
        command-line flag): ``read_dma(kind=)``, ``read_dma``/``read_sweeps(frequency_unit=)``,
        ``fit_prony``/``fit_time_data(extend=)``, ``superpose(vertical=, method=)``
        (``vertical="none"`` is None there).  Each is refused for a file it does not apply to
        (`APPLIES`).
    reference_temperature : float, optional
        Raw isotherms (``sweeps``) only: the temperature of their master curve (default: the
        ``temperature``, else the isotherm nearest the middle of the measured range).  The
        isotherms carry their own shift: no ``wlf`` or ``shift_table`` with them.

    Raises
    ------
    ValueError
        One line naming the option, the file and what is allowed.
    """
    from viscosine import materials as vm

    data = file_bytes(option, path)
    where = f"{option} {path}"
    try:
        form = vm.material_form(path, data=data)
    except ValueError as exc:
        raise ValueError(f"{where}: {reason(exc)}") from None
    if form == "sweeps":
        if wlf is not None or shift_table is not None:
            raise ValueError(f"{'--wlf' if wlf is not None else '--shift-table'} is not allowed "
                             f"with raw isotherms ({path}): their own shifts move them to "
                             "--temperature")
    elif (wlf is None and shift_table is None) != (temperature is None):
        if temperature is None:
            raise ValueError(f"{'--wlf' if wlf is not None else '--shift-table'} is not allowed "
                             "without --temperature: it shifts the material to that temperature")
        raise ValueError(f"--temperature {temperature!r} is not allowed without --wlf C1 C2 TREF "
                         "or --shift-table FILE: the shift a_T(T) of the material's times")
    fit_options = {"max_residual": max_residual, "per_decade": per_decade,
                   "loss_weight": loss_weight, "extend": extend}
    data_options = {"kind": kind, "frequency_unit": frequency_unit, "vertical": vertical,
                    "method": method}
    _refuse_inapplicable(form, path, {**fit_options, **data_options})
    shift, shift_info = shift_from_options(wlf, shift_table)
    fit_info = curve = model = None
    extra = {}
    nu = _checked_nu(nu)
    try:
        if form == "creep":
            creep = vm.read_creep(path, option="prony", data=data)
            terms = len([j for j in creep.J if j > 0.0])
            # the hand-off to the BEM drops a term below its floor, as for a fitted series
            prony, extra["dropped_terms"] = _for_bem(creep)
            model = None
            e_ref = 1.0
            if si:  # compliances in 1/Pa: units of the relaxed modulus 1/J0
                e_ref = 1.0 / prony.J0
                prony = roads.prony(1.0, tuple(j * e_ref for j in prony.J), prony.tau)
        else:
            if form == "relaxation":
                model = vm.read_relaxation(path, data=data)
            elif form in ("dma", "sweeps"):
                if form == "dma":
                    curve = vm.read_dma(path, data=data, nu=nu, kind=kind,
                                        frequency_unit=frequency_unit)
                    if curve.shear_nu is not None:
                        extra["shear_nu"] = curve.shear_nu
                else:
                    sp = _superposed(vm, path, temperature, reference_temperature, nu, extra,
                                     data_options)
                    curve, extra["superposition"] = sp.curve, sp.as_dict()
                    extra["temperature"] = sp.reference_temperature
                model = _fit(vm, curve, fit_options)
                if si:
                    model = model.in_pascals()
            else:
                model = _other_form(vm, form, path, extra, nu, fit_options)
                if si and model.fit is not None:
                    model = model.in_pascals()
            _check_range(model, form)
            terms = len([e for e in model.E if e > 0.0])
            e_ref = model.E_r if (form in FITTED or si) else 1.0
            prony, extra["dropped_terms"] = bem_series(model, e_ref)
            fit_info = _fit_info(model)
        if model is None:
            _check_creep_range(prony)
    except ValueError as exc:
        flagged = _flag_refusal(exc, path, nu, kind)
        if flagged is not None:
            raise ValueError(flagged) from None
        raise ValueError(f"{where}: {_nu_reason(exc, nu, form, path)}") from None
    window = model.fit.window if model is not None and model.fit is not None else None
    header = vm.read_window(path, data=data)
    if window is None and header is not None:
        window = header                       # a series written with its data's window
        extra["window_from"] = "the file's '# measured window' line"
    if extra.get("dropped_terms", 0) is None:
        del extra["dropped_terms"]
    read_options = {k: v for k, v in {**data_options, "extend": extend}.items() if v is not None}
    if form == "time" and per_decade is not None:  # its report does not say it was given
        read_options["per_decade"] = per_decade
    if read_options:                          # as given, for a worker that reads it again
        extra["read_options"] = read_options
    info = {"form": form, "path": os.path.abspath(path), "sha256": _sha256(data),
            "terms": terms, **references(form, si, e_ref, fit_info),
            "temperature": None, "shift": None, "log10_aT": None,
            "fit": fit_info, "units": "SI" if si else "file",
            "measured_window": None if window is None else list(window), **extra}
    m = Material(info, prony, model, curve, window)
    if form == "sweeps":
        return m                              # at its reference temperature: no shift
    if shift is not None:
        m = at_temperature(m, shift, shift_info, temperature,
                           "--wlf" if wlf is not None else f"--shift-table {shift_table}")
    return m


def problem_nu(m: Material, nu):
    """The Poisson ratio of the problem read with material ``m``: the ν that turned its shear
    data into tensile moduli (``shear_nu``: an LS-DYNA card's own, which ``nu`` only had to
    agree with), else ``nu``; so one ν gives both E = 2 (1 + ν) G and E* = E/(1 - ν²)."""
    used = m.info.get("shear_nu")
    return nu if used is None else used


def _fit_info(model):
    f = model.fit
    if f is None:
        return None
    from viscosine.materials import MeasuredWindow
    if isinstance(f, MeasuredWindow):           # a series file's measured window only
        return None
    if not hasattr(f, "storage_max"):          # a fit to E(t) or J(t)
        return {"kind": f.kind, "rms": f.rms, "max_residual": f.max, "terms": f.terms,
                "candidates": f.candidates, "per_decade": f.per_decade, "points": f.points,
                "modulus_unit": f.modulus_unit, "window": list(f.window),
                "seconds": f.seconds, "kk_range": None}
    return {"max_residual": f.max_residual, "bound": f.bound, "storage_max": f.storage_max,
            "storage_rms": f.storage_rms, "loss_max": f.loss_max, "loss_rms": f.loss_rms,
            "tan_delta_max": f.tan_delta_max, "per_decade": f.per_decade,
            "per_decade_chosen_by": f.chosen_by,
            "held_out": [list(h) for h in f.held_out], "loss_weight": f.loss_weight,
            "candidates": f.candidates, "modulus_unit": f.modulus_unit,
            "frequency_unit": f.frequency_unit, "window": list(f.window),
            "scatter": list(f.scatter), "kk_range": list(f.kk_range),
            "decades": [dict(d) for d in f.decades], "worst": [dict(p) for p in f.worst],
            "points": f.points, "merged": f.merged, "drops": list(f.drops),
            "relaxed_floor": f.relaxed_floor, "warnings": list(f.warnings)}


#: forms whose series is a fit to data: E_ref is the fit's relaxed modulus, tau_ref 1 s
FITTED = ("dma", "sweeps", "time")


def _superposed(vm, path, temperature, reference_temperature, nu, extra, options):
    """Raw isotherms shifted onto their master curve at ``temperature`` (else at
    ``reference_temperature``, else at the isotherm nearest the middle of the range); shear
    isotherms turned into tensile ones with ``nu`` first (``extra["shear_nu"]``)."""
    sweeps = vm.read_sweeps(path, frequency_unit=options["frequency_unit"])
    if sweeps.kind == "G":
        sweeps = sweeps.tensile(nu)
        extra["shear_nu"] = nu
    temps = sweeps.temperatures
    t0 = temperature if temperature is not None else reference_temperature
    if t0 is None:
        t0 = float(temps[min(range(temps.size),
                             key=lambda i: abs(temps[i] - 0.5 * (temps[0] + temps[-1])))])
    try:
        how = {k: options[k] for k in ("method", "vertical") if options[k] is not None}
        if how.get("vertical") == "none":
            how["vertical"] = None
        return vm.superpose(sweeps, t0, **how)
    except ValueError as exc:
        text = one_line(exc)
        if text.startswith("reference_temperature="):
            name = "--temperature" if temperature is not None else "--reference-temperature"
            text = f"{name} {text[len('reference_temperature='):]}"
        raise ValueError(text) from None


def _other_form(vm, form, path, extra, nu, fit_options):
    """The series of an E(t)/J(t) table (fitted) or of an FE card (read); shear data turned
    into tensile with ``nu`` (an LS-DYNA card's own ν: ``nu`` must agree), ``extra["shear_nu"]``
    the ν used."""
    if form == "time":
        data = vm.read_time_data(path)
        if data.shear:
            data = data.tensile(nu)
            extra["shear_nu"] = nu
        return vm.fit_time_data(data, **{k: fit_options[k] for k in ("per_decade", "extend")
                                         if fit_options[k] is not None})
    extra["card"] = vm.card_form(path)
    model = vm.read_card(path, nu=nu)
    used = vm.card_nu(path, extra["card"], nu=nu)
    if used is not None:
        extra["shear_nu"] = used
    return model


def fitted_shift(m: Material):
    """The WLF fitted to the isotherms of a ``sweeps`` material and its record's ``shift``
    (constants, errors, residual, the range where it holds), or (None, None)."""
    from viscosine import materials as vm
    sp = m.info.get("superposition")
    if sp is None:
        return None, None
    w = sp["wlf"]
    info = {"kind": "WLF fitted to the isotherms", "C1": w["C1"], "C2": w["C2"],
            "T_ref": w["T_ref"], "C1_error": w["C1_error"], "C2_error": w["C2_error"],
            "rms": w["rms"], "holds": w["holds"]}
    return vm.WLF(w["C1"], w["C2"], w["T_ref"]), info


def _ratio_limit():
    low, high, _ = roads.accepted("bem")["ratio"]
    return high


def _check_range(model, form):
    """Refuse, in the file's own relaxation numbers, a series whose glassy over relaxed modulus
    the BEM road does not take (it would refuse the creep series the user never wrote)."""
    high = _ratio_limit()
    ratio = model.glassy / model.E_r
    unit = (getattr(model.fit, "modulus_unit", None) if model.fit is not None else None) or ""
    if ratio > high:
        unit = f" {unit}" if unit else ""
        raise ValueError(f"glassy/relaxed (E_r + sum E_i)/E_r = {model.glassy:.4g}{unit}/"
                         f"{model.E_r:.4g}{unit} = {ratio:.3g} is above {high:g}, the largest "
                         "the BEM takes")


def _check_creep_range(prony):
    """The same for a creep file, in its numbers J0 and J(0+) = J0 - sum J_i."""
    high = _ratio_limit()
    jp = prony.J0 - sum(prony.J)
    if prony.J and prony.J0 / jp > high:
        raise ValueError(f"E∞/E0 = J0/J(0+) = {prony.J0:.4g}/{jp:.4g} = {prony.J0 / jp:.3g} is "
                         f"above {high:g}, the largest the BEM takes")


def at_temperature(m: Material, shift, shift_info, temperature, option="--wlf") -> Material:
    """The material ``m`` (at the shift's reference temperature) moved to ``temperature``.

    Every time is multiplied by a_T (`viscosine.materials.Maxwell.at_temperature`; a creep
    series' times directly: both forms scale alike), the measured window divided by it; the
    moduli and the reference units E_ref, tau_ref are unchanged.

    Raises
    ------
    ValueError
        ``--temperature T is not allowed: ...``: outside a shift table, at or below the WLF pole.
    """
    try:
        log_a = float(shift.log10_aT(temperature)) + 0.0  # -0.0 at T_ref reads 0.0
    except ValueError as exc:
        raise ValueError(f"--temperature {temperature!r}: {reason(exc)} ({option})") from None
    a = 10.0 ** log_a
    model = m.model
    if model is None:
        p = m.prony
        prony = roads.prony(p.J0, p.J, tuple(t * a for t in p.tau))
    else:
        model = model.at_temperature(shift, temperature)
        prony, dropped = bem_series(model, m.info["E_ref"] or 1.0)
    window = None if m.window is None else (m.window[0] / a, m.window[1] / a)
    info = {**m.info, "temperature": float(temperature), "shift": shift_info,
            "log10_aT": log_a, "fit": _fit_info(model) if model is not None else None,
            "measured_window": None if window is None else list(window)}
    if model is not None:
        info.pop("dropped_terms", None)
        if dropped is not None:
            info["dropped_terms"] = dropped
    return Material(info, prony, model, m.curve, window)


def from_model(model) -> Material:
    """A `viscosine.materials.Maxwell` (moduli in Pa, times in s; a DMA fit in the unit its data
    named) as the material of an SI problem: E_ref its relaxed modulus, tau_ref 1 s."""
    from viscosine import materials as vm
    if not isinstance(model, vm.Maxwell):
        raise ValueError(f"material={model!r} is not allowed: a file name or a "
                         "viscosine.materials.Maxwell (Pa, s)")
    model = model.in_pascals()
    form = ("relaxation" if model.fit is None or isinstance(model.fit, vm.MeasuredWindow) else
            "dma" if hasattr(model.fit, "storage_max") else "time")
    source = model.fit.source if model.fit is not None else None
    fit_info = _fit_info(model)
    sha = None
    if source and os.path.isfile(source):
        with open(source, "rb") as fh:
            sha = _sha256(fh.read())
    info = {"form": form, "path": source, "sha256": sha,
            "terms": len([e for e in model.E if e > 0.0]),
            **references(form, True, model.E_r, fit_info),
            "temperature": model.temperature, "shift": None, "log10_aT": None,
            "fit": fit_info, "units": "SI",
            "measured_window": None if model.fit is None else list(model.fit.window)}
    prony, dropped = bem_series(model, model.E_r)
    if dropped is not None:
        info["dropped_terms"] = dropped
    return Material(info, prony, model,
                    window=None if model.fit is None else model.fit.window)


def bem_series(model, e_ref):
    """``(bem.Prony, dropped)``: the exact creep form of ``model`` (`Maxwell.creep`, compliances
    in 1/e_ref, times in 1 s) without the terms below the BEM's floor TERM_MIN J(0+), which it
    refuses (a fit's negligible term, e.g. 1e-14 J(0+)), and the record's ``dropped_terms``
    (None when none): their count and largest weight w = J_k/J(0+).  Each moves the compliance
    J*(ω) by at most w J(0+), at most w relative to |J*| (`Creep.without_negligible`)."""
    return _for_bem(model.creep(E_ref=e_ref, tau_ref=1.0))


def negligible_dropped(prony):
    """``(bem.Prony, dropped)``: a creep series read by the BEM (a --prony file) without its
    terms below the BEM's floor, and the record's ``dropped_terms`` (None when none), as
    `bem_series` does for a --material file."""
    from viscosine import materials as vm
    out = _for_bem(vm.Creep(prony.J0, tuple(prony.J), tuple(prony.tau)))
    return (prony, None) if out[1] is None else out


def _for_bem(creep):
    """The one hand-off of a creep series to the BEM: ``(bem.Prony, dropped)`` without the terms
    below the floor its check applies (`roads.term_floor`), and the record's ``dropped_terms``."""
    series, weights = creep.without_negligible(roads.term_floor())
    return roads.prony(*series), _dropped(weights)


def _dropped(weights):
    """The record's ``dropped_terms`` of the weights w = J_k/J(0+) dropped below the BEM's
    floor (`Creep.without_negligible`), largest first; None when none."""
    if not weights:
        return None
    return {"count": len(weights), "largest_weight": weights[0], "floor": roads.term_floor(),
            "bound": "each term of weight w = J_k/J(0+) below the BEM's floor was dropped (J0 "
                     "kept): it moves J*(omega) by at most w J(0+), at most w relative to |J*|"}


def _fit(vm, curve, options):
    """`fit_prony` with the options given; a refusal of one goes up as it is (`read` words it
    for the command line through `_flag_refusal`, as the other forms' fits)."""
    return vm.fit_prony(curve, **{k: v for k, v in options.items() if v is not None})


def references(form, si, e_ref, fit_info) -> dict:
    """E_ref, tau_ref and what they are, and the record's time_unit sentence."""
    if si:
        e_is = "E_r, the relaxed modulus of the material [Pa]"
        t_is = "1 s"
    elif form in FITTED:
        unit = (fit_info or {}).get("modulus_unit") or "the data's modulus unit"
        e_is = f"E_r, the relaxed modulus of the Prony fit [{unit}]"
        t_is = ("1 s, the time unit of the data's times" if form == "time" else
                "1 s, the time unit of the DMA frequencies (rad/s or Hz)")
    else:
        e_is = ("the modulus unit of the file (compliances J0, J_i in 1/E_ref)" if form == "creep"
                else "the modulus unit of the file (moduli E_r, E_i in E_ref)")
        # a card's times are relaxation times too
        t_is = ("the time unit of the file, whose times are creep (retardation) times"
                if form == "creep" else
                "the time unit of the file, whose times are relaxation times (converted "
                "exactly to creep times)")
    kind = {"creep": "creep-series file", "relaxation": "relaxation-series file",
            "dma": "DMA master curve", "sweeps": "raw isotherms shifted onto a master curve",
            "time": "E(t) or J(t) table", "card": "FE Prony card"}[form]
    return {"E_ref": e_ref, "E_ref_is": e_is, "tau_ref": 1.0, "tau_ref_is": t_is,
            "time_unit": f"speed = V tau_ref k with tau_ref = {t_is} ({kind}); load = "
                         "p_inf (1 - nu^2)/E_ref"}


def reread(info) -> Material:
    """The material of a spec's description (a worker that did not receive the parsed one)."""
    shift = info.get("shift") or {}
    fit = info.get("fit") or {}
    as_fitted = dict(  # the fit's options as given (a default left to the fit)
        max_residual=fit.get("bound"),
        per_decade=fit.get("per_decade") if fit.get("per_decade_chosen_by") == "given" else None,
        loss_weight=fit.get("loss_weight") if fit.get("loss_weight", 1.0) != 1.0 else None,
        si=info.get("units") == "SI")
    as_fitted.update(info.get("read_options") or {})   # the readers' options as given
    if info.get("form") == "sweeps":          # their master curve, maybe moved by their WLF
        fitted = shift.get("kind") == "WLF fitted to the isotherms"
        base = read(info["path"], temperature=None if fitted else info.get("temperature"),
                    reference_temperature=shift.get("T_ref") if fitted else None,
                    nu=info.get("shear_nu"), **as_fitted)
        if not fitted:
            return base
        from viscosine import materials as vm
        return at_temperature(base, vm.WLF(shift["C1"], shift["C2"], shift["T_ref"]), shift,
                              info["temperature"])
    return read(info["path"], temperature=info.get("temperature"),
                wlf=(shift["C1"], shift["C2"], shift["T_ref"]) if shift.get("kind") == "WLF"
                else None,
                shift_table=shift.get("path") if shift.get("kind") == "table" else None,
                nu=info.get("shear_nu"), **as_fitted)


def probed(speed, contact_fraction):
    """(ω_lo, ω_hi) in rad per τ_ref: the harmonics n = 1 … ⌈1/contact_fraction⌉ at speed w."""
    top = max(1, math.ceil(1.0 / max(float(contact_fraction), 1e-300) - 1e-9))
    return speed, speed * top


def extrapolation(material, speed, contact_fraction):
    """The warning of a point whose frequencies leave the material's measured window (a fit's
    data, or a series file's '# measured window' line), or None.

    ``material``: a `Material` (or, as before, a fitted `Maxwell`).
    """
    window = getattr(material, "window", None)
    if window is None:
        fit = getattr(material, "fit", None)
        window = None if fit is None else fit.window
    if window is None or not speed > 0.0:
        return None
    lo, hi = probed(speed, contact_fraction)
    w0, w1 = window
    below = math.log10(w0 / lo) if lo < w0 else 0.0
    above = math.log10(hi / w1) if hi > w1 else 0.0
    if below <= 0.0 and above <= 0.0:
        return None
    sides = [f"{d:.2g} decade(s) {side}" for d, side in ((below, "below"), (above, "above"))
             if d > 0.0]
    return (f"frequencies {lo:.3g}..{hi:.3g} reach {' and '.join(sides)} the measured window "
            f"{w0:.3g}..{w1:.3g} of the material's data: the modulus there is extrapolated by "
            f"the Prony series (harmonics n = 1..{round(hi / lo)} of the contact at speed "
            f"{speed:.4g}; frequencies in rad per tau_ref)")
