"""Text tables as labs write them: the bytes of a file, its lines, separators, numbers.

Format knowledge (which columns, which units) lives in `_files`; this module only cuts text:

* a file is UTF-8 text (a byte-order mark is skipped); ``#`` starts a comment;
* fields are separated by ``;``, a tab, ``,`` or blanks: the first of these a line holds;
* with ``;``, tab or blank separators a decimal comma (``3,31``) is read as a decimal point;
* fields in double quotes are unquoted; with blank separators a bracketed unit (``E' [MPa]``)
  stays with its name.
"""
from __future__ import annotations

import math
import re
from pathlib import Path

from ..checks import bad

_DECIMAL_COMMA = re.compile(r"^[+-]?\d*,\d+(?:[eE][+-]?\d+)?$")


def read_text(path, option: str, data: bytes | None = None) -> str:
    """The text of a UTF-8 file (``data``: its bytes, already read by the caller, so that a file
    is opened once).  A missing, binary or non-UTF-8 file is the refusal of ``option=path``."""
    where = str(path)
    if data is None:
        try:
            data = Path(path).read_bytes()
        except OSError as exc:
            raise bad(option, where, f"a readable file ({exc.strerror or exc})") from None
    if b"\0" in data:
        raise bad(option, where, "a UTF-8 text file (this one is binary: NUL bytes)")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise bad(option, where, f"a UTF-8 text file (byte {exc.start} is not UTF-8)") from None
    return text.lstrip("\ufeff")


def lines(text: str) -> list:
    """``(line number, text)`` of each line with something left after its ``#`` comment."""
    out = []
    for number, raw in enumerate(text.splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if line:
            out.append((number, line))
    return out


def separator(line: str):
    """``;``, tab or ``,`` (the first a line holds, in that order), or None: blanks."""
    for sep in (";", "\t", ","):
        if sep in line:
            return sep
    return None


def split(line: str, sep) -> list:
    """The fields of a line (stripped, unquoted; trailing empty fields dropped)."""
    if sep is None:
        fields = []
        for tok in line.split():
            if fields and tok[:1] in "[(" and not fields[-1].endswith(("]", ")")):
                fields[-1] += " " + tok   # "E' [MPa]": the unit stays with its name
            else:
                fields.append(tok)
    else:
        fields = [f.strip() for f in line.split(sep)]
    fields = [f[1:-1].strip() if len(f) >= 2 and f[0] == f[-1] == '"' else f for f in fields]
    while fields and fields[-1] == "":
        fields.pop()
    return fields


def number(tok: str, sep):
    """The float a field holds, or None; a decimal comma is read where commas do not separate."""
    try:
        return float(tok)
    except ValueError:
        pass
    if sep != "," and _DECIMAL_COMMA.match(tok):
        return float(tok.replace(",", "."))
    return None


def is_finite_number(tok: str, sep) -> bool:
    v = number(tok, sep)
    return v is not None and math.isfinite(v)
