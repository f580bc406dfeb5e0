"""The inputs the semi-analytic road accepts, with the reason for every bound.

Everything inside these ranges is solved (or, if a root search ever failed, reported as a
failure with its residuals); everything outside is refused up front with a ValueError naming
the parameter, its value and what is allowed.  The bounds are where double precision, not the
physics, runs out, and they were verified by property-based tests over the whole box
(`tests/analytic/test_analytic_properties.py`) and a random sample of it (see docs/accuracy.md).

Units as in `analytic/__init__.py`: load p̃∞ = p∞(1 − ν²)/E0, penetration Δ/h, speed
V/V0 = Vτk, ratio E∞/E0, hk = h k.
"""
from __future__ import annotations

from viscosine.checks import at_most_one_control, check_reals

#: speeds in (0, SPEED_MIN) and above SPEED_MAX are refused; 0 is Westergaard's solution
SPEED_MIN, SPEED_MAX = 1e-30, 1e30
LOAD_MIN, LOAD_MAX = 1e-40, 1e40
PENETRATION_MIN = 1e-40
RATIO_MAX = 1e8
HK_MIN, HK_MAX = 1e-6, 1e6

#: name -> (low, high, "what is allowed: why").  Bounds are inclusive except ratio > 1.  The
#: command line shows only what is allowed (up to the first ': ', `viscosine.checks.allowed_part`),
#: so keep that part short.
ACCEPTED = {
    "load": (LOAD_MIN, LOAD_MAX,
             f"a mean pressure p̃∞ = p∞(1 − ν²)/E0 in [{LOAD_MIN:g}, {LOAD_MAX:g}]: the contact "
             "half-width ka ≈ 2√(p̃∞/(hk·E/E0)) and the products of small quantities in the "
             "friction stay far from underflow (verified over the whole accepted box); above, "
             "full contact, whose μ = τ̃f/p̃∞ is closed-form and would only approach underflow"),
    "penetration": (PENETRATION_MIN, 1.0,
                    f"a penetration Δ/h in [{PENETRATION_MIN:g}, 1] (1 is the transition to full "
                    "contact): below, the contact is narrower than the smallest load resolves"),
    "speed": (0.0, SPEED_MAX,
              f"V/V0 = Vτk equal to 0 or in [{SPEED_MIN:g}, {SPEED_MAX:g}]: 0 is elastic "
              "(Westergaard with E0); beyond, the viscoelastic corrections (ke, kê, μ ~ V/V0 or V0/V) "
              "fall below 1e-30 of the elastic solution and the memory layers below 1e-30 of the "
              "contact, a scale the quadrature is not verified on"),
    "ratio": (1.0, RATIO_MAX,
              f"E∞/E0 > 1 and ≤ {RATIO_MAX:g}: 1 is the elastic material (no standard linear "
              "solid); measured polymers across their glass transition reach 1e4 … 1e7; above "
              "1e8, Δ/h at light load and high speed (a difference of terms ρ times larger) "
              "would carry more than ~1e-8 relative rounding"),
    "hk": (HK_MIN, HK_MAX,
           f"hk in [{HK_MIN:g}, {HK_MAX:g}]: hk only scales the load (p̃∞/hk), pressures (hk) "
           "and friction ((hk)²); the bounds keep those scales far from under/overflow for every "
           "accepted load (the half-space theory itself asks for hk ≪ 1)"),
}


def validate(*, load=None, penetration=None, speed=None, ratio=None, hk=None):
    """Check the dimensionless inputs against `ACCEPTED`.

    Parameters
    ----------
    load, penetration, speed, ratio, hk : float or None
        As in `analytic.solve`; None means "not given" and is not checked.  At most one of load
        and penetration.

    Returns
    -------
    dict
        The given inputs as Python floats.

    Raises
    ------
    ValueError
        ``"name=value is not allowed: what is allowed (and why)"`` for the first bad input.
    """
    at_most_one_control(load, penetration)
    return check_reals(ACCEPTED, (("load", load), ("penetration", penetration),
                                  ("speed", speed), ("ratio", ratio), ("hk", hk)),
                       {"ratio": lambda v: 1.0 < v <= RATIO_MAX,
                        "speed": lambda v: v == 0.0 or SPEED_MIN <= v <= SPEED_MAX})
