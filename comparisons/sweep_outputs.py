"""A sweep's table and picture (``sweep --csv FILE --plot FILE``): one CSV row per solved point,
appended and flushed as each is printed, so that an interrupted sweep keeps its finished rows;
μ against the speed, one curve per load (or penetration), drawn from the points done when the
sweep ends (interrupted or not).

The header names each column with its unit: the conventions' groups (``speed [V/V0]``), or with
``--units SI`` metres, pascals and metres per second from the record's ``si`` block
(``speed [m/s]``).  An empty cell is a value the record does not have (``ke`` in full contact,
the error estimate of the semi-analytic road).
"""
from __future__ import annotations

import csv
import os

from ._errors import BadInput, Failed
from ._io import check_output_file

#: (header, where the value is) of each column: ``key`` in the record, ``si.key`` in its SI
#: block, ``error.key`` in its error estimate; a column whose cells are all empty is still written
_GROUPS = {"load": "p∞(1-ν²)/E0", "penetration": "Δ/h"}
_LINE = (("speed [V/V0]", "speed"), ("mu [-]", "mu"), ("tau_f [τf(1-ν²)/E0]", "tau_f"),
         ("penetration [Δ/h]", "penetration"), ("contact_fraction [2a/λ]", "contact_fraction"),
         ("ka [-]", "ka"), ("ke [-]", "ke"), ("ke_hat [-]", "ke_hat"),
         ("max_pressure [σ(1-ν²)/E0]", "max_pressure"), ("full_contact [-]", "full_contact"))
_LINE_SI = (("speed [m/s]", "si.speed"), ("mean_pressure [Pa]", "si.mean_pressure"),
            ("mu [-]", "mu"), ("friction_stress [Pa]", "si.friction_stress"),
            ("penetration [m]", "si.penetration"), ("contact_fraction [-]", "contact_fraction"),
            ("contact_halfwidth [m]", "si.contact_halfwidth"),
            ("eccentricity [m]", "si.eccentricity"),
            ("pressure_eccentricity [m]", "si.pressure_eccentricity"),
            ("max_pressure [Pa]", "si.max_pressure"), ("full_contact [-]", "full_contact"))
_SURFACE = (("speed [V/V0]", "speed"), ("direction [deg]", "direction"), ("mu [-]", "mu"),
            ("mu_lateral [-]", "mu_lateral"), ("tau_f [τf(1-ν²)/E0]", "tau_f"),
            ("penetration [Δ/h_ref]", "penetration"), ("contact_fraction [-]", "contact_fraction"),
            ("max_pressure [σ(1-ν²)/E0]", "max_pressure"))
_SURFACE_SI = (("speed [m/s]", "si.speed"), ("direction [deg]", "direction"),
               ("mean_pressure [Pa]", "si.mean_pressure"), ("mu [-]", "mu"),
               ("mu_lateral [-]", "mu_lateral"), ("friction_stress [Pa]", "si.friction_stress"),
               ("penetration [m]", "si.penetration"), ("contact_fraction [-]", "contact_fraction"),
               ("max_pressure [Pa]", "si.max_pressure"))
#: what every row ends with: the estimate, the mesh and the parameters that produced it
_TAIL = (("mu_error [-]", "error.mu"), ("nodes [-]", "nodes"), ("solver", "solver"),
         ("ratio [E∞/E0]", "ratio"), ("hk [-]", "hk"))


def columns(control, si, surface):
    """[(header, where)] of a sweep's table, in order (see the module's docstring)."""
    if si:
        head = [] if control == "load" else [("penetration_asked [m]", "si.penetration")]
        body = _SURFACE_SI if surface else _LINE_SI
        body = [c for c in body if not (control == "penetration" and c[1] == "si.penetration")]
        return head + list(body) + list(_TAIL)
    body = [c for c in (_SURFACE if surface else _LINE) if c[1] != control]
    return [(f"{control} [{_GROUPS[control]}]", control)] + body + list(_TAIL)


def value(record, where):
    """The cell of ``record`` at ``where`` ('' when absent; booleans as 0/1)."""
    kind, _, key = where.rpartition(".")
    holder = {"": record, "si": record.get("si"), "error": record.get("error_estimate")}[kind]
    v = (holder or {}).get(key)
    if v is None:
        return ""
    return int(v) if isinstance(v, bool) else v


def check(csv_path, plot_path):
    """Refuse, before any work, an output that could not be written.

    Raises
    ------
    BadInput
        naming the option, its value and what is allowed.
    """
    from .plots.sweep import FORMATS
    for option, path in (("--csv", csv_path), ("--plot", plot_path)):
        if path is not None:
            check_output_file(option, path)
    if plot_path is not None and os.path.splitext(plot_path)[1].lower() not in FORMATS:
        raise BadInput(f"--plot {plot_path}: must end in {', '.join(FORMATS)} (the format is "
                       "the extension's)")


class Outputs:
    """The table and the picture of one sweep; ``add(index, record)`` after each printed point,
    ``close()`` at the end (a ``with`` block does it, interrupted or not).

    Parameters
    ----------
    csv_path, plot_path : str or None
    control : {"load", "penetration"}
    n_speeds : int
        Speeds per curve (the sweep's inner loop).
    si, surface : bool
        ``--units SI``; a surface's sweep.
    """

    def __init__(self, csv_path, plot_path, *, control, n_speeds, si, surface):
        self.plot_path, self.control, self.n_speeds = plot_path, control, n_speeds
        self.si = si
        self.columns = columns(control, si, surface)
        self.curves = {}  # index of the load -> (label, speeds, mus)
        self.title = None
        self._fh = self._writer = None
        if csv_path is not None:
            try:
                self._fh = open(csv_path, "w", encoding="utf-8", newline="")
            except OSError as exc:
                raise Failed(f"cannot write --csv {csv_path} ({exc.strerror or exc})") from None
            self._writer = csv.writer(self._fh)
            self._row([h for h, _ in self.columns])

    def _row(self, cells):
        self._writer.writerow(cells)
        self._fh.flush()  # the row is on disk before the next point starts

    def add(self, index, record):
        """One solved point (the sweep's ``index``-th, loads outer): a row and a curve's point."""
        if self._writer is not None:
            self._row([value(record, w) for _, w in self.columns])
        if self.plot_path is None:
            return
        label, speeds, mus = self.curves.setdefault(index // self.n_speeds,
                                                    (self._label(record), [], []))
        speeds.append(record["si"]["speed"] if self.si else record["speed"])
        mus.append(record["mu"])
        if self.title is None:
            self.title = self._provenance(record)

    def _label(self, record):
        if self.si:
            if self.control == "load":
                return f"p∞ = {record['si']['mean_pressure']:.4g} Pa"
            return f"Δ = {record['si']['penetration']:.4g} m"
        if self.control == "load":
            return f"p̃∞ = {record['load']:.4g}"
        return f"Δ/h = {record['penetration']:.4g}"

    def _provenance(self, record):
        """The parameters that produced the figure, for its title."""
        parts = [f"viscosine {record.get('version', '')}", f"solver {record['solver']}"]
        if self.si and record.get("si_scales"):
            s = record["si_scales"]
            parts += [f"λ = {s['wavelength']:.4g} m", f"h = {s['amplitude']:.4g} m",
                      f"ν = {s['nu']:g}", f"E_ref = {s['E_ref']:.4g} Pa",
                      f"τ = {s['tau_ref']:.4g} s"]
        for key, name in (("ratio", "E∞/E0"), ("hk", "hk")):
            if record.get(key) is not None:
                parts.append(f"{name} = {record[key]:g}")
        return ", ".join(parts)

    def close(self):
        """Close the table; draw the curves of the points done."""
        if self._fh is not None:
            self._fh.close()
            self._fh = self._writer = None
        if self.plot_path is not None:
            from .plots.sweep import write_figure
            curves = [self.curves[k] for k in sorted(self.curves)]
            try:
                write_figure(self.plot_path, curves, title=self.title or "",
                             xlabel="V [m/s]" if self.si else "V/V0")
            except OSError as exc:
                raise Failed(f"cannot write --plot {self.plot_path} "
                             f"({exc.strerror or exc})") from None
            self.plot_path = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False
