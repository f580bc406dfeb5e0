"""Reading verify's inputs: fields CSV files, JSON lines of scalars, a callable; bad input named.

- Fields CSV (``--fields``): read by `comparisons.fields.read_fields_csv`, the one reader of
  the format ``point --fields`` writes (described there); with ``--units SI`` in Pa, m, m,
  converted with ``--E0 --nu --amplitude``.  Several files are results at several resolutions
  (N = the number of rows).
- Scalars (``--scalars``): JSON lines, one object per result, keyed like the conventions (``mu``,
  ``tau_f``, ``penetration``, ``separation``, ``load``, ``contact_fraction``, ``ka``, ``ke``,
  ``ke_hat``; conventions units), with ``nodes`` when there are several.
- A callable (``--callable module:function`` or ``path/to/file.py:function``), imported by
  `load_callable`; what it is called with and returns is in `comparisons.verify._results`.

Anything else is `comparisons._errors.BadInput`: one line naming the option, the value and what
is allowed.
"""
from __future__ import annotations

import importlib
import importlib.util
import json
import math
from pathlib import Path

from .._errors import bad_input
from .._io import read_text
from ._quantities import COMPARED_KEYS

#: short: a refusal is one line (the module's docstring and --help say the rest)
SCALARS_ALLOWED = "JSON lines of mu, tau_f, ... (see --help)"


def read_scalars_jsonl(path, option="--scalars", keys=COMPARED_KEYS,
                       allowed=SCALARS_ALLOWED) -> list[dict]:
    """The results of a JSON-lines file of scalars, each a dict of ``keys`` (``nodes`` kept
    when given; a surface case reads its own keys)."""
    text = read_text(option, path, allowed)
    out = []
    for i, ln in enumerate(text.splitlines(), 1):
        if not ln.strip() or ln.lstrip().startswith("#"):
            continue
        try:
            obj = json.loads(ln)
        except ValueError as exc:
            raise bad_input(option, path, f"line {i} is not JSON ({exc.msg})",
                            allowed) from None
        if not isinstance(obj, dict):
            raise bad_input(option, path, f"line {i} is not a JSON object", allowed)
        rec = {}
        for k in keys:
            v = obj.get(k)
            if v is None:
                continue
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise bad_input(option, path, f"line {i}: {k} = {v!r} is not a finite number",
                                allowed)
            rec[k] = float(v)
        if not rec:
            raise bad_input(option, path, f"line {i} has none of the keys "
                            f"{', '.join(keys)}", allowed)
        nodes = obj.get("nodes")
        if nodes is not None and (isinstance(nodes, bool) or not isinstance(nodes, int)
                                  or nodes < 1):
            raise bad_input(option, path, f"line {i}: nodes = {nodes!r}", "a positive integer")
        out.append({"nodes": nodes, "scalars": rec})
    if not out:
        raise bad_input(option, path, "no JSON object in the file", allowed)
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
    from_file = mod_name.endswith(".py")
    if from_file and not Path(mod_name).exists():
        raise bad_input(option, spec, f"no such file {mod_name}", allowed)
    try:
        if from_file:
            sp = importlib.util.spec_from_file_location(Path(mod_name).stem, mod_name)
            mod = importlib.util.module_from_spec(sp)
            sp.loader.exec_module(mod)
        else:
            mod = importlib.import_module(mod_name)
    except Exception as exc:  # any import failure is bad input, reported in one line
        raise bad_input(option, spec, f"cannot import {mod_name} ({type(exc).__name__}: {exc})",
                        allowed) from None
    fn = getattr(mod, func_name, None)
    if not callable(fn):
        raise bad_input(option, spec, f"{mod_name} has no callable {func_name}", allowed)
    return fn
