"""What the thin modules ``viscosine.analytic``, ``viscosine.bem`` and ``viscosine.comparisons``
share: a module-level ``__getattr__`` that answers any other public name of the package they
stand for (its own modules included, imported on first use) with the package's own object."""
from __future__ import annotations

import importlib


def forwarder(alias, package, names):
    """(``__getattr__``, ``__dir__``) for the module ``alias`` standing for ``package``.

    Parameters
    ----------
    alias : str
        The thin module's name (``"viscosine.bem"``), for the error message.
    package : module
        The package it stands for.
    names : list of str
        The names the thin module already holds (its ``__all__``).
    """
    def __getattr__(name):
        if not name.startswith("_"):
            if hasattr(package, name):
                return getattr(package, name)
            target = f"{package.__name__}.{name}"
            try:
                return importlib.import_module(target)
            except ModuleNotFoundError as exc:
                if exc.name != target:  # the module exists but something it needs does not
                    raise
        raise AttributeError(f"module {alias!r} has no attribute {name!r}")

    def __dir__():
        return sorted(set(names) | {n for n in dir(package) if not n.startswith("_")})

    return __getattr__, __dir__
