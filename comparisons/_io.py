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


# One rule for every output a command writes (a file or a folder), checked before any work:
# missing folders on its way are made (as `write_text` makes them); anything else that stops
# the writing is bad input (exit status 2) in one line naming the option, the path and why.
def _blocker(path):
    """Why folders cannot be made up to ``path`` (None when they can): the nearest existing
    ancestor must be a writable folder."""
    anc = os.path.dirname(os.path.abspath(path))
    while not os.path.lexists(anc):
        anc = os.path.dirname(anc)
    if not os.path.isdir(anc):
        return f"{anc} is a file, not a folder"
    if not os.access(anc, os.W_OK | os.X_OK):
        return f"the folder {anc} is not writable"
    return None


def _missing(folder):
    """The folders that do not exist on the way to ``folder``, deepest first."""
    out = []
    while not os.path.lexists(folder):
        out.append(folder)
        folder = os.path.dirname(folder)
    return out


def _make_folders(option, path, folder) -> None:
    """Make ``folder`` (and its missing parents), refusing in one line when it cannot be."""
    if os.path.isdir(folder):
        return
    why = _blocker(os.path.join(folder, "x"))
    if why is None:
        try:
            os.makedirs(folder, exist_ok=True)
            return
        except OSError as exc:
            why = f"cannot create {folder} ({exc.strerror})"
    raise BadInput(f"{option} {path}: {why}")


def check_output_file(option, path) -> None:
    """An output file must be writable: its folder made when missing (with its parents), and
    the file not a folder, device or FIFO.

    Raises
    ------
    BadInput
        naming ``option`` and ``path``.
    """
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a file")
    folder = os.path.dirname(os.path.abspath(path))
    _make_folders(option, path, folder)
    if os.path.lexists(path):
        st = os.stat(path) if os.path.exists(path) else os.lstat(path)
        if not stat.S_ISREG(st.st_mode):
            raise BadInput(f"{option} {path}: {_kind(st.st_mode)}, not a regular file")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder {folder} is not writable")


def check_output_dir(option, path, create) -> None:
    """An output folder: an existing writable folder, or one that can be made (its missing
    parents too); made now when ``create``, else made and removed again (the only sure test;
    the command makes it when it writes).

    Raises
    ------
    BadInput
        naming ``option`` and ``path``.
    """
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a folder")
    if os.path.lexists(path) and not os.path.isdir(path):
        raise BadInput(f"{option} {path}: an existing file, not a folder")
    if not os.path.isdir(path):
        why = _blocker(path)
        if why is not None:
            raise BadInput(f"{option} {path}: {why}")
        made = _missing(os.path.abspath(path))
        _make_folders(option, path, os.path.abspath(path))  # the only sure test is to make it
        if not create:  # made when written: leave nothing behind now
            for folder in made:
                os.rmdir(folder)
    if os.path.isdir(path) and not os.access(path, os.W_OK | os.X_OK):
        raise BadInput(f"{option} {path}: the folder is not writable")


def file_bytes(option, path, allowed=None, shown=None):
    """The bytes of an input file, which must be a regular UTF-8 text file.

    Raises
    ------
    BadInput
        One line ``<option> <path>: <problem>`` (a missing, special, unreadable, binary or
        non-UTF-8 file), then ``; allowed: <allowed>`` when given; ``shown``: the path as
        the message shows it, if not as given (a Python caller's ``'name.txt'``).
    """
    said = path if shown is None else shown
    if path == "":
        raise BadInput(f"{option} '' is not allowed: the name of a file")
    try:
        st = os.stat(path)
    except OSError as exc:
        raise bad_input(option, said, f"cannot read the file ({exc.strerror})", allowed) from None
    if not stat.S_ISREG(st.st_mode):  # a FIFO is refused here, never read (it could block)
        raise bad_input(option, said, f"not a regular file ({_kind(st.st_mode)})", allowed)
    try:
        with open(path, "rb") as fh:
            data = fh.read()
    except OSError as exc:
        raise bad_input(option, said, f"cannot read the file ({exc.strerror})", allowed) from None
    if b"\0" in data:
        raise bad_input(option, said, "a binary file, not text", allowed)
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise bad_input(option, said, f"not UTF-8 text (byte {exc.start})", allowed) from None
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
