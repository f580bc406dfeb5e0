"""DMA master curves: the layouts labs write, read by `read_dma`.  `_files` reads the other
material formats and tells the forms apart (`material_form`, which uses `_find_header`)."""
from __future__ import annotations

import math
import re

import numpy as np

from ..checks import bad
from . import _text
from ._dma import MasterCurve
from ._units import PASCALS, poisson

# --------------------------------------------------------------------------
# DMA master curves: the layouts labs write
# --------------------------------------------------------------------------
#: frequency units a DMA file may name, as (canonical name, factor to rad/s of the time unit)
FREQUENCY_UNITS = {"hz": ("Hz", 2.0 * math.pi), "1/s(hz)": ("Hz", 2.0 * math.pi),
                   "khz": ("Hz", 2e3 * math.pi), "rad/s": ("rad/s", 1.0),
                   "rad/sec": ("rad/s", 1.0), "rads-1": ("rad/s", 1.0),
                   "rads^-1": ("rad/s", 1.0), "rad*s^-1": ("rad/s", 1.0),
                   "rad.s-1": ("rad/s", 1.0), "rad·s-1": ("rad/s", 1.0), "rad/s)": ("rad/s", 1.0)}
#: the roles of a DMA file's columns; the name of each as the messages give it
ROLES = ("frequency", "storage", "loss")
#: non-comment lines searched for the header (lines before it, a title or metadata, are skipped)
HEADER_SEARCH = 50


def _column(raw: str) -> dict:
    """What a header field says: its ``role`` (frequency, storage, loss, tan_delta or None),
    ``kind`` ("E", "G" or None), ``unit`` (in brackets or parentheses), and for a frequency
    whether it is ``reduced`` (a_T f) or ``angular`` by its name (omega, w)."""
    text = raw.strip()
    for a, b in (("′", "'"), ("’", "'"), ("″", "''"), ('"', "''"), ("δ", "delta"),
                 ("ω", "omega")):
        text = text.replace(a, b)
    low = text.lower()
    unit = None
    if not low.startswith("tan"):            # tan(delta): a name, not a unit
        m = re.search(r"[\[(]([^\])]*)[\])]", text)
        if m:
            unit = m.group(1).strip() or None
            low = (low[:m.start()] + low[m.end():])
    key = re.sub(r"[\s_\-.*·,:/]", "", low)
    out = {"role": None, "kind": None, "unit": unit, "reduced": False, "angular": False,
           "name": raw.strip()}
    if key.startswith("tan") or "lossfactor" in key or key == "delta":
        out["role"] = "tan_delta"
    elif key.endswith("''") or key in ("e2", "g2") or ("loss" in key and "tang" not in key):
        out["role"] = "loss"
    elif key.endswith("'") or key in ("e1", "g1") or "stor" in key:
        out["role"] = "storage"
    elif ("freq" in key or "omega" in key or key in ("f", "w", "atf", "atw", "af", "aw")
          or "angular" in key):
        out["role"] = "frequency"
        out["reduced"] = "red" in key or key.startswith(("at", "af", "aw"))
        out["angular"] = "omega" in key or "angular" in key or key in ("w", "atw", "aw")
    if out["role"] in ("storage", "loss"):
        bare = key.replace("storage", "").replace("stor", "").replace("loss", "")
        bare = bare.replace("modulus", "").replace("'", "")
        if bare.startswith("g") or "shear" in key:
            out["kind"] = "G"
        elif bare.startswith("e") or "young" in key or "tensile" in key:
            out["kind"] = "E"
    return out


def _header_problem(number, fields, columns):
    """The refusal text of a line that is not a DMA header, or None when it is one."""
    for role in ROLES:
        hits = [c for c in columns if c["role"] == role]
        if role == "frequency" and len(hits) > 1:
            hits = [c for c in hits if c["reduced"]] or hits  # a_T f beside f: the master curve
        if len(hits) != 1:
            what = "no" if not hits else "more than one"
            return (f"a header line naming the columns frequency, storage, loss (line {number} "
                    f"has {what} column {role!r}: {', '.join(fields)})")
    return None


def _find_header(rows, where):
    """``(index of the header among rows, separator, fields, columns)``."""
    first = None
    for i, (number, line) in enumerate(rows[:HEADER_SEARCH]):
        sep = _text.separator(line)
        fields = _text.split(line, sep)
        if fields and all(_text.number(f, sep) is not None for f in fields):
            break                             # numbers before any header
        columns = [_column(f) for f in fields]
        problem = _header_problem(number, fields, columns)
        if problem is None:
            return i, sep, fields, columns
        if first is None or any(c["role"] for c in columns) and not any(
                c["role"] for c in first[1]):
            first = (problem, columns)
    if first is None:
        number = rows[0][0] if rows else 0
        first = (f"a header line naming the columns frequency, storage, loss (e.g. 'frequency "
                 f"[Hz], E' [MPa], E'' [MPa]'); line {number} holds numbers only", None)
    raise ValueError(f"{where} {first[0]}")


def _pick(columns, role):
    hits = [i for i, c in enumerate(columns) if c["role"] == role]
    if role == "frequency" and len(hits) > 1:
        hits = [i for i in hits if columns[i]["reduced"]]
    return hits[0] if hits else None


def _frequency_unit(unit, column, where):
    """The canonical frequency unit and factor to rad/s of a column, or (None, None)."""
    if unit is None:
        return ("rad/s", 1.0) if column["angular"] else (None, None)
    key = unit.strip().lower().replace(" ", "")
    if key in FREQUENCY_UNITS:
        return FREQUENCY_UNITS[key]
    raise ValueError(f"{where} a frequency unit Hz or rad/s (column {column['name']!r} is in "
                     f"{unit!r}; '1/s' could be either: write Hz or rad/s in the header)")


def _modulus_unit(u):
    if u is None or u.strip() in ("", "-", "1"):
        return None
    return u.strip()


def read_dma(path, *, kind: str | None = None, nu=None, frequency_unit: str | None = None,
             data: bytes | None = None) -> MasterCurve:
    """Read a DMA master curve from a text table, as labs write them.

    Layouts read (docs/materials.md shows one example of each)::

        # comments start with '#'
        frequency [Hz], storage [MPa], loss [MPa]
        0.01, 3.31, 0.152

        f;E';E''               <- names, then a row of units
        Hz;MPa;MPa
        1000;2,51;1,02         <- ';' separators, decimal commas, any row order

    * the header names the frequency (``frequency``, ``freq``, ``f``, ``omega``/``w`` (angular),
      ``reduced frequency``/``aT*f`` (preferred beside a raw one)), the storage modulus
      (``storage``, ``E'``, ``E_stor``, ``Estorage``, ``E1``, ``G'``...) and the loss modulus
      (``loss``, ``E''``, ``E"``, ``E_loss``, ``E2``, ``G''``...), in any order and case;
      a ``tan delta`` column is checked against E''/E' (a note when it disagrees); other
      columns are ignored; lines before the header (a title, metadata) are skipped;
    * units in brackets or parentheses after the name, or in a row of their own under the
      names: frequencies in Hz or rad/s; moduli in Pa, kPa, MPa, GPa, N/mm2 or psi (kept in
      the storage column's unit, which the curve records; a loss column in another known unit
      is converted to it);
    * fields separated by ``;``, tabs, ``,`` or blanks; decimal commas where commas do not
      separate; rows in any order (sorted; duplicate frequencies merged by `MasterCurve`).

    Parameters
    ----------
    path : str or Path
        The file (UTF-8 text).
    kind : {"E", "G"}, optional
        Tensile (E', E'') or shear (G', G'') moduli; default: what the column names say
        (``G'``, ``G_stor``: shear), else tensile.  Shear moduli become tensile ones with
        ``E = 2 (1 + nu) G``.
    nu : float, optional
        Poisson ratio in (-1, 0.5], required for shear moduli; refused with ``kind="E"``, and
        unused when the file holds tensile moduli and ``kind`` is None.
    frequency_unit : {"rad/s", "Hz"}, optional
        Unit of the frequency column ("s" stands for the curve's time unit).  Default: the
        unit the header gives, else rad/s.  A unit the header contradicts is refused.
    data : bytes, optional
        The file's bytes, when the caller has read them (the file is then not opened).

    Returns
    -------
    MasterCurve
        Angular frequencies, ``E'`` and ``E''``, with ``notes`` on what was read.

    Raises
    ------
    ValueError
        One line ``dma='path' is not allowed: ...`` naming the line and column at fault: an
        unreadable, binary or non-UTF-8 file, no header, ragged or non-numeric rows, values that
        are not finite or not positive, fewer than `MIN_POINTS` frequencies.
    """
    if kind not in (None, "E", "G"):
        raise bad("kind", kind, "'E' (tensile moduli), 'G' (shear moduli) or None (the "
                  "column names say)")
    if frequency_unit not in (None, "rad/s", "Hz"):
        raise bad("frequency_unit", frequency_unit, "'rad/s' (angular) or 'Hz' (cycles), or "
                  "None (the header's unit)")
    if kind == "E" and nu is not None:
        raise bad("nu", nu, "None with kind='E' (nu converts shear moduli; the file holds "
                  "tensile ones)")
    if nu is not None or kind == "G":
        nu = poisson(nu, "shear moduli (kind='G')")
    src = str(path)
    where = f"dma={src!r} is not allowed:"
    rows = _text.lines(_text.read_text(path, "dma", data))
    if not rows:
        raise bad("dma", src, "a header line naming the columns frequency, storage, loss, then "
                  "data (this file is empty or only comments)")
    head, sep, names, columns = _find_header(rows, where)
    notes = [f"lines before the header skipped (line {rows[head][0]} is the header)"] if head \
        else []
    pick = {role: _pick(columns, role) for role in ROLES + ("tan_delta",)}
    body = rows[head + 1:]
    units = {r: (columns[i]["unit"] if i is not None else None) for r, i in pick.items()}
    if body:
        first = _text.split(body[0][1], sep if sep is not None else _text.separator(body[0][1]))
        used = [i for i in pick.values() if i is not None and i < len(first)]
        if used and all(_text.number(first[i], sep) is None for i in used):
            for r, i in pick.items():         # a row of units under the names
                if i is not None and i < len(first) and units[r] is None:
                    units[r] = first[i].strip("[]() ") or None
            notes.append(f"units row (line {body[0][0]})")
            body = body[1:]
    values = {r: [] for r, i in pick.items() if i is not None}
    lines = []
    for number, line in body:
        fields = _text.split(line, sep if sep is not None else _text.separator(line))
        if len(fields) != len(names):
            raise ValueError(f"{where} {len(names)} fields on every line, as in the header "
                             f"(line {number} has {len(fields)})")
        for r in values:
            tok = fields[pick[r]]
            v = _text.number(tok, sep)
            if v is None:
                raise ValueError(f"{where} numeric data (line {number}: {r} {tok!r} is not a "
                                 f"number; column {names[pick[r]]!r})")
            if not math.isfinite(v):
                raise ValueError(f"{where} finite numbers (line {number}: {r} is {tok!r} in "
                                 f"column {names[pick[r]]!r})")
            values[r].append(v)
        lines.append(number)
    cols = {r: np.array(v, dtype=float) for r, v in values.items()}
    # frequency
    stated, to_rad = _frequency_unit(units["frequency"], columns[pick["frequency"]], where)
    if frequency_unit is None:
        frequency_unit, to_rad = (stated, to_rad) if stated else ("rad/s", 1.0)
    elif stated is not None and stated != frequency_unit:
        raise bad("frequency_unit", frequency_unit, f"the unit of the file's frequency column "
                  f"({units['frequency']!r} in {src!r}), or None")
    elif stated is None:
        to_rad = 2.0 * math.pi if frequency_unit == "Hz" else 1.0
    if columns[pick["frequency"]]["reduced"] and sum(c["role"] == "frequency"
                                                     for c in columns) > 1:
        notes.append(f"reduced frequency column {names[pick['frequency']]!r} used")
    omega = cols["frequency"] * to_rad
    # moduli: one unit, tensile
    su, lu = _modulus_unit(units["storage"]), _modulus_unit(units["loss"])
    loss = cols["loss"]
    if su and lu and su.lower() != lu.lower():
        fs, fl = PASCALS.get(su.lower()), PASCALS.get(lu.lower())
        if fs is None or fl is None:
            raise bad("dma", src, f"storage and loss in one unit (the header gives {su!r} and "
                      f"{lu!r}: a silent factor otherwise)")
        loss = loss * (fl / fs)
        notes.append(f"loss converted from {lu} to {su}")
    modulus_unit = su or lu
    kinds = {columns[pick[r]]["kind"] for r in ("storage", "loss")} - {None}
    named = kinds.pop() if len(kinds) == 1 else None
    if kind is not None and named is not None and named != kind:
        raise bad("kind", kind, f"the kind of moduli the file's columns name ({named}: "
                  f"{names[pick['storage']]!r}, {names[pick['loss']]!r}), or None")
    kind = kind or named or "E"
    factor = 1.0
    if kind == "G":
        nu = poisson(nu, f"the shear moduli of {src!r} (columns {names[pick['storage']]!r}, "
                     f"{names[pick['loss']]!r})")
        factor = 2.0 * (1.0 + nu)
        notes.append(f"shear moduli turned into tensile ones: E = 2 (1 + {nu:g}) G")
    if "tan_delta" in cols:
        notes.append(_tan_delta_note(cols, names[pick["tan_delta"]]))
    if omega.size > 1 and not np.all(np.diff(omega) > 0.0):
        notes.append("rows not in increasing frequency: sorted")

    def at(j, text):
        line = "" if j is None else f" (line {lines[j]})"
        return f"{where} {text}{line}"
    try:
        return MasterCurve(omega, cols["storage"] * factor, loss * factor, source=src,
                           modulus_unit=modulus_unit, frequency_unit=frequency_unit,
                           notes=tuple(notes), shear_nu=nu if kind == "G" else None)
    except ValueError as exc:
        text = str(exc)
        m = re.match(r"omega\[(\d+)\]=\S+ is not allowed: (.*)$", text)
        if m:
            raise ValueError(at(int(m.group(1)), m.group(2))) from None
        m = re.match(r"omega=.* is not allowed: (.*)$", text)
        raise ValueError(at(None, m.group(1) if m else text)) from None


def _tan_delta_note(cols, name):
    ratio = cols["loss"] / cols["storage"]
    with np.errstate(divide="ignore", invalid="ignore"):
        off = np.abs(ratio / cols["tan_delta"] - 1.0)
    med = float(np.nanmedian(off)) if off.size else 0.0
    if med > 0.05:
        return (f"the tan delta column {name!r} differs from E''/E' by {100 * med:.3g} % "
                "(median): check which columns are storage and loss")
    return f"the tan delta column {name!r} agrees with E''/E' (median {100 * med:.2g} %)"
