"""Every material file format, read in one place.

* creep series (``J0 <value>`` then ``J_i tau_i``): `read_creep` (``bem.read_prony`` calls it);
* relaxation series (``E_r <value>`` then ``E_i theta_i``): `read_relaxation`;
* DMA master curves (a table of frequency, storage, loss): `read_dma` (in `_dmafile`);
* time–temperature shift tables (temperature, log10 a_T): `read_shift_table`;
* `material_form` tells the three material forms (`FORMS`) apart from a file's first line.

A new format (raw multi-temperature sweeps, E(t)/J(t) tables, FE Prony cards) belongs here, beside
these readers, built on `_data_lines` (text, comments, line numbers) and `_read_table`
(named columns).
"""
from __future__ import annotations

import math

import numpy as np

from ..checks import bad
from . import _text
from ._series import Creep, Maxwell
from ._temperature import ShiftTable

#: the forms of a material file `material_form` tells apart
FORMS = ("creep", "relaxation", "dma", "sweeps", "time", "card")


def _split(line: str) -> list[str]:
    return [f.strip() for f in line.split(",")] if "," in line else line.split()


def _column_name(raw: str) -> tuple:
    """``'Storage [MPa]'`` -> ``('storage', 'MPa')``: the name in lower case, and the unit in
    brackets or parentheses (None without one)."""
    name, unit = raw.strip(), None
    for opener, closer in ("[]", "()"):
        if opener in name:
            name, rest = name.split(opener, 1)
            unit = rest.split(closer, 1)[0].strip()
            break
    return name.strip().lower().replace(" ", "_"), unit


def _data_lines(path, option: str, data: bytes | None = None) -> list:
    """``(line number, fields)`` of each non-comment line of a UTF-8 text file (``data``: its
    bytes when already read).

    ``#`` starts a comment; fields are separated by commas (or blanks when a line has no
    comma).  A missing, binary or non-UTF-8 file is the refusal of ``option=path``.
    """
    return [(n, _split(line)) for n, line in _text.lines(_text.read_text(path, option, data))]


def _read_table(path, option: str, columns: dict):
    """The named columns of a CSV file, with the line number of each row.

    ``columns`` maps each required column to the header names accepted for it.  ``#`` starts a
    comment; fields are separated by commas (or blanks when a line has no comma); the first
    non-comment line is the header.  Other columns are ignored.  Returns the columns, the line
    number of each row and the unit each required column's header gives (or None).  Raises the
    refusal of ``option=path`` naming the line for anything broken.
    """
    where = str(path)
    rows = _data_lines(path, option)
    need = ", ".join(columns)
    if not rows:
        raise bad(option, where, f"a header line naming the columns {need}, then data (this "
                  "file is empty or only comments)")
    head_line, head = rows[0]
    names = [_column_name(h) for h in head]
    index = {}
    for key, aliases in columns.items():
        hits = [i for i, (nm, _) in enumerate(names) if nm in aliases]
        if len(hits) != 1:
            what = "no" if not hits else "more than one"
            raise bad(option, where, f"a header line naming the columns {need} (line "
                      f"{head_line} has {what} column {key!r}: {', '.join(head)})")
        index[key] = hits[0]
    out = {key: [] for key in columns}
    lines = []
    for number, fields in rows[1:]:
        if len(fields) != len(head):
            raise bad(option, where, f"{len(head)} fields on every line, as in the header "
                      f"(line {number} has {len(fields)})")
        for key, i in index.items():
            tok = fields[i]
            try:
                v = float(tok)
            except ValueError:
                raise bad(option, where, f"numeric data (line {number}: {key} {tok!r} is not "
                          "a number)") from None
            if not math.isfinite(v):
                raise bad(option, where, f"finite numbers (line {number}: {key} is {tok!r})")
            out[key].append(v)
        lines.append(number)
    units = {key: names[i][1] for key, i in index.items()}
    return {k: np.array(v) for k, v in out.items()}, lines, units




def read_relaxation(path, *, data: bytes | None = None) -> Maxwell:
    """Read a relaxation-form (generalised Maxwell) Prony series from a text file.

    Format (``#`` starts a comment, fields separated by blanks or commas)::

        # E(t) = E_r + sum_i E_i exp(-t/theta_i)
        E_r 1.0         # relaxed (long-time) modulus
        2.0 0.3333      # one line per term: E_i (modulus)  theta_i (relaxation time)

    The ``E_r`` line (``E_r`` or ``Er``, any case) is required and comes first; there may be
    no terms (an elastic material).  It is the relaxation twin of the creep-series file of
    ``bem.read_prony`` (a first line ``J0 <value>``, then ``J_i tau_i`` with creep times), and
    the keyword of the first line says which of the two a file is.  Moduli and times are in
    the file's own units; `Maxwell.creep` converts exactly.

    Returns
    -------
    Maxwell

    Raises
    ------
    ValueError
        One line ``relaxation='path' is not allowed: ...`` naming the line at fault: a broken
        file (as for `read_dma`), a missing ``E_r`` line, a term line that is not two numbers,
        a non-finite value, ``E_r <= 0``, ``E_i < 0`` or ``theta_i <= 0``.
    """
    where = str(path)
    rows = [(n, [t for f in fields for t in f.split()]) for n, fields in
            _data_lines(path, "relaxation", data)]
    if not rows:
        raise bad("relaxation", where, "a first line 'E_r <value>' then lines 'E_i theta_i' "
                  "(this file is empty or only comments)")
    first_line, first = rows[0]
    if first[0].lower() not in ("e_r", "er") or len(first) != 2:
        raise bad("relaxation", where, f"a first line 'E_r <value>' then lines 'E_i theta_i' "
                  f"(line {first_line}: {' '.join(first)!r})")

    def numbers(number, tokens):
        out = []
        for tok in tokens:
            try:
                v = float(tok)
            except ValueError:
                raise bad("relaxation", where, f"numeric fields (line {number}: {tok!r} is "
                          "not a number)") from None
            if not math.isfinite(v):
                raise bad("relaxation", where, f"finite numbers (line {number}: {tok!r})")
            out.append(v)
        return out

    (e_r,) = numbers(first_line, first[1:])
    if not e_r > 0.0:
        raise bad("relaxation", where, f"a relaxed modulus E_r > 0 (line {first_line}: "
                  f"{e_r!r})")
    amps, times = [], []
    for number, fields in rows[1:]:
        if len(fields) != 2:
            raise bad("relaxation", where, f"exactly two numbers 'E_i theta_i' per term line "
                      f"(line {number} has {len(fields)})")
        e, th = numbers(number, fields)
        if not e >= 0.0:
            raise bad("relaxation", where, f"amplitudes E_i >= 0 (line {number}: {e!r})")
        if not th > 0.0:
            raise bad("relaxation", where, f"relaxation times theta_i > 0 (line {number}: "
                      f"{th!r})")
        amps.append(e)
        times.append(th)
    return Maxwell(e_r, tuple(amps), tuple(times))


def read_creep(path, *, option: str = "prony", data: bytes | None = None) -> Creep:
    """Read a creep-form (retardation) Prony series from a text file.

    Format (``#`` starts a comment, fields separated by blanks or commas)::

        J0 1.0          # relaxed compliance, in 1/E_ref
        0.6667 1.0      # one line per term: J_i (1/E_ref)  tau_i (tau_ref)

    The ``J0`` line is required and comes first; there may be no terms (an elastic material).
    ``J(t) = J0 - sum_i J_i exp(-t/tau_i)``, the ``tau_i`` retardation (creep) times.  A
    relaxation-form file (first line ``E_r <value>``, `read_relaxation`) is refused here, by name.
    Only the file's form is checked (the values' signs are the series' own checks, e.g.
    ``bem.Prony``).

    Parameters
    ----------
    path : str or Path
        The file (UTF-8 text).
    option : str
        The name refusals give the file (``bem.read_prony``'s ``prony``).

    Returns
    -------
    Creep
        ``(J0, J, tau)`` as written.

    Raises
    ------
    ValueError
        ``<option>='path' is not allowed: ...``: an unreadable, binary, non-UTF-8 or empty file,
        a missing ``J0`` line, a term line that is not two numbers, a non-finite value.
    """
    where = str(path)
    rows = [[t for f in fields for t in f.split()] for _, fields in
            _data_lines(path, option, data)]
    if not rows:
        raise bad(option, where, "a file with data (this one is empty or only comments)")
    if rows[0][0].lower() in ("e_r", "er"):  # the relaxation twin of this format
        raise bad(option, where, "a creep series (first line 'J0 <value>'); this is a "
                  "relaxation series (first line 'E_r'): convert it exactly with "
                  "viscosine.materials.read_relaxation(path).creep(), or give it to --material")
    if rows[0][0].lower() != "j0" or len(rows[0]) != 2:
        raise bad(option, where, "a first line 'J0 <value>' then lines 'J_i tau_i'")
    if any(len(r) != 2 for r in rows[1:]):
        raise bad(option, where, "exactly two numbers 'J_i tau_i' per term line")

    def numbers(tokens):
        out = []
        for t in tokens:
            try:
                v = float(t)
            except ValueError:
                raise bad(option, where, f"numeric fields ({t!r} is not a number)") from None
            if not math.isfinite(v):
                raise bad(option, where, f"finite numbers ({t!r} is not finite)")
            out.append(v)
        return out

    (j0,) = numbers(rows[0][1:])
    terms = [numbers(r) for r in rows[1:]]
    return Creep(j0, tuple(t[0] for t in terms), tuple(t[1] for t in terms))



def material_form(path, *, data: bytes | None = None) -> str:
    """Which of the accepted `FORMS` a material file is, from its first lines.

    * ``"creep"``: ``J0 <value>`` (a creep-series file, `read_creep`, ``bem.read_prony``);
    * ``"relaxation"``: ``E_r <value>`` (a relaxation-series file, `read_relaxation`);
    * ``"dma"``: a table whose header names frequency, storage and loss columns (`read_dma`);
    * ``"sweeps"``: such a table with a temperature column too (raw isotherms, `read_sweeps`);
    * ``"time"``: a header naming a time column and E(t) or J(t) (`read_time_data`);
    * ``"card"``: an FE Prony card or a pyvisco table (`read_card`; ``card_form`` says which).

    ``data``: the file's bytes when the caller has read them (the file is then not opened).

    Raises
    ------
    ValueError
        One line ``material='path' is not allowed: ...``: an unreadable, binary, non-UTF-8 or
        empty file, or a first line that is none of the three.
    """
    where = str(path)
    rows = _text.lines(_text.read_text(path, "material", data))
    # what is allowed, short (a command line shows only this), then each form
    short = "a creep or relaxation series, Prony card, E(t)/J(t) or DMA curve"
    forms = ("a creep series (first line 'J0 <value>'), a relaxation series (first line "
             "'E_r <value>'), an FE Prony card, E(t) or J(t) (time, E or J) or a DMA master "
             "curve (a table whose header names frequency, storage, loss; with temperature: "
             "raw isotherms)")
    if not rows:
        raise bad("material", where, f"{short} (empty or only comments): {forms}")
    number, line = rows[0]
    tokens = line.replace(",", " ").split()
    key = tokens[0].lower()
    # the newer forms' modules read tables with this module's helpers: imported here, not at
    # the top, so that the import graph has no cycle
    from ._cards import lines_form
    from ._sweeps import sweeps_header
    from ._timedata import time_header
    if lines_form([text for _, text in rows]) is not None:
        return "card"
    fields = _text.split(line, _text.separator(line))
    if sweeps_header(fields) is not None:
        return "sweeps"
    if time_header(fields) is not None:
        return "time"
    if key == "j0":
        return "creep"
    if key in ("e_r", "er"):
        return "relaxation"
    from ._dmafile import _find_header
    try:
        _find_header(rows, "")
        return "dma"
    except ValueError:
        pass
    shown = " ".join(tokens)
    if len(shown) > 40:
        shown = shown[:36] + " ..."
    raise bad("material", where, f"{short}: {forms}; line {number} begins {shown!r}")


_SHIFT_COLUMNS = {"temperature": ("temperature", "t", "temp"),
                  "log_aT": ("log_at", "log10_at", "log_a_t", "log10_a_t")}


def read_shift_table(path) -> ShiftTable:
    """Read a time–temperature shift table from a CSV file.

    Format: a header naming the columns ``temperature`` and ``log_aT`` (or ``log10_aT``; any
    case, an optional unit in brackets), then one row per temperature, increasing; ``#``
    starts a comment; other columns are ignored.

    Returns
    -------
    ShiftTable

    Raises
    ------
    ValueError
        One line naming the file (and line): a broken file as for `read_dma`, temperatures not
        strictly increasing, ``log10 a_T`` not strictly decreasing, fewer than 2 rows.
    """
    cols, lines, _ = _read_table(path, "shift_table", _SHIFT_COLUMNS)
    t, log_a = cols["temperature"], cols["log_aT"]
    if t.size < 2:
        raise bad("shift_table", str(path), f"at least 2 temperatures (got {t.size})")
    for j in range(1, t.size):
        if t[j] <= t[j - 1]:
            raise bad("shift_table", str(path), f"strictly increasing temperatures (line "
                      f"{lines[j]}: {t[j]!r} after {t[j - 1]!r})")
        if log_a[j] >= log_a[j - 1]:
            raise bad("shift_table", str(path), f"log10 a_T strictly decreasing with T "
                      f"(line {lines[j]}: {log_a[j]!r} after {log_a[j - 1]!r}; relaxation is "
                      "faster when hot)")
    return ShiftTable(tuple(t.tolist()), tuple(log_a.tolist()))
