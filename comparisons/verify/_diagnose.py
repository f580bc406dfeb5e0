"""Common slips recognised in a result (a mirrored sign or x, SI values without ``--units SI``,
fields one panel off their x, a uniform scale on σ, v or the stresses, a relaxation time taken
for a creep time), each named in one line of the verdict."""
from __future__ import annotations

import math

import numpy as np

from .. import roads
from .. import suite as _suite
from ..fields import as_grid
from ._quantities import COMPARED_KEYS, LABELS, measure
from ._reference import Reference
from ._results import Result

#: a value within this fraction of minus the reference is a mirrored sign
MIRRORED = 0.05
#: a field slip (mirrored x, a one-panel offset) is reported when undoing it shrinks σ's L2
#: difference below this fraction of what it was
SLIP_GAIN = 0.3
#: a uniform scale of σ, v or the stresses is named when it is off 1 by more than this (and
#: less than the factor 100 that `_unit_slips` reads as SI values without --units SI)
SCALE_SLIP = 0.01
#: a result "matches" the reference at another speed when each scalar it gives is within this
#: many times its tolerance plus floor of the reference there (a speed off by E∞/E0 moves μ
#: by tens of per cent; the margin covers the BEM's own error where it is the reference)
SWAP_MARGIN = 2.0
#: the BEM grid of a reference at the swapped speed where the semi-analytic road does not apply
SWAP_NODES = 8192


def _pressure_l2(grid, p, ref_p):
    pm = float(np.max(np.abs(ref_p)))
    return grid.l2(np.asarray(p, float) - ref_p) / pm if pm > 0 else math.inf


def diagnose(result: Result, reference: Reference, ev=None, si=False):
    """Common slips recognised in a result, each a one-line hint (empty when none is seen).

    - a mirrored sign: μ (or τ̃f) within 5 % of minus the reference (friction counted positive
      when it drives the motion), ke or kê within 5 % of minus the reference's (x mirrored:
      the sliding toward −x, or the leading edge taken at −x);
    - fields mirrored in x: σ(x) agrees with the reference's σ(−x) far better than with σ(x);
    - a one-panel offset (uniform grid): the fields agree with the reference after moving them
      by one panel (np.roll by ±1) far better than before;
    - a uniform scale: σ (or v) c × the reference's everywhere, 1 % < |c − 1| and c < 100
      (a modulus or 1 − ν² off); without fields, p̃∞ and τ̃f both c × the reference's, or τ̃f
      alone while μ agrees;
    - SI values without ``--units SI``: σ (or the load) two orders of magnitude or more above
      the reference's, or v/h two orders below, the ratio being what E0/(1 − ν²) in Pa or h in
      m would make it;
    - the solid's two times swapped: every scalar the result gives matches the reference at
      E∞/E0 times the speed (a relaxation time given as the creep time) or at the speed over
      E∞/E0 (the other way round), within SWAP_MARGIN times its tolerance plus floor.
    ``ev``: the verdict rows (a slip is reported only where a check failed); ``si``: whether
    the inputs were converted from SI.
    """
    out = []
    sc = result.scalars
    failed = {r["key"] for r in (ev or {}).get("quantities", []) if not r["passed"]}

    def ref(k):
        return reference.scalars.get(k, (None, None))[0]

    def flipped(k, floor=0.0):
        v, r = sc.get(k), ref(k)
        return (v is not None and r is not None and abs(r) > floor
                and abs(v + r) <= MIRRORED * abs(r))

    x_mirrored = flipped("ke", 1e-3) or flipped("ke_hat", 1e-3)
    f = result.fields
    ref_f = None
    if f is not None:
        ref_f, _ = reference.fields(np.asarray(f["x_over_lambda"], float))
        if failed:
            slip, mirrored = _field_slip(f, reference, ref_f)
            x_mirrored = x_mirrored or mirrored
            out += [slip] if slip else []
    if flipped("mu") or flipped("tau_f"):
        k = "mu" if flipped("mu") else "tau_f"
        out.append(f"{LABELS[k]} = {sc[k]:.6g} against {ref(k):.6g}: the friction has the "
                   "opposite sign; viscosine counts τf positive when it resists the motion "
                   "(docs/conventions.md, 'Frame and signs')"
                   + ("; here x is mirrored too, which flips it" if x_mirrored else ""))
    if x_mirrored and (flipped("ke", 1e-3) or flipped("ke_hat", 1e-3)):
        k = "ke" if flipped("ke", 1e-3) else "ke_hat"
        out.append(f"{LABELS[k]} = {sc[k]:.6g} against {ref(k):.6g}: x is mirrored; the "
                   "indenter slides toward +x and e, ê are positive toward the leading (+x) "
                   "edge (docs/conventions.md, 'Frame and signs')")
    if f is None and failed:
        out += _scalar_scale(sc, ref, failed)
    if not si:
        out += _unit_slips(f, ref_f, sc.get("load"), ref("load"))
    if failed & set(COMPARED_KEYS):
        swap = _time_swap(result, reference, ev)
        out += [swap] if swap else []
    return out


def _scaled(grid, a, ref_a):
    """(c, L2 of a − ref_a, L2 of a/c − ref_a), c the least-squares factor a ≈ c ref_a on the
    grid's quadrature (c None when the reference is 0)."""
    a, ref_a = np.asarray(a, float), np.asarray(ref_a, float)
    den = grid.mean(ref_a * ref_a)
    if not den > 0.0:
        return None, 0.0, 0.0
    c = float(grid.mean(a * ref_a) / den)
    if not (math.isfinite(c) and c > 0.0):
        return None, 0.0, 0.0
    return c, grid.l2(a - ref_a), grid.l2(a / c - ref_a)


def _field_scale(grid, f, ref_f):
    """Hints for σ or v a uniform factor off the reference's (a modulus or 1 − ν², a length)."""
    out = []
    c, base, fixed = _scaled(grid, f["pressure"], ref_f["pressure"])
    if c is not None and SCALE_SLIP < abs(c - 1.0) and c < 100.0 and fixed < SLIP_GAIN * base:
        pm = float(np.max(np.abs(ref_f["pressure"])))
        out.append(f"σ is the reference × {c:.3f} everywhere: modulus or (1 − ν²) scaling? (σ "
                   f"L2 / max σ {base / pm:.1e} → {fixed / pm:.1e} once divided by it; "
                   "viscosine's σ is σ(1 − ν²)/E0, E0 the relaxed modulus: σ/E0 is 1/(1 − ν²) "
                   "×, σ(1 − ν²)/E∞ is E0/E∞ ×)")
    if "displacement" in f:
        c, base, fixed = _scaled(grid, f["displacement"], ref_f["displacement"])
        if (c is not None and SCALE_SLIP < abs(c - 1.0) and c > 0.01
                and fixed < SLIP_GAIN * base):
            out.append(f"v is the reference × {c:.3f} everywhere: a length scale off? (v L2 / h "
                       f"{base:.1e} → {fixed:.1e} once divided by it; viscosine's v is over h, "
                       "the amplitude max y − mean y, not over 1/k or λ)")
    return out


def _scalar_scale(sc, ref, failed):
    """Without fields: p̃∞ and τ̃f both c × the reference's (or τ̃f alone while μ agrees)."""
    def ratio(k):
        v, r = sc.get(k), ref(k)
        return v / r if v is not None and r else None

    c_t, c_p = ratio("tau_f"), ratio("load")
    if "tau_f" not in failed or c_t is None or not (SCALE_SLIP < abs(c_t - 1.0) and c_t < 100.0):
        return []
    if c_p is not None and abs(c_p / c_t - 1.0) <= 1e-3 * abs(c_t - 1.0) + 1e-9:
        what = "p̃∞ and τ̃f are"
    elif c_p is None and "mu" in sc and "mu" not in failed:
        what = "τ̃f is"
    else:
        return []
    agrees = " while μ agrees" if "mu" in sc and "mu" not in failed else ""
    return [f"{what} the reference × {c_t:.3f}{agrees}: modulus or (1 − ν²) scaling? (the conventions' "
            "stresses are over E0/(1 − ν²), E0 the relaxed modulus)"]


def _scalars_at(point, speed):
    """The reference's scalars at ``point`` with another ``speed`` (the semi-analytic road, else
    the BEM on SWAP_NODES panels), or None where it cannot be had."""
    pt = dict(point, speed=speed)
    try:
        sol = (roads.analytic_solution(pt) if _suite.two_roads(pt)
               else _suite.bem_solution(pt, SWAP_NODES, base="/"))
    except (ValueError, RuntimeError):  # a speed outside the roads' range, a failed solve
        return None
    if not sol.success:
        return None
    return {k: float(v) for k in COMPARED_KEYS
            if (v := getattr(sol, k, None)) is not None}


def _time_swap(result, reference, ev):
    """A hint when the result matches the reference at E∞/E0 times the speed, or over it: the
    standard linear solid's relaxation time τ E0/E∞ taken for its creep time τ, or the reverse
    (docs/conventions.md, 'Creep times, not relaxation times'); None otherwise."""
    point = reference.point
    rho = point.get("ratio")
    if (not rho or rho <= 1.0 or point.get("prony") or point.get("material")
            or point.get("surface") or not point.get("speed")):
        return None
    rows = [r for r in ev["quantities"] if r["key"] in COMPARED_KEYS]
    for factor, what in ((rho, "at E∞/E0 times the speed: relaxation time given as a creep "
                               "time?"),
                         (1.0 / rho, "at the speed divided by E∞/E0: creep time given as a "
                                     "relaxation time?")):
        at = _scalars_at(point, point["speed"] * factor)
        if at is None:
            continue
        diffs = [(r, measure(r["key"], r["value"], at[r["key"]])) for r in rows if r["key"] in at]
        if diffs and all(d is not None and d <= SWAP_MARGIN * (r["tolerance"]
                                                             + r["derivation_floor"])
                         for r, d in diffs):
            return (f"matches {what} (V/V0 = {point['speed'] * factor:.6g} instead of "
                    f"{point['speed']:.6g}, E∞/E0 = {rho:g}; the speed group is V τ k with τ the "
                    "creep time, the relaxation time being τ E0/E∞: --tau-creep or --tau-relax "
                    "with --units SI)")
    return None



def _field_slip(f, reference, ref_f):
    """(a hint or None, whether x is mirrored) of fields ``f`` whose σ matches the reference's
    (``ref_f``, on their grid) mirrored in x, or else moved by one panel, far better than as
    they are."""
    grid = as_grid(f)
    x = np.asarray(f["x_over_lambda"], float)
    base = _pressure_l2(grid, f["pressure"], ref_f["pressure"])
    scaled = _field_scale(grid, f, ref_f)
    if scaled:
        return "; ".join(scaled), False
    if not base > 0:
        return None, False
    mirrored_ref, _ = reference.fields(-x)
    mir = _pressure_l2(grid, f["pressure"], mirrored_ref["pressure"])
    if mir < SLIP_GAIN * base:
        return (f"the fields match the reference mirrored in x (σ L2 / max σ {base:.1e} against "
                f"σ_ref(−x), {mir:.1e}): in viscosine's frame the indenter slides toward +x and "
                "the leading edge is the +x edge (docs/conventions.md, 'Frame and signs')"), True
    if grid.uniform:
        best = min((1, -1), key=lambda k: _pressure_l2(
            grid, np.roll(f["pressure"], k), ref_f["pressure"]))
        rolled = _pressure_l2(grid, np.roll(f["pressure"], best), ref_f["pressure"])
        if rolled < SLIP_GAIN * base:
            way = "+x" if best > 0 else "−x"
            return (f"the fields match the reference once moved by one panel toward {way} "
                    f"(σ L2 / max σ {base:.1e} → {rolled:.1e}, np.roll by {best:+d}): "
                    "x_over_lambda is one panel off its values (cell edges written for "
                    "centres, or an index counted from 1?)"), False
    return None, False


def _unit_slips(f, ref_f, load, ref_load):
    """Hints that values in SI came without ``--units SI``: from the fields ``f`` against the
    reference's ``ref_f`` when given, else from the load against the reference's."""
    out = []
    if f is not None and ref_f is not None:
        pr = float(np.max(np.abs(f["pressure"]))) / max(
            float(np.max(np.abs(ref_f["pressure"]))), 1e-300)
        if pr >= 100.0:
            out.append(f"σ is {pr:.2g} × the reference's: pressures in Pa without --units "
                       f"SI? (then E0/(1 − ν²) ≈ {pr:.2g} Pa; --units SI --E0 --nu "
                       "--amplitude converts them)")
        if "displacement" in f:
            vm = float(np.max(np.abs(ref_f["displacement"])))
            vr = float(np.max(np.abs(f["displacement"]))) / vm if vm > 0 else 1.0
            if 0.0 < vr <= 0.01:
                out.append(f"v is {vr:.2g} × the reference's: lengths in m without --units "
                           f"SI? (then the amplitude h ≈ {vr:.2g} m)")
    elif load is not None and ref_load:
        lr = load / ref_load
        if lr >= 100.0:
            out.append(f"the load is {lr:.2g} × the reference's: a mean pressure in Pa? "
                       "(the conventions' load is p∞(1 − ν²)/E0)")
    return out
