"""Raw multi-temperature frequency sweeps (the isotherms a DMA measures before any shifting).

Layout read by `read_sweeps` (docs/materials.md): one long table, one row per measured point,
with a header naming a temperature column and the frequency, storage and loss columns of a DMA
master curve (any order and case, units in brackets; other columns ignored)::

    # isotherms of a filled SBR, 0.1 ... 100 Hz
    temperature [degC], frequency [Hz], storage [MPa], loss [MPa]
    -30, 0.1, 812.4, 301.2
    -30, 0.1585, 870.0, 298.7
    ...
    -25, 0.1, 640.1, 310.5

Rows of one temperature form one isotherm (rows may come in any order; temperatures within
`SAME_TEMPERATURE` of one another are one isotherm, as instruments log a drifting set point).
The temperature unit (``degC``, ``C``, ``K``, ``degF``) is kept: a vertical shift T ρ/(T0 ρ0)
needs absolute temperatures, and the shift constants come out in the file's unit.  An optional
``density`` column gives ρ(T) for that vertical shift.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from ..checks import bad
from ._units import poisson
from ._files import _column_name, _data_lines

#: temperatures closer than this (in the file's unit) are one isotherm
SAME_TEMPERATURE = 0.05
#: fewest points of an isotherm, and fewest isotherms
MIN_ISOTHERM_POINTS = 3
MIN_ISOTHERMS = 3
#: header names of each column (lower case, blanks as underscores, unit removed)
COLUMNS = {"temperature": ("temperature", "temp", "t", "t_set", "temperature_set"),
           "frequency": ("frequency", "freq", "f", "omega", "angular_frequency", "w"),
           "storage": ("storage", "e'", "storage_modulus", "e1", "g'", "g1", "storage_(e')"),
           "loss": ("loss", "e''", "loss_modulus", "e2", "g''", "g2"),
           "density": ("density", "rho")}
#: temperature units and the offset that makes them kelvin (degF: scaled too)
KELVIN = {"k": ("K", 0.0), "degc": ("degC", 273.15), "c": ("degC", 273.15),
          "°c": ("degC", 273.15), "celsius": ("degC", 273.15), "degf": ("degF", None),
          "°f": ("degF", None)}


@dataclass(frozen=True, eq=False)
class Isotherm:
    """One frequency sweep at one temperature: angular frequencies (ascending), E', E''."""

    temperature: float
    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    density: float | None = None
    lines: tuple = ()


@dataclass(frozen=True, eq=False)
class Sweeps:
    """Isotherms ordered by temperature, with the units the file gave.

    Attributes
    ----------
    isotherms : tuple of Isotherm
        Ascending temperature; each sweep's frequencies ascending, in rad/s (of the time unit).
    temperature_unit : str or None
        ``"K"``, ``"degC"``, ``"degF"`` or None (not stated).
    modulus_unit, frequency_unit : str or None
        As in `MasterCurve` (frequency_unit is what the file gave: ``"Hz"`` or ``"rad/s"``).
    kind : str
        ``"E"`` (tensile) or ``"G"`` (shear, from the header's G' / G'').
    source : str or None
        The file.
    """

    isotherms: tuple
    temperature_unit: str | None = None
    modulus_unit: str | None = None
    frequency_unit: str | None = None
    kind: str = "E"
    source: str | None = None
    notes: tuple = field(default=())

    @property
    def temperatures(self) -> np.ndarray:
        return np.array([iso.temperature for iso in self.isotherms])

    def tensile(self, nu=None) -> "Sweeps":
        """These isotherms in tensile moduli: shear ones (``kind="G"``) times 2 (1 + nu), the
        Poisson ratio ``nu`` in (-1, 0.5] taken not to relax (E = 2 (1 + nu) G; the shifts are
        unchanged: one factor on every isotherm); tensile ones as they are (``nu`` unused)."""
        if self.kind != "G":
            return self
        nu = poisson(nu, f"the shear isotherms of {self.source or 'Sweeps'!r}")
        f = 2.0 * (1.0 + nu)
        isos = tuple(replace(i, storage=i.storage * f, loss=i.loss * f) for i in self.isotherms)
        return replace(self, isotherms=isos, kind="E",
                       notes=self.notes + (f"shear moduli turned into tensile ones: "
                                           f"E = 2 (1 + {nu:g}) G",))

    def kelvin(self, T):
        """Temperatures T (the file's unit) in kelvin; ValueError when the unit is unknown."""
        unit = (self.temperature_unit or "").lower()
        if unit == "k":
            return np.asarray(T, float)
        if unit == "degc":
            return np.asarray(T, float) + 273.15
        if unit == "degf":
            return (np.asarray(T, float) - 32.0) * 5.0 / 9.0 + 273.15
        raise bad("temperature_unit", self.temperature_unit, "K, degC or degF stated in the "
                  "header ('temperature [degC]'): the vertical shift T rho/(T0 rho0) needs "
                  "absolute temperatures")


def _role(name):
    for role, aliases in COLUMNS.items():
        if name in aliases:
            return role
    return None


def sweeps_header(fields):
    """``{role: column index}`` when a header line names temperature, frequency, storage and
    loss columns (and maybe density), else None."""
    roles = {}
    for i, raw in enumerate(fields):
        role = _role(_column_name(raw)[0])
        if role is None:
            continue
        if role in roles:
            return None
        roles[role] = i
    need = ("temperature", "frequency", "storage", "loss")
    return roles if all(r in roles for r in need) else None


def read_sweeps(path, *, frequency_unit: str | None = None) -> Sweeps:
    """Read raw frequency sweeps at several temperatures (module docstring).

    Parameters
    ----------
    path : str or Path
        UTF-8 text; ``#`` starts a comment; fields separated by commas or blanks.
    frequency_unit : {"Hz", "rad/s"}, optional
        The frequency column's unit when the header does not give one (default rad/s).

    Returns
    -------
    Sweeps

    Raises
    ------
    ValueError
        ``sweeps='path' is not allowed: ...`` naming the line at fault: no header with the four
        columns, a ragged or non-numeric row, a value <= 0, fewer than `MIN_ISOTHERMS`
        isotherms or an isotherm of fewer than `MIN_ISOTHERM_POINTS` distinct frequencies, a
        unit the file and the argument disagree on.
    """
    where = str(path)
    rows = _data_lines(path, "sweeps")
    if not rows:
        raise bad("sweeps", where, "a header naming temperature, frequency, storage and loss "
                  "columns, then one row per measured point (the file is empty)")
    head_line, head = rows[0]
    roles = sweeps_header(head)
    if roles is None:
        raise bad("sweeps", where, "a header naming temperature, frequency, storage and loss "
                  f"columns (line {head_line}: {', '.join(head)})")
    units = {role: _column_name(head[i])[1] for role, i in roles.items()}
    kinds = {_column_name(head[roles[r]])[0][:1] for r in ("storage", "loss")}
    kind = "G" if kinds == {"g"} else "E"
    t_unit = units["temperature"]
    t_name = None if t_unit is None else KELVIN.get(t_unit.strip().lower(), (t_unit, None))[0]
    stated = {"hz": "Hz", "rad/s": "rad/s", "1/s": None}.get((units["frequency"] or "").lower())
    if stated is not None and frequency_unit is not None and stated != frequency_unit:
        raise bad("frequency_unit", frequency_unit, f"the unit of the frequency column of "
                  f"{where!r} ({units['frequency']!r}), or None")
    f_unit = stated or frequency_unit or "rad/s"
    factor = 2.0 * math.pi if f_unit == "Hz" else 1.0
    mod_units = {units[r] for r in ("storage", "loss")}
    if len(mod_units) > 1:
        raise bad("sweeps", where, f"storage and loss in one unit (the header gives "
                  f"{units['storage']!r} and {units['loss']!r})")
    data = []
    for number, fields in rows[1:]:
        if len(fields) != len(head):
            raise bad("sweeps", where, f"{len(head)} fields on every line, as in the header "
                      f"(line {number} has {len(fields)})")
        row = {}
        for role, i in roles.items():
            try:
                v = float(fields[i])
            except ValueError:
                raise bad("sweeps", where, f"numeric data (line {number}: {role} "
                          f"{fields[i]!r} is not a number)") from None
            if not math.isfinite(v) or (role != "temperature" and v <= 0.0):
                raise bad("sweeps", where, f"finite {role} values"
                          + ("" if role == "temperature" else " > 0")
                          + f" (line {number}: {fields[i]!r})")
            row[role] = v
        data.append((number, row))
    return Sweeps(_isotherms(data, factor, where), temperature_unit=t_name,
                  modulus_unit=mod_units.pop(), frequency_unit=f_unit, kind=kind, source=where)


def _isotherms(data, factor, where):
    """Group rows into isotherms by temperature (ascending), each sorted by frequency."""
    data = sorted(data, key=lambda r: r[1]["temperature"])
    groups, current = [], []
    for item in data:
        if current and item[1]["temperature"] - current[0][1]["temperature"] > SAME_TEMPERATURE:
            groups.append(current)
            current = []
        current.append(item)
    if current:
        groups.append(current)
    if len(groups) < MIN_ISOTHERMS:
        raise bad("sweeps", where, f"at least {MIN_ISOTHERMS} temperatures (got "
                  f"{len(groups)}); a single curve is a master curve: give it as a DMA table")
    out = []
    for g in groups:
        g = sorted(g, key=lambda r: r[1]["frequency"])
        w = np.array([r["frequency"] for _, r in g]) * factor
        if np.unique(w).size < MIN_ISOTHERM_POINTS:
            raise bad("sweeps", where, f"at least {MIN_ISOTHERM_POINTS} frequencies per "
                      f"temperature (line {g[0][0]}: temperature {g[0][1]['temperature']!r} "
                      f"has {np.unique(w).size})")
        dens = [r["density"] for _, r in g if "density" in r]
        out.append(Isotherm(float(np.mean([r["temperature"] for _, r in g])), w,
                            np.array([r["storage"] for _, r in g]),
                            np.array([r["loss"] for _, r in g]),
                            float(np.mean(dens)) if dens else None,
                            tuple(n for n, _ in g)))
    return tuple(out)


def write_sweeps(path, sweeps_rows, *, temperature_unit="degC", frequency_unit="Hz",
                 modulus_unit="MPa", comment=None):
    """Write rows ``(T, f, E', E'')`` (frequencies in ``frequency_unit``) in the layout read by
    `read_sweeps`: the test sets and the tutorial's data are made with it."""
    lines = [] if comment is None else [f"# {c}" for c in comment.splitlines()]
    lines.append(f"temperature [{temperature_unit}],frequency [{frequency_unit}],"
                 f"storage [{modulus_unit}],loss [{modulus_unit}]")
    lines += [f"{t!r},{f!r},{e1!r},{e2!r}" for t, f, e1, e2 in sweeps_rows]
    from pathlib import Path
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")
