"""Linear viscoelastic materials in the forms users have, turned into the creep series the
boundary-element road takes.

Users hold a relaxation-form Prony series (a generalised Maxwell model, the material card of a
finite-element code) or a DMA master curve (storage and loss moduli against frequency at a
reference temperature, with a time–temperature shift).  The BEM road takes a creep series
(``bem.Prony(J0, J, tau)``).  This module reads, checks, fits and converts; it solves nothing and
imports neither road.

Conventions
-----------
* Relaxation (Maxwell) form: ``E(t) = E_r + sum_i E_i exp(-t/theta_i)`` for t > 0, relaxation
  times ``theta_i``.  A harmonic strain ``eps0 exp(i w t)`` gives the stress ``E*(w) eps0
  exp(i w t)`` with

      E*(w) = E_r + sum_i E_i i w theta_i / (1 + i w theta_i) = E' + i E'',   E'' >= 0 for w > 0

  (the engineering sign: the strain lags the stress).
* Creep (retardation) form: ``J(t) = J0 - sum_k J_k exp(-t/tau_k)`` (eq. 2.3 of the paper
  generalised), retardation times ``tau_k``, with ``J*(w) = J(0+) + sum_k J_k/(1 + i w tau_k) =
  1/E*(w)``, ``J0 = 1/E_r`` and ``J(0+) = J0 - sum_k J_k = 1/(E_r + sum_i E_i)``.  The BEM road's
  ``jstar(n, speed)`` is this J* at ``w = n * speed`` written with the opposite sign of i (its
  modes run the other way); the series is the same.
* Units: moduli in any one unit, times in any one unit, angular frequencies in rad per that time
  unit.  `Maxwell.creep` takes ``E_ref`` and ``tau_ref`` to return the nondimensional series the
  BEM road expects (compliances in ``1/E_ref``, times in ``tau_ref``).  `Maxwell.in_pascals`
  turns a fit to data whose header named the modulus unit (`PASCALS`) into Pa.
* Files: `read_relaxation` (a relaxation series, first line ``E_r <value>``), `read_dma` (a
  master curve), `read_shift_table`; `material_form` tells a material file's form (`FORMS`)
  from its first line, ``J0`` marking the creep-series file of ``bem.read_prony``.

The two forms are exactly interconvertible: with ``p = -s`` (s the Laplace variable) the modulus
``E(p) = E_r - p sum_i E_i theta_i/(1 - p theta_i)`` is decreasing between its poles
``p = 1/theta_i``, so it has one zero below the first pole and one between each pair of
consecutive poles; these zeros are ``1/tau_k`` (the retardation times interlace with the
relaxation times, ``tau_1 > theta_1 > tau_2 > theta_2 > ...``) and ``J_k`` is the residue of
``1/E`` there.  The inverse runs the same routine on the compliance in the variable ``u = 1/p``.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): eq. (2.3), the creep
function of the standard linear solid, and eqs (2.7)–(2.8), the modulus at the sliding frequency.
N. W. Tschoegl, The Phenomenological Theory of Linear Viscoelastic Behavior (Springer, 1989),
ch. 4 (interconversion of the Prony forms).  S. W. Park & R. A. Schapery, Int. J. Solids Struct.
36, 1653 (1999) (Prony fits to frequency-domain data).  M. L. Williams, R. F. Landel & J. D. Ferry,
J. Am. Chem. Soc. 77, 3701 (1955) (the WLF shift).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import NamedTuple

import numpy as np

from .checks import bad, real, reals, series

#: fewest points of a DMA curve (and of a shift table's pair of columns) that are accepted
MIN_POINTS = 5
#: modulus units a DMA header may name (``storage [MPa]``), in pascals (matched ignoring case)
PASCALS = {"pa": 1.0, "kpa": 1e3, "mpa": 1e6, "gpa": 1e9, "n/mm2": 1e6, "n/mm^2": 1e6}
#: the forms of a material file `material_form` tells apart
FORMS = ("creep", "relaxation", "dma")


# --------------------------------------------------------------------------
# Interconversion: the zeros of a sum of simple poles
# --------------------------------------------------------------------------
def _interlaced_zeros(g0: float, c: np.ndarray, t: np.ndarray):
    """Zeros of ``G(x) = g0 - x sum_i c_i t_i/(1 - x t_i)`` on x > 0, and ``-G'`` there.

    ``g0 = G(0) > 0``, ``c_i > 0``, ``t_i > 0`` distinct.  G decreases between its poles
    ``1/t_i``, from ``g0`` at 0 and from +inf right of each pole, to -inf left of the next: one
    zero below the first pole and one between each pair.  Returns ``(x, D)`` ascending, with
    ``D = -G'(x) = sum_i c_i t_i/(1 - x t_i)^2 > 0``.

    Each zero is sought in the half (in log space) of its interval that holds it, written in the
    relative distance y to that half's pole, ``x = P (1 + sigma y)``: the function brentq sees is
    ``y G``, finite at the pole, and the factor ``1 - x t`` of that pole is ``-sigma y`` exactly,
    so a zero that sits within a few ulp of a pole (a tiny term) keeps full relative accuracy in
    its distance to the pole, which is what the residue needs.
    """
    from scipy.optimize import brentq

    order = np.argsort(-t)          # poles 1/t ascending
    c, t = c[order], t[order]
    poles = 1.0 / t
    ct = c * t
    n = t.size
    rtol = 4.0 * np.finfo(float).eps
    tiny = 1e-300                   # brentq needs xtol > 0; the relative rtol does the work

    def direct(x):                  # G itself, away from every pole
        d = 1.0 - x * t
        return g0 - x * np.sum(ct / d), d

    def anchored(j, sigma):
        """y -> (y G(P_j (1 + sigma y)), d) with the j-th factor exact."""
        ratio = t / t[j]
        mask = np.arange(n) != j

        def f(y):
            one = 1.0 + sigma * y
            d = 1.0 - ratio * one
            d[j] = -sigma * y
            rest = g0 - poles[j] * one * np.sum(ct[mask] / d[mask])
            return y * rest + sigma * c[j] * one, d
        return f

    def solve(f, span):
        y = brentq(lambda v: f(v)[0], 0.0, span, xtol=tiny, rtol=rtol, maxiter=400)
        return y, f(y)[1]

    roots, slopes = [], []
    for k in range(n):
        right = poles[k]
        if k == 0:  # from 0 (no pole: G(0) = g0 > 0) to the first pole
            mid = 0.5 * right
            left_value = direct(mid)[0]
        else:
            mid = math.sqrt(poles[k - 1] * right)
            left = anchored(k - 1, 1.0)
            left_span = mid / poles[k - 1] - 1.0
            left_value = left(left_span)[0]      # left_span * G(mid)
        if left_value < 0.0:                     # the zero is in the left half
            if k == 0:
                x = brentq(lambda v: direct(v)[0], 0.0, mid, xtol=tiny, rtol=rtol,
                           maxiter=400)
                d = 1.0 - x * t
            else:
                y, d = solve(left, left_span)
                x = poles[k - 1] * (1.0 + y)
        else:
            right_f = anchored(k, -1.0)
            right_span = 1.0 - mid / right
            if right_f(right_span)[0] > 0.0:     # the zero is in the right half
                y, d = solve(right_f, right_span)
                x = right * (1.0 - y)
            else:                                # G(mid) is zero to rounding
                x = mid
                d = 1.0 - x * t
        roots.append(x)
        slopes.append(float(np.sum(ct / (d * d))))
    return np.array(roots), np.array(slopes)


def _merged(amplitudes, times):
    """Terms with a positive amplitude, equal times summed (one pole each), as arrays."""
    merged = {}
    for a, t in zip(amplitudes, times):
        if a > 0.0:
            merged[t] = merged.get(t, 0.0) + a
    ts = np.array(sorted(merged), dtype=float)
    return np.array([merged[v] for v in ts.tolist()], dtype=float), ts


class Creep(NamedTuple):
    """A creep (retardation) series ``J(t) = J0 - sum_k J_k exp(-t/tau_k)``.

    Unpacks as ``(J0, J, tau)``, so ``bem.Prony(*creep)`` builds the BEM road's material.
    """

    J0: float
    J: tuple
    tau: tuple

    def compliance(self, omega):
        """``J*(w) = J(0+) + sum_k J_k/(1 + i w tau_k)``, ``J(0+) = J0 - sum_k J_k``.

        ``J(0+)`` is formed from the series as the BEM road forms it, by subtraction (here
        with an exact sum), so its relative error is ``~ eps * J0/J(0+)``: that of the
        representation, not of the conversion.
        """
        w = np.asarray(omega, dtype=float)
        out = np.full(w.shape, self.J0 - math.fsum(self.J), dtype=complex)
        for j, tau in zip(self.J, self.tau):
            out += j / (1.0 + 1j * w * tau)
        return out


# --------------------------------------------------------------------------
# Relaxation form
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class FitReport:
    """How well a fitted Prony series reproduces the data it was fitted to.

    Residuals are relative, ``model/datum - 1``, at the data's frequencies.

    Attributes
    ----------
    window : (float, float)
        The measured frequencies ``(w_min, w_max)``, in rad per time unit of the series (shifted
        with the series by `Maxwell.at_temperature`).
    per_decade : float
        Candidate relaxation times per decade.
    candidates, terms : int
        Relaxation times offered to the fit, and those kept (non-zero amplitude).
    storage_max, storage_rms, loss_max, loss_rms, tan_delta_max, tan_delta_rms : float
        Largest and root-mean-square relative residual of E', E'' and tan δ.
    bound : float
        The largest relative residual on E' and E'' the fit was allowed.
    source : str or None
        The data file, when the curve was read from one.
    modulus_unit : str or None
        The unit of the moduli (``E_r``, ``E_i``) as the data gave it (``"MPa"``), or None
        when the data did not say.
    """

    window: tuple
    per_decade: float
    candidates: int
    terms: int
    storage_max: float
    storage_rms: float
    loss_max: float
    loss_rms: float
    tan_delta_max: float
    tan_delta_rms: float
    bound: float
    source: str | None = None
    modulus_unit: str | None = None

    @property
    def max_residual(self) -> float:
        """The larger of the largest relative residuals of E' and E'' (what `bound` limits)."""
        return max(self.storage_max, self.loss_max)

    def summary(self) -> str:
        """One line: terms, and max/RMS residuals in per cent."""
        return (f"{self.terms} terms ({self.per_decade:g}/decade); relative residual max/RMS: "
                f"E' {100 * self.storage_max:.2f}/{100 * self.storage_rms:.2f} %, "
                f"E'' {100 * self.loss_max:.2f}/{100 * self.loss_rms:.2f} %, "
                f"tan δ {100 * self.tan_delta_max:.2f}/{100 * self.tan_delta_rms:.2f} %")


@dataclass(frozen=True)
class Maxwell:
    """Relaxation modulus ``E(t) = E_r + sum_i E_i exp(-t/theta_i)`` (generalised Maxwell).

    Parameters
    ----------
    E_r : float
        Relaxed (long-time, rubbery) modulus, > 0, in any modulus unit.
    E : sequence of float
        Amplitudes ``E_i >= 0``, same unit.
    theta : sequence of float
        Relaxation times ``theta_i > 0``, in any time unit -- relaxation, not retardation
        (creep) times.
    temperature : float, optional
        The temperature the series holds at, when it was moved there by `at_temperature`
        (None: the reference temperature of its master curve).
    fit : FitReport, optional
        Set by `fit_prony`: residuals against the data and the measured window.

    Raises
    ------
    ValueError
        Non-finite values, ``E_r <= 0``, ``E_i < 0``, ``theta_i <= 0`` or lengths that differ.
    """

    E_r: float
    E: tuple = ()
    theta: tuple = ()
    temperature: float | None = None
    fit: FitReport | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        e_r = real("E_r", self.E_r, "a finite relaxed modulus E_r > 0", lambda v: v > 0.0)
        ee = series("E", self.E, "finite amplitudes E_i >= 0", lambda v: v >= 0.0)
        tt = series("theta", self.theta, "finite relaxation times theta_i > 0", lambda v: v > 0.0)
        if len(ee) != len(tt):
            raise bad("E", self.E, f"one amplitude per relaxation time (got {len(ee)} "
                      f"amplitudes and {len(tt)} times)")
        if self.temperature is not None:
            object.__setattr__(self, "temperature", real(
                "temperature", self.temperature, "a finite temperature or None"))
        object.__setattr__(self, "E_r", e_r)
        object.__setattr__(self, "E", ee)
        object.__setattr__(self, "theta", tt)

    @property
    def glassy(self) -> float:
        """Instantaneous (glassy) modulus ``E_r + sum_i E_i``."""
        return self.E_r + math.fsum(self.E)

    def relaxation(self, t):
        """``E(t)`` for t > 0 (the same time unit as theta)."""
        t = np.asarray(t, dtype=float)
        out = np.full(t.shape, self.E_r)
        for e, th in zip(self.E, self.theta):
            out = out + e * np.exp(-t / th)
        return out

    def modulus(self, omega):
        """Complex modulus ``E*(w) = E_r + sum_i E_i i w theta_i/(1 + i w theta_i)``.

        Parameters
        ----------
        omega : array_like
            Angular frequencies ``w >= 0``, in rad per time unit of theta.

        Returns
        -------
        ndarray of complex
            ``E' + i E''``: both are sums of non-negative terms (nothing cancels), and
            ``E'' >= 0`` for ``w >= 0``.
        """
        w = np.asarray(omega, dtype=float)
        re = np.full(w.shape, self.E_r)
        im = np.zeros(w.shape)
        with np.errstate(divide="ignore", over="ignore", invalid="ignore"):
            for e, th in zip(self.E, self.theta):
                x = w * th
                inv = 1.0 / x           # x^2/(1 + x^2) as 1/(1 + x^-2): no overflow at huge x
                re = re + e / (1.0 + inv * inv)
                im = im + e * np.where(x > 1.0, inv / (1.0 + inv * inv), x / (1.0 + x * x))
        return re + 1j * im

    def compliance(self, omega):
        """Complex compliance ``J*(w) = 1/E*(w)`` (``J' - i J''``)."""
        return 1.0 / self.modulus(omega)

    def creep(self, *, E_ref: float = 1.0, tau_ref: float = 1.0) -> Creep:
        """The exact creep (retardation) form of this series.

        Parameters
        ----------
        E_ref : float
            Modulus unit of the result: compliances are returned in ``1/E_ref`` (for the BEM
            road's convention, ``E_ref`` is the reference modulus of its units, e.g. ``E_r``).
        tau_ref : float
            Time unit of the result: retardation times are returned in ``tau_ref``.

        Returns
        -------
        Creep
            ``(J0, J, tau)`` with ``J0 = 1/E_r``, ``J(0+) = J0 - sum J_k = 1/glassy`` and the
            retardation times ascending, one per distinct relaxation time with a non-zero
            amplitude; ``bem.Prony(*m.creep(E_ref=..., tau_ref=...))`` is the BEM material.

        Notes
        -----
        The retardation rates ``1/tau_k`` are the zeros of ``E(p)`` (module docstring), found by
        brentq in each interval between consecutive poles, and ``J_k = 1/(p_k D_k)`` with
        ``D_k = -E'(p_k)``.  Accuracy is a few ulp in each ``tau_k`` and ``J_k``; ``J(0+)``
        formed as ``J0 - sum J_k`` carries the cancellation ``~ eps * glassy/E_r`` that any
        ``(J0, J_k)`` representation carries.
        """
        e_ref = real("E_ref", E_ref, "a finite modulus unit > 0", lambda v: v > 0.0)
        t_ref = real("tau_ref", tau_ref, "a finite time unit > 0", lambda v: v > 0.0)
        c, t = _merged(self.E, self.theta)
        j0 = 1.0 / self.E_r
        if not c.size:
            return Creep(j0 * e_ref, (), ())
        p, slope = _interlaced_zeros(self.E_r, c, t)
        amps = 1.0 / (p * slope)
        taus = 1.0 / p
        order = np.argsort(taus)
        return Creep(j0 * e_ref, tuple((amps[order] * e_ref).tolist()),
                     tuple((taus[order] / t_ref).tolist()))

    @classmethod
    def from_creep(cls, J0, J, tau) -> "Maxwell":
        """The relaxation form of the creep series ``J(t) = J0 - sum_k J_k exp(-t/tau_k)``.

        Parameters
        ----------
        J0 : float
            Relaxed compliance, > 0.
        J : sequence of float
            Amplitudes ``J_k >= 0``, with ``J(0+) = J0 - sum_k J_k > 0``.
        tau : sequence of float
            Retardation times ``tau_k > 0``.

        Returns
        -------
        Maxwell
            ``E_r = 1/J0``, relaxation times ascending (moduli in the inverse unit of the
            compliances, times in the unit of tau).
        """
        j0 = real("J0", J0, "a finite relaxed compliance J0 > 0", lambda v: v > 0.0)
        jj = series("J", J, "finite amplitudes J_k >= 0", lambda v: v >= 0.0)
        tt = series("tau", tau, "finite retardation times tau_k > 0", lambda v: v > 0.0)
        if len(jj) != len(tt):
            raise bad("J", J, f"one amplitude per retardation time (got {len(jj)} amplitudes "
                      f"and {len(tt)} times)")
        j_plus = j0 - math.fsum(jj)
        if not j_plus > 0.0:
            raise bad("J0", J0, f"J(0+) = J0 - sum(J_k) = {j_plus!r} must be > 0")
        c, t = _merged(jj, tt)
        if not c.size:
            return cls(1.0 / j0)
        # in u = 1/p the compliance is J(0+) - u sum_k (J_k/tau_k)/(1 - u/tau_k): the same form
        u, slope = _interlaced_zeros(j_plus, c, 1.0 / t)
        amps = 1.0 / (u * slope)
        return cls(1.0 / j0, tuple(amps.tolist()), tuple(u.tolist()))

    @property
    def measured_window(self):
        """``(w_min, w_max)`` of the data this series was fitted to, or None."""
        return None if self.fit is None else self.fit.window

    def extrapolation_warning(self, omega_lo, omega_hi=None):
        """A message when frequencies ``[omega_lo, omega_hi]`` leave the measured window.

        Parameters
        ----------
        omega_lo, omega_hi : float
            The lowest and highest angular frequency a calculation probes (for a sliding
            contact the modes ``k_n V``), in rad per time unit of theta; ``omega_hi`` defaults
            to ``omega_lo``.

        Returns
        -------
        str or None
            None inside the window or when the series has no measured window (it was not
            fitted to data); otherwise one line saying by how many decades, on which side, the
            modulus is extrapolated.
        """
        lo = real("omega_lo", omega_lo, "a finite frequency > 0", lambda v: v > 0.0)
        hi = lo if omega_hi is None else real("omega_hi", omega_hi,
                                              f"a finite frequency >= omega_lo={lo!r}",
                                              lambda v: v >= lo)
        if self.fit is None:
            return None
        w0, w1 = self.fit.window
        below = math.log10(w0 / lo) if lo < w0 else 0.0
        above = math.log10(hi / w1) if hi > w1 else 0.0
        if below <= 0.0 and above <= 0.0:
            return None
        sides = []
        if below > 0.0:
            sides.append(f"{below:.2g} decade(s) below")
        if above > 0.0:
            sides.append(f"{above:.2g} decade(s) above")
        return (f"frequencies {lo:.3g}..{hi:.3g} reach {' and '.join(sides)} the measured "
                f"window {w0:.3g}..{w1:.3g} of the DMA data: the modulus there is extrapolated "
                "by the Prony fit")

    def at_temperature(self, shift, T) -> "Maxwell":
        """The series at temperature T (thermorheologically simple: every time scaled by a_T).

        Parameters
        ----------
        shift : WLF or ShiftTable
            Anything with ``log10_aT(T)``, log10 of the shift factor relative to the master
            curve's reference temperature.
        T : float
            Temperature, in the unit of the shift.

        Returns
        -------
        Maxwell
            Moduli unchanged, ``theta_i`` multiplied by ``a_T(T)/a_T(T_self)`` (``T_self`` the
            series' own temperature; the reference when None), the measured window divided by
            the same factor.
        """
        T = real("T", T, "a finite temperature")
        log_a = float(shift.log10_aT(T))
        if self.temperature is not None:
            log_a -= float(shift.log10_aT(self.temperature))
        a = 10.0 ** log_a
        fit = self.fit
        if fit is not None:
            fit = replace(fit, window=(fit.window[0] / a, fit.window[1] / a))
        return Maxwell(self.E_r, self.E, tuple(th * a for th in self.theta), temperature=T,
                       fit=fit)

    def in_pascals(self) -> "Maxwell":
        """The series with its moduli in pascals (times unchanged).

        Returns
        -------
        Maxwell
            A series fitted to data whose header named a modulus unit (``fit.modulus_unit``,
            one of `PASCALS`) scaled to Pa; a series with no fit (built by hand: its moduli are
            in Pa by the SI front's convention) as it is.

        Raises
        ------
        ValueError
            A fit to data that named no modulus unit, or a unit not in `PASCALS`: the factor
            would be a guess.
        """
        if self.fit is None:
            return self
        unit = self.fit.modulus_unit
        factor = None if unit is None else PASCALS.get(unit.strip().lower())
        if factor is None:
            raise bad("modulus_unit", unit, "a modulus unit the DMA header names, one of Pa, "
                      "kPa, MPa, GPa (e.g. 'storage [MPa]'), to express the fit in pascals")
        fit = replace(self.fit, modulus_unit="Pa")
        return Maxwell(self.E_r * factor, tuple(e * factor for e in self.E), self.theta,
                       temperature=self.temperature, fit=fit)


# --------------------------------------------------------------------------
# Text tables (DMA curves, shift tables)
# --------------------------------------------------------------------------
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


def _data_lines(path, option: str) -> list:
    """``(line number, fields)`` of each non-comment line of a UTF-8 text file.

    ``#`` starts a comment; fields are separated by commas (or blanks when a line has no
    comma).  A missing, binary or non-UTF-8 file is the refusal of ``option=path``.
    """
    where = str(path)
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
    rows = []
    for number, raw in enumerate(text.lstrip("\ufeff").splitlines(), start=1):
        line = raw.split("#", 1)[0].strip()
        if line:
            rows.append((number, _split(line)))
    return rows


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


# --------------------------------------------------------------------------
# Prony-series files and the form of a material file
# --------------------------------------------------------------------------
def read_relaxation(path) -> Maxwell:
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
            _data_lines(path, "relaxation")]
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


def material_form(path) -> str:
    """Which of the accepted `FORMS` a material file is, from its first non-comment line.

    * ``"creep"``: ``J0 <value>`` (a creep-series file, ``bem.read_prony``);
    * ``"relaxation"``: ``E_r <value>`` (a relaxation-series file, `read_relaxation`);
    * ``"dma"``: a CSV header naming the columns frequency, storage and loss (`read_dma`).

    Raises
    ------
    ValueError
        One line ``material='path' is not allowed: ...``: an unreadable, binary, non-UTF-8 or
        empty file, or a first line that is none of the three.
    """
    where = str(path)
    rows = _data_lines(path, "material")
    accepted = ("a creep series (first line 'J0 <value>'), a relaxation series (first line "
                "'E_r <value>') or a DMA master curve (a CSV header naming frequency, storage, "
                "loss)")
    if not rows:
        raise bad("material", where, f"{accepted} (this file is empty or only comments)")
    number, fields = rows[0]
    tokens = [t for f in fields for t in f.split()]
    key = tokens[0].lower()
    if key == "j0":
        return "creep"
    if key in ("e_r", "er"):
        return "relaxation"
    names = {_column_name(f)[0] for f in fields}
    if all(names & set(aliases) for aliases in _DMA_COLUMNS.values()):
        return "dma"
    shown = " ".join(tokens)
    if len(shown) > 40:
        shown = shown[:36] + " ..."
    raise bad("material", where, f"{accepted} (line {number} begins {shown!r})")


# --------------------------------------------------------------------------
# DMA master curves
# --------------------------------------------------------------------------
def _loss_bound(omega, loss):
    """Largest rise of E' each interval of data can have: the integral of E'' over ln w.

    For any relaxation spectrum ``dE'/dln w <= E''`` (kernels ``2x^2/(1 + x^2)^2 <=
    x/(1 + x^2)``), and between data points ``w_a < w_a lam < w_b = c w_a`` each kernel gives
    ``E''(w_a lam) <= min(lam E''_a, (c/lam) E''_b)``; the integral of that bound over ln lam
    in [0, ln c] is returned.
    """
    a, b = loss[:-1], loss[1:]
    c = omega[1:] / omega[:-1]
    cross = np.clip(np.sqrt(c * b / a), 1.0, c)   # where lam a = (c/lam) b
    return a * (cross - 1.0) + b * (c / cross - 1.0)


def _check_curve(omega, storage, loss, noise, where):
    """Refuse a curve that no linear viscoelastic solid could give; ``where(j)`` names row j."""
    if omega.size < MIN_POINTS:
        raise ValueError(where(None, f"at least {MIN_POINTS} points (got {omega.size})"))
    for name, arr in (("frequency", omega), ("storage", storage), ("loss", loss)):
        wrong = ~np.isfinite(arr)
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, f"finite values ({name} is {float(arr[j])!r})"))
    checks = [
        (omega <= 0.0, lambda j: f"frequencies > 0 (frequency {float(omega[j])!r})"),
        (storage <= 0.0, lambda j: f"a storage modulus > 0 (storage {float(storage[j])!r})"),
        (loss <= 0.0, lambda j: f"a loss modulus > 0: a solid that dissipates "
                                f"(loss {float(loss[j])!r})"),
    ]
    for wrong, text in checks:
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, text(j)))
    step = np.diff(omega)
    if (step <= 0.0).any():
        j = int(np.flatnonzero(step <= 0.0)[0]) + 1
        kind = "a duplicate" if step[j - 1] == 0.0 else "out of order"
        raise ValueError(where(j, f"frequencies strictly increasing (frequency "
                         f"{float(omega[j])!r} after {float(omega[j - 1])!r}: {kind})"))
    drop = storage[1:] < storage[:-1] * (1.0 - noise)
    if drop.any():
        j = int(np.flatnonzero(drop)[0]) + 1
        raise ValueError(where(j, f"a storage modulus that does not decrease with frequency "
                         f"(storage {float(storage[j])!r} after {float(storage[j - 1])!r}; every "
                         "relaxation mode stiffens with frequency)"))
    rise = np.diff(storage)
    bound = _loss_bound(omega, loss)
    over = rise > bound * (1.0 + noise) + noise * storage[1:]
    if over.any():
        j = int(np.flatnonzero(over)[0]) + 1
        raise ValueError(where(j, f"a loss tangent at least the slope of ln E' against ln w "
                         f"(E' rises by {rise[j - 1]:.4g} from the previous point, more than "
                         f"the loss can allow, {bound[j - 1]:.4g}: tan δ = "
                         f"{loss[j] / storage[j]:.4g} is too small for any relaxation "
                         "spectrum, Kramers-Kronig; check the columns and units)"))


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """A DMA master curve in tensile form: ``E'(w)``, ``E''(w)`` at a reference temperature.

    Parameters
    ----------
    omega : array_like
        Angular frequencies, strictly increasing, > 0, in rad per time unit.
    storage, loss : array_like
        ``E'`` and ``E''`` (> 0), in any one modulus unit.
    noise : float
        Relative scatter tolerated by the physical checks (0: none).
    source : str, optional
        Where the data came from (a file name), for provenance.
    modulus_unit : str, optional
        The unit of ``storage`` and ``loss`` (``"MPa"``), when known; see `PASCALS`.

    Raises
    ------
    ValueError
        Fewer than `MIN_POINTS` points, non-finite or non-positive values, frequencies not
        strictly increasing, a storage modulus that decreases with frequency, or a loss too
        small for the rise of the storage modulus (no relaxation spectrum gives it).
    """

    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    noise: float = 0.0
    source: str | None = None
    modulus_unit: str | None = None

    def __post_init__(self):
        noise = real("noise", self.noise, "a relative scatter in [0, 1)", lambda v: 0.0 <= v < 1.0)
        arrays = {}
        for name in ("omega", "storage", "loss"):
            value = getattr(self, name)
            arr = reals(name, value, "a 1-D sequence of numbers").ravel()
            arr.flags.writeable = False
            arrays[name] = arr
        sizes = [a.size for a in arrays.values()]
        if len(set(sizes)) != 1:
            raise bad("storage", self.storage, "as many values as omega and loss (sizes of "
                      f"omega, storage, loss: {sizes})")

        def where(j, text):
            if j is None:
                return str(bad("omega", self.omega, text))
            return f"omega[{j}]={float(arrays['omega'][j])!r} is not allowed: {text}"
        _check_curve(arrays["omega"], arrays["storage"], arrays["loss"], noise, where)
        for name, arr in arrays.items():
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "noise", noise)

    @property
    def tan_delta(self) -> np.ndarray:
        """Loss tangent ``E''/E'``."""
        return self.loss / self.storage

    @property
    def window(self) -> tuple:
        """``(w_min, w_max)``: the measured frequencies."""
        return float(self.omega[0]), float(self.omega[-1])


_DMA_COLUMNS = {"frequency": ("frequency", "freq", "omega", "f"),
                "storage": ("storage",), "loss": ("loss",)}


def read_dma(path, *, kind: str = "E", nu=None, frequency_unit: str | None = None,
             noise: float = 0.0) -> MasterCurve:
    """Read a DMA master curve from a CSV file.

    Format::

        # comments start with '#'; say here the units and the reference temperature
        frequency, storage, loss
        0.01, 3.31, 0.152
        ...

    The header names the columns ``frequency``, ``storage`` and ``loss`` (any order, any case,
    an optional unit in brackets such as ``storage [MPa]``); other columns are ignored.  Fields
    are separated by commas (or blanks).  Moduli are kept in the file's unit, which the curve
    records (``modulus_unit``) when the header gives one; storage and loss in different units
    are refused.

    Parameters
    ----------
    path : str or Path
        The file (UTF-8 text).
    kind : {"E", "G"}
        Whether the moduli are tensile (E', E'') or shear (G', G''); shear moduli are turned
        into tensile ones with ``E = 2 (1 + nu) G``.
    nu : float, optional
        Poisson ratio in (-1, 0.5], required for ``kind="G"`` (and only then).
    frequency_unit : {"rad/s", "Hz"}, optional
        Unit of the frequency column: angular frequency, or cycles per time unit (multiplied by
        2 pi); "s" stands for whatever time unit the curve uses.  Default: the unit the header
        gives the column (``frequency [Hz]``), else "rad/s".  A unit given here that the
        header contradicts is refused (a silent factor 2 pi otherwise).
    noise : float
        Relative scatter tolerated by the physical checks (see `MasterCurve`).

    Returns
    -------
    MasterCurve
        Angular frequencies, ``E'`` and ``E''``.

    Raises
    ------
    ValueError
        One line naming the file (and the line where one is at fault): unreadable, binary or
        non-UTF-8 files, a missing header or column, ragged or non-numeric rows, and every
        refusal of `MasterCurve`.
    """
    if kind not in ("E", "G"):
        raise bad("kind", kind, "'E' (tensile moduli) or 'G' (shear moduli)")
    if frequency_unit not in (None, "rad/s", "Hz"):
        raise bad("frequency_unit", frequency_unit, "'rad/s' (angular) or 'Hz' (cycles), or "
                  "None (the header's unit)")
    if kind == "G":
        if nu is None:
            raise bad("nu", nu, "a Poisson ratio in (-1, 0.5] to turn shear moduli into "
                      "tensile ones (kind='G')")
        nu = real("nu", nu, "a Poisson ratio in (-1, 0.5]", lambda v: -1.0 < v <= 0.5)
        factor = 2.0 * (1.0 + nu)
    else:
        if nu is not None:
            raise bad("nu", nu, "None with kind='E' (nu converts shear moduli; the file "
                      "holds tensile ones)")
        factor = 1.0
    noise = real("noise", noise, "a relative scatter in [0, 1)", lambda v: 0.0 <= v < 1.0)
    cols, lines, units = _read_table(path, "dma", _DMA_COLUMNS)
    stated = {"hz": "Hz", "rad/s": "rad/s"}.get((units["frequency"] or "").lower())
    if frequency_unit is None:
        frequency_unit = stated or "rad/s"
    elif stated is not None and stated != frequency_unit:
        raise bad("frequency_unit", frequency_unit, f"the unit of the file's frequency column "
                   f"({units['frequency']!r} in {str(path)!r}), or None")
    omega = cols["frequency"] * (2.0 * math.pi if frequency_unit == "Hz" else 1.0)
    storage, loss = cols["storage"] * factor, cols["loss"] * factor
    given = {u for u in (units["storage"], units["loss"]) if u}
    if len(given) > 1:
        raise bad("dma", str(path), f"storage and loss in one unit (the header gives "
                   f"{units['storage']!r} and {units['loss']!r}: a silent factor otherwise)")
    modulus_unit = given.pop() if given else None

    def where(j, text):
        at = "" if j is None else f" (line {lines[j]})"
        return f"dma={str(path)!r} is not allowed: {text}{at}"
    _check_curve(omega, storage, loss, noise, where)
    return MasterCurve(omega, storage, loss, noise=noise, source=str(path),
                       modulus_unit=modulus_unit)


# --------------------------------------------------------------------------
# Prony fit
# --------------------------------------------------------------------------
def _kernels(omega, theta):
    """Storage and loss kernels ``x^2/(1 + x^2)``, ``x/(1 + x^2)`` with ``x = w theta``."""
    x = np.outer(omega, theta)
    return x * x / (1.0 + x * x), x / (1.0 + x * x)


def fit_prony(curve: MasterCurve, *, per_decade: float = 2, extend: float = 1.0,
              max_residual: float = 0.05) -> Maxwell:
    """Fit a generalised Maxwell series to a master curve (non-negative least squares).

    Relaxation times are fixed, log-spaced over ``1/w_max .. 1/w_min`` widened by ``extend``
    decades on each side; ``E_r`` and the ``E_i >= 0`` solve one scipy ``nnls`` problem in
    which each datum's equation is divided by the datum, so E' and E'' are fitted jointly in
    relative terms.  Terms the fit sets to zero are dropped.

    Parameters
    ----------
    curve : MasterCurve
        The data (frequencies in rad per time unit: the series' times come out in that unit).
    per_decade : float
        Relaxation times per decade, >= 0.5.  One per decade leaves a ripple of several per
        cent on E'' for a broad spectrum; two is the default.
    extend : float
        Decades added to the span of times on each side (>= 0).
    max_residual : float
        The largest relative residual on E' or E'' accepted (> 0).

    Returns
    -------
    Maxwell
        With ``fit`` set: a `FitReport` (residuals and the measured window).

    Raises
    ------
    ValueError
        A fit whose largest relative residual exceeds ``max_residual``, or whose relaxed
        modulus comes out zero (the data never reach a rubbery plateau the series can hold).
    """
    from scipy.optimize import nnls

    if not isinstance(curve, MasterCurve):
        raise bad("curve", curve, "a MasterCurve (see read_dma)")
    per_decade = real("per_decade", per_decade, "relaxation times per decade in [0.5, 20]",
                      lambda v: 0.5 <= v <= 20.0)
    extend = real("extend", extend, "decades in [0, 5]", lambda v: 0.0 <= v <= 5.0)
    bound = real("max_residual", max_residual, "a relative residual bound > 0", lambda v: v > 0.0)
    w, e1, e2 = curve.omega, curve.storage, curve.loss
    lo = -math.log10(w[-1]) - extend
    hi = -math.log10(w[0]) + extend
    count = int(math.ceil((hi - lo) * per_decade - 1e-9)) + 1
    theta = np.logspace(lo, hi, count)
    k1, k2 = _kernels(w, theta)
    a = np.zeros((2 * w.size, count + 1))
    a[: w.size, 0] = 1.0 / e1
    a[: w.size, 1:] = k1 / e1[:, None]
    a[w.size:, 1:] = k2 / e2[:, None]
    # columns to unit norm: a positive scaling keeps the constraint and mends the conditioning
    # (amplitudes span the rubbery to the glassy modulus)
    scale = np.linalg.norm(a, axis=0)
    z, _ = nnls(a / scale, np.ones(2 * w.size), maxiter=50 * (count + 1))
    coef = z / scale
    if not coef[0] > 0.0:
        raise bad("curve", curve.source or "MasterCurve", "data that reach a relaxed "
                   "(rubbery) plateau: the fit gives E_r = 0, a fluid, below the lowest "
                   f"frequency {w[0]:.3g}")
    keep = coef[1:] > 0.0
    model = Maxwell(float(coef[0]), tuple(coef[1:][keep].tolist()),
                    tuple(theta[keep].tolist()))
    mod = model.modulus(w)
    r1 = mod.real / e1 - 1.0
    r2 = mod.imag / e2 - 1.0
    r3 = (mod.imag / mod.real) / (e2 / e1) - 1.0
    stats = [(float(np.max(np.abs(r))), float(np.sqrt(np.mean(r * r)))) for r in (r1, r2, r3)]
    report = FitReport(window=curve.window, per_decade=per_decade, candidates=count,
                       terms=int(keep.sum()), storage_max=stats[0][0], storage_rms=stats[0][1],
                       loss_max=stats[1][0], loss_rms=stats[1][1], tan_delta_max=stats[2][0],
                       tan_delta_rms=stats[2][1], bound=bound, source=curve.source,
                       modulus_unit=curve.modulus_unit)
    if report.max_residual > bound:
        raise bad("max_residual", bound, f"a bound the fit meets: the best non-negative "
                   f"Prony series with {per_decade:g} times per decade misses the data by "
                   f"{100 * report.max_residual:.3g} % (E' {100 * report.storage_max:.3g} %, "
                   f"E'' {100 * report.loss_max:.3g} %); more times per decade, or data a "
                   "relaxation spectrum can fit")
    return replace(model, fit=report)


# --------------------------------------------------------------------------
# Time-temperature shifts
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class WLF:
    """Williams–Landel–Ferry shift: ``log10 a_T = -C1 (T - T_ref)/(C2 + T - T_ref)``.

    Parameters
    ----------
    C1 : float
        > 0 (dimensionless; 17.44 for the "universal" constants).
    C2 : float
        > 0, in the temperature unit (51.6 K for the "universal" constants).
    T_ref : float
        Reference temperature of the master curve (``a_T = 1``), same unit.

    Notes
    -----
    ``a_T`` multiplies times (relaxation is faster when hot: ``a_T < 1`` above ``T_ref``);
    a reduced frequency is ``w a_T``.  T at or below the pole ``T_ref - C2`` is refused.
    """

    C1: float
    C2: float
    T_ref: float

    def __post_init__(self):
        object.__setattr__(self, "C1", real("C1", self.C1, "a finite C1 > 0", lambda v: v > 0.0))
        object.__setattr__(self, "C2", real("C2", self.C2,
                                            "a finite C2 > 0 (in the temperature unit)",
                                            lambda v: v > 0.0))
        object.__setattr__(self, "T_ref", real("T_ref", self.T_ref,
                                               "a finite reference temperature"))

    def log10_aT(self, T):
        """``log10 a_T`` at T (scalar or array); T must be above ``T_ref - C2``."""
        arr = reals("T", T, "temperatures")
        dt = arr - self.T_ref
        outside = ~(np.isfinite(arr) & (self.C2 + dt > 0.0))
        if outside.any():
            v = float(arr.ravel()[np.flatnonzero(outside.ravel())[0]])
            raise bad("T", v, f"a finite temperature above the WLF pole T_ref - C2 = "
                      f"{self.T_ref - self.C2!r}")
        out = -self.C1 * dt / (self.C2 + dt)
        return float(out) if out.ndim == 0 else out

    def a_T(self, T):
        """Shift factor ``a_T = 10**log_aT(T)``."""
        return 10.0 ** self.log10_aT(T)


@dataclass(frozen=True)
class ShiftTable:
    """Tabulated shift ``log10 a_T(T)``, linear between the points, refused outside them.

    Parameters
    ----------
    T : sequence of float
        Temperatures, strictly increasing, at least 2.
    log_aT : sequence of float
        ``log10 a_T`` at each, strictly decreasing (relaxation is faster when hot).

    Notes
    -----
    Linear interpolation of ``log10 a_T`` keeps the table's monotony and never overshoots.
    """

    T: tuple
    log_aT: tuple

    def __post_init__(self):
        tt = series("T", self.T, "finite temperatures")
        ll = series("log_aT", self.log_aT, "finite values of log10 a_T")
        if len(tt) != len(ll):
            raise bad("log_aT", self.log_aT, f"one value per temperature ({len(tt)})")
        if len(tt) < 2:
            raise bad("T", self.T, "at least 2 temperatures")
        if any(b <= a for a, b in zip(tt, tt[1:])):
            raise bad("T", self.T, "strictly increasing temperatures")
        if any(b >= a for a, b in zip(ll, ll[1:])):
            raise bad("log_aT", self.log_aT, "log10 a_T strictly decreasing with T "
                      "(relaxation is faster when hot)")
        object.__setattr__(self, "T", tt)
        object.__setattr__(self, "log_aT", ll)

    def log10_aT(self, T):
        """``log10 a_T`` at T (scalar or array) inside the table."""
        arr = reals("T", T, "temperatures")
        outside = ~(np.isfinite(arr) & (arr >= self.T[0]) & (arr <= self.T[-1]))
        if outside.any():
            v = float(arr.ravel()[np.flatnonzero(outside.ravel())[0]])
            raise bad("T", v, f"a temperature inside the shift table [{self.T[0]!r}, "
                      f"{self.T[-1]!r}] (no extrapolation)")
        out = np.interp(arr, self.T, self.log_aT)
        return float(out) if np.ndim(out) == 0 else out

    def a_T(self, T):
        """Shift factor ``a_T = 10**log_aT(T)``."""
        return 10.0 ** self.log10_aT(T)


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
