"""Figures: the only part of viscosine that imports matplotlib.

Every figure function takes plain numbers (or a record, a store, a material of `viscosine`) and
draws on an Axes or writes a PNG; none solves anything.  matplotlib is imported on first use, on
the file-only Agg backend, so that importing the comparison layer stays cheap and never opens a
window.

* `paper`: the paper's figures 3–12 with both roads (the report);
* `fields`: σ(x) and v(x) of both roads and their difference (the report);
* `convergence`: the BEM's error against N with its observed orders (the report);
* `peers`: Tamaas's error as its time step is halved (the report);
* `materials`: E′, E″ and tan δ of a Prony series (the report, ``verify``, the suite export)
  and a DMA curve against its Prony fit;
* `mastercurve`: the friction master curve μ(V, T) (``python -m comparisons mastercurve``);
* `sweep`: μ against the speed, one curve per load (``python -m comparisons sweep --plot``);
* `layers`: μ, 2a/λ and p̃FC on a layer of finite thickness, bonded or frictionless (the report).

The report's numbers come from `comparisons.report_numbers`; here they are only drawn.
"""
from __future__ import annotations

import dataclasses
import functools
import hashlib
import json
import os
import types

import numpy as np

#: the PNG text entries of a figure drawn by a `kept_when_unchanged` writer: the digest of its
#: inputs, and what the writer returned (JSON) when that is not the path
INPUTS_KEY = "viscosine inputs"
RETURNED_KEY = "viscosine returned"
_pending = [None]  # the inputs digest of the writer now drawing (`save` writes it)


def pyplot():
    """``matplotlib.pyplot`` on the Agg backend (figures are written to files, never shown)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def save(fig, path_png, returned=None):
    """Write a finished figure to ``path_png`` (tight layout, 110 dpi) and close it; returns the
    path.  Drawn by a `kept_when_unchanged` writer, the PNG holds the digest of the writer's
    inputs and ``returned`` (what the writer returns, when not the path)."""
    meta = {}
    if _pending[0] is not None:
        meta[INPUTS_KEY] = _pending[0]
        if returned is not None:
            meta[RETURNED_KEY] = json.dumps(returned)
    fig.tight_layout()
    fig.savefig(path_png, dpi=110, metadata=meta or None)
    pyplot().close(fig)
    return path_png


def kept_when_unchanged(write):
    """Decorate a figure writer ``write(path_png, *inputs)``: when ``path_png`` is a PNG this
    writer drew from the same inputs (the digest in its text entries: the inputs, the writer,
    the source of this package and matplotlib's version), it is kept as it is and not drawn
    again (a figure costs about a second; ``report --resume`` redraws none of its 22 when no
    run changed).  Inputs the digest cannot read (`_digest`) are always drawn."""
    @functools.wraps(write)
    def writer(path_png, *args, **kwargs):
        try:
            key = _key(write, args, kwargs)
        except TypeError:
            key = None
        if key is not None:
            kept = _kept(path_png, key)
            if kept is not None:
                return path_png if kept[0] is None else kept[0]
        _pending[0] = key
        try:
            return write(path_png, *args, **kwargs)
        finally:
            _pending[0] = None
    return writer


def _kept(path_png, key):
    """``(returned or None,)`` when ``path_png`` is a PNG drawn from inputs of digest ``key``,
    else None (no file, another figure, an unreadable one)."""
    if not os.path.isfile(path_png):
        return None
    try:
        from PIL import Image
        with Image.open(path_png) as im:
            text = dict(getattr(im, "text", {}) or {})
    except Exception:  # noqa: BLE001 - any file that is not such a PNG is drawn again
        return None
    if text.get(INPUTS_KEY) != key:
        return None
    returned = text.get(RETURNED_KEY)
    try:
        return (None if returned is None else json.loads(returned),)
    except ValueError:
        return None


@functools.lru_cache(maxsize=1)
def _source():
    """The bytes of this package's modules and matplotlib's version, digested once."""
    import matplotlib
    h = hashlib.sha256(matplotlib.__version__.encode())
    here = os.path.dirname(os.path.abspath(__file__))
    for name in sorted(os.listdir(here)):
        if name.endswith(".py"):
            with open(os.path.join(here, name), "rb") as fh:
                h.update(name.encode() + b"\0" + fh.read())
    return h.hexdigest()


def _key(write, args, kwargs):
    h = hashlib.sha256(_source().encode())
    _digest(h, (write, args, kwargs))
    return h.hexdigest()


def _digest(h, obj):
    """Feed ``obj`` into the hash ``h``, type by type; TypeError for a type it cannot read."""
    if obj is None or isinstance(obj, (bool, int, float, complex, str, bytes, np.generic)):
        h.update(f"{type(obj).__name__}:{obj!r};".encode())
    elif isinstance(obj, np.ndarray):
        if obj.dtype.hasobject:
            _digest(h, obj.tolist())
        else:
            h.update(f"nd:{obj.dtype.str}:{obj.shape};".encode())
            h.update(np.ascontiguousarray(obj).tobytes())
    elif isinstance(obj, dict):
        h.update(f"dict:{len(obj)};".encode())
        for k in sorted(obj, key=repr):
            _digest(h, k)
            _digest(h, obj[k])
    elif isinstance(obj, (list, tuple)):
        h.update(f"{type(obj).__name__}:{len(obj)};".encode())
        for v in obj:
            _digest(h, v)
    elif dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        h.update(f"dc:{type(obj).__module__}.{type(obj).__qualname__};".encode())
        for f in dataclasses.fields(obj):
            _digest(h, f.name)
            _digest(h, getattr(obj, f.name))
    elif isinstance(obj, types.FunctionType) and obj.__module__.startswith(__name__):
        # a drawing of this package (its globals are in `_source`): its code, defaults, cells
        code = obj.__code__
        h.update(f"fn:{obj.__module__}.{obj.__qualname__};".encode() + code.co_code)
        _digest(h, [c for c in code.co_consts if not isinstance(c, types.CodeType)])
        _digest(h, (obj.__defaults__, obj.__kwdefaults__,
                    [c.cell_contents for c in obj.__closure__ or ()]))
    else:
        raise TypeError(f"cannot digest a {type(obj).__name__}")
