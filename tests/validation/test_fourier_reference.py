"""The Fourier-collocation reference (`analytic.references.fourier`): identities, closed forms,
limits, invariances and the cross-check against the semi-analytic solver.

The reference shares no code with either road's solver; these tests hold it to the standard
linear solid, where the semi-analytic road is exact to ~1e-10, and to the identities any
material must satisfy.  The solves use a small configuration (levels 512, 1024, 2048 with 8
shifts, ~0.5 s a point) whose worst errors over 20 resolved points (E∞/E0 3 and 10, V/V0 0.1 to
10, loads 0.05 to 0.45 and Δ/h = 0.6) were measured at 5.5e-6 (ka, a contact of 2 % of the
period), 1.4e-6 (ke), 5e-8 (kê), 1.1e-7 (Δ/h, relative), 5.6e-7 (μ, relative), each within
1.05 times the solver's own estimate; the tiers below are those worst errors with a margin of
about two.
"""
import math

import numpy as np
import pytest

import analytic
from analytic import westergaard
from analytic.references import fourier
from analytic.references.fourier import _grid
from analytic.full_contact import friction_stress, modulus
from conftest import ROUNDOFF

FAST = {"nodes": (512, 1024, 2048), "shifts": 8}
#: discretisation tiers of FAST (absolute for ka, ke, kê; relative for Δ/h, μ, load)
TOL = {"ka": 1e-5, "ke": 3e-6, "ke_hat": 1e-7, "penetration": 3e-7, "mu": 1e-6, "load": 3e-7}
RELATIVE = ("penetration", "mu", "load")
#: a solve of the same problem written two ways differs by the rounding of the operator
#: (~1e-16) carried through the restricted solve and the edge fit: measured below 1e-14 on
#: every scalar, so the ROUNDOFF tier
SAME = ROUNDOFF


def _err(key, got, want):
    return abs(got / want - 1.0) if key in RELATIVE else abs(got - want)


# ------------------------------------------------------------------ material identities
@pytest.mark.parametrize("ratio", [1.5, 3.0, 100.0])
@pytest.mark.parametrize("speed", [0.0, 1e-3, 1.0, 1e3])
def test_sls_compliance_and_modulus_in_both_forms(ratio, speed):
    """J* = (1 − inw/ρ)/(1 − inw) from the creep form, E* = (1 − inw)/(1 − inw/ρ) from the
    relaxation form (E_r = 1, E_1 = ρ − 1, θ_1 = 1/ρ): J*E* = 1, Im J* > 0 for n > 0."""
    n = np.array([1.0, 2.0, 7.0, 1000.0])
    relax = (1.0, [ratio - 1.0], [1.0 / ratio])
    j = fourier.complex_compliance(n, speed, ratio=ratio)
    e = fourier.complex_modulus(n, speed, relaxation=relax)
    x = n * speed
    np.testing.assert_allclose(j, (1 - 1j * x / ratio) / (1 - 1j * x), rtol=ROUNDOFF)
    np.testing.assert_allclose(e, (1 - 1j * x) / (1 - 1j * x / ratio), rtol=ROUNDOFF)
    np.testing.assert_allclose(j * e, 1.0, rtol=ROUNDOFF)
    np.testing.assert_allclose(fourier.complex_compliance(n, speed, relaxation=relax), j,
                               rtol=ROUNDOFF)
    if speed > 0.0:
        assert np.all(j.imag > 0.0) and np.all(e.imag < 0.0)


def test_spectra_of_the_two_forms():
    """The relaxation time of the SLS is τE0/E∞; a relaxation series' creep form (partial
    fractions at the zeros of E(s)) has the compliance 1/E* at every mode."""
    sls = fourier.material(ratio=4.0)
    assert sls.relaxation_times() == pytest.approx((0.25,), rel=ROUNDOFF)
    back = fourier.material(relaxation=(1.0, [3.0], [0.25])).creep_terms()
    assert back[0] == pytest.approx(0.25, rel=ROUNDOFF)
    assert back[1][0] == pytest.approx((0.75, 1.0), rel=ROUNDOFF)
    relax = (0.5, [1.0, 2.0, 0.3], [0.01, 1.0, 30.0])
    jplus, terms = fourier.material(relaxation=relax).creep_terms()
    creep = (jplus + sum(a for a, _ in terms), [a for a, _ in terms], [t for _, t in terms])
    n = np.array([1.0, 3.0, 40.0])
    for speed in (0.0, 0.05, 2.0, 300.0):
        np.testing.assert_allclose(fourier.complex_compliance(n, speed, creep=creep),
                                   1.0 / fourier.complex_modulus(n, speed, relaxation=relax),
                                   rtol=ROUNDOFF)


# ------------------------------------------------------------------ full contact (Appendix B)
@pytest.mark.parametrize("ratio", [3.0, 10.0])
@pytest.mark.parametrize("speed", [0.0, 0.01, 1.0, 5.0, 1e4])
@pytest.mark.parametrize("hk", [0.5, 1.0, 2.0])
def test_full_contact_closed_form_against_the_semi_analytic_road(ratio, speed, hk):
    fc = fourier.full_contact(speed, hk=hk, ratio=ratio)
    fr = fourier.full_contact(speed, hk=hk, relaxation=(1.0, [ratio - 1.0], [1.0 / ratio]))
    mag, delta = modulus(speed, ratio)
    for f in (fc, fr):
        assert f["load_threshold"] == pytest.approx(analytic.transition_load(speed, ratio, hk),
                                                    rel=ROUNDOFF)
        assert f["tau_f"] == pytest.approx(friction_stress(speed, ratio, hk), rel=ROUNDOFF,
                                           abs=1e-300)
        assert f["ke_hat"] == pytest.approx(delta, rel=ROUNDOFF, abs=1e-300)
    load = 1.2 * fc["load_threshold"]
    res = fourier.fourier_solve(load=load, speed=speed, ratio=ratio, hk=hk)
    ref = analytic.solve(load=load, speed=speed, ratio=ratio, hk=hk)
    assert res.success and res.full_contact and ref.full_contact and res.ke is None
    for key in ("ka", "ke_hat", "penetration", "tau_f", "mu"):
        assert getattr(res, key) == pytest.approx(getattr(ref, key), rel=ROUNDOFF, abs=1e-300)


def test_full_contact_of_a_general_series_and_its_threshold():
    """For any series: the closed-form pressure at p̃FC is ≥ 0 with its minimum at 0, and
    just below p̃FC the collocation finds a contact that fills nearly the whole period."""
    creep = (1.0, [0.5, 0.3], [0.2, 5.0])
    fc = fourier.full_contact(0.7, creep=creep)
    at = fourier.fourier_solve(penetration=1.0, speed=0.7, creep=creep)
    assert at.full_contact and at.load == pytest.approx(fc["load_threshold"], rel=ROUNDOFF)
    # sampled on 1024 points, the zero at the trough is missed by at most ~(π/1024)² of the
    # amplitude
    assert 0.0 <= at.pressure.min() <= 1e-5 * at.pressure.max()
    below = fourier.fourier_solve(load=0.97 * fc["load_threshold"], speed=0.7, creep=creep,
                                  **FAST)
    assert below.success and not below.full_contact and below.contact_fraction > 0.8
    assert below.mu > fc["tau_f"] / fc["load_threshold"]   # more friction than at transition


# ------------------------------------------------------------------ against the semi-analytic road
POINTS = [dict(load=0.05, speed=0.1, ratio=3.0), dict(load=0.45, speed=0.1, ratio=3.0),
          dict(load=0.3, speed=1.0, ratio=3.0), dict(load=0.05, speed=10.0, ratio=10.0),
          dict(load=0.45, speed=10.0, ratio=3.0), dict(penetration=0.6, speed=1.0, ratio=10.0)]


@pytest.mark.parametrize("point", POINTS, ids=lambda p: "-".join(f"{k}{v:g}" for k, v in
                                                                  p.items()))
def test_against_the_semi_analytic_road(point):
    res = fourier.fourier_solve(**point, **FAST)
    ref = analytic.solve(**point)
    assert res.success and not res.full_contact and ref.success, res.message
    for key, tol in TOL.items():
        err = _err(key, getattr(res, key), getattr(ref, key))
        assert err <= tol, (key, err)
        # the estimate is honest to within the measured factor (1.05) plus a margin (the
        # control itself is exact: estimate 0, error rounding)
        assert err <= 2.0 * res.error_estimate[key] + ROUNDOFF, (key, err,
                                                                 res.error_estimate[key])


def test_fields_satisfy_the_contact_conditions():
    res = fourier.fourier_solve(load=0.3, speed=1.0, ratio=3.0, **FAST)
    p, g, v = res.pressure, res.gap, res.displacement
    assert p.min() >= -1e-12 * p.max() and g.min() >= -1e-12
    assert np.max(np.abs(p * g)) <= 1e-12 * p.max()
    assert p.mean() == pytest.approx(0.3, rel=1e-12)
    assert abs(v.mean()) <= 1e-12          # v from the mean line of the deformed surface
    assert np.all(g[p > 0.0] == 0.0) and np.all(g[p == 0.0] > 0.0)
    (patch,) = res.patches
    assert patch["width"] == pytest.approx(res.contact_fraction, rel=1e-6)
    assert patch["load"] == pytest.approx(0.3, rel=1e-12)


def test_displacement_is_the_fourier_series_of_the_pressure():
    """Identity: the displacement field of a solved grid against the dense sum
    k v(X_j) = Σ_n (2/|n|) J*(n) σ̂_n e^{2πinX_j} (Nyquist: real part), summed directly."""
    creep = (1.0, [0.5, 0.3], [0.2, 5.0])
    res = fourier.fourier_solve(load=0.2, speed=0.7, creep=creep, nodes=(512, 1024), shifts=2)
    assert res.success and res.x_over_lambda.size == 1024
    x, p = res.x_over_lambda, res.pressure
    n = np.arange(-511, 513)                                 # N = 1024: modes −511 … 512
    shat = np.exp(-2j * np.pi * np.outer(n, x)) @ p / x.size
    sym = np.zeros(n.size, dtype=complex)
    nz = n != 0
    sym[nz] = 2.0 / np.abs(n[nz]) * fourier.complex_compliance(np.abs(n[nz]), 0.7, creep=creep)
    sym[n < 0] = np.conj(sym[n < 0])                         # J*(−n) = conj J*(n)
    sym[n == 512] = sym[n == 512].real
    v = (np.exp(2j * np.pi * np.outer(x, n)) @ (sym * shat)).real
    np.testing.assert_allclose(res.displacement, v / res.hk, atol=1e-13)


def test_toeplitz_solve_matches_dense_lu():
    """Identity: the restricted solve by Levinson's recursion (one patch) against dense LU."""
    rng = np.random.default_rng(7)
    n = 256
    modes = np.arange(n // 2 + 1, dtype=float)
    sym = np.zeros(modes.size, dtype=complex)
    sym[1:] = 2.0 / modes[1:] * fourier.complex_compliance(modes[1:], 1.0, ratio=10.0)
    sym[0] = sym[1].real
    col = np.fft.irfft(sym, n)
    idx = (200 + np.arange(150)) % n                          # a run through the period's end
    idx.sort()
    rhs = rng.standard_normal((idx.size, 2))
    lev = _grid._restricted_solve(col, [(200, 150)], idx, rhs)
    dense = _grid._restricted_solve(col, [(200, 100), (44, 50)], idx, rhs)  # forces LU
    np.testing.assert_allclose(lev, dense, rtol=0, atol=1e-11 * np.abs(dense).max())


def test_shift_averaging_removes_most_of_the_grid_error():
    """On 2048 points a single grid errs by ~1e-7 (Δ/h, μ) and ~1e-5 (ka), with a sign that
    follows the edges' positions between the points; eight shifted grids averaged err by
    ~20 to 40 times less (measured), here asked for ten."""
    point = dict(load=0.3, speed=1.0, ratio=3.0)
    ref = analytic.solve(**point)
    one = fourier.fourier_solve(**point, nodes=(512, 1024, 2048), shifts=1).levels[-1]
    avg = fourier.fourier_solve(**point, nodes=(512, 1024, 2048), shifts=8).levels[-1]
    for key in ("penetration", "mu", "ka"):
        e1 = abs(one["scalars"][key] - getattr(ref, key))
        e8 = abs(avg["scalars"][key] - getattr(ref, key))
        assert e8 < 0.1 * e1, (key, e1, e8)


def test_default_configuration_certifies_at_1e_minus_6():
    """The defaults (1024 … 8192 points, 16 shifts) on one point: errors measured at 3e-9 (ka),
    4e-9 (ke), 1e-10 (kê, Δ/h, μ), well inside the 1e-6 a BEM is certified at."""
    point = dict(load=0.3, speed=1.0, ratio=3.0)
    res = fourier.fourier_solve(**point)
    ref = analytic.solve(**point)
    for key in ("ka", "ke", "ke_hat", "penetration", "mu"):
        err = _err(key, getattr(res, key), getattr(ref, key))
        assert err <= 3e-8 and err <= 2.0 * res.error_estimate[key], (key, err)
        assert res.error_estimate[key] <= 1e-7, key


# ------------------------------------------------------------------ the same problem two ways
def _scalars(res):
    return {k: getattr(res, k) for k in ("contact_fraction", "ka", "ke", "ke_hat", "penetration",
                                         "tau_f", "mu", "load")}


def _same(a, b):
    assert a.success and b.success
    sa, sb = _scalars(a), _scalars(b)
    for key in sa:
        assert sa[key] == pytest.approx(sb[key], rel=SAME, abs=SAME), key


def test_creep_and_relaxation_forms_give_the_same_answer():
    kw = dict(load=0.3, speed=1.0, **FAST)
    _same(fourier.fourier_solve(ratio=3.0, **kw),
          fourier.fourier_solve(relaxation=(1.0, [2.0], [1.0 / 3.0]), **kw))
    # a two-term series: its relaxation form by partial fractions written out here
    # (independently of the module's root search), J(s) = J+ + Σ J_i/(1 + sτ_i)
    jp, j1, j2, t1, t2 = 0.3, 0.5, 0.2, 0.1, 2.0
    num = np.polymul([t1, 1.0], [t2, 1.0])                       # (1 + sτ1)(1 + sτ2)
    den = np.polyadd(jp * num, np.polyadd(j1 * np.array([t2, 1.0]), j2 * np.array([t1, 1.0])))
    # J(s) = den/num, so E(s) = num/den
    roots = np.roots(den).real                                  # poles r_k = −1/θ_k of E(s)
    # E(s) = E∞ − Σ E_k/(1 + sθ_k): the residue of E at r_k is −E_k/θ_k
    thetas = -1.0 / roots
    amps = -thetas * np.polyval(num, roots) / np.polyval(np.polyder(den), roots)
    relax = (num[0] / den[0] - amps.sum(), list(amps), list(thetas))
    creep = (jp + j1 + j2, [j1, j2], [t1, t2])
    kw = dict(load=0.2, speed=0.8, **FAST)
    _same(fourier.fourier_solve(creep=creep, **kw), fourier.fourier_solve(relaxation=relax, **kw))


def test_splitting_a_term_changes_nothing():
    kw = dict(load=0.3, speed=1.0, **FAST)
    j1 = 2.0 / 3.0
    _same(fourier.fourier_solve(ratio=3.0, **kw),
          fourier.fourier_solve(creep=(1.0, [0.5 * j1, 0.5 * j1], [1.0, 1.0]), **kw))
    _same(fourier.fourier_solve(relaxation=(1.0, [2.0], [1.0 / 3.0]), **kw),
          fourier.fourier_solve(relaxation=(1.0, [1.0, 1.0], [1.0 / 3.0, 1.0 / 3.0]), **kw))


@pytest.mark.parametrize("c", [1e-3, 7.0])
def test_scaling_every_time_by_c_and_the_speed_by_1_over_c_changes_nothing(c):
    creep = (1.0, [0.4, 0.3], [0.5, 4.0])
    scaled = (1.0, [0.4, 0.3], [0.5 * c, 4.0 * c])
    _same(fourier.fourier_solve(load=0.25, speed=0.6, creep=creep, **FAST),
          fourier.fourier_solve(load=0.25, speed=0.6 / c, creep=scaled, **FAST))


# ------------------------------------------------------------------ Westergaard limits
CREEP = (1.0, [0.5, 0.3], [0.2, 5.0])    # J0 = 1, J(0+) = 0.2: relaxed E 1, glassy E 5


@pytest.mark.parametrize("speed,compliance", [(0.0, 1.0), (1e9, 0.2)])
def test_speed_limits_are_westergaard(speed, compliance):
    """V → 0: elastic with the relaxed compliance J0; V → ∞ (memory lengths 1e8 periods, so
    viscous corrections ~1e-9): elastic with the glassy J(0+); both frictionless."""
    m = 1.0 / compliance
    load = 0.4 * westergaard.full_contact_load(1.0, m)
    res = fourier.fourier_solve(load=load, speed=speed, creep=CREEP, **FAST)
    assert res.success
    assert res.ka == pytest.approx(westergaard.half_angle(load, 1.0, m), abs=TOL["ka"])
    assert res.penetration == pytest.approx(westergaard.penetration(load, 1.0, m),
                                            rel=TOL["penetration"])
    assert abs(res.ke) <= TOL["ke"] and abs(res.ke_hat) <= TOL["ke_hat"]
    assert res.mu <= 1e-8


def test_unresolved_memory_is_refused_and_small_speed_tends_to_westergaard():
    """At V/V0 = 1e-9 the pressure relaxes over 1e-10 λ: refused by default; asked for anyway,
    the answer is Westergaard's with J0 (the memory moves it by ~1e-9)."""
    load = 0.4 * westergaard.full_contact_load(1.0, 1.0)
    res = fourier.fourier_solve(load=load, speed=1e-9, creep=CREEP, **FAST)
    assert not res.success and "memory layer" in res.message and math.isnan(res.mu)
    res = fourier.fourier_solve(load=load, speed=1e-9, creep=CREEP, require_resolved=False,
                                **FAST)
    assert res.success and any("memory layer" in w for w in res.warnings)
    assert res.ka == pytest.approx(westergaard.half_angle(load, 1.0, 1.0), abs=TOL["ka"])
    assert res.penetration == pytest.approx(westergaard.penetration(load, 1.0, 1.0),
                                            rel=TOL["penetration"])
    length, resolved = fourier.memory_resolution(0.1, 8192, ratio=100.0)
    assert length == pytest.approx(0.1 / (2 * math.pi * 100.0)) and not resolved


# ------------------------------------------------------------------ Richardson
def test_richardson_recovers_a_clean_order_and_refuses_noise():
    ns = [512, 1024, 2048, 4096]
    q = [2.0 + 3.0 * n ** -2.0 + 5.0 * n ** -3.0 for n in ns]
    value, est, order, extra = fourier.richardson(ns, q)
    assert extra and order == pytest.approx(2.0, abs=0.1)
    assert abs(value - 2.0) < 0.2 * abs(q[-1] - 2.0) and abs(value - 2.0) <= est
    noisy = [2.0 + e for e in (1e-6, -2e-7, 3e-7, -1e-8)]
    value, est, order, extra = fourier.richardson(ns, noisy)
    assert not extra and value == noisy[-1] and est >= abs(noisy[-1] - noisy[-2])


# ------------------------------------------------------------------ bad input
GOOD = dict(load=0.3, speed=1.0)
BAD = [
    ("load", 0.0), ("load", -1.0), ("load", math.nan), ("load", "0.3"),
    ("penetration", 0.0), ("penetration", 1.5), ("penetration", math.inf),
    ("speed", -1.0), ("speed", math.nan), ("speed", True),
    ("hk", 0.0), ("hk", math.inf),
    ("ratio", 0.5), ("ratio", math.nan),
    ("creep", (1.0, [1.0], [1.0])), ("creep", (1.0, [0.5], [-1.0])),
    ("creep", (1.0, [0.2, 0.3], [1.0])), ("creep", 3.0),
    ("relaxation", (0.0, [1.0], [1.0])), ("relaxation", (1.0, [-1.0], [1.0])),
    ("nodes", 1023), ("nodes", 16384), ("nodes", (2048, 1024)), ("nodes", 32),
    ("shifts", 0), ("shifts", 65), ("shifts", 2.0),
    ("require_resolved", "yes"),
]


@pytest.mark.parametrize("name,value", BAD, ids=lambda v: repr(v))
def test_bad_input_names_parameter_value_and_what_is_allowed(name, value):
    kw = dict(GOOD)
    if name == "penetration":
        kw.pop("load")
    kw[name] = value
    with pytest.raises(ValueError) as exc:
        fourier.fourier_solve(**kw)
    msg = str(exc.value)
    assert msg.startswith(f"{name}={value!r} is not allowed: "), msg


def test_controls_and_materials_are_exclusive():
    with pytest.raises(ValueError, match=r"^load=0\.3, penetration=0\.5 is not allowed"):
        fourier.fourier_solve(load=0.3, penetration=0.5, speed=1.0)
    with pytest.raises(ValueError, match=r"^load=None, penetration=None is not allowed"):
        fourier.fourier_solve(speed=1.0)
    with pytest.raises(ValueError, match=r"^creep=.* is not allowed: one material only"):
        fourier.fourier_solve(load=0.3, speed=1.0, ratio=3.0, creep=(1.0, [0.5], [1.0]))
