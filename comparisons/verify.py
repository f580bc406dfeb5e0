"""`python -m comparisons verify`: another code's results in, a verdict and a report out.

    python -m comparisons verify (--case NAME | (--load P | --penetration D) --speed S
                                  [--ratio R] [--hk H] [--profile F] [--prony F])
                                 (--fields F.csv [F.csv ...] | --scalars F.jsonl |
                                  --callable MODULE:FUNCTION [--nodes N ...] |
                                  --peer tamaas [--nodes N ...] [--dt-cells C ... | --dt T])
                                 [--rtol R] [--tol NAME=VALUE ...] [--units SI --E0 ... ]
                                 [--out DIR] [--label TEXT] [--no-figures]

Inputs
------
- Fields CSV (``--fields``): a header line with the columns ``x_over_lambda, pressure`` and
  optionally ``displacement, gap`` (any order, other columns ignored), ``#`` comment lines allowed
  before it, one row per point of a uniform grid over one period (any offset, increasing x, the
  end point not repeated); or, with a ``width`` column, a non-uniform grid: each row's cell
  width (x/λ), the cells consecutive in row order over one period, the first centred on its row
  (the format ``python -m comparisons point --fields`` writes after a contact window).  Units of
  the conventions (pressure σ(1 − ν²)/E0, displacement v/h, gap/h), or SI with ``--units SI``
  (Pa, m, m) and ``--E0 --nu --amplitude`` to convert them.  Several files are results at
  several resolutions (N = the number of rows).
- Scalars (``--scalars``): JSON lines, one object per result, keyed like the conventions (``mu``,
  ``tau_f``, ``penetration``, ``separation``, ``load``, ``contact_fraction``, ``ka``, ``ke``,
  ``ke_hat``; conventions units), with ``nodes`` when there are several.
- A callable (``--callable module:function`` or ``path/to/file.py:function``): called as
  ``function(point, nodes)`` for each ``--nodes`` with ``point`` the operating point (a dict:
  ``load`` or ``penetration``, ``speed``, and ``ratio``/``hk`` or absolute ``prony``/``profile``
  file paths, or for a suite case that names a material file of any form an absolute
  ``material`` path with its ``temperature`` and ``wlf`` when given, as
  :func:`comparisons._materials.read` takes them); it returns a :class:`viscosine.Fields` (its cells too, on a non-uniform grid), a
  dict of arrays keyed like the CSV columns, or an object with ``.fields`` (and optionally
  ``.scalars``, a dict).
  :func:`viscosine_bem` is such a callable (viscosine's own BEM).
- ``--peer tamaas``: :mod:`comparisons.peers.tamaas` (imported only when asked for): at each
  ``--nodes`` (default 256 512 1024) a dt study with dt = C·T/N for each ``--dt-cells`` C
  (default 4 2 1), extrapolated to dt → 0 by the peer's Richardson step (``extrapolate``, the
  one the report uses), fields included; the verdict is on the extrapolated values, each shown
  with its estimated error.  Progress goes to standard error, one line per run.

Scalars from fields (documented, deterministic)
-----------------------------------------------
On the user's grid x_j (spacing 1/M), every mean the grid's own quadrature
(`viscosine.Fields.mean`: the plain mean on a uniform grid, Σ width_j f_j on a non-uniform one):

- load p̃∞ = mean σ_j (rectangle rule, exact for a trigonometric polynomial);
- τ̃f = −(1/2π) mean σ_j (ky)′(x_j): eq. (3.1), τf = −(1/λ)∫σ ∂v/∂x dx, with ∂v/∂x = ∂y/∂x on
  the contact (the only place where σ ≠ 0) and the profile's exact slope; μ = τ̃f/p̃∞;
- s/h = mean gap_j when the gap is given, else the mean over the contact points of
  y/h − v_j (in contact gap = v − y + s = 0); Δ/h = 1 − s/h;
- contact points: σ_j > 1e-9 max σ; patches are the cyclic runs of contact points;
- each edge (`edge_offset`, verify's own fit): σ² at the contact points and, when the gap is
  given, gap^(2/3) at the free points are analytic with a simple zero at the edge (σ ∝ d^½ and
  gap ∝ d^(3/2)); each side is fitted by a cubic plus a discretisation tail b h/d over the points
  ~√M/16 … ~√M/4 from the edge and again over ~√M/16 … ~√M/2 (a side cut short by the next
  edge: over the first half of its points, then all of them; too short for that, it has no
  such fit).  The sides whose zero moves by at most 2e-3 h between the two windows give the
  edge, their first zeros averaged (viscosine's BEM places its own edges so: its fields give
  back its edges).  Without such a side, the zeros of plain cubics over ~√M/16 … ~√M/2 are
  averaged over the sides whose two zeros agree to 0.1 h (a side that moves more has another
  scale next to the edge, such as a relaxation layer, which bends a plain fit by up to half a
  spacing), else over every side (fewer points on short sides; with no zero at all, σ²
  extrapolated linearly from the last two contact points).  On a non-uniform grid the fit runs
  on the cells of the edge's own width (1/M read as that width), up to the first cell of
  another width;
- per patch: ka = π·width, ke = 2π(centre − summit), kê = 2π(centroid − summit) with the centroid
  Σw_jσ_j x_j/Σw_jσ_j over the patch (w_j the cell widths) and the summit the highest profile
  point inside it (the crest 0 for the sinusoid); with several patches the top-level ka, ke, kê
  are not defined;
- full contact (every point in contact): ka = π, ke undefined, kê the phase by which the pressure
  leads the profile in the profile's dominant mode n: arg(ŷ_n/σ̂_n)/n.

Verdicts
--------
Each quantity is compared with the reference: relative difference for μ, τf, Δ/h, s/h, the load
and the contact fraction; absolute for ka, ke, kê (radians) and the contact edges (x/λ);
field norms over the user's grid (L2 by its quadrature): ``pressure_L2``, ``pressure_Linf`` (of
σ − σ_ref, over max |σ_ref|) and ``displacement_L2``, ``displacement_Linf``, ``gap_Linf`` (of v/h,
gap/h).  The tolerances follow from the grid of the result (N: its fields' points per period,
else its ``--nodes`` or ``nodes``).  Scalars and edges: max(1e-4, 3 e_N), e_N what viscosine's
BEM misses the reference by on N panels, in the same measure and with the same derivation from
its fields (`grid_errors`: the larger of its error at N and half its error at N/2, so that an
error that happens to cross zero at N does not shrink it): the discretisation error of a correct
panel solver at this case; 1e-4 when N is not known.  An explicit ``--rtol`` is a flat tolerance
of every scalar and of the edges, as asked.  Field norms: FIELD_LAW (a square-root contact edge
keeps a correct solver's σ L∞ ~ (N·2a/λ)^(-1/2) and its σ L2 ~ N^(-1) at any practical N; 3 ×
the worst constant measured on viscosine's own BEM).  ``--tol NAME=VALUE`` sets any one.  The
verdict states each tolerance and why, one line each.  A quantity passes when its difference is
at most its tolerance plus its floor, each floor stated too: on a known grid, 0.1 of a spacing per
contact edge for ka, ke, 2a/λ and the edges (POSITION_PANELS: a correct solver's edges err by up
to ~0.05 of a spacing with where each falls in its cell, which e_N of one solver does not
sample), and for a scalar derived from fields, at least what the same derivation gives on the
reference's own fields sampled on the same grid (`derivation_floor`).  The verdict also names
common slips the inputs look like (`diagnose`: a mirrored sign or x, SI values without
``--units SI``, fields one panel off their x).  The reference is
the semi-analytic road where it applies (sinusoid on the standard linear solid), else the BEM
(the suite's certified values for ``--case``, else a convergence study as the suite's; its
fields on the user's grid at N = M·2^k ≥ 2^16); the report says which, and the reference's own
uncertainty.

Several resolutions give the solver's convergence study: per quantity the order of its error
against the reference (least-squares slope over N), the self-convergence order and Richardson
value (:func:`comparisons.suite.study`), and the error of the Richardson value.

Output: ``DIR/report.md``, ``DIR/report.html`` (offline, images embedded), ``DIR/verdict.json``
and the figures (the fields, the convergence study and, for a Prony material, the material's E′,
E″ and tan δ with the operating point's sliding frequency marked); exit status 0 when every
tolerance holds, 1 otherwise (or when the solver under test, the reference or the writing of the
report fails), 2 for bad input (one line on standard error, ``python -m comparisons verify: ``
then the option, the value and what is allowed, under 400 characters).

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (eq. 3.1 for the
friction; the problem and the semi-analytic road).
"""
from __future__ import annotations

import datetime
import functools
import hashlib
import importlib
import importlib.util
import json
import math
import os
import platform
import sys
import time
import warnings
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from viscosine import Fields
from viscosine._fields import UNIFORM_SPACING, WIDTH
from viscosine._protocol import SCALAR_KEYS

from . import _errors, roads
from . import suite as _suite
from ._io import check_output_dir, write_text
from .convergence import observed_order
from .fields import true_runs

#: the scalars verify compares: the numbers among the protocol's scalars
#: (`viscosine._protocol.SCALAR_KEYS`, all but the flag full_contact) and the controls
#: separation and load; relatively (REL) or in absolute terms (ABS: positions, in radians)
REL = ("mu", "tau_f", "penetration", "separation", "load", "contact_fraction")
ABS = ("ka", "ke", "ke_hat")
COMPARED_KEYS = REL + ABS
assert set(COMPARED_KEYS) == (set(SCALAR_KEYS) - {"full_contact"}) | {"separation", "load"}
NORM_KEYS = ("pressure_L2", "pressure_Linf", "displacement_L2", "displacement_Linf", "gap_Linf",
             "edges")
ALL_KEYS = COMPARED_KEYS + NORM_KEYS
LABELS = {"mu": "μ", "tau_f": "τ̃f", "penetration": "Δ/h", "separation": "s/h",
          "load": "p̃∞", "contact_fraction": "2a/λ", "ka": "ka", "ke": "ke", "ke_hat": "kê",
          "pressure_L2": "σ L2 / max σ", "pressure_Linf": "σ L∞ / max σ",
          "displacement_L2": "v L2 / h", "displacement_Linf": "v L∞ / h",
          "gap_Linf": "gap L∞ / h", "edges": "contact edges (x/λ)"}
DEFAULT_RTOL = 1e-4
#: On a known grid of N points the default tolerance of a scalar and of the contact edges is
#: max(DEFAULT_RTOL, GRID_FACTOR · e_N), e_N what viscosine's BEM misses the reference by on N
#: panels (`grid_errors`): a correct solver's discretisation error at the case, which the flat 1e-4
#: is not at N = 512 (2a/λ 2.7e-3 at sls-light-v1, μ 9.9e-3 at sls-ratio1000-full)
GRID_FACTOR = 3.0
#: `grid_errors` solves no grid finer than this (2 s there); a finer result gets DEFAULT_RTOL,
#: which its grid's error is then far below on the suite (μ of sls-ratio1000-full, its worst:
#: 3.7e-4 at N = 4096, 6e-9 at 16384)
GRID_MAX_NODES = 1 << 18
#: On a grid of N points no position is judged finer than this fraction of a spacing per contact
#: edge (`position_floor`, added to the tolerance like the derivation floor): a correct solver's
#: edges err by a few hundredths of a spacing, varying with where each edge falls in its cell, and
#: an edge read from fields cannot know how the solver discretised next to it; e_N samples one
#: solver at one such place.  Measured over the suite's 13 partial-contact SLS cases at N = 512 …
#: 4096 on viscosine's BEM and the Fourier collocation (analytic.fourier_solve, shifts=1), their
#: own ka, ke, 2a/λ and those derived from their fields, each over the spacing it implies per
#: edge: at most 0.047 (an edge from the Fourier fields, sls-hk0.05, N = 512; its own ka at
#: sls-light-v1 0.040, the BEM's 0.037).  A tenth is twice that, and a tenth of the one-panel
#: shift that must fail
POSITION_PANELS = 0.1
DEFAULT_NODES = (1024, 2048, 4096, 8192)
#: the default ladder of ``--peer tamaas`` (grid nodes; each is a dt study, see DEFAULT_DT_CELLS):
#: Tamaas's time grows about 4.3 times per doubling of N (N steps of N log N), so the ladder stops
#: at 1024 (measured: 1.7, 7 and 40 s for the three dt studies at p̃∞ = 0.15, V/V0 = 1.058)
DEFAULT_PEER_NODES = (256, 512, 1024)
#: ``--peer tamaas``: time steps of its dt study, in cell crossings T/N, coarse to fine
DEFAULT_DT_CELLS = (4, 2, 1)

#: The default tolerances of the field norms, derived from the grid.  A square-root contact edge
#: leaves a correct solver an error at the edge panels that shrinks only like (panels across the
#: contact)^(-1/2) in L∞ and like N^(-1) in L2 (relative to max σ), and a displacement error like
#: N^(-3/2).  key -> (K, p, contact-aware): tolerance K·N^(-p), for σ with N·c in place of N
#: (L∞: K (N c)^(-1/2); L2: K N^(-1) c^(-1/2), c = 2a/λ of the reference, 1 in full contact).
#: K is 3 × the largest constant measured on viscosine's BEM at fixed N = 512, 1024, …, 8192
#: against the semi-analytic reference on the 17 standard-linear-solid cases of the suite
#: (MEASURED_FIELD_CONSTANTS, measured by `field_constants`; tests/test_verify.py checks the
#: worst ones).
FIELD_LAW = {
    "pressure_Linf": (1.4, 0.5, True),
    "pressure_L2": (1.4, 1.0, True),
    "displacement_Linf": (2.6, 1.5, False),
    "displacement_L2": (0.18, 1.5, False),
    "gap_Linf": (2.6, 1.5, False),
}
#: key -> (largest constant, where): σ over 16 of the 17 cases; the 17th, sls-ratio1000 (E∞/E0 =
#: 1000 at V/V0 = 10: its relaxation layer spans under two panels at N = 1024), reaches 1.15 (L∞)
#: and 1.17 (L2), still inside K = 1.4
MEASURED_FIELD_CONSTANTS = {
    "pressure_Linf": (0.455, "sls-ratio10, N = 4096"),
    "pressure_L2": (0.465, "sls-partial-v1, N = 2048"),
    "displacement_Linf": (0.848, "sls-partial-v100, N = 1024"),
    "displacement_L2": (0.059, "sls-partial-v100, N = 1024"),
    "gap_Linf": (0.852, "sls-partial-v100, N = 1024"),
}
CONTACT = 1e-9          # contact points: σ > CONTACT · max σ
MIN_POINTS = 8
REFERENCE_MIN_NODES = 1 << 16


class BadInput(ValueError):
    """Bad input to verify: one line naming the option, the value and what is allowed."""


def _bad(option, value, problem, allowed=None):
    text = f"{option}: {problem}" if value is None else f"{option} {value}: {problem}"
    if allowed:
        text += f"; allowed: {allowed}"
    return BadInput(text)


# =========================================================================== reading inputs
FIELDS_ALLOWED = ("a UTF-8 CSV: '#' lines, a header with x_over_lambda,pressure"
                  "[,displacement,gap][,width], one row per point over one period, uniform or "
                  "with cell widths (docs/conventions.md, 'Fields')")


def _text(path, option, allowed):
    """The text of a file, or BadInput naming the option and the file (missing, empty, binary,
    not UTF-8)."""
    p = Path(path)
    if not p.exists():
        raise _bad(option, path, "no such file", allowed)
    if p.is_dir():
        raise _bad(option, path, "is a directory, not a file", allowed)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise _bad(option, path, f"cannot be read ({exc.strerror})", allowed) from None
    if not raw.strip():
        raise _bad(option, path, "the file is empty", allowed)
    if b"\0" in raw:
        raise _bad(option, path, "a binary file, not text", allowed)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise _bad(option, path, f"not UTF-8 text (byte {exc.start})", allowed) from None


def parse_fields_csv(text, option="--fields", name="<text>") -> dict:
    """The columns of a fields CSV (see the module docstring) as float arrays, checked.

    Returns
    -------
    dict
        ``x_over_lambda``, ``pressure`` and, when present, ``displacement``, ``gap`` and
        ``width`` (the cells of a non-uniform grid).

    Raises
    ------
    BadInput
        Missing columns, non-numeric values, fewer than 8 rows, a grid that is not uniform over
        one period (without widths) or whose cells do not make one period (with them).
    """
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise _bad(option, name, "no header line (only comments)", FIELDS_ALLOWED)
    head = [h.strip().lower() for h in lines[0].split(",")]
    if "x_over_lambda" not in head or "pressure" not in head:
        raise _bad(option, name, f"the columns x_over_lambda and pressure are required "
                   f"(found: {', '.join(head)})", FIELDS_ALLOWED)
    cols = {c: head.index(c) for c in ("x_over_lambda", "pressure", "displacement", "gap", WIDTH)
            if c in head}
    rows = []
    for i, ln in enumerate(lines[1:], 2):
        cells = [c.strip() for c in ln.split(",")]
        if len(cells) < len(head):
            raise _bad(option, name, f"row {i - 1} has {len(cells)} fields, the header "
                       f"{len(head)}", FIELDS_ALLOWED)
        try:
            rows.append([float(cells[j]) for j in cols.values()])
        except ValueError:
            raise _bad(option, name, f"row {i - 1}: not a number in {ln.strip()[:60]!r}",
                       FIELDS_ALLOWED) from None
    data = np.array(rows, dtype=float).reshape(-1, len(cols))
    if data.shape[0] < MIN_POINTS:
        raise _bad(option, name, f"{data.shape[0]} rows", f"at least {MIN_POINTS} points")
    if not np.all(np.isfinite(data)):
        raise _bad(option, name, "non-finite values (nan or inf)", "finite numbers")
    out = {c: data[:, k] for k, c in enumerate(cols)}
    check_grid(out["x_over_lambda"], option, name, out.get(WIDTH))
    return out


def check_grid(x, option="--fields", name="<fields>", widths=None):
    """BadInput unless x is increasing and uniform over exactly one period (end not repeated),
    or, with ``widths``, the cells they give make one period with each point in its own."""
    x = np.asarray(x, float)
    if widths is not None:
        z = np.zeros(x.size)
        try:
            Fields(x, z, z, z, widths=widths)
        except ValueError as exc:
            raise _bad(option, name, f"the width column does not describe the grid ({exc})",
                       "cells consecutive in row order over one period, the first centred on "
                       "its row, each point in its cell") from None
        return
    m = x.size
    dx = np.diff(x)
    spread = float(np.max(np.abs(dx * m - 1.0))) if m > 1 else math.inf
    if abs(x[-1] - x[0] - 1.0) < 1e-9:
        raise _bad(option, name, "the end point of the period is repeated",
                   "one period, x_last = x_first + 1 − 1/M (drop the last row)")
    if not spread < UNIFORM_SPACING:
        raise _bad(option, name, f"x_over_lambda is not a uniform grid over one period "
                   f"(spacing × M − 1 reaches {spread:.2e})",
                   "x_j = x_0 + j/M, j = 0..M−1, increasing")


def read_fields_csv(path, option="--fields") -> dict:
    """Read and check one fields CSV file (BadInput on anything the module docstring excludes)."""
    return parse_fields_csv(_text(path, option, FIELDS_ALLOWED), option, str(path))


SCALARS_ALLOWED = ("a UTF-8 file of JSON objects, one per line, keyed like the conventions "
                   "(mu, tau_f, penetration, ka, ...), with 'nodes' when there are several")


def read_scalars_jsonl(path, option="--scalars") -> list[dict]:
    """The results of a JSON-lines file of scalars, each a dict (``nodes`` kept when given)."""
    text = _text(path, option, SCALARS_ALLOWED)
    out = []
    for i, ln in enumerate(text.splitlines(), 1):
        if not ln.strip() or ln.lstrip().startswith("#"):
            continue
        try:
            obj = json.loads(ln)
        except ValueError as exc:
            raise _bad(option, path, f"line {i} is not JSON ({exc.msg})", SCALARS_ALLOWED) from None
        if not isinstance(obj, dict):
            raise _bad(option, path, f"line {i} is not a JSON object", SCALARS_ALLOWED)
        rec = {}
        for k in COMPARED_KEYS:
            v = obj.get(k)
            if v is None:
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise _bad(option, path, f"line {i}: {k} = {v!r} is not a finite number",
                           SCALARS_ALLOWED)
            rec[k] = float(v)
        if not rec:
            raise _bad(option, path, f"line {i} has none of the keys {', '.join(COMPARED_KEYS)}",
                       SCALARS_ALLOWED)
        nodes = obj.get("nodes")
        if nodes is not None and (isinstance(nodes, bool) or not isinstance(nodes, int)
                                  or nodes < 1):
            raise _bad(option, path, f"line {i}: nodes = {nodes!r}", "a positive integer")
        out.append({"nodes": nodes, "scalars": rec})
    if not out:
        raise _bad(option, path, "no JSON object in the file", SCALARS_ALLOWED)
    if len(out) > 1 and any(r["nodes"] is None for r in out):
        raise _bad(option, path, f"{len(out)} results without 'nodes'",
                   "one result, or a 'nodes' key on every line (a convergence study)")
    if len({r["nodes"] for r in out}) != len(out):
        raise _bad(option, path, "two results with the same 'nodes'", "one result per resolution")
    return out


def load_callable(spec, option="--callable"):
    """The function named by ``module:function`` or ``path/to/file.py:function``."""
    allowed = "module:function or path/to/file.py:function, importable, the function callable"
    if not isinstance(spec, str) or spec.count(":") < 1:
        raise _bad(option, spec, "not of the form module:function", allowed)
    mod_name, func_name = spec.rsplit(":", 1)
    try:
        if mod_name.endswith(".py"):
            if not Path(mod_name).exists():
                raise _bad(option, spec, f"no such file {mod_name}", allowed)
            sp = importlib.util.spec_from_file_location(Path(mod_name).stem, mod_name)
            mod = importlib.util.module_from_spec(sp)
            sp.loader.exec_module(mod)
        else:
            mod = importlib.import_module(mod_name)
    except BadInput:
        raise
    except Exception as exc:  # any import failure is bad input, reported in one line
        raise _bad(option, spec, f"cannot import {mod_name} ({type(exc).__name__}: {exc})",
                   allowed) from None
    fn = getattr(mod, func_name, None)
    if not callable(fn):
        raise _bad(option, spec, f"{mod_name} has no callable {func_name}", allowed)
    return fn


# =========================================================================== operating point
def point_from_case(name):
    """(operating point with absolute file paths, suite case) of a suite case."""
    try:
        case = _suite.get_case(name)
    except _suite.SuiteError:
        import difflib
        names = _suite.case_names()
        near = difflib.get_close_matches(str(name), names, n=3, cutoff=0.5)
        raise _bad("--case", name, "not a suite case",
                   f"one of the {len(names)} cases `python -m comparisons suite --list` prints"
                   + (f" (closest: {', '.join(near)})" if near else
                      f", e.g. {', '.join(names[:3])}")) from None
    point = dict(case["point"])
    for k in ("profile", "prony", "material"):
        if point.get(k):
            point[k] = str(_suite.data_path(point[k]))
    return point, case


def check_point(point, option_prefix="--"):
    """BadInput unless the operating point dict is valid (ranges as the two roads accept)."""
    def num(name, test, allowed):
        v = point.get(name)
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v) \
                or not test(v):
            raise _bad(option_prefix + name, v, "out of range", allowed)
        return float(v)
    if (point.get("load") is None) == (point.get("penetration") is None):
        raise _bad(option_prefix + "load", point.get("load"),
                   "give exactly one of --load and --penetration", "one of them")
    if point.get("load") is not None:
        num("load", lambda v: v > 0.0, "a mean pressure p̃∞ > 0")
    else:
        num("penetration", lambda v: 0.0 < v <= 1.0, "Δ/h in (0, 1]")
    num("speed", lambda v: v >= 0.0, "V/V0 ≥ 0")
    if point.get("prony"):
        if point.get("ratio") is not None:
            raise _bad("--ratio", point["ratio"], "given with --prony",
                       "one of --ratio and --prony")
    else:
        num("ratio", lambda v: v > 1.0, "E∞/E0 > 1")
    if point.get("profile"):
        if point.get("hk") is not None:
            raise _bad("--hk", point["hk"], "given with --profile", "one of --hk and --profile")
    else:
        num("hk", lambda v: v > 0.0, "hk > 0")
    for k, reader in (("profile", roads.read_profile), ("prony", roads.read_prony)):
        if point.get(k):
            path = point[k]
            _text(path, "--" + k, f"a {k} file (see bem.read_{k})")
            try:
                reader(path)
            except ValueError as exc:
                raise _bad("--" + k, path, str(exc).split(": ", 1)[-1],
                           f"the format of bem.read_{k}") from None
    return point


# =========================================================================== scalars from fields
def _grid(fields) -> Fields:
    """The `viscosine.Fields` of a fields dict, for its quadrature (a column it lacks is zeros
    there: only what the dict holds is ever read from it)."""
    x = np.asarray(fields["x_over_lambda"], float)
    z = np.zeros(x.size)
    cols = [fields.get(c) for c in ("pressure", "displacement", "gap")]
    return Fields(x, *(z if a is None else a for a in cols), widths=fields.get(WIDTH))


def _same_width(idx, w, h):
    """The leading indices of ``idx`` whose cells have the width h (the edge fit's spacing)."""
    same = np.abs(w[idx] - h) <= 1e-9 * h
    return idx if same.all() else idx[:int(np.argmin(same))]


# The contact edges: verify's own fit (no solver's code), the model in the module docstring.
# Near an edge σ ∝ d^½ and gap ∝ d^(3/2) with analytic corrections, so σ² (inside) and
# gap^(2/3) (outside) are analytic with a simple zero at the edge; a grid adds a tail that decays
# away from it (~h/d for a panel solver), which a plain polynomial mistakes for a shift.
#: degree of the polynomial part of every edge fit
EDGE_DEGREE = 3
#: passes of the fixed point in the tail's distances (measured to contract by 0.1-0.3 a pass);
#: a side that has not settled to 1e-10 h after them gives no zero
EDGE_PASSES = 40
#: a side whose zero moves by at most this many spacings between its two windows holds the model
#: to the fit's resolution (~1e-4 h on exact samples; viscosine's BEM's edge fit uses the same
#: bound, so its fields give back its own edges)
EDGE_STILL = 2e-3
#: with no side that still, a side counts in the plain fits only if both its windows place a
#: zero and the zeros agree to this many spacings (the resolution POSITION_PANELS claims): a side
#: that fails it has another scale in its window (a relaxation layer next to the edge), which
#: bends a plain fit by up to half a spacing (measured: the leading edge from the Fourier
#: collocation's fields at sls-partial-v0.1, N = 1024, 0.54 h with the pressure's side, 0.003 h
#: without it; on exact samples and viscosine's BEM's fields of the 13 partial-contact SLS suite
#: cases at N = 512 … 4096 no edge gets worse by more than 0.002 h for it)
EDGE_HOLDS = 0.1


def _edge_windows(m):
    """(first, narrow last, plain last) point indices of the edge fits on a grid of m points."""
    first = max(1, int(round(math.sqrt(m) / 16.0)))
    return (first, max(first + EDGE_DEGREE + 4, int(round(math.sqrt(m) / 4.0))),
            max(first + 6, int(round(math.sqrt(m) / 2.0))))


def _nearest_real_root(coef, near):
    """The real root of the polynomial Σ coef_k t^k nearest ``near`` (None without one)."""
    roots = np.polynomial.polynomial.polyroots(coef)
    real = roots.real[np.abs(roots.imag) < 1e-9]
    return float(real[np.argmin(np.abs(real - near))]) if real.size else None


def _plain_roots(sides, h, m):
    """The plain fit's root of each side (None where it has none in [−h, 2h]): the
    least-squares cubic over the points ~√m/16 … ~√m/2 from the edge (from the edge point on,
    quadratic, where fewer remain), its root nearest the edge."""
    first, _, last = _edge_windows(m)
    roots = []
    for vals, sign, shift in sides:
        top = min(last, vals.size - 1)
        lo = first if top - first >= 5 else 0
        root = None
        if top - lo >= 3:
            k = np.arange(lo, top + 1)
            pos = sign * (k + shift) * h
            scale = float(np.max(np.abs(pos)))
            coef = np.polynomial.polynomial.polyfit(pos / scale, vals[k],
                                                    3 if top - lo >= 5 else 2)
            root = _nearest_real_root(coef, 0.0)
            root = root * scale if root is not None and -h <= root * scale <= 2.0 * h else None
        roots.append(root)
    return roots


def _tail_zero(vals, sign, shift, lo, hi, start, h):
    """The zero near ``start`` of the least-squares cubic + b h/|d| through vals[k] at the
    offsets sign (k + shift) h, k = lo … hi (d = offset − zero, the zero iterated to a fixed
    point); None with too few points, a zero outside [−h/2, 3h/2] or no fixed point."""
    hi = min(hi, vals.size - 1)
    if hi - lo < EDGE_DEGREE + 4:
        return None
    k = np.arange(lo, hi + 1)
    pos = sign * (k + shift) * h
    scale = hi * h
    poly = np.vander(pos / scale, EDGE_DEGREE + 1, increasing=True)
    zero = start
    for _ in range(EDGE_PASSES):
        design = np.column_stack((poly, h / np.abs(pos - zero)))
        coef = np.linalg.lstsq(design, vals[k], rcond=None)[0]
        root = _nearest_real_root(coef[:-1], zero / scale)
        if root is None or not -0.5 * h <= root * scale <= 1.5 * h:
            return None
        moved, zero = abs(root * scale - zero), root * scale
        if moved <= 1e-10 * h:
            return zero
    return None


def edge_offset(inside_sq, outside_23, h, m):
    """How far a contact edge lies beyond the last contact point (x/λ, toward the free side).

    Parameters
    ----------
    inside_sq : ndarray
        σ² at the contact points counted inward from the edge (index 0 the last contact point,
        at offset 0; index k at −k h).
    outside_23 : ndarray
        gap^(2/3) at the free points counted outward (index k at offset (k + 1) h); may be empty.
    h : float
        The spacing (x/λ).
    m : int
        Points per period (the fit windows grow like √m).

    Returns
    -------
    float
        The offset, in [−h/2, 3h/2].  Each side is fitted by a cubic plus a tail b h/d over the
        points ~√m/16 … ~√m/4 from the edge (its narrow window; a side cut short by the next
        edge: the first half of its points) and over twice as many (its wide window).  The
        narrow zeros of the sides whose two zeros agree to EDGE_STILL h are averaged.  Else
        the plain fits (`_plain_roots`) of the sides whose two zeros agree to EDGE_HOLDS h are
        averaged; with none (or no root), those of every side; with none of them either, σ²
        extrapolated linearly from the last two contact points (at most h), else h/2.  A mean
        of plain roots is clipped to [−h/2, 3h/2].
    """
    sides = ((inside_sq, -1.0, 0.0), (outside_23, 1.0, 1.0))
    plain = _plain_roots(sides, h, m)
    found = [r for r in plain if r is not None]
    if found:
        start = min(max(sum(found) / len(found), -0.5 * h), 1.5 * h)
    elif inside_sq.size >= 2 and inside_sq[1] > inside_sq[0]:
        start = min(h, h * inside_sq[0] / (inside_sq[1] - inside_sq[0]))
    else:
        start = 0.5 * h
    first, narrow, _ = _edge_windows(m)
    moves = []  # per side: (how far its zero moves between the windows, its narrow zero)
    for vals, sign, shift in sides:
        top = min(narrow, (vals.size - 1) // 2)
        near = _tail_zero(vals, sign, shift, first, top, start, h)
        wide = _tail_zero(vals, sign, shift, first, 2 * top, start, h)
        moves.append((math.inf, None) if near is None or wide is None else
                     (abs(near - wide), near))
    still = [z for d, z in moves if d <= EDGE_STILL * h]
    if still:
        return sum(still) / len(still)
    held = [r for r, (d, _) in zip(plain, moves) if r is not None and d <= EDGE_HOLDS * h]
    if held:
        return min(max(sum(held) / len(held), -0.5 * h), 1.5 * h)
    return start


def scalars_from_fields(fields, shape):
    """Scalars and contact patches computed from fields over one period.

    Parameters
    ----------
    fields : dict
        ``x_over_lambda``, ``pressure`` and optionally ``displacement``, ``gap`` (conventions
        units; x uniform over one period, increasing) and ``width`` (the cells of a non-uniform
        grid; see the module docstring).
    shape : comparisons.suite.ProfileShape
        The indenter (k·y and its slope anywhere).

    Returns
    -------
    (dict, list of dict)
        The scalars (keys of COMPARED_KEYS plus ``full_contact``; a key is absent when the fields
        cannot give it) and the patches (``trailing_edge``, ``leading_edge``, ``load``,
        ``centroid``, ``summit``, ``ka``, ``ke``, ``ke_hat``).  The method is in the module
        docstring.
    """
    grid = _grid(fields)
    uniform = grid.uniform
    x = grid.x_over_lambda
    p = grid.pressure
    v = fields.get("displacement")
    g = fields.get("gap")
    m = x.size
    h = 1.0 / m
    w_cells = grid.widths
    pmax = float(np.max(p))
    out = {}
    load = grid.mean("pressure")
    out["load"] = load
    tau = -grid.mean(p * shape(x, 1)) / (2.0 * math.pi)
    out["tau_f"] = tau
    if load != 0.0:
        out["mu"] = tau / load
    contact = p > CONTACT * pmax if pmax > 0.0 else np.zeros(m, bool)
    hk = shape.amplitude
    if g is not None:
        sep = grid.mean("gap")
    elif v is not None and contact.any():
        rest = (shape(x) / hk - np.asarray(v, float))[contact]
        sep = (float(np.mean(rest)) if uniform else  # the mean over the contact's own cells
               float(np.sum(w_cells[contact] * rest) / np.sum(w_cells[contact])))
    else:
        sep = None
    if sep is not None:
        out["separation"] = sep
        out["penetration"] = 1.0 - sep
    full = bool(contact.all())
    out["full_contact"] = full
    patches = []
    if full:
        out.update(ka=math.pi, contact_fraction=1.0)
        if uniform:
            yh = np.fft.rfft(shape(x))
            sh = np.fft.rfft(p)
            n = int(np.argmax(np.abs(yh[1:]))) + 1
            out["ke_hat"] = float(np.angle(yh[n] / sh[n])) / n
        else:  # the dominant mode of the profile, then both coefficients by the grid's quadrature
            n = int(np.argmax(np.abs(np.fft.rfft(shape(np.arange(4096) / 4096 - 0.5))[1:]))) + 1
            phase = np.exp(-2j * math.pi * n * x)
            yn = np.sum(w_cells * shape(x) * phase)
            sn = np.sum(w_cells * p * phase)
            out["ke_hat"] = float(np.angle(yn / sn)) / n
        return out, patches
    runs = true_runs(contact)
    for i, (first, length) in enumerate(runs):
        nxt = runs[(i + 1) % len(runs)][0]
        prv_first, prv_len = runs[i - 1]
        free_after = (nxt - (first + length)) % m
        free_before = (first - (prv_first + prv_len)) % m
        if len(runs) == 1:
            free_after = free_before = m - length
        half = (length - 1) // 2 + 1
        last = first + length - 1
        i_lead = (last - np.arange(half)) % m
        i_trail = (first + np.arange(half)) % m
        o_lead = (last + 1 + np.arange(free_after // 2)) % m
        o_trail = (first - 1 - np.arange(free_before // 2)) % m
        h_lead = h_trail = h
        m_lead = m_trail = m
        if not uniform:  # each edge is fitted on the cells of its own width, read as 1/M
            h_lead, h_trail = float(w_cells[last % m]), float(w_cells[first])
            m_lead, m_trail = int(round(1.0 / h_lead)), int(round(1.0 / h_trail))
            i_lead, o_lead = (_same_width(i, w_cells, h_lead) for i in (i_lead, o_lead))
            i_trail, o_trail = (_same_width(i, w_cells, h_trail) for i in (i_trail, o_trail))
        ins_lead = p[i_lead] ** 2
        ins_trail = p[i_trail] ** 2
        if g is not None:
            ga = np.abs(np.asarray(g, float))
            out_lead = ga[o_lead] ** (2.0 / 3.0)
            out_trail = ga[o_trail] ** (2.0 / 3.0)
        else:
            out_lead = out_trail = np.zeros(0)
        x_first = x[first]
        ids = (first + np.arange(length)) % m
        if uniform:
            x_last = x_first + (length - 1) * h  # unwrapped across the end of the period
            xs = x_first + h * np.arange(length)
            w = p[ids]
        else:
            xs = x_first + np.mod(x[ids] - x_first, 1.0)
            x_last = float(xs[-1])
            w = p[ids] * w_cells[ids] * m  # the pressures weighed by their cells (over 1/M)
        lead = x_last + edge_offset(ins_lead, out_lead, h_lead, m_lead)
        trail = x_first - edge_offset(ins_trail, out_trail, h_trail, m_trail)
        centroid = float(np.dot(w, xs) / w.sum()) if w.sum() > 0 else 0.5 * (trail + lead)
        summit = shape.summit(trail, lead)
        shift = -math.floor(0.5 * (trail + lead) - summit + 0.5)
        patches.append({"trailing_edge": trail + shift, "leading_edge": lead + shift,
                        "load": float(w.sum()) / m, "centroid": centroid + shift,
                        "summit": summit, "ka": math.pi * (lead - trail),
                        "ke": math.pi * (trail + lead) - 2.0 * math.pi * summit,
                        "ke_hat": 2.0 * math.pi * (centroid - summit)})
    patches.sort(key=lambda r: _suite._wrap(0.5 * (r["trailing_edge"] + r["leading_edge"])))
    out["contact_fraction"] = float(sum(r["leading_edge"] - r["trailing_edge"] for r in patches))
    if len(patches) == 1:
        out.update(ka=patches[0]["ka"], ke=patches[0]["ke"], ke_hat=patches[0]["ke_hat"])
    return out, patches


# =========================================================================== the reference
@dataclass
class Reference:
    """The reference of a verification: scalars, patches and fields on any grid.

    ``road`` is ``"semi-analytic"`` or ``"BEM"``; ``scalars[key]`` = (value, uncertainty) with an
    absolute uncertainty; ``patches`` a list of dicts with ``trailing_edge``, ``leading_edge``.
    """

    road: str
    description: str
    point: dict
    scalars: dict
    patches: list
    full_contact: bool | None
    shape: object
    _analytic: object = None
    _bem_cache: dict = field(default_factory=dict)

    def fields(self, x):
        """(reference fields at x, their absolute uncertainty per column) as dicts of arrays."""
        x = np.asarray(x, float)
        if self._analytic is not None:
            f = self._analytic.fields(x)
            vals = {"pressure": np.asarray(f.pressure), "displacement": np.asarray(f.displacement),
                    "gap": np.asarray(f.gap)}
            unc = {k: np.full(x.size, 1e-12 * max(1.0, float(np.max(np.abs(a)))))
                   for k, a in vals.items()}
            return vals, unc
        m = x.size
        n_ref = m * 2
        while n_ref < REFERENCE_MIN_NODES:
            n_ref *= 2
        fine = self._bem_on(x, n_ref)
        coarse = self._bem_on(x, n_ref // 2)
        unc = {k: np.abs(fine[k] - coarse[k]) for k in fine}
        return fine, unc

    def _bem_on(self, x, n):
        if n not in self._bem_cache:
            res = _suite.bem_solution(self.point, n, base="/")
            if not res.success:
                raise RuntimeError(f"the reference BEM did not converge at N = {n}: "
                                   f"{res.message.splitlines()[0][:200]}")
            self._bem_cache[n] = _suite.bem_fields(res)
        X, p, v, g = self._bem_cache[n]
        # aligned grid points are panel centres; others are interpolated (σ² and gap^(2/3)
        # are the quantities that are smooth through an edge)
        pos = (np.asarray(x, float) + 0.5) * n
        idx = np.rint(pos)
        if np.all(np.abs(pos - idx) < 1e-6):
            j = idx.astype(np.int64) % n
            return {"pressure": p[j], "displacement": v[j], "gap": g[j]}
        xe = np.concatenate((X - 1.0, X, X + 1.0))
        xw = np.asarray(x, float) - np.floor(np.asarray(x, float) + 0.5)

        def lin(a):
            return np.interp(xw, xe, np.tile(a, 3))
        return {"pressure": np.sqrt(lin(p ** 2)), "displacement": lin(v),
                "gap": lin(np.abs(g) ** (2.0 / 3.0)) ** 1.5}


def reference_for(point, case=None) -> Reference:
    """The reference for an operating point: the semi-analytic road where it applies, else the
    suite's certified BEM values (``case``) or a BEM convergence study as the suite's."""
    shape = _suite.ProfileShape(point, base="/")
    if _suite.two_roads(point):
        sol = roads.analytic_solution(point)
        if not sol.success:
            raise RuntimeError(f"the semi-analytic reference failed: {sol.message}")
        sc = {}
        for k in COMPARED_KEYS:
            v = getattr(sol, k, None)
            if v is not None:
                sc[k] = (float(v), 1e-12 * abs(float(v)))
        if case is not None:  # the certified values carry the two roads' agreement
            for k, r in case["certified"]["scalars"].items():
                if r["value"] is not None and r["error"] is not None:
                    sc[k] = (float(r["value"]), float(r["error"]))
        patches = []
        if not sol.full_contact:
            patches = [{"trailing_edge": (sol.ke - sol.ka) / (2 * math.pi),
                        "leading_edge": (sol.ke + sol.ka) / (2 * math.pi)}]
        desc = ("the semi-analytic road (analytic/: Hunter's transformation, the closure "
                "(2.14)–(2.15), Appendix B in full contact)"
                + (f"; scalars as certified in the suite case {case['name']}" if case else ""))
        return Reference("semi-analytic", desc, point, sc, patches, bool(sol.full_contact),
                         shape, _analytic=sol)
    if case is None:
        nodes = [2 ** k for k in range(10, 19)]
        case = {"name": "reference", "title": "reference", "point": point, "nodes": nodes}
        cert, _ = _suite.compute(case, base="/")
        case = dict(case, certified=cert)
        desc = ("the BEM (bem/), a convergence study over N = 2^10 … 2^18 as the suite's "
                "(Richardson values; uncertainty 10 × the estimate)")
    else:
        desc = f"the BEM (bem/): the certified values of the suite case {case['name']}"
    cert = case["certified"]
    sc = {k: (float(r["value"]), float(r["error"]) if r["error"] is not None else math.inf)
          for k, r in cert["scalars"].items() if r["value"] is not None}
    full = bool(cert["exact"].get("full_contact"))
    for k in ("ka", "contact_fraction", "penetration", "separation"):
        if k in cert["exact"] and cert["exact"][k] is not None and k not in sc:
            sc[k] = (float(cert["exact"][k]), 0.0)
    if cert["patches"]:
        patches = [{"trailing_edge": p["trailing_edge"]["value"],
                    "leading_edge": p["leading_edge"]["value"]} for p in cert["patches"]]
    elif not full and "ka" in sc:
        s0 = shape.summit(-0.5, 0.5) if not shape.sinusoid else 0.0
        ka, ke = sc["ka"][0], sc["ke"][0]
        patches = [{"trailing_edge": s0 + (ke - ka) / (2 * math.pi),
                    "leading_edge": s0 + (ke + ka) / (2 * math.pi)}]
    else:
        patches = []
    return Reference("BEM", desc, point, sc, patches, full, shape)


# =========================================================================== the solver's results
@dataclass
class Result:
    """One result of the solver under test: its resolution, fields (dict or None) and scalars."""

    nodes: int | None
    fields: dict | None
    scalars: dict
    patches: list
    source: str   # "fields" or "solver"
    errors: dict | None = None  # the solver's own error estimates (absolute), when it gave some


def _as_fields(obj, option, label):
    """A dict of arrays from a Fields, a dict, or an object with .fields."""
    f = getattr(obj, "fields", obj)
    if callable(f) and not isinstance(f, dict):
        f = f()
    if isinstance(f, dict):
        d = {k: np.asarray(v, float) for k, v in f.items() if v is not None}
    elif isinstance(f, Fields):
        d = {k: np.asarray(v, float) for k, v in f.as_dict().items()}  # with its cells
    else:
        d = {}
        for k in ("x_over_lambda", "pressure", "displacement", "gap"):
            v = getattr(f, k, None)
            if v is not None:
                d[k] = np.asarray(v, float)
    if "x_over_lambda" not in d or "pressure" not in d:
        raise _bad(option, label, "returned no x_over_lambda and pressure",
                   "a viscosine.Fields, a dict of arrays or an object with .fields")
    n = d["x_over_lambda"].size
    if any(a.shape != (n,) for a in d.values()) or n < MIN_POINTS:
        raise _bad(option, label, "returned columns of different lengths or too few points",
                   f"1-D arrays of one length >= {MIN_POINTS}")
    check_grid(d["x_over_lambda"], option, label, d.get(WIDTH))
    return d


def results_from_fields(fields_list, shape, nodes=None, solver_scalars=None):
    out = []
    for i, f in enumerate(fields_list):
        sc, patches = scalars_from_fields(f, shape)
        source = "fields"
        if solver_scalars and solver_scalars[i]:
            sc = {**sc, **{k: float(v) for k, v in solver_scalars[i].items()
                           if k in COMPARED_KEYS and v is not None}}
            source = "solver (fields for the rest)"
        out.append(Result(nodes[i] if nodes else f["x_over_lambda"].size, f, sc, patches, source))
    return out


def to_conventions(fields, E0, nu, amplitude):
    """SI fields (Pa, m, m) in the conventions' units (σ(1 − ν²)/E0, v/h, gap/h)."""
    scale = (1.0 - nu * nu) / E0
    out = dict(fields)
    out["pressure"] = np.asarray(fields["pressure"], float) * scale
    for k in ("displacement", "gap"):
        if k in fields:
            out[k] = np.asarray(fields[k], float) / amplitude
    return out


def viscosine_bem(point, nodes):
    """viscosine's own BEM as a ``--callable``: ``comparisons.verify:viscosine_bem``.

    Returns the BEM's fields at its panel centres (x/λ = j/N − ½) as a dict of arrays.
    """
    res = _suite.bem_solution(point, int(nodes), base="/")
    if not res.success:
        raise RuntimeError(f"BEM not converged at N = {nodes}: {res.message.splitlines()[0]}")
    x, p, v, g = _suite.bem_fields(res)
    return {"x_over_lambda": x, "pressure": p, "displacement": v, "gap": g}


def _tamaas_module():
    try:
        return importlib.import_module("comparisons.peers.tamaas")
    except ImportError as exc:
        raise _bad("--peer", "tamaas", f"comparisons.peers.tamaas is not available ({exc})",
                   "a viscosine with the peers extra ('.[peers]')") from None


def peer_tamaas(point, nodes, dt=None, cells=None, progress=None):
    """Results of the third-party code Tamaas through :mod:`comparisons.peers.tamaas`.

    Imported only here, when ``--peer tamaas`` is asked for.  With ``dt`` (units of τ): one run,
    ``solve(*, load, speed, ratio, hk, nodes, dt)``.  Otherwise a dt study on this grid,
    ``dt_extrapolation(..., cells_per_step=cells)`` (default DEFAULT_DT_CELLS: T/N × 4, 2, 1),
    extrapolated to dt → 0 with the peer's own Richardson step (the one the report uses).
    Either returns an object with ``.fields`` (a viscosine.Fields) and ``.scalars``; the study
    also has ``.error`` (the estimated error of each extrapolated scalar).
    """
    peer = _tamaas_module()
    kw = {"load": point.get("load"), "speed": point["speed"], "ratio": point["ratio"],
          "hk": point["hk"], "nodes": int(nodes)}
    if dt is not None:
        return peer.solve(**kw, dt=dt)
    return peer.dt_extrapolation(**kw, cells_per_step=tuple(cells or DEFAULT_DT_CELLS),
                                 progress=progress)


# =========================================================================== comparison
def _measure(key, value, ref):
    if value is None or ref is None:
        return None
    if key in REL:
        return abs(value - ref) / abs(ref) if ref != 0.0 else abs(value - ref)
    return abs(value - ref)


def _match(ref_patches, patches):
    """Edge differences (x/λ) of matched patches; None when the patch counts differ."""
    if len(ref_patches) != len(patches):
        return None
    diffs = []
    for r in ref_patches:
        best = min(patches, key=lambda q: abs(_suite._wrap(
            0.5 * (q["trailing_edge"] + q["leading_edge"])
            - 0.5 * (r["trailing_edge"] + r["leading_edge"]))))
        shift = round(0.5 * (r["trailing_edge"] + r["leading_edge"])
                      - 0.5 * (best["trailing_edge"] + best["leading_edge"]))
        diffs.append((best["trailing_edge"] + shift - r["trailing_edge"],
                      best["leading_edge"] + shift - r["leading_edge"]))
    return diffs


def norms(result: Result, reference: Reference):
    """Field norms of a result against the reference on the result's grid (with the reference's
    uncertainty in the same norms), and the reference fields there."""
    if result.fields is None:
        return {}, {}, None
    f = result.fields
    grid = _grid(f)  # the norms weigh each point by its cell
    ref, unc = reference.fields(f["x_over_lambda"])
    pm = float(np.max(np.abs(ref["pressure"])))
    out, out_unc = {}, {}
    dp = f["pressure"] - ref["pressure"]
    out["pressure_L2"] = grid.l2(dp) / pm
    out["pressure_Linf"] = grid.linf(dp) / pm
    out_unc["pressure_L2"] = grid.l2(unc["pressure"]) / pm
    out_unc["pressure_Linf"] = grid.linf(unc["pressure"]) / pm
    if "displacement" in f:
        dv = f["displacement"] - ref["displacement"]
        out["displacement_L2"] = grid.l2(dv)
        out["displacement_Linf"] = grid.linf(dv)
        out_unc["displacement_L2"] = grid.l2(unc["displacement"])
        out_unc["displacement_Linf"] = grid.linf(unc["displacement"])
    if "gap" in f:
        out["gap_Linf"] = grid.linf(f["gap"] - ref["gap"])
        out_unc["gap_Linf"] = grid.linf(unc["gap"])
    return out, out_unc, ref


def grid_size(fields, reference):
    """(N, c) of the field law (FIELD_LAW) for fields on the user's grid against a reference.

    N is the number of points per period; on a non-uniform grid (cells of several widths) N is
    1/width of the coarsest cell holding a contact edge of the reference (1/the coarsest cell in
    full contact).  c is the narrowest patch width of the reference over λ (its contact
    fraction with one patch), 1 in full contact.
    """
    grid = _grid(fields)
    m = grid.x_over_lambda.size
    edges = [e for p in reference.patches for e in (p["trailing_edge"], p["leading_edge"])]
    if grid.uniform:
        n = float(m)
    else:
        w = grid.widths
        if edges:
            ce = grid.cell_edges
            start = float(ce[0])
            where = [int(np.searchsorted(ce, start + (e - start) % 1.0, side="right")) - 1
                     for e in edges]
            n = 1.0 / float(max(w[min(max(i, 0), m - 1)] for i in where))
        else:
            n = 1.0 / float(np.max(w))
    if reference.full_contact or not reference.patches:
        c = 1.0
    else:
        c = min(p["leading_edge"] - p["trailing_edge"] for p in reference.patches)
        c = min(max(c, 1e-12), 1.0)
    return n, c


def field_tolerance(key, n, c):
    """The default tolerance of one field norm on N = n points, contact width c (FIELD_LAW)."""
    k, p, contact = FIELD_LAW[key]
    if not contact:
        return k * n ** -p
    return k * (n * c) ** -0.5 if key == "pressure_Linf" else k / (n * math.sqrt(c))


def _field_reason(key, n, c):
    k, p, contact = FIELD_LAW[key]
    const, where = MEASURED_FIELD_CONSTANTS[key]
    grid = f"N = {n:.0f}" + (f", c = 2a/λ = {c:.4g} of the reference" if contact and c < 1.0
                             else (", full contact (c = 1)" if contact else ""))
    if key == "pressure_Linf":
        law, why = f"{k:g} (N c)^-1/2", ("a square-root contact edge leaves a correct solver "
                                         "~(panels across the contact)^-1/2 at the edge panels")
    elif key == "pressure_L2":
        law, why = f"{k:g} N^-1 c^-1/2", ("the edge panels' error ~(N c)^-1/2 over a width "
                                          "~1/N gives a correct solver ~N^-1 c^-1/2")
    else:
        law, why = f"{k:g} N^-3/2", "a correct solver's displacement converges like N^-3/2"
    return (f"{law} with {grid}: {why}; K = 3 × {const:g}, the worst of viscosine's BEM on "
            f"the suite's standard-linear-solid cases at N = 512…8192 ({where})")


def field_constants(point, nodes, case=None):
    """The constants of FIELD_LAW that viscosine's BEM reaches at one operating point on N
    panels: each field norm against the reference over its law with K = 1 (how
    MEASURED_FIELD_CONSTANTS was measured, at N = 512 … 8192 on the suite's SLS cases)."""
    ref = reference_for(point, case)
    res = results_from_fields([viscosine_bem(point, nodes)], ref.shape)[0]
    nm = norms(res, ref)[0]
    n, c = grid_size(res.fields, ref)
    return {k: nm[k] / (field_tolerance(k, n, c) / FIELD_LAW[k][0]) for k in FIELD_LAW
            if k in nm}


@functools.lru_cache(maxsize=64)
def _bem_derived(point_json, nodes, columns):
    """(scalars, patches, own scalars): those derived from viscosine's BEM fields on ``nodes``
    panels, keeping only ``columns``, as from a user's, and the BEM's own (cached: a run asks
    for the same grid more than once); None when the BEM cannot solve there."""
    point = json.loads(point_json)
    if not MIN_POINTS <= nodes <= GRID_MAX_NODES:
        return None
    try:
        with warnings.catch_warnings():  # its coarse-grid caveats are about this very allowance
            warnings.simplefilter("ignore")
            res = _suite.bem_solution(point, int(nodes), base="/")
            if not res.success:
                return None
            x, p, v, g = _suite.bem_fields(res)
    except (RuntimeError, ValueError, ArithmeticError):
        return None
    f = {"x_over_lambda": x, "pressure": p, "displacement": v, "gap": g}
    f = {k: f[k] for k in ("x_over_lambda",) + columns}
    own = {k: v for k, v in res.scalars().items() if k in COMPARED_KEYS and v is not None}
    return (*scalars_from_fields(f, _suite.ProfileShape(point, base="/")), own)


def _bem_errors(reference, nodes, columns):
    key = json.dumps(reference.point, sort_keys=True, default=float)
    got = _bem_derived(key, int(nodes), tuple(columns))
    if got is None:
        return {}
    sc, patches, own = got
    out = {}
    for k in COMPARED_KEYS:  # a correct solver's miss: the BEM's own or its fields', the larger
        ref = reference.scalars.get(k, (None, None))[0]
        got_k = [m for m in (_measure(k, sc.get(k), ref), _measure(k, own.get(k), ref))
                 if m is not None]
        if got_k:
            out[k] = max(got_k)
    edges = _match(reference.patches, patches) if reference.patches else None
    if edges:
        out["edges"] = max(max(abs(a), abs(b)) for a, b in edges)
    return out


def grid_errors(reference, nodes, columns=_suite.FIELD_COLUMNS):
    """e_N of every scalar and of the edges: what viscosine's BEM misses ``reference`` by on
    ``nodes`` panels, the larger of its error at N and half its error at N/2 (an error that
    happens to cross zero at N does not shrink it); for a scalar, the larger of the BEM's own
    value's miss and that of the value derived from its fields.

    Each in the verdict's measure (`_measure`; edges: the worst, x/λ), with the scalars derived
    from the BEM's fields by `scalars_from_fields` keeping only ``columns``, as the verdict
    derives the user's.  A key is missing when the BEM at N does not give it (it cannot solve
    there, or finds another number of patches than the reference).
    """
    at_n = _bem_errors(reference, nodes, columns)
    at_half = _bem_errors(reference, int(nodes) // 2, columns)
    return {k: max(e, 0.5 * at_half[k]) if k in at_half else e for k, e in at_n.items()}


def _grid_tolerances(rtol, reference, nodes, columns):
    """{key: (tolerance, reason)} of the scalars and the edges on a known grid: max(rtol,
    GRID_FACTOR · e_N) (`grid_errors`); the keys where rtol binds share one reason."""
    n = int(round(nodes))
    errs = grid_errors(reference, n, columns)
    keys = COMPARED_KEYS + ("edges",)
    law = f"max({rtol:.1e}, {GRID_FACTOR:g} e_N), N = {n}"
    floor = [errs[k] for k in keys if k in errs and GRID_FACTOR * errs[k] <= rtol]
    out = {}
    for k in keys:
        e = errs.get(k)
        if e is None and n > GRID_MAX_NODES:
            out[k] = (rtol, f"the default {rtol:.1e}: N = {n} is above the {GRID_MAX_NODES} "
                            "panels on which viscosine's BEM measures the grid's error")
        elif e is None:
            out[k] = (rtol, f"the default {rtol:.1e}: viscosine's BEM on N = {n} panels does not "
                            "give this quantity to measure the grid's error by")
        elif GRID_FACTOR * e > rtol:
            out[k] = (GRID_FACTOR * e, f"{law}: e_N = {e:.1e} is viscosine's BEM's error on this "
                                       "grid (the larger of its error at N and half that at "
                                       "N/2), a correct solver's discretisation error here")
        else:
            out[k] = (rtol, f"{law}: {rtol:.1e} binds, viscosine's BEM errs by e_N ≤ "
                            f"{max(floor):.1e} on this grid")
    return out


def tolerances(rtol=DEFAULT_RTOL, tol=None, fields=None, reference=None, rtol_given=None,
               nodes=None):
    """The tolerance of every quantity and why: {key: (tolerance, reason)}.

    Scalars and the contact edges: ``rtol`` when it was asked for; else, on a known grid (that
    of ``fields``, else ``nodes``) and with a ``reference``, max(rtol, GRID_FACTOR · e_N)
    (`grid_errors`), and ``rtol`` without a grid.  Field norms: `field_tolerance` on the grid of
    ``fields`` against ``reference`` (FIELD_LAW), or ``rtol`` without fields.  ``tol``
    overrides any of them.  ``rtol_given``: whether ``rtol`` was asked for (else it is the
    default).
    """
    if rtol_given is None:
        rtol_given = rtol != DEFAULT_RTOL
    src = (f"--rtol {rtol:.1e}" if rtol_given else f"the default --rtol {rtol:.1e}")
    grid = "" if rtol_given else ": the grid is not known (no fields, no nodes)"
    out = {}
    for k in COMPARED_KEYS:
        out[k] = (rtol, f"{src} (relative for μ, τ̃f, Δ/h, s/h, p̃∞, 2a/λ; absolute in "
                        f"radians for ka, ke, kê){grid}")
    out["edges"] = (rtol, f"{src} (absolute, in x/λ){grid}")
    n = c = None
    if fields is not None and reference is not None:
        n, c = grid_size(fields, reference)
    if not rtol_given and reference is not None and (n or nodes):
        cols = [k for k in _suite.FIELD_COLUMNS if fields is None or k in fields]
        out.update(_grid_tolerances(rtol, reference, n or nodes, cols))
    for k in FIELD_LAW:
        if n is None:
            out[k] = (rtol, src)
        else:
            out[k] = (field_tolerance(k, n, c), _field_reason(k, n, c))
    for k, v in (tol or {}).items():
        out[k] = (v, f"--tol {k}={v:g}")
    return out


def derivation_floor(result: Result, reference: Reference):
    """What the derivation of scalars from fields costs on the result's grid.

    The same derivation (:func:`scalars_from_fields`) applied to the reference's own fields
    sampled on the result's grid (with the columns the result has), measured against the
    reference's scalars and edges.  A result whose fields are the reference's own samples differs
    by exactly this much; the verdict allows it on top of the tolerance.
    """
    if result.fields is None:
        return {}
    x = result.fields["x_over_lambda"]
    ref, _ = reference.fields(x)
    f = {"x_over_lambda": x, **{k: ref[k] for k in ("pressure", "displacement", "gap")
                                 if k in result.fields}}
    if WIDTH in result.fields:  # the same cells
        f[WIDTH] = result.fields[WIDTH]
    sc, patches = scalars_from_fields(f, reference.shape)
    out = {}
    for k in COMPARED_KEYS:
        if k in sc and k in reference.scalars and result.source == "fields":
            out[k] = _measure(k, sc[k], reference.scalars[k][0])
    edges = _match(reference.patches, patches) if reference.patches else None
    if edges:
        out["edges"] = max(max(abs(a), abs(b)) for a, b in edges)
    return out


def _points(result, reference):
    """N of a result: `grid_size` of its fields, else its ``nodes`` (None when not known)."""
    return grid_size(result.fields, reference)[0] if result.fields is not None else result.nodes


def position_floor(result: Result, reference: Reference):
    """The grid's resolution of the positions: {key: floor in the verdict's measure}.

    POSITION_PANELS of a spacing per contact edge on the result's grid (`grid_size` of its
    fields, else its ``nodes``): the edges POSITION_PANELS/N (x/λ), ka and ke 2π POSITION_PANELS/N
    (both edges off), 2a/λ 2 P POSITION_PANELS/N over the reference's 2a/λ (P patches).  Empty
    when N is not known or the reference has no patches (full contact).
    """
    n = _points(result, reference)
    if not n or not reference.patches:
        return {}
    d = POSITION_PANELS / n
    out = {"edges": d}
    c = reference.scalars.get("contact_fraction", (None, None))[0]
    if c:
        out["contact_fraction"] = 2.0 * len(reference.patches) * d / c
    if len(reference.patches) == 1:
        out["ka"] = out["ke"] = 2.0 * math.pi * d
    return out


def _floor_lines(rows, n):
    """One line per kind of floor that some row shown carries: the position floor (its values)
    and the derivation floor."""
    lines = []
    pos = [r for r in rows if r.get("floor_kind") == "position"]
    if pos:
        vals = ", ".join(f"{r['label']} {r['derivation_floor']:.1e}" for r in pos)
        lines.append(f"{', '.join(r['label'] for r in pos)}: + {POSITION_PANELS:g} spacing per "
                     f"edge on N = {n:.0f} ({vals}): a correct solver's edges err by up to ~0.05 "
                     "spacing, with where each edge falls in its cell, which e_N (one solver) "
                     "does not sample")
    der = [r["label"] for r in rows if r.get("floor_kind") == "derivation"]
    if der:
        lines.append(f"{', '.join(der)}: + what the same derivation from fields errs by on the "
                     "reference's own fields sampled on this grid (each in the report)")
    return lines


def evaluate(results, reference: Reference, rtol=DEFAULT_RTOL, tol=None, rtol_given=None,
             si=False):
    """Verdicts of the finest result, and the convergence study of all of them.

    A quantity passes when its difference from the reference is at most its tolerance
    (`tolerances`: for the scalars and the edges max(rtol, GRID_FACTOR · e_N) on the finest
    result's grid, or ``rtol`` when that grid is not known or ``rtol`` was asked for; the grid's
    FIELD_LAW for the field norms; ``tol`` for any) plus its floor: the larger of, for ka, ke,
    2a/λ and the edges on a known grid, the grid's resolution of a position (`position_floor`)
    and, for a quantity derived from fields, the derivation floor on the same grid
    (:func:`derivation_floor`).

    Returns
    -------
    dict
        ``verdict`` ("PASS"/"FAIL"), ``quantities`` (rows: key, label, value, reference,
        difference, measure, tolerance, tolerance_reason, derivation_floor (the floor added,
        whichever kind), floor_kind ("position", "derivation" or None without a floor),
        reference_uncertainty, solver_error (the solver's own estimate of its error, in the
        same measure, when it gave one), passed, note), ``tolerances`` (one line per
        tolerance: the quantities, the value and why), ``floors`` (one line per kind of floor
        added, and why), ``edges``, ``failed`` (the labels of
        the failing quantities), ``nodes``, ``convergence`` (or None) and ``diagnosis``
        (common slips recognised in the inputs: `diagnose`; ``si``: the inputs were
        converted from SI units).
    """
    results = sorted(results, key=lambda r: (r.nodes is None, r.nodes or 0))
    best = results[-1]
    tols = tolerances(rtol, tol, best.fields, reference, rtol_given, nodes=best.nodes)
    derived = derivation_floor(best, reference)
    position = position_floor(best, reference)
    floor = {k: (max(derived.get(k, 0.0), position.get(k, 0.0)),
                 "position" if position.get(k, 0.0) > derived.get(k, 0.0) else "derivation")
             for k in set(derived) | set(position)}
    errs = best.errors or {}
    rows = []
    for k in COMPARED_KEYS:
        val = best.scalars.get(k)
        ref, unc = reference.scalars.get(k, (None, None))
        if val is None or ref is None:
            continue
        d = _measure(k, val, ref)
        unc_m = unc / abs(ref) if (k in REL and ref) else unc
        own = errs.get(k)
        if own is not None and k in REL and ref:
            own = own / abs(ref)
        rows.append(_row(k, val, ref, d, "relative" if k in REL else "absolute (rad)",
                         tols[k], unc_m, *floor.get(k, (0.0, None)), solver_error=own))
    nm, nm_unc, _ = norms(best, reference)
    for k, v in nm.items():
        rows.append(_row(k, v, 0.0, v, "relative to max σ" if k.startswith("pressure")
                         else "absolute (over h)", tols[k], nm_unc.get(k), 0.0))
    edges = None
    if best.fields is not None and reference.full_contact is not None:
        if reference.full_contact or best.scalars.get("full_contact"):
            if bool(best.scalars.get("full_contact")) != bool(reference.full_contact):
                rows.append(_row("edges", math.inf, 0.0, math.inf, "absolute (x/λ)",
                                 tols["edges"], None, 0.0,
                                 note=f"full contact: {best.scalars.get('full_contact')}, "
                                      f"reference {reference.full_contact}"))
        else:
            edges = _match(reference.patches, best.patches)
            if edges is None:
                rows.append(_row("edges", math.inf, 0.0, math.inf, "absolute (x/λ)",
                                 tols["edges"], None, 0.0,
                                 note=f"{len(best.patches)} patches, reference "
                                      f"{len(reference.patches)}"))
            else:
                worst = max(max(abs(a), abs(b)) for a, b in edges)
                rows.append(_row("edges", worst, 0.0, worst, "absolute (x/λ)", tols["edges"],
                                 None, *floor.get("edges", (0.0, None))))
    failed = [r["label"] for r in rows if not r["passed"]]
    shown = [r["key"] for r in rows]
    ev = {"verdict": "FAIL" if failed or not rows else "PASS", "quantities": rows,
          "tolerances": _tolerance_lines(tols, shown),
          "floors": _floor_lines(rows, _points(best, reference)), "edges": edges,
          "failed": failed,
          "nodes": best.nodes,
          "convergence": convergence(results, reference) if len(results) > 1 else None}
    ev["diagnosis"] = diagnose(best, reference, ev, si=si)
    return ev


def _tolerance_lines(tols, keys):
    """One line per distinct (tolerance as printed, reason) over the quantities shown, in their
    order (μ and τ̃f share their relative error, to round-off)."""
    groups = {}
    for k in keys:
        v, why = tols[k]
        groups.setdefault((f"{v:.1e}", why), []).append(LABELS[k])
    return [f"{', '.join(labels)}: {v}, {why}" for (v, why), labels in groups.items()]


def _row(key, value, ref, diff, measure, tol, ref_unc, floor, floor_kind=None, note="",
         solver_error=None):
    """One verdict row.  ``floor``: added to the tolerance; ``floor_kind``: "position" (the
    grid's resolution of a position, `position_floor`) or else the derivation floor."""
    tol, reason = tol
    floor = floor or 0.0
    position = floor_kind == "position"
    ok_diff = diff is not None and math.isfinite(diff)
    passed = bool(ok_diff and diff <= tol + floor)
    if not note:
        if floor > 0.0 and ok_diff and tol < diff <= tol + floor:
            note = ("the grid limits this check: the difference is within "
                    + (f"{POSITION_PANELS:g} of a spacing per edge ({floor:.1e})" if position else
                       f"what the same derivation errs by on the reference's own fields on this "
                       f"grid ({floor:.1e})"))
        elif floor > tol and ok_diff and diff > tol + floor:
            note = ("not explained by the grid: " + (
                f"it resolves a position to {floor:.1e}" if position else
                f"the derivation on this grid errs by only {floor:.1e}"))
        elif ref_unc is not None and math.isfinite(ref_unc) and ref_unc > 0.1 * tol:
            note = "the reference's uncertainty exceeds a tenth of the tolerance"
        if solver_error is not None and solver_error > tol:
            note = "; ".join(filter(None, [note, f"the solver's own error estimate "
                                                 f"{solver_error:.1e} exceeds the tolerance"]))
    return {"key": key, "label": LABELS[key], "value": value, "reference": ref,
            "difference": diff, "measure": measure, "tolerance": tol, "tolerance_reason": reason,
            "derivation_floor": floor, "floor_kind": floor_kind if floor > 0.0 else None,
            "reference_uncertainty": ref_unc,
            "solver_error": solver_error, "passed": passed, "note": note}


#: a value within this fraction of minus the reference is a mirrored sign
MIRRORED = 0.05
#: a field slip (mirrored x, a one-panel offset) is reported when undoing it shrinks σ's L2
#: difference below this fraction of what it was
SLIP_GAIN = 0.3


def _pressure_l2(grid, p, ref_p):
    pm = float(np.max(np.abs(ref_p)))
    return grid.l2(np.asarray(p, float) - ref_p) / pm if pm > 0 else math.inf


def diagnose(result: Result, reference: Reference, ev=None, si=False):
    """Common slips recognised in a result, each a one-line hint (empty when none is seen).

    - a mirrored sign: μ (or τ̃f) within 5 % of minus the reference (friction counted positive
      when it drives the motion), ke or kê within 5 % of minus the reference's (x mirrored:
      the sliding toward −x, or the leading edge taken at −x);
    - fields mirrored in x: σ(x) agrees with the reference's σ(−x) far better than with σ(x);
    - a one-panel offset (uniform grid): the fields agree with the reference after moving them
      by one panel (np.roll by ±1) far better than before;
    - SI values without ``--units SI``: σ (or the load) two orders of magnitude or more above
      the reference's, or v/h two orders below, the ratio being what E0/(1 − ν²) in Pa or h in
      m would make it.
    ``ev``: the verdict rows (a slip is reported only where a check failed); ``si``: whether
    the inputs were converted from SI.
    """
    out = []
    sc = result.scalars
    failed = {r["key"] for r in (ev or {}).get("quantities", []) if not r["passed"]}

    def ref(k):
        return reference.scalars.get(k, (None, None))[0]

    def flipped(k, floor=0.0):
        v, r = sc.get(k), ref(k)
        return (v is not None and r is not None and abs(r) > floor
                and abs(v + r) <= MIRRORED * abs(r))

    x_mirrored = flipped("ke", 1e-3) or flipped("ke_hat", 1e-3)
    f = result.fields
    grid = _grid(f) if f is not None else None
    ref_f = None
    if f is not None:
        x = np.asarray(f["x_over_lambda"], float)
        ref_f, _ = reference.fields(x)
        base = _pressure_l2(grid, f["pressure"], ref_f["pressure"])
        if base > 0 and failed:
            mirrored_ref, _ = reference.fields(-x)
            mir = _pressure_l2(grid, f["pressure"], mirrored_ref["pressure"])
            if mir < SLIP_GAIN * base:
                x_mirrored = True
                out.append(f"the fields match the reference mirrored in x (σ L2 / max σ "
                           f"{base:.1e} against σ_ref(−x), {mir:.1e}): in viscosine's frame the "
                           "indenter slides toward +x and the leading edge is the +x edge "
                           "(docs/conventions.md, 'Frame and signs')")
            elif grid.uniform:
                best = min((1, -1), key=lambda k: _pressure_l2(
                    grid, np.roll(f["pressure"], k), ref_f["pressure"]))
                rolled = _pressure_l2(grid, np.roll(f["pressure"], best), ref_f["pressure"])
                if rolled < SLIP_GAIN * base:
                    way = "+x" if best > 0 else "−x"
                    out.append(f"the fields match the reference once moved by one panel toward "
                               f"{way} (σ L2 / max σ {base:.1e} → {rolled:.1e}, np.roll by "
                               f"{best:+d}): x_over_lambda is one panel off its values (cell "
                               "edges written for centres, or an index counted from 1?)")
    if flipped("mu") or flipped("tau_f"):
        k = "mu" if flipped("mu") else "tau_f"
        out.append(f"{LABELS[k]} = {sc[k]:.6g} against {ref(k):.6g}: the friction has the "
                   "opposite sign; viscosine counts τf positive when it resists the motion "
                   "(docs/conventions.md, 'Frame and signs')"
                   + ("; here x is mirrored too, which flips it" if x_mirrored else ""))
    if x_mirrored and (flipped("ke", 1e-3) or flipped("ke_hat", 1e-3)):
        k = "ke" if flipped("ke", 1e-3) else "ke_hat"
        out.append(f"{LABELS[k]} = {sc[k]:.6g} against {ref(k):.6g}: x is mirrored; the "
                   "indenter slides toward +x and e, ê are positive toward the leading (+x) "
                   "edge (docs/conventions.md, 'Frame and signs')")
    if not si:
        if f is not None and ref_f is not None:
            pr = float(np.max(np.abs(f["pressure"]))) / max(
                float(np.max(np.abs(ref_f["pressure"]))), 1e-300)
            if pr >= 100.0:
                out.append(f"σ is {pr:.2g} × the reference's: pressures in Pa without --units "
                           f"SI? (then E0/(1 − ν²) ≈ {pr:.2g} Pa; --units SI --E0 --nu "
                           "--amplitude converts them)")
            if "displacement" in f:
                vm = float(np.max(np.abs(ref_f["displacement"])))
                vr = float(np.max(np.abs(f["displacement"]))) / vm if vm > 0 else 1.0
                if 0.0 < vr <= 0.01:
                    out.append(f"v is {vr:.2g} × the reference's: lengths in m without --units "
                               f"SI? (then the amplitude h ≈ {vr:.2g} m)")
        elif sc.get("load") is not None and ref("load"):
            lr = sc["load"] / ref("load")
            if lr >= 100.0:
                out.append(f"the load is {lr:.2g} × the reference's: a mean pressure in Pa? "
                           "(the conventions' load is p∞(1 − ν²)/E0)")
    return out


ORDER_FLOOR = 1e-12  # differences below this are round-off: left out of the order fit


def fit_order(nodes, errors):
    """Order p of err ∝ N^−p: least squares over the finite errors above ORDER_FLOOR (NaN when
    fewer than two remain)."""
    return observed_order(nodes, errors, ORDER_FLOOR)


def convergence(results, reference):
    """Per quantity: values and errors against the reference over N, the order of the error,
    the self-convergence order and Richardson value, and the Richardson value's error."""
    res = [r for r in results if r.nodes is not None]
    nodes = [r.nodes for r in res]
    out = {"nodes": nodes, "quantities": {}}
    norm_rows = [norms(r, reference)[0] for r in res]
    for k in COMPARED_KEYS + NORM_KEYS[:-1]:
        if k in COMPARED_KEYS:
            vals = [r.scalars.get(k) for r in res]
            ref = reference.scalars.get(k, (None, None))[0]
            if ref is None or any(v is None for v in vals):
                continue
            errs = [_measure(k, v, ref) for v in vals]
        else:
            vals = [nr.get(k) for nr in norm_rows]
            if any(v is None for v in vals):
                continue
            errs, ref = vals, 0.0
        q = {"values": vals, "errors": errs, "order_vs_reference": fit_order(nodes, errs)}
        if k in COMPARED_KEYS and len(vals) >= 3 and _doubling(nodes):
            st = _suite.study(nodes, vals, last=min(_suite.LAST, len(vals) - 1))
            q.update(self_order=st["order"], richardson=st["richardson"],
                     richardson_error=_measure(k, st["richardson"], ref)
                     if math.isfinite(st["richardson"]) else None)
        out["quantities"][k] = q
    return out


def _doubling(nodes):
    return all(b == 2 * a for a, b in zip(nodes[:-1], nodes[1:]))


# =========================================================================== report
def _fmt(v, spec=".6g"):
    if v is None:
        return "—"
    if isinstance(v, bool):
        return "yes" if v else "no"
    if isinstance(v, float) and not math.isfinite(v):
        return "inf" if v > 0 else "—"
    return format(v, spec)


def _figures(folder, results, reference, ev, label):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = []
    best = sorted(results, key=lambda r: r.nodes or 0)[-1]
    if best.fields is not None:
        f = best.fields
        x = f["x_over_lambda"]
        order = np.argsort(_suite_wrap(x))
        xs = _suite_wrap(x)[order]
        ref, _ = reference.fields(x)
        rows = 3 if "displacement" in f else 2
        fig, axes = plt.subplots(rows, 1, figsize=(7.5, 2.6 * rows), sharex=True)
        step = max(1, x.size // 128)
        ax = axes[0]
        ax.plot(xs, ref["pressure"][order], "k-", lw=1.0, label=f"reference ({reference.road})")
        ax.plot(xs[::step], f["pressure"][order][::step], "o", ms=3, mfc="none", color="C3",
                label=label)
        ax.set_ylabel("σ(1 − ν²)/E0")
        ax.legend(fontsize=7)
        if "displacement" in f:
            ax = axes[1]
            ax.plot(xs, ref["displacement"][order], "k-", lw=1.0, label="reference")
            ax.plot(xs[::step], f["displacement"][order][::step], "s", ms=2.5, mfc="none",
                    color="C0", label=label)
            ax.set_ylabel("v/h")
            ax.legend(fontsize=7)
        ax = axes[-1]
        pm = float(np.max(np.abs(ref["pressure"])))
        ax.plot(xs, (f["pressure"] - ref["pressure"])[order] / pm, "C3-", lw=0.8,
                label="(σ − σ_ref)/max σ_ref")
        if "displacement" in f:
            ax.plot(xs, (f["displacement"] - ref["displacement"])[order], "C0-", lw=0.8,
                    label="(v − v_ref)/h")
        ax.set_ylabel("difference")
        ax.set_xlabel("x/λ (crest at 0, sliding toward +x)")
        ax.legend(fontsize=7)
        for a in axes:
            a.grid(True, alpha=0.3)
        axes[0].set_title(f"{label}, N = {best.nodes}, against the {reference.road} reference",
                          fontsize=9)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "fields.png"), dpi=100)
        plt.close(fig)
        names.append(("fields.png", f"σ and v of {label} (markers) against the reference (lines), "
                                    "and their difference"))
    conv = ev["convergence"]
    if conv and conv["quantities"]:
        fig, ax = plt.subplots(figsize=(7.0, 4.6))
        n = np.array(conv["nodes"], float)
        colours = plt.cm.tab20(np.linspace(0.0, 1.0, 20))
        for i, (k, q) in enumerate(conv["quantities"].items()):
            e = np.array([np.nan if v is None else v for v in q["errors"]], float)
            if not np.any(e > ORDER_FLOOR):
                continue  # round-off only (e.g. a load that the solver imposes exactly)
            ax.loglog(n, e, "os^dv<>ph*"[i % 10] + "-", ms=4, mfc="none",
                      color=colours[(3 * i) % 20],
                      label=f"{LABELS[k]}: p = {_fmt(q['order_vs_reference'], '.2f')}")
        ax.set_xlabel("N (resolution of the solver under test)")
        ax.set_ylabel("difference from the reference")
        ax.set_title(f"Convergence of {label} against the {reference.road} reference", fontsize=9)
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=6, ncol=2)
        fig.tight_layout()
        fig.savefig(os.path.join(folder, "convergence.png"), dpi=100)
        plt.close(fig)
        names.append(("convergence.png", f"Differences of {label} from the reference against N, "
                                         "with the fitted orders p"))
    return names


def _material_figure(folder, point):
    """E′, E″ and tan δ of the operating point's Prony material, its sliding frequency marked."""
    from . import _figures
    j0, terms = _figures.prony_numbers(point["prony"])
    speed = float(point["speed"])
    _figures.material_figure(os.path.join(folder, "material.png"), j0, terms, speeds=[speed],
                             speeds_label=f"sliding frequency kV: ωτ_ref = V/V0 = {speed:g}")
    return ("material.png", f"The material of {Path(point['prony']).name}: storage and loss "
                            f"moduli E′, E″ (units E_ref) and tan δ against ωτ_ref; vertical line: "
                            f"the sliding frequency of the operating point, ωτ_ref = V/V0 = "
                            f"{speed:g}")


def _suite_wrap(x):
    x = np.asarray(x, float)
    return x - np.floor(x + 0.5)


def markdown(ev, point, reference, results, label, figures, inputs, case=None):
    """The report as Markdown."""
    from ._html import table
    lines = [f"# viscosine verify: {label}", ""]
    n_fail = len(ev["failed"])
    lines += [f"**Verdict: {ev['verdict']}**" + (
        f" — {n_fail} of {len(ev['quantities'])} quantities outside their tolerance: "
        + ", ".join(ev["failed"]) if n_fail else
        f" — all {len(ev['quantities'])} quantities within their tolerance"), ""]
    op = [[k, _fmt(v) if isinstance(v, (int, float)) else str(v)] for k, v in point.items()
          if v is not None]
    if case:
        op.insert(0, ["suite case", f"{case['name']}: {case['title']}"])
    lines += ["## Operating point", "", table(["input", "value"], op)]
    lines += ["## Reference", "", f"The reference is {reference.description}.", ""]
    lines += [f"## Verdict per quantity (finest result, N = {ev['nodes']})", "",
              "Differences are relative for μ, τ̃f, Δ/h, s/h, p̃∞ and 2a/λ, absolute for ka, ke, "
              "kê (rad) and the contact edges (x/λ); field norms are over the solver's grid, σ "
              "relative to the reference's max σ, v and gap in units of h.", ""]
    own = any(r.get("solver_error") is not None for r in ev["quantities"])
    rows = [[r["label"], _fmt(r["value"], ".10g"), _fmt(r["reference"], ".10g"),
             _fmt(r["difference"], ".2e"), r["measure"], _fmt(r["tolerance"], ".1e"),
             _fmt(r["derivation_floor"], ".1e"), _fmt(r["reference_uncertainty"], ".1e")]
            + ([_fmt(r.get("solver_error"), ".1e")] if own else [])
            + ["PASS" if r["passed"] else "FAIL", r["note"]] for r in ev["quantities"]]
    lines += [table(["quantity", "value", "reference", "difference", "measure", "tolerance",
                     "floor", "reference uncertainty"]
                    + (["solver's estimated error"] if own else []) + ["verdict", "note"], rows),
              "A quantity passes when its difference is at most its tolerance plus its floor: "
              f"for ka, ke, 2a/λ and the edges on a known grid at least {POSITION_PANELS:g} of a "
              "spacing per contact edge (the grid's resolution of a position), and for a scalar "
              "derived from fields at least what the same derivation gives on the reference's "
              "own fields sampled on the solver's grid (the rectangle rule on point samples of a "
              "field with square-root edges errs by O(M^-1.5))."
              + (" The solver's estimated error is its own (here: the size of the next term of "
                 "its extrapolation to dt → 0); it is shown, not added to the tolerance."
                 if own else ""), ""]
    lines += ["### The tolerances, and why", ""] + [f"- {t}" for t in ev["tolerances"]] + [""]
    if ev.get("floors"):
        lines += ["Floors added to the tolerances:", ""] + [f"- {t}" for t in ev["floors"]] + [""]
    if ev.get("diagnosis"):
        lines += ["### Diagnosis", "", "Common slips the inputs look like:", ""] + [
            f"- {d}" for d in ev["diagnosis"]] + [""]
    best = sorted(results, key=lambda r: r.nodes or 0)[-1]
    if best.patches or reference.patches:
        prow = []
        for j, p in enumerate(best.patches, 1):
            prow.append([str(j), _fmt(p["trailing_edge"], ".8f"), _fmt(p["leading_edge"], ".8f"),
                         _fmt(p["load"], ".6g"), _fmt(p["ka"], ".8f"), _fmt(p["ke"], ".8f"),
                         _fmt(p["ke_hat"], ".8f")])
        lines += ["### Contact patches from the solver's fields", "",
                  table(["patch", "trailing edge", "leading edge", "load", "ka", "ke", "kê"], prow)
                  if prow else "(no fields)\n"]
        if ev["edges"]:
            lines += [table(["patch", "trailing edge − reference", "leading edge − reference"],
                            [[str(j), f"{a:.2e}", f"{b:.2e}"]
                             for j, (a, b) in enumerate(ev["edges"], 1)])]
    for name, caption in figures:
        lines += [f"![{caption}]({name})", ""]
    conv = ev["convergence"]
    if conv:
        lines += ["## Convergence study of the solver", "",
                  "Order vs reference: least-squares slope of log |difference| against log N. "
                  "Self-convergence: the order of successive differences and the Richardson "
                  "value (comparisons.suite.study), when N doubles from one result to the next.",
                  ""]
        head = ["quantity"] + [f"N = {n}" for n in conv["nodes"]] + [
            "order vs reference", "self order", "Richardson", "Richardson − reference"]
        rows = []
        for k, q in conv["quantities"].items():
            rows.append([LABELS[k]] + [_fmt(e, ".2e") for e in q["errors"]]
                        + [_fmt(q["order_vs_reference"], ".2f"), _fmt(q.get("self_order"), ".2f"),
                           _fmt(q.get("richardson"), ".10g"),
                           _fmt(q.get("richardson_error"), ".2e")])
        lines += ["Differences from the reference at each N:", "", table(head, rows)]
    lines += ["## How the scalars are computed from fields", "", SCALARS_FROM_FIELDS, ""]
    import viscosine
    prov = [["viscosine", viscosine.__version__], ["python", platform.python_version()],
            ["numpy", np.__version__],
            ["date (UTC)", datetime.datetime.now(datetime.timezone.utc)
             .strftime("%Y-%m-%d %H:%M:%S")]]
    prov += [[k, v] for k, v in inputs.items()]
    lines += ["## Provenance", "", table(["item", "value"], prov)]
    return "\n".join(lines)


SCALARS_FROM_FIELDS = (
    "p̃∞ = mean σ over the grid; τ̃f = −(1/2π) mean σ (ky)′ (eq. 3.1 with ∂v/∂x = ∂y/∂x on the "
    "contact); μ = τ̃f/p̃∞; s/h = mean gap (or, without a gap column, the mean of y/h − v over "
    "the contact points); Δ/h = 1 − s/h; contact points σ > 1e-9 max σ. Each edge by verify's "
    "own fit: σ² inside and gap^(2/3) outside have a simple zero at the edge, and the point "
    "values also carry a discretisation tail that decays away from it (like h/d for a panel "
    "solver, h the spacing, d the distance to the edge), so each side is fitted by least "
    "squares with a cubic plus b h/d over the points ~√M/16 … √M/4 from the edge (d measured "
    "from the zero found so far, iterated) and again over ~√M/16 … √M/2 (a side cut short by "
    "the next edge: its first half, then all of it); the sides whose zero moves by at most "
    "2e-3 h between the two give the edge (averaged; viscosine's BEM places its own edges so). "
    "Without one, plain cubics over ~√M/16 … √M/2, averaged over the sides whose two zeros "
    "agree to 0.1 h (a side that moves more has another scale next to the edge, such as a "
    "relaxation layer), else over both (σ² extrapolated linearly from the last two contact "
    "points when even those are too few). ka = π·width, "
    "ke = 2π(centre − summit), kê = 2π(centroid − summit); in full contact "
    "kê = arg(ŷ_n/σ̂_n)/n in the profile's dominant mode.")


def _jsonable(o):
    if isinstance(o, dict):
        return {k: _jsonable(v) for k, v in o.items()}
    if isinstance(o, (list, tuple)):
        return [_jsonable(v) for v in o]
    if isinstance(o, (np.floating, float)):
        return float(o) if math.isfinite(o) else None
    if isinstance(o, (np.integer,)):
        return int(o)
    if isinstance(o, np.bool_):
        return bool(o)
    return o


def write_report(folder, ev, point, reference, results, label, inputs, case=None,
                 figures=True):
    """Write report.md, report.html (offline) and verdict.json into ``folder``."""
    from . import _html
    os.makedirs(folder, exist_ok=True)
    figs = _figures(folder, results, reference, ev, label) if figures else []
    if figures and point.get("prony"):
        figs.append(_material_figure(folder, point))
    md = markdown(ev, point, reference, results, label, figs, inputs, case)
    write_text(Path(folder) / "report.md", md)
    write_text(Path(folder) / "report.html",
                         _html.render(md, folder, title=f"viscosine verify: {label}"))
    doc = {"verdict": ev["verdict"], "failed": ev["failed"], "label": label, "point": point,
           "case": case["name"] if case else None, "reference": {
               "road": reference.road, "description": reference.description},
           "nodes": ev["nodes"], "quantities": ev["quantities"],
           "tolerances": ev["tolerances"], "floors": ev.get("floors", []),
           "diagnosis": ev["diagnosis"], "edges": ev["edges"],
           "convergence": ev["convergence"], "inputs": inputs,
           "results": [{"nodes": r.nodes, "source": r.source, "scalars": r.scalars,
                        "estimated_errors": r.errors, "patches": r.patches} for r in results]}
    write_text(Path(folder) / "verdict.json",
                         json.dumps(_jsonable(doc), indent=1, ensure_ascii=False,
                                    allow_nan=False) + "\n")


# =========================================================================== Python API
def _point_and_case(case):
    if isinstance(case, str):
        return point_from_case(case)
    if isinstance(case, dict):
        point = {"ratio": None, "hk": None, **case}
        if not point.get("prony") and point["ratio"] is None:
            point["ratio"] = 3.0
        if not point.get("profile") and point["hk"] is None:
            point["hk"] = 1.0
        point = {k: v for k, v in point.items() if v is not None}
        for k in ("profile", "prony"):
            if point.get(k):
                point[k] = str(Path(point[k]).resolve())
        return check_point(point, option_prefix=""), None
    raise TypeError(f"case={case!r}: a suite case name or an operating-point dict")


def assert_agrees(fields_or_scalars, case, rtol=None, tol=None):
    """Assert that a result agrees with the reference of a case (pytest-friendly).

    Parameters
    ----------
    fields_or_scalars : viscosine.Fields, dict, or object with ``.fields``
        Fields over one period (a Fields, or a dict with ``x_over_lambda`` and ``pressure`` and
        optionally ``displacement``, ``gap``), or a dict of scalars keyed like the conventions.
    case : str or dict
        A suite case name, or an operating point (``load`` or ``penetration``, ``speed``, and
        ``ratio``/``hk`` or ``prony``/``profile`` file paths).
    rtol : float, optional
        A flat tolerance of every scalar and of the contact edges (relative or absolute as in
        the module docstring).  By default max(1e-4, 3 e_N) on the fields' grid of N points
        (`grid_errors`), 1e-4 for scalars; the field norms' tolerances follow from the grid
        (FIELD_LAW).
    tol : dict, optional
        Tolerances per quantity (keys of ALL_KEYS), overriding both.

    Raises
    ------
    AssertionError
        Naming each quantity outside its tolerance, both values and the difference.
    """
    point, c = _point_and_case(case)
    ref = reference_for(point, c)
    obj = fields_or_scalars
    is_scalars = isinstance(obj, dict) and "pressure" not in obj and "x_over_lambda" not in obj
    if is_scalars:
        sc = {k: float(v) for k, v in obj.items() if k in COMPARED_KEYS and v is not None}
        results = [Result(obj.get("nodes"), None, sc, [], "solver")]
    else:
        f = _as_fields(obj, "fields_or_scalars", type(obj).__name__)
        results = results_from_fields([f], ref.shape)
    ev = evaluate(results, ref, rtol=DEFAULT_RTOL if rtol is None else rtol, tol=tol,
                  rtol_given=rtol is not None)
    if ev["verdict"] != "PASS":
        bad = [r for r in ev["quantities"] if not r["passed"]]
        lines = [f"{r['label']} ({r['key']}): {_fmt(r['value'], '.10g')} vs reference "
                 f"{_fmt(r['reference'], '.10g')}, difference {_fmt(r['difference'], '.3e')} "
                 f"({r['measure']}) > tolerance {r['tolerance']:.1e}"
                 + (f" [{r['note']}]" if r["note"] else "") for r in bad]
        if not ev["quantities"]:
            lines = ["no quantity could be compared with the reference"]
        raise AssertionError(f"disagrees with the {ref.road} reference of "
                             f"{case if isinstance(case, str) else point}:\n  "
                             + "\n  ".join(lines))
    return ev


# =========================================================================== the command
def _parse_tols(items):
    out = {}
    for it in items:
        if "=" not in it:
            raise _bad("--tol", it, "not NAME=VALUE", ", ".join(ALL_KEYS))
        k, v = it.split("=", 1)
        k = k.strip()
        if k not in ALL_KEYS:
            raise _bad("--tol", it, f"unknown quantity {k!r}", ", ".join(ALL_KEYS))
        try:
            val = float(v)
        except ValueError:
            raise _bad("--tol", it, "the value is not a number", "a tolerance > 0") from None
        if not (math.isfinite(val) and val > 0):
            raise _bad("--tol", it, "out of range", "a finite tolerance > 0")
        out[k] = val
    return out


def _point_from_args(args):
    """(operating point, case, SI scales or None) from the parsed options."""
    given = {k: getattr(args, k) for k in ("load", "penetration", "speed", "ratio", "hk",
                                            "profile", "prony")}
    if args.case:
        extra = [k for k, v in given.items() if v is not None]
        if extra:
            raise _bad(f"--{extra[0]}", given[extra[0]], "given with --case",
                       "--case alone, or the operating-point options without --case")
        point, case = point_from_case(args.case)
        si = None
        if args.units == "SI":
            si = _si_fields(args)
        return point, case, si
    if given["speed"] is None:
        raise _bad("--speed", None, "missing", "--case NAME or --speed with --load/--penetration")
    if args.units == "SI":
        from viscosine._si import scales
        if given["profile"] or given["prony"]:
            raise _bad("--units", "SI", "given with --profile/--prony",
                       "SI operating points for the sinusoid on the standard linear solid")
        need = [k for k in ("E0", "Einf", "tau", "nu", "wavelength", "amplitude")
                if getattr(args, k) is None]
        if need:
            raise _bad(f"--{need[0]}", None, "missing with --units SI",
                       "--E0 --Einf --tau --nu --wavelength --amplitude")
        try:
            sc = scales(E0=args.E0, Einf=args.Einf, tau=args.tau, nu=args.nu,
                        wavelength=args.wavelength, amplitude=args.amplitude, speed=given["speed"],
                        mean_pressure=given["load"], penetration=given["penetration"])
        except ValueError as exc:
            raise BadInput(str(exc)) from None
        point = {"load": sc.load, "penetration": sc.penetration, "speed": sc.speed,
                 "ratio": sc.ratio, "hk": sc.hk}
        point = {k: v for k, v in point.items() if v is not None}
        return check_point(point), None, _si_fields(args)
    point = {k: v for k, v in given.items() if v is not None}
    if not point.get("prony") and point.get("ratio") is None:
        point["ratio"] = 3.0
    if not point.get("profile") and point.get("hk") is None:
        point["hk"] = 1.0
    for k in ("profile", "prony"):
        if point.get(k):
            point[k] = str(Path(point[k]).resolve())
    return check_point(point), None, None


def _si_fields(args):
    need = [k for k in ("E0", "nu", "amplitude") if getattr(args, k) is None]
    if need:
        raise _bad(f"--{need[0]}", None, "missing with --units SI",
                   "--E0, --nu and --amplitude to convert SI fields")
    if not (args.E0 > 0 and -1.0 < args.nu <= 0.5 and args.amplitude > 0):
        raise _bad("--E0", args.E0, "E0, nu or amplitude out of range",
                   "E0 > 0 Pa, nu in (-1, 0.5], amplitude > 0 m")
    return (args.E0, args.nu, args.amplitude)


def _sha(path):
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]


#: verify's one-line messages stay under 400 characters with the command's prefix
MESSAGE_LIMIT = 399 - len("python -m comparisons verify: ")


def _short(text, limit=MESSAGE_LIMIT):
    """The first line of a message within ``limit`` characters: long paths keep their head and
    their end (…), then the 'allowed' part is cut, then the end (an ellipsis says so)."""
    line = str(text).strip().splitlines()[0] if str(text).strip() else ""
    if len(line) > limit:
        line = " ".join(w if len(w) <= 60 else w[:20] + "…" + w[-36:] for w in line.split(" "))
    if len(line) > limit and "; allowed: " in line:
        head, allowed = line.split("; allowed: ", 1)
        room = limit - len(head) - len("; allowed: ")
        line = head if room < 20 else f"{head}; allowed: {allowed[:room - 1].rstrip()}…"
    return line if len(line) <= limit else line[:limit - 1].rstrip() + "…"


def _peer_progress(label, total):
    """A progress callback for the peer's dt studies: one line on standard error per run."""
    state = {"done": 0, "t0": None}

    def report(row):
        if state["t0"] is None:
            state["t0"] = time.monotonic() - row["wall_time"]
        state["done"] += 1
        cells = row["cells_per_step"] / row["steps_per_cell"]
        print(f"verify: {label} N = {row['nodes']}, dt = {cells:g} × T/N: "
              f"{'steady' if row['success'] else 'FAILED'} after {row['periods']} periods, "
              f"{row['wall_time']:.1f} s (run {state['done']} of {total}, "
              f"{time.monotonic() - state['t0']:.0f} s in all)", file=sys.stderr, flush=True)
    return report


def run(args) -> int:
    """`python -m comparisons verify` from its parsed options (``args``: an argparse namespace
    of `comparisons.cli.verify`); prints the verdict; exit status 0 (pass) or 1 (fail).

    Bad input is raised as `comparisons._errors.BadInput` (one line on standard error with the
    command's prefix, exit status 2) and a failure of the solver under test, of the reference or
    of writing the report as `comparisons._errors.Failed` (exit status 1), each within
    `MESSAGE_LIMIT` characters.
    """
    try:
        return _run(args)
    except BadInput as exc:
        raise _errors.BadInput(_short(exc)) from None


def _run(args) -> int:
    tols = _parse_tols(args.tol)
    rtol_given = args.rtol is not None
    rtol = args.rtol if rtol_given else DEFAULT_RTOL
    if not (math.isfinite(rtol) and rtol > 0):
        raise _bad("--rtol", rtol, "out of range", "a finite tolerance > 0")
    point, case, si = _point_from_args(args)
    peer = bool(args.peer)
    nodes = args.nodes or list(DEFAULT_PEER_NODES if peer else DEFAULT_NODES)
    if any(n < MIN_POINTS for n in nodes):
        raise _bad("--nodes", min(nodes), "too small", f"integers >= {MIN_POINTS}")
    if len(set(nodes)) != len(nodes):
        raise _bad("--nodes", " ".join(map(str, nodes)), "repeated", "distinct resolutions")
    if args.nodes and not (args.callable or peer):
        raise _bad("--nodes", " ".join(map(str, args.nodes)), "without --callable or --peer",
                   "--nodes with --callable or --peer (fields files carry their own N)")
    for opt, val in (("--dt", args.dt), ("--dt-cells", args.dt_cells)):
        if val is not None and not peer:
            raise _bad(opt, val if not isinstance(val, list) else " ".join(map(str, val)),
                       "without --peer", f"{opt} with --peer tamaas")
    if args.dt is not None and not (math.isfinite(args.dt) and args.dt > 0):
        raise _bad("--dt", args.dt, "out of range", "a time step > 0 in units of τ")
    cells = None
    if args.dt_cells is not None:
        cells = sorted(args.dt_cells, reverse=True)
        if not all(math.isfinite(c) and c > 0 for c in cells) or len(set(cells)) != len(cells):
            raise _bad("--dt-cells", " ".join(f"{c:g}" for c in args.dt_cells),
                       "not distinct positive numbers",
                       "time steps in cell crossings T/N, e.g. 4 2 1")
    try:  # before any work, as point and sweep check theirs
        check_output_dir("--out", args.out, create=False)
    except _errors.BadInput as exc:
        raise _errors.BadInput(_short(exc)) from None
    inputs = {}
    shape = _suite.ProfileShape(point, base="/")
    if args.fields:
        fl = []
        for path in args.fields:
            f = read_fields_csv(path, "--fields")
            if si:
                f = to_conventions(f, *si)
            fl.append(f)
            inputs[f"--fields {path}"] = f"sha256 {_sha(path)}, {f['x_over_lambda'].size} rows"
        if len({f["x_over_lambda"].size for f in fl}) != len(fl):
            raise _bad("--fields", " ".join(args.fields), "two files with the same number "
                       "of rows", "one file per resolution")
        results = results_from_fields(fl, shape)
        label = args.label or "fields from " + ", ".join(Path(p).name for p in args.fields)
    elif args.scalars:
        recs = read_scalars_jsonl(args.scalars)
        inputs[f"--scalars {args.scalars}"] = f"sha256 {_sha(args.scalars)}"
        results = [Result(r["nodes"], None, r["scalars"], [], "solver") for r in recs]
        label = args.label or f"scalars from {Path(args.scalars).name}"
    else:
        if args.callable:
            fn = load_callable(args.callable)
            label = args.label or args.callable
            call = lambda n: fn(dict(point), n)  # noqa: E731
            opt = "--callable"
            inputs[opt] = args.callable
        else:
            if not _suite.two_roads(point):
                raise _bad("--peer", "tamaas", "with --profile/--prony",
                           "the sinusoid on the standard linear solid")
            if point.get("load") is None:
                raise _bad("--peer", "tamaas", "with --penetration", "--load")
            _tamaas_module()  # bad input now, before any work, if it is missing
            label = args.label or "Tamaas (comparisons.peers.tamaas)"
            runs = len(nodes) * (1 if args.dt is not None else len(cells or DEFAULT_DT_CELLS))
            progress = _peer_progress("Tamaas", runs)
            call = lambda n: peer_tamaas(point, n, args.dt, cells, progress)  # noqa: E731
            opt = "--peer"
            ladder = cells or DEFAULT_DT_CELLS
            inputs[opt] = "tamaas" + (f", dt = {args.dt:g} τ" if args.dt is not None else
                                      ", dt = " + ", ".join(f"{c:g}" for c in ladder) + " × T/N, "
                                      + ("extrapolated to dt → 0" if len(ladder) >= 2 else
                                         "no extrapolation"))
        fl, scs, ers, extrapolated = [], [], [], []
        for n in sorted(nodes):
            try:
                obj = call(n)
            except BadInput:
                raise
            except Exception as exc:  # the solver under test failed: its verdict, not ours
                raise _errors.Failed(_short(f"{label} failed at N = {n}: {type(exc).__name__}: "
                                         f"{exc}")) from None
            if getattr(obj, "success", True) is False:
                raise _errors.Failed(_short(f"{label} did not converge at N = {n}: "
                                         f"{getattr(obj, 'message', '')}"))
            f = _as_fields(obj, opt, label)
            if si:
                f = to_conventions(f, *si)
            fl.append(f)
            sc = getattr(obj, "scalars", None)
            scs.append(sc() if callable(sc) else sc)
            err = getattr(obj, "error", None)
            ers.append({k: float(v) for k, v in err.items() if v is not None}
                       if isinstance(err, dict) else None)
            extrapolated.append(len(getattr(obj, "cells_per_step", ()) or ()) >= 2)
        results = results_from_fields(fl, shape, nodes=sorted(nodes), solver_scalars=scs)
        for r, e, x in zip(results, ers, extrapolated):
            r.errors = e or None
            if x:
                r.source += "; extrapolated to dt → 0"
    if args.units == "SI":
        inputs["units"] = f"SI (E0 = {si[0]:g} Pa, nu = {si[1]:g}, amplitude = {si[2]:g} m)"
    try:
        ref = reference_for(point, case)
        ev = evaluate(results, ref, rtol=rtol, tol=tols, rtol_given=rtol_given,
                      si=si is not None)
    except RuntimeError as exc:
        raise _errors.Failed(_short(exc)) from None
    try:
        write_report(args.out, ev, point, ref, results, label, inputs, case,
                     figures=not args.no_figures)
    except OSError as exc:
        raise _errors.Failed(_short(f"--out {args.out}: cannot write the report "
                                 f"({exc.strerror or exc})")) from None
    for r in ev["quantities"]:
        own = ("" if r.get("solver_error") is None else
               f"; the solver's estimated error {r['solver_error']:.1e}")
        floor = f" + floor {r['derivation_floor']:.1e}" if r.get("floor_kind") else ""
        print(f"{'PASS' if r['passed'] else 'FAIL'} {r['key']} ({r['label']}): "
              f"{_fmt(r['value'], '.10g')} vs {_fmt(r['reference'], '.10g')}, difference "
              f"{_fmt(r['difference'], '.2e')} ({r['measure']}), tolerance "
              f"{r['tolerance']:.1e}{floor}{own}")
    for line in ev["tolerances"]:
        print(f"tolerance: {line}")
    for line in ev.get("floors", []):
        print(f"floor: {line}")
    conv = ev["convergence"]
    if conv:
        print("orders vs reference: " + ", ".join(
            f"{k} {_fmt(q['order_vs_reference'], '.2f')}" for k, q in conv["quantities"].items()))
    for line in ev["diagnosis"]:
        print(f"diagnosis: {line}")
    failed = f" ({', '.join(ev['failed'])})" if ev["failed"] else ""
    summary = f"verify: {ev['verdict']}{failed}; report in {os.path.join(args.out, 'report.md')}"
    print(summary, file=sys.stderr)
    return 0 if ev["verdict"] == "PASS" else 1
