"""The DMA fit against pyvisco's and ANSYS's fits on pyvisco's example master curves
(`comparisons.bench.materials_peers`, docs/materials.md, "Against pyvisco").

Two claims, each of which can fail:
- the peers' tables are read as their authors meant them: evaluated on the shipped rows, each
  gives back the residual pyvisco itself printed for it (``ls_res``, and ``err`` for the
  minimised fits, the same quantity), to round-off; a wrong frequency unit, a wrong sign of
  ``1 - sum alpha_i`` or a row dropped would not (the time-domain tables likewise, on E(t));
- where each fitter's objective says it should win, it does: our default weighs the relative
  residuals of E' and E'' equally, the peers minimise absolute residuals over E_0 (the glassy
  modulus), in which E'' (a few per cent of E_0) hardly counts, so our E'' and tan delta RMS
  are below every peer's; our fit to E' alone (``loss_weight=0``) is the optimum of the
  relative E' residual over its grid of times (non-negative least squares, a global optimum),
  where the peers optimise an absolute one that lets the rubbery decades go, so its E' RMS is
  at most the best peer's (measured: 1.7-3.2 % against 2.7-10.2 % for the best peer).  Where the peers fit better (E' against our
  default on inconsistent data, pyvisco's own figure of merit) the docs say so.

In the time domain (pyvisco's E(t) master curve, `comparisons.bench.materials_peers_time`) our
fit meets the residual it reports and meets E(t) better than every peer (RMS, largest, and
pyvisco's ls_res); no E'' is measured, so E'' is judged only against the spread of our own
fits at other densities, which every peer's E'' exceeds.
"""
import math

import pytest

from comparisons.bench import materials_peers as mp
from comparisons.bench import materials_peers_time as mpt


@pytest.fixture(scope="module")
def results():
    return {name: mp.compare(name, nu) for name, nu in mp.SETS}


ALL_TABLES = sorted(p for p in mp.DATA.glob("*.csv") if p.name.count(".") == 2)
TABLES = [p for p in ALL_TABLES if p.name.split(".")[0] not in mpt.TIME_SETS]
TIME_TABLES = [p for p in ALL_TABLES if p.name.split(".")[0] in mpt.TIME_SETS]


def test_every_set_has_pyvisco_tables_and_the_ansys_ones_are_where_pyvisco_ships_them():
    names = {p.name for p in ALL_TABLES}
    for name in [n for n, _ in mp.SETS] + list(mpt.TIME_SETS):
        assert {f"{name}.pyvisco-initial.csv", f"{name}.pyvisco-opt.csv"} <= names
    assert {n for n in names if n.endswith(".ansys.csv")} == {
        "user-master.ansys.csv", "eplexor-raw-master.ansys.csv", "time-user-master.ansys.csv"}


@pytest.mark.parametrize("path", TABLES, ids=lambda p: p.name)
def test_a_peer_table_read_back_gives_pyvisco_its_own_residual(path):
    table = mp.read_peer_table(path)
    f, e1, e2 = mp.rows(path.name.split(".")[0])
    got = mp.ls_res(table.modulus(2.0 * math.pi * f), e1, e2, table.E_0)
    assert got == pytest.approx(table.header["ls_res"], rel=1e-9)
    if path.name.endswith("pyvisco-opt.csv"):      # its err is the same least-squares residual
        assert got == pytest.approx(table.header["err"], rel=1e-9)


def test_our_default_fits_loss_and_tan_delta_better_than_every_peer(results):
    for name, res in results.items():
        ours = res["fitters"][mp.OURS]
        for peer, m in res["fitters"].items():
            if peer in (mp.OURS, mp.OURS_STORAGE):
                continue
            assert ours["loss"][0] < m["loss"][0], (name, peer)
            assert ours["tan_delta"][0] < m["tan_delta"][0], (name, peer)


def test_our_storage_only_fit_meets_storage_at_least_as_well_as_the_best_peer(results):
    for name, res in results.items():
        peers = [m["storage"][0] for p, m in res["fitters"].items()
                 if p not in (mp.OURS, mp.OURS_STORAGE)]
        assert res["fitters"][mp.OURS_STORAGE]["storage"][0] <= min(peers), name


def test_the_command_line_prints_the_table(capsys):
    from comparisons.cli import main

    assert main(["bench", "--materials-peers"]) == 0
    out = capsys.readouterr().out
    assert out.startswith("| data set (points, KK range) | fitter | terms |")
    for name, _ in mp.SETS:
        assert f"| {name} (" in out
    assert "| data set (points, window rad/s) | fitter | terms | E(t) RMS/max % |" in out
    for name in mpt.TIME_SETS:
        assert f"| {name} (" in out and f"| {name} | {mpt.OWN_SCATTER} (" in out


# --- time domain: E(t) master curves (comparisons.bench.materials_peers_time) ---------------

@pytest.fixture(scope="module")
def time_results():
    return {name: mpt.compare_time(name) for name in mpt.TIME_SETS}


@pytest.mark.parametrize("path", TIME_TABLES, ids=lambda p: p.name)
def test_a_time_domain_peer_table_read_back_gives_pyvisco_its_own_residual(path):
    table = mp.read_peer_table(path)
    t, e = mpt.time_rows(path.name.split(".")[0])
    got = mpt.ls_res_time(mpt.relaxation(table, t), e, table.E_0)
    assert got == pytest.approx(table.header["ls_res"], rel=1e-9)
    if "err" in table.header:   # pyvisco's own optimiser value: the same residual (sum alpha < 1)
        assert got == pytest.approx(table.header["err"], rel=1e-9)


def test_our_time_fit_meets_the_residual_it_reports(time_results):
    for name, res in time_results.items():
        rms, largest = res["fitters"][mp.OURS]["relax"]
        assert rms == pytest.approx(res["fit"].rms, rel=1e-9), name
        assert largest == pytest.approx(res["fit"].max, rel=1e-9), name


def test_our_time_fit_meets_e_of_t_better_than_every_peer(time_results):
    """Measured: E(t) RMS 0.10 % (largest 0.59 %) against 0.25-2.6 % (2.2-16 %), and pyvisco's
    own figure of merit below each peer's."""
    for name, res in time_results.items():
        ours = res["fitters"][mp.OURS]
        for peer, m in res["fitters"].items():
            if peer == mp.OURS:
                continue
            assert ours["relax"][0] < m["relax"][0], (name, peer)
            assert ours["relax"][1] < m["relax"][1], (name, peer)
            assert ours["ls_res"] < m["ls_res"], (name, peer)


def test_the_peers_loss_moduli_lie_outside_the_spread_of_our_equally_good_fits(time_results):
    """Our fits at other densities meet E(t) about as well as the default; their E'' spread
    (interior RMS) is what the data leave open.  Each peer's E'' differs from ours by more: the
    difference is the peer's fit, not the data's indeterminacy."""
    for name, res in time_results.items():
        sc = res["scatter"]
        assert sc["relax"][1] < min(m["relax"][0] for p, m in res["fitters"].items()
                                     if p != mp.OURS), name
        for peer, m in res["fitters"].items():
            if peer == mp.OURS:
                continue
            assert m["against_ours"]["loss"][1][0] > sc["loss"][1][0], (name, peer)


@pytest.mark.parametrize("argv, named", [(["--points", "3"], "--points 3"),
                                         (["--max-log2n", "10"], "--max-log2n 10"),
                                         (["--materials"], "not allowed with")])
def test_the_command_line_refuses_options_that_do_not_apply(argv, named, capsys):
    from comparisons.cli import main

    assert main(["bench", "--materials-peers", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert named in err and "\n" not in err and len(err) <= 160
