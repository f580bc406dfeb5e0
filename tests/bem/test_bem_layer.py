"""`bem.solve(layer=...)`: a layer on a rigid foundation in place of the half-space.

The operator's mode n is the half-space's times S(|n| k d, nu) (docs/layers.md §1), built as the
half-space's discrete symbol plus an alias sum (`bem._layer.symbol_correction`).  Checked here:
the alias sum against brute force, the thick layer against the half-space (bit for bit), full
contact against its closed form, the elastic limits, the thin incompressible layer's t^-3
stiffening, the adaptive estimate against a fine fixed mesh, and bad input.
"""
import math

import numpy as np
import pytest
import scipy.fft as sfft

import bem
from bem import _layer
from bem._grid import _Grid
from bem._influence import collocation_shifts, influence_coefficients_nd
from conftest import ROUNDOFF

SLS3 = bem.Prony.standard_linear_solid(3.0)
LAYERS = (bem.Layer(thickness=1.0, foundation="bonded", nu=0.5),
          bem.Layer(thickness=1.0, foundation="frictionless", nu=0.3))


def _alias(n, nodes, material, speed, shifts, reach, factor=None):
    """Brute-force alias sum over m = n + p N, |p| <= reach, of the continuum symbol (times
    ``factor(m)``)."""
    m = n + nodes * np.arange(-reach, reach + 1)
    m = m[m != 0]
    c = _layer.continuum_symbol(m, material.j_plus, material.terms, speed, nodes, shifts)
    return complex(np.sum(c if factor is None else c * factor(m)))


@pytest.mark.parametrize("material, speed, nodes", [
    (SLS3, 1.0, 16), (SLS3, 0.0, 16),
    (bem.Prony.standard_linear_solid(10.0), 0.3, 32)])  # the last with a collocation shift
def test_symbol_is_the_alias_sum(material, speed, nodes):
    """The half-space's symbol (made in real space) is the alias sum of the continuum symbol
    (2e-16 … 2e-15 of its largest mode measured, the alternating tail at 20000 aliases ~1e-15);
    the layer's (that plus `symbol_correction`) is the alias sum times S, to the same."""
    h = 1.0 / nodes
    lengths = [speed * t / (2.0 * math.pi) for _, t in material.terms]
    shifts = collocation_shifts(h, material.j_plus, material.terms, lengths)
    if material.ratio == 10.0:
        assert shifts[0] > 0.0  # the phase of the shifted memory part is checked too
    sym = sfft.rfft(influence_coefficients_nd(material.j_plus, material.terms, speed, nodes))
    scale = np.max(np.abs(sym[1:]))
    modes = range(1, nodes // 2 + 1)
    half = np.array([_alias(n, nodes, material, speed, shifts, 20000) for n in modes])
    assert np.max(np.abs(sym[1:] - half)) <= 1e-14 * scale
    for layer in (*LAYERS, bem.Layer(thickness=0.05, foundation="bonded", nu=0.3)):
        grid = _Grid(bem.Sinusoid(1.0), material, speed, nodes, layer)
        brute = np.array([_alias(n, nodes, material, speed, shifts, 20000, layer.factor)
                          for n in modes])
        assert np.max(np.abs(grid.op.symbol[1:] - brute)) <= 1e-14 * scale
        # and the layer changed it: S(kd) < 1 on mode 1
        assert abs(grid.op.symbol[1] - sym[1]) > 1e-3 * scale


@pytest.mark.parametrize("kd, foundation", [(25.0, "bonded"), (40.0, "frictionless")])
def test_thick_layer_is_the_half_space_bitwise(kd, foundation):
    """From k d = 25 on S = 1 exactly for every mode: the operator is the half-space's and so
    is every number of the answer, bit for bit (a fixed mesh and an adaptive one)."""
    layer = bem.Layer(thickness=kd, foundation=foundation, nu=0.5)
    assert _layer.symbol_correction(layer, 1.0, (), 0.0, 64, ()) is None
    for opts in ({"nodes": 4096}, {"rtol": 1e-5}):
        ref = bem.solve(load=0.3, speed=1.0, **opts)
        got = bem.solve(load=0.3, speed=1.0, layer=layer, **opts)
        assert got.success and ref.success
        assert got.scalars() == ref.scalars()
        assert got.nodes == ref.nodes
        assert np.array_equal(got.pressure, ref.pressure)
        assert np.array_equal(got.displacement, ref.displacement)
        assert np.array_equal(got.gap, ref.gap)
        assert got.error_estimate == ref.error_estimate
        assert "layer" not in ref.diagnostics and got.diagnostics["layer"]["thickness"] == kd


@pytest.mark.parametrize("layer", LAYERS)
def test_full_contact_closed_form(layer):
    """Full contact of the sinusoid: sigma = p + 2 Re(sigma_1 e^{2 pi i X}) with
    sigma_1 = (hk/2)/(2 S(kd) J*(1)) (mode 1 of the layer's operator).  The panel values are the
    point values over sinc(pi n/N) mode by mode; the aliases of mode 1 add ~1.6/N^2 (2.4e-11 at
    2^18).  The other modes vanish to the rounding of the samples amplified by the inverse
    symbol (~ n: 2e-12 measured).  hk = 0.1: the crest's approach, h, stays within d = 10 h
    (at hk = k d = 1 it would reach the foundation, and the answer is refused)."""
    s = layer.factor([1.0])[0]
    assert s < 0.9  # the layer matters
    hk = 0.1
    exact = 0.25 * hk / (s * complex(SLS3.jstar([1.0], 1.0)[0]))
    nodes, load = 2 ** 18, 4.0 * abs(exact)  # twice the full-contact load
    r = bem.solve(load=load, speed=1.0, material=SLS3, hk=hk, nodes=nodes, layer=layer)
    assert r.success and r.full_contact
    sh = sfft.rfft(r.pressure) / nodes
    point = -sh[1] * np.sinc(1.0 / nodes)  # -: panel 0 sits at X = -1/2
    assert abs(point - exact) <= 1e-10 * abs(exact)
    assert abs(sh[0].real - load) <= ROUNDOFF * load
    assert np.max(np.abs(sh[2:])) <= 1e-10 * abs(exact)  # sample rounding times |1/symbol| ~ n
    # the full-contact threshold: the pressure's minimum at zero, p_FC = 2|sigma_1|
    t = bem.solve(penetration=1.0, speed=1.0, material=SLS3, hk=hk, nodes=2 ** 14, layer=layer)
    assert t.success and t.full_contact
    assert t.load == pytest.approx(2.0 * abs(exact), rel=1e-7)  # (pi/N)^2/2 panel sampling


@pytest.mark.parametrize("layer", LAYERS)
def test_elastic_limits(layer):
    """V -> 0 is the elastic layer with the relaxed modulus E0, V -> inf with the glassy one
    E_inf = 3 E0: at rest the standard linear solid's answer is the elastic J = 1's; at w = 1e10
    it is the elastic J = 1's at a third of the load with three times its pressure (J* - J(0+)
    ~ J_1/(w tau) = 7e-11)."""
    opts = dict(nodes=4096, layer=layer)
    half = bem.solve(load=0.3, speed=0.0, material=SLS3, nodes=4096)
    rest = bem.solve(load=0.3, speed=0.0, material=SLS3, **opts)
    elastic = bem.solve(load=0.3, speed=0.0, material=bem.Prony(1.0), **opts)
    assert abs(rest.penetration - half.penetration) > 1e-2  # the layer matters
    assert rest.penetration == pytest.approx(elastic.penetration, rel=1e-12)
    assert rest.ka == pytest.approx(elastic.ka, abs=1e-12)
    assert np.allclose(rest.pressure, elastic.pressure, rtol=0, atol=1e-10)  # Krylov tol
    assert rest.mu == 0.0
    fast = bem.solve(load=0.3, speed=1e10, material=SLS3, **opts)
    glassy = bem.solve(load=0.1, speed=0.0, material=bem.Prony(1.0), **opts)
    assert fast.success and glassy.success
    assert fast.penetration == pytest.approx(glassy.penetration, rel=1e-8)
    assert fast.ka == pytest.approx(glassy.ka, abs=1e-8)
    assert np.allclose(fast.pressure, 3.0 * glassy.pressure, rtol=0, atol=1e-8)  # 4e-9 seen
    assert abs(fast.ke) < 1e-8


def test_thin_incompressible_layer_stiffens_like_t_cubed():
    """A thin bonded incompressible layer in full contact: p_FC = hk/(2 S(kd) |J*(1)|) with
    S = (2/3) t^3 (1 - (9/5) t^2 + O(t^4)): the measured exponent of p_FC in kd tends to -3 as
    kd falls, and p_FC (2/3)(kd)^3 (1 - (9/5)(kd)^2) tends to hk/(2 |J*(1)|).  On N panels the
    aliases of mode 1 (S ~ 1) add ~1/(S(kd) N^3) to its tiny symbol S(kd), and its round-off
    grows like N/S(kd) (`finest_nodes`): N = 2^16 keeps both below 1e-8 down to kd = 0.05.
    hk = 0.01 keeps the crest's approach, h, within the thinnest layer (d = 5 h)."""
    kds, hk = (0.05, 0.1, 0.2), 0.01
    loads = []
    for kd in kds:
        layer = bem.Layer(thickness=kd, foundation="bonded", nu=0.5)
        r = bem.solve(penetration=1.0, speed=1.0, material=SLS3, hk=hk, nodes=2 ** 16,
                      layer=layer)
        assert r.success and r.full_contact
        exact = hk / (2.0 * layer.factor([1.0])[0] * abs(complex(SLS3.jstar([1.0], 1.0)[0])))
        assert r.load == pytest.approx(exact, rel=1e-7)
        loads.append(r.load)
    slopes = np.diff(np.log(loads)) / np.diff(np.log(kds))
    assert abs(slopes[0] + 3.0) < 0.03 and abs(slopes[0] + 3.0) < abs(slopes[1] + 3.0), slopes
    asym = hk / (2.0 * abs(complex(SLS3.jstar([1.0], 1.0)[0])))
    two_terms = loads[0] * (2.0 / 3.0) * kds[0] ** 3 * (1.0 - 1.8 * kds[0] ** 2)
    assert two_terms == pytest.approx(asym, rel=1e-4)  # the t^4 term: ~1e-5 at kd = 0.05


def test_a_layer_too_thin_for_the_mesh_is_refused():
    """The lowest mode of a very thin layer is round-off on a fine grid: refused, naming the
    mesh (a fixed one) or the layer (too thin for any grid), never answered."""
    thin = bem.Layer(thickness=1e-3, foundation="bonded", nu=0.5)  # S = 6.7e-10
    with pytest.raises(ValueError, match=r"^layer="):
        bem.solve(load=0.3, speed=1.0, layer=thin)
    layer = bem.Layer(thickness=0.05, foundation="bonded", nu=0.5)
    with pytest.raises(ValueError, match=r"^nodes=1048576 is not allowed: at most 82960"):
        bem.solve(penetration=1.0, speed=1.0, nodes=2 ** 20, layer=layer)
    with pytest.raises(ValueError, match=r"^layer="):
        bem.solve_si(nu=0.5, wavelength=0.01, amplitude=1e-4, speed=1.0, E0=1e6, Einf=3e6,
                     tau_creep=1.0, mean_pressure=1e4, layer=layer)


@pytest.mark.parametrize("layer", LAYERS)
def test_adaptive_estimate_is_honest(layer):
    """The adaptive mesh on a layer (SLS E_inf/E0 = 3, p~ = 0.3, V/V0 = 1, kd = 1) meets
    rtol = 1e-4, and its estimate bounds the error against a mesh 64 times finer than the
    one it stopped on (the reference's own error far below): true error <= 3 x estimate."""
    r = bem.solve(load=0.3, speed=1.0, material=SLS3, rtol=1e-4, layer=layer)
    assert r.success, r.message
    est = r.error_estimate
    assert est is not None and "window" not in r.diagnostics
    ref = bem.solve(load=0.3, speed=1.0, material=SLS3, nodes=64 * r.nodes, layer=layer)
    assert ref.success
    # the friction's two forms (dissipation, weighted by S per mode, and direct) agree
    assert r.residuals["friction_mismatch"] < 1e-5 and ref.residuals["friction_mismatch"] < 1e-6
    for key in ("ka", "ke", "ke_hat"):
        assert abs(getattr(r, key) - getattr(ref, key)) <= 3.0 * est[key], key
    for key in ("penetration", "mu", "tau_f"):
        true = abs(getattr(r, key) / getattr(ref, key) - 1.0)
        assert true <= 3.0 * est[key], key
    # the uniform mode: Delta/h as on the half-space, the approach adds the compression
    d = r.diagnostics["layer"]
    mean = layer.uniform * layer.thickness * SLS3.J0 * r.load / 1.0
    assert d["mean_displacement"] == pytest.approx(mean, rel=ROUNDOFF)
    assert d["approach"] == pytest.approx(r.penetration + mean, rel=ROUNDOFF)


def test_unresolved_layer_is_not_estimated():
    """A layer thinner than MIN_LAYER_PANELS panels of N/4 leaves the estimate untrusted: a
    fixed mesh that does not resolve d has no estimate, where the half-space has one."""
    layer = bem.Layer(thickness=0.02, foundation="bonded", nu=0.3)  # d = 0.0032 lambda
    ref = bem.solve(load=0.3, speed=1.0, nodes=4096)
    r = bem.solve(load=0.3, speed=1.0, nodes=4096, layer=layer)  # 3.3 panels across d at N/4
    assert ref.error_estimate is not None
    assert r.error_estimate is None
    assert "layer's thickness" in r.diagnostics["estimate_note"]


def test_a_layer_can_be_replaced_field_by_field():
    import dataclasses
    a = bem.Layer(thickness_over_wavelength=0.5, foundation="bonded", nu=0.4)
    b = dataclasses.replace(a, nu=0.3)
    assert (b.thickness, b.thickness_over_wavelength, b.nu) == (a.thickness, 0.5, 0.3)
    with pytest.raises(ValueError, match=r"^thickness="):
        dataclasses.replace(a, thickness=1.0)  # with the old d/lambda: two thicknesses


def test_thickness_over_wavelength():
    a = bem.Layer(thickness_over_wavelength=0.5, foundation="bonded", nu=0.4)
    assert a.thickness == math.pi and a.thickness_over_wavelength == 0.5
    b = bem.Layer(thickness=math.pi, foundation="bonded", nu=0.4)
    assert b.thickness_over_wavelength == pytest.approx(0.5, rel=ROUNDOFF)


@pytest.mark.parametrize("kwargs, name", [
    ({"thickness": 0.0}, "thickness"), ({"thickness": -1.0}, "thickness"),
    ({"thickness": math.nan}, "thickness"), ({"thickness": math.inf}, "thickness"),
    ({"thickness": "1"}, "thickness"), ({"thickness": 1e-5}, "thickness"),
    ({}, "thickness"), ({"thickness": 1.0, "thickness_over_wavelength": 0.1}, "thickness"),
    ({"thickness_over_wavelength": -0.1}, "thickness_over_wavelength"),
    ({"thickness": 1.0, "foundation": "glued"}, "foundation"),
    ({"thickness": 1.0, "foundation": None}, "foundation"),
    ({"thickness": 1.0, "nu": 0.6}, "nu"), ({"thickness": 1.0, "nu": -1.0}, "nu"),
    ({"thickness": 1.0, "nu": math.nan}, "nu"), ({"thickness": 1.0, "nu": None}, "nu")])
def test_bad_layer(kwargs, name):
    args = {"foundation": "bonded", "nu": 0.5, **kwargs}
    with pytest.raises(ValueError, match=rf"^{name}="):
        bem.Layer(**args)


def test_bad_layer_argument():
    with pytest.raises(ValueError, match=r"^layer="):
        bem.solve(load=0.3, speed=1.0, nodes=1024, layer={"thickness": 1.0})


def test_a_penetration_through_the_layer_is_refused():
    """Under penetration control the approach is at least Δ: Δ ≥ d ((Δ/h) hk ≥ k d) is refused
    before any work, naming the penetration and the largest one allowed.  (An incompressible
    bonded layer does not compress on the whole: its approach is Δ itself.)"""
    layer = bem.Layer(thickness=0.5, foundation="bonded", nu=0.5)
    with pytest.raises(ValueError, match=r"penetration=0\.6 is not allowed: .*Δ/h < k d/hk = 0\.5"):
        bem.validate(penetration=0.6, speed=1.0, hk=1.0, layer=layer)
    with pytest.raises(ValueError, match=r"penetration=0\.5 is not allowed"):
        bem.solve(penetration=0.5, speed=1.0, layer=layer)
    assert bem.solve(penetration=0.49, speed=1.0, layer=layer, nodes=1024).success


def test_a_load_that_pushes_through_the_layer_is_no_answer():
    """Under load control the approach is known after the solve: a load whose crest reaches
    the foundation (approach h ≥ d) is not a success, and says why; just below, it is."""
    layer = bem.Layer(thickness=0.3, foundation="frictionless", nu=0.3)
    deep = bem.solve(load=2.0, speed=1.0, layer=layer, nodes=1024)
    assert deep.diagnostics["layer"]["approach"] >= 0.3
    assert not deep.success and deep.status == 4
    assert "reaches the foundation" in deep.message
    shallow = bem.solve(load=0.05, speed=1.0, layer=layer, nodes=1024)
    assert shallow.success and shallow.diagnostics["layer"]["approach"] < 0.3


def test_the_record_carries_the_layer():
    """as_dict: the layer at the top of the record (thickness, foundation, ν, the approach),
    the same numbers as diagnostics["layer"]; no such key on the half-space."""
    layer = bem.Layer(thickness_over_wavelength=0.25, foundation="bonded", nu=0.4)
    r = bem.solve(load=0.2, speed=1.0, layer=layer, nodes=1024)
    rec = r.as_dict()
    assert rec["layer"] == r.diagnostics["layer"]
    assert rec["layer"]["thickness_over_wavelength"] == 0.25
    assert rec["layer"]["approach"] == pytest.approx(rec["penetration"]
                                                     + rec["layer"]["mean_displacement"])
    assert "layer" not in rec["diagnostics"]
    assert "layer" not in bem.solve(load=0.2, speed=1.0, nodes=1024).as_dict()


def test_friction_at_the_full_contact_threshold_does_not_see_the_layer():
    """At Δ/h = 1 (the threshold of full contact) τf and p̃FC both carry 1/S(kd) of mode 1, so
    μ = (hk/2) sin δ(kV), δ the loss angle, on every layer and the half-space alike, to the
    panel sampling error, ~(π/N)²/6 ≈ 2.4e-8 at N = 4096 for all; the aliases of mode 1 add
    ~1/(S(kd) N³) on a layer (6e-10 measured between them at d/λ = 0.05, S = 0.012)."""
    e1 = 1.0 / complex(SLS3.jstar([1.0], 1.0)[0])
    hk = 0.01
    universal = -(hk / 2.0) * e1.imag / abs(e1)
    layers = (None, bem.Layer(thickness_over_wavelength=0.05, foundation="bonded", nu=0.5),
              bem.Layer(thickness_over_wavelength=0.2, foundation="frictionless", nu=0.3))
    mus = []
    for layer in layers:
        r = bem.solve(penetration=1.0, speed=1.0, hk=hk, nodes=4096, layer=layer)
        assert r.success and r.full_contact
        mus.append(r.mu)
        assert r.mu == pytest.approx(universal, rel=1e-7)
    assert max(mus) - min(mus) <= 2e-9 * universal
