"""The operating point's one home: the table from parameter to option and keyword (every bad
value named as typed, on the command line and in Python), the defaults applied once, and the
one rule for outputs that cannot be written (exit status 2, one line, missing folders made)."""
from __future__ import annotations

import os

import pytest

from comparisons import cli, runner
from comparisons import operating_point as op
from comparisons._errors import BadInput

BASE = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "64"]

#: parameter -> (its keyword, command-line options of a bad value, the same in Python)
BAD = {
    "load": (["point", "--solver", "bem", "--load", "-1", "--speed", "1", "--nodes", "64"],
             dict(load=-1.0, speed=1.0, nodes=64)),
    "penetration": (["point", "--solver", "bem", "--penetration", "1.5", "--speed", "1",
                     "--nodes", "64"], dict(penetration=1.5, speed=1.0, nodes=64)),
    "speed": (["point", "--solver", "bem", "--load", "0.3", "--speed", "-1", "--nodes", "64"],
              dict(load=0.3, speed=-1.0, nodes=64)),
    "ratio": (BASE + ["--ratio", "0.5"], dict(load=0.3, speed=1.0, nodes=64, ratio=0.5)),
    "hk": (BASE + ["--hk", "-1"], dict(load=0.3, speed=1.0, nodes=64, hk=-1.0)),
    "nodes": (["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--nodes", "3"],
              dict(load=0.3, speed=1.0, nodes=3)),
    "rtol": (["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--rtol", "-1"],
             dict(load=0.3, speed=1.0, rtol=-1.0)),
    "max_nodes": (["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--max-nodes",
                   "3"], dict(load=0.3, speed=1.0, max_nodes=3)),
    "foundation": (BASE + ["--thickness", "0.5", "--foundation", "bonded", "--nu", "2"],
                   dict(load=0.3, speed=1.0, nodes=64,
                        layer={"thickness_over_wavelength": 0.5, "foundation": "bonded",
                               "nu": 2.0})),
    "direction": (BASE + ["--surface", "bisinusoid", "--direction", "nan"],
                  dict(load=0.3, speed=1.0, nodes=64, surface={"kind": "bisinusoid"},
                       direction=float("nan"))),
    "aspect": (BASE + ["--surface", "bisinusoid", "--aspect", "0"],
               dict(load=0.3, speed=1.0, nodes=64, surface={"kind": "bisinusoid",
                                                            "aspect": 0.0})),
}
#: the parameter a refusal names (a layer's ν refused as nu; its option --nu)
NAMED = {"foundation": "nu"}


def _cli(argv, capsys):
    rc = cli.main(argv)
    return rc, capsys.readouterr().err.strip()


@pytest.mark.parametrize("param", sorted(BAD))
def test_every_bad_value_names_its_option_on_the_cli_and_its_keyword_in_python(param, capsys):
    argv, kw = BAD[param]
    name = NAMED.get(param, param)
    rc, err = _cli(argv, capsys)
    option = op.PARAMETERS[name][op.CLI]
    assert rc == 2, err
    assert f"point: {option} " in err and ": must be " in err, err
    assert "\n" not in err and len(err) <= 160, err  # one line: what is allowed, not why
    point = op.build("bem", **{k: v for k, v in kw.items() if k != "direction"},
                     direction=kw.get("direction"))
    with pytest.raises(BadInput) as exc:
        runner.validate(point)  # the Python door: the keyword, as typed there
    keyword = op.PARAMETERS[name][op.PYTHON]
    assert str(exc.value).startswith(f"{keyword}="), str(exc.value)


@pytest.mark.parametrize("name", ["prony", "profile", "surface"])
def test_an_unreadable_file_is_named_as_given_at_each_door(name, tmp_path, capsys):
    """On the command line by its option; in a spec dict given to `runner` by its key."""
    missing = str(tmp_path / "gone.txt")
    desc = {"kind": "file", "path": missing} if name == "surface" else {"path": missing}
    spec = dict(solver="bem", load=0.3, speed=1.0, nodes=64, **{name: desc})
    with pytest.raises(BadInput) as exc:
        runner.validate(spec)
    assert str(exc.value).startswith(f"{name} path {missing!r}: cannot read the file"), exc.value
    out = runner.run(spec)
    assert out["kind"] == "bad_input" and out["error"] == str(exc.value)
    rc, err = _cli(["point", "--solver", "bem", "--load", "0.3", "--speed", "1", f"--{name}",
                    missing], capsys)
    assert rc == 2 and f"--{name} {missing}: cannot read the file" in err, err


def test_every_parameter_of_the_table_has_an_option_and_a_keyword():
    for name, (option, keyword) in op.PARAMETERS.items():
        assert option.startswith("--") and keyword.isidentifier(), name
    # what the command line parses is named by the table (no option spelt elsewhere)
    from comparisons.cli import _common  # noqa: F401  (the parser's options)
    parser = cli.build_parser()
    point = next(a for a in parser._subparsers._group_actions[0].choices["point"]._actions
                 if "--load" in a.option_strings)
    assert op.option("load") in point.option_strings


def test_si_refusals_name_the_option_typed(capsys):
    rc, err = _cli(["point", "--solver", "analytic", "--units", "SI", "--load", "-1", "--speed",
                    "0.01", "--E0", "1e6", "--Einf", "3e6", "--tau-creep", "0.01", "--nu", "0.5",
                    "--wavelength", "0.01", "--amplitude", "0.001"], capsys)
    assert rc == 2 and "point: --load -1.0: must be a finite pressure > 0 [Pa]" in err


#: options that do not go together: (the point, the parameter refused, its value, why on the
#: command line, why in Python)
PAIRS = [
    ({"load": 0.1, "speed": 1.0, "prony": "p.txt", "ratio": 3.0}, "ratio", "3.0",
     "the --prony file fixes the material", "the prony file fixes the material"),
    ({"load": 0.1, "speed": 1.0, "profile": "z.txt", "hk": 2.0}, "hk", "2.0",
     "the --profile file fixes the indenter and its amplitude",
     "the profile file fixes the indenter and its amplitude"),
    ({"load": 0.1, "penetration": 0.5, "speed": 1.0}, "penetration", "0.5",
     "give one of --load and --penetration", "give one of load and penetration"),
]


@pytest.mark.parametrize("point, name, value, cli_why, python_why", PAIRS,
                         ids=[p[1] for p in PAIRS])
def test_options_that_do_not_go_together_are_named_as_typed_at_each_door(
        point, name, value, cli_why, python_why, capsys):
    from comparisons import verify
    from comparisons.verify._point import check_point
    with pytest.raises(BadInput) as exc:
        check_point(dict(point), op.CLI)
    assert str(exc.value) == f"--{name} {value} is not allowed here: {cli_why}"
    with pytest.raises(ValueError) as exc:  # the Python door: the keyword, never the option
        verify.assert_agrees({"mu": 0.1}, dict(point))
    assert str(exc.value) == f"{name}={value} is not allowed here: {python_why}"
    assert "--" not in str(exc.value)
    if name == "penetration":
        return  # on the command line the parser refuses --load with --penetration itself
    argv = ["verify", "--scalars", "s.jsonl"]  # and the command line says it in its own words
    for k, v in point.items():
        argv += [f"--{k}", str(v)]
    rc, err = _cli(argv, capsys)
    assert rc == 2 and err == f"python -m comparisons verify: --{name} {value} is not " \
        f"allowed here: {cli_why}", err


def test_command_line_only_pairs_name_their_options(capsys):
    rc, err = _cli(["verify", "--scalars", "s.jsonl", "--case", "sls-partial-v1", "--ratio",
                    "2"], capsys)
    assert rc == 2 and err.endswith("verify: --ratio 2.0 is not allowed here: --case gives the "
                                    "operating point"), err
    rc, err = _cli(["verify", "--scalars", "s.jsonl", "--load", "0.1", "--speed", "1",
                    "--prony", "p.txt", "--units", "SI"], capsys)
    assert rc == 2 and "verify: --units SI is not allowed here: SI points are" in err, err
    with pytest.raises(BadInput) as exc:  # point's own (the files are read before)
        op.build("bem", load=0.3, speed=1.0, hk=2.0, profile="z.txt")
    assert str(exc.value) == ("--hk is not allowed here: the --profile file fixes the indenter "
                              "and its amplitude")


def test_refusals_and_missing_options_have_one_form_at_each_door():
    assert str(op.refuse("max_nodes", "why", "3")) == "--max-nodes 3 is not allowed here: why"
    assert str(op.refuse("max_nodes", "why", "3", op.PYTHON)) == \
        "max_nodes=3 is not allowed here: why"
    assert str(op.refuse("units", "why")) == "--units is not allowed here: why"
    assert str(op.missing("tau_creep", "needs")) == "--tau-creep is missing: needs"
    assert str(op.missing("tau_creep", "needs", op.PYTHON)) == "tau_creep is missing: needs"
    for name in op.PARAMETERS:
        assert op.said(name) == op.option(name)
        assert op.said(name, op.PYTHON) == op.PARAMETERS[name][op.PYTHON]


def test_bem_only_options_are_refused_on_the_analytic_road_in_one_wording(capsys):
    for extra, option in ((["--rtol", "1e-3"], "--rtol"), (["--max-nodes", "64"], "--max-nodes"),
                          (["--thickness", "0.5", "--foundation", "bonded", "--nu", "0.5"],
                           "--thickness"), (["--surface", "bisinusoid"], "--surface")):
        rc, err = _cli(["point", "--solver", "analytic", "--load", "0.3", "--speed", "1", *extra],
                       capsys)
        assert rc == 2 and f"point: {option}" in err and "a BEM option" in err, err


def test_the_defaults_are_applied_in_one_place():
    a = op.build("analytic", load=0.3, speed=1.0)
    b = op.build("bem", load=0.3, speed=1.0)
    s = op.build("bem", load=0.3, speed=1.0, surface={"kind": "bisinusoid"})
    assert (a.ratio, a.hk, a.rtol) == (op.DEFAULTS["ratio"], op.DEFAULTS["hk"], None)
    assert (b.ratio, b.hk, b.rtol) == (3.0, 1.0, op.DEFAULTS["rtol"])
    assert s.hk is None and s.rtol == op.DEFAULTS["surface_rtol"] and s.direction == 0.0
    assert op.at("bem", 1.0, load=0.3).spec() == b.spec()
    assert op.ratio_of({}) == 3.0 and op.hk_of({"hk": 2}) == 2.0
    assert op.complete_case({"load": 0.3, "speed": 1.0, "prony": "p.txt"}) == {
        "load": 0.3, "speed": 1.0, "prony": "p.txt", "hk": 1.0}


def test_a_point_is_frozen_and_reads_like_its_spec():
    p = op.at("bem", 1.0, load=0.3, nodes=64)
    with pytest.raises(Exception):
        p.load = 0.5
    q = p.replace(load=0.5)
    assert q["load"] == 0.5 and p["load"] == 0.3 and q.get("layer") is None
    assert list(p) == list(op.SPEC_KEYS) and op.from_spec(p.spec()) == p


def test_the_depth_rule_of_a_layer():
    assert op.penetration_clears_layer(0.5, 1.0, 0.6)
    assert not op.penetration_clears_layer(0.6, 1.0, 0.6)


# ------------------------------------------------------------------------------ outputs
def _outputs(tmp):
    """Every command's output option, each to a path through a file (cannot be made)."""
    f = tmp / "afile"
    f.write_text("x")
    bad = str(f / "sub")
    return {
        "point --fields": ["point", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                           "--fields", bad + "/x.csv"],
        "sweep --fields": ["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                           "--fields", bad],
        "report --out": ["report", "--quick", "--out", bad],
        "suite --export": ["suite", "--export", bad],
        "suite --out": ["suite", "--check", "--cases", "sls-partial-v1", "--out", bad],
        "verify --out": ["verify", "--load", "0.3", "--speed", "1", "--scalars", str(f),
                         "--out", bad],
        "mastercurve --out": ["mastercurve", "--material", "x.txt", "--temperatures", "20",
                              "--speeds", "1", "--load", "1e5", "--wavelength", "0.01",
                              "--amplitude", "0.001", "--nu", "0.5", "--out", bad],
    }


@pytest.mark.parametrize("name", ["point --fields", "sweep --fields", "report --out",
                                  "suite --export", "suite --out", "verify --out"])
def test_an_output_that_cannot_be_written_is_bad_input_in_one_line(name, tmp_path, capsys):
    rc, err = _cli(_outputs(tmp_path)[name], capsys)
    option = name.split()[1]
    assert rc == 2, err
    assert f"{option} " in err and "is a file, not a folder" in err, err
    assert "does not exist" not in err and len(err) <= 160 + len(str(tmp_path)) * 2, err
    assert not os.path.exists(tmp_path / "afile" / "sub")


def test_missing_folders_on_the_way_to_an_output_are_made(tmp_path, capsys):
    out = tmp_path / "a" / "b" / "x.csv"
    rc, err = _cli(["point", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                    "--fields", str(out)], capsys)
    assert rc == 0 and out.is_file(), err
    folder = tmp_path / "c" / "d"
    rc, err = _cli(["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                    "--fields", str(folder)], capsys)
    assert rc == 0 and any(folder.iterdir()), err


def test_a_folder_that_cannot_be_made_is_refused_before_any_work(tmp_path, capsys):
    locked = tmp_path / "locked"
    locked.mkdir()
    locked.chmod(0o500)
    try:
        if os.access(locked, os.W_OK) and os.path.isdir("/proc"):
            # a user who may write anywhere (root, as in CI containers): /proc takes no folder
            rc, err = _cli(["report", "--quick", "--out", "/proc/viscosine-test/r"], capsys)
            assert rc == 2 and "cannot create /proc/viscosine-test/r" in err, err
        else:
            rc, err = _cli(["report", "--quick", "--out", str(locked / "r")], capsys)
            assert rc == 2 and "is not writable" in err, err
        assert len(err.strip().splitlines()) == 1
    finally:
        locked.chmod(0o700)
