"""The certified benchmark suite: steady viscoelastic sliding cases with certified digits.

    python -m comparisons suite --export DIR [--cases NAME ...]
    python -m comparisons suite --check [--cases NAME ...] [--out DIR] [--resume] [--workers W]
                                        [--scheduler ADDRESS]
    python -m comparisons suite --certify [--cases NAME ...]          (maintainers)

The suite lives in ``comparisons/data/suite/``: ``suite.json`` (the cases, their inputs and their
certified values), the profile and material files it names and one fields file per case
(``fields/NAME.csv``).  A case's material is the standard linear solid (``ratio``), a creep series
(``prony``: the format of :func:`bem.read_prony`) or a material file of any form (``material``: a
creep series, a relaxation series or a DMA master curve, read by
:func:`comparisons._materials.read`, with an optional ``temperature`` and ``wlf`` [C1, C2, T_ref]);
its profile is the sinusoid (``hk``) or a profile file (``profile``, :func:`bem.read_profile`).

How a value is certified (one rule for every case)
--------------------------------------------------
Every case is solved by the BEM on the meshes ``nodes`` (powers of two).  The convergence study of
a scalar q uses the last ``LAST + 1`` meshes: the differences ``d_i = |q_i − q_{i−1}|``, the
observed order p (least-squares slope of log d_i against log N_i; no certification below 0.5,
capped at 4), the envelope ``D`` (the smallest line of slope −p above every d_i, taken at the
finest mesh), the Richardson value ``q_R = q_L + (q_L − q_{L−1})/(2^p − 1)`` and the error
estimate ``E = D/(2^p − 1)`` (the tail sum of the envelope; it bounds the error of q_L and
|q_R − q_L|).  When the last two differences are below ROUNDOFF |q| (1e-11 |q|) the study is in
the round-off regime: ``q_R = q_L`` and ``E`` = the larger of ROUNDOFF |q| and the last difference.
When the order is below MIN_ORDER but the values all lie within SCATTER_FLOOR |q| (1e-8 |q|) of
each other and move both up and down, they have settled and scatter (the sub-panel edge fits):
``q_R = q_L`` and ``E`` = their spread.  Values that only rise (or only fall) drift, however
little, and are not converging.

- Two roads (standard linear solid and sinusoid, where the semi-analytic road applies): the
  certified value is the semi-analytic one, a, and its certified digits are those on which the
  two roads agree, with the error ``e = |a − q_R|`` (q_R replaced by the finest value q_L when the
  study is in the round-off regime or its differences scatter without an order ≥ 0.5: the
  sub-panel edge estimates make single refinements scatter once they reach ~1e-10).
- BEM only (Prony series, other profiles): the certified value is q_R and ``e = SAFETY · E``
  (SAFETY = 10).
- BEM and the Fourier reference (a sinusoid case on a Prony material that declares
  ``"reference": "fourier"``, opt-in per case): the case is also solved by
  :func:`analytic.fourier_solve` (dense Fourier collocation sharing no code with the BEM; creep
  series of the case's material, ``require_resolved=False``: its own estimates and refusals
  decide).  The certified value is q_R and ``e = max(SAFETY · E, |q_R − q_F|)``, q_F the Fourier
  value: the digits on which both roads agree, never more than the BEM's own study supports.
  The evidence records q_F and the reference's own error estimate (made absolute).  These
  broad-spectrum cases are where a BEM-only study is least safe (memory layers far below the
  panel width are handled by the edge fits, not resolved): an independent road is the check.

A failed BEM solve on any of the finest meshes, or a failed reference, certifies nothing (0
digits, case status "incomplete", the solver's message in the notes); ``--check`` then says when
a recomputation would certify more.

In every case the number of certified significant digits is the largest d with
``e < ½ · 10^(floor(log10 |value|) − d + 1)`` — half a unit of the last certified digit bounds e
— and that half unit at least 1e-10 |value| (RELATIVE_FLOOR, ten times the round-off level: the
round-off of the BEM's sums differs between machines, and a certified digit must survive
recomputation anywhere).
A quantity that is exact by construction (ka = π in full contact, the input of a
penetration-controlled case, …) is listed as exact.

Fields (σ, v, gap on the grid x_j = j/M − ½, M = FIELD_POINTS, a subset of the BEM's panel
centres) carry an absolute error per point: two roads, the semi-analytic value with the largest
|analytic − BEM| at the point and its two neighbours (finest mesh); otherwise (BEM only, and the
Fourier-referenced cases, whose reference is judged on the scalars), the finest mesh's
value with SAFETY × the largest change between the two finest meshes at the point and its two
neighbours (the tail sum of a first-order sequence, the pointwise order near a contact edge).
Every error is at least 1e-11 × the largest magnitude of its column (round-off).

`--check` recomputes every case and exits with status 1 when a certified digit changed: a scalar
moved by half a unit of its last certified digit or more, its recomputed evidence supports fewer
digits than shipped, a field value moved by more than its certified error, or an exact value
differs.  Recomputation that supports more digits than shipped is reported (run ``--certify``),
not a failure.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (the problem, the
standard linear solid of eq. 2.3, the friction of eq. 3.1).
"""
from __future__ import annotations

import csv
import hashlib
import io
import json
import math
import os
import shutil
import sys
import time
from pathlib import Path

import numpy as np

from . import roads as _roads
from ._io import write_text
from .convergence import observed_order, richardson

DATA = Path(__file__).resolve().parent / "data" / "suite"
SUITE_FILE = DATA / "suite.json"

SAFETY = 10.0        # margin on the BEM's own error estimate (BEM-only cases and fields)
MAX_DIGITS = 12      # a hard cap; RELATIVE_FLOOR is what binds
RELATIVE_FLOOR = 1e-10  # half a unit of the last certified digit is never below 1e-10 |value|:
                        # ten times the round-off level, which differs between machines, so a
                        # certified digit survives recomputation anywhere
FIELD_FLOOR = 1e-11  # a field error is never below this × the largest magnitude of its column
LAST = 4             # differences of the finest meshes that make the convergence study
ROUNDOFF = 1e-11     # relative size of a difference that is round-off, not discretisation
FIELD_POINTS = 256   # the stated grid of the fields, x_j = j/M − 1/2
MIN_ORDER = 0.5      # below this observed order nothing is certified (not converging) ...
#: ... unless every value of the study lies within this × |q| of the others and they move both
#: ways: the sub-panel edge fits settle and then scatter without an order.  A one-way drift is
#: not scatter (measured: prony4-partial's ka rises by ~5e-9 per doubling over N = 2^14 ... 2^20,
#: a spread of 2.1e-8, with differences that do not shrink)
SCATTER_FLOOR = 1e-8
MAX_ORDER = 4.0

#: the certification rule, as written into the suite data and the exported README
RULE = (
    "Every case is solved by the BEM on meshes N = 2^10 ... 2^18. The convergence study of a "
    f"scalar q uses the {LAST + 1} finest meshes: the differences d_i = |q_i - q_(i-1)|, the "
    "observed order p (least-squares slope of log d_i against log N_i; nothing is certified "
    f"below {MIN_ORDER}, p is capped at {MAX_ORDER:g}), the envelope D (the smallest line of "
    "slope -p above every d_i, at the finest mesh), the Richardson value "
    "q_R = q_L + (q_L - q_(L-1))/(2^p - 1) and "
    "the error estimate E = D/(2^p - 1). When the last two differences are below "
    f"{ROUNDOFF:g} |q| the study is in the round-off regime: q_R = q_L and E is the larger of "
    f"{ROUNDOFF:g} |q| and the last difference. When p is below {MIN_ORDER} but the values of "
    f"the study all lie within {SCATTER_FLOOR:g} |q| of each other and move both up and down, "
    "they have settled and scatter (the sub-panel edge fits): q_R = q_L and E is their spread "
    "(largest minus smallest); values that move one way only drift and are not converging. "
    "Two roads (standard linear solid and sinusoid): the certified value is the semi-analytic one, "
    "a, with the error e = |a - q_R| (the digits on which the two roads agree; q_R is replaced by "
    "the finest value q_L when the study is in the round-off regime or its differences scatter "
    f"with an observed order below {MIN_ORDER}). BEM only (Prony "
    f"series, other profiles): the certified value is q_R with e = {SAFETY:g} E. BEM and the "
    "Fourier reference (sinusoid on a Prony material, cases that declare it): the point is also "
    "solved by the independent Fourier collocation of analytic.fourier_solve (the creep series of "
    "the case's material), and the certified value is q_R with "
    f"e = max({SAFETY:g} E, |q_R - q_F|), q_F the Fourier value: the digits on which both roads "
    "agree, never more than the BEM's own study supports; a failed reference certifies nothing. "
    "The certified "
    "significant digits are the largest d with e < 1/2 * 10^(floor(log10|value|) - d + 1) (half "
    "a unit of the last certified digit bounds e) and that half unit at least "
    f"{RELATIVE_FLOOR:g} |value| (ten times the round-off level, so that a certified digit "
    "survives recomputation on another machine). Fields on the stated grid carry "
    "an absolute error per point: two roads, the largest |semi-analytic - BEM(finest N)| at the "
    "point and its two neighbours; otherwise (the Fourier-referenced cases too: their reference "
    f"is judged on the scalars), {SAFETY:g} x the largest change between the two "
    f"finest meshes at the point and its neighbours; never below {FIELD_FLOOR:g} x the largest "
    "magnitude of the column. A failed solve on any of the finest meshes certifies nothing.")

FIELD_COLUMNS = ("pressure", "displacement", "gap")
TOP_KEYS = ("mu", "tau_f", "penetration", "separation", "load", "contact_fraction", "ka", "ke",
            "ke_hat")
PATCH_KEYS = ("summit", "trailing_edge", "leading_edge", "load", "ka", "ke", "ke_hat")


class SuiteError(ValueError):
    """Bad input to the suite (unknown case, unreadable data); one line for the command line."""


# --------------------------------------------------------------------------- digits
def digits(value, error) -> int:
    """Certified significant digits of ``value`` given an absolute error bound ``error``.

    The largest d in 0..MAX_DIGITS with ``error < ½ · 10^(floor(log10|value|) − d + 1)`` and
    that half unit at least RELATIVE_FLOOR · |value|; 0 for a zero or non-finite value or a
    non-finite error.
    """
    if value is None or error is None or not math.isfinite(value) or not math.isfinite(error) \
            or value == 0.0:
        return 0
    e10 = math.floor(math.log10(abs(value)))
    for d in range(MAX_DIGITS, 0, -1):
        hu = 0.5 * 10.0 ** (e10 - d + 1)
        if error < hu and hu >= RELATIVE_FLOOR * abs(value):
            return d
    return 0


def half_unit(value, ndigits) -> float:
    """Half a unit of the last of ``ndigits`` significant digits of ``value`` (inf for 0 digits)."""
    if ndigits <= 0 or value == 0.0:
        return math.inf
    return 0.5 * 10.0 ** (math.floor(math.log10(abs(value))) - ndigits + 1)


def rounded(value, ndigits) -> str:
    """``value`` written with ``ndigits`` significant digits ("" when none is certified)."""
    if value is None or ndigits <= 0 or not math.isfinite(value):
        return ""
    e10 = math.floor(math.log10(abs(value))) if value != 0.0 else 0
    if -5 <= e10 < 6:
        return f"{value:.{max(ndigits - 1 - e10, 0)}f}"
    return f"{value:.{ndigits - 1}e}"


# --------------------------------------------------------------------------- convergence
def study(nodes, values, last=LAST):
    """Convergence study of one scalar over meshes doubling in N (see the module docstring).

    Parameters
    ----------
    nodes : sequence of int
        The meshes, each twice the previous one.
    values : sequence of float
        The scalar on each mesh (NaN where the solve failed).
    last : int
        Number of finest differences used (``last + 1`` meshes).

    Returns
    -------
    dict
        ``order`` (observed, NaN in the round-off regime or when undetermined), ``richardson``,
        ``estimate`` (error estimate E, inf when not converging), ``finest`` and ``regime``
        ("asymptotic", "round-off", "scatter", "not converging" or "too few meshes").
    """
    N = np.asarray(nodes, float)
    q = np.asarray(values, float)
    out = {"order": float("nan"), "richardson": float("nan"), "estimate": float("inf"),
           "finest": float(q[-1]) if q.size else float("nan"), "regime": "too few meshes"}
    if q.size < last + 1 or not np.all(np.isfinite(q[-(last + 1):])):
        return out
    q = q[-(last + 1):]
    N = N[-(last + 1):]
    d = np.abs(np.diff(q))
    floor = ROUNDOFF * float(np.max(np.abs(q)))
    if np.all(d[-2:] <= floor):
        out.update(order=float("nan"), richardson=float(q[-1]), estimate=max(floor, float(d[-1])),
                   regime="round-off")
        return out
    dd = np.maximum(d, floor)
    p = observed_order(N[1:], dd)
    out["order"] = p
    if not p >= MIN_ORDER:
        spread = float(np.max(q) - np.min(q))
        steps = np.sign(np.diff(q)[d > floor])
        # a drift (every step one way) is not scatter, however small: it may go on
        if spread <= SCATTER_FLOOR * float(np.max(np.abs(q))) and \
                np.any(steps > 0) and np.any(steps < 0):
            out.update(richardson=float(q[-1]), estimate=max(floor, spread), regime="scatter")
        else:
            out["regime"] = "not converging"
        return out
    pu = min(p, MAX_ORDER)
    r = 2.0 ** pu - 1.0
    steps = np.arange(-(d.size - 1), 1, dtype=float)  # 0 at the finest difference
    envelope = float(np.max(dd * 2.0 ** (pu * steps)))
    out.update(richardson=richardson(q[-2], q[-1], pu), estimate=envelope / r,
               regime="asymptotic")
    return out


# --------------------------------------------------------------------------- the suite file
def load_suite(path=None) -> dict:
    """The suite as a dict (``version``, ``description``, ``rule``, ``cases``: a list of case
    dicts); ``path`` defaults to the shipped ``suite.json``."""
    path = SUITE_FILE if path is None else path
    try:
        with open(path, encoding="utf-8") as fh:
            return json.load(fh)
    except (OSError, ValueError) as exc:
        raise SuiteError(f"suite data {path}: cannot be read ({exc})") from None


def case_names(suite=None) -> list[str]:
    suite = suite or load_suite()
    return [c["name"] for c in suite["cases"]]


def select(suite, names):
    """The cases named (all when ``names`` is empty), in suite order; SuiteError for an unknown
    name."""
    cases = suite["cases"]
    if not names:
        return list(cases)
    known = {c["name"]: c for c in cases}
    bad = [n for n in names if n not in known]
    if bad:
        raise SuiteError(f"--cases {bad[0]!r} is not allowed: one of {', '.join(known)}")
    return [c for c in cases if c["name"] in set(names)]


def get_case(name, suite=None) -> dict:
    return select(suite or load_suite(), [name])[0]


def two_roads(point) -> bool:
    """True when the semi-analytic road applies (sinusoid on the standard linear solid)."""
    return not point.get("profile") and not point.get("prony") and not point.get("material")


#: the independent references a case may declare (``"reference"``), beyond the two roads
REFERENCES = ("fourier",)


def reference_of(case):
    """The independent reference a case declares (None or one of REFERENCES); SuiteError for
    one it may not have."""
    ref = case.get("reference")
    if ref is None:
        return None
    if ref not in REFERENCES:
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed: "
                         f"one of {', '.join(REFERENCES)} or none")
    p = case["point"]
    if p.get("profile") or two_roads(p):
        # the Fourier collocation solves the sinusoid only, and the standard linear solid has
        # the semi-analytic road already
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed here: a "
                         "sinusoid on a Prony material (prony or material), not "
                         + ("a profile file" if p.get("profile") else "the standard linear solid"))
    return ref


def data_path(rel) -> Path:
    return DATA / rel


def case_material(point, base=DATA):
    """The :class:`comparisons._materials.Material` of a point that names a ``material`` file
    (any form: creep, relaxation, DMA; at ``temperature`` with ``wlf`` when given); SuiteError
    naming the file for a bad one."""
    from . import _materials
    wlf = point.get("wlf")
    try:
        return _materials.read(str(Path(base) / point["material"]),
                               temperature=point.get("temperature"),
                               wlf=tuple(float(v) for v in wlf) if wlf is not None else None)
    except ValueError as exc:
        raise SuiteError(f"material {point['material']}: {str(exc).splitlines()[0]}") from None


def _problem(point, base=DATA):
    """(profile, material) objects of the BEM for an operating point dict."""
    if point.get("prony"):
        material = _roads.read_prony(Path(base) / point["prony"])
    elif point.get("material"):
        material = case_material(point, base).prony
    else:
        material = _roads.standard_linear_solid(point.get("ratio", 3.0))
    if point.get("profile"):
        profile = _roads.read_profile(Path(base) / point["profile"])
    else:
        profile = _roads.sinusoid(point.get("hk", 1.0))
    return profile, material


#: the Fourier reference's estimates are relative for these (absolute for ka, ke, ke_hat)
_FOURIER_RELATIVE = ("load", "penetration", "tau_f", "mu", "contact_fraction")


def _fourier_evidence(ref, key):
    """(value, absolute error estimate) of scalar ``key`` from a Fourier result (NaN when it
    does not give one)."""
    v = _value(ref, key)
    est = ref.error_estimate or {}
    if key == "separation":  # s/h = 1 − Δ/h: the absolute error of Δ/h
        e = est.get("penetration")
        e = float("nan") if e is None else float(e) * abs(_value(ref, "penetration"))
    else:
        e = est.get(key)
        e = float("nan") if e is None else float(e) * (abs(v) if key in _FOURIER_RELATIVE
                                                         else 1.0)
    return v, e


def bem_solution(point, nodes, base=DATA, problem=None):
    """The BEM solution at an operating point on ``nodes`` panels (`roads.bem_solution`, Krylov
    tolerance `roads.BEM_TOL`); ``problem`` is read from the point's files under ``base`` when
    not given."""
    return _roads.bem_solution(point, nodes, problem or _problem(point, base))


def bem_fields(res):
    """(x, pressure, displacement, gap) of a BEM result at its panel centres, on the uniform
    grid of a fixed mesh (ValueError for a non-uniform one, whose cells these columns lose)."""
    f = res.fields() if callable(getattr(res, "fields", None)) else res
    if not getattr(f, "uniform", True):
        raise ValueError("the BEM fields are on a non-uniform grid (a contact window): "
                         "solve on a fixed mesh (nodes=N) for panel centres j/N - 1/2")
    return (np.asarray(f.x_over_lambda, float), np.asarray(f.pressure, float),
            np.asarray(f.displacement, float), np.asarray(f.gap, float))


# --------------------------------------------------------------------------- profiles
class ProfileShape:
    """k·y of the indenter as a trigonometric series, evaluated anywhere (units of :mod:`bem`).

    Built from the operating point: ``hk`` (sinusoid) or the samples of a profile file (their
    trigonometric interpolant, as :class:`bem.SampledProfile`).  Used for the summit of each
    contact patch and, in :mod:`comparisons.verify`, for the slope in the friction integral.
    """

    def __init__(self, point, base=DATA):
        if point.get("profile"):
            prof = _roads.read_profile(Path(base) / point["profile"])
            y = np.asarray(prof.heights, float)
            m = y.size
            f = np.fft.rfft(y) / m
            c = 2.0 * f[1:]
            if m % 2 == 0:
                c[-1] = f[-1]
            self.n = np.arange(1, f.size, dtype=float)
            self.c = c * np.exp(1j * np.pi * self.n)  # samples start at X = −1/2
            self.sinusoid = False
        else:
            self.n = np.array([1.0])
            self.c = np.array([float(point.get("hk", 1.0)) + 0j])
            self.sinusoid = True
        self.amplitude = float(self.max_value())

    def __call__(self, x, der=0):
        """d^der(k y)/dX^der at X = x (X = x/λ, crest of the sinusoid at 0; mean removed)."""
        x = np.atleast_1d(np.asarray(x, float))
        out = np.zeros(x.shape)
        for lo in range(0, self.n.size, 64):  # blocks keep the phase matrix small
            n = self.n[lo:lo + 64]
            c = self.c[lo:lo + 64] * (2j * np.pi * n) ** der
            out += (np.exp(2j * np.pi * np.outer(x, n)) @ c).real
        return out

    def _newton_max(self, x, lo=-math.inf, hi=math.inf):
        for _ in range(60):
            d1, d2 = float(self(x, 1)[0]), float(self(x, 2)[0])
            if d2 >= 0.0:
                break
            step = -d1 / d2
            x = min(max(x + step, lo), hi)
            if abs(step) < 1e-15:
                break
        return x

    def max_value(self):
        xs = np.arange(4096) / 4096 - 0.5
        ys = self(xs)
        j = int(np.argmax(ys))
        return float(self(self._newton_max(float(xs[j])))[0])

    def summit(self, trailing, leading):
        """X of the highest profile point in [trailing, leading] (sub-1e-13 by Newton)."""
        if self.sinusoid:
            return float(round((0.5 * (trailing + leading))))  # the crest at an integer X
        xs = np.linspace(trailing, leading, 2049)
        j = int(np.argmax(self(xs)))
        return self._newton_max(float(xs[j]), trailing, leading)


# --------------------------------------------------------------------------- generated inputs
SELF_AFFINE = {"seed": 20140392, "samples": 256, "modes": 16, "hurst": 0.8}


def self_affine_heights(seed=20140392, samples=256, modes=16, hurst=0.8):
    """A self-affine periodic profile k·y at x/λ = j/samples − 1/2 (deterministic).

    Modes n = 1..modes with amplitudes n^−(1+H) (power spectrum ∝ q^−2(1+H), Hurst exponent H)
    and phases uniform in [0, 2π) from ``numpy.random.default_rng(seed)``; scaled so that the
    highest of 2^16 evenly spaced points of the series is 1 above its mean.  ``samples`` > 2 modes,
    so the samples' trigonometric interpolant is the series itself.
    """
    rng = np.random.default_rng(seed)
    n = np.arange(1, modes + 1, dtype=float)
    amp = n ** -(1.0 + hurst)
    phase = rng.uniform(0.0, 2.0 * np.pi, modes)

    def series(x):
        return np.cos(2.0 * np.pi * np.outer(x, n) + phase) @ amp

    scale = float(np.max(series(np.arange(1 << 16) / (1 << 16) - 0.5)))
    return series(np.arange(samples) / samples - 0.5) / scale


def harmonic_heights(amplitudes, phases, samples=64):
    """k·y = Σ a_n cos(2π n x/λ + φ_n) at x/λ = j/samples − 1/2 (exact for n < samples/2)."""
    x = np.arange(samples) / samples - 0.5
    n = np.arange(1, len(amplitudes) + 1, dtype=float)
    phase = np.asarray(phases, float)
    return np.cos(2.0 * np.pi * np.outer(x, n) + phase) @ np.asarray(amplitudes, float)


#: the generated broad spectra of the suite's Fourier-referenced cases (materials/*.txt): decades
#: are (log10 of the shortest, of the longest) time, ratio is E∞/E0 = J0/J(0+) = E(0+)/E_r
BROAD24 = {"terms": 24, "decades": (-6.0, 6.0), "ratio": 1000.0}
LOGNORMAL32 = {"terms": 32, "decades": (-5.0, 5.0), "ratio": 100.0, "width": 2.0}
RELAX16 = {"terms": 16, "decades": (-4.0, 4.0), "ratio": 300.0}


def creep_spectrum(terms, decades, ratio, width=None):
    """A creep series (J0 = 1, J_i, τ_i) of E∞/E0 = ``ratio`` (deterministic).

    ``terms`` retardation times ``τ_i = 10**linspace(decades[0], decades[1], terms)``; amplitudes
    equal (a box spectrum, ``width`` None) or log-normal in τ (weights
    ``exp(−½ ((log10 τ_i − centre)/width)²)``, centre the middle decade), scaled so that
    ``Σ J_i = 1 − 1/ratio`` (J(0+) = 1/ratio).
    """
    lo, hi = decades
    tau = 10.0 ** np.linspace(lo, hi, terms)
    if width is None:
        wgt = np.ones(terms)
    else:
        wgt = np.exp(-0.5 * ((np.log10(tau) - 0.5 * (lo + hi)) / width) ** 2)
    amps = wgt / wgt.sum() * (1.0 - 1.0 / ratio)
    return 1.0, tuple(float(a) for a in amps), tuple(float(t) for t in tau)


def relaxation_spectrum(terms, decades, ratio):
    """A relaxation series (E_r = 1, E_i, θ_i) of E∞/E0 = ``ratio``: ``terms`` equal moduli
    ``E_i = (ratio − 1)/terms`` at relaxation times ``θ_i = 10**linspace(*decades, terms)``."""
    theta = 10.0 ** np.linspace(decades[0], decades[1], terms)
    return 1.0, tuple((ratio - 1.0) / terms for _ in theta), tuple(float(t) for t in theta)


def series_file_text(first, base, amplitudes, times, comment) -> str:
    """A series file: ``#`` comment lines, ``<first> <base>`` (``J0`` for a creep series, the
    format of :func:`bem.read_prony`; ``E_r`` for a relaxation series,
    :func:`viscosine.materials.read_relaxation`), then one ``amplitude time`` line per term."""
    lines = [f"# {line}" for line in comment.splitlines()] + [f"{first} {float(base)!r}"]
    lines += [f"{float(a)!r} {float(t)!r}" for a, t in zip(amplitudes, times)]
    return "\n".join(lines) + "\n"


# --------------------------------------------------------------------------- patches
def patch_records(res, shape):
    """The contact patches of a BEM result as dicts keyed by PATCH_KEYS.

    Edges are unwrapped so that the patch centre lies within ½ of its summit (the highest
    profile point inside the patch); ka = π·width, ke = 2π(centre − summit),
    kê = 2π(centroid − summit) (for the sinusoid the summit is the crest at 0 and these are the
    conventions' ka, ke, kê).  Sorted by centre, taken in [−½, ½).
    """
    out = []
    for p in getattr(res, "patches", ()) or ():
        t, l = float(p.trailing_edge), float(p.leading_edge)
        centroid = getattr(p, "centroid", None)
        if centroid is None:  # older result objects: kê measured from X = 0
            centroid = float(p.ke_hat) / (2.0 * math.pi)
        summit = shape.summit(t, l)
        shift = -math.floor(0.5 * (t + l) - summit + 0.5)
        t, l = t + shift, l + shift
        centroid = float(centroid) - math.floor(float(centroid) - summit + 0.5)
        out.append({"summit": summit, "trailing_edge": t, "leading_edge": l,
                    "load": float(p.load), "ka": math.pi * (l - t),
                    "ke": math.pi * (t + l) - 2.0 * math.pi * summit,
                    "ke_hat": 2.0 * math.pi * (centroid - summit)})
    return sorted(out, key=lambda r: _wrap(0.5 * (r["trailing_edge"] + r["leading_edge"])))


def _wrap(x):
    """x taken into [−½, ½)."""
    return x - math.floor(x + 0.5)


def match_patches(reference, patches):
    """For each patch of ``reference``, the patch of ``patches`` whose centre is nearest (modulo
    one period) if it is within half the reference patch's width and no other reference patch
    claims it; None otherwise (a patch that is missing or split on this mesh)."""
    if patches is None:
        return [None] * len(reference)
    centre = lambda r: 0.5 * (r["trailing_edge"] + r["leading_edge"])  # noqa: E731
    picks = []
    for r in reference:
        dist = [abs(_wrap(centre(q) - centre(r))) for q in patches]
        j = int(np.argmin(dist)) if dist else -1
        ok = j >= 0 and dist[j] < 0.5 * (r["leading_edge"] - r["trailing_edge"])
        picks.append(j if ok else None)
    taken = [j for j in picks if j is not None]
    return [patches[j] if j is not None and taken.count(j) == 1 else None for j in picks]


# --------------------------------------------------------------------------- one case
def _scalar_keys(point, full_contact, n_patches):
    keys = ["mu", "tau_f"]
    if point.get("load") is None:
        keys += ["load"]
    elif not full_contact:  # in full contact Δ/h = 1 and s = 0 exactly
        keys += ["penetration", "separation"]
    if not full_contact:
        keys += ["contact_fraction"]
        if n_patches == 1:
            keys += ["ka", "ke"]
    if full_contact or n_patches == 1:
        keys += ["ke_hat"]
    return keys


def _value(obj, key):
    v = getattr(obj, key, None)
    return float("nan") if v is None else float(v)


FOURIER_METHOD = "bem convergence + fourier reference"


def _certify(value_ref, seq_nodes, seq_values, roads, fourier=None):
    """One scalar's record.  ``roads``: the semi-analytic value ``value_ref`` is certified; else
    the BEM's q_R, checked against ``fourier`` ((value, absolute estimate) of the Fourier
    reference; (NaN, NaN) when it failed) when given."""
    st = study(seq_nodes, seq_values)
    ev = {"nodes": [int(n) for n in seq_nodes], "values": [_num(v) for v in seq_values],
          "order": _num(st["order"]), "richardson": _num(st["richardson"]),
          "estimate": _num(st["estimate"]), "regime": st["regime"]}
    if fourier is not None:
        value = st["richardson"]
        gap = abs(value - fourier[0])
        # the digits both roads agree on, never more than the BEM's own study supports; no
        # reference value (a failed reference) leaves no agreement to certify
        err = max(SAFETY * st["estimate"], gap) if math.isfinite(gap) else math.inf
        nd = digits(value, err)
        return {"value": _num(value), "digits": nd, "rounded": rounded(value, nd),
                "error": _num(err), "method": FOURIER_METHOD, "bem": ev,
                "fourier": {"value": _num(fourier[0]), "estimate": _num(fourier[1])}}
    if roads:
        # the BEM's best value: extrapolated when its study is asymptotic, else the finest mesh
        # (no study at all, e.g. a failed mesh, certifies nothing)
        best = st["richardson"] if st["regime"] == "asymptotic" else st["finest"]
        value = value_ref
        err = abs(value_ref - best) if (math.isfinite(best) and math.isfinite(value_ref)
                                        and st["regime"] != "too few meshes") else math.inf
        how = "two roads"
    else:
        value = st["richardson"]
        err = SAFETY * st["estimate"]
        how = "bem convergence"
    nd = digits(value, err)
    rec = {"value": _num(value), "digits": nd, "rounded": rounded(value, nd), "error": _num(err),
           "method": how, "bem": ev}
    if roads:
        rec["analytic"] = _num(value_ref)
    return rec


def _num(v):
    """JSON-safe float (None for NaN/inf)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def compute(case, base=DATA, progress=None):
    """Recompute one case: its certified scalars, patches and fields.

    Parameters
    ----------
    case : dict
        A case of ``suite.json`` (``name``, ``point``, ``nodes``).
    base : path
        Where the profile and Prony files of the case are.
    progress : callable, optional
        Called with one line of text per mesh.

    Returns
    -------
    (dict, dict)
        The ``certified`` record (as stored in ``suite.json``) and the fields columns on the
        stated grid (``x_over_lambda`` and, for each of FIELD_COLUMNS, the value and ``<col>_err``).
    """
    point = case["point"]
    nodes = [int(n) for n in case["nodes"]]
    roads = two_roads(point)
    reference = reference_of(case)
    problem = _problem(point, base)
    shape = ProfileShape(point, base)
    M = int(case.get("field_points", FIELD_POINTS))
    if nodes[-1] % M or nodes[-2] % M:
        raise SuiteError(f"case {case['name']}: the two finest meshes must be multiples of {M}")

    runs, patches, failures = [], [], []
    grid_fields = {}
    for n in nodes:
        t0 = time.perf_counter()
        r = bem_solution(point, n, base, problem)
        runs.append(r if r.success else None)
        if not r.success:
            failures.append(f"N = {n}: {r.message.splitlines()[0][:200]}")
        patches.append(patch_records(r, shape) if r.success else None)
        if n in nodes[-2:] and r.success:
            # the stated grid's points are panel centres of N = n (a multiple of M): the
            # linear resampling gives the panel values themselves, not averages
            g = r.fields().resample(M, method="linear")
            grid_fields[n] = {c: getattr(g, c) for c in ("x_over_lambda",) + FIELD_COLUMNS}
        if progress:
            progress(f"N = {n}: {'ok' if r.success else 'FAILED'} "
                     f"({time.perf_counter() - t0:.2f} s)")

    ref = _roads.analytic_solution(point) if roads else None
    if ref is not None and not ref.success:
        failures.append(f"semi-analytic: {ref.message}")
        ref_ok = False
    else:
        ref_ok = ref is not None
    four = _roads.fourier_solution(point, problem[1]) if reference == "fourier" else None
    four_ok = four is not None and bool(four.success)
    if four is not None and not four_ok:
        failures.append(f"Fourier reference: {four.message.splitlines()[0][:200]}")
    fin = next((r for r in reversed(runs) if r is not None), None)
    full = bool(ref.full_contact) if ref_ok else bool(fin.full_contact) if fin else False
    fulls = {bool(r.full_contact) for r in runs if r is not None}
    if full:
        npatch = 1
    elif patches[-1] is not None:
        npatch = len(patches[-1])
    else:
        npatch = 1 if roads else 0
    keys = _scalar_keys(point, full, npatch)

    scalars = {}
    for k in keys:
        seq = [_value(r, k) if r is not None else float("nan") for r in runs]
        if k in ("ka", "ke", "ke_hat") and not full and not roads:
            # single patch on another profile: measured from its summit
            seq = [p[0][k] if p and len(p) == 1 else float("nan") for p in patches]
        a = _value(ref, k) if ref_ok else float("nan")
        fv = None
        if four is not None:
            fv = _fourier_evidence(four, k) if four_ok else (float("nan"), float("nan"))
        scalars[k] = _certify(a, nodes, seq, roads and ref_ok, fv)
        if roads and not ref_ok:
            scalars[k]["method"] = "two roads (semi-analytic failed)"

    exact = {"full_contact": full}
    if point.get("penetration") is not None:
        exact["penetration"] = float(point["penetration"])
    if full:
        exact.update(ka=math.pi, contact_fraction=1.0, penetration=1.0, separation=0.0, ke=None)

    patch_out = []
    if not full and npatch > 1:
        matched = [match_patches(patches[-1], p) for p in patches]
        for j in range(npatch):
            rec = {}
            for k in PATCH_KEYS:
                seq = [m[j][k] if m[j] is not None else float("nan") for m in matched]
                rec[k] = _certify(float("nan"), nodes, seq, False)
            patch_out.append(rec)

    fields, field_summary = _certified_fields(point, nodes, grid_fields, ref if ref_ok else None,
                                              M, roads)
    status = "complete"
    notes = []
    if failures:
        status = "incomplete"
        notes.append("solver failures: " + "; ".join(failures))
    if len(fulls) > 1 or (ref_ok and fin is not None and bool(fin.full_contact) != full) \
            or (four_ok and bool(four.full_contact) != full):
        status = "incomplete"
        notes.append("the roads or meshes disagree on full contact")
    method = "two roads" if roads else FOURIER_METHOD if four is not None else "bem convergence"
    certified = {"method": method, "status": status,
                 "notes": notes, "scalars": scalars, "exact": exact, "patches": patch_out,
                 "fields": field_summary}
    if four is not None:
        # what the reference was and what it said (its caveats included), not its timing:
        # the record must not change when nothing certified does
        certified["reference"] = {"solver": "analytic.fourier_solve", "success": four_ok,
                                  "message": four.message.splitlines()[0][:300],
                                  "warnings": [w[:300] for w in four.warnings],
                                  "nodes": [int(n) for n in four.nodes],
                                  "shifts": int(four.shifts), "require_resolved": False}
    return certified, fields


def _neighbour_max(a):
    """max over each point and its two periodic neighbours."""
    return np.maximum(np.maximum(a, np.roll(a, 1)), np.roll(a, -1))


def _certified_fields(point, nodes, grid_fields, ref, M, roads):
    x = np.arange(M) / M - 0.5
    out = {"x_over_lambda": x}
    finest, second = nodes[-1], nodes[-2]
    bl = grid_fields.get(finest)
    bp = grid_fields.get(second)
    summary = {"file": None, "points": M, "grid": f"x_over_lambda = j/{M} - 1/2, j = 0..{M - 1}",
               "max_error": {}, "source": None}
    if roads and ref is not None:
        f = ref.fields(x)
        vals = {"pressure": f.pressure, "displacement": f.displacement, "gap": f.gap}
        summary["source"] = (f"semi-analytic values; error = largest |semi-analytic − BEM "
                             f"(N = {finest})| at the point and its neighbours")
        for c in FIELD_COLUMNS:
            a = np.asarray(vals[c], float)
            diff = np.abs(a - bl[c]) if bl is not None else np.full(M, np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(_neighbour_max(diff), FIELD_FLOOR * np.max(np.abs(a)))
    else:
        summary["source"] = (f"BEM values at N = {finest}; error = {SAFETY:g} × largest change "
                             f"from N = {second} at the point and its neighbours")
        for c in FIELD_COLUMNS:
            if bl is None:
                out[c] = np.full(M, np.nan)
                out[c + "_err"] = np.full(M, np.inf)
                continue
            a = np.asarray(bl[c], float)
            diff = np.abs(a - bp[c]) if bp is not None else np.full(M, np.inf)
            out[c] = a
            out[c + "_err"] = np.maximum(SAFETY * _neighbour_max(diff),
                                         FIELD_FLOOR * np.max(np.abs(a)))
    for c in FIELD_COLUMNS:
        summary["max_error"][c] = _num(float(np.max(out[c + "_err"])))
    return out, summary


# --------------------------------------------------------------------------- fields files
FIELDS_HEADER = ["x_over_lambda"] + [c for col in FIELD_COLUMNS for c in (col, col + "_err")]


def write_fields(path, case, fields):
    """The fields CSV: ``#`` lines (case, grid, units, how the errors are certified), a header,
    then one row per grid point; values to 17 significant digits, errors to 3."""
    buf = io.StringIO()
    buf.write(f"# viscosine benchmark suite, case {case['name']}: {case['title']}\n")
    buf.write(f"# grid: {case['certified']['fields']['grid']}\n")
    buf.write("# units: pressure = sigma (1 - nu^2)/E0, displacement = v/h (into the body, "
              "from the mean line of the deformed surface), gap = gap/h\n")
    buf.write("# <column>_err: certified absolute error of the value on the same row\n")
    buf.write(f"# {case['certified']['fields']['source']}\n")
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(FIELDS_HEADER)
    for j in range(len(fields["x_over_lambda"])):
        row = [repr(float(fields["x_over_lambda"][j]))]
        for c in FIELD_COLUMNS:
            row += [repr(float(fields[c][j])), f"{float(fields[c + '_err'][j]):.3e}"]
        w.writerow(row)
    write_text(path, buf.getvalue())


def read_fields(path) -> dict:
    """The columns of a fields CSV written by :func:`write_fields` (``#`` lines skipped)."""
    with open(path, encoding="utf-8") as fh:
        rows = [r for r in csv.reader(line for line in fh if not line.startswith("#"))]
    head = rows[0]
    data = np.array(rows[1:], dtype=float)
    return {h: data[:, i] for i, h in enumerate(head)}


def case_fields(case, base=DATA) -> dict:
    """The shipped fields of a case (columns of its fields CSV)."""
    return read_fields(Path(base) / case["certified"]["fields"]["file"])


# --------------------------------------------------------------------------- compare
def _as_float(v):
    return float("nan") if v is None else float(v)


def compare(old, new, old_fields=None, new_fields=None):
    """Differences between a shipped certification and a recomputed one.

    Returns
    -------
    (list of str, list of str)
        ``changed``: every certified digit that changed (each line names the quantity, both
        values and the difference); ``raised``: quantities the recomputation certifies to more
        digits than shipped.
    """
    changed, raised = [], []

    def one(label, o, n):
        if n is None:
            if o["digits"] > 0:
                changed.append(f"{label}: certified {o['rounded']} ({o['digits']} digits) but no "
                               "longer computed")
            return
        ov, nv = _as_float(o["value"]), _as_float(n["value"])
        if o["digits"] > 0:
            diff = abs(nv - ov) if math.isfinite(nv) else math.inf
            if not diff < half_unit(ov, o["digits"]):
                changed.append(f"{label}: certified {o['rounded']} ({o['digits']} digits), "
                               f"recomputed {nv!r}, difference {diff:.3e} ≥ half a unit "
                               f"{half_unit(ov, o['digits']):.1e}")
            elif n["digits"] < o["digits"]:
                changed.append(f"{label}: certified to {o['digits']} digits, the recomputed "
                               f"evidence supports {n['digits']} (error {n['error']})")
        if n["digits"] > o["digits"]:
            raised.append(f"{label}: {o['digits']} → {n['digits']} digits")

    for k, o in old["scalars"].items():
        one(k, o, new["scalars"].get(k))
    for k in new["scalars"]:
        if k not in old["scalars"] and new["scalars"][k]["digits"] > 0:
            raised.append(f"{k}: newly certified ({new['scalars'][k]['digits']} digits)")
    for k, v in old["exact"].items():
        if new["exact"].get(k, "missing") != v:
            changed.append(f"{k}: exact value {v!r}, recomputed {new['exact'].get(k, 'missing')!r}")
    if len(old["patches"]) != len(new["patches"]):
        changed.append(f"patches: {len(old['patches'])} certified, "
                       f"{len(new['patches'])} recomputed")
    else:
        for j, (po, pn) in enumerate(zip(old["patches"], new["patches"])):
            for k in PATCH_KEYS:
                one(f"patch {j + 1} {k}", po[k], pn[k])
    if old_fields is not None and new_fields is not None:
        for c in FIELD_COLUMNS:
            o, n, e = old_fields[c], new_fields[c], old_fields[c + "_err"]
            bad = ~(np.abs(n - o) <= e)
            if np.any(bad):
                j = int(np.flatnonzero(bad)[0])
                xj = old_fields["x_over_lambda"][j]
                changed.append(f"field {c}: {int(bad.sum())} values moved by more than their "
                               f"certified error (first at x/λ = {xj:.6f}: "
                               f"{o[j]!r} → {n[j]!r}, error {e[j]:.2e})")
    return changed, raised


# --------------------------------------------------------------------------- check
def _case_key(case) -> str:
    """Hash of what determines a case's recomputation: its definition, its input files, the
    version and the source of both roads."""
    import viscosine
    h = hashlib.sha256()
    h.update(json.dumps({k: case[k] for k in ("name", "point", "nodes")}, sort_keys=True).encode())
    h.update(str(case.get("field_points", FIELD_POINTS)).encode())
    if case.get("reference"):  # only when declared: the keys of the other cases stay as they were
        h.update(f"reference={case['reference']}".encode())
    for k in ("profile", "prony", "material"):
        if case["point"].get(k):
            h.update((DATA / case["point"][k]).read_bytes())
    if case["point"].get("material"):
        # the conversion and the DMA fit are the material's reading, outside both roads' source
        from viscosine import materials as vm

        from . import _materials
        for mod in (vm, _materials):
            h.update(Path(mod.__file__).read_bytes())
    h.update(viscosine.__version__.encode())
    h.update(_roads.source_hash().encode())
    return h.hexdigest()[:20]


def _recompute(name):
    """Worker entry: recompute one case by name (plain data in, plain data out)."""
    case = get_case(name)
    t0 = time.perf_counter()
    cert, fields = compute(case)
    return {"name": name, "key": _case_key(case), "certified": cert,
            "fields": {k: np.asarray(v).tolist() for k, v in fields.items()},
            "seconds": time.perf_counter() - t0}


def _recomputed(cases, out, resume, workers, scheduler, log):
    """Yield each case's recomputation (reusing finished ones from ``out`` with ``resume``)."""
    todo = []
    for case in cases:
        path = Path(out) / f"{case['name']}.json" if out else None
        if resume and path is not None and path.exists():
            try:
                doc = json.loads(path.read_text(encoding="utf-8"))
            except ValueError:
                doc = None
            if doc and doc.get("key") == _case_key(case):
                log(f"suite: {case['name']}: reused from {path}")
                yield doc
                continue
        todo.append(case["name"])

    def save(doc):
        if out:
            write_text(Path(out) / f"{doc['name']}.json", json.dumps(doc))
        return doc

    if not todo:
        return
    # one mechanism for every parallel run of the project (comparisons/_cluster.py): this
    # process, local processes or a Dask cluster; a case whose recomputation raises or whose
    # worker dies comes back as a Failure and is reported, the others go on
    from . import _cluster
    local = workers if (workers and workers > 1 and len(todo) > 1 and not scheduler) else None
    with _cluster.executor(local, scheduler) as ex:
        for i, value in ex.imap(_recompute, todo, ordered=False):
            if isinstance(value, _cluster.Failure):
                yield {"name": todo[i], "failed": value.error, "seconds": 0.0}
            else:
                yield save(value)


def check(names=(), out=None, resume=False, workers=1, scheduler=None, log=None, suite=None):
    """Recompute the cases and compare them with the shipped certification.

    Parameters
    ----------
    names : sequence of str
        Cases to check (all when empty).
    out : path, optional
        Folder where each recomputed case is written as soon as it is done.
    resume : bool
        Reuse the cases already recomputed in ``out`` (same definition, same version).
    workers : int
        Processes (1: in this process).
    scheduler : str, optional
        Address of a Dask distributed scheduler (instead of local processes).
    log : callable, optional
        Progress lines (default: standard error).
    suite : dict, optional
        The suite to check against (default: the shipped one).

    Returns
    -------
    dict
        ``ok`` (no certified digit changed and every case recomputed), ``cases`` (per case:
        name, changed, raised, seconds, status; a case whose recomputation raised or whose
        worker died has status "failed" and says why in ``changed``) and ``seconds``.
    """
    log = log or (lambda s: print(s, file=sys.stderr, flush=True))
    suite = suite or load_suite()
    cases = select(suite, names)
    t0 = time.monotonic()
    results = []
    by_name = {c["name"]: c for c in cases}
    for i, doc in enumerate(_recomputed(cases, out, resume, workers, scheduler, log), 1):
        case = by_name[doc["name"]]
        if "failed" in doc:  # the recomputation itself failed: nothing certified is confirmed
            results.append({"name": doc["name"], "raised": [], "seconds": 0.0,
                            "changed": [f"recomputation failed: {doc['failed']}"],
                            "status": "failed", "notes": [doc["failed"]]})
            log(f"suite: [{i}/{len(cases)}] {doc['name']}: FAILED ({doc['failed']})")
            continue
        old_fields = case_fields(case)
        new_fields = {k: np.asarray(v, float) for k, v in doc["fields"].items()}
        changed, raised = compare(case["certified"], doc["certified"], old_fields, new_fields)
        results.append({"name": doc["name"], "changed": changed, "raised": raised,
                        "seconds": doc.get("seconds", 0.0), "status": doc["certified"]["status"],
                        "notes": doc["certified"]["notes"]})
        what = "CHANGED" if changed else "ok"
        log(f"suite: [{i}/{len(cases)}] {doc['name']}: {what} ({doc.get('seconds', 0.0):.1f} s, "
            f"{time.monotonic() - t0:.0f} s in all)")
    order = {c["name"]: i for i, c in enumerate(cases)}
    results.sort(key=lambda r: order[r["name"]])
    return {"ok": not any(r["changed"] for r in results), "cases": results,
            "seconds": time.monotonic() - t0}


# --------------------------------------------------------------------------- certify
def certify(names=(), log=None, suite_file=None):
    """Recompute the cases and write their certification into the suite data (maintainers)."""
    log = log or (lambda s: print(s, file=sys.stderr, flush=True))
    suite_file = SUITE_FILE if suite_file is None else suite_file
    suite = load_suite(suite_file)
    cases = select(suite, names)
    for case in cases:
        t0 = time.perf_counter()
        cert, fields = compute(case, progress=lambda s, n=case["name"]: log(f"suite: {n}: {s}"))
        rel = f"fields/{case['name']}.csv"
        cert["fields"]["file"] = rel
        case["certified"] = cert
        write_fields(DATA / rel, case, fields)
        log(f"suite: {case['name']}: certified in {time.perf_counter() - t0:.1f} s "
            f"(mu {cert['scalars']['mu']['digits']} digits)")
    suite["rule"] = RULE
    write_text(suite_file, json.dumps(suite, indent=1, ensure_ascii=False) + "\n")


# --------------------------------------------------------------------------- export
#: what the export calls each form of a material file
FORM_NAMES = {"creep": "creep series", "relaxation": "relaxation series (generalised Maxwell)",
              "dma": "DMA master curve"}
#: the files an exported case folder writes itself (a copied material file never takes one)
EXPORT_FILES = ("inputs.json", "prony.txt", "profile.csv", "scalars.json", "scalars.csv",
                "fields.csv", "material.png")


def _source_name(point) -> str:
    """The name under which an export copies a case's original material file."""
    name = Path(point["material"]).name
    return name if name not in EXPORT_FILES else "source-" + name


def _prony_text(point) -> str:
    if point.get("prony"):
        return (DATA / point["prony"]).read_text(encoding="utf-8")
    if point.get("material"):
        m = case_material(point)
        info, pr = m.info, m.prony
        name = Path(point["material"]).name
        copied = "copied alongside" + ("" if _source_name(point) == name
                                       else f" as {_source_name(point)}")
        lines = [f"# creep series converted from {name} ({copied}): a "
                 f"{FORM_NAMES[info['form']]}, sha256 {info['sha256']}",
                 "# converted by comparisons._materials.read (relaxation series: exactly; DMA "
                 "curve: its Prony fit, then exactly)"]
        if info.get("fit"):
            f = info["fit"]
            lines.append(f"# DMA fit: {f['per_decade']:g} relaxation times per decade, largest "
                         f"relative residual {f['max_residual']:.3g} (bound {f['bound']:g}), "
                         f"measured window {f['window'][0]:.4g}..{f['window'][1]:.4g} rad/s"
                         + (" (shifted to the temperature below)"
                            if info.get("temperature") is not None else ""))
        if info.get("temperature") is not None:
            sh = info["shift"]
            lines.append(f"# at temperature {info['temperature']:g} (WLF C1 = {sh['C1']:g}, "
                         f"C2 = {sh['C2']:g}, T_ref = {sh['T_ref']:g}: log10 a_T = "
                         f"{info['log10_aT']:.6g}; every time multiplied by a_T)")
        lines.append(f"# J(t) = J0 - sum_i J_i exp(-t/tau_i), {len(pr.J)} terms; compliances in "
                     f"1/E_ref, E_ref = {info['E_ref_is']} = {info['E_ref']!r}; retardation "
                     f"(creep) times in tau_ref, tau_ref = {info['tau_ref_is']}")
        lines.append(f"J0 {float(pr.J0)!r}")
        lines += [f"{float(j)!r} {float(t)!r}" for j, t in zip(pr.J, pr.tau)]
        return "\n".join(lines) + "\n"
    r = float(point.get("ratio", 3.0))
    return ("# standard linear solid, E_inf/E0 = %r: J(t) = J0 - J1 exp(-t/tau)\n"
            "# compliances in 1/E0, times in the creep time tau\n"
            "J0 1.0\n%r 1.0\n" % (r, 1.0 - 1.0 / r))


def _profile_text(point) -> str:
    if point.get("profile"):
        return (DATA / point["profile"]).read_text(encoding="utf-8")
    hk = float(point.get("hk", 1.0))
    m = 64  # the trigonometric interpolant of 64 samples is exactly hk cos(2 pi x)
    lines = [f"# sinusoid k*y = {hk!r} cos(2 pi x/lambda), sampled at x/lambda = j/{m} - 1/2",
             "x_over_lambda,ky"]
    lines += [f"{j / m - 0.5!r},{hk * math.cos(2 * math.pi * (j / m - 0.5))!r}" for j in range(m)]
    return "\n".join(lines) + "\n"


def _inputs(case, suite) -> dict:
    p = case["point"]
    d = {"name": case["name"], "title": case["title"], "suite_version": suite["version"],
         "control": "load" if p.get("load") is not None else "penetration"}
    d.update(_roads.point_controls(p))
    d["speed"] = float(p["speed"])
    if p.get("profile"):
        text = (DATA / p["profile"]).read_text(encoding="utf-8")
        about = " ".join(ln.lstrip("# ").strip() for ln in text.splitlines() if ln.startswith("#"))
        d["profile"] = {"kind": "samples (trigonometric interpolant)", "file": "profile.csv",
                        "description": about}
    else:
        d["profile"] = {"kind": "sinusoid", "hk": float(p.get("hk", 1.0)), "file": "profile.csv"}
    units = ("load = p (1 - nu^2)/E_ref; speed = V tau_ref k; lengths in wavelengths "
             "(x/lambda, crest at 0, sliding toward +x), heights k*y; compliances in "
             "1/E_ref, times in tau_ref")
    if p.get("prony"):
        d["material"] = {"kind": "prony", "file": "prony.txt", "figure": "material.png"}
    elif p.get("material"):
        info = case_material(p).info
        d["material"] = {"kind": FORM_NAMES[info["form"]],
                         "file": "prony.txt",
                         "file_is": "the creep series the BEM solves, converted from source_file",
                         "source_file": _source_name(p), "source_sha256": info["sha256"],
                         "E_ref": info["E_ref"], "E_ref_is": info["E_ref_is"],
                         "tau_ref_is": info["tau_ref_is"],
                         "terms": info["terms"], "temperature": info["temperature"],
                         "shift": info["shift"], "log10_aT": info["log10_aT"],
                         "fit": info["fit"], "figure": "material.png"}
        units += f" (E_ref = {info['E_ref_is']}; tau_ref = {info['tau_ref_is']})"
    else:
        d["material"] = {"kind": "standard linear solid", "ratio": float(p.get("ratio", 3.0)),
                         "file": "prony.txt"}
    if not p.get("material"):
        units += " (E_ref = E0, tau_ref = tau: the creep time)"
    d["units"] = units
    if two_roads(p):
        d["reference_road"] = "semi-analytic (two roads agree)"
    elif reference_of(case) == "fourier":
        d["reference_road"] = ("BEM (convergence study), checked against the independent "
                               "Fourier-collocation reference analytic.fourier_solve (the digits "
                               "both agree on)")
    else:
        d["reference_road"] = "BEM (convergence study)"
    return d


def _scalar_rows(cert):
    rows = []
    for k, r in cert["scalars"].items():
        rows.append(["", k, r["value"], r["digits"], r["rounded"], r["error"], r["method"]])
    for k, v in cert["exact"].items():
        rows.append(["", k, v, "exact", "" if v is None else repr(v), 0.0, "exact"])
    for j, p in enumerate(cert["patches"], 1):
        for k in PATCH_KEYS:
            r = p[k]
            rows.append([j, k, r["value"], r["digits"], r["rounded"], r["error"], r["method"]])
    return rows


def export(folder, names=(), suite=None):
    """Write the suite as plain CSV/JSON, one folder per case plus ``README.md`` and ``index.json``.

    Returns the list of case folders written.
    """
    suite = suite or load_suite()
    cases = select(suite, names)
    folder = Path(folder)
    written = []
    for case in cases:
        d = folder / case["name"]
        cert = case["certified"]
        write_text(d / "inputs.json", json.dumps(_inputs(case, suite), indent=1,
                                                    ensure_ascii=False) + "\n")
        write_text(d / "prony.txt", _prony_text(case["point"]))
        if case["point"].get("material"):  # the file as the user would hold it
            shutil.copyfile(DATA / case["point"]["material"], d / _source_name(case["point"]))
        if case["point"].get("prony") or case["point"].get("material"):
            _material_png(d / "material.png", case)
        write_text(d / "profile.csv", _profile_text(case["point"]))
        sc = {"case": case["name"], "status": cert["status"], "notes": cert["notes"],
              "method": cert["method"],
              "scalars": {k: {kk: r[kk] for kk in ("value", "digits", "rounded", "error", "method")}
                          for k, r in cert["scalars"].items()},
              "exact": cert["exact"],
              "patches": [{k: {kk: p[k][kk] for kk in ("value", "digits", "rounded", "error")}
                           for k in PATCH_KEYS} for p in cert["patches"]],
              "fields": {"file": "fields.csv", "grid": cert["fields"]["grid"],
                         "max_error": cert["fields"]["max_error"]}}
        write_text(d / "scalars.json", json.dumps(sc, indent=1, ensure_ascii=False) + "\n")
        buf = io.StringIO()
        w = csv.writer(buf, lineterminator="\n")
        w.writerow(["patch", "quantity", "value", "certified_digits", "rounded", "error_bound",
                    "method"])
        for row in _scalar_rows(cert):
            w.writerow(["" if v is None else (repr(v) if isinstance(v, float) else v) for v in row])
        write_text(d / "scalars.csv", buf.getvalue())
        shutil.copyfile(DATA / cert["fields"]["file"], d / "fields.csv")
        written.append(d)
    index = {"suite_version": suite["version"], "description": suite["description"],
             "rule": suite["rule"], "cases": [c["name"] for c in cases]}
    write_text(folder / "index.json", json.dumps(index, indent=1, ensure_ascii=False) + "\n")
    write_text(folder / "README.md", _index_readme(suite, cases))
    return written


def _material_png(path, case):
    """E′, E″ and tan δ of a case's Prony material, its sliding frequency V/V0 marked."""
    from . import _figures
    point = case["point"]
    if point.get("prony"):
        j0, terms = _figures.prony_numbers(DATA / point["prony"])
        source = Path(point["prony"]).name
    else:  # the creep series converted from the material file, as the BEM solves it
        pr = case_material(point).prony
        j0, terms = float(pr.J0), [(float(j), float(t)) for j, t in zip(pr.J, pr.tau)]
        source = Path(point["material"]).name + (f" at T = {point['temperature']:g}"
                                                  if point.get("temperature") is not None else "")
    speed = float(point["speed"])
    if len(terms) <= 4:
        series = "(J_i, τ_i) = " + ", ".join(f"({j:g}, {t:g})" for j, t in terms)
    else:  # a broad spectrum: its extent, not every term, fits in a title
        taus = [t for _, t in terms]
        series = f"{len(terms)} terms, τ_i = {min(taus):.3g} … {max(taus):.3g}"
    tmp = path.with_name(path.stem + ".part.png")
    _figures.material_figure(tmp, j0, terms, speeds=[speed],
                             speeds_label=f"sliding frequency kV: ωτ_ref = V/V0 = {speed:g}",
                             title=f"{case['name']} ({source}): J0 = {j0:g}, {series}"
                                   + f"; E∞/E0 = {j0 / (j0 - sum(j for j, _ in terms)):.4g}")
    os.replace(tmp, path)


def summary_table(cases) -> str:
    """The Markdown table of `summary_rows` (`suite --list`, the exported README)."""
    from ._html import table
    return table(["case", "title", "μ digits", "Δ/h digits", "certified by"], summary_rows(cases))


def summary_rows(cases):
    """(case, title, μ digits, Δ/h or load digits, how) for each case."""
    rows = []
    for c in cases:
        cert = c["certified"]
        sc = cert["scalars"]
        if "penetration" in sc:
            second = str(sc["penetration"]["digits"])
        elif "load" in sc:  # penetration control: Δ/h is the input, the load is certified
            second = f"input ({sc['load']['digits']} in the load)"
        else:
            second = "exact (full contact)"
        rows.append([c["name"], c["title"], str(sc["mu"]["digits"]), second,
                     cert["method"] + ("" if cert["status"] == "complete"
                                       else f" — {cert['status']}")])
    return rows


def _index_readme(suite, cases) -> str:
    out = [f"# viscosine benchmark suite, version {suite['version']}", "",
           suite["description"], "",
           "Each folder is one case:", "",
           "- `inputs.json`: the operating point (load or penetration control, speed) and what "
           "the indenter and the material are, in the units stated there;",
           "- `profile.csv`: the indenter, k·y at x/λ = j/M − 1/2 (columns `x_over_lambda,ky`; "
           "the profile is the trigonometric interpolant of the samples);",
           "- `prony.txt`: the creep function, a line `J0 value` then one line `J_i tau_i` per "
           "term, J(t) = J0 − Σ J_i exp(−t/τ_i), compliances in 1/E_ref, retardation (creep) "
           "times in τ_ref; a case whose material is a relaxation series or a DMA master curve "
           "(`inputs.json` says which, at which temperature) gets the creep series it was "
           "converted to, its header naming the original file (copied alongside) and its "
           "SHA-256;",
           "- `scalars.json` and `scalars.csv`: every certified value with its certified "
           "significant digits, the value rounded to them, and the error bound behind them;",
           "- `fields.csv`: pressure, displacement and gap on a stated grid, each with its "
           "certified absolute error (`<column>_err`);",
           "- `material.png` (cases with a Prony material): the storage and loss moduli E′, E″ "
           "and the loss tangent of `prony.txt` against frequency, with the case's sliding "
           "frequency ω = kV (ωτ_ref = V/V0) marked.", "",
           "Quantities (keys of `scalars.json`): `mu` (μ = τf/p∞), `tau_f` (τf(1 − ν²)/E0), "
           "`penetration` (Δ/h), `separation` (s/h = 1 − Δ/h, the mean gap), `load` (p̃∞, "
           "certified under penetration control), `contact_fraction` (2a/λ), `ka`, `ke`, "
           "`ke_hat` (one patch or full contact); with several patches, per patch: `summit` "
           "(x/λ of the highest profile point in the patch), `trailing_edge`, `leading_edge` "
           "(x/λ), `load` (its share of p̃∞), `ka`, `ke`, `ke_hat`. `exact` lists what holds by "
           "construction (full contact: ka = π, Δ/h = 1, s = 0; the input Δ/h).", "",
           "Units and signs: pressure σ(1 − ν²)/E0 (positive in compression), displacement v/h "
           "(positive into the body, from the mean line of the deformed surface), gap/h; "
           "x/λ with the crest at 0 and the indenter sliding toward +x; μ = τf/p∞ with τf "
           "positive when it resists; ka, ke, kê in radians (per patch measured from the "
           "patch's summit).", "",
           "## How the digits are certified", "", suite["rule"], "",
           "## Cases", "",
           summary_table(cases),
           *_materials_list(cases),
           "Cite: Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (the "
           "problem and the semi-analytic method).", ""]
    return "\n".join(out)


def _materials_list(cases):
    """README lines linking the material figure of each Prony case (none without one)."""
    prony = [c for c in cases if c["point"].get("prony") or c["point"].get("material")]
    if not prony:
        return []
    return (["Prony materials (creep functions, creep times; `docs/conventions.md` of "
             "viscosine, 'Creep times, not relaxation times'):", ""]
            + [f"- {c['name']}: [{c['name']}/material.png]({c['name']}/material.png) "
               f"({Path(c['point'].get('prony') or c['point']['material']).name}"
               + (f" at T = {c['point']['temperature']:g}"
                  if c["point"].get("temperature") is not None else "")
               + f", V/V0 = {c['point']['speed']:g})"
               for c in prony] + [""])


def check_lines(res):
    """The lines `check`'s result ``res`` prints, one or more per case: ok (with its status
    when not complete), CHANGED or FAILED with what changed, and the digits that can be raised."""
    out = []
    for r in res["cases"]:
        if r["status"] == "failed":
            out.append(f"{r['name']}: FAILED")
            out += [f"  {line}" for line in r["changed"]]
        elif r["changed"]:
            out.append(f"{r['name']}: CHANGED")
            out += [f"  {line}" for line in r["changed"]]
        else:
            out.append(f"{r['name']}: ok" + (f" ({r['status']}: {'; '.join(r['notes'])[:300]})"
                                             if r["status"] != "complete" else ""))
        out += [f"  can be raised: {line} (run suite --certify --cases {r['name']})"
                for line in r["raised"]]
    return out
