"""The options of a --material file on the command line: which flag gives which keyword of the
materials API (`FLAGS`), which files each applies to (`APPLIES`), and the refusals of an option
given where it does not apply, of --nu and of a flag's value, in the command line's words
(`comparisons._materials.read` uses them)."""
from __future__ import annotations

import os

from viscosine.checks import shown

from ._errors import one_line, reason

#: a material file's form, as a refusal names it
_FORM_NAMES = {"creep": "a creep series", "relaxation": "a relaxation series",
               "time": "an E(t) or J(t) table", "card": "an FE Prony card",
               "dma": "a DMA master curve", "sweeps": "raw isotherms"}

#: the readers' and fits' keywords besides the fit options of `operating_point.FIT_OPTIONS`
DATA_OPTIONS = ("kind", "frequency_unit", "extend", "vertical", "method")
#: the files each option of a --material file applies to (refused for the others)
APPLIES = {"max_residual": ("dma", "sweeps"), "loss_weight": ("dma", "sweeps"),
           "per_decade": ("dma", "sweeps", "time"), "extend": ("dma", "sweeps", "time"),
           "kind": ("dma",), "frequency_unit": ("dma", "sweeps"),
           "vertical": ("sweeps",), "method": ("sweeps",)}
#: every keyword of the materials API a --material file goes through, and the command-line
#: flag that gives it (None: none, `NO_FLAG` says why); the same on point, sweep, mastercurve
FLAGS = {
    "read_dma": {"kind": "--material-kind", "nu": "--nu", "frequency_unit": "--frequency-unit",
                 "data": None},
    "read_sweeps": {"frequency_unit": "--frequency-unit"},
    "superpose": {"reference_temperature": "--temperature", "method": "--shift-method",
                  "vertical": "--vertical-shift"},
    "fit_prony": {"per_decade": "--per-decade", "extend": "--extend",
                  "max_residual": "--max-residual", "loss_weight": "--loss-weight"},
    "read_time_data": {},
    "fit_time_data": {"per_decade": "--per-decade", "extend": "--extend"},
    "read_card": {"form": None, "nu": "--nu"},
}
#: why a keyword has no flag
NO_FLAG = {"data": "the file's bytes, which the command line reads once (for its SHA-256)",
           "form": "told from the card's keywords (TB,PRONY, *VISCOELASTIC, *MAT_076, tau_i "
                   "and alpha_i): each form needs its own, so a card has exactly one"}
#: an option's flag (the keyword's name in the refusals of `_refuse_inapplicable`)
FLAG_OF = {k: v for table in FLAGS.values() for k, v in table.items() if v is not None}
#: what each file form is, as "it applies to ..." names it
_APPLIES_TO = {"dma": "a DMA curve", "sweeps": "raw isotherms", "time": "an E(t)/J(t) table"}


def _refuse_inapplicable(form, path, options):
    """Refuse an option given for a file it does not apply to (`APPLIES`), naming the file's
    form and the forms it applies to (not the file: the line stays short)."""
    for name, value in options.items():
        if value is None or form in APPLIES[name]:
            continue
        names = [_APPLIES_TO[f] for f in APPLIES[name]]
        to = " or ".join([", ".join(names[:-1]), names[-1]] if len(names) > 1 else names)
        typed = value if isinstance(value, str) else shown(value)
        raise ValueError(f"{FLAG_OF[name]} {typed}: not for {_FORM_NAMES[form]} "
                         f"(it applies to {to})")


#: what a shear file holds, as the refusal that asks for --nu names it
_SHEAR = {"dma": "shear moduli G', G''", "sweeps": "shear isotherms G', G''",
          "time": "a shear modulus G(t)", "card": "shear moduli G_0, G_i"}


def _nu_allowed():
    """The Poisson ratios --nu may give (`viscosine.materials` ``POISSON_ALLOWED``)."""
    from viscosine.materials import POISSON_ALLOWED
    return POISSON_ALLOWED


def _checked_nu(nu):
    """--nu as a float (`viscosine.materials` ``poisson``), or None; ValueError naming --nu."""
    from viscosine.materials import poisson
    if nu is None:
        return None
    try:
        return poisson(nu, "shear moduli")
    except ValueError:
        raise ValueError(f"--nu {shown(nu)}: must be {_nu_allowed()}") from None


def _flag_refusal(exc, path, nu=None, kind=None):
    """The refusal of a flag's value (`FLAG_OF`, not --nu) as ``--flag value: must be ...``,
    the file by its name only; None for any other error."""
    from viscosine.checks import Refusal
    if isinstance(exc, Refusal) and exc.name == "nu" and nu is None and kind == "G":
        return f"--nu is missing: --material-kind G needs it, {_nu_allowed()} (E = 2 (1 + ν) G)"
    if isinstance(exc, Refusal) and exc.name == "nu" and nu is not None and kind == "E":
        return f"--nu {shown(nu)}: not with --material-kind E (ν converts shear moduli only)"
    if not (isinstance(exc, Refusal) and exc.name in FLAG_OF and exc.name != "nu"):
        return None
    said = reason(exc).replace(repr(str(path)), repr(os.path.basename(path)))
    said = said.replace(", or None", ", or leave it out")  # None: the flag left out
    return f"{FLAG_OF[exc.name]} {exc.value}: {said}"


def _nu_reason(exc, nu, form, path):
    """What to say of a refusal: one about ν (a shear file without --nu, or an LS-DYNA card
    whose BULK fixes another ν) or another option in the command line's words; any other as
    `reason` says it."""
    from viscosine.checks import Refusal
    if not (isinstance(exc, Refusal) and exc.name == "nu"):
        return reason(exc)
    if nu is None:
        return (f"it holds {_SHEAR.get(form, 'shear moduli')}: give --nu, {_nu_allowed()} "
                "(E = 2 (1 + ν) G)")
    if form == "card":
        from viscosine import materials as vm
        own = vm.card_nu(path)
        return (f"--nu {nu!r} contradicts the LS-DYNA card's ν = {own:.6g} (from BULK and G0 = "
                "sum G_i): omit --nu or give that ν")
    return f"--nu {nu!r}: must be {one_line(exc.allowed)}"
