"""The boundary-element road under the project's name: ``import viscosine.bem``,
``from viscosine.bem import solve``.  The objects are :mod:`bem`'s own
(``viscosine.bem.solve is bem.solve``); any other public name of :mod:`bem`, its modules
included, is looked up there on first use.  Importing this module does not import
:mod:`analytic` (the two roads stay independent)."""
import bem as _package
from bem import *  # noqa: F401,F403  (bem.__all__: the public API)

from ._forward import forwarder as _forwarder

__all__ = list(_package.__all__)
__getattr__, __dir__ = _forwarder(__name__, _package, __all__)
