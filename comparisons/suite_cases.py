"""The suite's rule and what a case's point is made of: the constants of the certification
rule (`RULE`, the margin `SAFETY`, the fields' floor and grid, the columns and keys), whether
both roads apply (`two_roads`), a surface case (`is_surface`), the reference a case declares
(`reference_of`), its material and the BEM's problem (`case_material`, `bem_solution`).

Shared by `comparisons.suite` (the cases, ``--check``, ``--certify``), `comparisons.suite_compute`
(one case certified) and `comparisons.suite_surfaces` (the surface cases); `comparisons.suite`
re-exports every name.  The rule itself is stated in `comparisons.suite`'s docstring.
"""
from __future__ import annotations

import math
from pathlib import Path

from . import operating_point as op
from . import roads as _roads
from ._errors import SuiteError
from .convergence import LAST, MAX_ORDER, MIN_ORDER, RELATIVE_FLOOR, ROUNDOFF, SCATTER_FLOOR
from .suite_inputs import DATA

SAFETY = 10.0        # margin on the BEM's own error estimate (BEM-only cases and fields)
FIELD_FLOOR = 1e-11  # a field error is never below this × the largest magnitude of its column
#: ... and a pressure the BEM gives (BEM-only cases) never below this × its largest value.  The
#: pressure is the unknown of the linear solves, fixed only to the Krylov tolerance times the
#: contact's conditioning: two solves of one mesh that both meet it (started from different
#: coarser grids) differ by up to 2.8e-9 of the largest pressure at N = 2^18 (the suite's
#: BEM-only cases, measured; the floor is ten times that, as SAFETY is on a measured change).
#: The finest mesh starts from the second finest, so the two share that part and their change
#: does not show it.
BEM_PRESSURE_FLOOR = 3e-8
FIELD_POINTS = 256   # the stated grid of the fields, x_j = j/M − 1/2

#: the certification rule, as written into the suite data and the exported README
RULE = (
    "Every case is solved by the BEM on meshes N = 2^10 ... 2^18. The convergence study of a "
    f"scalar q uses the {LAST + 1} finest meshes: the differences d_i = |q_i - q_(i-1)|, the "
    "observed order p (least-squares slope of log d_i against log N_i; nothing is certified "
    f"below {MIN_ORDER}, p is capped at {MAX_ORDER:g}), the envelope D (the smallest line of "
    "slope -p above every d_i, at the finest mesh), the Richardson value "
    "q_R = q_L + (q_L - q_(L-1))/(2^p - 1) and "
    "the error estimate E = D/(2^p - 1). When the last two differences are below "
    f"{ROUNDOFF:g} |q| the study is in the round-off regime: q_R = q_L and E is the larger of "
    f"{ROUNDOFF:g} |q| and the last difference. When p is below {MIN_ORDER} but the values of "
    f"the study all lie within {SCATTER_FLOOR:g} |q| of each other and move both up and down, "
    "they have settled and scatter (the sub-panel edge fits): q_R = q_L and E is their spread "
    "(largest minus smallest); values that move one way only drift and are not converging. "
    "Two roads (standard linear solid and sinusoid): the certified value is the semi-analytic one, "
    "a, with the error e = |a - q_R| (the digits on which the two roads agree; q_R is replaced by "
    "the finest value q_L when the study is in the round-off regime or its differences scatter "
    f"with an observed order below {MIN_ORDER}). BEM only (Prony "
    f"series, other profiles): the certified value is q_R with e = {SAFETY:g} E. BEM and the "
    "Fourier reference (sinusoid on a Prony material, or on the standard linear solid over a "
    "layer, where the semi-analytic road does not apply; cases that declare it): the point is "
    "also solved by the independent Fourier collocation of analytic.fourier_solve (the creep "
    "series of the case's material, the case's layer), and the certified value is q_R with "
    f"e = max({SAFETY:g} E, |q_R - q_F|), q_F the Fourier value: the digits on which both roads "
    "agree, never more than the BEM's own study supports; a failed reference certifies nothing. "
    "The certified "
    "significant digits are the largest d with e < 1/2 * 10^(floor(log10|value|) - d + 1) (half "
    "a unit of the last certified digit bounds e) and that half unit at least "
    f"{RELATIVE_FLOOR:g} |value| (ten times the round-off level, so that a certified digit "
    "survives recomputation on another machine). Fields on the stated grid carry "
    "an absolute error per point: two roads, the largest |semi-analytic - BEM(finest N)| at the "
    "point and its two neighbours; otherwise (the Fourier-referenced cases too: their reference "
    f"is judged on the scalars), {SAFETY:g} x the largest change between the two "
    f"finest meshes at the point and its neighbours; never below {FIELD_FLOOR:g} x the largest "
    f"magnitude of the column ({BEM_PRESSURE_FLOOR:g} for a pressure the BEM gives: the part of "
    "its linear solves, fixed to the Krylov tolerance, that the two finest meshes share). A "
    "failed solve on any of the finest meshes certifies nothing.")

FIELD_COLUMNS = ("pressure", "displacement", "gap")
TOP_KEYS = ("mu", "tau_f", "penetration", "separation", "load", "contact_fraction", "ka", "ke",
            "ke_hat", "approach", "mean_displacement")
#: the scalars of a layer only (`_scalar_keys`): read from the BEM's ``diagnostics["layer"]``
LAYER_KEYS = ("approach", "mean_displacement")


# --------------------------------------------------------------------------- a case's point
def two_roads(point) -> bool:
    """True when the semi-analytic road applies (sinusoid on the standard linear solid, on the
    half-space: the road has no layer)."""
    return (not point.get("profile") and not point.get("prony") and not point.get("material")
            and not point.get("layer") and not point.get("surface"))


def is_surface(case_or_point) -> bool:
    """True for a surface case (or its point): a rigid periodic surface, ``point["surface"]``."""
    point = case_or_point.get("point", case_or_point)
    return bool(point.get("surface"))


#: the independent references a case may declare (``"reference"``), beyond the two roads
REFERENCES = ("fourier",)


def reference_of(case):
    """The independent reference a case declares (None or one of REFERENCES); SuiteError for
    one it may not have."""
    ref = case.get("reference")
    if ref is None:
        return None
    if ref not in REFERENCES:
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed: "
                         f"one of {', '.join(REFERENCES)} or none")
    p = case["point"]
    if p.get("profile") or two_roads(p):
        # the Fourier collocation solves the sinusoid only, and the standard linear solid on the
        # half-space has the semi-analytic road already (on a layer it has not: allowed)
        raise SuiteError(f"case {case['name']}: reference {ref!r} is not allowed here: a "
                         "sinusoid on a Prony material (prony or material) or over a layer, not "
                         + ("a profile file" if p.get("profile")
                            else "the standard linear solid on the half-space"))
    return ref


def data_path(rel) -> Path:
    return DATA / rel


#: what each form of a material file is called (in the export's inputs.json and prony.txt)
FORM_NAMES = {"creep": "creep series", "relaxation": "relaxation series (generalised Maxwell)",
              "dma": "DMA master curve"}


def case_material(point, base=DATA):
    """The :class:`comparisons._materials.Material` of a point that names a ``material`` file
    (any form: creep, relaxation, DMA; at ``temperature`` with ``wlf`` when given); SuiteError
    naming the file for a bad one."""
    from . import _materials
    wlf = point.get("wlf")
    try:
        return _materials.read(str(Path(base) / point["material"]),
                               temperature=point.get("temperature"),
                               wlf=tuple(float(v) for v in wlf) if wlf is not None else None)
    except ValueError as exc:
        raise SuiteError(f"material {point['material']}: {str(exc).splitlines()[0]}") from None


def _problem(point, base=DATA):
    """(profile, material) objects of the BEM for an operating point dict."""
    if point.get("prony"):
        material = _roads.read_prony(Path(base) / point["prony"])
    elif point.get("material"):
        material = case_material(point, base).prony
    else:
        material = _roads.standard_linear_solid(op.ratio_of(point))
    if point.get("profile"):
        profile = _roads.read_profile(Path(base) / point["profile"])
    else:
        profile = _roads.sinusoid(op.hk_of(point))
    return profile, material


def increasing_meshes(case) -> list:
    """A case's meshes (``nodes``), which must be distinct and in increasing order: a mesh study
    answers them coarse to fine.  SuiteError otherwise."""
    nodes = [int(n) for n in case["nodes"]]
    if nodes != sorted(set(nodes)):
        raise SuiteError(f"case {case['name']}: the meshes {nodes} must be distinct and in "
                         "increasing order")
    return nodes


def bem_solution(point, nodes, base=DATA, problem=None):
    """The BEM solution at an operating point on ``nodes`` panels (`roads.bem_solution`, Krylov
    tolerance `roads.BEM_TOL`); ``problem`` is read from the point's files under ``base`` when
    not given."""
    return _roads.bem_solution(point, nodes, problem or _problem(point, base))


def _num(v):
    """JSON-safe float (None for NaN/inf)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None
