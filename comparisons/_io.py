"""Files written so that an interrupted run never leaves half of one: the one atomic writer of
text (UTF-8, '\\n' line ends, whatever the locale) and what makes a document JSON; the checks,
before any work, that an output file or folder can be written; the one reader of an input
file's bytes (and text); one line on standard error; the reader of a CSV's numeric columns."""
from __future__ import annotations

import csv
import math
import os
import secrets
import stat
import sys
from pathlib import Path

import numpy as np

from ._errors import BadInput, bad_input


def temporary_name(path) -> str:
    """A name beside ``path`` that no other process or write uses (hidden, ``.part``)."""
    folder, base = os.path.split(os.fspath(path))
    return os.path.join(folder, f".{base}.{os.getpid()}.{secrets.token_hex(4)}.part")


def write_text(path, text: str) -> None:
    """Write ``text`` to ``path`` atomically: into a temporary file in the same folder (made
    when missing), renamed over ``path`` once complete; the temporary file never outlives a
    failure."""
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    tmp = temporary_name(path)
    try:
        with open(tmp, "w", encoding="utf-8", newline="\n") as fh:
            fh.write(text)
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.unlink(tmp)


def jsonable(o):
    """``o`` ready for strict JSON (``allow_nan=False``): NumPy scalars as Python's, non-finite
    floats as None (JSON null), tuples as lists, through dicts and lists."""
    if isinstance(o, dict):
        return {k: jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [jsonable(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return float(o) if math.isfinite(o) else None
    if isinstance(o, np.integer):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o


def stderr(text) -> None:
    """One line (or more) on standard error, at once."""
    print(text, file=sys.stderr, flush=True)


def check_output_file(option, path) -> None:
    """An output file must be creatable: its folder exists, and it is not a folder/device/FIFO.

    Raises
    ------
    BadInput
        naming ``option`` and ``path``.
    """
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a file")
    folder = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(folder):
        raise BadInput(f"{option} {path}: the folder {folder} does not exist")
    if os.path.lexists(path):
        st = os.stat(path) if os.path.exists(path) else os.lstat(path)
        if not stat.S_ISREG(st.st_mode):
            raise BadInput(f"{option} {path}: {_kind(st.st_mode)}, not a regular file")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder {folder} is not writable")


def check_output_dir(option, path, create) -> None:
    """An output folder: an existing folder, or (create) one whose parent exists.

    Raises
    ------
    BadInput
        naming ``option`` and ``path``.
    """
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a folder")
    if os.path.exists(path):
        if not os.path.isdir(path):
            raise BadInput(f"{option} {path}: an existing file, not a folder")
    else:
        parent = os.path.dirname(os.path.abspath(path))
        if not os.path.isdir(parent):
            raise BadInput(f"{option} {path}: the folder {parent} does not exist")
        if not os.access(parent, os.W_OK | os.X_OK):  # it could not be made there
            raise BadInput(f"{option} {path}: the folder {parent} is not writable")
        if create:
            try:
                os.mkdir(path)
            except OSError as exc:
                raise BadInput(f"{option} {path}: cannot create the folder ({exc.strerror})") from None
    if os.path.isdir(path) and not os.access(path, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder is not writable")


def file_bytes(option, path, allowed=None):
    """The bytes of an input file, which must be a regular UTF-8 text file.

    Raises
    ------
    BadInput
        One line ``<option> <path>: <problem>`` (a missing, special, unreadable, binary or
        non-UTF-8 file), then ``; allowed: <allowed>`` when given.
    """
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a file")
    try:
        st = os.stat(path)
    except OSError as exc:
        raise bad_input(option, path, f"cannot read the file ({exc.strerror})", allowed) from None
    if not stat.S_ISREG(st.st_mode):  # a FIFO is refused here, never read (it could block)
        raise bad_input(option, path, f"not a regular file ({_kind(st.st_mode)})", allowed)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise bad_input(option, path, f"cannot read the file ({exc.strerror})", allowed) from None
    if b"\0" in data:
        raise bad_input(option, path, "a binary file, not text", allowed)
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise bad_input(option, path, f"not UTF-8 text (byte {exc.start})", allowed) from None
    return data


def read_text(option, path, allowed):
    """The text of an input file (`file_bytes`, each refusal naming what is ``allowed``); a
    missing file is said to be one, and a file of blank lines only is refused as empty."""
    if not os.path.exists(path):
        raise bad_input(option, path, "no such file", allowed)
    data = file_bytes(option, path, allowed)
    if not data.strip():
        raise bad_input(option, path, "the file is empty", allowed)
    return data.decode("utf-8")


def _kind(mode):
    if stat.S_ISDIR(mode):
        return "a folder"
    if stat.S_ISFIFO(mode):
        return "a FIFO"
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "a device"
    if stat.S_ISSOCK(mode):
        return "a socket"
    return "not a regular file"


def read_columns(path) -> dict:
    """The columns of a UTF-8 CSV of numbers (``#`` lines skipped, then a header row): name →
    float array (the suite's fields files, written by `comparisons.suite.write_fields`)."""
    with open(path, encoding="utf-8") as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
    head = rows[0]
    data = np.array(rows[1:], dtype=float)
    return {h: data[:, i] for i, h in enumerate(head)}
