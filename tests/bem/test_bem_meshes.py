"""`bem.solve_meshes` and `bem.solve_surface_meshes`: a mesh study whose grids are solved once.

Each result must be what the fixed mesh answers on its own: the same bits where the study and
the fixed mesh solve the same grids (the coarsest meshes), the same answer to the Krylov
tolerance where only the start of a coarse grid differs, the same error estimate, and the same
refusals of bad input (before anything is solved).
"""
import numpy as np
import pytest

import bem

LINE = dict(load=0.3, speed=1.0, ratio=3.0)
# the fixed mesh starts N/32, N/128 ... by quarters below N/8 from N >= 8192: the grids differ
LINE_SAME_GRIDS = (1024, 2048, 4096)
SURFACE = dict(load=0.2, speed=1.0, ratio=3.0, surface=bem.bisinusoid(1.0), direction=30.0)


def _close(a: dict, b: dict, rel):
    assert a.keys() == b.keys()
    for k in a:
        if isinstance(a[k], float):
            assert a[k] == pytest.approx(b[k], rel=rel, abs=1e-14), k
        else:
            assert a[k] == b[k], k


def test_each_mesh_of_a_line_study_is_the_fixed_mesh():
    nodes = [1024, 2048, 4096, 8192, 16384]
    study = list(bem.solve_meshes(nodes=nodes[::-1], **LINE))  # any order: answered coarse first
    assert [r.nodes for r in study] == nodes
    for r in study:
        own = bem.solve(nodes=r.nodes, **LINE)
        assert r.success and own.success
        if r.nodes in LINE_SAME_GRIDS:
            assert r.scalars() == own.scalars()
            assert r.error_estimate == own.error_estimate
            np.testing.assert_array_equal(r.pressure, own.pressure)
            assert r.levels == own.levels
        else:
            # tol = 1e-10 on the gaps, relative to h k: the answers agree far below the grid error
            _close(r.scalars(), own.scalars(), 1e-8)
            _close(r.error_estimate, own.error_estimate, 1e-4)
            assert np.max(np.abs(r.pressure - own.pressure)) < 1e-8 * np.max(own.pressure)
            # the study's grids halve in turn: N/8 was started from N/16 here
            assert [lv[0] for lv in r.levels][-5:] == [r.nodes >> k for k in (4, 3, 2, 1, 0)]


def test_a_line_study_yields_each_mesh_as_it_is_solved(monkeypatch):
    from bem import _study
    solved = []
    real = _study._level

    def spy(p, run, n, *args):
        solved.append(n)
        return real(p, run, n, *args)
    monkeypatch.setattr(_study, "_level", spy)
    it = bem.solve_meshes(nodes=[512, 1024], **LINE)
    assert solved == []  # nothing before the first result is asked for
    first = next(it)
    assert first.nodes == 512 and solved == [128, 256, 512]
    assert next(it).nodes == 1024 and solved[-1] == 1024
    with pytest.raises(StopIteration):
        next(it)
    monkeypatch.undo()
    assert first.levels == bem.solve(nodes=512, **LINE).levels


def test_a_penetration_study_on_a_layer_is_the_fixed_mesh():
    kw = dict(penetration=0.5, speed=3.0, ratio=10.0,
              layer=bem.Layer(thickness=0.5 * 2 * np.pi, foundation="bonded", nu=0.45))
    study = list(bem.solve_meshes(nodes=[1024, 2048], **kw))
    for r in study:
        own = bem.solve(nodes=r.nodes, **kw)
        assert r.scalars() == own.scalars() and r.diagnostics == own.diagnostics


@pytest.mark.parametrize("nodes,why", [
    (1024, "a sequence of meshes"),
    ("1024", "a sequence of meshes"),
    ([], "at least one mesh"),
    ([1000, 1024], "1024/1000 is not a power of two"),
    ([512, 1536], "1536/512 is not a power of two"),
    ([4, 8], "nodes=4"),
    ([8.5, 16], "nodes=8.5"),
    ([1024, 2048, 1024], "distinct meshes"),
])
def test_bad_meshes_are_refused_by_name(nodes, why):
    with pytest.raises(ValueError, match="nodes") as e:
        bem.solve_meshes(nodes=nodes, **LINE)
    assert why in str(e.value)


@pytest.mark.parametrize("solve,kw,name", [
    (bem.solve_meshes, dict(LINE, load=-1.0), "load"),
    (bem.solve_meshes, dict(LINE, tol=1.0), "tol"),
    (bem.solve_surface_meshes, dict(SURFACE, load=-1.0), "load"),
    (bem.solve_surface_meshes, dict(SURFACE, max_inner=0), "max_inner"),
])
def test_bad_input_is_refused_before_anything_is_solved(solve, kw, name):
    """At the call, not at the first result: the study is an iterator."""
    with pytest.raises(ValueError, match=f"^{name}="):
        solve(nodes=[64, 128], **kw)


def test_each_grid_of_a_surface_study_is_the_fixed_grid():
    nodes = [32, 64, 128]
    study = list(bem.solve_surface_meshes(nodes=nodes[::-1], **SURFACE))
    assert [r.nodes for r in study] == nodes
    for r in study:
        own = bem.solve_surface(nodes=r.nodes, **SURFACE)
        assert r.success and own.success and r.n_patches == own.n_patches
        if r.nodes in (32, 64):  # the same grids (8 ... 32, 8 ... 64) from the same start
            assert r.mu == own.mu and r.error_estimate == own.error_estimate
            np.testing.assert_array_equal(r.pressure, own.pressure)
        else:  # N/8 started from N/16 here, afresh on the fixed grid
            for k in ("mu", "mu_lateral", "penetration", "contact_fraction", "max_pressure"):
                assert getattr(r, k) == pytest.approx(getattr(own, k), rel=1e-9), k
            _close(r.error_estimate, own.error_estimate, 1e-4)
            assert np.max(np.abs(r.pressure - own.pressure)) < 1e-8 * np.max(own.pressure)


def test_a_surface_study_refuses_a_grid_below_the_surface_modes():
    s = bem.self_affine(hurst=0.8, rolloff=1.0, short_cutoff=8.0, rms_slope=0.5)
    assert s.min_nodes()[0] > 8
    with pytest.raises(ValueError, match="nodes=8 is not allowed: at least 18 panels"):
        bem.solve_surface_meshes(nodes=[8, 64], load=0.2, speed=1.0, surface=s)


def test_a_surface_estimate_rests_only_on_grids_that_halve(monkeypatch):
    """A grid that failed breaks the chain: the next grid's estimate is not made from grids
    four or eight times coarser (the fixed grid gives none there either)."""
    from bem import _surface_solver as S
    from bem._result import OUTER_EXHAUSTED
    real = S._solve_one

    def failing(grid, *args, **kw):
        res = real(grid, *args, **kw)
        if grid.shape[0] == 32:
            res = dict(res, status=OUTER_EXHAUSTED, message="made to fail here")
        return res
    monkeypatch.setattr(S, "_solve_one", failing)
    r64 = list(bem.solve_surface_meshes(nodes=[64], **SURFACE))[0]
    fixed = bem.solve_surface(nodes=64, **SURFACE)
    assert [lv[0] for lv in r64.levels] == [8, 16, 32, 64] and r64.levels[2][3] != 0
    assert r64.error_estimate is None and fixed.error_estimate is None
    assert r64.mu == fixed.mu


def test_the_suite_refuses_meshes_out_of_order():
    from comparisons import suite
    case = suite.get_case("sls-above-fc-v1")
    with pytest.raises(suite.SuiteError, match="increasing order"):
        suite.compute(dict(case, nodes=list(reversed(case["nodes"]))))
