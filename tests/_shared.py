"""Expensive results that several test files read: made once per test session and, when
pytest-xdist spreads the files over processes, once for all of them (the first process to ask
makes it under a file lock, the others wait and read the same folder).

What a shared folder holds must only be read by the tests: a test that changes it works on a
copy (`shutil.copytree`).
"""
import contextlib
import json
import os
import subprocess
import sys


@contextlib.contextmanager
def _locked(path):
    try:
        import fcntl
    except ImportError:  # no flock (Windows): each process makes its own copy
        yield
        return
    with open(path, "w") as f:
        fcntl.flock(f, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(f, fcntl.LOCK_UN)


def shared_folder(tmp_path_factory, name, make):
    """The folder ``name`` that ``make(folder)`` fills, once per session (once across xdist's
    processes where the lock exists)."""
    base = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        base = base.parent  # shared by every process of this run
    folder = base / f"shared-{name}"
    done = folder / ".made"
    with _locked(base / f"shared-{name}.lock"):
        if not done.exists():
            folder.mkdir(exist_ok=True)
            make(folder)
            done.write_text("")
    return folder


def run_cli(*args, cwd):
    """`python -m comparisons ARGS` in ``cwd``."""
    return subprocess.run([sys.executable, "-m", "comparisons", *args], capture_output=True,
                          text=True, cwd=cwd)


def quick_report(tmp_path_factory):
    """`python -m comparisons report --quick --workers 1` into a shared folder: (report folder,
    the finished process) — its exit status, standard output and standard error as the run left
    them.  One process for its runs: the other test process fills the second core (the runs in
    two processes: test_cli.py's sweep, test_suite.py's check)."""
    def make(folder):
        out = folder / "report"
        out.mkdir()
        proc = run_cli("report", "--quick", "--workers", "1", "--out", str(out), cwd=out)
        (folder / "proc.json").write_text(json.dumps(
            {"args": proc.args, "returncode": proc.returncode, "stdout": proc.stdout,
             "stderr": proc.stderr}))
    folder = shared_folder(tmp_path_factory, "quick-report", make)
    proc = subprocess.CompletedProcess(**json.loads((folder / "proc.json").read_text()))
    return folder / "report", proc
