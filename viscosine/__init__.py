"""viscosine: a numerical verifier for the steady sliding of a rigid periodic indenter over a
linear viscoelastic half-space.

Two independent roads solve the same problem and never import each other:

* :mod:`analytic` — the semi-analytic method of Menga, Putignano, Carbone & Demelio (Proc. R.
  Soc. A 470, 20140392, 2014): Hunter's transformation, the periodic elastic solution and the
  closure for the contact half-width and eccentricity (standard linear solid, sinusoid);
* :mod:`bem` — a periodic boundary-element method on the steady-sliding Green's function (any
  periodic profile, any Prony-series material);

and :mod:`comparisons` checks one against the other (``python -m comparisons``).

This package holds what both roads share without sharing any numerics: the version, the field
container :class:`Fields` and the SI result :class:`SIResult`, and the modules the packages build
on (:mod:`viscosine.checks` the input checks, :mod:`viscosine.protocol` the result protocol,
:mod:`viscosine.fields`, :mod:`viscosine.si` the SI front, :mod:`viscosine.table` sweeps as
tables, :mod:`viscosine.materials` relaxation series and master curves): no package reaches into
another's private modules.  ``viscosine.analytic``,
``viscosine.bem`` and ``viscosine.comparisons`` are thin modules that hand out the three packages'
own objects (``from viscosine.bem import solve``; imported on first use), and
``python -m viscosine`` (or the ``viscosine`` command) is ``python -m comparisons``.
"""
from __future__ import annotations

import importlib

from .fields import Fields
from .si import SIResult


class ViscosineWarning(UserWarning):
    """What a result says about its own accuracy that the caller should see (also kept in the
    result's ``warnings`` and in every JSON record): for example a memory layer under a panel,
    whose edges then carry an error of the order of the layer."""

__version__ = "0.3.0"

#: the accuracy the adaptive BEM aims at by default (``bem.solve(rtol=None)``, the command line
#: without --rtol): every estimated error of mu, Delta/h, ka, ke below it.  Here, not in bem, so
#: that the command line reads the one value without importing the solver
DEFAULT_RTOL = 1e-6
#: the default accuracy target of a surface (three-dimensional contact): every estimated error
#: of mu, Delta/h_ref (relative) and the contact fraction (absolute) below it (docs/surfaces.md)
SURFACE_RTOL = 1e-3

_LAZY = {"analytic", "bem", "comparisons"}


def __getattr__(name):  # the roads are imported only when asked for
    if name in _LAZY:
        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module 'viscosine' has no attribute {name!r}")


__all__ = ["DEFAULT_RTOL", "SURFACE_RTOL", "Fields", "SIResult", "ViscosineWarning", "__version__", "analytic", "bem", "comparisons"]
