"""The Fourier reference on a layer (`analytic.fourier_solve(layer=...)`, its layer factor).

The layer factor S of `analytic.references._layer` is solved there from Navier's equations (a 4 x 4
system per mode); here it is held to the closed forms of docs/layers.md §1, typed in and evaluated
in 50-digit decimal arithmetic.  The solver is held to the half-space (bit for bit without a layer
and for a layer thick enough that every S is 1), to the full-contact closed form, and to the BEM
road (`bem.solve(layer=bem.Layer(...))`) at partial contact, each within the sum of the two codes'
error estimates.

Measured here (FAST: levels 512, 1024, 2048, 8 shifts): S within 1.0e-15 (5 ulp) of the closed
forms over t in [1e-3, 60] and the five ν; at the eight BEM points (the BEM adaptive at its
default rtol) the worst |BEM − reference| is 0.21 of the sum of the estimates (contact
fraction; μ 0.14, Δ/h 0.13), relative deviations up to 2.0e-6, 6.7e-7 and 4.8e-8.
"""
import dataclasses
import math
from decimal import Decimal, localcontext

import numpy as np
import pytest
import scipy.linalg

import analytic
import bem
from analytic.references import _layer, fourier
from analytic.references.fourier import _grid, _measure
from bem import _layer as bem_layer
from conftest import ROUNDOFF

FAST = {"nodes": (512, 1024, 2048), "shifts": 8}
FOUNDATIONS = ("bonded", "frictionless")
NUS = (-0.9, 0.0, 0.3, 0.49, 0.5)
SCALARS = ("load", "contact_fraction", "ka", "ke", "ke_hat", "penetration", "tau_f", "mu")
#: the 3-term creep series of the cross-check: J(0+) = 0.25, relaxation times 0.13 … 24
CREEP3 = (1.0, [0.3, 0.25, 0.2], [0.3, 3.0, 30.0])


def closed_form(t, nu, foundation):
    """docs/layers.md §1, the forms in q = e^{−2t} (κ = 3 − 4ν), in 50 digits: the bonded
    numerator cancels to O(t³) at ν = ½, which double precision would not survive."""
    with localcontext() as ctx:
        ctx.prec = 50
        t, nu = Decimal(float(t)), Decimal(float(nu))
        q = (-2 * t).exp()
        if foundation == "bonded":
            k = 3 - 4 * nu
            s = (k * (1 - q * q) - 4 * t * q) / (k * (1 + q * q) + (1 + k * k + 4 * t * t) * q)
        else:
            s = (1 - q) ** 2 / ((1 - q * q) + 4 * t * q)
        return float(s)


def _layer_of(kd, foundation, nu):
    return {"thickness": kd, "foundation": foundation, "nu": nu}


# ------------------------------------------------------------------ the layer factor
@pytest.mark.parametrize("foundation", FOUNDATIONS)
@pytest.mark.parametrize("nu", NUS)
def test_layer_factor_against_the_closed_forms(foundation, nu):
    t = np.concatenate([np.geomspace(1e-3, 60.0, 150),
                        [np.nextafter(_layer.T_SWITCH, 0.0), _layer.T_SWITCH]])
    got = analytic.layer_factor(t, nu, foundation)
    want = np.array([closed_form(v, nu, foundation) for v in t])
    err = np.abs(got / want - 1.0)
    assert err.max() <= 1e-13, (t[np.argmax(err)], err.max())


def _navier_matrix(nu):
    a, b, c = nu / (1 - nu), (1 - 2 * nu) / (2 * (1 - nu)), 2 / (1 - nu)
    return np.array([[0, -1, 1, 0], [a, 0, 0, b], [c, 0, 0, -a], [0, 0, 1, 0]], float)


@pytest.mark.parametrize("nu", NUS)
def test_the_two_constructions_solve_navier(nu):
    """The decaying functions satisfy y' = M y (complex-step derivative, exact to rounding) and
    the Taylor coefficients sum to exp(M t) (scipy's expm)."""
    m = _navier_matrix(nu)
    t = np.array([1.5, 4.0])
    for zeta in (0.0, 0.7, 1.5):
        h = 1e-30
        z = np.full(2, zeta) + 1j * h
        d = _layer._basis(z, t, nu).imag / h
        y = _layer._basis(np.full(2, zeta), t, nu)
        np.testing.assert_allclose(d, m @ y, rtol=0, atol=1e-14 * np.abs(y).max())
    coef = _layer._taylor(nu)
    for tt in (0.3, 0.999):
        series = sum(c * tt ** j for j, c in enumerate(coef))
        np.testing.assert_allclose(series, scipy.linalg.expm(m * tt), rtol=1e-14, atol=1e-15)


@pytest.mark.parametrize("foundation", FOUNDATIONS)
def test_thick_and_zero_thickness(foundation):
    """S = 1 exactly from T_HALF_SPACE on (1 − S < 2^-54 from t ≈ 22.6 at worst), below it
    1 − S follows the first reflection between the faces; S(0) = 0."""
    beyond = np.array([_layer.T_HALF_SPACE, 30.0, 1e3, np.inf])
    for nu in (0.5, 0.3, -0.9):
        np.testing.assert_array_equal(analytic.layer_factor(beyond, nu, foundation), 1.0)
        assert analytic.layer_factor(20.0, nu, foundation) < 1.0
        assert analytic.layer_factor(0.0, nu, foundation) == 0.0
        kappa = 3 - 4 * nu
        t = 12.0
        lead = (((1 + 2 * t) ** 2 + kappa ** 2) / kappa if foundation == "bonded"
                else 2 * (1 + 2 * t)) * math.exp(-2 * t)
        assert 1 - analytic.layer_factor(t, nu, foundation) == pytest.approx(lead, rel=1e-5)


@pytest.mark.parametrize("nu", [-0.9, 0.0, 0.3, 0.49, 0.5])
def test_the_uniform_mode(nu):
    """C of the uniform mode: the bonded layer in uniaxial strain, C = lim 2S/t; the
    frictionless one free to spread (ends free: no resultant lateral stress), C = 1 = lim 2S/t;
    held ends would give the bonded value.  The BEM road's `uniform_compliance` gives the same
    numbers for the same definitions (its default is the free one too)."""
    t = 1e-7
    for foundation in FOUNDATIONS:
        c = _layer.uniform_compliance(nu, foundation)
        assert 2 * analytic.layer_factor(t, nu, foundation) / t == pytest.approx(
            c, rel=1e-12, abs=1e-12)
        for lateral in ("free", "held"):
            assert _layer.uniform_compliance(nu, foundation, lateral) == pytest.approx(
                bem_layer.uniform_compliance(nu, foundation, lateral), rel=ROUNDOFF,
                abs=ROUNDOFF)
    assert _layer.uniform_compliance(nu, "frictionless", "held") == pytest.approx(
        (1 - 2 * nu) / (1 - nu) ** 2, rel=ROUNDOFF, abs=ROUNDOFF)


# ------------------------------------------------------------------ the half-space unchanged
@pytest.mark.parametrize("point", [dict(load=0.3, speed=1.0, ratio=3.0),
                                   dict(penetration=0.6, speed=1.0,
                                        creep=(1.0, [0.5, 0.3], [0.2, 5.0]))])
def test_no_layer_is_the_half_space_reference(point):
    """layer=None answers as no layer argument does, bit for bit and record for record, and
    says nothing of a layer (the half-space's code path: a thick layer, below, must then meet
    it exactly)."""
    res = fourier.fourier_solve(**point, **FAST, layer=None)
    assert res.success
    assert res.layer is None and res.approach is None and res.mean_displacement is None
    plain = fourier.fourier_solve(**point, **FAST)
    a, b = res.as_dict(), plain.as_dict()
    a.pop("elapsed"), b.pop("elapsed")
    assert a == b and "layer" not in a and "approach" not in a
    assert np.array_equal(res.pressure, plain.pressure)


@pytest.mark.parametrize("foundation, nu", [("bonded", 0.5), ("frictionless", 0.3)])
def test_a_thick_layer_is_the_half_space(foundation, nu):
    """From k d = T_HALF_SPACE on every S is 1: the same bits as the half-space reference;
    the uniform mode adds the layer's mean displacement to the approach."""
    kd = 30.0
    half = fourier.fourier_solve(load=0.3, speed=1.0, **FAST)
    res = fourier.fourier_solve(load=0.3, speed=1.0, **FAST, layer=_layer_of(kd, foundation, nu))
    assert res.success and half.success
    assert res.scalars() == half.scalars()
    assert {k: res.error_estimate[k] for k in half.error_estimate} == half.error_estimate
    for f in ("pressure", "gap", "displacement"):
        assert np.array_equal(getattr(res, f), getattr(half, f))
    c = _layer.uniform_compliance(nu, foundation)
    assert res.mean_displacement == pytest.approx(c * kd * 1.0 * 0.3, rel=ROUNDOFF)
    assert res.approach == res.penetration + res.mean_displacement
    assert res.layer["thickness"] == kd and res.layer["factor_mode_1"] == 1.0
    assert res.as_dict()["layer"]["foundation"] == foundation


# ------------------------------------------------------------------ full contact
LAYERS = [_layer_of(0.5, "bonded", 0.5), _layer_of(2.0, "frictionless", 0.3),
          _layer_of(0.1, "bonded", 0.3)]


@pytest.mark.parametrize("lay", LAYERS, ids=lambda v: f"{v['foundation']}-{v['thickness']}")
def test_full_contact_closed_form(lay):
    """p̃FC = (hk/2)|E*(1)|/S, τ̃f = −(hk)² Im E*(1)/(4S), kê = −arg E*(1), with S of the closed
    form; one grid of the collocation above p̃FC (every point in contact) gives the same
    pressure and, by its dissipation weighted by S, the same τ̃f."""
    speed, hk = 1.0, 0.8
    s = closed_form(lay["thickness"], lay["nu"], lay["foundation"])
    e1 = complex(fourier.complex_modulus([1.0], speed, creep=CREEP3)[0])
    fc = fourier.full_contact(speed, hk=hk, creep=CREEP3, layer=lay, load=3.0)
    half = fourier.full_contact(speed, hk=hk, creep=CREEP3)
    assert fc["layer_factor"] == pytest.approx(s, rel=1e-13)
    assert fc["load_threshold"] == pytest.approx(hk * abs(e1) / (2 * s), rel=ROUNDOFF)
    assert fc["tau_f"] == pytest.approx(-hk * hk * e1.imag / (4 * s), rel=ROUNDOFF)
    assert fc["ke_hat"] == half["ke_hat"]
    c = _layer.uniform_compliance(lay["nu"], lay["foundation"])
    assert fc["approach"] == pytest.approx(1.0 + c * lay["thickness"] * 1.0 * 3.0 / hk,
                                           rel=ROUNDOFF)
    # the grid: n = 256, every point active, pressure and dissipation as the closed form
    mat = fourier.material(creep=CREEP3)
    n = 256
    factor = analytic.layer_factor(np.arange(n // 2 + 1) * lay["thickness"], lay["nu"],
                                   lay["foundation"])
    load = 1.5 * fc["load_threshold"]
    grid = _grid._solve_grid(n, 0.25, mat, speed, hk, "load", load, [(-0.5, 0.5)], factor)
    assert grid.converged and grid.active.all()
    exact = load + fc["load_threshold"] * np.cos(2 * np.pi * grid.x + np.angle(e1))
    np.testing.assert_allclose(grid.sigma, exact, rtol=0, atol=1e-12 * load)
    sc, _, _ = _measure._grid_scalars(grid, mat, speed, hk, (0.25, ()), factor)
    assert sc["tau_f"] == pytest.approx(fc["tau_f"], rel=1e-11)
    assert sc["penetration"] == pytest.approx(1.0, abs=1e-12)
    # the solver in full contact: the closed form, its threshold under penetration control
    res = fourier.fourier_solve(load=load, speed=speed, hk=hk, creep=CREEP3, layer=lay)
    assert res.success and res.full_contact and res.tau_f == fc["tau_f"]
    # the 1024 samples miss the trough by at most (π/1024)²/2 of the amplitude
    amp = fc["load_threshold"]
    assert 0.0 <= res.pressure.min() - (load - amp) <= 5e-6 * amp
    at = fourier.fourier_solve(penetration=1.0, speed=speed, hk=hk, creep=CREEP3, layer=lay)
    assert at.load == fc["load_threshold"] and at.error_estimate["approach"] == 0.0


def test_full_contact_against_the_collocation_just_below():
    """Just below p̃FC the grids find a contact that fills nearly the whole period."""
    lay = _layer_of(0.5, "frictionless", 0.3)
    fc = fourier.full_contact(1.0, ratio=3.0, layer=lay)
    below = fourier.fourier_solve(load=0.97 * fc["load_threshold"], speed=1.0, layer=lay,
                                  **FAST)
    assert below.success and not below.full_contact and below.contact_fraction > 0.8
    assert below.mu > fc["tau_f"] / fc["load_threshold"]


@pytest.mark.parametrize("lay", LAYERS[:2], ids=lambda v: f"{v['foundation']}-{v['thickness']}")
def test_full_contact_against_the_bem(lay):
    """The BEM in full contact on the same layer: its threshold (panel sampling, (π/N)²/2 =
    1.2e-8 at N = 2^14) and, above it, τ̃f, μ, kê and the approach (hk = 0.2: the approach,
    at least h in full contact, stays below d, which the BEM requires)."""
    hk = 0.2
    material = bem.Prony(CREEP3[0], tuple(CREEP3[1]), tuple(CREEP3[2]))
    layer = bem.Layer(**lay)
    fc = fourier.full_contact(1.0, hk=hk, creep=CREEP3, layer=lay)
    t = bem.solve(penetration=1.0, speed=1.0, material=material, hk=hk, nodes=2 ** 14,
                  layer=layer)
    assert t.success and t.full_contact, t.message
    assert t.load == pytest.approx(fc["load_threshold"], rel=1e-7)
    load = 1.5 * fc["load_threshold"]
    fc = fourier.full_contact(1.0, hk=hk, creep=CREEP3, layer=lay, load=load)
    b = bem.solve(load=load, speed=1.0, material=material, hk=hk, nodes=2 ** 14, layer=layer)
    assert b.success and b.full_contact, b.message
    assert b.tau_f == pytest.approx(fc["tau_f"], rel=1e-7)
    assert b.mu == pytest.approx(fc["mu"], rel=1e-7)
    assert b.ke_hat == pytest.approx(fc["ke_hat"], abs=1e-7)
    assert b.diagnostics["layer"]["approach"] == pytest.approx(fc["approach"], rel=1e-9)


# ------------------------------------------------------------------ partial contact: the BEM
#: (k d, foundation, ν, material, speed, load): two thicknesses, both foundations, the standard
#: linear solid with E∞/E0 = 3 and a 3-term creep series, V/V0 from 0.1 to 10, p̃ 0.1 … 0.3
#: (with the approach below d: the BEM refuses an indenter that reaches the foundation)
BEM_POINTS = [
    (0.5, "bonded", 0.5, "sls", 1.0, 0.2),
    (0.5, "bonded", 0.3, "sls", 10.0, 0.3),
    (0.5, "frictionless", 0.3, "sls", 0.1, 0.1),
    (0.5, "frictionless", 0.0, "creep", 1.0, 0.15),
    (2.0, "bonded", 0.3, "creep", 10.0, 0.3),
    (2.0, "bonded", 0.5, "creep", 1.0, 0.1),
    (2.0, "frictionless", 0.5, "sls", 10.0, 0.2),
    (2.0, "frictionless", 0.3, "sls", 0.1, 0.3),
]


def _ids(p):
    return f"kd{p[0]}-{p[1][:4]}-nu{p[2]}-{p[3]}-w{p[4]}-p{p[5]}"


@pytest.mark.parametrize("point", BEM_POINTS, ids=_ids)
def test_against_the_bem(point):
    """|BEM − reference| within the sum of the two error estimates (the reference's relative
    for μ, Δ/h and the contact fraction; the BEM's absolute for the contact fraction), the
    uniform mode the same, the approach within the penetrations' estimates."""
    kd, foundation, nu, which, speed, load = point
    if which == "sls":
        mine, material = {"ratio": 3.0}, bem.Prony.standard_linear_solid(3.0)
    else:
        mine, material = {"creep": CREEP3}, bem.Prony(CREEP3[0], tuple(CREEP3[1]),
                                                      tuple(CREEP3[2]))
    lay = _layer_of(kd, foundation, nu)
    ref = fourier.fourier_solve(load=load, speed=speed, layer=lay, **mine, **FAST)
    b = bem.solve(load=load, speed=speed, material=material, layer=bem.Layer(**lay))
    assert ref.success and b.success, (ref.message, b.message)
    assert not ref.full_contact and not b.full_contact
    est, eb = ref.error_estimate, b.error_estimate
    for key in ("mu", "penetration"):
        r, v = getattr(ref, key), getattr(b, key)
        assert abs(v - r) <= est[key] * abs(r) + eb[key] * abs(v) + ROUNDOFF * abs(r), key
    cf, vb = ref.contact_fraction, b.contact_fraction
    assert abs(vb - cf) <= est["contact_fraction"] * cf + eb["contact_fraction"] + ROUNDOFF
    d = b.diagnostics["layer"]
    assert d["mean_displacement"] == pytest.approx(ref.mean_displacement, rel=1e-9)
    assert abs(d["approach"] - ref.approach) <= (est["penetration"] * ref.penetration
                                                 + eb["penetration"] * b.penetration + 1e-9)
    assert d["uniform_compliance"] == pytest.approx(ref.layer["uniform_compliance"], rel=ROUNDOFF)


# ------------------------------------------------------------------ resolution of d
def test_an_unresolved_thickness_is_refused_unless_asked_for():
    """A layer whose d spans under MIN_THICKNESS_POINTS points of the finest grid: refused (not
    a success), or solved with a warning; full contact (closed form) needs no grid."""
    kd = 2 * math.pi * 10.0 / 2048        # d spans 10 points of 2048
    lay = _layer_of(kd, "bonded", 0.3)
    length, resolved = fourier.thickness_resolution(kd, 2048)
    assert length == pytest.approx(10.0 / 2048, rel=ROUNDOFF) and not resolved
    assert fourier.thickness_resolution(kd, 8192)[1]
    res = fourier.fourier_solve(load=0.1, speed=1.0, layer=lay, **FAST)
    assert not res.success and "layer's thickness" in res.message and math.isnan(res.mu)
    assert math.isnan(res.approach)
    res = fourier.fourier_solve(load=0.1, speed=1.0, layer=lay, require_resolved=False,
                                nodes=(256, 512, 1024), shifts=2)
    assert res.success and any("layer's thickness" in w for w in res.warnings)
    fc = fourier.full_contact(1.0, layer=lay)
    full = fourier.fourier_solve(load=1.1 * fc["load_threshold"], speed=1.0, layer=lay, **FAST)
    assert full.success and full.full_contact


def test_an_approach_that_reaches_the_foundation_is_warned_of():
    lay = _layer_of(0.3, "frictionless", 0.3)
    res = fourier.fourier_solve(load=0.4, speed=1.0, layer=lay, nodes=(1024, 2048), shifts=2)
    assert res.approach >= 0.3 and any("reaches the foundation" in w for w in res.warnings)


# ------------------------------------------------------------------ bad input
BAD_LAYERS = [
    ({"thickness": 0.0}, "layer['thickness']"), ({"thickness": -1.0}, "layer['thickness']"),
    ({"thickness": math.nan}, "layer['thickness']"),
    ({"thickness": math.inf}, "layer['thickness']"),
    ({"thickness": "1"}, "layer['thickness']"), ({"thickness": True}, "layer['thickness']"),
    ({"thickness": 1e-120, "nu": 0.5}, "layer['thickness']"),   # S = (2/3) t³ underflows
    ({"foundation": "glued"}, "layer['foundation']"), ({"foundation": None}, "layer['foundation']"),
    ({"foundation": "Bonded"}, "layer['foundation']"),
    ({"nu": 0.6}, "layer['nu']"), ({"nu": -1.0}, "layer['nu']"), ({"nu": math.nan}, "layer['nu']"),
    ({"nu": 0.5000001}, "layer['nu']"), ({"nu": None}, "layer['nu']"),
    ({"extra": 1}, "layer"),
]


@pytest.mark.parametrize("change, name", BAD_LAYERS, ids=lambda v: repr(v))
def test_bad_layer_entries(change, name):
    lay = {**_layer_of(1.0, "bonded", 0.3), **change}
    for call in (lambda: fourier.fourier_solve(load=0.3, speed=1.0, layer=lay),
                 lambda: fourier.full_contact(1.0, layer=lay)):
        with pytest.raises(ValueError) as exc:
            call()
        msg = str(exc.value)
        assert msg.startswith(f"{name}=") and " is not allowed: " in msg, msg


@pytest.mark.parametrize("layer", [1.0, "bonded", (1.0, "bonded", 0.3), [1.0],
                                   bem.Layer(thickness=1.0, foundation="bonded", nu=0.3),
                                   {"thickness": 1.0, "foundation": "bonded"}, {}],
                         ids=lambda v: type(v).__name__ + str(len(v) if isinstance(v, dict)
                                                               else ""))
def test_a_layer_that_is_not_the_mapping_is_refused(layer):
    with pytest.raises(ValueError) as exc:
        fourier.fourier_solve(load=0.3, speed=1.0, layer=layer)
    msg = str(exc.value)
    assert msg.startswith("layer=") and "thickness" in msg and "foundation" in msg, msg


def test_bad_layer_factor_arguments():
    for t in (-1.0, math.nan, [0.5, -2.0], "1"):
        with pytest.raises(ValueError, match=r"^t="):
            analytic.layer_factor(t, 0.3, "bonded")
    with pytest.raises(ValueError, match=r"^nu=0\.6 is not allowed: a Poisson ratio"):
        analytic.layer_factor(1.0, 0.6, "bonded")
    with pytest.raises(ValueError, match=r"^foundation='free' is not allowed: 'bonded'"):
        analytic.layer_factor(1.0, 0.3, "free")
    with pytest.raises(ValueError, match=r"^lateral='fixed' is not allowed"):
        _layer.uniform_compliance(0.3, "frictionless", "fixed")
    assert isinstance(analytic.layer_factor(1.0, 0.3, "bonded"), float)
    assert analytic.layer_factor([[1.0, 2.0]], 0.3, "bonded").shape == (1, 2)


def test_the_layer_result_is_a_plain_record():
    res = fourier.fourier_solve(load=0.2, speed=1.0, layer=_layer_of(0.5, "bonded", 0.5),
                                nodes=(512, 1024), shifts=2)
    d = res.as_dict()
    assert d["layer"]["nu"] == 0.5 and d["approach"] == res.approach
    assert dataclasses.replace(res).approach == res.approach
    assert res.error_estimate["approach"] > 0.0 and res.error_estimate["mean_displacement"] == 0.0
