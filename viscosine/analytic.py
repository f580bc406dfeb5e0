"""The semi-analytic road under the project's name: ``import viscosine.analytic``,
``from viscosine.analytic import solve``.  The objects are :mod:`analytic`'s own
(``viscosine.analytic.solve is analytic.solve``); any other public name of :mod:`analytic`, its
modules included (``viscosine.analytic.persson``), is looked up there on first use.  Importing
this module does not import :mod:`bem` (the two roads stay independent)."""
import analytic as _package
from analytic import *  # noqa: F401,F403  (analytic.__all__: the public API)

from ._forward import forwarder as _forwarder

__all__ = list(_package.__all__)
__getattr__, __dir__ = _forwarder(__name__, _package, __all__)
