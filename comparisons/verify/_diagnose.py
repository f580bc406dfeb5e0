"""Common slips recognised in a result (a mirrored sign or x, SI values without ``--units SI``,
fields one panel off their x), each named in one line of the verdict."""
from __future__ import annotations

import math

import numpy as np

from ..fields import as_grid
from ._quantities import LABELS
from ._reference import Reference
from ._results import Result

#: a value within this fraction of minus the reference is a mirrored sign
MIRRORED = 0.05
#: a field slip (mirrored x, a one-panel offset) is reported when undoing it shrinks σ's L2
#: difference below this fraction of what it was
SLIP_GAIN = 0.3


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
    - SI values without ``--units SI``: σ (or the load) two orders of magnitude or more above
      the reference's, or v/h two orders below, the ratio being what E0/(1 − ν²) in Pa or h in
      m would make it.
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
    if not si:
        out += _unit_slips(f, ref_f, sc.get("load"), ref("load"))
    return out



def _field_slip(f, reference, ref_f):
    """(a hint or None, whether x is mirrored) of fields ``f`` whose σ matches the reference's
    (``ref_f``, on their grid) mirrored in x, or else moved by one panel, far better than as
    they are."""
    grid = as_grid(f)
    x = np.asarray(f["x_over_lambda"], float)
    base = _pressure_l2(grid, f["pressure"], ref_f["pressure"])
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
