"""``python -m comparisons verify``: the command, from its parsed options to the verdict
printed and the report written.

Exit status 0 when every tolerance holds, 1 otherwise (or when the solver under test, the
reference or the writing of the report fails), 2 for bad input (one line on standard error,
``python -m comparisons verify: `` then the option, the value and what is allowed, under 400
characters).
"""
from __future__ import annotations

import hashlib
import math
import os
import sys
import time
from pathlib import Path

from .. import operating_point as op
from .. import suite as _suite
from .._errors import BadInput, Failed, bad_input
from .._io import check_output_dir
from ..fields import MIN_POINTS, read_fields_csv
from ..suite_inputs import ProfileShape
from ._compare import evaluate
from ._inputs import load_callable, read_scalars_jsonl
from ._point import is_surface_case, point_from_args
from ._quantities import ALL_KEYS
from ._reference import reference_for
from ._report import fmt, write_report
from ._results import (DEFAULT_DT_CELLS, Result, as_fields, peer_tamaas, results_from_fields,
                       tamaas_module, to_conventions)
from ._surface_fields import OWN_KEYS, as_surface_fields, check_fields, read_npz
from ._surface_judge import evaluate as surface_evaluate
from ._surface_judge import surface_result
from ._surface_reference import SURFACE_DEFAULT_NODES, SURFACE_KEYS, surface_reference
from ._surface_report import write_report as write_surface_report
from ._tolerances import DEFAULT_RTOL

DEFAULT_NODES = (1024, 2048, 4096, 8192)
#: the default ladder of ``--peer tamaas`` (grid nodes; each is a dt study, see DEFAULT_DT_CELLS):
#: Tamaas's time grows about 4.3 times per doubling of N (N steps of N log N), so the ladder stops
#: at 1024 (measured: 1.7, 7 and 40 s for the three dt studies at p̃∞ = 0.15, V/V0 = 1.058)
DEFAULT_PEER_NODES = (256, 512, 1024)

#: verify's one-line messages stay under 400 characters with the command's prefix
MESSAGE_LIMIT = 399 - len("python -m comparisons verify: ")


def run(args) -> int:
    """`python -m comparisons verify` from its parsed options (``args``: an argparse namespace
    of `comparisons.cli.verify`); prints the verdict; exit status 0 (pass) or 1 (fail).

    Bad input is raised as `comparisons._errors.BadInput` (one line on standard error with the
    command's prefix, exit status 2) and a failure of the solver under test, of the reference or
    of writing the report as `comparisons._errors.Failed` (exit status 1), each within
    `MESSAGE_LIMIT` characters.
    """
    try:
        return _run(args)
    except BadInput as exc:
        raise BadInput(_short(exc)) from None


def _run(args) -> int:
    """`run`, its messages of bad input at any length."""
    if args.case and is_surface_case(args.case):
        return _run_surface(args)
    tols, rtol, rtol_given = _tolerance_options(args)
    point, case, si = point_from_args(args)
    nodes, cells = _resolutions(args)
    check_output_dir("--out", args.out, create=False)  # before any work, as point, sweep do
    inputs = {}
    shape = ProfileShape(point, base="/")
    if args.fields:
        results, label = _from_fields(args, shape, si, inputs)
    elif args.scalars:
        results, label = _from_scalars(args, inputs)
    else:
        results, label = _from_solver(args, point, shape, si, nodes, cells, inputs)
    if args.units == "SI":
        inputs["units"] = f"SI (E0 = {si[0]:g} Pa, nu = {si[1]:g}, amplitude = {si[2]:g} m)"
    try:
        ref = reference_for(point, case)
        ev = evaluate(results, ref, rtol=rtol, tol=tols, rtol_given=rtol_given,
                      si=si is not None)
    except RuntimeError as exc:
        raise Failed(_short(exc)) from None
    try:
        write_report(args.out, ev, point, ref, results, label, inputs, case,
                     figures=not args.no_figures)
    except OSError as exc:
        raise Failed(_short(f"--out {args.out}: cannot write the report "
                            f"({exc.strerror or exc})")) from None
    _print_verdict(ev)
    failed = f" ({', '.join(ev['failed'])})" if ev["failed"] else ""
    summary = f"verify: {ev['verdict']}{failed}; report in {os.path.join(args.out, 'report.md')}"
    print(summary, file=sys.stderr)
    return 0 if ev["verdict"] == "PASS" else 1


def _tolerance_options(args, keys=ALL_KEYS):
    """(tolerances asked for per quantity, rtol, whether rtol was asked for), checked."""
    tols = _parse_tols(args.tol, keys)
    rtol_given = args.rtol is not None
    rtol = args.rtol if rtol_given else DEFAULT_RTOL
    if not (math.isfinite(rtol) and rtol > 0):
        raise op.must_be("--rtol", rtol, "a finite tolerance > 0")
    return tols, rtol, rtol_given


def _parse_tols(items, keys=ALL_KEYS):
    """{quantity: tolerance} of the ``--tol NAME=VALUE`` options, checked (``keys``: the
    quantities of the case's geometry)."""
    out = {}
    for it in items:
        if "=" not in it:
            raise bad_input("--tol", it, "not NAME=VALUE", ", ".join(keys))
        k, v = it.split("=", 1)
        k = k.strip()
        if k not in keys:
            raise bad_input("--tol", it, f"unknown quantity {k!r}", ", ".join(keys))
        try:
            val = float(v)
        except ValueError:
            raise op.must_be("--tol", it, "a finite tolerance > 0") from None
        if not (math.isfinite(val) and val > 0):
            raise op.must_be("--tol", it, "a finite tolerance > 0")
        out[k] = val
    return out


def _resolutions(args):
    """(the resolutions N of ``--callable`` or ``--peer``, the peer's time steps in cell
    crossings coarse to fine or None), checked."""
    peer = bool(args.peer)
    nodes = args.nodes or list(DEFAULT_PEER_NODES if peer else DEFAULT_NODES)
    if any(n < MIN_POINTS for n in nodes):
        raise op.must_be("--nodes", min(nodes), f"integers >= {MIN_POINTS}")
    if len(set(nodes)) != len(nodes):
        raise bad_input("--nodes", " ".join(map(str, nodes)), "repeated", "distinct resolutions")
    if args.nodes and not (args.callable or peer):
        raise bad_input("--nodes", " ".join(map(str, args.nodes)), "without --callable or --peer",
                        "--nodes with --callable or --peer (fields files carry their own N)")
    for opt, val in (("--dt", args.dt), ("--dt-cells", args.dt_cells)):
        if val is not None and not peer:
            raise bad_input(opt, val if not isinstance(val, list) else " ".join(map(str, val)),
                            "without --peer", f"{opt} with --peer tamaas")
    if args.dt is not None and not (math.isfinite(args.dt) and args.dt > 0):
        raise op.must_be("--dt", args.dt, "a finite time step > 0 in units of τ")
    cells = None
    if args.dt_cells is not None:
        cells = sorted(args.dt_cells, reverse=True)
        if not all(math.isfinite(c) and c > 0 for c in cells) or len(set(cells)) != len(cells):
            raise op.must_be("--dt-cells", " ".join(f"{c:g}" for c in args.dt_cells),
                             "distinct time steps > 0 in cell crossings T/N, e.g. 4 2 1")
    return nodes, cells


def _from_fields(args, shape, si, inputs):
    """(results, label) of ``--fields``, each file's hash in ``inputs``."""
    fl = []
    for path in args.fields:
        f = read_fields_csv(path, "--fields")
        if si:
            f = to_conventions(f, *si)
        fl.append(f)
        inputs[f"--fields {path}"] = f"sha256 {_sha(path)}, {f['x_over_lambda'].size} rows"
    if len({f["x_over_lambda"].size for f in fl}) != len(fl):
        raise bad_input("--fields", " ".join(args.fields), "two files with the same number "
                        "of rows", "one file per resolution")
    label = args.label or "fields from " + ", ".join(Path(p).name for p in args.fields)
    return results_from_fields(fl, shape), label


def _from_scalars(args, inputs):
    """(results, label) of ``--scalars``, the file's hash in ``inputs``."""
    recs = read_scalars_jsonl(args.scalars)
    inputs[f"--scalars {args.scalars}"] = f"sha256 {_sha(args.scalars)}"
    results = [Result(r["nodes"], None, r["scalars"], [], "solver") for r in recs]
    return results, args.label or f"scalars from {Path(args.scalars).name}"


def _from_solver(args, point, shape, si, nodes, cells, inputs):
    """(results, label) of ``--callable`` or ``--peer``: the solver under test at each N."""
    call, label, opt = _solver_under_test(args, point, nodes, cells, inputs)
    fl, scs, ers, extrapolated = [], [], [], []
    for n in sorted(nodes):
        obj = _solve(call, n, label)
        f = as_fields(obj, opt, label)
        if si:
            f = to_conventions(f, *si)
        fl.append(f)
        sc = getattr(obj, "scalars", None)
        scs.append(sc() if callable(sc) else sc)
        err = getattr(obj, "error", None)
        ers.append({k: float(v) for k, v in err.items() if v is not None}
                   if isinstance(err, dict) else None)
        extrapolated.append(len(getattr(obj, "cells_per_step", ()) or ()) >= 2)
    results = results_from_fields(fl, shape, nodes=sorted(nodes), solver_scalars=scs)
    for r, e, x in zip(results, ers, extrapolated):
        r.errors = e or None
        if x:
            r.source += "; extrapolated to dt → 0"
    return results, label


def _solver_under_test(args, point, nodes, cells, inputs):
    """(call: N → the solver's output, label, option) of ``--callable`` or ``--peer tamaas``,
    what it is in ``inputs``."""
    if args.callable:
        fn = load_callable(args.callable)
        inputs["--callable"] = args.callable
        return (lambda n: fn(dict(point), n)), args.label or args.callable, "--callable"
    if point.get("layer"):
        raise bad_input("--peer", "tamaas", f"with a case on a layer ({args.case})",
                        "the sinusoid on the standard linear solid half-plane")
    if not _suite.two_roads(point):
        raise bad_input("--peer", "tamaas", "with --profile/--prony",
                        "the sinusoid on the standard linear solid")
    if point.get("load") is None:
        raise bad_input("--peer", "tamaas", "with --penetration", "--load")
    tamaas_module()  # bad input now, before any work, if it is missing
    label = args.label or "Tamaas (comparisons.peers.tamaas)"
    runs = len(nodes) * (1 if args.dt is not None else len(cells or DEFAULT_DT_CELLS))
    progress = _peer_progress("Tamaas", runs)
    ladder = cells or DEFAULT_DT_CELLS
    inputs["--peer"] = "tamaas" + (f", dt = {args.dt:g} τ" if args.dt is not None else
                                   ", dt = " + ", ".join(f"{c:g}" for c in ladder) + " × T/N, "
                                   + ("extrapolated to dt → 0" if len(ladder) >= 2 else
                                      "no extrapolation"))
    return (lambda n: peer_tamaas(point, n, args.dt, cells, progress)), label, "--peer"


def _solve(call, n, label):
    """The solver under test's output at N = n; its failure is its verdict (Failed)."""
    try:
        obj = call(n)
    except Exception as exc:  # the solver under test failed: its verdict, not ours
        raise Failed(_short(f"{label} failed at N = {n}: {type(exc).__name__}: {exc}")) from None
    if getattr(obj, "success", True) is False:
        raise Failed(_short(f"{label} did not converge at N = {n}: "
                            f"{getattr(obj, 'message', '')}"))
    return obj


def _print_verdict(ev):
    """The verdict on standard output: a line per quantity, tolerance, floor and diagnosis, and
    the orders of a convergence study."""
    for r in ev["quantities"]:
        own = ("" if r.get("solver_error") is None else
               f"; the solver's estimated error {r['solver_error']:.1e}")
        floor = f" + floor {r['derivation_floor']:.1e}" if r.get("floor_kind") else ""
        print(f"{'PASS' if r['passed'] else 'FAIL'} {r['key']} ({r['label']}): "
              f"{fmt(r['value'], '.10g')} vs {fmt(r['reference'], '.10g')}, difference "
              f"{fmt(r['difference'], '.2e')} ({r['measure']}), tolerance "
              f"{r['tolerance']:.1e}{floor}{own}")
    for line in ev["tolerances"]:
        print(f"tolerance: {line}")
    for line in ev.get("floors", []):
        print(f"floor: {line}")
    conv = ev["convergence"]
    if conv:
        print("orders vs reference: " + ", ".join(
            f"{k} {fmt(q['order_vs_reference'], '.2f')}" for k, q in conv["quantities"].items()))
        for line in conv.get("notes", []):
            print(f"orders: {line}")
    for line in ev["diagnosis"]:
        print(f"diagnosis: {line}")


# ------------------------------------------------------------------------------ surface cases
#: what --scalars may hold on a surface case
SURFACE_SCALARS_ALLOWED = ("JSON lines of mu, mu_lateral, penetration, "
                           "contact_fraction, load (see --help)")


def _run_surface(args) -> int:
    """`_run` on a surface case: 2-D fields (``.npz``), scalars or a callable against the
    case's certified values (`_surface_reference`, `_surface_judge`, `_surface_report`)."""
    if args.peer:
        raise bad_input("--peer", args.peer, f"with a surface case ({args.case})",
                        "a line case (the sinusoid on the standard linear solid half-plane)")
    if args.units == "SI":
        raise bad_input("--units", "SI", f"with a surface case ({args.case})",
                        "the conventions' units (docs/conventions.md, 'Surfaces')")
    point, case, _ = point_from_args(args)
    tols, rtol, rtol_given = _tolerance_options(args, SURFACE_KEYS)
    if args.nodes and not args.callable:
        raise bad_input("--nodes", " ".join(map(str, args.nodes)), "without --callable",
                        "--nodes with --callable (fields files carry their own N)")
    nodes = list(args.nodes or SURFACE_DEFAULT_NODES)
    if any(n < MIN_POINTS for n in nodes) or len(set(nodes)) != len(nodes):
        raise op.must_be("--nodes", " ".join(map(str, nodes)), f"distinct integers >= {MIN_POINTS}")
    check_output_dir("--out", args.out, create=False)
    ref = surface_reference(point, case)
    inputs = {}
    if args.fields:
        results, label = _surface_from_fields(args, point, ref, inputs)
    elif args.scalars:
        recs = read_scalars_jsonl(args.scalars, keys=OWN_KEYS, allowed=SURFACE_SCALARS_ALLOWED)
        inputs[f"--scalars {args.scalars}"] = f"sha256 {_sha(args.scalars)}"
        results = [Result(r["nodes"], None, r["scalars"], [], "solver") for r in recs]
        label = args.label or f"scalars from {Path(args.scalars).name}"
    else:
        fn = load_callable(args.callable)
        inputs["--callable"] = args.callable
        label = args.label or args.callable
        results = []
        for n in sorted(nodes):
            obj = _solve(lambda k: fn(dict(point), k), n, label)
            f, own = as_surface_fields(obj, "--callable", label, _aspect(ref))
            results.append(surface_result(f, own, point, ref, "--callable", label, n))
    ev = surface_evaluate(results, ref, rtol=rtol, tol=tols, rtol_given=rtol_given)
    try:
        write_surface_report(args.out, ev, point, ref, results, label, inputs, case,
                             figures=not args.no_figures)
    except OSError as exc:
        raise Failed(_short(f"--out {args.out}: cannot write the report "
                            f"({exc.strerror or exc})")) from None
    _print_verdict(ev)
    failed = f" ({', '.join(ev['failed'])})" if ev["failed"] else ""
    print(f"verify: {ev['verdict']}{failed}; report in {os.path.join(args.out, 'report.md')}",
          file=sys.stderr)
    return 0 if ev["verdict"] == "PASS" else 1


def _aspect(ref):
    """Ly/Lx of a surface reference (its stated grid's y starts at −½ Ly/Lx)."""
    return -2.0 * float(ref.fields["y"][0])


def _surface_from_fields(args, point, ref, inputs):
    """(results, label) of ``--fields`` on a surface case: ``.npz`` files of the conventions,
    each file's hash in ``inputs``; the speed and direction a file states must be the case's."""
    results = []
    for path in args.fields:
        raw, scalars = read_npz(path)
        f = check_fields(raw, "--fields", path, _aspect(ref))
        for k in ("speed", "direction"):
            want = float(point.get(k, 0.0))
            if k in scalars and not math.isclose(scalars[k], want, rel_tol=1e-9, abs_tol=1e-12):
                raise bad_input("--fields", path, f"{k} = {scalars[k]:g} in the file, the case "
                                f"{args.case} has {want:g}", "the case's operating point")
        own = {k: v for k, v in scalars.items() if k in OWN_KEYS and k != "load"}
        results.append(surface_result(f, own, point, ref, "--fields", path))
        inputs[f"--fields {path}"] = (f"sha256 {_sha(path)}, {f['x'].size} x {f['y'].size} "
                                      "points")
    if len({r.nodes for r in results}) != len(results):
        raise bad_input("--fields", " ".join(args.fields), "two files with the same grid",
                        "one file per resolution")
    label = args.label or "fields from " + ", ".join(Path(p).name for p in args.fields)
    return results, label


def _sha(path):
    """The first 16 hexadecimal digits of a file's SHA-256, for the report's provenance."""
    return hashlib.sha256(Path(path).read_bytes()).hexdigest()[:16]


def _short(text, limit=MESSAGE_LIMIT):
    """The first line of a message within ``limit`` characters: long paths keep their head and
    their end (…), then the 'allowed' part is cut, then the end (an ellipsis says so)."""
    line = str(text).strip().splitlines()[0] if str(text).strip() else ""
    if len(line) > limit:
        line = " ".join(w if len(w) <= 60 else w[:20] + "…" + w[-36:] for w in line.split(" "))
    if len(line) > limit and "; allowed: " in line:
        head, allowed = line.split("; allowed: ", 1)
        room = limit - len(head) - len("; allowed: ")
        line = head if room < 20 else f"{head}; allowed: {allowed[:room - 1].rstrip()}…"
    return line if len(line) <= limit else line[:limit - 1].rstrip() + "…"


def _peer_progress(label, total):
    """A progress callback for the peer's dt studies: one line on standard error per run."""
    state = {"done": 0, "t0": None}

    def report(row):
        if state["t0"] is None:
            state["t0"] = time.monotonic() - row["wall_time"]
        state["done"] += 1
        cells = row["cells_per_step"] / row["steps_per_cell"]
        print(f"verify: {label} N = {row['nodes']}, dt = {cells:g} × T/N: "
              f"{'steady' if row['success'] else 'FAILED'} after {row['periods']} periods, "
              f"{row['wall_time']:.1f} s (run {state['done']} of {total}, "
              f"{time.monotonic() - state['t0']:.0f} s in all)", file=sys.stderr, flush=True)
    return report

