"""The results store never trusts a broken file: truncated, empty or garbage JSON and .npz files,
and a file that holds another spec or comes from another version, are re-run with a note; temporary names are unique per
process, so two runs on one folder never collide; `report --resume` goes through it."""
import json
import multiprocessing
import os

import numpy as np
import pytest

from comparisons import operating_point as op
from comparisons import report, runner
from comparisons.store import Store, StoreError, key

SPEC = op.at("bem", 1.0, load=0.3, nodes=64)
OTHER = op.at("bem", 2.0, load=0.3, nodes=64)


@pytest.fixture(scope="module")
def solved():
    out = runner.run(SPEC, fields=True)
    assert out["ok"], out["error"]
    return out


@pytest.fixture
def store(tmp_path, solved):
    notes = []
    st = Store(str(tmp_path / "results"), note=notes.append)
    st.put(SPEC, solved, fields=True)
    st.notes = notes
    return st


def _path(st, spec, ext):
    return os.path.join(st.folder, f"{key(spec)}.{ext}")


def test_round_trip(store, solved):
    assert store.has(SPEC, fields=True) and store.notes == []
    doc = store.get(SPEC, fields=True)
    assert doc["ok"] and doc["record"] == solved["record"]
    assert np.array_equal(doc["fields"]["pressure"], solved["fields"].pressure)
    assert not store.has(OTHER) and store.notes == []  # missing is not worth a note


def _truncate(path):
    data = open(path, "rb").read()
    open(path, "wb").write(data[: len(data) // 2])


def _empty(path):
    open(path, "wb").close()


def _garbage(path):
    open(path, "wb").write(b"\x00\xff\xfe garbage \x89PNG\r\n")


def _valid_json_not_a_result(path):
    open(path, "w").write("[1, 2, 3]")


@pytest.mark.parametrize("damage", [_truncate, _empty, _garbage, _valid_json_not_a_result])
def test_a_broken_json_is_run_again_with_a_note(damage, store):
    damage(_path(store, SPEC, "json"))
    assert not store.has(SPEC)
    assert len(store.notes) == 1 and "running it again" in store.notes[0]
    with pytest.raises(StoreError):
        store.get(SPEC)


@pytest.mark.parametrize("damage", [_truncate, _empty, _garbage])
def test_a_broken_npz_is_run_again_when_its_fields_are_needed(damage, store):
    damage(_path(store, SPEC, "npz"))
    assert store.has(SPEC)                      # the scalars alone are fine
    assert not store.has(SPEC, fields=True)     # the fields are not
    assert "npz is unreadable" in store.notes[0]


def test_npz_with_wrong_arrays_is_not_trusted(store):
    path = _path(store, SPEC, "npz")
    for arrays in ({"x_over_lambda": np.zeros(4)},
                   {n: np.zeros(4 + (n == "gap")) for n in ("x_over_lambda", "pressure", "displacement", "gap")},
                   {n: np.full(4, np.nan) for n in ("x_over_lambda", "pressure", "displacement", "gap")}):
        np.savez(open(path, "wb"), **arrays)
        assert not store.has(SPEC, fields=True)


@pytest.mark.parametrize("edit,fragment", [
    (lambda d: d["spec"].update(speed=3.0), "holds another one"),
    (lambda d: d["record"].update(penetration=2.0), "outside (0, 1]"),
    (lambda d: d["record"].update(mu=None), "mu"),
    (lambda d: d["record"].pop("ka"), "missing"),
    (lambda d: d.update(ok="yes"), "true/false"),
    (lambda d: d["record"].update(load=0.4), "asked for"),
    (lambda d: d.update(version="0.2.0"), "stored by viscosine 0.2.0"),  # keys meant else
    (lambda d: d.pop("version"), "stored by viscosine None"),
])
def test_a_record_that_does_not_match_or_is_not_valid_is_not_trusted(edit, fragment, store):
    path = _path(store, SPEC, "json")
    doc = json.load(open(path))
    edit(doc)
    json.dump(doc, open(path, "w"))
    assert store.problem(SPEC) is not None and fragment in store.problem(SPEC)


def test_non_finite_numbers_in_a_record_are_not_trusted(store):
    path = _path(store, SPEC, "json")
    text = open(path).read().replace('"mu": ', '"mu": NaN, "mu_was": ', 1)
    open(path, "w").write(text)
    assert "not a finite number" in store.problem(SPEC)


def test_temporary_names_are_unique_per_process_and_nothing_is_left(tmp_path, solved, monkeypatch):
    import comparisons.store as store_mod
    seen = []
    real = os.replace
    monkeypatch.setattr(store_mod.os, "replace", lambda a, b: (seen.append(a), real(a, b))[1])
    st = Store(str(tmp_path), note=lambda _: None)
    st.put(SPEC, solved, fields=True)
    st.put(SPEC, solved, fields=True)
    names = [os.path.basename(s) for s in seen]
    assert len(names) == 4 and len(set(names)) == 4
    assert all(f".{os.getpid()}." in n and n.endswith(".part") for n in names)
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(
        [f"{key(SPEC)}.json", f"{key(SPEC)}.npz"])


def _writer(folder, out, n):
    st = Store(folder, note=lambda _: None)
    for _ in range(n):
        st.put(SPEC, out, fields=True)


def test_two_processes_writing_one_folder_never_collide(tmp_path, solved):
    """Before: both wrote `<key>.part.json`, and one os.replace found its file gone."""
    ctx = multiprocessing.get_context("fork")
    procs = [ctx.Process(target=_writer, args=(str(tmp_path), solved, 40)) for _ in range(2)]
    for p in procs:
        p.start()
    for p in procs:
        p.join(60)
    assert [p.exitcode for p in procs] == [0, 0]
    st = Store(str(tmp_path), note=lambda _: None)
    assert st.has(SPEC, fields=True)
    assert not [p for p in tmp_path.iterdir() if p.name.endswith(".part")]


def test_report_resume_reruns_only_what_is_missing_or_broken(tmp_path, monkeypatch, capsys):
    jobs = [(op.at("bem", s, load=0.3, nodes=64), s == 1.0) for s in (0.5, 1.0, 2.0)]
    monkeypatch.setattr(report, "bem_runs", lambda cfg: list(jobs))
    monkeypatch.setattr(report, "tamaas_runs", lambda cfg: [])
    cfg = report.config(True, workers=1)
    st = Store(str(tmp_path))
    report.execute(cfg, st, resume=False)
    capsys.readouterr()
    _truncate(_path(st, jobs[1][0], "npz"))        # the fields of the second run
    _garbage(_path(st, jobs[2][0], "json"))        # the scalars of the third
    mtime = os.stat(_path(st, jobs[0][0], "json")).st_mtime_ns
    report.execute(cfg, st, resume=True)
    err = capsys.readouterr().err
    assert "report: 3 BEM runs, 1 already done" in err
    assert err.count("running it again") == 2 and "Traceback" not in err
    assert os.stat(_path(st, jobs[0][0], "json")).st_mtime_ns == mtime
    assert all(st.has(spec, f) for spec, f in jobs)


def test_the_one_text_writer_is_utf8_and_atomic(tmp_path, monkeypatch):
    """comparisons._io.write_text: UTF-8 with '\\n' whatever the locale (the report's μ, ∞),
    the folder made, and nothing left behind by a write that fails."""
    import os

    from comparisons import _io
    path = tmp_path / "a" / "report.md"
    _io.write_text(path, "μ = 0.30, E∞/E0 = 3\n")
    assert path.read_bytes() == "μ = 0.30, E∞/E0 = 3\n".encode("utf-8")

    def broken(src, dst):
        raise OSError(28, "No space left on device")
    monkeypatch.setattr(os, "replace", broken)
    with pytest.raises(OSError):
        _io.write_text(path, "other")
    assert path.read_bytes() == "μ = 0.30, E∞/E0 = 3\n".encode("utf-8")
    assert sorted(p.name for p in path.parent.iterdir()) == ["report.md"]
