"""Materials, profiles and their file formats (validated, nondimensional).

Units: compliances in ``1/E_ref``, retardation times in ``tau_ref``; heights are
``k y`` with ``X = x/lambda`` and the crest of the sinusoid at ``X = 0``.  For the
standard linear solid of the paper ``E_ref = E0`` and ``tau_ref = tau``.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from viscosine.checks import bad, real, reals, series
from viscosine.materials import read_creep


# --------------------------------------------------------------------------
# Creep function (eq. 2.3 generalised to a Prony series)
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class Prony:
    """Creep function ``J(t) = J0 - sum_i J_i exp(-t/tau_i)`` for t > 0 (eq. 2.3).

    Parameters
    ----------
    J0 : float
        Relaxed (long-time) compliance, in ``1/E_ref``.
    J : sequence of float
        Prony amplitudes ``J_i >= 0``, in ``1/E_ref``.
    tau : sequence of float
        Retardation (creep) times ``tau_i > 0``, in ``tau_ref`` -- not relaxation
        times (docs/conventions.md: creep and relaxation times).

    Raises
    ------
    ValueError
        If the series is not a creep function: non-finite values, ``J_i < 0``,
        ``tau_i <= 0``, lengths that differ, or ``J(0+) = J0 - sum J_i <= 0``.
    """

    J0: float
    J: tuple = ()
    tau: tuple = ()
    #: E∞/E0 exactly as given to `standard_linear_solid` (None for any other series); it is
    #: reported as given, not recomputed from the compliances (which rounds 3 to 3.000…01)
    ratio: float | None = field(default=None, compare=False, repr=False)

    def __post_init__(self):
        j0 = real("J0", self.J0, "a finite positive compliance")
        jj = series("J", self.J, "finite amplitudes J_i >= 0", lambda v: v >= 0.0)
        tt = series("tau", self.tau, "finite retardation times tau_i > 0", lambda v: v > 0.0)
        if len(jj) != len(tt):
            raise bad("J", self.J, f"one amplitude per retardation time (got {len(jj)} "
                      f"amplitudes and {len(tt)} times)")
        if not j0 - sum(jj) > 0.0:
            raise bad("J0", self.J0, f"J(0+) = J0 - sum(J_i) = {j0 - sum(jj)!r} must be > 0 "
                      "(a creep function starts at a positive instantaneous compliance)")
        if self.ratio is not None:
            r = real("ratio", self.ratio, "the E∞/E0 of this series: use "
                     "Prony.standard_linear_solid(ratio)")
            if (j0, jj, tt) != (1.0, (1.0 - 1.0 / r,), (1.0,)):
                raise bad("ratio", self.ratio, "the E∞/E0 of this series: use "
                          "Prony.standard_linear_solid(ratio)")
            object.__setattr__(self, "ratio", r)
        object.__setattr__(self, "J0", j0)
        object.__setattr__(self, "J", jj)
        object.__setattr__(self, "tau", tt)

    @classmethod
    def standard_linear_solid(cls, ratio: float) -> "Prony":
        """The paper's material (eq. 2.3) with ``ratio = E_inf/E0 >= 1``.

        Units ``E_ref = E0``, ``tau_ref = tau``: ``J0 = 1``, ``J_1 = 1 - 1/ratio``,
        ``tau_1 = 1``.
        """
        r = real("ratio", ratio, "a finite E_inf/E0 >= 1", lambda v: v >= 1.0)
        return cls(1.0, (1.0 - 1.0 / r,), (1.0,), ratio=r)

    @property
    def j_plus(self) -> float:
        """Instantaneous compliance J(0+) = 1/E_inf."""
        return self.J0 - sum(self.J)

    @property
    def terms(self) -> tuple:
        """((J_i, tau_i), ...)."""
        return tuple(zip(self.J, self.tau))

    @property
    def relaxation_times(self) -> tuple:
        """Relaxation times of the pressure, in ``tau_ref`` (ascending).

        They are -1/s at the zeros of ``s J(s) = J(0+) + sum_i J_i/(1 + s tau_i)``, one below
        the leftmost pole -1/tau_i and one between each pair of poles; for the standard linear
        solid ``tau E0/E_inf``.  At speed w the pressure memory acts over a length
        ``w tau_R / (2 pi)`` wavelengths behind each edge (the layer the mesh must resolve).
        """
        from scipy.optimize import brentq
        merged = {}
        for j, t in self.terms:  # equal times are one term (and would make an empty bracket)
            if j > 0.0:
                merged[t] = merged.get(t, 0.0) + j
        terms = sorted(merged.items(), key=lambda jt: jt[0])
        if not terms:
            return ()
        terms = [(j, t) for t, j in terms]
        f = lambda s: self.j_plus + sum(j / (1.0 + s * t) for j, t in terms)
        poles = sorted(-1.0 / t for _, t in terms)
        out = []
        lo = poles[0] * 2.0
        while f(lo) <= 0.0:  # f → J(0+) > 0 as s → −∞
            lo *= 2.0
        edges = [lo] + poles
        for a, b in zip(edges[:-1], edges[1:]):
            # f decreases from +∞ just right of a pole to −∞ just left of the next: step in from
            # each end until the sign is right (the root may sit much nearer one pole than the
            # span between them, e.g. for times decades apart or a small term)
            if a == lo:
                ta = lo  # f(lo) > 0 by the loop above
            else:
                d = 0.5 * (b - a)
                while f(a + d) <= 0.0 and a + d != a:
                    d *= 0.5
                ta = a + d
            d = 0.5 * (b - a)
            while f(b - d) >= 0.0 and b - d != b:
                d *= 0.5
            tb = b - d
            out.append(-1.0 / brentq(f, ta, tb, xtol=1e-15 * abs(b), rtol=1e-15))
        return tuple(sorted(out))

    def jstar(self, n, speed: float):
        """Complex compliance of mode n at sliding speed w: J*(-k_n V).

        ``J*(n) = J(0+) + sum_i J_i / (1 - i n w tau_i)`` (eq. 2.5 in Fourier space);
        its imaginary part is positive for n > 0, which is why the pressure leads.
        """
        n = np.asarray(n, dtype=float)
        out = np.full(n.shape, self.j_plus, dtype=complex)
        for j_i, tau_i in self.terms:
            out += j_i / (1.0 - 1j * n * speed * tau_i)
        return out


# --------------------------------------------------------------------------
# Profiles of the rigid indenter (one period, crest of the sinusoid at X = 0)
# --------------------------------------------------------------------------
def _fold(n: np.ndarray, c: np.ndarray, nodes: int, der: int = 0) -> np.ndarray:
    """Values at t = j/nodes of sum_n Re(c_n (2 pi i n)^der e^{2 pi i n t}) (n >= 1).

    Modes are folded onto the nodes-point grid (exact evaluation, any nodes).
    """
    coef = c * (2j * np.pi * n) ** der
    full = np.zeros(nodes, complex)
    ni = n.astype(np.int64)
    # Re(z) = (z + conj z)/2: fold the mode and its mirror image
    np.add.at(full, ni % nodes, 0.5 * coef)
    np.add.at(full, (-ni) % nodes, 0.5 * np.conj(coef))
    return np.fft.ifft(full).real * nodes


def _direct(n, c, t, der=0):
    """The same series at scattered points t (direct sum)."""
    ph = np.exp(2j * np.pi * np.outer(np.atleast_1d(t), n))
    return (ph @ (c * (2j * np.pi * n) ** der)).real


def _max_of_series(n: np.ndarray, c: np.ndarray) -> float:
    """Maximum over one period of sum_n Re(c_n e^{2 pi i n t}) (grid, then Newton)."""
    grid = 1 << max(8, int(np.ceil(np.log2(8 * n.max()))))
    vals = _fold(n, c, grid)
    best = float(vals.max())
    for j in np.argsort(vals)[-3:]:
        t = j / grid
        for _ in range(40):
            d1 = _direct(n, c, t, 1)[0]
            d2 = _direct(n, c, t, 2)[0]
            if d2 >= 0.0:
                break
            step = float(np.clip(-d1 / d2, -1.0 / grid, 1.0 / grid))
            t += step
            if abs(step) < 1e-16:
                break
        best = max(best, float(_direct(n, c, t)[0]))
    return best


class _Profile:
    """Common interface: k y and d(k y)/dX at the N panel centres X_j = j/N - 1/2
    (mean removed), and the amplitude h k = max(k y) - mean(k y)."""

    def _spectrum(self):  # pragma: no cover - abstract
        """(n >= 1, c_n) with k y - mean = sum_n Re(c_n e^{2 pi i n t}), t = X + 1/2."""
        raise NotImplementedError

    def sample(self, nodes: int) -> np.ndarray:
        """k y - mean(k y) at the panel centres."""
        n, c = self._spectrum()
        return _fold(n, c, nodes)

    def slope(self, nodes: int) -> np.ndarray:
        """d(k y)/dX at the panel centres."""
        n, c = self._spectrum()
        return _fold(n, c, nodes, 1)


@dataclass(frozen=True)
class Sinusoid(_Profile):
    """``k y = hk cos(2 pi X)`` (the paper's indenter), ``hk > 0``."""

    hk: float = 1.0

    def __post_init__(self):
        v = real("hk", self.hk, "a finite amplitude hk > 0", lambda v: v > 0.0)
        object.__setattr__(self, "hk", v)

    @property
    def amplitude(self) -> float:
        """max(ky) - mean(ky) = hk."""
        return self.hk

    def sample(self, nodes):
        return self.hk * np.cos(2.0 * np.pi * (np.arange(nodes) / nodes - 0.5))

    def slope(self, nodes):
        return -2.0 * np.pi * self.hk * np.sin(2.0 * np.pi * (np.arange(nodes) / nodes - 0.5))

    def _spectrum(self):
        return np.array([1.0]), np.array([-self.hk + 0j])  # cos(2 pi X) = -cos(2 pi t)


@dataclass(frozen=True)
class Harmonics(_Profile):
    """``k y = sum_n a_n cos(2 pi n X + phi_n)``, n = 1, 2, ... (one period).

    Parameters
    ----------
    amplitudes : sequence of float
        ``a_n`` (in units of 1/k), not all zero.
    phases : sequence of float
        ``phi_n`` in radians, same length.
    """

    amplitudes: tuple = ()
    phases: tuple = ()

    def __post_init__(self):
        allowed = "finite harmonic amplitudes, not all zero"
        a = series("amplitudes", self.amplitudes, allowed)
        if not any(v != 0.0 for v in a):
            raise bad("amplitudes", self.amplitudes, allowed)
        allowed = f"{len(a)} finite phases (one per amplitude)"
        p = series("phases", self.phases, allowed)
        if len(p) != len(a):
            raise bad("phases", self.phases, allowed)
        object.__setattr__(self, "amplitudes", a)
        object.__setattr__(self, "phases", p)

    def _spectrum(self):
        n = np.arange(1, len(self.amplitudes) + 1, dtype=float)
        # X = t - 1/2 shifts mode n by e^{-i pi n}
        c = np.asarray(self.amplitudes) * np.exp(1j * np.asarray(self.phases)) * (-1.0) ** n
        return n, c

    @property
    def amplitude(self) -> float:
        """max(ky) - mean(ky) of the continuous profile."""
        n, c = self._spectrum()
        return _max_of_series(n, c)


@dataclass(frozen=True, eq=False)
class SampledProfile(_Profile):
    """Heights ``k y`` sampled at ``X_j = j/M - 1/2``, j = 0..M-1 (one period, M >= 8).

    The profile between samples is their trigonometric interpolant (the unique
    trigonometric polynomial of degree <= M/2 through the samples; for even M the
    Nyquist mode is a cosine).  At N panel centres it is evaluated exactly (modes
    folded onto the N-point grid), so ``nodes = M`` reproduces the samples; for
    N < M this is sampling of the interpolant, not a low-pass filter.  The mean
    height only fixes the indenter's mean line and is removed.
    """

    heights: np.ndarray = field(repr=False)

    def __post_init__(self):
        arr = reals("heights", self.heights, "an array of k*y over one period")
        if arr.ndim != 1:
            raise bad("heights", f"<array of shape {arr.shape}>",
                      "a one-dimensional array of k*y over one period")
        if arr.size < 8:
            raise bad("heights", f"<{arr.size} samples>", "at least 8 samples over one period")
        if not np.all(np.isfinite(arr)):
            raise bad("heights", "<array with non-finite values>", "finite heights")
        if np.ptp(arr) == 0.0:
            raise bad("heights", "<constant array>", "a profile that is not flat")
        arr.flags.writeable = False
        object.__setattr__(self, "heights", arr)

    def _spectrum(self):
        y = self.heights
        m = y.size
        f = np.fft.rfft(y) / m
        c = 2.0 * f[1:]
        if m % 2 == 0:
            c[-1] = f[-1]  # Nyquist mode: f cos(pi M t)
        return np.arange(1, f.size, dtype=float), c

    @property
    def amplitude(self) -> float:
        """max(ky) - mean(ky) of the interpolant."""
        n, c = self._spectrum()
        return _max_of_series(n, c)


# --------------------------------------------------------------------------
# Files
# --------------------------------------------------------------------------
def _rows(path, option) -> list[list[str]]:
    """The non-comment lines of a UTF-8 text file, split on commas and blanks; a ValueError
    naming the file when it is binary, not UTF-8 or holds no data."""
    data = Path(path).read_bytes()
    if b"\0" in data:
        raise bad(option, str(path), "a UTF-8 text file (this one is binary: NUL bytes)")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise bad(option, str(path), f"a UTF-8 text file (byte {exc.start} is not UTF-8)") from None
    rows = []
    for raw in text.lstrip("\ufeff").splitlines():
        line = raw.split("#", 1)[0].strip()
        if line:
            rows.append(line.replace(",", " ").split())
    if not rows:
        raise bad(option, str(path), "a file with data (this one is empty or only comments)")
    return rows


def _numbers(option, path, tokens):
    """Floats of the tokens; a ValueError naming the file for a non-numeric or non-finite one."""
    out = []
    for t in tokens:
        try:
            v = float(t)
        except ValueError:
            raise bad(option, str(path), f"numeric fields ({t!r} is not a number)") from None
        if not math.isfinite(v):
            raise bad(option, str(path), f"finite numbers ({t!r} is not finite)")
        out.append(v)
    return out


def _is_number(tok: str) -> bool:
    try:
        float(tok)
        return True
    except ValueError:
        return False


def read_profile(path) -> SampledProfile:
    """Read a profile over one period from a text or CSV file.

    Format: one sample per line, ``#`` starts a comment, fields separated by
    commas or blanks, an optional non-numeric header line (e.g.
    ``x_over_lambda,ky``).  Either one column, the heights ``k y`` at
    ``X_j = j/M - 1/2`` (j = 0..M-1), or two columns ``x_over_lambda, ky`` whose
    first column must be exactly those positions (equally spaced, one period, the
    end point X = 1/2 not repeated).  At least 8 samples.  The file is read as UTF-8
    text; a binary, non-UTF-8 or empty file, or a non-finite value, is refused with a
    ValueError naming the file.

    Returns
    -------
    SampledProfile
    """
    rows = _rows(path, "profile")
    if not all(_is_number(t) for t in rows[0]):
        rows = rows[1:]
    if not rows:
        raise bad("profile", str(path), "a file with at least 8 samples of k*y")
    width = {len(r) for r in rows}
    if len(width) != 1 or width.pop() not in (1, 2):
        raise bad("profile", str(path), "one column (k*y) or two columns (x_over_lambda, k*y) "
                  "on every line")
    data = np.array([_numbers("profile", path, r) for r in rows])
    if data.shape[1] == 2:
        x = data[:, 0]
        m = x.size
        expected = np.arange(m) / m - 0.5
        if m >= 2 and abs(x[-1] - 0.5) < 1e-9 and abs(x[0] + 0.5) < 1e-9:
            raise bad("profile", str(path), "exactly one period: drop the repeated end point "
                      "x_over_lambda = 0.5")
        if not np.allclose(x, expected, rtol=0.0, atol=1e-9):
            raise bad("profile", str(path), "x_over_lambda = j/M - 1/2 for j = 0..M-1 "
                      "(one period, equally spaced, starting at -0.5)")
        data = data[:, 1]
    else:
        data = data[:, 0]
    return SampledProfile(data)


def read_prony(path) -> Prony:
    """Read a Prony creep function from a text or CSV file.

    Format (``#`` starts a comment, fields separated by blanks or commas)::

        J0 1.0          # relaxed compliance, in 1/E_ref
        0.6667 1.0      # one line per term: J_i (1/E_ref)  tau_i (tau_ref)

    The ``J0`` line is required and comes first; there may be no terms (an
    elastic material).  J(t) = J0 - sum_i J_i exp(-t/tau_i), tau_i are
    retardation (creep) times.  The format is read by `viscosine.materials.read_creep`, where
    every material file format lives; a relaxation-form file (first line ``E_r <value>``) is
    refused there, by name.  A binary, non-UTF-8 or empty file, or a non-finite value, is
    refused with a ValueError naming the file.

    Returns
    -------
    Prony
    """
    return Prony(*read_creep(path, option="prony"))
