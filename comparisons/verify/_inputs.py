"""Reading verify's inputs: fields CSV files, JSON lines of scalars, a callable; bad input named.

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
- A callable (``--callable module:function`` or ``path/to/file.py:function``), imported by
  `load_callable`; what it is called with and returns is in `comparisons.verify._results`.

Anything else is `BadInput`: one line naming the option, the value and what is allowed.
"""
from __future__ import annotations

import importlib
import importlib.util
import json
import math
from pathlib import Path

import numpy as np

from viscosine import Fields
from viscosine._fields import UNIFORM_SPACING, WIDTH

from ._quantities import COMPARED_KEYS

MIN_POINTS = 8


class BadInput(ValueError):
    """Bad input to verify: one line naming the option, the value and what is allowed."""


def bad_input(option, value, problem, allowed=None):
    """The BadInput ``option value: problem; allowed: allowed`` (without the value when None)."""
    text = f"{option}: {problem}" if value is None else f"{option} {value}: {problem}"
    if allowed:
        text += f"; allowed: {allowed}"
    return BadInput(text)


FIELDS_ALLOWED = ("a UTF-8 CSV: '#' lines, a header with x_over_lambda,pressure"
                  "[,displacement,gap][,width], one row per point over one period, uniform or "
                  "with cell widths (docs/conventions.md, 'Fields')")


def read_text(path, option, allowed):
    """The text of a file, or BadInput naming the option and the file (missing, empty, binary,
    not UTF-8)."""
    p = Path(path)
    if not p.exists():
        raise bad_input(option, path, "no such file", allowed)
    if p.is_dir():
        raise bad_input(option, path, "is a directory, not a file", allowed)
    try:
        raw = p.read_bytes()
    except OSError as exc:
        raise bad_input(option, path, f"cannot be read ({exc.strerror})", allowed) from None
    if not raw.strip():
        raise bad_input(option, path, "the file is empty", allowed)
    if b"\0" in raw:
        raise bad_input(option, path, "a binary file, not text", allowed)
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise bad_input(option, path, f"not UTF-8 text (byte {exc.start})", allowed) from None


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
        raise bad_input(option, name, "no header line (only comments)", FIELDS_ALLOWED)
    head = [h.strip().lower() for h in lines[0].split(",")]
    if "x_over_lambda" not in head or "pressure" not in head:
        raise bad_input(option, name, f"the columns x_over_lambda and pressure are required "
                        f"(found: {', '.join(head)})", FIELDS_ALLOWED)
    cols = {c: head.index(c) for c in ("x_over_lambda", "pressure", "displacement", "gap", WIDTH)
            if c in head}
    rows = []
    for i, ln in enumerate(lines[1:], 2):
        cells = [c.strip() for c in ln.split(",")]
        if len(cells) < len(head):
            raise bad_input(option, name, f"row {i - 1} has {len(cells)} fields, the header "
                            f"{len(head)}", FIELDS_ALLOWED)
        try:
            rows.append([float(cells[j]) for j in cols.values()])
        except ValueError:
            raise bad_input(option, name, f"row {i - 1}: not a number in {ln.strip()[:60]!r}",
                            FIELDS_ALLOWED) from None
    data = np.array(rows, dtype=float).reshape(-1, len(cols))
    if data.shape[0] < MIN_POINTS:
        raise bad_input(option, name, f"{data.shape[0]} rows", f"at least {MIN_POINTS} points")
    if not np.all(np.isfinite(data)):
        raise bad_input(option, name, "non-finite values (nan or inf)", "finite numbers")
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
            raise bad_input(option, name, f"the width column does not describe the grid ({exc})",
                            "cells consecutive in row order over one period, the first centred on "
                            "its row, each point in its cell") from None
        return
    m = x.size
    dx = np.diff(x)
    spread = float(np.max(np.abs(dx * m - 1.0))) if m > 1 else math.inf
    if abs(x[-1] - x[0] - 1.0) < 1e-9:
        raise bad_input(option, name, "the end point of the period is repeated",
                        "one period, x_last = x_first + 1 − 1/M (drop the last row)")
    if not spread < UNIFORM_SPACING:
        raise bad_input(option, name, f"x_over_lambda is not a uniform grid over one period "
                        f"(spacing × M − 1 reaches {spread:.2e})",
                        "x_j = x_0 + j/M, j = 0..M−1, increasing")


def read_fields_csv(path, option="--fields") -> dict:
    """Read and check one fields CSV file (BadInput on anything the module docstring excludes)."""
    return parse_fields_csv(read_text(path, option, FIELDS_ALLOWED), option, str(path))


SCALARS_ALLOWED = ("a UTF-8 file of JSON objects, one per line, keyed like the conventions "
                   "(mu, tau_f, penetration, ka, ...), with 'nodes' when there are several")


def read_scalars_jsonl(path, option="--scalars") -> list[dict]:
    """The results of a JSON-lines file of scalars, each a dict (``nodes`` kept when given)."""
    text = read_text(path, option, SCALARS_ALLOWED)
    out = []
    for i, ln in enumerate(text.splitlines(), 1):
        if not ln.strip() or ln.lstrip().startswith("#"):
            continue
        try:
            obj = json.loads(ln)
        except ValueError as exc:
            raise bad_input(option, path, f"line {i} is not JSON ({exc.msg})",
                            SCALARS_ALLOWED) from None
        if not isinstance(obj, dict):
            raise bad_input(option, path, f"line {i} is not a JSON object", SCALARS_ALLOWED)
        rec = {}
        for k in COMPARED_KEYS:
            v = obj.get(k)
            if v is None:
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise bad_input(option, path, f"line {i}: {k} = {v!r} is not a finite number",
                                SCALARS_ALLOWED)
            rec[k] = float(v)
        if not rec:
            raise bad_input(option, path, f"line {i} has none of the keys "
                            f"{', '.join(COMPARED_KEYS)}", SCALARS_ALLOWED)
        nodes = obj.get("nodes")
        if nodes is not None and (isinstance(nodes, bool) or not isinstance(nodes, int)
                                  or nodes < 1):
            raise bad_input(option, path, f"line {i}: nodes = {nodes!r}", "a positive integer")
        out.append({"nodes": nodes, "scalars": rec})
    if not out:
        raise bad_input(option, path, "no JSON object in the file", SCALARS_ALLOWED)
    if len(out) > 1 and any(r["nodes"] is None for r in out):
        raise bad_input(option, path, f"{len(out)} results without 'nodes'",
                        "one result, or a 'nodes' key on every line (a convergence study)")
    if len({r["nodes"] for r in out}) != len(out):
        raise bad_input(option, path, "two results with the same 'nodes'",
                        "one result per resolution")
    return out


def load_callable(spec, option="--callable"):
    """The function named by ``module:function`` or ``path/to/file.py:function``."""
    allowed = "module:function or path/to/file.py:function, importable, the function callable"
    if not isinstance(spec, str) or spec.count(":") < 1:
        raise bad_input(option, spec, "not of the form module:function", allowed)
    mod_name, func_name = spec.rsplit(":", 1)
    try:
        if mod_name.endswith(".py"):
            if not Path(mod_name).exists():
                raise bad_input(option, spec, f"no such file {mod_name}", allowed)
            sp = importlib.util.spec_from_file_location(Path(mod_name).stem, mod_name)
            mod = importlib.util.module_from_spec(sp)
            sp.loader.exec_module(mod)
        else:
            mod = importlib.import_module(mod_name)
    except BadInput:
        raise
    except Exception as exc:  # any import failure is bad input, reported in one line
        raise bad_input(option, spec, f"cannot import {mod_name} ({type(exc).__name__}: {exc})",
                        allowed) from None
    fn = getattr(mod, func_name, None)
    if not callable(fn):
        raise bad_input(option, spec, f"{mod_name} has no callable {func_name}", allowed)
    return fn
