"""The a-posteriori error estimate of the adaptive mesh: the scalars of each converged grid,
their differences over the last three or four grids, and the bound on what the grids cannot see
(memory lengths under a few panels)."""
from __future__ import annotations

import math

import numpy as np

from . import _assemble, _edges
from ._assemble import _window_friction
from ._edges import (ROUNDOFF, _full_patch, _patches, counted_contact, edge_lag_reach, edge_lags,
                     fit_panels)
from ._influence import collocation_shifts
from ._layer import MIN_LAYER_PANELS


#: the error estimate is this factor times the first-order bound of the last differences
ESTIMATE_SAFETY = 1.5
#: consecutive grids an estimate uses at most: N, N/2, N/4, N/8
ESTIMATE_GRIDS = 4
#: a patch narrower than this many panels on the coarsest grid of an estimate is not resolved
MIN_PATCH_PANELS = 8
#: a Prony term's memory length w tau_i/(2 pi) (in wavelengths) is resolved from this many panels
MIN_MEMORY_PANELS = 4.0
#: what the edge fits' memory-lag correction (`edge_lags`) may leave of a term's first-order
#: edge shift, in the estimate's bound, on LAG_RESIDUAL_PANELS panels; it falls like
#: 1/sqrt(panels) beyond (the fits reach sqrt(panels)/16 panels out)
LAG_RESIDUAL = 0.1
LAG_RESIDUAL_PANELS = 4096
#: what the grids leave of the first-order edge shift of a memory of a panel or more that the
#: edge fits do not correct, besides its collocation shift's part
PANEL_MEMORY_RESIDUAL = 0.03
#: the remainder of the first-order memory law bounded by this times L_eff/a (measured at most
#: 0.84 L/a on the standard linear solid, `_assemble._lag_friction`)
LAG_LAW_SAFETY = 1.5
#: a partial contact whose deepest gap is below this many times the validity gate's round-off
#: (1e-12 h) gets no estimate: just below the full-contact load (3e-8 below p_FC) gaps of
#: 8e-12 h and 3e-13 h gave ka 1e-6 and 3.5e-5 off, the grids agreeing to 1e-7; at 9e-8 below,
#: 2.5e-11 h, the answers lay within their estimates
MIN_GAP_DEPTH = 20.0
#: keys of the error estimate: relative for these (the grids' differences over |q_N|), absolute
#: for ka, ke, ke_hat
RELATIVE_KEYS = ("penetration", "tau_f", "mu", "load")
#: ... and relative too, but over |q_N| only after the unresolved memory's edge shift is added
#: to its absolute bound (the shift moves the edges, hence the contact's width)
AREA_KEY = "contact_fraction"
ESTIMATE_KEYS = ("contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu")
#: ... and under penetration control, where the load is an output, this one too
LOAD_KEY = "load"


def _level_scalars(res, grid, profile, material, speed, amp):
    """The scalars of one converged grid (for the estimate): plain floats, None where null."""
    sigma = res["sigma"]
    active = res["active"]
    if grid.window:
        tau_f = _window_friction(sigma, grid, material, speed)
        mean_p = float(sigma.sum()) / grid.nodes
        res["friction"] = (tau_f, None)  # build_result's, should this grid be the answer
    else:
        spectra = _assemble._spectra(sigma, grid.y)  # the friction's, and the law's below
        res["friction"] = _assemble._friction(sigma, grid.y, material, speed, spectra,
                                              grid.layer)
        tau_f = res["friction"][0]
        mean_p = float(sigma.mean())
    out = {"pfc": res.get("pfc"), "load": mean_p,
           "penetration": (amp - grid.s_offset - float(res["s"])) / amp, "tau_f": tau_f,
           "mu": tau_f / mean_p if mean_p > 0 else math.nan,
           # the gaps' round-off that the validity gate allows, over h (ROUNDOFF of the scale)
           "gap_roundoff": ROUNDOFF * (grid.scale / amp),
           "panels": grid.n}
    if active.all():
        p = _full_patch(sigma, grid.y, profile, mean_p)
        out.update(contact_fraction=1.0, ka=math.pi, ke=None, ke_hat=p.ke_hat, npatch=1,
                   min_panels=grid.n)
        return out
    # round-off slivers (a negligible share of the load across gaps at the validity gate's
    # round-off) are not counted as patches: `counted_contact`
    counted = counted_contact(sigma, res["gap"], active, grid.scale)
    # the edge fits' windows: the period's panels, or after the gap step a narrow gap's
    # (`fit_panels`)
    fit = fit_panels(counted) if res.get("exact_gaps") else grid.n
    patches = _patches(sigma, res["gap"], counted, grid.x, grid.h, profile, grid.y, grid.window,
                       edge_lags(material, speed, grid.h, fit), fit)
    res["patches"] = patches  # the next grid's start needs their edges too
    out["panels"] = fit  # what the edge fits see (`_unresolved_memory`)
    if not grid.window and _lag_law_applies(material, speed, grid):
        # every memory far under the fitted distances: the dissipation form converges like
        # 1/N there, the first-order memory law like 1/N^2 plus its remainder (in the estimate)
        tau_law, l_eff = _assemble._lag_friction(sigma, grid.y, material, speed, spectra)
        res["friction_law"] = (tau_law, res["friction"][1])
        half = 0.5 * min(p.width for p in patches)
        out.update(tau_f_law=tau_law, mu_law=tau_law / mean_p if mean_p > 0 else math.nan,
                   lag_law=LAG_LAW_SAFETY * l_eff / half)
    frac = float(sum(p.width for p in patches))
    # the deepest gap, in units of the validity gate's round-off (`MIN_GAP_DEPTH`), where the
    # gaps are differences C sigma - y + s; the gap step's are solved for (exact to their own
    # precision, `_grid._gap_solve`)
    out["gap_depth"] = None if res.get("exact_gaps") else \
        float(np.max(res["gap"])) / (ROUNDOFF * grid.scale)
    out.update(contact_fraction=frac, npatch=len(patches),
               min_panels=min(p.panels for p in patches),
               min_gap_panels=_narrowest_gap(counted) if len(patches) == 1 else None)
    if len(patches) == 1:
        p = patches[0]
        out.update(ka=p.ka, ke=p.ke, ke_hat=p.ke_hat)
    else:
        out.update(ka=None, ke=None, ke_hat=None)
    return out


def _narrowest_gap(counted):
    """Panels of the narrowest run of free panels between the counted patches (one patch: the
    period less it; checked like a patch's width, `MIN_PATCH_PANELS`)."""
    free = _edges._runs(~counted)
    return min(length for _, length in free) if free else counted.size


def _lag_law_applies(material, speed, grid):
    """Whether every Prony term with a memory has it at most the edge fits' reach on this grid
    (`edge_lag_reach`: far under the distances the edges are fitted over), where the friction
    is taken from the first-order memory law (`_assemble._lag_friction`)."""
    reach = edge_lag_reach(grid.h, grid.n)
    lengths = [speed * t / (2.0 * math.pi) for j, t in material.terms if j > 0.0]
    return bool(lengths) and speed > 0.0 and max(lengths) <= reach


def _unresolved_memory(material, speed, nodes, panels=None):
    """Bound on the contact-edge error of the Prony terms whose memory length
    ``L_i = w tau_i/(2 pi)`` (wavelengths) spans fewer than MIN_MEMORY_PANELS panels of `nodes`
    (``panels``: the panels the edge fits see, when not a period's, as for `edge_lags`).

    A grid that does not resolve ``L_i`` misses the inner layer of the term at the contact
    edges, whose effect on the edges is first order in ``L_i``: ``S_i = pi L_i J_i/(J_i +
    J_loc)`` on ka and ke, with ``J_loc = J(0+) + sum of J_j over the terms of shorter memory``
    (what acts at once on the scale ``L_i``).  For the standard linear solid this is ``(1 -
    1/rho) w/2``, the first-order retreat of the trailing edge at low speed.  The bound counts
    a share of each ``S_i``:

    - a memory the edge fits correct (`edge_lags`, far below the fitted distances):
      LAG_RESIDUAL on LAG_RESIDUAL_PANELS panels, falling like 1/sqrt(panels) beyond;
    - any other: all of it under a panel, PANEL_MEMORY_RESIDUAL from one panel;
    - plus ``delta/L_i`` for a term collocated ``delta`` downstream against the sawtooth
      (`_influence.collocation_shifts`): the shift moves the term's memory, and the edges with
      it, by ``delta`` (``pi delta J_i/(J_i + J_loc)``).

    Measured on the standard linear solid against the semi-analytic road (E_inf/E0 = 1.5, 3,
    10, 30, 100, 300, 1000; p~ = 0.02 ... 0.4; 4096 ... 262144 panels), the BEM's ka and ke
    less their elastic (V = 0) discretisation error, over ``S``: a corrected memory under 0.4
    panel leaves at most 0.041, 0.017, 0.0087 and 0.0044 on 4096, 16384, 65536 and 262144
    panels; an uncorrected one of 0.45 panel up to 1.0, of 0.7 panel 0.012, of 1 ... 3.9
    panels 0.009 unshifted; a shifted one ``delta/L`` to three digits (0.03 ... 0.17).  The
    bound is carried by the estimate; it is not a reason to refine.
    """
    h = 1.0 / nodes
    fitted = nodes if panels is None else panels
    corrected = edge_lag_reach(h, fitted)
    lag_share = LAG_RESIDUAL * min(1.0, math.sqrt(LAG_RESIDUAL_PANELS / fitted))
    lengths = [speed * t / (2.0 * math.pi) for _, t in material.terms]
    shifts = collocation_shifts(h, material.j_plus, material.terms, lengths)
    bound = 0.0
    j_loc = material.j_plus
    for i in sorted(range(len(lengths)), key=lambda i: material.terms[i][1]):
        j, length = material.terms[i][0], lengths[i]
        if j > 0.0 and 0.0 < length < MIN_MEMORY_PANELS * h:
            share = lag_share if length <= corrected else \
                (PANEL_MEMORY_RESIDUAL if length >= h else 1.0)
            share = min(1.0, share + shifts[i] / length)
            bound += share * math.pi * length * j / (j + j_loc)
        j_loc += j
    return bound


def _halvings(scalars: list) -> list:
    """The last (N, scalars) of ``scalars`` (converged grids, coarse to fine) whose N halve in
    turn, N, N/2, ... (at most ESTIMATE_GRIDS), fine to coarse: the grids an estimate rests on.
    A grid missing from the sequence (one that failed) breaks the chain.  The surface BEM's
    estimate rests on the same chain."""
    run = [scalars[-1]]
    for n, sc in reversed(scalars[:-1]):
        if len(run) == ESTIMATE_GRIDS or n * 2 != run[-1][0]:
            break
        run.append((n, sc))
    return run


def _estimate(scalars, material, speed, layer=None, load_given=True):
    """A-posteriori error estimate from the last converged grids N/8 (when there), N/4, N/2, N.

    Each scalar q is assumed to converge at least at first order in 1/N, so the error of q_N is
    bounded by |q_N - q_N/2| and, against accidentally small differences (the edges' position in
    their panels makes the errors oscillate: two grids can agree by chance), by
    |q_N - q_N/2^j|/2^(j-1) and |q_N/2^(j-1) - q_N/2^j|/2^(j-1) for j = 2, 3; the estimate is
    ESTIMATE_SAFETY times the largest (relative to |q_N| for Delta/h, tau_f, mu and the contact
    fraction, whose bound takes the unresolved memory's term before it is made relative; absolute
    for ka, ke and ke_hat).  Delta/h adds ESTIMATE_SAFETY times the validity gate's round-off of a gap (1e-12 h), below which no
    separation is certified (measured: 2.6e-13 h at Delta/h = 4.6e-4, where the grids agreed
    to 7e-14 h).  Returns
    (estimate, reason, note): reason is None when the grids resolve the contact, else why the
    estimate is not trusted yet; note says what the estimate includes for the memory lengths
    the grids do not resolve (None when they resolve them all, or when every grid of the run is
    in full contact: no edges, no inner layers).  On a ``layer`` (a `bem.Layer`) the estimate is
    not trusted (a reason) while its thickness d spans fewer than MIN_LAYER_PANELS panels of
    N/4 in partial contact.  Under penetration control (``load_given`` False) the load p~ is
    an output and gets its estimate like the others (relative; its grids' differences and the
    memory term), not built from those of tau_f and mu.
    """
    if len(scalars) < 3:
        return None, "fewer than three converged grids", None
    run = _halvings(scalars)
    if len(run) < 3:
        return None, "no three consecutive converged grids", None
    counts = {sc["npatch"] for _, sc in run}
    if len(counts) > 1:
        return None, ("the number of contact patches changes with N (" +
                      ", ".join(str(sc["npatch"]) for _, sc in reversed(run)) + ")"), None
    est = {}
    for k in ESTIMATE_KEYS + (() if load_given else (LOAD_KEY,)):
        vals = [sc[k] for _, sc in run]  # fine to coarse
        if any(v is None for v in vals):
            est[k] = None
            continue
        e = ESTIMATE_SAFETY * _first_order_bound(vals)
        if k == "penetration":
            # the validity gate counts gaps within ROUNDOFF of their scale (h; a window's drop)
            # as zero: the separation is not certified below that, whatever the grids agree to
            # (it shows where Delta/h is small)
            e += ESTIMATE_SAFETY * max(sc["gap_roundoff"] for _, sc in run)
        est[k] = _over(e, vals[0]) if k in RELATIVE_KEYS else e
    reason = None
    n0, a = run[min(2, len(run) - 1)]  # N/4: the coarsest grid every estimate uses
    if a["min_panels"] < MIN_PATCH_PANELS:
        reason = f"a contact patch spans {a['min_panels']} panels at N={n0} " \
                 f"(at least {MIN_PATCH_PANELS} are needed)"
    elif (a.get("min_gap_panels") or n0) < MIN_PATCH_PANELS:
        # just below full contact the gap is the narrow part: its edges are fitted on it too
        reason = f"a gap spans {a['min_gap_panels']} panels at N={n0} " \
                 f"(at least {MIN_PATCH_PANELS} are needed)"
    # full contact has no edges, hence no inner layers: a single harmonic per mode, which the
    # exact panel coefficients give to O(1/N^2) whatever the memory lengths (Appendix B)
    full = all(sc["contact_fraction"] == 1.0 for _, sc in run)
    if reason is None and layer is not None and not full:
        # a layer adds the length d, over which the pressure of a thin layer varies at the
        # contact edges: not resolved below MIN_LAYER_PANELS panels at N/4, not estimated
        # (full contact has one harmonic per mode, exact whatever d)
        across = n0 * layer.thickness_over_wavelength
        if across < MIN_LAYER_PANELS:
            reason = (f"the layer's thickness spans {across:.2g} panels at N={n0} (at least "
                      f"{MIN_LAYER_PANELS:g} are needed)")
    if reason is None:
        reason = _transition_unsettled(run)
    depth = run[0][1].get("gap_depth")
    if reason is None and not full and depth is not None and depth < MIN_GAP_DEPTH:
        reason = (f"the deepest gap is {depth:.2g} times the validity gate's round-off at "
                  f"N={run[0][0]} (at least {MIN_GAP_DEPTH:g} are needed: the edges are "
                  "fitted on gaps at round-off)")
    shift = 0.0 if full else _unresolved_memory(material, speed, n0, a.get("panels"))
    note = _choose_friction_form(run, est)
    if shift > 0.0:
        for k in est:
            if est[k] is not None:
                est[k] += ESTIMATE_SAFETY * shift
        memo = (f"a memory length w tau_i/(2 pi) spans fewer than {MIN_MEMORY_PANELS:g} "
                f"panels at N={n0}: its edge shift, up to {shift:.1e}, is in the estimate")
        note = memo if note is None else f"{note}; {memo}"
    est[AREA_KEY] = _over(est[AREA_KEY], run[0][1][AREA_KEY])
    return est, reason, note


def _over(e, value):
    """An absolute error estimate ``e`` made relative to ``value`` (None stays None)."""
    if e is None:
        return None
    scale = abs(value)
    return e / scale if scale > 0 else (0.0 if e == 0 else math.inf)


def _transition_unsettled(run):
    """Why full or partial contact is not settled by the grids (None when it is): the load lies
    within the estimated error of the grids' full-contact load p_FC (ESTIMATE_SAFETY times the
    first-order bound of its last values, as for the scalars).  A grid's p_FC is the minimum of
    its full-contact pressure over the panel centres, off by O(1/N^2) relative (1e-6 at 2048
    panels): 6.9e-8 below p_FC (E_inf/E0 = 2.6, V/V0 = 0.5) the grids 512 ... 2048 were all in
    full contact, and full contact was answered with an estimate of zero."""
    vals = [sc.get("pfc") for _, sc in run]
    if any(v is None for v in vals):
        return None
    spread = ESTIMATE_SAFETY * _first_order_bound(vals)
    load = run[0][1]["load"]
    if abs(vals[0] - load) <= spread:
        return (f"the load is within the estimated error {spread / load:.1e} of the grids' "
                f"full-contact load at N={run[0][0]} (it lies {(vals[0] - load) / load:.1e} "
                "below it)")
    return None


def _choose_friction_form(run, est):
    """Where every grid of the run (fine to coarse) has the first-order memory law too, the
    law's estimate of tau_f and mu (its grids' differences and its remainder); the form with the
    smaller estimate of mu gives the answer (``use_law`` on the finest grid's scalars, and
    ``est`` updated).  Returns the note saying the law was chosen, else None."""
    if not (all("mu_law" in sc for _, sc in run) and est.get("mu") is not None):
        return None
    law = max(sc["lag_law"] for _, sc in run)
    law_est = {}
    for k in ("tau_f", "mu"):
        vals = [sc[k + "_law"] for _, sc in run]
        scale = abs(vals[0])
        bound = _first_order_bound(vals)
        law_est[k] = (ESTIMATE_SAFETY * bound / scale if scale > 0 else math.inf) \
            + ESTIMATE_SAFETY * law
    use = law_est["mu"] < est["mu"]
    run[0][1]["use_law"] = use
    if not use:
        return None
    est.update(law_est)
    return (f"friction from the first-order memory law (every memory far under the fitted "
            f"distances); its remainder, up to {law:.1e} relative, is in the estimate")


def _first_order_bound(vals):
    """The error bound of vals[0] (fine to coarse grids, halving) for at least first-order
    convergence: |q_N - q_N/2| and, against accidentally small differences, |q_N - q_N/2^j| and
    |q_N/2^(j-1) - q_N/2^j| over 2^(j-1) (`_estimate`)."""
    cands = [abs(vals[0] - vals[1])]
    for j in range(2, len(vals)):
        w = 0.5 ** (j - 1)
        cands += [w * abs(vals[0] - vals[j]), w * abs(vals[j - 1] - vals[j])]
    return max(cands)


def _met(estimate, values, rtol):
    """Whether the estimate meets rtol on mu, Delta/h (relative), under penetration control the
    load (relative, where the estimate has it) and ka, ke (absolute; where several patches leave
    ka and ke undefined, the contact fraction's absolute estimate times pi: the sum of the
    patches' ka, on ka's scale).  ``values``: the scalars of the grid the estimate is of."""
    keys = ["mu", "penetration"] + ([LOAD_KEY] if LOAD_KEY in estimate else [])
    keys += ["ka", "ke"] if values["npatch"] == 1 else [AREA_KEY]
    for k in keys:
        e = estimate.get(k)
        if e is None:
            if k == "ke" and values["ke"] is None:  # full contact: no ke
                continue
            return False
        if k == AREA_KEY:  # the estimate is relative: back to absolute, on ka's scale
            e = math.pi * e * abs(values[AREA_KEY])
        if not e <= rtol:
            return False
    return True

