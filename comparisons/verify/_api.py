"""The Python API of verify: `assert_agrees`, a pytest-friendly verdict on a result."""
from __future__ import annotations

from ._compare import evaluate
from ._point import point_and_case
from ._quantities import COMPARED_KEYS
from ._reference import reference_for
from ._report import fmt
from ._results import Result, as_fields, results_from_fields
from ._tolerances import DEFAULT_RTOL


def assert_agrees(fields_or_scalars, case, rtol=None, tol=None):
    """Assert that a result agrees with the reference of a case (pytest-friendly).

    Parameters
    ----------
    fields_or_scalars : viscosine.Fields, dict, or object with ``.fields``
        Fields over one period (a Fields, or a dict with ``x_over_lambda`` and ``pressure`` and
        optionally ``displacement``, ``gap``), or a dict of scalars keyed like the conventions.
    case : str or dict
        A suite case name, or an operating point (``load`` or ``penetration``, ``speed``, and
        ``ratio``/``hk`` or ``prony``/``profile`` file paths, and optionally ``layer``: the plain
        layer description of `comparisons.roads.layer`, checked).
    rtol : float, optional
        A flat tolerance of every scalar and of the contact edges (relative or absolute as in
        `comparisons.verify._quantities`).  By default max(1e-4, 3 e_N) on the fields' grid of
        N points (`grid_errors`), 1e-4 for scalars; the field norms' tolerances follow from the
        grid (FIELD_LAW).
    tol : dict, optional
        Tolerances per quantity (keys of ALL_KEYS), overriding both.

    Raises
    ------
    AssertionError
        Naming each quantity outside its tolerance, both values and the difference.
    """
    point, c = point_and_case(case)
    ref = reference_for(point, c)
    obj = fields_or_scalars
    is_scalars = isinstance(obj, dict) and "pressure" not in obj and "x_over_lambda" not in obj
    if is_scalars:
        sc = {k: float(v) for k, v in obj.items() if k in COMPARED_KEYS and v is not None}
        results = [Result(obj.get("nodes"), None, sc, [], "solver")]
    else:
        f = as_fields(obj, "fields_or_scalars", type(obj).__name__)
        results = results_from_fields([f], ref.shape)
    ev = evaluate(results, ref, rtol=DEFAULT_RTOL if rtol is None else rtol, tol=tol,
                  rtol_given=rtol is not None)
    if ev["verdict"] != "PASS":
        bad = [r for r in ev["quantities"] if not r["passed"]]
        lines = [f"{r['label']} ({r['key']}): {fmt(r['value'], '.10g')} vs reference "
                 f"{fmt(r['reference'], '.10g')}, difference {fmt(r['difference'], '.3e')} "
                 f"({r['measure']}) > tolerance {r['tolerance']:.1e}"
                 + (f" [{r['note']}]" if r["note"] else "") for r in bad]
        if not ev["quantities"]:
            lines = ["no quantity could be compared with the reference"]
        raise AssertionError(f"disagrees with the {ref.road} reference of "
                             f"{case if isinstance(case, str) else point}:\n  "
                             + "\n  ".join(lines))
    return ev

