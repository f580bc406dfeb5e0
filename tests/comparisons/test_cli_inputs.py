"""The command line refuses every class of odd input up front: exit status 2, one line on standard
error naming the option, nothing on standard output, never a traceback (run in process: the
behaviour is that of `python -m comparisons`, which only calls `cli.main`)."""
import os

import pytest

from comparisons import cli
from comparisons import operating_point as op

POINT = ["point", "--solver", "bem", "--load", "0.3", "--speed", "1"]
APOINT = ["point", "--solver", "analytic", "--load", "0.3", "--speed", "1"]
SWEEP = ["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1"]
BSWEEP = ["sweep", "--solver", "bem", "--load", "0.3", "--speed", "1"]

# argv (with {tmp}, {fifo}, {binary}, {latin1}, {file}, {profile}, {prony} filled in), fragment
ODD = [
    # meshes: below 8, beyond the BEM's cap, not an integer, on every subcommand that takes one
    (POINT + ["--nodes", "7"], "--nodes 7"),
    (POINT + ["--nodes", "0"], "--nodes 0"),
    (POINT + ["--nodes", "1000000000"], "--nodes 1000000000"),
    (POINT + ["--nodes", "12.5"], "not an integer"),
    (BSWEEP + ["--nodes", "7"], "--nodes 7"),
    (["crosscheck", "--nodes", "0"], "--nodes 0"),
    (["crosscheck", "--nodes", "7"], "--nodes 7"),
    (["crosscheck", "--nodes", "1024", "1000000000"], "--nodes 1000000000"),
    (APOINT + ["--fields", "{tmp}/f.csv", "--nodes", "4"], "--nodes 4"),
    # --fields: empty, missing folder, a folder, a device, a FIFO
    (POINT + ["--fields", ""], "--fields ''"),
    (POINT + ["--fields", "{file}/f.csv"], "file.txt is a file, not a folder"),
    (POINT + ["--fields", "{tmp}"], "a folder"),
    (POINT + ["--fields", "/dev/null"], "a device"),
    (POINT + ["--fields", "{fifo}"], "a FIFO"),
    (SWEEP + ["--fields", "{file}"], "an existing file"),
    (SWEEP + ["--fields", "{file}/dir"], "file.txt is a file, not a folder"),
    (SWEEP + ["--fields", ""], "--fields ''"),
    # input files: binary, not UTF-8, a FIFO (must not block), a folder, missing, empty name
    (POINT + ["--profile", "{binary}"], "--profile"),
    (POINT + ["--profile", "{binary}"], "binary"),
    (POINT + ["--prony", "{latin1}"], "not UTF-8"),
    (POINT + ["--profile", "{fifo}"], "a FIFO"),
    (POINT + ["--prony", "{tmp}"], "a folder"),
    (POINT + ["--prony", "{tmp}/missing.txt"], "cannot read"),
    (POINT + ["--prony", ""], "--prony ''"),
    (BSWEEP + ["--prony", "{latin1}"], "--prony"),
    # options that do not apply to the inputs
    (["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--hk", "2", "--profile",
      "{profile}"], "--hk"),
    (["point", "--solver", "bem", "--load", "0.3", "--speed", "1", "--ratio", "2", "--prony",
      "{prony}"], "--ratio"),
    (APOINT + ["--profile", "{profile}"], "--profile"),
    (APOINT + ["--prony", "{prony}"], "--prony"),
    (APOINT + ["--nodes", "64"], "--nodes"),
    (APOINT + ["--rtol", "1e-3"], "--rtol"),
    (APOINT + ["--max-nodes", "4096"], "--max-nodes"),
    (SWEEP + ["--nodes", "64"], "--nodes"),
    (POINT + ["--nodes", "1024", "--rtol", "1e-3"], "--rtol"),
    (POINT + ["--nodes", "1024", "--max-nodes", "4096"], "--max-nodes"),
    # point takes exactly one value; an option is given once; abbreviations are not guessed
    (["point", "--solver", "analytic", "--load", "0.3", "--speed", "1", "2"], "use sweep"),
    (["point", "--solver", "analytic", "--load", "0.3", "0.4", "--speed", "1"], "use sweep"),
    (APOINT + ["--load", "0.4"], "--load given twice"),
    (SWEEP + ["--speed", "2"], "--speed given twice"),
    (APOINT + ["--rat", "2"], "unrecognized arguments"),
    (["point", "--solver", "analytic", "--load", "0.3", "--penetration", "0.5", "--speed", "1"],
     "not allowed with"),
    (["point", "--solver", "analytic", "--load", "0.3"], "--speed"),
    (["point", "--solver", "tamaas", "--load", "0.3", "--speed", "1"], "--solver"),
    # values outside the roads' accepted ranges
    (["point", "--solver", "analytic", "--load", "nan", "--speed", "1"], "load"),
    (["point", "--solver", "analytic", "--load", "1e400", "--speed", "1"], "load"),
    (["point", "--solver", "bem", "--load", "-1", "--speed", "1"], "load"),
    (["point", "--solver", "bem", "--penetration", "1.5", "--speed", "1"], "penetration"),
    (["point", "--solver", "analytic", "--load", "0.3", "--speed", "-1"], "speed"),
    (["point", "--solver", "bem", "--load", "0.3", "--speed", "inf"], "speed"),
    (APOINT + ["--ratio", "0.5"], "ratio"),
    (POINT + ["--hk", "0"], "hk"),
    (["sweep", "--solver", "analytic", "--load", "0.3", "-1", "--speed", "1"], "load"),
    # log ranges
    (["sweep", "--solver", "analytic", "--load", "1:10:0", "--speed", "1"], "COUNT"),
    (["sweep", "--solver", "analytic", "--load", "0:10:5", "--speed", "1"], "START and STOP"),
    (["sweep", "--solver", "analytic", "--load", "1:10", "--speed", "1"], "START:STOP:COUNT"),
    (["sweep", "--solver", "analytic", "--load", "1:2:x", "--speed", "1"], "COUNT"),
    (["sweep", "--solver", "analytic", "--load", "1:2:1", "--speed", "1"], "COUNT"),
    (["sweep", "--solver", "analytic", "--load", "1:2:10000000", "--speed", "1"], "COUNT"),
    # a value starting with '-' is a value (argparse would take it for an option)
    (["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "-1:10:5"],
     "argument --speed: '-1:10:5': START and STOP of a log range must be finite and > 0"),
    (["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1", "-1:10:5"],
     "'-1:10:5': START and STOP"),
    (["point", "--solver", "analytic", "--load", "0.3", "--speed", "-1e-3"], "--speed -0.001"),
    (["point", "--solver", "bem", "--load", "-.5", "--speed", "1"], "--load -0.5"),
    # parallelism
    (SWEEP + ["--workers", "0"], "--workers 0"),
    (SWEEP + ["--workers", "-1"], "--workers -1"),
    (SWEEP + ["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler"),
    (["report", "--workers", "0"], "--workers 0"),
    (["report", "--workers", "-1"], "--workers -1"),
    (["report", "--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], "--scheduler"),
    (["report", "--out", "{file}"], "an existing file"),
    (["report", "--out", ""], "--out ''"),
    # bench and crosscheck
    (["bench", "--points", "0"], "--points 0"),
    (["bench", "--points", "-5"], "--points -5"),
    (["bench", "--cluster", "--max-log2n", "10"], "--max-log2n"),
    (["bench", "--max-log2n", "40"], "--max-log2n 40"),
    (["bench", "--light"], "--light"),
    (["bench", "--bem", "--light"], "--light"),
    (["bench", "--seed", "3"], "--seed"),
    (["bench", "--materials", "--light"], "--light"),
    (["bench", "--materials", "--honesty"], "not allowed with"),
    (["bench", "--workers", "2"], "--workers"),
    (["bench", "--honesty", "--workers", "2"], "--workers"),
    (["bench", "--materials", "--workers", "0"], "--workers 0"),
    (["crosscheck", "--tolerances", "--nodes", "1024"], "not allowed with"),
    ([], "required"),
    (["frobnicate"], "invalid choice"),
]


@pytest.fixture
def paths(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # report's default --out must never land in the source tree
    fifo = tmp_path / "fifo"
    os.mkfifo(fifo)
    (tmp_path / "binary.txt").write_bytes(b"J0 1.0\n\x00\x01\x02\n")
    (tmp_path / "latin1.txt").write_bytes("J0 1.0 # caf\xe9\n0.5 1.0\n".encode("latin-1"))
    (tmp_path / "file.txt").write_text("not a folder\n")
    (tmp_path / "profile.txt").write_text("\n".join(str(v) for v in
                                                   [1, 0.7, 0, -0.7, -1, -0.7, 0, 0.7]) + "\n")
    (tmp_path / "prony.txt").write_text("J0 1.0\n0.5 1.0\n")
    return {"tmp": str(tmp_path), "fifo": str(fifo), "binary": str(tmp_path / "binary.txt"),
            "latin1": str(tmp_path / "latin1.txt"), "file": str(tmp_path / "file.txt"),
            "profile": str(tmp_path / "profile.txt"), "prony": str(tmp_path / "prony.txt")}


@pytest.mark.parametrize("argv,fragment", ODD, ids=[" ".join(a)[:60] for a, _ in ODD])
def test_odd_input_is_refused_up_front(argv, fragment, paths, capsys):
    argv = [a.format(**paths) for a in argv]
    rc = cli.main(argv)
    out = capsys.readouterr()
    assert rc == 2, out.err
    assert out.out == ""
    lines = out.err.strip().splitlines()
    assert len(lines) == 1, out.err
    assert "Traceback" not in out.err
    assert fragment in lines[0], lines[0]
    assert lines[0].startswith("python -m comparisons")
    assert not os.path.exists(os.path.join(paths["tmp"], "report"))  # no work was done


def test_help_of_point_matches_what_point_accepts(capsys):
    assert cli.main(["point", "--help"]) == 0
    text = capsys.readouterr().out
    assert "--speed S " in text and "[S ...]" not in text and "[P ...]" not in text
    assert cli.main(["sweep", "--help"]) == 0
    text = capsys.readouterr().out
    assert "--speed S [S ...]" in text and "START:STOP:COUNT" in text
    # every option point's help shows, point parses
    sub = next(a for a in cli.build_parser()._actions if a.dest == "command")
    point = sub.choices["point"]
    shown = {o for a in point._actions for o in a.option_strings}
    assert {"--solver", "--load", "--penetration", "--speed", "--ratio", "--hk", "--nodes",
            "--rtol", "--max-nodes", "--profile", "--prony", "--fields"} <= shown
    for a in point._actions:
        if a.dest in ("load", "penetration", "speed"):
            assert a.nargs is None  # one value


def test_every_subcommand_has_help(capsys):
    for name in ("point", "sweep", "report", "crosscheck", "bench", "suite", "verify"):
        assert cli.main([name, "--help"]) == 0
        assert "usage: python -m comparisons " + name in capsys.readouterr().out


def test_a_subcommand_in_its_own_module_registers_with_one_line(monkeypatch, capsys):
    import sys
    import types
    mod = types.ModuleType("comparisons.cli.demo")

    def add_parser(sub):
        p = sub.add_parser("demo", help="a demonstration")
        p.add_argument("--x", type=int, default=1)
        p.set_defaults(run=mod.run)
    mod.add_parser = add_parser
    mod.run = lambda args: 0 if args.x == 5 else 1
    monkeypatch.setitem(sys.modules, "comparisons.cli.demo", mod)
    monkeypatch.setattr(cli, "SUBCOMMANDS", cli.SUBCOMMANDS + (mod,))
    assert cli.main(["demo", "--x", "5"]) == 0
    assert cli.main(["demo", "--y"]) == 2
    assert "unrecognized arguments: --y" in capsys.readouterr().err


def test_a_broken_subcommand_module_does_not_take_the_others_down(monkeypatch, capsys):
    def broken(sub):
        raise ImportError("no module named 'something'")
    import types
    import sys
    mod = types.ModuleType("comparisons.cli.broken")
    mod.add_parser = broken
    mod.run = lambda args: 0
    monkeypatch.setitem(sys.modules, "comparisons.cli.broken", mod)
    monkeypatch.setattr(cli, "SUBCOMMANDS", cli.SUBCOMMANDS + (mod,))
    assert cli.main(["point", "--solver", "analytic", "--load", "0.3", "--speed", "1"]) == 0
    capsys.readouterr()
    assert cli.main(["broken", "--anything"]) == 1
    err = capsys.readouterr().err
    assert err.strip() == ("python -m comparisons broken: unavailable (ImportError: no module "
                           "named 'something')")


def test_help_of_point_and_sweep_shows_the_accepted_range_of_each_input(capsys):
    import analytic
    import bem
    for name in ("point", "sweep"):
        assert cli.main([name, "--help"]) == 0
        text = " ".join(capsys.readouterr().out.split())
        assert "accepted inputs (analytic.ACCEPTED and bem.ACCEPTED" in text
        for option, key in (("--load", "load"), ("--penetration", "penetration"),
                            ("--speed", "speed"), ("--ratio", "ratio"), ("--hk", "hk"),
                            ("--nodes", "nodes"), ("--rtol", "rtol"), ("--max-nodes", "max_nodes"),
                            ("--prony", "material")):
            for road, table in (("analytic", analytic.ACCEPTED), ("bem", bem.ACCEPTED)):
                if key in table:
                    allowed = " ".join(op.allowed_part(table[key][2]).split())
                    assert f"{road}: {allowed}" in text, (name, option, road)
        assert "analytic: a mean pressure p̃∞ = p∞(1 − ν²)/E0 in [1e-40, 1e+40]" in text
        # the literal range (the loop above reads it from the tables): both roads to 1e8
        assert "bem: E∞/E0 > 1 + 1e-12 and ≤ 1e+08" in text
        assert "analytic: E∞/E0 > 1 and ≤ 1e+08" in text


def test_an_unwritable_report_folder_is_refused_like_point_and_sweep(read_only_folder, capsys):
    locked = read_only_folder
    for out, where in ((locked / "report", f"the folder {locked} is not writable"),
                       (locked, "the folder is not writable")):
        assert cli.main(["report", "--out", str(out)]) == 2
        err = capsys.readouterr().err.strip()
        assert err == f"python -m comparisons report: --out {out}: {where}"
    assert cli.main(["sweep", "--solver", "analytic", "--load", "0.3", "--speed", "1",
                     "--fields", str(locked)]) == 2
    assert capsys.readouterr().err.strip().endswith(f"--fields {locked}: the folder is not "
                                                    "writable")
    assert not (locked / "report").exists()
