"""The adaptive mesh: `solve`, the public entry of the BEM road (a study over fixed meshes, their
grids solved once, is :mod:`bem._study`'s `solve_meshes`).

Nested iteration: the problem is solved on grids N = 512, 1024, ... (:mod:`bem._grid`, each
started from the contact of the one before: the sub-panel contact edges of one grid give the
active set on the next, so that a grid usually needs two or three outer steps) until the error
estimate (:mod:`bem._estimate`) of four grids meets ``rtol`` (`_on_four_grids`: the first stop,
N = 2048, has N = 256 solved for it); a fixed ``nodes`` solves ..., N/128, N/32, N/8, N/4, N/2,
N.  A single narrow patch hands over to a contact window (:mod:`bem._window`).

The steps of `solve`: `_problem` checks the inputs and fills in the defaults (one `_Problem`);
`_refine` runs the sequence of grids (`_sizes`), each solved with its retries (`_solve_level`)
and then measured (`_level`), a contact window tried where it is wanted (`_try_window`);
`_grids_result` decides what the grids answer (`_short_of_target` flags a target not met) and
assembles the result.
"""
from __future__ import annotations

import warnings
from dataclasses import dataclass, field
from typing import Any

from viscosine import DEFAULT_RTOL, ViscosineWarning
from viscosine.checks import bad, positive_int, real

from ._accepted import ACCEPTED, MAX_NODES, validate
from ._assemble import build_result
from ._estimate import (ESTIMATE_GRIDS, ESTIMATE_SAFETY, _estimate, _halvings, _level_scalars,
                        _met, _unresolved_memory)
from ._grid import START_NODES, _Grid, _solve_one
from ._inputs import Prony, Sinusoid
from ._layer import Layer, finest_nodes
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
#: the coarsest grid of the ladder that starts a first grid that failed from every elastic
#: contact (`_coarse_start`)
LADDER_NODES = START_NODES // 8
#: consecutive failed grids, none converged yet, after which the adaptive mesh gives up
MAX_FAILED_FROM_SCRATCH = 5
#: nested=False tries the full-contact start with at most these active-set steps and Krylov
#: iterations per step, and no wider second try (the paper's point takes 6 steps of at most 9
#: at 2^20; E_inf/E0 = 1000 at V/V0 = 0.01 stagnated at 300 per step for 50 steps) before the
#: elastic start
COLD_DIRECT_STEPS = 20
COLD_DIRECT_INNER = 40
#: ... and a Krylov restart of at least this (its first steps' inexact solves, on a set half as
#: wide again as the contact, need 9-14 iterations; restarted at 8 they took 14 where 9 do:
#: the paper's point at 2^20, 124.5 -> 113.5 FFT pairs)
COLD_DIRECT_RESTART = 12


def solve(*, load=None, penetration=None, speed, profile=None, material=None, ratio=None,
          hk=None, nodes=None, rtol=None, max_nodes=None, tol=1e-10, max_outer=50,
          restart=8, max_inner=300, nested=True, layer=None) -> BemResult:
    """Steady sliding of a rigid periodic indenter on a viscoelastic half-plane (eq. 2.4-2.5).

    The problem is solved on a sequence of grids N = 512, 1024, 2048, ... (each started from
    the contact of the previous one).  The differences between the scalars of the last three
    or four grids give an a-posteriori estimate of each scalar's discretisation error (see
    `error_estimate` of the result).  With ``nodes=None`` (the default) the sequence stops at
    the first grid whose estimate of four grids meets ``rtol`` (three agree by chance too
    often; the first such grid, 2048, has 256 solved for it; full contact stops on three);
    with ``nodes`` it stops at that grid.

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
        Adaptive mesh only: the target of the estimated errors, relative for Delta/h, mu and,
        under penetration control, the load; absolute for ka and ke (the contact fraction's
        absolute error times pi with several patches).
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
        the last three or four give the error estimate).  False solves ``nodes`` alone, from the
        full-contact pressure lowered until, clipped at zero, it carries the load (with a
        Krylov restart of at least 12; should that fail, once more from the relaxed
        elastic contact, then from the elastic contact with the first harmonic's compliance
        |J*|), with no estimate.  The adaptive
        mesh is always nested.
    layer : Layer, optional
        A layer of thickness d on a rigid foundation in place of the half-space (``bem.Layer``:
        k d, the foundation, the Poisson ratio); default None, the half-space.  Mode n of the
        operator is the half-space's times the layer factor S(|n| k d, nu) (``docs/layers.md``);
        the scalars keep their meaning (Δ/h from the mean line of the deformed surface) and
        ``diagnostics["layer"]`` adds the indenter's absolute approach; a penetration with
        (Δ/h) hk ≥ k d is refused (ValueError) and an answer whose approach reaches the
        foundation (approach hk ≥ k d) is not a success (status 4).  No contact window with
        a layer (the periodic grids answer); the estimate is trusted once d spans
        ``bem._layer.MIN_LAYER_PANELS`` panels of N/4.

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
    return _announced(_refine(_problem(
        load=load, penetration=penetration, speed=speed, profile=profile, material=material,
        ratio=ratio, hk=hk, nodes=nodes, rtol=rtol, max_nodes=max_nodes, tol=tol,
        max_outer=max_outer, restart=restart, max_inner=max_inner, nested=nested, layer=layer)))


# --------------------------------------------------------------------------
# The inputs, checked and completed
# --------------------------------------------------------------------------
@dataclass(frozen=True)
class _Problem:
    """The inputs of `solve`, checked, with their defaults filled in (units of :mod:`bem`).

    ``rtol`` and ``max_nodes`` are None on a fixed mesh (``nodes`` given), ``nodes`` None on
    the adaptive one; exactly one of ``load`` and ``penetration`` is None.  ``amp`` is h k,
    ``control`` and ``asked`` the control and its value, ``sep`` the separation
    ``h k (1 - Delta/h)`` asked for under penetration control (else None).
    """

    profile: Any
    material: Prony
    speed: float
    load: float | None
    penetration: float | None
    nodes: int | None
    rtol: float | None
    max_nodes: int | None
    tol: float
    max_outer: int
    restart: int
    max_inner: int
    nested: Any  # as given: only its truth counts
    layer: Layer | None = None  # None: the half-space
    amp: float = field(init=False)
    control: str = field(init=False)
    asked: float = field(init=False)
    sep: float | None = field(init=False)

    def __post_init__(self):
        amp = float(self.profile.amplitude)
        by_load = self.load is not None
        object.__setattr__(self, "amp", amp)
        object.__setattr__(self, "control", "load" if by_load else "penetration")
        object.__setattr__(self, "asked", self.load if by_load else self.penetration)
        object.__setattr__(self, "sep", None if by_load else amp * (1.0 - self.penetration))


def _problem(*, load, penetration, speed, profile, material, ratio, hk, nodes, rtol, max_nodes,
             tol, max_outer, restart, max_inner, nested, layer=None) -> _Problem:
    """`solve`'s inputs as one `_Problem`; ValueError (naming the parameter, its value and what
    is allowed) on the first bad one, in the order: the control, speed, `validate`'s
    (bem.ACCEPTED), the layer, the options of a fixed or an adaptive mesh (on a layer, at most
    `finest_nodes` panels), the solver's options."""
    if (load is None) == (penetration is None):
        raise bad("load", load, "exactly one of load and penetration "
                  f"(got load={load!r}, penetration={penetration!r})")
    if speed is None:
        raise bad("speed", speed, ACCEPTED["speed"][2])
    validate(load=load, penetration=penetration, speed=speed, ratio=ratio, hk=hk,
             profile=profile, material=material, nodes=nodes, rtol=rtol, max_nodes=max_nodes,
             layer=layer)
    # validate has refused everything outside bem.ACCEPTED, conflicting options and a layer
    # that is not one, too thin for the fixed mesh or the first grid, or out of the
    # penetration's reach
    if profile is None:
        profile = Sinusoid(1.0 if hk is None else hk)
    if material is None:
        material = Prony.standard_linear_solid(3.0 if ratio is None else ratio)
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
    if layer is not None and nodes is None:
        max_nodes = min(max_nodes, finest_nodes(layer))
    return _Problem(
        profile=profile, material=material, speed=float(speed),
        load=None if load is None else float(load),
        penetration=None if penetration is None else float(penetration),
        nodes=nodes, rtol=rtol, max_nodes=max_nodes,
        tol=real("tol", tol, "a finite tolerance in (0, 0.01]", lambda v: 0.0 < v <= 1e-2),
        max_outer=positive_int("max_outer", max_outer, 1),
        restart=positive_int("restart", restart, 1),
        max_inner=positive_int("max_inner", max_inner, 1), nested=nested, layer=layer)


# --------------------------------------------------------------------------
# The sequence of grids
# --------------------------------------------------------------------------
@dataclass
class _Run:
    """What the sequence of grids has found so far (`_refine`, `_level`)."""

    levels: list = field(default_factory=list)   # per grid: (nodes, nit, inner its, status)
    scalars: list = field(default_factory=list)  # (nodes, scalars) of the converged grids
    best: tuple | None = None  # (res, grid) of the finest grid so far: the next grid's start
    last: tuple | None = None  # the same, kept for the answer
    good: tuple | None = None  # (res, grid) of the finest converged grid
    estimate: dict | None = None
    reason: str | None = None  # why the estimate is not trusted (or the grids gave up)
    note: str | None = None    # what the estimate carries for unresolved memory lengths
    reached: int | None = None  # the grid whose estimate met rtol
    failed: int = 0            # consecutive grids that did not converge
    stopped: bool = False      # no finer grid is to be solved
    window: dict | None = None  # what the contact window gave, once tried
    # how the first grid was started, for the estimate's extra grid (`_on_four_grids`): the
    # elastic pair it converged from, and the coarse ladder's last grid where it was used
    first_start: Any = None
    coarse: tuple | None = None


def _sizes(p: _Problem) -> list:
    """The grids to solve, coarse to fine: a fixed mesh's N and (nested) its exact halvings
    N/2, N/4, N/8 (the estimate's grids), then quarters N/32, N/128, ... while they stay at or
    above START_NODES/2 (or N/4 where that is coarser, never below 8 panels) and halvings
    after (they only give the next grid its start); on the adaptive mesh START_NODES, 2 START_NODES, ... up to max_nodes."""
    if p.nodes is not None:
        low = max(8, min(START_NODES // 2, p.nodes // 4))
        sizes = [p.nodes]
        while p.nested and sizes[-1] % 2 == 0 and sizes[-1] // 2 >= low:
            # a start from a grid 4 times coarser costs its grid no more active-set steps
            # than one from the grid 2 times coarser (N = 2^20: the same steps, 3 of 44 FFT
            # pairs fewer); jumps of 8 cost the finer grid extra steps where the memory matters
            step = 4 if (len(sizes) >= ESTIMATE_GRIDS and sizes[-1] % 4 == 0
                         and sizes[-1] // 4 >= low) else 2
            sizes.append(sizes[-1] // step)
        sizes.reverse()
        return sizes
    sizes = []
    n = START_NODES
    while n <= p.max_nodes:
        sizes.append(n)
        n *= 2
    return sizes


def _refine(p: _Problem) -> BemResult:
    """Solve the grids of `_sizes` in turn until one stops the sequence; the contact window's
    answer where one was given, else `_grids_result`."""
    run = _Run()
    elastic, harmonic = _elastic_starts(p)
    for n in _sizes(p):
        answer = _level(p, run, n, elastic, harmonic)
        if answer is not None:
            return answer
        if run.stopped:
            break
    return _grids_result(p, run)


def _elastic_starts(p: _Problem):
    """The elastic pairs (profile, compliance) a first grid may start from: the relaxed
    compliance J0, then the first harmonic's |J*| at this speed (`_solve_level`)."""
    return ((p.profile, Prony(p.material.J0)),
            (p.profile, Prony(abs(complex(p.material.jstar([1.0], p.speed)[0])))))


def _level(p: _Problem, run: _Run, n: int, elastic, harmonic) -> BemResult | None:
    """Solve and measure the grid of N = n panels into ``run``: its estimate, whether the
    sequence stops there (the target met, or too many grids failed), and a contact window
    where one is wanted (returns the window's answer, if it gave one)."""
    grid = _Grid(p.profile, p.material, p.speed, n, p.layer)
    res = _solve_level(p, run, grid, elastic, harmonic)
    run.levels.append((n, res["nit"], tuple(res["inner"]), res["status"]))
    # an unconverged grid still gives the next one a better start than none
    run.last = run.best = (res, grid)
    if res["status"] != CONVERGED:
        run.failed += 1
        if p.nodes is None and run.failed >= (2 if run.scalars else MAX_FAILED_FROM_SCRATCH):
            # two finer grids in a row failed after a converged one (or the first few
            # grids all failed): refining further only costs more, each failed grid
            # running all its active-set steps
            run.reason = (f"the solve did not converge on N={run.levels[-run.failed][0]} … "
                          f"N={n} ({res['message']})")
            run.stopped = True
        return None
    run.failed = 0
    run.good = (res, grid)
    values = _level_scalars(res, grid, p.profile, p.material, p.speed, p.amp)
    run.scalars.append((n, values))
    run.estimate, run.reason, run.note = _estimate(run.scalars, p.material, p.speed, p.layer,
                                                   load_given=p.load is not None)
    if values.get("use_law"):  # the estimate chose the first-order memory law
        res["friction_dissipation"], res["friction"] = res["friction"], res["friction_law"]
    if p.nodes is None and run.reason is None and _met(run.estimate, values, p.rtol) and \
            _on_four_grids(p, run, elastic, harmonic):
        run.reached = n
        run.stopped = True
        return None
    # no contact window on a layer: its Toeplitz column is the half-space's real-space one
    if p.nodes is None and run.window is None and p.layer is None and \
            _window_wanted(p.load, p.profile, values):
        return _try_window(p, run, res, grid)
    return None


def _on_four_grids(p: _Problem, run: _Run, elastic, harmonic) -> bool:
    """Whether the estimate that met the target rests on four grids, N/8 ... N; the adaptive
    mesh stops only there.  Three grids can agree by chance: the edges' place in their panels
    makes each grid's error oscillate (at E_inf/E0 = 1e4, half a wavelength in contact at the
    loss peak, Delta/h is off by 2.7e-7, 1.4e-7 and 2.2e-7 on 512, 1024 and 2048 panels, where
    640 and 896 give 2.0e-6 and 6.1e-7), and two coarse errors small by chance make the last
    differences smaller than the finest error (there 1.8 times).  Where the estimate has three
    grids and the fourth lies below the ladder's first grid (N/8 = START_NODES/2: the first
    stop, N = 2048), that grid is solved now (from the start that served the first grid, else
    with a first grid's retries, `_solve_level`; the coarse ladder's, where the first grid
    was started from it, is taken as it is), its scalars join the estimate and the target is
    judged again; where it lies in the ladder it failed, and the next grid gives the four.
    Full contact (every grid of the estimate) has no edges and stops on three."""
    count = len(_halvings(run.scalars))  # the grids the estimate rests on
    if count >= ESTIMATE_GRIDS or \
            all(sc["contact_fraction"] == 1.0 for _, sc in run.scalars[-count:]):
        return True  # full contact has no edges: its errors fall smoothly, O(1/N^2)
    n = run.scalars[-1][0]
    m = n >> count
    if m >= START_NODES:  # a grid of the ladder, which did not converge
        run.reason = f"the estimate rests on {count} grids (N={m} did not converge)"
        return False
    if run.coarse is not None and run.coarse[1].n == m:
        res, grid = run.coarse  # the first grid was started from it
    else:
        grid = _Grid(p.profile, p.material, p.speed, m, p.layer)
        res = _solve_one(grid, p.load, p.sep, [None], p.tol, p.max_outer, p.restart,
                         p.max_inner, elastic=run.first_start or elastic)
        if res["status"] != CONVERGED:  # the first grid's retries
            res = _solve_level(p, _Run(), grid, elastic, harmonic)
    run.levels.insert(0, (m, res["nit"], tuple(res["inner"]), res["status"]))
    if res["status"] != CONVERGED:
        run.reason = f"the estimate rests on {count} grids (N={m} did not converge)"
        return False
    values = _level_scalars(res, grid, p.profile, p.material, p.speed, p.amp)
    run.scalars.insert(len(run.scalars) - count, (m, values))
    run.estimate, run.reason, run.note = _estimate(run.scalars, p.material, p.speed, p.layer,
                                                   load_given=p.load is not None)
    finest = run.scalars[-1][1]
    res_n = run.good[0]
    res_n["friction"] = res_n["friction_law"] if finest.get("use_law") else \
        res_n.get("friction_dissipation", res_n["friction"])
    return run.reason is None and _met(run.estimate, finest, p.rtol)


def _solve_level(p: _Problem, run: _Run, grid, elastic, harmonic) -> dict:
    """One grid of the sequence with its retries: from the coarser grid's contact (nested=False:
    from the full-contact pressure, lowered until clipped at zero it carries the load); should
    that fail, from the elastic contact ``elastic`` (the first grid: then from ``harmonic``'s,
    the elastic contact with the first harmonic's |J*|, then from coarser grids,
    `_coarse_start`).  Returns `_solve_one`'s state."""
    n = grid.n
    steps = p.max_outer if run.good is None else min(p.max_outer, MAX_OUTER_AFTER_CONVERGED)
    # the coarser grid is handed over in a list that _solve_one empties, so that it is
    # freed once it has given its start (memory at large N)
    start, run.best, run.last = [run.best], None, None
    if p.nodes is not None:
        run.good = None  # a fixed mesh answers on its own grid or not at all
    # nested=False: first from the full-contact pressure (lowered until clipped at zero it
    # carries the load: `_grid._clip_shift`), with few Krylov steps each (where the operator is
    # far from normal, a stiff material at low speed, they stagnate from there); then, as any
    # grid that fails, from the elastic contact
    direct = not p.nested and START_NODES < n <= MAX_NODES_RETRY
    if direct:
        res = _solve_one(grid, p.load, p.sep, start, p.tol, min(steps, COLD_DIRECT_STEPS),
                         max(p.restart, COLD_DIRECT_RESTART), min(p.max_inner, COLD_DIRECT_INNER),
                         widen=False, carry=True)
    else:
        res = _solve_one(grid, p.load, p.sep, start, p.tol, steps, p.restart, p.max_inner,
                         elastic=elastic)
    if res["status"] != CONVERGED and (run.levels[:-1] or direct) and n <= MAX_NODES_RETRY:
        # the coarser contact can be a poor start where the finer grid first resolves a
        # memory length; try once more from the elastic contact on this grid (not on the
        # largest grids, where a failing retry costs minutes)
        retry = _solve_one(grid, p.load, p.sep, [None], p.tol,
                           p.max_outer if n <= MAX_NODES_FULL_RETRY else steps, p.restart,
                           p.max_inner, elastic=elastic)
        if retry["status"] == CONVERGED or run.good is None:
            res = retry
    if res["status"] != CONVERGED and not run.levels and harmonic != elastic:
        # the first grid failed from the relaxed contact: try from the elastic contact with
        # the compliance |J*| of the first harmonic at this speed, near the glassy one at
        # high speed (from the relaxed contact a stiff material at high speed shrinks its
        # contact by one panel per active-set step and runs out of steps on every grid).
        # Only there: on a finer grid the coarser contact is the better start
        retry = _solve_one(grid, p.load, p.sep, [None], p.tol, p.max_outer, p.restart,
                           p.max_inner, elastic=harmonic)
        if retry["status"] == CONVERGED:
            res, run.first_start = retry, harmonic
    if res["status"] != CONVERGED and not run.levels and p.nested and n > LADDER_NODES:
        # still failed: a stiff edge (E_inf/E0 >= 1e4 at the loss peak) retreats by one panel
        # per active-set step, and a start 70 panels too wide runs out of steps; coarser grids
        # cover the distance in fewer steps, so start from the ladder below this grid
        run.coarse = _coarse_start(p, n, harmonic)
        retry = _solve_one(grid, p.load, p.sep, [run.coarse], p.tol,
                           p.max_outer, p.restart, p.max_inner)
        if retry["status"] == CONVERGED:
            res = retry
    return res


def _coarse_start(p: _Problem, n: int, harmonic):
    """(res, grid) of the grid n/2, solved nested from LADDER_NODES up (the coarsest from
    ``harmonic``'s elastic contact): the first grid's last start.  E_inf/E0 = 1e4 ... 1e8 at
    the loss peak, contacts of a quarter and half a wavelength: 11-17 steps at 64 panels, 1-3
    on each finer grid (from the elastic contact at 512: over 50)."""
    best, m = None, LADDER_NODES
    while m < n:
        g = _Grid(p.profile, p.material, p.speed, m, p.layer)
        best = (_solve_one(g, p.load, p.sep, [best], p.tol, p.max_outer, p.restart,
                           p.max_inner, elastic=harmonic), g)
        m *= 2
    return best


def _try_window(p: _Problem, run: _Run, res, grid) -> BemResult | None:
    """Hand the single narrow patch of the converged grid (res, grid) over to a contact window
    (:mod:`bem._window`): its answer when it met the target and passed the validity gate, else
    None (the periodic grids go on as without it; ``run.window`` says what it gave)."""
    window = run.window = _window_refine(res, grid, p.profile, p.material, p.speed, p.load,
                                         p.rtol, p.tol, p.max_outer, p.restart, p.max_inner)
    if window["reached"]:
        answer = build_result(window["res"], window["grid"], p.profile, p.material, p.speed,
                              p.amp, p.load, run.levels + window["levels"], asked=p.asked,
                              control=p.control, error_estimate=window["estimate"],
                              rtol=p.rtol, extra_diagnostics={"window": window["summary"]},
                              memory_bound=_memory_bound(p, window["grid"].nodes))
        if answer.success:
            return answer
        window["summary"]["outcome"] = answer.message
    window["res"] = window["grid"] = None  # memory
    return None


# --------------------------------------------------------------------------
# The answer of the periodic grids
# --------------------------------------------------------------------------
def _grids_result(p: _Problem, run: _Run) -> BemResult:
    """The result of the periodic grids: the last grid's (a fixed mesh's, or the one that met
    the target); on an adaptive mesh that did not meet it, the finest converged grid's, flagged
    (`_short_of_target`).  A fixed mesh whose coarser grids do not support an estimate has
    none."""
    res, grid = run.last
    if p.nodes is None and run.reached is None and run.good is not None:
        res, grid = _short_of_target(p, run)
    # the grids below a fixed one do not resolve the contact: no estimate
    estimate = None if p.nodes is not None and run.reason is not None else run.estimate
    shown_note = "; ".join(t for t in (run.reason, run.note) if t)
    extra = {"estimate_note": shown_note} if shown_note else {}
    if run.window is not None:
        extra["window"] = run.window["summary"]
    return build_result(res, grid, p.profile, p.material, p.speed, p.amp, p.load, run.levels,
                        asked=p.asked, control=p.control, error_estimate=estimate,
                        rtol=p.rtol, extra_diagnostics=extra or None, on_layer=p.layer,
                        memory_bound=_memory_bound(p, grid.n))


def _memory_bound(p: _Problem, n: int) -> float:
    """What the memory lengths N = n panels do not resolve may shift μ by (relative), as the
    estimate carries it (`_estimate._unresolved_memory`, times ESTIMATE_SAFETY)."""
    return ESTIMATE_SAFETY * _unresolved_memory(p.material, p.speed, n) if p.speed > 0 else 0.0


def _short_of_target(p: _Problem, run: _Run):
    """(res, grid) of the finest converged grid, its status STATUS_TARGET and its message the
    target, where the refinement stopped, why, and the estimate reached."""
    res, grid = run.good
    res = dict(res)
    res["status"] = STATUS_TARGET
    shown = "no estimate" if run.estimate is None else "estimated errors " + ", ".join(
        f"{k}={v:.2e}" for k, v in run.estimate.items() if v is not None)
    top = run.levels[-1][0]
    stop = "max_nodes" if top == p.max_nodes else f"refinement stopped at N={top}"
    reason = run.reason
    res["message"] = (f"accuracy target rtol={p.rtol:g} not reached (finest converged grid "
                      f"N={grid.n}, {stop}): {reason + '; ' if reason else ''}{shown}")
    return res, grid


def _announced(result):
    """The result, its warnings raised as `viscosine.ViscosineWarning` (a Python caller sees
    what the command line prints; they stay in ``result.warnings``)."""
    for text in result.warnings:
        warnings.warn(text, ViscosineWarning, stacklevel=3)
    return result

