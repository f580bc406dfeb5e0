"""A results store in which every finished operating point is its own file.

Each BEM or analytic run is keyed by a hash of its spec (a plain dict of dimensionless numbers).
Scalars go to `<key>.json`, fields (when asked for) to `<key>.npz`; both are written to a
temporary name and renamed, so an interrupted report loses nothing it has finished and
`--resume` never reads a half-written file.
"""
from __future__ import annotations

import hashlib
import json
import os

import numpy as np


def key(spec):
    text = json.dumps(spec, sort_keys=True)
    return hashlib.sha1(text.encode()).hexdigest()[:16]


class Store:
    def __init__(self, folder):
        self.folder = folder
        os.makedirs(folder, exist_ok=True)

    def _path(self, k, ext):
        return os.path.join(self.folder, f"{k}.{ext}")

    def has(self, spec, fields=False):
        """True when the run is stored (with its fields, if asked for and it converged)."""
        k = key(spec)
        if not os.path.exists(self._path(k, "json")):
            return False
        if not fields:
            return True
        with open(self._path(k, "json")) as fh:
            ok = json.load(fh)["ok"]
        return not ok or os.path.exists(self._path(k, "npz"))

    def put(self, spec, out, fields=False):
        k = key(spec)
        if fields and out.get("fields") is not None:
            tmp = self._path(k, "part.npz")
            np.savez(tmp, **{n: np.asarray(v, dtype=float) for n, v in out["fields"].items()})
            os.replace(tmp, self._path(k, "npz"))
        doc = {"spec": spec, "ok": out["ok"], "record": out["record"], "error": out["error"],
               "seconds": out.get("seconds")}
        tmp = self._path(k, "part.json")
        with open(tmp, "w") as fh:
            json.dump(doc, fh)
        os.replace(tmp, self._path(k, "json"))

    def get(self, spec, fields=False):
        k = key(spec)
        with open(self._path(k, "json")) as fh:
            doc = json.load(fh)
        if fields and doc["ok"]:
            with np.load(self._path(k, "npz")) as z:
                doc["fields"] = {n: z[n] for n in z.files}
        return doc
