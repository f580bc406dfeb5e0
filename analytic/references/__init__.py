"""Independent references: codes that answer the package's problem by other means than the paper's.

None of this is the paper's method (that is the rest of `analytic`: Hunter's transformation, the
elastic arc solution of Appendix A and the closure (2.14)–(2.15), `analytic.solve`).  These codes
are here to judge that road and the BEM from outside, or to be set beside them:

- `fourier` (`fourier_solve`): a dense Fourier-collocation solver of the line contact for any
  Prony-series material, on the half-space or on a layer.  It is the only referee of broad
  spectra (memory layers of many decades) and of layers, where the semi-analytic road has no
  answer.
- `surface` (`surface.solve`): the rigid periodic surface (three-dimensional contact), solved by
  Douglas–Rachford splitting on its own grids with its own measurements and error estimate.
- `persson`: Persson's mean-field theory of rubber friction on a self-affine spectrum.  A
  theory, not a solver of the same equations: it is set beside the surface results, and no
  tolerance judges against it.
- `_layer`: the layer factor S(|n| k d, ν) of one Fourier mode, solved from Navier's equations.
  Plain linear elasticity that the two references above share (the paper's road has no layer);
  `bem` keeps its own closed forms (`bem/_layer.py`), so the factor is still checked across
  codes.

Why they are independent, and the rule that keeps them so: a reference is worth something only
if a mistake in the code it checks cannot reach it.  So no module here imports `bem` or any module
of the paper's road (`analytic.solver`, `hunter`, `_closure`, `_kernels`, `_result`,
`_accepted`, `full_contact`, `westergaard`, `dimensional`), and none of those imports this
package; the references share only `_layer` among themselves, and `viscosine`'s input checks and
plain-record helpers with everyone.  ``tests/test_layout.py`` holds these rules.  The package
front `analytic` re-exports `fourier_solve` and `layer_factor` under their long-standing public
names; nothing else of it reaches in here.

Units as in `analytic`: lengths in 1/k (k = 2π/λ, or 2π/Lx for a surface), pressures in
E0/(1 − ν²) (E_ref for a general series), times in τ; each module states its own in full.
"""
from ._layer import layer_factor
from .fourier import fourier_solve

__all__ = ["fourier_solve", "layer_factor"]
