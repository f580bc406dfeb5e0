"""The measured window travels with a series: written into a series file, read back from it.

A series fitted to data (or converted from a fit) is trusted between the lowest and highest
frequency the data measured.  `write_series` writes a relaxation (``E_r`` first) or creep
(``J0`` first) series file as `read_relaxation` and `read_creep` read it, with the window as a
header comment both readers skip::

    # measured window: 0.000628 628000000 rad/s  (from dma-sbr.csv, sha256 155eb27d...)
    E_r 3.14348
    ...

`read_window` finds that line in any material file: ``(w_lo, w_hi)`` in rad per time unit of
the file, or None.  `read_series` reads a relaxation or creep series file into a `Maxwell` whose
``fit`` is a `MeasuredWindow` when the file has the line, so that the Python route
(``bem.solve_si(material=...)``) warns as the command line does.
"""
from __future__ import annotations

import hashlib
import math
import re
from dataclasses import dataclass, replace
from pathlib import Path

from ..checks import bad
from ._series import Maxwell

#: the header line, as written and as searched
PREFIX = "# measured window:"
_PATTERN = re.compile(r"^\s*#\s*measured window:\s*([^\s,]+)[\s,]+([^\s,]+)\s*rad/s",
                      re.IGNORECASE)


@dataclass(frozen=True)
class MeasuredWindow:
    """The measured window a series file carried: what `Maxwell.extrapolation_warning` needs,
    and no fit report (the file holds the series, not the data).

    ``modulus_unit`` is "Pa": a series file's moduli are in pascals on the SI route by its
    convention (`Maxwell.in_pascals` leaves them as they are).
    """

    window: tuple
    source: str | None = None
    modulus_unit: str | None = "Pa"


def read_series(path) -> Maxwell:
    """A relaxation (``E_r`` first) or creep (``J0`` first, converted exactly) series file,
    with its measured window (`MeasuredWindow`) when it has a ``# measured window`` line."""
    from ._files import material_form, read_creep, read_relaxation
    data = Path(path).read_bytes()
    form = material_form(path, data=data)
    if form == "relaxation":
        model = read_relaxation(path, data=data)
    elif form == "creep":
        model = Maxwell.from_creep(*read_creep(path, option="series", data=data))
    else:
        raise bad("series", str(path), f"a relaxation or creep series file (this is {form})")
    window = read_window(path, data)
    return model if window is None else replace(model, fit=MeasuredWindow(window, str(path)))


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
