"""Operating points solved for the command line: one (`point`) or many in order (`sweep`), each
record printed as one JSON line on standard output as soon as it is solved, its fields written on
request; warnings, failures and progress one line each on standard error.

The specs come validated (`comparisons.cli` resolves and checks every input before any work);
what a road still refuses is `BadInput`, what cannot be done `Failed` (`comparisons._errors`).
"""
from __future__ import annotations

import json
import os
import time

from . import runner
from .runner import read_files  # noqa: F401  (sweep's: each input file read once)
from ._errors import BadInput, Failed
from ._io import check_output_dir, stderr
from .fields import write_fields_csv
from .progress import Progress


def dump(record) -> str:
    """A record as one line of strict JSON (no NaN, no infinity)."""
    return json.dumps(record, allow_nan=False)


def describe(spec) -> str:
    """'load=0.3, speed=1.0' (or penetration=…): the point as the messages name it."""
    ctl = "load" if spec.get("load") is not None else "penetration"
    return f"{ctl}={spec[ctl]!r}, speed={spec['speed']!r}"


def write_fields(path, out, spec) -> None:
    """Write the fields of a solved point (`runner.run`'s ``out``) to the CSV file ``path`` (a
    surface's to the ``.npz`` file ``path``).

    Raises
    ------
    Failed
        when the file cannot be written.
    """
    f = out["fields"]
    try:
        if spec.get("surface") is not None:  # a surface's fields: .npz (conventions.md)
            f.save(path)
            return
        write_fields_csv(path, f, runner.fields_header(out["record"], spec, f))
    except OSError as exc:
        raise Failed(f"cannot write --fields {path} ({exc.strerror or exc})") from None


def point(spec, fields=None) -> bool:
    """Solve one spec and print its record; with ``fields`` (a file name) write its fields there.

    Returns True, or False when the point could not be solved (said on standard error).

    Raises
    ------
    BadInput
        a road refuses the point.
    Failed
        the fields cannot be written.
    """
    out = runner.run(spec, fields=fields is not None, deep=True)
    for w in out["warnings"]:
        stderr(f"point: warning: {w}")
    if out["kind"] == "bad_input":
        raise BadInput(f"{out['error']}")
    if not out["ok"]:
        stderr(f"point: {describe(spec)}: {out['error']}")
        return False
    if fields is not None:
        write_fields(fields, out, spec)
    print(dump(out["record"]), flush=True)
    return True


def _fmt_value(v):
    """Shortest exact text of a float for a file name: 0.3, 1 (not 1.0), 1e-05."""
    text = repr(float(v))
    return text[:-2] if text.endswith(".0") else text


def field_file_name(spec, used, index):
    """``<solver>_<control><value>_speed<value>.csv`` (``.npz`` for a surface); unique within
    `used` (then ``_<index>``).

    Only digits, letters, ``.``, ``+``, ``-`` and ``_`` appear (floats are finite, validated).
    """
    ctl = "load" if spec.get("load") is not None else "penetration"
    stem = f"{spec['solver']}_{ctl}{_fmt_value(spec[ctl])}_speed{_fmt_value(spec['speed'])}"
    ext = ".npz" if spec.get("surface") is not None else ".csv"
    name = f"{stem}{ext}"
    if name in used:
        name = f"{stem}_{index + 1}{ext}"
    used.add(name)
    return name


def sweep(base, control, values, speeds, *, workers=None, scheduler=None, fields=None,
          on_record=None):
    """Solve ``base`` at every (``control`` value, speed) pair, values in the outer loop, in
    this process, ``workers`` local processes or on the Dask cluster of ``scheduler``; print
    each record in order; with ``fields`` (a folder, made here) write each point's fields to
    ``fields/<field_file_name>``; ``on_record(index, record)`` after each printed record (the
    sweep's table and picture, `comparisons.sweep_outputs`).

    Returns
    -------
    (failed, refused): the points that could not be solved, and those of them a road refused.

    Raises
    ------
    BadInput
        bad ``workers`` or ``scheduler``, the cluster extra missing (`MissingPackage`),
        ``fields`` not creatable.
    Failed
        the scheduler cannot be reached (`ClusterError`).
    """
    from . import _cluster
    total = len(values) * len(speeds)
    ex = _cluster.executor(workers, scheduler)
    if fields is not None:
        check_output_dir("--fields", fields, create=True)

    def spec_at(i):
        return base.replace(**{control: values[i // len(speeds)],
                                "speed": speeds[i % len(speeds)]})

    specs = (spec_at(i) for i in range(total))
    fn = runner._run_with_fields if fields is not None else runner.run
    chunk = max(1, min(64, total // (8 * max(1, ex.workers))))
    used, failed, bad = set(), 0, 0
    progress = Progress()  # in place on a terminal, a line every few seconds in a log
    t0 = time.monotonic()
    with ex:
        for i, out in ex.imap(fn, specs, chunksize=chunk):
            spec = spec_at(i)
            where = f"sweep: point {i + 1}/{total} ({describe(spec)})"
            if isinstance(out, _cluster.Failure):
                out = {"ok": False, "kind": "failed", "error": f"could not solve: {out.error}",
                       "warnings": []}
            for w in out["warnings"]:
                progress.say(f"{where}: warning: {w}")
            if out["ok"] and fields is not None:
                path = os.path.join(fields, field_file_name(spec, used, i))
                try:
                    write_fields(path, out, spec)
                except Failed as exc:
                    out = {**out, "ok": False, "error": str(exc)}
            if out["ok"]:
                print(dump(out["record"]), flush=True)
                if on_record is not None:
                    on_record(i, out["record"])
            else:
                failed += 1
                bad += out["kind"] == "bad_input"
                progress.say(f"{where}: {out['error']}")
            now = time.monotonic()
            eta = ""
            if 10 <= i + 1 < total:  # an estimate only once a few points are in
                eta = f" (about {(now - t0) / (i + 1) * (total - i - 1):.0f} s left)"
            progress.update(f"sweep: {i + 1}/{total} points, {failed} failed, {now - t0:.1f} s"
                            f"{eta}", final=i + 1 == total)
    progress.close()
    if failed:
        stderr(f"sweep: {failed} of {total} points could not be solved")
    return failed, bad
