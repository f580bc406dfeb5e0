"""The progress line (`comparisons.progress`): in a log at most one line per interval and none
for a short run, on a terminal one line rewritten in place; a failure always shown whole; the
sweep, the report's runs, the suite and mastercurve use it."""
import io

import pytest

from comparisons import cli, progress
from comparisons.progress import Progress


class Clock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


def _log(interval=5.0):
    stream, clock = io.StringIO(), Clock()
    return Progress(stream, interval=interval, tty=False, clock=clock), stream, clock


def test_a_log_gets_at_most_one_line_per_interval():
    """The report's ~549 runs over 80 s: 16 lines in a log (one every 5 s), not 549."""
    p, stream, clock = _log()
    n = 549
    for i in range(n):
        clock.t += 80.0 / n
        p.update(f"run {i + 1}/{n}", final=i + 1 == n)
    lines = stream.getvalue().splitlines()
    assert len(lines) == 16 and lines[-1] == f"run {n}/{n}"
    assert all(line.startswith("run ") for line in lines)


def test_a_short_run_writes_nothing_but_its_failures():
    p, stream, clock = _log()
    for i in range(10):
        clock.t += 0.1
        p.update(f"point {i}", final=i == 9)
        if i == 4:
            p.say("point 4: FAILED (why)")
    p.close()
    assert stream.getvalue() == "point 4: FAILED (why)\n"


def test_a_terminal_gets_one_line_rewritten_in_place():
    stream, clock = io.StringIO(), Clock()
    p = Progress(stream, tty=True, clock=clock)
    p.update("1/3")
    clock.t += 0.01
    p.update("2/3")  # within the redraw interval: skipped
    p.say("2/3: warning")
    clock.t += 1.0
    p.update("3/3", final=True)
    p.close()
    assert stream.getvalue() == ("\r1/3\x1b[K" "\r\x1b[K2/3: warning\n1/3\x1b[K"
                                 "\r3/3\x1b[K" "\n")


@pytest.mark.parametrize("interval, lines", [(0.0, 3), (1e9, 0)])
def test_the_sweep_uses_it(capsys, monkeypatch, interval, lines):
    """Every point's line when the interval is nothing, none when it is forever; the record
    lines on standard output unchanged."""
    monkeypatch.setattr(progress, "INTERVAL", interval)
    rc = cli.main(["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "0.1", "1", "10"])
    out = capsys.readouterr()
    assert rc == 0 and len(out.out.splitlines()) == 3
    assert sum(ln.startswith("sweep: ") for ln in out.err.splitlines()) == lines, out.err


def test_the_long_jobs_use_it():
    """The report's runs, the suite, mastercurve and the benchmarks write progress through
    `Progress` (no per-item print to standard error left)."""
    import inspect

    from comparisons import mastercurve, report_runs, suite
    from comparisons.bench import bem, materials, trust
    for module in (report_runs, suite, mastercurve, bem, materials, trust):
        assert "Progress()" in inspect.getsource(module), module.__name__
    assert "file=sys.stderr" not in inspect.getsource(report_runs._progress)
