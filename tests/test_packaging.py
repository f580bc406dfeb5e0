"""The README opens with the two set-up commands, and CI runs the second one verbatim."""
import pathlib
import re

ROOT = pathlib.Path(__file__).resolve().parents[1]


def _readme_commands():
    text = (ROOT / "README.md").read_text()
    block = re.search(r"```\n(.*?)```", text, re.S).group(1)
    return [line for line in block.splitlines() if line.strip()]


def test_readme_opens_with_two_commands():
    text = (ROOT / "README.md").read_text()
    assert text.split("\n", 2)[2].startswith("```")  # title, blank line, then the commands
    cmds = _readme_commands()
    assert len(cmds) == 2
    assert "pip install ." in cmds[0] and "python -m comparisons" in cmds[0]
    assert "pip install '.[test]'" in cmds[1] and "pytest" in cmds[1]
    # the whole suite, the long studies too, one file per process on both cores
    assert cmds[1].endswith("pytest --slow -n 2 --dist loadfile")


def test_ci_runs_the_readme_test_command():
    ci = (ROOT / ".ci" / "run").read_text().splitlines()
    assert _readme_commands()[1] in ci


def test_roads_do_not_import_each_other():
    pat = {"bem": re.compile(r"^\s*(from|import)\s+analytic\b", re.M),
           "analytic": re.compile(r"^\s*(from|import)\s+bem\b", re.M)}
    for pkg, rx in pat.items():
        for f in (ROOT / pkg).glob("*.py"):
            assert not rx.search(f.read_text()), f"{f} imports the other road"
