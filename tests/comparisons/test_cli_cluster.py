"""Sweeps on a cluster: a local Dask cluster (2 worker processes) returns exactly what the local run
returns, in order, with a failing point reported and the others kept; a worker process that dies
loses only its own point; missing `distributed` and an unreachable scheduler are one line."""
import os
import sys

import pytest

from comparisons import _cluster, cli, report, runner
from comparisons import operating_point as op
from comparisons.store import Store

distributed = pytest.importorskip("distributed")
cloudpickle = pytest.importorskip("cloudpickle")
# the workers cannot import this test module: ship its functions by value
cloudpickle.register_pickle_by_value(sys.modules[__name__])

SWEEP = ["sweep", "--solver", "analytic", "--load", "0.2", "0.5", "--speed", "1", "2", "3"]


@pytest.fixture(scope="module")
def cluster():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cl:
        yield cl


def _square_or_fail(x):
    if x == 5:
        raise FloatingPointError("overflow at five")
    return x * x


def _die_on_seven(x):
    if x == 7:
        os._exit(3)  # the worker process dies, as when the system kills it
    return x * x


def _install_flaky(fail_speed=2.0):
    """Make analytic.solve raise at one speed in this process (run on every worker)."""
    import analytic
    real = getattr(analytic, "_real_solve", analytic.solve)
    analytic._real_solve = real

    def flaky(**kw):
        if kw["speed"] == fail_speed:
            raise ZeroDivisionError("injected at speed 2")
        return real(**kw)
    analytic.solve = flaky


def _remove_flaky():
    import analytic
    analytic.solve = getattr(analytic, "_real_solve", analytic.solve)


def test_executors_agree_in_order_with_a_failing_item(cluster):
    items = list(range(12))
    with _cluster.SerialExecutor() as ex:
        serial = list(ex.imap(_square_or_fail, items, chunksize=3))
    with _cluster.executor(scheduler=cluster.scheduler_address) as ex:
        assert ex.workers == 2
        dask = list(ex.imap(_square_or_fail, items, chunksize=3))
    with _cluster.executor(workers=2) as ex:
        procs = list(ex.imap(_square_or_fail, iter(items), chunksize=2))
    assert serial == dask == procs
    assert serial[5] == (5, _cluster.Failure("FloatingPointError: overflow at five"))
    assert [v for i, v in serial if i != 5] == [i * i for i in items if i != 5]


def test_sweep_on_a_dask_cluster_returns_exactly_the_local_sweep(cluster, monkeypatch, capsys):
    client = distributed.Client(cluster.scheduler_address)
    try:
        client.run(_install_flaky)
        import analytic
        monkeypatch.setattr(analytic, "solve", analytic.solve)      # restored after the test
        monkeypatch.setattr(analytic, "_real_solve", analytic.solve, raising=False)
        _install_flaky()                               # and in this process, for the local run
        rc_local = cli.main(SWEEP)
        local = capsys.readouterr()
        rc_dask = cli.main(SWEEP + ["--scheduler", cluster.scheduler_address])
        dask = capsys.readouterr()
    finally:
        client.run(_remove_flaky)
        client.close()
    assert rc_local == rc_dask == 1
    assert dask.out == local.out and len(dask.out.splitlines()) == 4   # 6 points, 2 failed
    failed = [ln for ln in dask.err.splitlines() if "could not solve" in ln]
    assert failed == [ln for ln in local.err.splitlines() if "could not solve" in ln]
    assert failed[0].startswith("sweep: point 2/6 (load=0.2, speed=2.0): could not solve: "
                                "ZeroDivisionError: injected at speed 2")
    assert "Traceback" not in dask.err


def test_report_runs_on_a_dask_cluster(cluster, tmp_path, monkeypatch):
    jobs = [(op.at("bem", s, load=0.3, nodes=64), s == 1.0) for s in (0.5, 1.0)]
    monkeypatch.setattr(report, "bem_runs", lambda cfg: list(jobs))
    monkeypatch.setattr(report, "tamaas_runs", lambda cfg: [])
    st = Store(str(tmp_path))
    report.execute(report.config(True), st, resume=False, scheduler=cluster.scheduler_address)
    local = {k: runner.run(spec, fields=f) for k, (spec, f) in enumerate(jobs)}
    for k, (spec, f) in enumerate(jobs):
        assert st.get(spec, f)["record"] == local[k]["record"]


def test_a_dead_worker_process_loses_only_its_point():
    with _cluster.executor(workers=2) as ex:
        got = list(ex.imap(_die_on_seven, range(12), chunksize=3))
    assert [i for i, _ in got] == list(range(12))
    assert isinstance(got[7][1], _cluster.Failure) and "died" in got[7][1].error
    assert [v for i, v in got if i != 7] == [i * i for i in range(12) if i != 7]


def test_without_distributed_the_message_names_the_extra(monkeypatch, capsys):
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed → ImportError
    rc = cli.main(SWEEP + ["--scheduler", "tcp://127.0.0.1:1"])
    err = capsys.readouterr().err
    assert rc == 2 and "pip install 'viscosine[cluster]'" in err and len(err.splitlines()) == 1


def test_an_unreachable_scheduler_is_a_cluster_error():
    with pytest.raises(_cluster.ClusterError, match="cannot connect"):
        _cluster.DaskExecutor("tcp://127.0.0.1:9", timeout=0.5)


def test_in_this_process_each_point_comes_out_as_soon_as_it_is_done():
    calls = []

    def f(x):
        calls.append(x)
        return x
    it = _cluster.SerialExecutor().imap(f, range(100), chunksize=64)
    assert next(it) == (0, 0) and calls == [0]  # nothing computed ahead of the output
