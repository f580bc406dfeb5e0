"""How tests/conftest.py queues the files for pytest-xdist's --dist loadfile (CI's command): the
files holding slow tests first, then the others by their number of tests, each file's tests in
their own order; any other run keeps the collected order."""
from types import SimpleNamespace

import conftest


def _items(spec):
    """spec: (file, test, slow?) in collection order."""
    return [SimpleNamespace(nodeid=f"{f}::{t}",
                            get_closest_marker=lambda name, s=slow: "slow" if s and name == "slow"
                            else None) for f, t, slow in spec]


def _config(workerinput):
    return SimpleNamespace(workerinput=workerinput)


SPEC = [("a.py", "t1", False), ("a.py", "t2", False), ("a.py", "t3", False),
        ("b.py", "t1", False), ("b.py", "whole", True),
        ("c.py", "t1", False), ("c.py", "t2", False), ("c.py", "t3", False), ("c.py", "t4", False),
        ("d.py", "t1", True)]


def test_slow_files_first_then_by_number_of_tests_each_in_its_own_order():
    items = _items(SPEC)
    conftest._heavy_files_first(_config({"heavy_files_first": True}), items)
    assert [i.nodeid for i in items] == [
        "b.py::t1", "b.py::whole", "d.py::t1",
        "c.py::t1", "c.py::t2", "c.py::t3", "c.py::t4", "a.py::t1", "a.py::t2", "a.py::t3"]


def test_without_slow_tests_the_order_is_xdist_s_own():
    items = _items([(f, t, False) for f, t, _ in SPEC])  # a run without --slow
    conftest._heavy_files_first(_config({"heavy_files_first": True}), items)
    assert [i.nodeid.split("::")[0] for i in items] == ["c.py"] * 4 + ["a.py"] * 3 + \
        ["b.py"] * 2 + ["d.py"]


def test_other_runs_keep_the_collected_order():
    for workerinput in ({}, {"workerid": "gw0"}):
        items = _items(SPEC)
        conftest._heavy_files_first(_config(workerinput), items)
        assert [i.nodeid for i in items] == [f"{f}::{t}" for f, t, _ in SPEC]


def test_the_controller_turns_off_xdist_s_reordering_and_tells_its_processes():
    cfg = SimpleNamespace(option=SimpleNamespace(dist="loadfile", loadscopereorder=True))
    conftest.pytest_configure(cfg)
    assert cfg.option.loadscopereorder is False
    node = SimpleNamespace(config=cfg, workerinput={"workerid": "gw0"})
    conftest.pytest_configure_node(node)
    assert node.workerinput["heavy_files_first"] is True
    other = SimpleNamespace(option=SimpleNamespace(dist="load", loadscopereorder=True))
    conftest.pytest_configure(other)
    node = SimpleNamespace(config=other, workerinput={})
    conftest.pytest_configure_node(node)
    assert other.option.loadscopereorder is True and node.workerinput == {}
