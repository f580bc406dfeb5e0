"""The two Prony forms (relaxation `Maxwell`, creep `Creep`) and their exact interconversion.

See the package docstring for the conventions (signs, units, the interlacing of the times).
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..checks import bad, real, series
from ._units import PASCALS

if TYPE_CHECKING:  # the fit module builds on this one
    from ._fit import FitReport


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

    def without_negligible(self, floor):
        """``(series, weights)``: this series without its terms ``J_k < floor J(0+)`` (a
        solver's floor on a term), ``J0`` kept, and the weights ``J_k/J(0+)`` dropped (largest
        first; empty when none).

        Dropping a term of weight w = J_k/J(0+) changes J*(w) by J_k i w tau_k/(1 + i w tau_k):
        by at most w J(0+), i.e. at most w relative to |J*| (|J*| >= Re J* >= J(0+)).  J(0+)
        grows by J_k, so the floor is applied to the grown J(0+) until no kept term is below.
        """
        jp = self.J0 - math.fsum(self.J)
        keep = list(range(len(self.J)))
        while True:
            grown = self.J0 - math.fsum(self.J[k] for k in keep)
            small = [k for k in keep if 0.0 < self.J[k] < floor * grown]
            if not small:
                break
            keep = [k for k in keep if k not in small]
        weights = sorted((self.J[k] / jp for k in range(len(self.J))
                          if k not in keep and self.J[k] > 0.0), reverse=True)
        if len(keep) == len(self.J):
            return self, ()
        return (Creep(self.J0, tuple(self.J[k] for k in keep), tuple(self.tau[k] for k in keep)),
                tuple(weights))



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


