"""Files written so that an interrupted run never leaves half of one: the one atomic writer of
text (UTF-8, '\\n' line ends, whatever the locale)."""
from __future__ import annotations

import os
import secrets
from pathlib import Path


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
