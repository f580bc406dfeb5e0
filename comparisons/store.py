"""A results store in which every finished operating point is its own file, and no file is trusted.

Each run is keyed by a hash of its spec (a plain dict of dimensionless numbers).  Scalars go to
``<key>.json``, fields (when asked for) to ``<key>.npz``.  Both are written under a temporary name
unique to the writing process (pid and a random suffix, so two runs on one folder never share
one) and renamed into place, so an interrupted run loses nothing it has finished.

Reading back, every file is validated before it is used (`Store.problem`): the JSON must parse,
hold the spec it is filed under, come from this version of viscosine (a record's keys may
mean other things in another), and — for a converged run — a record that passes the last line
of defence (`comparisons.gate`); the .npz must hold the four fields as finite 1-D arrays of one
length (and, for a non-uniform grid, their cell widths ``width``, making one period:
`viscosine.Fields`), or for a surface the grid's x and y and the three fields on it.  A truncated, empty or garbage file is treated as missing: ``has`` notes it
on standard error and the run is done again.
"""
from __future__ import annotations

import hashlib
import json
import os
import sys

import numpy as np

import viscosine
from viscosine import Fields
from viscosine.fields import WIDTH  # the cells of a non-uniform grid (optional)

from . import gate
from . import operating_point as op
from ._errors import StoreError, one_line
from ._io import temporary_name

FIELD_NAMES = ("x_over_lambda", "pressure", "displacement", "gap")
#: a surface's fields: the grid's centres and the fields on it (conventions.md, 'Surfaces')
SURFACE_FIELDS = ("x", "y", "pressure", "displacement", "gap")


def key(spec):
    """The file stem of a spec: a hash of its JSON form."""
    text = json.dumps(op.public(spec), sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


class Store:
    """One folder of results.

    Parameters
    ----------
    folder : str
        Created if missing.
    note : callable, optional
        Receives one line for each stored file found unusable (default: standard error).
    """

    def __init__(self, folder, note=None):
        self.folder = folder
        os.makedirs(folder, exist_ok=True)
        self._note = note or (lambda text: print(text, file=sys.stderr, flush=True))

    def _path(self, k, ext):
        return os.path.join(self.folder, f"{k}.{ext}")

    # ---------------------------------------------------------------- reading
    def _load(self, spec, fields):
        """The stored document (with its fields if asked for); StoreError saying why not."""
        k = key(spec)
        path = self._path(k, "json")
        if not os.path.exists(path):
            raise StoreError("missing")
        try:
            with open(path, encoding="utf-8") as fh:
                doc = json.load(fh)
        except (OSError, UnicodeDecodeError, ValueError) as exc:
            raise StoreError(f"{os.path.basename(path)} is unreadable ({type(exc).__name__}: "
                             f"{one_line(exc)})") from None
        why = _check_doc(doc, spec)
        if why:
            raise StoreError(f"{os.path.basename(path)}: {why}")
        if fields and doc["ok"]:
            npz = self._path(k, "npz")
            try:
                with np.load(npz, allow_pickle=False) as z:
                    doc["fields"] = {n: np.array(z[n]) for n in z.files}
            except Exception as exc:  # any unreadable archive (truncated zip, garbage, missing)
                raise StoreError(f"{os.path.basename(npz)} is unreadable ({type(exc).__name__}: "
                                 f"{one_line(exc)})") from None
            why = (_check_surface_fields(doc["fields"]) if spec.get("surface") is not None
                   else _check_fields(doc["fields"]))
            if why:
                raise StoreError(f"{os.path.basename(npz)}: {why}")
        return doc

    def problem(self, spec, fields=False):
        """None when the run is stored and usable (with its fields, if asked for); else why not."""
        try:
            self._load(spec, fields)
        except StoreError as exc:
            return str(exc)
        return None

    def has(self, spec, fields=False):
        """True when the run is stored and usable; a stored but unusable file is noted."""
        why = self.problem(spec, fields)
        if why is not None and why != "missing":
            self._note(f"store: {why}; running it again")
        return why is None

    def get(self, spec, fields=False):
        """The stored document ``{"spec", "ok", "record", "error", "seconds"[, "fields"]}``.

        Raises
        ------
        StoreError
            When it is missing or cannot be trusted.
        """
        return self._load(spec, fields)

    # ---------------------------------------------------------------- writing
    def put(self, spec, out, fields=False):
        """Store one `runner.run` result (its fields too, when asked for and present)."""
        k = key(spec)
        if fields and out.get("fields") is not None and spec.get("surface") is not None:
            f = out["fields"]  # a surface's: the grid and 2-D fields (conventions.md)
            self._atomic(self._path(k, "npz"), lambda fh: np.savez(
                fh, **{n: np.asarray(getattr(f, n), dtype=float) for n in SURFACE_FIELDS}),
                "wb")
        elif fields and out.get("fields") is not None:
            f = out["fields"]
            data = f.as_dict() if hasattr(f, "as_dict") else f
            names = FIELD_NAMES + ((WIDTH,) if data.get(WIDTH) is not None else ())
            self._atomic(self._path(k, "npz"), lambda fh: np.savez(
                fh, **{n: np.asarray(data[n], dtype=float) for n in names}), "wb")
        doc = {"spec": op.public(spec), "ok": bool(out["ok"]), "record": out["record"],
               "error": out["error"], "seconds": out.get("seconds"),
               "version": viscosine.__version__}
        text = json.dumps(doc, allow_nan=False)
        self._atomic(self._path(k, "json"), lambda fh: fh.write(text), "w")

    @staticmethod
    def _atomic(path, write, mode):
        tmp = temporary_name(path)
        try:
            with open(tmp, mode, **({"encoding": "utf-8"} if "b" not in mode else {})) as fh:
                write(fh)
            os.replace(tmp, path)
        finally:
            if os.path.exists(tmp):
                os.unlink(tmp)


def _check_doc(doc, spec):
    """Why a stored JSON document cannot be used for `spec`, or None."""
    if not isinstance(doc, dict) or not {"spec", "ok", "record", "error"} <= set(doc):
        return "not a stored result (keys spec, ok, record, error expected)"
    if doc["spec"] != op.public(spec):
        return "filed under this spec but holds another one"
    if doc.get("version") != viscosine.__version__:  # keys may mean other things in another
        return f"stored by viscosine {doc.get('version')}, not {viscosine.__version__}"
    if not isinstance(doc["ok"], bool):
        return "ok is not true/false"
    if doc["ok"]:
        check = gate.check_surface_record if spec.get("surface") is not None else \
            gate.check_record
        why = check(doc["record"], spec)
        if why:
            return why
    elif not isinstance(doc["error"], str):
        return "a failed run without its error message"
    return None


def _check_fields(fields):
    if set(fields) - {WIDTH} != set(FIELD_NAMES):
        return f"fields {sorted(fields)} instead of {list(FIELD_NAMES)} (and optionally {WIDTH})"
    arrays = [fields[n] for n in sorted(fields)]
    if any(a.ndim != 1 for a in arrays) or len({a.size for a in arrays}) != 1 or arrays[0].size == 0:
        return "fields are not 1-D arrays of one length"
    if not all(np.issubdtype(a.dtype, np.floating) and np.all(np.isfinite(a)) for a in arrays):
        return "fields are not finite floats"
    if WIDTH in fields:
        try:
            Fields.from_columns(fields)
        except ValueError as exc:
            return f"the cells of the fields do not make one period ({exc})"
    return None


def _check_surface_fields(fields):
    if set(fields) != set(SURFACE_FIELDS):
        return f"fields {sorted(fields)} instead of {list(SURFACE_FIELDS)}"
    x, y = fields["x"], fields["y"]
    shape = (x.size, y.size)
    if x.ndim != 1 or y.ndim != 1 or x.size == 0 or y.size == 0:
        return "the grid's x and y are not 1-D arrays"
    if any(fields[n].shape != shape for n in ("pressure", "displacement", "gap")):
        return f"fields are not arrays of the grid's shape {shape}"
    if not all(np.issubdtype(a.dtype, np.floating) and np.all(np.isfinite(a))
               for a in fields.values()):
        return "fields are not finite floats"
    return None
