"""The comparison layer under the project's name: ``viscosine.comparisons.suite``,
``from viscosine.comparisons import verify``.  Each name is :mod:`comparisons`' own module,
imported on first use (the package imports nothing up front)."""
import comparisons as _package

from ._forward import forwarder as _forwarder

__all__: list = []
__getattr__, __dir__ = _forwarder(__name__, _package, __all__)
