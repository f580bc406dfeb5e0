"""The BEM's a-posteriori error estimate and its adaptive mesh, against the semi-analytic road
(the other road is the oracle: the estimate is the BEM's own, built without it)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest

import analytic
import bem

#: operating points across the regimes: slow (memory length resolved late), the friction peak,
#: fast, light load, a stiff material, a thin indenter
POINTS = [dict(load=0.3, speed=0.1), dict(load=0.3, speed=1.0), dict(load=0.3, speed=10.0),
          dict(load=0.01, speed=1.0), dict(load=0.5, speed=1.0, ratio=10.0),
          dict(load=0.1, speed=3.0, hk=0.5), dict(load=0.3, speed=1e-3)]


def _true(r, ref):
    return {"mu": abs(r.mu / ref.mu - 1), "penetration": abs(r.penetration / ref.penetration - 1),
            "ka": abs(r.ka - ref.ka), "ke": abs(r.ke - ref.ke)}


@pytest.mark.parametrize("kw", POINTS, ids=lambda kw: ",".join(f"{k}={v:g}" for k, v in kw.items()))
def test_estimate_bounds_the_true_error_on_a_fixed_mesh(kw):
    """At N = 4096 the estimate is above the true error (the honesty study's criterion is 95 %
    of points below, all below 3×; on these points every one is below)."""
    ref = analytic.solve(**kw)
    r = bem.solve(**kw, nodes=4096)
    assert r.success and r.error_estimate is not None, r.message
    for key, err in _true(r, ref).items():
        assert err <= r.error_estimate[key], (key, err, r.error_estimate[key])


@pytest.mark.parametrize("kw", POINTS, ids=lambda kw: ",".join(f"{k}={v:g}" for k, v in kw.items()))
def test_adaptive_default_meets_its_target(kw):
    """The default (rtol 1e-6) answers within 10 × rtol of the semi-analytic road, with an
    estimate below rtol on μ, Δ/h, ka and ke, on a power-of-two mesh it reports."""
    ref = analytic.solve(**kw)
    r = bem.solve(**kw)
    assert r.success, r.message
    assert r.rtol == 1e-6 and r.nodes & (r.nodes - 1) == 0 and r.nodes >= 2048
    for key, err in _true(r, ref).items():
        assert r.error_estimate[key] <= 1e-6, (key, r.error_estimate[key])
        assert err <= 1e-5, (key, err)
    rec = json.loads(json.dumps(r.as_dict(), allow_nan=False))
    assert rec["rtol"] == 1e-6 and rec["nodes"] == r.nodes


def test_tighter_target_uses_a_finer_mesh():
    a = bem.solve(load=0.3, speed=1.0, rtol=1e-4)
    b = bem.solve(load=0.3, speed=1.0, rtol=1e-7)
    assert a.success and b.success and b.nodes > a.nodes
    assert max(b.error_estimate[k] for k in ("mu", "penetration", "ka", "ke")) <= 1e-7


def test_cap_reached_is_not_an_answer():
    r = bem.solve(load=0.3, speed=0.1, max_nodes=4096)
    assert not r.success and r.status == 5
    assert "rtol=1e-06 not reached" in r.message and "N=4096" in r.message
    assert "ka=" in r.message  # the estimate reached is stated
    assert r.error_estimate["ka"] > 1e-6


def test_unresolved_memory_length_enters_the_estimate():
    """At V/V0 = 1e-3 (memory length 1.6e-4 λ) the trailing edge retreats from Westergaard's by
    (1 − 1/ρ)(V/V0)/2 = 3.3e-4 (the paper's first-order law).  On N = 512 and 1024 the memory
    lies far below the distances the edge fits use: their zeros find the outer fields' edges,
    and the memory lag of the fits (bem._edges.edge_lags) puts the edges back; without it ka
    is off by the whole shift.  At every N the estimate, which carries what the lag may leave
    and the whole shift of a memory between the fitted distances (N = 2048), covers the true
    error."""
    ref = analytic.solve(load=0.3, speed=1e-3)
    shift = (1 - 1 / 3) * 1e-3 / 2
    for n in (512, 1024, 2048, 4096):
        r = bem.solve(load=0.3, speed=1e-3, nodes=n)
        err = max(abs(r.ka - ref.ka), abs(r.ke - ref.ke))
        if n <= 1024:
            assert err < 0.1 * shift, n
        assert r.error_estimate["ka"] >= err and r.error_estimate["ke"] >= err, n
        assert "memory length" in r.diagnostics["estimate_note"]
    assert abs(r.ka - ref.ka) < 0.01 * shift


def test_fast_contact_ahead_of_its_crest_is_measured_from_the_crest():
    """At high speed on a stiff material the contact lies wholly ahead of the crest (ke > ka):
    ke is still measured from the crest, and a one-harmonic profile gives the sinusoid's ke."""
    kw = dict(load=5.26e-4, speed=2.88)
    mat = bem.Prony.standard_linear_solid(204.9)
    ref = analytic.solve(**kw, ratio=204.9, hk=0.0495)
    assert ref.ke > ref.ka
    a = bem.solve(**kw, material=mat, profile=bem.Sinusoid(0.0495), nodes=65536)
    b = bem.solve(**kw, material=mat, profile=bem.Harmonics(amplitudes=(0.0495,), phases=(0.0,)),
                  nodes=65536)
    assert a.patches[0].summit == 0.0 and abs(b.patches[0].summit) < 1e-12
    assert abs(a.ke - ref.ke) < 1e-4 and abs(b.ke - a.ke) < 1e-9


def test_options_of_the_other_mode_are_refused():
    with pytest.raises(ValueError, match="rtol"):
        bem.solve(load=0.3, speed=1.0, nodes=1024, rtol=1e-6)
    with pytest.raises(ValueError, match="max_nodes"):
        bem.solve(load=0.3, speed=1.0, nodes=1024, max_nodes=4096)
    with pytest.raises(ValueError, match="nested"):
        bem.solve(load=0.3, speed=1.0, nested=False)


def test_tiny_contact_is_refined_until_resolved():
    """p̃∞ = 1e-6: the contact spans 0.0005 λ, a fraction of a panel at N = 512; the default
    refines (to 2^21) and answers within 10 × rtol."""
    ref = analytic.solve(load=1e-6, speed=1.0)
    r = bem.solve(load=1e-6, speed=1.0)
    assert r.success, r.message
    assert r.nodes >= 2 ** 20
    for key, err in _true(r, ref).items():
        assert err <= 1e-5, (key, err)
    assert math.isfinite(r.error_estimate["mu"])


def test_dual_solve_equals_the_primal_on_the_same_contact():
    """With most panels in contact the solver works on the free panels' displacements; on the
    same active set both formulations solve the same discrete equations."""
    import numpy as np
    from bem import _grid as S
    mat = bem.Prony.standard_linear_solid(3.0)
    grid = S._Grid(bem.Sinusoid(1.0), mat, 1.0, 2048)
    r = bem.solve(load=0.6, speed=1.0, nodes=2048)
    active = r.pressure > 0
    assert 2 * active.sum() > active.size  # the dual branch's regime
    idx = np.flatnonzero(active)
    free = np.flatnonzero(~active)
    sp, s_p, _, _, ok_p, product = S._linear_solve(
        grid, idx, 0.6, None, np.append(np.zeros(idx.size), 0.0), 1e-12, 40, 600)
    sd, s_d, _, _, ok_d, _ = S._dual_solve(grid, free, 0.6, grid.y[free], 1e-12, 40, 600)
    assert ok_p and ok_d
    # the primal step's last Krylov product is C sigma on every panel: the gaps need no other
    assert np.array_equal(product, grid.op.apply(sp))
    # both bound their residuals near 1e-12; pressures agree to the conditioning, N/2 × that
    assert np.max(np.abs(sp - sd)) < 1e-8 * np.max(sp) and abs(s_p - s_d) < 1e-10


def test_large_grid_near_transition_uses_the_free_panels_and_is_right(monkeypatch):
    """From 2^19 panels a mostly-in-contact step solves on the free panels; just below the
    transition the answer still lies within its estimate of the semi-analytic road."""
    from bem import _grid as S
    n = S.DUAL_MIN_NODES
    calls = _spy_dual(monkeypatch)
    ref = analytic.solve(load=0.66, speed=1.0)
    r = bem.solve(load=0.66, speed=1.0, nodes=n)
    assert r.success and r.contact_fraction > 0.5 and r.levels[-1][0] == n
    assert calls and all(size == n for size in calls)
    for key, err in _true(r, ref).items():
        assert err <= r.error_estimate[key], (key, err, r.error_estimate[key])


def test_free_panel_step_that_cycles_hands_over_to_the_primal(monkeypatch):
    """E_inf/E0 = 3, V/V0 = 0.01, p̃ = 0.5, 4e-5 below the full-contact load: the free region is
    0.5 % of the period and its gaps ~1e-6 h, below what the free-panel step's pressures resolve
    at 2^20 (the rounding C^+ amplifies): its active sets cycled (refused after 39 s); after
    DUAL_MAX_STEPS of them the primal step decides, and the answer lies within its estimate of
    the semi-analytic road.  (By default the free-panel step is no longer taken there: its
    floor is 1e-4 of the load's deficit below p_FC, `DUAL_MAX_DEFICIT_FLOOR`, and within
    GAP_STEP_DEFICIT of p_FC the gap step solves; both are turned off here to test the
    hand-over.)"""
    from bem import _grid as S
    kw = dict(load=0.5, speed=0.01)
    grid = S._Grid(bem.Sinusoid(1.0), bem.Prony.standard_linear_solid(3.0), 0.01, 2 ** 20)
    assert S._dual_floor(grid) > S.DUAL_MAX_DEFICIT_FLOOR * S._full_contact_deficit(grid, 0.5)
    assert S._full_contact_deficit(grid, 0.5) <= S.GAP_STEP_DEFICIT * 0.5
    monkeypatch.setattr(S, "DUAL_MAX_DEFICIT_FLOOR", math.inf)
    monkeypatch.setattr(S, "GAP_STEP_DEFICIT", 0.0)
    calls = _spy_dual(monkeypatch)
    r = bem.solve(**kw, nodes=2 ** 20)
    assert r.success, r.message
    assert 2 ** 20 in calls and r.levels[-1][1] >= 3  # free-panel steps, then the primal
    ref = analytic.solve(**kw)
    for key, err in _true(r, ref).items():
        assert err <= r.error_estimate[key], (key, err, r.error_estimate[key])


def _spy_dual(monkeypatch):
    """Grid sizes on which the free-panel step ran."""
    from bem import _grid as S
    calls = []
    real = S._dual_solve

    def spy(grid, *args, **kw):
        calls.append(grid.n)
        return real(grid, *args, **kw)

    monkeypatch.setattr(S, "_dual_solve", spy)
    return calls


def test_stiff_material_keeps_the_primal_step_on_large_grids(monkeypatch):
    """E_inf/E0 = 155: 1/symbol is ~50 times larger than at 3, so the free-panel step's
    rounding floor would leave ~1e-7 of the load on free panels (enough to make the active set
    cycle at 2^21); the primal step is kept, and the answer lies within its estimate."""
    from bem import _grid as S
    kw = dict(load=0.2865632629223341, speed=0.1325833457667525, ratio=154.70144143871462,
              hk=0.853255930270687)
    n = S.DUAL_MIN_NODES
    calls = _spy_dual(monkeypatch)
    r = bem.solve(**kw, nodes=n)
    assert r.success and r.contact_fraction > 0.5, r.message
    assert calls == []
    ref = analytic.solve(**kw)
    for key, err in _true(r, ref).items():
        assert err <= r.error_estimate[key], (key, err, r.error_estimate[key])


#: stiff materials at low speed, refused before the collocation shift and the Krylov retry
#: (restarted GMRES stagnated, then the active set walked a sawtooth through the contact)
STIFF = [dict(load=0.0010928481031606443, speed=0.03558650412074666, ratio=753.3368294168052,
              hk=0.03947921320897125)]


@pytest.mark.parametrize("kw", STIFF, ids=["ratio753"])
def test_stiff_material_at_low_speed_is_answered(kw):
    """Answered within its target; the true error below 3 × the estimate (the honesty study's
    bound at every point; Δ/h is right to 2e-11, where the two roads' rounding shows)."""
    ref = analytic.solve(**kw)
    r = bem.solve(**kw)
    assert r.success, r.message
    for key, err in _true(r, ref).items():
        assert r.error_estimate[key] <= 1e-6, (key, r.error_estimate[key])
        assert err <= 3 * r.error_estimate[key], (key, err, r.error_estimate[key])


@pytest.mark.slow  # about 50 s: 2^22 panels
def test_cycle_at_round_off_is_judged_by_the_validity_gate():
    """E_inf/E0 995 at V/V0 3e-4 on 2^22 panels: the trailing-edge panels flip between a
    pressure of -1e-2 of the maximum (active) and a gap of -1e-12 h (free), and the active set
    cycles. After the cycle the panels are judged with the validity gate's allowance: the
    solve converges, and the answer lies within its error estimate of the semi-analytic road."""
    kw = dict(load=0.00012770623151446626, speed=0.0003018332059429246,
              ratio=995.1842324068758, hk=5.310040304019914)
    r = bem.solve(**kw, nodes=2 ** 22)
    assert r.success and "after a cycle" in r.message, r.message
    ref = analytic.solve(**kw)
    for key, err in _true(r, ref).items():
        assert err <= r.error_estimate[key], (key, err, r.error_estimate[key])


def test_penetration_estimate_has_the_round_off_floor_of_the_separation():
    """Grids that agree exactly still leave Δ/h uncertain by the gap round-off the validity
    gate allows (1e-12 h): the relative estimate is 1.5e-12/(Δ/h), larger at small Δ/h (at
    Δ/h = 4.6e-4, E∞/E0 487, N = 2^24, the true error was 3.4 × an estimate without it)."""
    from bem import _estimate as S
    sls = bem.Prony.standard_linear_solid(3.0)
    for pen in (0.5, 4.6e-4, 1e-7):
        sc = dict(penetration=pen, tau_f=0.1, mu=0.2, contact_fraction=0.3, ka=1.0, ke=0.1,
                  ke_hat=0.1, npatch=1, min_panels=1000, gap_roundoff=1e-12)
        est, reason, note = S._estimate([(n, dict(sc)) for n in (1024, 2048, 4096)], sls, 1.0)
        assert reason is None and note is None
        assert est["penetration"] == pytest.approx(1.5e-12 / pen, rel=1e-12)
        assert est["mu"] == 0.0 and est["ka"] == 0.0
        # a contact window measures gaps from the crest: the floor is 1e-12 of its drop
        sc["gap_roundoff"] = 1e-12 * 3 * pen
        est, _, _ = S._estimate([(n, dict(sc)) for n in (1024, 2048, 4096)], sls, 1.0)
        assert est["penetration"] == pytest.approx(1.5e-12 * 3, rel=1e-12)


def test_contact_fraction_estimate_is_relative_and_the_target_absolute():
    """The contact fraction's estimate is relative (docs/conventions.md): the first-order bound
    of its grids, plus the unresolved memory's edge shift, over |fraction|.  The adaptive mesh
    still stops on its absolute error (times pi, where several patches leave ka and ke
    undefined), and under penetration control on the load's estimate too."""
    from bem import _estimate as S
    sls = bem.Prony.standard_linear_solid(3.0)
    sc = dict(penetration=0.5, tau_f=0.1, mu=0.2, ka=1.0, ke=0.1, ke_hat=0.1, npatch=1,
              min_panels=1000, gap_roundoff=0.0)
    # fractions converging at first order to 0.02: 0.02 + 1e-4 * 1024/n
    run = [(n, dict(sc, contact_fraction=0.02 + 1e-4 * 1024 / n)) for n in (1024, 2048, 4096)]
    finest = 0.02 + 0.25e-4
    bound = 1.5 * 0.375e-4  # 1.5 x the largest of the three differences
    est, reason, note = S._estimate(run, sls, 1.0)
    assert reason is None and note is None
    assert est["contact_fraction"] == pytest.approx(bound / finest, rel=1e-12)
    assert est["contact_fraction"] >= 0.25e-4 / finest  # it bounds the true (relative) error
    speed = 2 * math.pi / 2048  # a memory length of half a panel at N/4 = 1024
    shift = S._unresolved_memory(sls, speed, 1024)
    est2, _, _ = S._estimate(run, sls, speed)
    assert est2["contact_fraction"] == pytest.approx((bound + 1.5 * shift) / finest, rel=1e-12)
    # several patches: met on pi x the absolute estimate, whatever the fraction
    values = dict(run[-1][1], npatch=2, ka=None, ke=None)
    many = dict(mu=0.0, penetration=0.0, contact_fraction=est["contact_fraction"])
    absolute = math.pi * bound
    assert S._met(many, values, 1.01 * absolute) and not S._met(many, values, 0.99 * absolute)
    # under penetration control the load's estimate (relative) must meet rtol too
    one = dict(mu=0.0, penetration=0.0, ka=0.0, ke=0.0)
    assert S._met(one, run[-1][1], 1e-6)
    assert not S._met(dict(one, load=2e-6), run[-1][1], 1e-6)
    assert S._met(dict(one, load=0.5e-6), run[-1][1], 1e-6)


def test_first_order_memory_law_against_the_semi_analytic_road():
    """Memories far under every fitted distance: the friction of the first-order memory law
    (bem._assemble._lag_friction) misses the semi-analytic μ by its second-order remainder, of
    the order of L/a (measured 0.04 … 0.84 L/a), inside the bound the estimate carries."""
    from bem import _assemble, _estimate
    for ratio, load in ((1.5, 0.001), (3.0, 0.01), (1000.0, 0.3)):
        mat = bem.Prony.standard_linear_solid(ratio)
        ref = analytic.solve(load=load, speed=1e-4, ratio=ratio)
        r = bem.solve(load=load, speed=1e-4, ratio=ratio, nodes=8192)
        f = r.fields()
        y = np.cos(2 * np.pi * np.asarray(f.x_over_lambda))
        tau, l_eff = _assemble._lag_friction(np.asarray(f.pressure), y - y.mean(), mat, 1e-4)
        rel = (tau / np.mean(f.pressure)) / ref.mu - 1.0
        scale = l_eff / (0.5 * r.contact_fraction)
        assert 0.1 * scale < rel < _estimate.LAG_LAW_SAFETY * scale, (ratio, load, rel, scale)


def test_the_adaptive_mesh_takes_the_memory_law_where_its_estimate_is_smaller():
    """At V/V0 = 1e-8 the dissipation form's μ converges like 1/N (the memory is 1e-9 λ); the
    first-order memory law's remainder bound is 4e-8: the estimate chooses the law, says so,
    answers on a coarse grid (2^21 without it), and covers the semi-analytic μ."""
    ref = analytic.solve(load=0.3, speed=1e-8)
    r = bem.solve(load=0.3, speed=1e-8)
    assert r.success and r.nodes <= 16384, r.message
    assert "first-order memory law" in r.diagnostics["estimate_note"]
    assert abs(r.mu / ref.mu - 1) <= r.error_estimate["mu"] <= 1e-6


def _near_full_contact_state(nodes=4096, gap_step=True):
    """A converged grid 1e-4 below the full-contact load (E_inf/E0 = 3, V/V0 = 1): one patch,
    the period less a gap of about 26 panels at N = 4096 (``gap_step=False``: solved by the
    primal step, whose gaps are differences C sigma - y + s)."""
    from bem import _grid as S
    from bem._grid import _Grid, _solve_one
    from bem._inputs import Prony, Sinusoid
    from comparisons.roads import full_contact_load
    profile, material = Sinusoid(1.0), Prony.standard_linear_solid(3.0)
    load = full_contact_load(1.0, 3.0, 1.0) * (1.0 - 1e-4)
    grid = _Grid(profile, material, 1.0, nodes)
    saved = S.GAP_STEP_DEFICIT
    S.GAP_STEP_DEFICIT = saved if gap_step else 0.0
    try:
        res = _solve_one(grid, load, None, [None], 1e-10, 50, 8, 300,
                         elastic=(profile, Prony(material.J0)))
    finally:
        S.GAP_STEP_DEFICIT = saved
    assert res["exact_gaps"] == gap_step
    assert res["status"] == 0 and not res["active"].all()
    return res, grid, profile, material, load


def _with_sliver(res, load, share, gap_between):
    """``res`` with a two-panel run of contact carrying ``share`` of the load placed in the gap,
    three panels past the patch's leading edge, the three panels between at ``gap_between``."""
    res = dict(res, sigma=res["sigma"].copy(), gap=res["gap"].copy(),
               active=res["active"].copy())
    n = res["active"].size
    free = np.flatnonzero(~res["active"])
    first_free = int(free[0])  # the gap is one run away from the ends of the period
    assert free.size > 12 and np.all(np.diff(free) == 1)
    between = first_free + np.arange(3)
    sliver = first_free + 3 + np.arange(2)
    res["gap"][between] = gap_between
    res["gap"][sliver] = 0.0
    res["active"][sliver] = True
    res["sigma"][sliver] = 0.5 * share * load * n
    return res


def test_a_round_off_sliver_next_to_the_patch_is_not_counted():
    """A run of one or two panels carrying 1e-12 of the load across gaps of 3e-13 h (what the
    solve leaves near full contact at N = 2^22) is one contact with its patch to round-off:
    one patch, the same edges, and the estimate is not withheld; a run carrying 1e-6 of the
    load, or one behind a gap above the validity gate's round-off, stays a patch."""
    from bem._edges import counted_contact
    from bem._estimate import _level_scalars
    res, grid, profile, material, load = _near_full_contact_state()
    clean = _level_scalars(dict(res), grid, profile, material, 1.0, 1.0)
    assert clean["npatch"] == 1
    sliv = _with_sliver(res, load, 1e-12, 3e-13)
    counted = counted_contact(sliv["sigma"], sliv["gap"], sliv["active"], grid.scale)
    np.testing.assert_array_equal(counted, res["active"])
    sc = _level_scalars(sliv, grid, profile, material, 1.0, 1.0)
    assert sc["npatch"] == 1
    # only the gap side of the leading edge sees the changed gaps; the fit holds to 1e-3 of ka
    assert abs(sc["ka"] - clean["ka"]) < 1e-3 and abs(sc["mu"] / clean["mu"] - 1) < 1e-9
    for share, between in ((1e-6, 3e-13), (1e-12, 1e-9)):
        other = _with_sliver(res, load, share, between)
        kept = counted_contact(other["sigma"], other["gap"], other["active"], grid.scale)
        assert kept is other["active"]
        assert _level_scalars(other, grid, profile, material, 1.0, 1.0)["npatch"] == 2


def test_the_estimate_is_given_across_a_sliver_on_one_grid():
    """Grids of one patch with a round-off sliver on one of them: the patch count is the same
    on every grid, so the estimate is trusted (it was withheld: '1, 1, 3')."""
    from bem._estimate import _estimate, _level_scalars
    scalars = []
    for n in (2048, 4096, 8192):  # the gap spans 13 panels and more (at least 8 are needed)
        res, grid, profile, material, load = _near_full_contact_state(n)
        if n == 8192:
            res = _with_sliver(res, load, 1e-12, 3e-13)
        scalars.append((n, _level_scalars(res, grid, profile, material, 1.0, 1.0)))
    est, reason, _ = _estimate(scalars, material, 1.0)
    assert reason is None and est["ka"] is not None


def test_just_below_full_contact_is_answered_within_its_estimate():
    """E_inf/E0 = 100, V/V0 = 24.7, 1.5e-6 below the full-contact load: the slivers of the
    gap's edges made the patch count 1, 2, 5, 5 and the Krylov residual moved the edges, refused
    at 2^24 after minutes; now one patch on every grid and an answer (at 2^19, 4 s) within its
    estimate of the semi-analytic road."""
    kw = dict(load=11.99916452292466, speed=24.699309839052606, ratio=100.0)
    r = bem.solve(**kw, max_nodes=2 ** 20)
    assert r.success, r.message
    assert r.n_patches == 1 and r.contact_fraction > 0.999
    ref = analytic.solve(**kw)
    for key, err in _true(r, ref).items():
        # the two roads agree to about 1e-11 on mu: below that the reference's own rounding
        assert err <= r.error_estimate[key] + 1e-10, (key, err, r.error_estimate[key])


def test_a_gap_at_round_off_gives_no_estimate():
    """3e-8 below p_FC the deepest gap is a few times the validity gate's 1e-12 h and the grids
    agree on edges that are round-off (ka 1.1e-6 and 3.5e-5 off under estimates of 9e-7 and
    1.4e-7): below MIN_GAP_DEPTH times that round-off the estimate is not trusted, where the
    gaps are differences (the primal step); the gap step's are solved for: no such rule."""
    from bem._estimate import MIN_GAP_DEPTH, _estimate, _level_scalars
    res, grid, profile, material, _ = _near_full_contact_state(4096)
    assert _level_scalars(res, grid, profile, material, 1.0, 1.0)["gap_depth"] is None
    scalars = []
    for n in (2048, 4096, 8192):  # the gap spans 13 panels and more (at least 8 are needed)
        res, grid, profile, material, load = _near_full_contact_state(n, gap_step=False)
        scalars.append((n, _level_scalars(res, grid, profile, material, 1.0, 1.0)))
    assert scalars[-1][1]["gap_depth"] > 1e3 * MIN_GAP_DEPTH  # 1e-4 below: gaps of 1e-7 h
    assert _estimate(scalars, material, 1.0)[1] is None
    scalars[-1][1]["gap_depth"] = 0.5 * MIN_GAP_DEPTH
    est, reason, _ = _estimate(scalars, material, 1.0)
    assert reason is not None and "round-off" in reason


def test_the_adaptive_mesh_stops_on_four_grids():
    """Three grids can agree by chance: at E∞/E0 = 1e4 with half a wavelength in contact at the
    loss peak, the edges' place in their panels leaves Δ/h off by 2.7e-7, 1.4e-7 and 2.2e-7 on
    512, 1024 and 2048 panels, and 1.5 × the first-order bound of those three is 1.3e-7.  The
    first stop (N = 2048 at rtol 1e-3) has N = 256 solved for it, and its estimate covers the
    error; full contact, without edges, stops on three grids."""
    from analytic.full_contact import modulus
    ratio, speed = 1e4, 100.0
    half = 0.5 * modulus(speed, ratio)[0]
    load = 0.6 * half
    ref = analytic.solve(load=load, speed=speed, ratio=ratio)
    q = [bem.solve(load=load, speed=speed, ratio=ratio, nodes=n).penetration
         for n in (2048, 1024, 512)]
    three = 1.5 * max(abs(q[0] - q[1]), abs(q[0] - q[2]) / 2, abs(q[1] - q[2]) / 2) / q[0]
    err = abs(q[0] / ref.penetration - 1)
    assert three < err  # what three grids alone would have claimed
    r = bem.solve(load=load, speed=speed, ratio=ratio, rtol=1e-3)
    assert r.success and r.nodes == 2048, r.message
    assert [lv[0] for lv in r.levels] == [256, 512, 1024, 2048]
    assert r.penetration == pytest.approx(q[0], rel=1e-12)
    for key, e in _true(r, ref).items():
        assert e <= r.error_estimate[key] <= 1e-3, (key, e, r.error_estimate[key])
    full = bem.solve(load=2.0 * half, speed=speed, ratio=ratio, rtol=1e-3)
    assert full.full_contact and [lv[0] for lv in full.levels] == [512, 1024, 2048]
