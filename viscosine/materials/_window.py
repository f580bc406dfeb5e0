"""The measured window travels with a series: written into a series file, read back from it.

A series fitted to data (or converted from a fit) is trusted between the lowest and highest
frequency the data measured.  `write_series` writes a relaxation (``E_r`` first) or creep
(``J0`` first) series file as `read_relaxation` and `read_creep` read it, with the window as a
header comment both readers skip::

    # measured window: 0.000628 628000000 rad/s  (from dma-sbr.csv, sha256 155eb27d...)
    E_r 3.14348
    ...

`read_window` finds that line in any material file: ``(w_lo, w_hi)`` in rad per time unit of
the file, or None.
"""
from __future__ import annotations

import hashlib
import math
import re
from pathlib import Path

from ..checks import bad
from ._series import Maxwell

#: the header line, as written and as searched
PREFIX = "# measured window:"
_PATTERN = re.compile(r"^\s*#\s*measured window:\s*([^\s,]+)[\s,]+([^\s,]+)\s*rad/s",
                      re.IGNORECASE)


def read_window(path, data: bytes | None = None):
    """``(w_lo, w_hi)`` of a file's ``# measured window: LO HI rad/s`` line, or None.

    Raises
    ------
    ValueError
        A window line whose numbers are not 0 < LO <= HI (``window='path' is not allowed``).
    """
    if data is None:
        data = Path(path).read_bytes()
    for line in data.decode("utf-8", errors="replace").splitlines()[:50]:
        m = _PATTERN.match(line)
        if m:
            try:
                lo, hi = float(m.group(1)), float(m.group(2))
            except ValueError:
                lo = hi = math.nan
            if not (math.isfinite(lo) and math.isfinite(hi) and 0.0 < lo <= hi):
                raise bad("window", str(path), f"a line '{PREFIX} LO HI rad/s' with 0 < LO <= "
                          f"HI (got {line.strip()!r})")
            return lo, hi
    return None


def write_series(path, model: Maxwell, *, form: str = "relaxation", window=None,
                 source: str | None = None, E_ref: float = 1.0, tau_ref: float = 1.0):
    """Write ``model`` as a relaxation or creep series file that keeps its measured window.

    Parameters
    ----------
    model : Maxwell
        The series; its ``fit.window`` is the window unless ``window`` is given.
    form : {"relaxation", "creep"}
        ``E_r`` then ``E_i theta_i``, or ``J0`` then ``J_i tau_i`` (`Maxwell.creep`, exact).
    window : (float, float), optional
        Measured frequencies (rad per time unit of the series).
    source : str, optional
        The data file: named in the header with its SHA-256.
    E_ref, tau_ref : float
        Units of a creep file (as `Maxwell.creep`); the window is written in 1/tau_ref.
    """
    if form not in ("relaxation", "creep"):
        raise bad("form", form, "'relaxation' or 'creep'")
    if window is None and getattr(model, "fit", None) is not None:
        window = model.fit.window
    lines = []
    if window is not None:
        lo, hi = (w * tau_ref for w in window)
        note = ""
        if source is not None:
            digest = hashlib.sha256(Path(source).read_bytes()).hexdigest()
            note = f"  (from {Path(source).name}, sha256 {digest})"
        lines.append(f"{PREFIX} {lo!r} {hi!r} rad/s{note}")
    if form == "relaxation":
        lines.append(f"E_r {model.E_r!r}")
        lines += [f"{e!r} {t!r}" for e, t in zip(model.E, model.theta)]
    else:
        c = model.creep(E_ref=E_ref, tau_ref=tau_ref)
        lines.append(f"J0 {c.J0!r}")
        lines += [f"{j!r} {t!r}" for j, t in zip(c.J, c.tau)]
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")
