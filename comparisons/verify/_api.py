"""The Python API of verify: `assert_agrees`, a pytest-friendly verdict on a result."""
from __future__ import annotations

from ._compare import evaluate
from ._point import is_surface_case, point_and_case
from ._quantities import COMPARED_KEYS
from ._reference import reference_for
from ._report import fmt
from ._results import Result, as_fields, results_from_fields
from ._surface_fields import OWN_KEYS, as_surface_fields
from ._surface_judge import evaluate as surface_evaluate
from ._surface_judge import surface_result
from ._surface_reference import surface_reference
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
        layer description of `comparisons.roads.layer`, checked).  A surface case (by name
        only) takes the 2-D fields of the conventions (a dict of ``x``, ``y``, ``pressure``
        and optionally ``displacement``, ``gap``, or an object with ``.fields`` and
        ``.scalars``) or a dict of its scalars (``mu``, ``mu_lateral``, ``penetration``,
        ``contact_fraction``, ``load``, and ``nodes``).
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
    if isinstance(case, str) and is_surface_case(case):
        return _assert_surface(fields_or_scalars, case, rtol, tol)
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
        lines += [f"diagnosis: {d}" for d in ev["diagnosis"]]
        raise AssertionError(f"disagrees with the {ref.road} reference of "
                             f"{case if isinstance(case, str) else point}:\n  "
                             + "\n  ".join(lines))
    return ev



def _assert_surface(obj, name, rtol, tol):
    """`assert_agrees` on a surface case."""
    point, case = point_and_case(name)
    ref = surface_reference(point, case)
    if isinstance(obj, dict) and "pressure" not in obj:
        sc = {k: float(v) for k, v in obj.items() if k in OWN_KEYS and v is not None}
        results = [Result(obj.get("nodes"), None, sc, [], "solver", own=tuple(sc))]
    else:
        f, own = as_surface_fields(obj, "fields_or_scalars", type(obj).__name__,
                                   -2.0 * float(ref.fields["y"][0]))
        results = [surface_result(f, own, point, ref, "fields_or_scalars",
                                  type(obj).__name__)]
    ev = surface_evaluate(results, ref, rtol=DEFAULT_RTOL if rtol is None else rtol, tol=tol,
                          rtol_given=rtol is not None)
    if ev["verdict"] != "PASS":
        bad = [r for r in ev["quantities"] if not r["passed"]]
        lines = [f"{r['label']} ({r['key']}): {fmt(r['value'], '.10g')} vs reference "
                 f"{fmt(r['reference'], '.10g')}, difference {fmt(r['difference'], '.3e')} "
                 f"({r['measure']}) > tolerance {r['tolerance']:.1e}" for r in bad]
        raise AssertionError(f"disagrees with the certified surface case {name}:\n  "
                             + "\n  ".join(lines or ["no quantity could be compared"]))
    return ev
