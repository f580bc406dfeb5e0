"""Linear viscoelastic materials in the forms users have, turned into the creep series the
boundary-element road takes.

Users hold a relaxation-form Prony series (a generalised Maxwell model, the material card of a
finite-element code) or a DMA master curve (storage and loss moduli against frequency at a
reference temperature, with a time–temperature shift).  The BEM road takes a creep series
(``bem.Prony(J0, J, tau)``).  This module reads, checks, fits and converts; it solves nothing and
imports neither road.

Conventions
-----------
* Relaxation (Maxwell) form: ``E(t) = E_r + sum_i E_i exp(-t/theta_i)`` for t > 0, relaxation
  times ``theta_i``.  A harmonic strain ``eps0 exp(i w t)`` gives the stress ``E*(w) eps0
  exp(i w t)`` with

      E*(w) = E_r + sum_i E_i i w theta_i / (1 + i w theta_i) = E' + i E'',   E'' >= 0 for w > 0

  (the engineering sign: the strain lags the stress).
* Creep (retardation) form: ``J(t) = J0 - sum_k J_k exp(-t/tau_k)`` (eq. 2.3 of the paper
  generalised), retardation times ``tau_k``, with ``J*(w) = J(0+) + sum_k J_k/(1 + i w tau_k) =
  1/E*(w)``, ``J0 = 1/E_r`` and ``J(0+) = J0 - sum_k J_k = 1/(E_r + sum_i E_i)``.  The BEM road's
  ``jstar(n, speed)`` is this J* at ``w = n * speed`` written with the opposite sign of i (its
  modes run the other way); the series is the same.
* Units: moduli in any one unit, times in any one unit, angular frequencies in rad per that time
  unit.  `Maxwell.creep` takes ``E_ref`` and ``tau_ref`` to return the nondimensional series the
  BEM road expects (compliances in ``1/E_ref``, times in ``tau_ref``).  `Maxwell.in_pascals`
  turns a fit to data whose header named the modulus unit (`PASCALS`) into Pa.
* Files (`viscosine.materials._files`; master curves in `_dmafile`): `read_creep` (a creep
  series, first line ``J0 <value>``; ``bem.read_prony`` reads it), `read_relaxation` (a
  relaxation series, first line ``E_r <value>``), `read_dma` (a master curve),
  `read_shift_table`; `material_form` tells a material file's form (`FORMS`) from its first
  line.

Modules: ``_series`` (the two Prony forms and their interconversion), ``_dma`` (master curves
and their checks), ``_fit`` (the Prony fit and its report), ``_temperature`` (WLF and shift
tables), ``_files`` and ``_dmafile`` (every file format; ``_text`` cuts the text of a table:
separators, decimal commas, comments), ``_units`` (the units a file may state); ``_sweeps`` (raw isotherms at several
temperatures) and ``_superposition`` (their shifts, WLF and master curve), ``_timedata`` (E(t)
and J(t) fitted directly), ``_cards`` (ANSYS, Abaqus, LS-DYNA cards and pyvisco tables),
``_window`` (the measured window written into and read from series files), ``_synthetic`` (data
made from a known series: the test set).

The two forms are exactly interconvertible: with ``p = -s`` (s the Laplace variable) the modulus
``E(p) = E_r - p sum_i E_i theta_i/(1 - p theta_i)`` is decreasing between its poles
``p = 1/theta_i``, so it has one zero below the first pole and one between each pair of
consecutive poles; these zeros are ``1/tau_k`` (the retardation times interlace with the
relaxation times, ``tau_1 > theta_1 > tau_2 > theta_2 > ...``) and ``J_k`` is the residue of
``1/E`` there.  The inverse runs the same routine on the compliance in the variable ``u = 1/p``.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392 (2014): eq. (2.3), the creep
function of the standard linear solid, and eqs (2.7)–(2.8), the modulus at the sliding frequency.
N. W. Tschoegl, The Phenomenological Theory of Linear Viscoelastic Behavior (Springer, 1989),
ch. 4 (interconversion of the Prony forms).  S. W. Park & R. A. Schapery, Int. J. Solids Struct.
36, 1653 (1999) (Prony fits to frequency-domain data).  M. L. Williams, R. F. Landel & J. D. Ferry,
J. Am. Chem. Soc. 77, 3701 (1955) (the WLF shift).
"""
from __future__ import annotations

from ._dma import MERGE_RTOL, MIN_POINTS, MasterCurve
from ._dmafile import read_dma
from ._files import FORMS, material_form, read_creep, read_relaxation, read_shift_table
from ._fit import FitReport, fit_prony
from ._series import Creep, Maxwell
from ._temperature import WLF, ShiftTable
from ._units import PASCALS, POISSON_ALLOWED, poisson
from ._cards import FORMS as CARD_FORMS
from ._cards import card_form, card_nu, read_card, write_card
from ._superposition import Superposition, WLFFit, fit_wlf, shift_table_text, superpose
from ._sweeps import Sweeps, read_sweeps, write_sweeps
from ._synthetic import isotherm_rows, lognormal_series, time_rows
from ._timedata import TimeData, TimeFitReport, fit_time_data, read_time_data
from ._window import MeasuredWindow, read_series, read_window, write_series

__all__ = ["Creep", "FORMS", "FitReport", "MERGE_RTOL", "MIN_POINTS", "MasterCurve", "Maxwell",
           "PASCALS", "POISSON_ALLOWED", "ShiftTable", "WLF", "fit_prony", "material_form", "poisson", "read_creep", "read_dma",
           "read_relaxation", "read_shift_table",
           # raw isotherms, time-domain data, FE cards, the measured window (part 2)
           "CARD_FORMS", "Superposition", "Sweeps", "TimeData", "TimeFitReport", "WLFFit",
           "card_form", "card_nu", "isotherm_rows", "lognormal_series", "time_rows",
           "MeasuredWindow", "read_series",
           "fit_time_data", "fit_wlf", "read_card", "read_sweeps", "read_time_data",
           "read_window", "shift_table_text", "superpose", "write_card", "write_series",
           "write_sweeps"]
