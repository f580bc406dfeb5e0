"""Shared tolerance tiers: each names what kind of claim a test makes.

ROUNDOFF     algebraic identities and closed forms evaluated two ways (a few hundred ulp).
QUADRATURE   integrals of the semi-analytic road done by two different quadratures, and the
             consistency identities of a solved point (closure residuals, mean pressure, edges).
LIMIT        the semi-analytic solution against an exact limit (Westergaard, Hunter) where the
             physical deviation is below it.
BEM tiers are discretisation errors: they are measured by the convergence study and written
next to that measurement in the BEM and cross-solver tests.
"""
import os

import pytest

ROUNDOFF = 1e-12
QUADRATURE = 1e-10
LIMIT = 1e-9


# ---------------------------------------------------------------------------- the slow studies
def pytest_addoption(parser):
    parser.addoption("--slow", action="store_true",
                     help="also run the tests marked slow (the long studies; CI runs them)")


def _named(item, config):
    """The test was named by its node id on the command line (`file.py::test[...]`)."""
    tail = item.nodeid.split("::", 1)[-1]
    return any("::" in a and tail.startswith(a.split("::", 1)[1]) for a in config.args)


def pytest_collection_modifyitems(config, items):
    """Leave out the tests marked slow unless --slow is given, a -m expression chooses the
    tests, or the test is named by its node id; under --dist loadfile, heavy files first."""
    if not (config.getoption("--slow") or config.option.markexpr):
        slow = [i for i in items if i.get_closest_marker("slow") and not _named(i, config)]
        if slow:
            config.hook.pytest_deselected(items=slow)
            left_out = set(slow)
            items[:] = [i for i in items if i not in left_out]
    _heavy_files_first(config, items)


def _loadfile(config):
    return getattr(config.option, "dist", "no") == "loadfile"


def pytest_configure(config):
    """Under --dist loadfile the files are queued in the order the processes collect them
    (`_heavy_files_first`), not re-sorted by xdist by their number of tests; an xdist process
    runs the surface FFTs on one thread."""
    if _loadfile(config) and hasattr(config.option, "loadscopereorder"):
        config.option.loadscopereorder = False
    if hasattr(config, "workerinput"):
        # the test processes fill the cores: one FFT thread each (the surface BEM's; the same
        # bits on any number, tests/bem/test_bem_surface.py), and the commands they start
        os.environ.setdefault("VISCOSINE_FFT_THREADS", "1")


@pytest.hookimpl(optionalhook=True)
def pytest_configure_node(node):
    """Tell each xdist process (whose own --dist reads "no") to order its collection."""
    if _loadfile(node.config):
        node.workerinput["heavy_files_first"] = True


def _heavy_files_first(config, items):
    """Queue the files holding slow tests first (the whole suite recomputed, 2^22 panels, ...),
    then the others by their number of tests (xdist's own order): a minutes-long file started
    last under --dist loadfile would leave the other core idle at the end of the run."""
    if not getattr(config, "workerinput", {}).get("heavy_files_first"):
        return
    count, slow, first = {}, set(), {}
    for i in items:  # the slow tests still here are the ones this run runs
        f = i.nodeid.split("::", 1)[0]
        count[f] = count.get(f, 0) + 1
        first.setdefault(f, len(first))
        if i.get_closest_marker("slow"):
            slow.add(f)
    items.sort(key=lambda i: (lambda f: (f not in slow, -count[f], first[f]))(
        i.nodeid.split("::", 1)[0]))


def pytest_report_header(config):
    if not (config.getoption("--slow") or config.option.markexpr):
        return "slow tests: left out (run them with --slow, as CI does)"


# ---------------------------------------------------------------------------- both cores


@pytest.hookimpl(tryfirst=True)
def pytest_cmdline_main(config):
    """A plain `pytest` (no paths, no -n) runs the default suite on up to two processes, a
    file's tests in one (pytest-xdist, --dist loadfile): about 9 CPU minutes in one process,
    under 5 minutes of wall time on two cores.  Named files, -n, -p no:xdist or a single core
    keep one process."""
    if (hasattr(config, "workerinput") or not config.pluginmanager.hasplugin("xdist")
            or config.args_source != pytest.Config.ArgsSource.TESTPATHS
            or config.getoption("numprocesses", None) is not None):
        return
    cores = min(2, len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity")
                else os.cpu_count() or 1)
    if cores > 1:
        config.option.numprocesses, config.option.dist = cores, "loadfile"


# ---------------------------------------------------------------------------- the working folder


@pytest.fixture(autouse=True)
def _working_folder(tmp_path_factory, monkeypatch):
    """Every test runs in a folder of its own: what a command writes beside itself (a DMA fit's
    figure, a bench's JSON lines) never lands in the checkout, and no test sees another's."""
    monkeypatch.chdir(tmp_path_factory.mktemp("cwd"))


@pytest.fixture
def read_only_folder(tmp_path, monkeypatch):
    """A folder the process may not write into (``tmp_path/locked``): as root every folder is
    writable, so ``os.access`` is made to see this one read-only."""
    import os
    locked = tmp_path / "locked"
    locked.mkdir()
    real = os.access
    monkeypatch.setattr(os, "access", lambda p, mode, **k: False if str(p).startswith(
        str(locked)) else real(p, mode, **k))
    return locked


# ---------------------------------------------------------------------------- shared results
@pytest.fixture(scope="session")
def quick_report(tmp_path_factory):
    """`report --quick` run once for test_report.py and test_report_layers.py (its layer
    section's runs are among the report's): (report folder, finished process). Read only: a
    test that changes the folder works on a copy."""
    import _shared
    return _shared.quick_report(tmp_path_factory)
