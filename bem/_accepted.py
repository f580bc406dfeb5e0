"""The inputs the boundary-element road accepts, with the reason for every bound.

Everything inside these ranges is solved, or reported as an unconverged result with its
residuals; everything outside is refused up front with a ValueError naming the parameter, its
value and what is allowed.  The bounds were chosen from actual solves at N = 1024 at and beyond
each extreme (see `tests/bem/test_bem_protocol.py`, which also samples the whole box at random).

Units as in `bem/__init__.py`: load p∞(1 − ν²)/E_ref, penetration Δ/h, speed V τ_ref k, ratio
E∞/E0 of the standard linear solid, hk = h k; Prony compliances in 1/E_ref, times in τ_ref.
"""
from __future__ import annotations

import math
import os

from viscosine.checks import at_most_one_control, bad, check_reals, integer, real

#: speeds in (0, SPEED_MIN) and above SPEED_MAX are refused; 0 is the elastic (relaxed) solution
SPEED_MIN, SPEED_MAX = 1e-30, 1e30
#: p̃∞/(hk): the contact must span panels (the width 2a/λ ≈ (2/π)√(2p̃∞/hk) at light load)
LOAD_OVER_AMPLITUDE = (1e-8, 1e6)
HK_MIN, HK_MAX = 1e-6, 1e6
LOAD_MIN, LOAD_MAX = LOAD_OVER_AMPLITUDE[0] * HK_MIN, LOAD_OVER_AMPLITUDE[1] * HK_MAX
PENETRATION_MIN = 1e-7
#: E∞/E0 of a viscoelastic material: above 1 + RATIO_EPS (below, the viscoelastic part is
#: round-off) and at most RATIO_MAX
RATIO_EPS, RATIO_MAX = 1e-12, 1e8
#: Prony series: relaxed compliance, creep times, and the smallest non-zero term over J(0+)
J0_MIN, J0_MAX = 1e-6, 1e6
TAU_MIN, TAU_MAX = 1e-30, 1e30
TERM_MIN = 1e-12
RTOL_MIN, RTOL_MAX = 1e-10, 1e-2
NODES_MIN = 8
#: bytes per panel of a solve (operator, its FFTs, the Krylov basis and the fields): the
#: tracemalloc peak at 2^20 is 81-126 for E_inf/E0 = 3 and 159 for a stiff material mostly in
#: contact (python -m comparisons bench --bem), 134 without the kept preconditioned Krylov
#: vectors, which grids whose active set exceeds 2^21 panels (restart 8) do not keep: at the
#: sizes this cap decides (2^22 and up) a solve stays under it
BYTES_PER_PANEL = 150


def _max_nodes():
    """The largest power of two whose solve fits in half the machine's memory, in [2^16, 2^24]."""
    try:
        ram = os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES")
    except (AttributeError, ValueError, OSError):  # a platform without sysconf
        ram = 0
    n = 2 ** 16
    while n < 2 ** 24 and 2 * n * BYTES_PER_PANEL <= ram / 2:
        n *= 2
    return n


#: panels per period refused above this (depends on the machine's memory; 2^16 … 2^24)
MAX_NODES = _max_nodes()

#: name -> (low, high, "what is allowed: why").  Bounds are inclusive unless the text says so.
#: The command line shows only what is allowed (up to the first ': ' outside brackets,
#: `viscosine.checks.allowed_part`), so keep that part short.
ACCEPTED = {
    "load": (LOAD_MIN, LOAD_MAX,
             f"a mean pressure p̃∞ = p∞(1 − ν²)/E_ref with p̃∞/(hk) in [{LOAD_OVER_AMPLITUDE[0]:g}, "
             f"{LOAD_OVER_AMPLITUDE[1]:g}]: hk is the amplitude of the profile; below, the contact "
             "(2a/λ ≈ (2/π)√(2p̃∞/hk)) is narrower than the finest mesh resolves and Δ/h nears "
             "round-off; above, full contact with σ = p̃∞ + O(hk), whose oscillating part (which "
             "carries the friction) would lose more than ~1e-10 to rounding"),
    "penetration": (PENETRATION_MIN, 1.0,
                    f"a penetration Δ/h in [{PENETRATION_MIN:g}, 1] (1 is full contact at its "
                    "threshold load): below, about the penetration of the smallest accepted load, "
                    "and Δ/h = 1 − s/h would carry more than ~1e-9 relative rounding"),
    "speed": (0.0, SPEED_MAX,
              f"V τ_ref k equal to 0 or in [{SPEED_MIN:g}, {SPEED_MAX:g}]: 0 is elastic (relaxed "
              "moduli); beyond, the viscoelastic corrections fall below 1e-30 of the "
              "elastic solution; at 1e308 the kernel overflows"),
    "ratio": (1.0, RATIO_MAX,
              f"E∞/E0 > 1 + {RATIO_EPS:g} and ≤ {RATIO_MAX:g}: nearer 1 the viscoelastic part is "
              "round-off (for an elastic material give material=bem.Prony(J0)); measured polymers "
              "across their glass transition reach 1e4 … 1e7 (glassy over rubbery modulus), and "
              "up to 1e8 the answers agree with the semi-analytic road within their estimates "
              "(tests/validation/test_stiff_ratio.py); above, J(0+) = J0/ratio nears the round-off of "
              "J0 − ΣJ_i.  From about 300 up, "
              "where the pressure memory layer is thinner than a panel, the active-set and Krylov "
              "iterations may not converge (measured at N = 1024 … 2^17): such points come back "
              "unconverged with their residuals, never as an answer"),
    "hk": (HK_MIN, HK_MAX,
           f"hk in [{HK_MIN:g}, {HK_MAX:g}]: hk only scales the load, pressures and friction; the "
           "bounds keep those scales far from under/overflow (at 1e308 the solve overflows; the "
           "half-space theory itself asks for hk ≪ 1)"),
    "nodes": (NODES_MIN, MAX_NODES,
              f"an integer number of panels per period in [{NODES_MIN}, {MAX_NODES}]: the upper "
              f"bound is the largest power of two whose solve (~{BYTES_PER_PANEL} bytes per panel) "
              "fits in half of this machine's memory, at most 2^24"),
    "max_nodes": (NODES_MIN, MAX_NODES,
                  f"a power of two in [{NODES_MIN}, {MAX_NODES}]: the cap of the adaptive "
                  "refinement; its upper bound is that of nodes"),
    "rtol": (RTOL_MIN, RTOL_MAX,
             f"a relative accuracy target in [{RTOL_MIN:g}, {RTOL_MAX:g}]: tighter than 1e-10 "
             "is below what the edge estimates resolve on the largest meshes; looser than 1e-2 "
             "is not an answer"),
    "material": (None, None,
                 f"a bem.Prony creep function with J0 in [{J0_MIN:g}, {J0_MAX:g}] (compliances in "
                 f"1/E_ref: choose E_ref a modulus of the material), creep times in [{TAU_MIN:g}, "
                 f"{TAU_MAX:g}] τ_ref, each non-zero J_i at least {TERM_MIN:g} J(0+), and "
                 f"E∞/E0 = J0/J(0+) either 1 (no term: elastic) or in (1 + {RATIO_EPS:g}, "
                 f"{RATIO_MAX:g}]: outside, the relaxation times and the kernel under/overflow "
                 "or the iterations stop converging (see ratio)"),
    "profile": (HK_MIN, HK_MAX,
                "a bem.Sinusoid, bem.Harmonics or bem.SampledProfile with a finite amplitude "
                f"(max k y − mean k y) in [{HK_MIN:g}, {HK_MAX:g}] (as hk)"),
}


def _integer(name, value):
    low, high, text = ACCEPTED[name]
    return integer(name, value, text, lambda v: low <= v <= high
                   and not (name == "max_nodes" and v & (v - 1)))


def _check_material(material):
    from ._inputs import Prony
    text = ACCEPTED["material"][2]
    if not isinstance(material, Prony):
        raise bad("material", material, text)
    jp = material.j_plus
    if not J0_MIN <= material.J0 <= J0_MAX:
        raise bad("material", material, f"J0={material.J0!r} is outside [{J0_MIN:g}, {J0_MAX:g}] 1/E_ref; {text}")
    for j, t in material.terms:
        if not TAU_MIN <= t <= TAU_MAX:
            raise bad("material", material, f"tau_i={t!r} is outside [{TAU_MIN:g}, {TAU_MAX:g}] τ_ref; {text}")
        if 0.0 < j < TERM_MIN * jp:
            raise bad("material", material, f"J_i={j!r} is below {TERM_MIN:g} J(0+); {text}")
    ratio = material.J0 / jp
    if any(j > 0.0 for j in material.J) and not 1.0 + RATIO_EPS < ratio <= RATIO_MAX:
        raise bad("material", material, f"E∞/E0 = J0/J(0+) = {ratio!r} is outside (1 + {RATIO_EPS:g}, {RATIO_MAX:g}]; {text}")
    return material


def _check_profile(profile):
    from ._inputs import _Profile
    text = ACCEPTED["profile"][2]
    if not isinstance(profile, _Profile):
        raise bad("profile", profile, text)
    amp = float(profile.amplitude)
    if not (math.isfinite(amp) and HK_MIN <= amp <= HK_MAX):
        raise bad("profile", profile, f"its amplitude is {amp!r}; {text}")
    return amp


def validate(*, load=None, penetration=None, speed=None, ratio=None, hk=None, profile=None,
             material=None, nodes=None, rtol=None, max_nodes=None, layer=None,
             **solver_options):
    """Check the inputs of `bem.solve` against `ACCEPTED`.

    Parameters
    ----------
    load, penetration, speed, ratio, hk, profile, material, nodes, rtol, max_nodes
        As in `bem.solve`; None means "not given" and is not checked.  At most one of load and
        penetration, of ratio and material, of hk and profile.
    layer : bem.Layer, optional
        As in `bem.solve`: checked to be a Layer whose lowest mode the fixed mesh (or the
        adaptive mesh's first grid) keeps within its round-off budget (`_layer.finest_nodes`),
        and, under penetration control, one the penetration does not cross: Δ < d, that is
        (Δ/h) hk < k d (the approach from the undeformed face is Δ plus the mean compression,
        never less).
    **solver_options
        Further options of `bem.solve` (tol, max_outer, …): not checked here (`bem.solve`
        checks them).

    Returns
    -------
    dict
        The given numeric inputs as Python floats (nodes, max_nodes as int).

    Raises
    ------
    ValueError
        ``"name=value is not allowed: what is allowed (and why)"`` for the first bad input.
    """
    at_most_one_control(load, penetration)
    if ratio is not None and material is not None:
        raise ValueError(f"ratio={ratio!r} is not allowed: no ratio with material=… (the Prony "
                         "series fixes the moduli)")
    if hk is not None and profile is not None:
        raise ValueError(f"hk={hk!r} is not allowed: no hk with profile=… (the profile fixes the "
                         "amplitude)")
    out = check_reals(ACCEPTED, (("penetration", penetration), ("speed", speed),
                                 ("ratio", ratio), ("hk", hk), ("rtol", rtol)),
                      {"ratio": lambda v: 1.0 + RATIO_EPS < v <= RATIO_MAX,
                       "speed": lambda v: v == 0.0 or SPEED_MIN <= v <= SPEED_MAX})
    amp = out.get("hk", 1.0)
    if profile is not None:
        amp = _check_profile(profile)
    if material is not None:
        _check_material(material)
    if load is not None:
        v = real("load", load, ACCEPTED["load"][2], kind=True)
        low, high = LOAD_OVER_AMPLITUDE
        if not (v > 0.0 and low <= v / amp <= high):
            raise bad("load", v, ACCEPTED["load"][2] + f" (here hk = {amp!r})")
        out["load"] = v
    for name, value in (("nodes", nodes), ("max_nodes", max_nodes)):
        if value is not None:
            out[name] = _integer(name, value)
    if layer is not None:
        _check_layer(layer, out.get("nodes"), out.get("penetration"), amp)
    return out


def _check_layer(layer, nodes, penetration, amp):
    """A layer `validate` accepts (see there); ValueError naming the input at fault."""
    from ._grid import START_NODES
    from ._layer import SYMBOL_ROUNDOFF_BUDGET, Layer, finest_nodes
    if not isinstance(layer, Layer):
        raise bad("layer", layer, "a bem.Layer (thickness k d, foundation, nu) or None (the "
                  "half-space)")
    finest = finest_nodes(layer)
    if (nodes if nodes is not None else START_NODES) > finest:
        name, value = ("nodes", nodes) if nodes is not None else ("layer", layer)
        raise bad(name, value, f"at most {finest} panels with this layer (k d = "
                  f"{layer.thickness:g}, S(kd) = {float(layer.factor([1.0])[0]):.3g}): the "
                  "layer's lowest mode, S(kd) times the half-space's, would carry a relative "
                  f"round-off above {SYMBOL_ROUNDOFF_BUDGET:g} on more panels")
    if penetration is not None and penetration * amp >= layer.thickness:
        raise bad("penetration", penetration, f"Δ/h < k d/hk = {layer.thickness / amp:.6g} "
                  f"(k d = {layer.thickness:g}, hk = {amp:g}): a penetration the layer can "
                  "take; deeper, the indenter would reach the foundation")

