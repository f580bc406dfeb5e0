"""The project's names: the ``viscosine`` command and ``python -m viscosine`` are the command line
of ``python -m comparisons`` (one parser, its name in the messages); ``viscosine.bem``,
``viscosine.analytic`` and ``viscosine.comparisons`` import and hand out the packages' own objects;
every ``viscosine.`` name the README and the docs show exists."""
import functools
import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
#: the console script `pip install` puts beside the interpreter (pyproject [project.scripts])
SCRIPT = Path(sys.executable).parent / "viscosine"
POINT = ["point", "--solver", "analytic", "--load", "0.3", "--speed", "1"]


@functools.lru_cache(maxsize=None)  # the reference runs once for both doors
def _reference(*argv):
    return _run([sys.executable, "-m", "comparisons", *argv])


def _run(argv):
    proc = subprocess.run(argv, capture_output=True, text=True, cwd=ROOT)
    assert "Traceback" not in proc.stderr, proc.stderr
    return proc


DOORS = {"script": ([str(SCRIPT)], "viscosine"),
         "module": ([sys.executable, "-m", "viscosine"], "python -m viscosine")}


@pytest.mark.parametrize("door", DOORS)
def test_each_door_answers_a_point_as_python_m_comparisons_does(door):
    argv, prog = DOORS[door]
    if door == "script":
        assert SCRIPT.exists(), f"{SCRIPT}: run pip install -e . (pyproject [project.scripts])"
    ours, ref = _run(argv + POINT), _reference(*POINT)
    assert ours.returncode == ref.returncode == 0, ours.stderr
    assert json.loads(ours.stdout) == json.loads(ref.stdout)
    # bad input: the same one-line refusal and status 2, under the name it was called by
    refused = ("point", "--solver", "analytic", "--load", "0", "--speed", "1")
    bad, ref = _run(argv + list(refused)), _reference(*refused)
    assert bad.returncode == ref.returncode == 2 and bad.stdout == ""
    assert bad.stderr.startswith(f"{prog} point: ") and len(bad.stderr.splitlines()) == 1
    assert bad.stderr == ref.stderr.replace("python -m comparisons", prog)


def test_the_help_is_the_same_parser():
    ours = _run([sys.executable, "-m", "viscosine", "--help"])
    ref = _run([sys.executable, "-m", "comparisons", "--help"])
    assert ours.returncode == ref.returncode == 0
    words = ref.stdout.replace("python -m comparisons", "python -m viscosine").split()
    assert ours.stdout.split() == words  # the usage line's indent follows the name's length
    assert "mastercurve" in ours.stdout


def test_viscosine_bem_and_analytic_are_the_roads_own_objects():
    import analytic
    import bem
    import comparisons.suite

    import viscosine
    import viscosine.analytic
    import viscosine.bem
    from viscosine.analytic import solve as a_solve
    from viscosine.bem import solve as b_solve
    from viscosine.comparisons import suite
    assert b_solve is bem.solve and a_solve is analytic.solve and suite is comparisons.suite
    assert viscosine.bem.__all__ == bem.__all__ and viscosine.analytic.__all__ == analytic.__all__
    assert all(getattr(viscosine.bem, n) is getattr(bem, n) for n in bem.__all__)
    import analytic.westergaard  # a module of the package, looked up on first use
    assert viscosine.analytic.westergaard is analytic.westergaard
    assert "solve_surface" in dir(viscosine.bem)
    with pytest.raises(AttributeError, match="'viscosine.bem' has no attribute 'nothing'"):
        viscosine.bem.nothing  # noqa: B018
    with pytest.raises(ImportError):
        from viscosine.bem import nothing  # noqa: F401


def test_one_road_under_its_new_name_does_not_import_the_other():
    for road, other in (("bem", "analytic"), ("analytic", "bem")):
        code = (f"import sys; from viscosine.{road} import solve; "
                f"print(sorted(m for m in sys.modules if m.split('.')[0] == {other!r}))")
        proc = _run([sys.executable, "-c", code])
        assert proc.returncode == 0 and proc.stdout.strip() == "[]", (road, proc)


def _documented_names():
    """Every `viscosine.<name>[.<name>...]` the README and the docs show in code."""
    names = set()
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = path.read_text(encoding="utf-8")
        fenced = re.findall(r"^```\w*\n(.*?)^```$", text, re.M | re.S)
        prose = re.sub(r"^```\w*\n.*?^```$", "", text, flags=re.M | re.S)
        for code in fenced + re.findall(r"`([^`]+)`", prose):
            names |= set(re.findall(r"\bviscosine((?:\.\w+)+)", code))
            names |= {f".{m}" for m in re.findall(r"\bimport viscosine\.(\w+)", code)}
    return sorted(names)


def test_every_viscosine_name_the_docs_show_exists():
    import importlib
    names = _documented_names()
    assert {".bem", ".analytic", ".comparisons", ".Fields"} <= set(names), names
    for dotted in names:
        obj = importlib.import_module("viscosine")
        for part in dotted.strip(".").split("."):
            obj = getattr(obj, part)  # AttributeError names what the docs promise in vain
