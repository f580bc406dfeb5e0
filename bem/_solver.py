"""The adaptive mesh: `solve`, the public entry of the BEM road.

Nested iteration: the problem is solved on grids N = 512, 1024, ... (:mod:`bem._grid`, each
started from the contact of the one before: the sub-panel contact edges of one grid give the
active set on the next, so that a grid usually needs two or three outer steps) until the error
estimate (:mod:`bem._estimate`) meets ``rtol``; a fixed ``nodes`` solves N/4^l, ..., N/4, N.  A
single narrow patch hands over to a contact window (:mod:`bem._window`).
"""
from __future__ import annotations

import warnings

from viscosine import DEFAULT_RTOL, ViscosineWarning
from viscosine._checks import bad, positive_int, real

from ._accepted import ACCEPTED, MAX_NODES, validate
from ._assemble import build_result
from ._estimate import _estimate, _level_scalars, _met
from ._grid import START_NODES, _Grid, _solve_one
from ._inputs import Prony, Sinusoid
from ._result import CONVERGED, STATUS_TARGET, BemResult
from ._window import _window_refine, _window_wanted


#: the default cap of the adaptive mesh: the memory cap bem.MAX_NODES (2^24 where memory
#: allows, about 2.5 GB and a minute for that grid)
ADAPTIVE_MAX_NODES = MAX_NODES
#: active-set steps on a grid started from a converged coarser one (it usually needs 1 to 5)
MAX_OUTER_AFTER_CONVERGED = 15
#: the largest grid on which a failed solve is retried from the elastic contact
MAX_NODES_RETRY = 2 ** 21
#: up to this grid the retry gets all max_outer active-set steps (from the elastic contact
#: it may need 15-20), above it MAX_OUTER_AFTER_CONVERGED
MAX_NODES_FULL_RETRY = 2 ** 18
#: consecutive failed grids, none converged yet, after which the adaptive mesh gives up
MAX_FAILED_FROM_SCRATCH = 5
#: nested=False tries the full-contact start with at most these active-set steps and Krylov
#: iterations per step, and no wider second try (the paper's point takes 9 steps of at most 7
#: at 2^20; E_inf/E0 = 1000 at V/V0 = 0.01 stagnated at 300 per step for 50 steps) before the
#: elastic start
COLD_DIRECT_STEPS = 20
COLD_DIRECT_INNER = 40


def solve(*, load=None, penetration=None, speed, profile=None, material=None, ratio=None,
          hk=None, nodes=None, rtol=None, max_nodes=None, tol=1e-10, max_outer=50,
          restart=8, max_inner=300, nested=True) -> BemResult:
    """Steady sliding of a rigid periodic indenter on a viscoelastic half-plane (eq. 2.4-2.5).

    The problem is solved on a sequence of grids N = 512, 1024, 2048, ... (each started from
    the contact of the previous one).  The differences between the scalars of the last three
    grids give an a-posteriori estimate of each scalar's discretisation error (see
    `error_estimate` of the result).  With ``nodes=None`` (the default) the sequence stops at
    the first grid whose estimate meets ``rtol``; with ``nodes`` it stops at that grid.

    Parameters
    ----------
    load : float, optional
        Mean pressure ``p (1 - nu^2)/E_ref > 0`` (load control).
    penetration : float, optional
        ``Delta/h`` in (0, 1] (penetration control; the load is an output).  At 1
        the contact is full and the load is not unique: the smallest one (the
        full-contact threshold) is returned.  Give exactly one of the two.
    speed : float
        ``w = V tau_ref k >= 0`` (``V/V0`` of the paper for the standard linear solid).
    profile : Sinusoid, Harmonics or SampledProfile, optional
        The indenter, ``k y`` over one period, crest of the sinusoid at X = 0; default
        ``Sinusoid(hk)``.
    material : Prony, optional
        Creep function (compliances in ``1/E_ref``, times in ``tau_ref``); default the
        standard linear solid with ``ratio``.
    ratio : float, optional
        ``E_inf/E0`` of the default standard linear solid (default 3); not with ``material``.
    hk : float, optional
        Amplitude of the default sinusoid (default 1); not with ``profile``.
    nodes : int, optional
        Panels per period (a power of two is not required): a fixed mesh.  Default: adaptive
        (whose ``result.nodes`` is, after a contact window, the panels per period of the
        window's grid, which may exceed ``max_nodes``; ``result.diagnostics["window"]`` then
        describes the window).
    rtol : float, optional
        Adaptive mesh only: the target of the estimated errors, relative for Delta/h and mu,
        absolute for ka and ke (the contact fraction times pi with several patches).
        Default ``viscosine.DEFAULT_RTOL`` (1e-6).
    max_nodes : int, optional
        Adaptive mesh only: the largest periodic grid (a power of two, up to
        ``bem.MAX_NODES``); default ``bem.MAX_NODES`` (2^24, or less where memory is smaller).
        A contact window has its own bound, 2^21 panels in the window.
        When the target is not met there, the result is not a success and says which
        estimate was reached.
    tol : float
        Bound on the 2-norm of the residual of each Krylov solve, relative to the
        amplitude h k (so on every gap on the contact, in units of h, and on the
        load equation); default 1e-10.
    max_outer : int
        Active-set iterations per grid.
    restart, max_inner : int
        GMRES restart length and iteration cap per linear solve.  A solve that stagnates is
        tried once more with a restart length of 40 (less where its basis would pass 690 MB).
    nested : bool
        With ``nodes``: solve the coarser grids first (their contact starts the next grid, and
        the last three give the error estimate).  False solves ``nodes`` alone, from the
        full-contact pressure clipped at zero (should that fail, once more from the relaxed
        elastic contact, then from the elastic contact with the first harmonic's compliance
        |J*|), with no estimate.  The adaptive
        mesh is always nested.

    Returns
    -------
    BemResult

    Raises
    ------
    ValueError
        On bad input, naming the parameter, its value and what is allowed.

    References
    ----------
    Eq. (2.2)-(2.5) (operator), (3.1) (friction), Appendix B (full contact).
    """
    if (load is None) == (penetration is None):
        raise bad("load", load, "exactly one of load and penetration "
                  f"(got load={load!r}, penetration={penetration!r})")
    if speed is None:
        raise bad("speed", speed, ACCEPTED["speed"][2])
    validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk,
             profile=profile, material=material, nodes=nodes, rtol=rtol, max_nodes=max_nodes)
    # validate has refused everything outside bem.ACCEPTED (and conflicting options)
    if profile is None:
        profile = Sinusoid(1.0 if hk is None else hk)
    if material is None:
        material = Prony.standard_linear_solid(3.0 if ratio is None else ratio)
    speed = float(speed)
    load = None if load is None else float(load)
    penetration = None if penetration is None else float(penetration)
    if nodes is not None:
        nodes = positive_int("nodes", nodes, 8)
        for name, v in (("rtol", rtol), ("max_nodes", max_nodes)):
            if v is not None:
                raise bad(name, v, f"nothing with nodes={nodes}: {name} steers the adaptive "
                          "mesh (nodes=None)")
    else:
        if nested is not True:
            raise bad("nested", nested, "True without nodes (the adaptive mesh is nested)")
        rtol = DEFAULT_RTOL if rtol is None else float(rtol)
        max_nodes = ADAPTIVE_MAX_NODES if max_nodes is None else max(int(max_nodes), START_NODES)
    tol = real("tol", tol, "a finite tolerance in (0, 0.01]", lambda v: 0.0 < v <= 1e-2)
    max_outer = positive_int("max_outer", max_outer, 1)
    restart = positive_int("restart", restart, 1)
    max_inner = positive_int("max_inner", max_inner, 1)

    amp = float(profile.amplitude)
    control, asked = ("load", load) if load is not None else ("penetration", penetration)
    sep = None if penetration is None else amp * (1.0 - penetration)
    if nodes is not None:  # the fixed grid and the halvings below it down to START_NODES
        low = max(8, min(START_NODES // 2, nodes // 4))  # at least N/4 for an estimate
        sizes = [nodes]
        while nested and sizes[-1] % 2 == 0 and sizes[-1] // 2 >= low:
            sizes.append(sizes[-1] // 2)
        sizes.reverse()
    else:
        sizes = []
        n = START_NODES
        while n <= max_nodes:
            sizes.append(n)
            n *= 2
    levels = []      # one entry per grid: (nodes, nit, inner iterations, status)
    scalars = []     # (nodes, dict of scalars) of the converged grids, coarse to fine
    best = None      # (res, grid) of the finest converged grid
    estimate = None
    reason = None
    note = None      # what the estimate carries for unresolved memory lengths
    reached = None
    failed = 0
    good = None      # (res, grid) of the finest converged grid
    window = None    # what the contact window gave, once tried
    harmonic = (profile, Prony(abs(complex(material.jstar([1.0], speed)[0]))))
    for n in sizes:
        grid = _Grid(profile, material, speed, n)
        steps = max_outer if good is None else min(max_outer, MAX_OUTER_AFTER_CONVERGED)
        elastic = (profile, Prony(material.J0))
        # the coarser grid is handed over in a list that _solve_one empties, so that it is
        # freed once it has given its start (memory at large N)
        start, best, last, res = [best], None, None, None
        if nodes is not None:
            good = None  # a fixed mesh answers on its own grid or not at all
        # nested=False: first from the full-contact pressure clipped at zero, with few Krylov
        # steps each (where the operator is far from normal, a stiff material at low speed,
        # they stagnate from there); then, as any grid that fails, from the elastic contact
        direct = not nested and START_NODES < n <= MAX_NODES_RETRY
        if direct:
            res = _solve_one(grid, load, sep, start, tol, min(steps, COLD_DIRECT_STEPS),
                             restart, min(max_inner, COLD_DIRECT_INNER), widen=False)
        else:
            res = _solve_one(grid, load, sep, start, tol, steps, restart, max_inner,
                             elastic=elastic)
        if res["status"] != CONVERGED and (levels[:-1] or direct) and n <= MAX_NODES_RETRY:
            # the coarser contact can be a poor start where the finer grid first resolves a
            # memory length; try once more from the elastic contact on this grid (not on the
            # largest grids, where a failing retry costs minutes)
            retry = _solve_one(grid, load, sep, [None], tol,
                               max_outer if n <= MAX_NODES_FULL_RETRY else steps, restart,
                               max_inner, elastic=elastic)
            if retry["status"] == CONVERGED or good is None:
                res = retry
        if res["status"] != CONVERGED and not levels and harmonic != elastic:
            # the first grid failed from the relaxed contact: try from the elastic contact with
            # the compliance |J*| of the first harmonic at this speed, near the glassy one at
            # high speed (from the relaxed contact a stiff material at high speed shrinks its
            # contact by one panel per active-set step and runs out of steps on every grid).
            # Only there: on a finer grid the coarser contact is the better start
            retry = _solve_one(grid, load, sep, [None], tol, max_outer, restart, max_inner,
                               elastic=harmonic)
            if retry["status"] == CONVERGED:
                res = retry
        levels.append((n, res["nit"], tuple(res["inner"]), res["status"]))
        last = (res, grid)
        # an unconverged grid still gives the next one a better start than none
        best = (res, grid)
        if res["status"] != CONVERGED:
            failed += 1
            if nodes is None and failed >= (2 if scalars else MAX_FAILED_FROM_SCRATCH):
                # two finer grids in a row failed after a converged one (or the first few
                # grids all failed): refining further only costs more, each failed grid
                # running all its active-set steps
                reason = (f"the solve did not converge on N={levels[-failed][0]} … N={n} "
                          f"({res['message']})")
                break
            continue
        failed = 0
        good = (res, grid)
        scalars.append((n, _level_scalars(res, grid, profile, material, speed, amp)))
        estimate, reason, note = _estimate(scalars, material, speed)
        if scalars[-1][1].get("use_law"):  # the estimate chose the first-order memory law
            res["friction"] = res["friction_law"]
        if nodes is None and reason is None and _met(estimate, scalars[-1][1], rtol):
            reached = n
            break
        if nodes is None and window is None and _window_wanted(load, profile, scalars[-1][1]):
            window = _window_refine(res, grid, profile, material, speed, load, rtol, tol,
                                    max_outer, restart, max_inner)
            if window["reached"]:
                wres, wgrid = window["res"], window["grid"]
                answer = build_result(wres, wgrid, profile, material, speed, amp, load,
                                      levels + window["levels"], asked=asked, control=control,
                                      error_estimate=window["estimate"], rtol=rtol,
                                      extra_diagnostics={"window": window["summary"]})
                if answer.success:
                    return _announced(answer)
                window["summary"]["outcome"] = answer.message
            # the window gave no answer: the periodic grids go on as without it
            window["res"] = window["grid"] = None  # memory
    res, grid = last
    if nodes is None and reached is None and good is not None:
        # the finest converged grid, flagged: its estimate did not meet the target
        res, grid = good
        res = dict(res)
        res["status"] = STATUS_TARGET
        shown = "no estimate" if estimate is None else "estimated errors " + ", ".join(
            f"{k}={v:.2e}" for k, v in estimate.items() if v is not None)
        stop = "max_nodes" if levels[-1][0] == max_nodes else f"refinement stopped at N={levels[-1][0]}"
        res["message"] = (f"accuracy target rtol={rtol:g} not reached (finest converged grid "
                          f"N={grid.n}, {stop}): {reason + '; ' if reason else ''}{shown}")
    if nodes is not None and reason is not None:
        estimate = None  # the grids below a fixed one do not resolve the contact: no estimate
    shown_note = "; ".join(t for t in (reason, note) if t)
    extra = {"estimate_note": shown_note} if shown_note else {}
    if window is not None:
        extra["window"] = window["summary"]
    return _announced(build_result(res, grid, profile, material, speed, amp, load, levels,
                                   asked=asked, control=control, error_estimate=estimate,
                                   rtol=rtol if nodes is None else None,
                                   extra_diagnostics=extra or None))


def _announced(result):
    """The result, its warnings raised as `viscosine.ViscosineWarning` (a Python caller sees
    what the command line prints; they stay in ``result.warnings``)."""
    for text in result.warnings:
        warnings.warn(text, ViscosineWarning, stacklevel=3)
    return result

