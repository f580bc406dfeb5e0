"""Third-party contact codes run on the project's problem, as independent witnesses.

A peer is a code nobody on the project wrote, driven to the steady sliding of the rigid sinusoid
over the standard linear solid (an elastic code: to its elastic limit) and converted to the
project's conventions (crest frame, σ(1 − ν²)/E0 positive in compression, v/h into the body from
the deformed mean line, gap/h, μ = τf/p∞).
It shares no numerics with either road; only `comparisons` compares them.

* :mod:`comparisons.peers.tamaas` — Tamaas's transient viscoelastic solver
  (``tamaas.MaxwellViscoelastic``) stepped to steady sliding (``pip install 'viscosine[peers]'``).
* :mod:`comparisons.peers.contactmechanics` — ContactMechanics's elastic layer on a rigid flat
  (bonded) and its Polonsky–Keer contact solver: the layer of `bem` in the elastic limit,
  mode by mode and in contact (``docs/layers.md`` §8; same extra).  Elastic only, so it is not
  a ``verify --peer``.
* :mod:`comparisons.peers.surfaces` — on rigid periodic surfaces (three-dimensional contact):
  Tamaas's and ContactMechanics' elastic Polonsky–Keer solvers on the project's grid, and
  Tamaas's transient viscoelastic solver with the surface moved along a grid axis until the
  sliding is steady, extrapolated in the time step (``docs/surfaces.md``; same extra).

The third-party libraries are imported lazily, inside the functions that need them, so this
package imports without them.
"""
from __future__ import annotations

#: peer name -> module, for the command line (``verify --peer NAME``; steady sliding only)
PEERS = {"tamaas": "comparisons.peers.tamaas"}

__all__ = ["PEERS"]
