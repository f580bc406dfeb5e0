"""The surface reference (`analytic.references.surface`): an independent solver for a rigid
periodic surface sliding over a viscoelastic half-space, checked against closed forms, the line
contact's semi-analytic road, its own symmetries and limits, and its own convergence.

Tolerance tiers: ROUNDOFF for closed forms and exact identities of the discrete problem (the
iteration stops at 1e-10 of the peak pressure, so identities between two solves hold to
ITERATION); the discretisation error is the solver's own estimate, which the comparisons with
the line contact must meet.
"""
import json
import math

import numpy as np
import pytest

import analytic
from analytic.references import surface as sr
from analytic.references.surface import _measure
from conftest import ROUNDOFF

#: two solves of one discrete problem (or of two mirror images) agree to the iteration's stop
ITERATION = 1e-8

BISINUSOID = {(1, 0): 1.0, (0, 1): 1.0}     # k z = hk [cos kx + cos ky], hk = 1
RIDGES = {(1, 0): 1.0}                      # k z = cos kx, uniform in y: the line's sinusoid
#: a cell 1/16 as wide as long holds a surface uniform in y with nx/16 points across
THIN = 1.0 / 16.0


def _jstar(n, w, j0, jj, tt):
    """J*(n) = J(0+) + Σ J_i/(1 − i n w τ_i), written here again from the conventions."""
    out = complex(j0 - sum(jj))
    for a, t in zip(jj, tt):
        out += a / (1.0 - 1j * n * w * t)
    return out


def _within(value, reference, estimate, relative):
    """|value − reference| within the estimate (relative to |reference| when ``relative``)."""
    err = abs(value - reference) / (abs(reference) if relative else 1.0)
    return err <= estimate, f"error {err:.3e} against estimate {estimate:.3e}"


# --------------------------------------------------------------------------------------------
# Full contact: σ̂_q = ẑ_q/Ĉ(q) in closed form
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("harmonics, aspect, direction, material, speed", [
    ({(1, 0): 0.3, (0, 1): 0.2j, (1, 1): 0.1, (2, -1): 0.05 + 0.02j}, 1.3, 37.0,
     (1.0, (0.4, 0.3), (0.5, 3.0)), 2.0),
    ({(1, 0): 0.4, (1, 2): -0.1 + 0.1j, (0, 3): 0.05}, 0.7, -120.0, (2.0, (1.5,), (0.2,)), 0.7),
    (BISINUSOID, 1.0, 0.0, (1.0, (2.0 / 3.0,), (1.0,)), 1.0),
])
def test_full_contact_is_the_closed_form(harmonics, aspect, direction, material, speed):
    load = 4.0
    res = sr.solve(load=load, speed=speed, heights=harmonics, aspect=aspect,
                   direction=direction, material=material, nodes=(16, 32))
    assert res.success and res.full_contact
    assert res.contact_fraction == 1.0 and res.n_patches == 1
    assert res.penetration == pytest.approx(1.0, abs=ROUNDOFF)
    sigma = _assert_full_contact_sum(res, harmonics, aspect, direction, material, speed, load)
    assert res.max_pressure == pytest.approx(np.max(sigma), rel=1e-3)


def _assert_full_contact_sum(res, harmonics, aspect, direction, material, speed, load,
                             factor=lambda q: 1.0):
    """σ, μ, the lateral μ and the direct μ of a full contact against the closed-form sum over
    the modes, Ĉ(q) times ``factor(q)`` (a layer's S(|q| k d)); returns the closed-form σ."""
    th = math.radians(direction)
    e, ep = (math.cos(th), math.sin(th)), (-math.sin(th), math.cos(th))
    xx, yy = np.meshgrid(res.x, res.y, indexing="ij")
    sigma = np.full(xx.shape, load)
    tau = lateral = 0.0
    for (m, n), c in harmonics.items():
        q = (m, n / aspect)
        c_hat = 2.0 * factor(q) / math.hypot(*q) * _jstar(q[0] * e[0] + q[1] * e[1], speed,
                                                           *material)
        sigma += (c / c_hat * np.exp(2j * math.pi * (m * xx + n * yy / aspect))).real
        # k z = Re[c e^{iq·X}]: σ_±q = (c/2)/Ĉ(±q), each dissipating (q·ê) Im Ĉ |σ_q|²
        power = abs(c) ** 2 / (2.0 * abs(c_hat) ** 2)
        tau += (q[0] * e[0] + q[1] * e[1]) * c_hat.imag * power
        lateral -= (q[0] * ep[0] + q[1] * ep[1]) * c_hat.imag * power
    assert np.max(np.abs(res.pressure - sigma)) <= ROUNDOFF * np.max(sigma)
    assert res.mu == pytest.approx(tau / load, rel=ROUNDOFF, abs=ROUNDOFF)
    assert res.mu_lateral == pytest.approx(lateral / load, rel=ROUNDOFF, abs=ROUNDOFF)
    # the friction from the surface's slope is the same sum in full contact (u = z̃)
    assert res.diagnostics["mu_direct"] == pytest.approx(res.mu, rel=ROUNDOFF, abs=ROUNDOFF)
    return sigma


def test_full_contact_of_ridges_is_appendix_b():
    """A surface uniform in y sliding along x: the line contact's mode symbol, exactly."""
    line = analytic.solve(load=2.0, speed=1.0)
    assert line.full_contact
    res = sr.solve(load=2.0, speed=1.0, heights=RIDGES, aspect=0.25, nodes=(16, 32))
    assert res.full_contact
    assert res.mu == pytest.approx(line.mu, rel=ROUNDOFF)
    assert abs(res.mu_lateral) <= ROUNDOFF


# --------------------------------------------------------------------------------------------
# The line contact: ridges along x, across, and at an angle
# --------------------------------------------------------------------------------------------
def test_ridges_sliding_across_are_the_line_contact():
    line = analytic.solve(load=0.3, speed=1.0)
    res = sr.solve(load=0.3, speed=1.0, heights=RIDGES, aspect=THIN, nodes=(256, 512, 1024))
    assert res.success, res.message
    assert res.n_patches == 1
    est = res.error_estimate
    for key, ref, rel in (("mu", line.mu, True), ("penetration", line.penetration, True),
                          ("contact_fraction", line.contact_fraction, True)):
        ok, why = _within(getattr(res, key), ref, est[key], rel)
        assert ok, f"{key}: {why}"
    assert abs(res.mu_lateral) <= ROUNDOFF


def test_ridges_sliding_along_themselves_are_westergaard():
    """θ = 90°: every mode is static (q·ê = 0), the relaxed elastic contact, no friction."""
    line = analytic.solve(load=0.3, speed=0.0)
    res = sr.solve(load=0.3, speed=1.0, heights=RIDGES, aspect=THIN, direction=90.0,
                   nodes=(128, 256, 512))
    assert res.success, res.message
    assert abs(res.mu) <= ROUNDOFF and abs(res.mu_lateral) <= ROUNDOFF
    est = res.error_estimate
    for key, ref, rel in (("penetration", line.penetration, True),
                          ("contact_fraction", line.contact_fraction, True)):
        ok, why = _within(getattr(res, key), ref, est[key], rel)
        assert ok, f"{key}: {why}"


def test_oblique_ridges_are_the_line_contact_at_w_cos_theta():
    """μ = cos θ μ_line(w cos θ), μ_lateral = sin θ μ_line(w cos θ): the solid pushes across
    the ridges only, along −x, which is to the left of V (ê⊥) for 0 < θ < 90°."""
    w, theta = 2.0, 40.0
    c, s = math.cos(math.radians(theta)), math.sin(math.radians(theta))
    line = analytic.solve(load=0.3, speed=w * c)
    res = sr.solve(load=0.3, speed=w, heights=RIDGES, aspect=THIN, direction=theta,
                   nodes=(128, 256, 512))
    assert res.success, res.message
    assert res.mu_lateral > 0.0
    est = res.error_estimate
    ok, why = _within(res.mu, c * line.mu, est["mu"], True)
    assert ok, f"mu: {why}"
    ok, why = _within(res.mu_lateral, s * line.mu, est["mu_lateral"], False)
    assert ok, f"mu_lateral: {why}"
    ok, why = _within(res.penetration, line.penetration, est["penetration"], True)
    assert ok, f"penetration: {why}"
    # the same discrete problem as the ridges crossed at w cos θ: an identity of the grids
    along = sr.solve(load=0.3, speed=w * c, heights=RIDGES, aspect=THIN, nodes=(128, 256, 512))
    assert res.mu == pytest.approx(c * along.mu, rel=ITERATION)
    assert res.mu_lateral == pytest.approx(s * along.mu, rel=ITERATION)
    assert res.penetration == pytest.approx(along.penetration, rel=ITERATION)


# --------------------------------------------------------------------------------------------
# Limits and symmetries
# --------------------------------------------------------------------------------------------
def test_slow_sliding_is_the_relaxed_elastic_contact():
    slow = sr.solve(load=0.3, speed=1e-12, heights=BISINUSOID, nodes=(32, 64))
    rest = sr.solve(load=0.3, speed=0.0, heights=BISINUSOID, nodes=(32, 64))
    assert abs(slow.mu) <= 1e-10 and rest.mu == 0.0
    for key in ("penetration", "contact_fraction", "max_pressure"):
        assert getattr(slow, key) == pytest.approx(getattr(rest, key), rel=ITERATION)


def test_fast_sliding_is_the_glassy_elastic_contact_when_no_mode_is_static():
    """At 30° no mode q ≠ 0 of the bi-sinusoid's grid is across V: V → ∞ is J(0+) = 1/3
    everywhere.  Along x the modes (0, n) stay static at any speed and keep J0."""
    glassy = sr.solve(load=0.3, speed=0.0, heights=BISINUSOID, material=(1.0 / 3.0, (), ()),
                      nodes=(32, 64))
    fast = sr.solve(load=0.3, speed=1e12, heights=BISINUSOID, direction=30.0, nodes=(32, 64))
    assert abs(fast.mu) <= 1e-8
    for key in ("penetration", "contact_fraction", "max_pressure"):
        assert getattr(fast, key) == pytest.approx(getattr(glassy, key), rel=ITERATION)
    along_x = sr.solve(load=0.3, speed=1e12, heights=BISINUSOID, nodes=(32, 64))
    assert abs(along_x.penetration - glassy.penetration) > 1e-2


def test_mirror_images_have_the_same_friction_and_opposite_lateral_force():
    """z = h_x cos kx + h_y cos(2πy/Ly) is even in y: sliding at −θ is the mirror of +θ."""
    surface = {(1, 0): 0.8, (0, 1): 0.5}
    kw = dict(load=0.3, speed=1.0, heights=surface, aspect=1.5, nodes=(32, 64))
    up = sr.solve(direction=35.0, **kw)
    down = sr.solve(direction=-35.0, **kw)
    assert up.success and down.success
    assert abs(up.mu_lateral) > 1e-3      # anisotropy turns the force away from −V
    assert down.mu == pytest.approx(up.mu, rel=ITERATION)
    assert down.mu_lateral == pytest.approx(-up.mu_lateral, rel=ITERATION)
    assert down.contact_fraction == pytest.approx(up.contact_fraction, rel=ITERATION)


# --------------------------------------------------------------------------------------------
# The solver's own consistency
# --------------------------------------------------------------------------------------------
def test_the_solution_satisfies_the_contact_conditions():
    res = sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(32, 64))
    assert res.success and res.h_ref == pytest.approx(2.0, rel=ROUNDOFF)
    p, gap, u = res.pressure, res.gap, res.displacement
    assert p.min() >= 0.0
    assert gap.min() >= -ITERATION and np.max(np.abs(gap[p > 0.0])) <= ITERATION
    assert p.mean() == pytest.approx(0.3, rel=ROUNDOFF)
    assert abs(u.mean()) <= ROUNDOFF
    # the mean gap is the separation s/h_ref = 1 − Δ/h_ref (of this grid)
    assert gap.mean() == pytest.approx(1.0 - res.levels[-1]["shifted"][0]["penetration"],
                                       abs=ROUNDOFF)
    assert res.diagnostics["complementarity"] <= ITERATION
    # the friction from the surface's slope converges more slowly than the dissipation's sum
    # (measured: 3.2e-4 apart at 64², 8e-7 at 512²)
    assert res.diagnostics["mu_direct"] == pytest.approx(res.mu, rel=1e-3)


def test_patches_are_counted_across_the_cell_s_edges():
    """Four crests per cell, three of them cut by its edges: four patches, not nine."""
    res = sr.solve(load=0.05, speed=1.0, heights={(2, 0): 1.0, (0, 2): 1.0}, nodes=(32, 64))
    assert res.success and res.n_patches == 4
    json.dumps(res.as_dict(), allow_nan=False)


def test_penetration_control_inverts_load_control():
    by_load = sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(32, 64, 128))
    by_pen = sr.solve(penetration=by_load.penetration, speed=1.0, heights=BISINUSOID,
                      nodes=(32, 64, 128))
    assert by_pen.success
    assert by_pen.load == pytest.approx(0.3, rel=by_load.error_estimate["penetration"]
                                        + by_pen.error_estimate["load"])
    # Δ/h_ref = 1 is the threshold of full contact: p̃_FC = hk |E*|, here at rest (E = E0)
    threshold = sr.solve(penetration=1.0, speed=0.0, heights=BISINUSOID, nodes=(16, 32))
    assert threshold.full_contact
    assert threshold.load == pytest.approx(1.0, rel=ROUNDOFF)


def test_callable_array_and_harmonics_are_one_surface():
    """The panel centres of the conventions: x_i = i/nx − ½, y_j = (j/ny − ½)·aspect."""
    aspect = 1.5
    kw = dict(load=0.3, speed=1.0, aspect=aspect, direction=20.0)
    harmonics = sr.solve(heights={(1, 0): 0.8, (0, 1): 0.5}, nodes=(32, 64), **kw)
    func = sr.solve(heights=lambda x, y: 0.8 * np.cos(2 * np.pi * x)
                    + 0.5 * np.cos(2 * np.pi * y / aspect), nodes=(32, 64), **kw)
    x = np.arange(32) / 32 - 0.5
    y = (np.arange(48) / 48 - 0.5) * aspect
    samples = 0.8 * np.cos(2 * np.pi * x)[:, None] + 0.5 * np.cos(2 * np.pi * y / aspect)
    array = sr.solve(heights=samples, nodes=(32, 64), **kw)
    for other in (func, array):
        assert other.grids == harmonics.grids == ((32, 48), (64, 96))
        for key in ("mu", "mu_lateral", "penetration", "contact_fraction", "max_pressure"):
            assert getattr(other, key) == pytest.approx(getattr(harmonics, key), rel=ITERATION)


# --------------------------------------------------------------------------------------------
# Convergence
# --------------------------------------------------------------------------------------------
def test_friction_converges_at_the_measured_order():
    """The bi-sinusoid hk = 1, p̃ = 0.3, V/V0 = 1, E∞/E0 = 3.  Measured (the errors of the
    grids 64, 128, 256 against the one at 512): 6.9e-5, −6.0e-6, −4.9e-7 in μ = 0.27196, the
    orders 3.5 and 3.6; to 1024 the finest's own error is 4.6e-8."""
    res = sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(64, 128, 256, 512))
    assert res.success
    mus = [lv["scalars"]["mu"] for lv in res.levels]
    errors = [abs(m - mus[-1]) for m in mus[:-1]]
    orders = [math.log2(a / b) for a, b in zip(errors[:-1], errors[1:])]
    assert min(orders) >= 3.0, orders
    assert res.error_estimate["mu"] <= 1e-5


def test_richardson_on_known_sequences():
    ns = (64, 128, 256, 512)
    value, est, order, extrapolated = sr.richardson(ns[:3], [1.0 + 3.0 * n ** -2.0
                                                             for n in ns[:3]])
    assert not extrapolated and order == pytest.approx(2.0, rel=1e-9)
    assert value == 1.0 + 3.0 * 256 ** -2.0 and est == pytest.approx(3.0 * 256 ** -2.0)
    value, est, order, extrapolated = sr.richardson(ns, [1.0 + 3.0 * n ** -2.0 for n in ns])
    # extrapolated, with the finest grid's error as the estimate
    assert extrapolated and value == pytest.approx(1.0, abs=1e-14)
    assert est == pytest.approx(3.0 * 512 ** -2.0)
    # errors that change sign: the finest value, with the differences as the estimate
    value, est, order, extrapolated = sr.richardson(ns[:3], [1.0 + 1e-3, 1.0 - 1e-4, 1.0])
    assert not extrapolated and value == 1.0 and est == pytest.approx(1.1e-3 * 128 / 256)


def test_the_contact_area_of_a_disc_from_its_gap():
    """The refined area of a disc of radius R whose gap opens like d^{3/2} outside: the
    nodal count is off by the cells the circle cuts, the fit is not."""
    for n in (64, 128):
        x = (np.arange(n) + 0.5) / n - 0.5
        r = np.hypot(*np.meshgrid(x, x, indexing="ij"))
        radius = 0.3137
        gap = np.maximum(r - radius, 0.0) ** 1.5 * (1.0 + 0.7 * (r - radius))
        area, band, fitted = _measure._contact_area(r < radius, gap, 1.0)
        assert fitted == band
        assert abs(area - math.pi * radius ** 2) <= 2.0 / n ** 2


# --------------------------------------------------------------------------------------------
# Bad inputs
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("kwargs, name", [
    (dict(load=-0.3), "load"),
    (dict(load=float("nan")), "load"),
    (dict(load=0.3, penetration=0.5), "load"),
    (dict(load=None), "load"),
    (dict(penetration=1.5), "penetration"),
    (dict(penetration=0.0), "penetration"),
    (dict(speed=-1.0), "speed"),
    (dict(speed="fast"), "speed"),
    (dict(direction=720.0), "direction"),
    (dict(aspect=0.0), "aspect"),
    (dict(ratio=0.5), "ratio"),
    (dict(ratio=3.0, material=(1.0, (0.5,), (1.0,))), "ratio"),
    (dict(material=(1.0, (1.5,), (1.0,))), "material"),
    (dict(material=(1.0, (0.5,), (1.0, 2.0))), "material"),
    (dict(material=(1.0, (0.5,), (-1.0,))), "material"),
    (dict(heights="bisinusoid"), "heights"),
    (dict(heights=np.ones(8)), "heights"),
    (dict(heights=np.ones((8, 8))), "heights"),
    (dict(heights=np.full((8, 8), np.nan)), "heights"),
    (dict(heights={(1, 0): "one"}), "heights"),
    (dict(heights={(1.5, 0): 1.0}), "heights"),
    (dict(heights=lambda x, y: np.ones(3)), "heights"),
    (dict(nodes=63), "nodes"),
    (dict(nodes=4), "nodes"),
    (dict(nodes=(64, 32)), "nodes"),
    (dict(nodes=(32, 64.0)), "nodes"),
    (dict(nodes=4096), "nodes"),
    (dict(heights={(5, 0): 1.0}, nodes=(8, 16)), "nodes"),
    (dict(heights=np.random.default_rng(1).random((12, 12)), nodes=(16, 32)), "nodes"),
    (dict(tol=0.0), "tol"),
])
def test_bad_inputs_are_refused_by_name(kwargs, name):
    args = dict(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(16, 32))
    if "penetration" in kwargs and "load" not in kwargs:
        args.pop("load")
    args.update(kwargs)
    with pytest.raises(ValueError, match=rf"^{name}=.* is not allowed: "):
        sr.solve(**args)


# --------------------------------------------------------------------------------------------
# A layer on a rigid foundation: mode q's symbol times S(|q| k d, ν)
# --------------------------------------------------------------------------------------------
BONDED = {"thickness_over_wavelength": 0.5, "foundation": "bonded", "nu": 0.5}


def test_no_layer_is_the_half_space_and_its_record_is_unchanged():
    args = dict(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(16, 32, 64))
    plain_ = sr.solve(**args)
    none = sr.solve(**args, layer=None)
    assert none.layer is None and none.mean_displacement is None and none.approach is None
    assert "layer" not in none.diagnostics and "mean_displacement" not in none.error_estimate
    a, b = plain_.as_dict(), none.as_dict()
    a.pop("elapsed"), b.pop("elapsed")
    for lv in a["levels"] + b["levels"]:
        lv.pop("seconds")
    assert a == b and not {"layer", "mean_displacement", "approach"} & set(a)
    assert np.array_equal(plain_.pressure, none.pressure)


@pytest.mark.parametrize("layer", [
    {"thickness": 25.0, "foundation": "bonded", "nu": 0.3},
    {"thickness_over_wavelength": 10.0, "foundation": "frictionless", "nu": 0.5},
])
def test_a_thick_layer_is_the_half_space(layer):
    """From k d = 25 on every mode's S is 1 exactly (|q| ≥ 1): the half-space bit for bit."""
    args = dict(load=0.3, speed=1.0, heights=BISINUSOID, direction=20.0, nodes=(16, 32, 64))
    half = sr.solve(**args)
    thick = sr.solve(**args, layer=layer)
    assert thick.success
    for key in sr.SCALAR_KEYS + ("load", "tau_f", "separation"):
        assert getattr(thick, key) == getattr(half, key), key
    for key in ("pressure", "gap", "displacement"):
        assert np.array_equal(getattr(thick, key), getattr(half, key)), key
    assert all(thick.error_estimate[k] == v for k, v in half.error_estimate.items())
    # its uniform mode still compresses: k v̄0 = C (k d) J0 p̃ over k h_ref (h_ref = 2h here)
    kd = layer.get("thickness") or 2.0 * math.pi * layer["thickness_over_wavelength"]
    nu = layer["nu"]
    c = 1.0 if layer["foundation"] == "frictionless" else (1 - 2 * nu) / (1 - nu) ** 2
    assert thick.mean_displacement == pytest.approx(c * kd * 0.3 / 2.0, rel=ROUNDOFF)
    assert thick.approach == pytest.approx(thick.penetration + thick.mean_displacement,
                                           rel=ROUNDOFF)
    assert thick.layer["thickness"] == pytest.approx(kd, rel=ROUNDOFF)
    assert thick.diagnostics["layer"]["approach"] == thick.approach
    assert thick.as_dict()["mean_displacement"] == thick.mean_displacement


@pytest.mark.parametrize("layer, material, direction", [
    ({"thickness": 0.4, "foundation": "bonded", "nu": 0.3}, (1.0, (0.4, 0.3), (0.5, 3.0)), 37.0),
    ({"thickness_over_wavelength": 0.1, "foundation": "frictionless", "nu": 0.2},
     (2.0, (1.5,), (0.2,)), -120.0),
    (BONDED, (1.0, (2.0 / 3.0,), (1.0,)), 0.0),
])
def test_full_contact_on_a_layer_is_the_closed_form(layer, material, direction):
    """σ_q = z_q/(Ĉ(q) S(|q| k d)), the friction Σ (q·ê) Im(Ĉ S)|σ_q|², the mean compression
    C (k d) J0 p̃."""
    from analytic.references._layer import layer_factor, uniform_compliance
    # heights well below d and a load whose compression stays short of the foundation
    harmonics, aspect, speed, load = {(1, 0): 0.01, (0, 1): 0.007j, (1, 1): 0.003}, 1.3, 1.5, 0.3
    res = sr.solve(load=load, speed=speed, heights=harmonics, aspect=aspect,
                   direction=direction, material=material, nodes=(16, 32), layer=layer)
    assert res.success and res.full_contact and res.contact_fraction == 1.0
    kd = layer.get("thickness") or 2.0 * math.pi * layer["thickness_over_wavelength"]
    factors = {q: layer_factor(math.hypot(*q) * kd, layer["nu"], layer["foundation"])
               for q in ((m, n / aspect) for m, n in harmonics)}
    assert all(0.0 < f < 1.0 for f in factors.values())
    _assert_full_contact_sum(res, harmonics, aspect, direction, material, speed, load,
                             factor=factors.__getitem__)
    mean = uniform_compliance(layer["nu"], layer["foundation"]) * kd * material[0] * load \
        / res.h_ref
    assert res.mean_displacement == pytest.approx(mean, rel=ROUNDOFF, abs=ROUNDOFF)
    assert res.approach == pytest.approx(1.0 + mean, rel=ROUNDOFF)


def test_the_bisinusoid_on_a_bonded_layer_agrees_with_the_bem():
    """hk = 1, p̃ = 0.3, V/V0 = 1 on a bonded incompressible layer d/Lx = 0.5: the surface BEM
    on 256 panels and this reference on 64 … 256 agree within the sum of their estimates."""
    import bem
    ref = sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, layer=BONDED)
    got = bem.solve_surface(load=0.3, speed=1.0, nodes=256, layer=bem.Layer(
        thickness_over_wavelength=0.5, foundation="bonded", nu=0.5))
    assert ref.success and got.success
    # a layer is stiffer than the half-space: less penetration at the same load
    half = sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(16, 32, 64))
    assert ref.penetration < half.penetration
    for key in ("mu", "penetration", "contact_fraction"):
        a, b = getattr(ref, key), getattr(got, key)
        ea, eb = ref.error_estimate[key] * abs(a), got.error_estimate[key] * abs(b)  # relative
        assert abs(a - b) <= ea + eb, (key, a, b, ea, eb)
    assert ref.n_patches == got.n_patches == 1
    lay = got.diagnostics["layer"]
    assert ref.mean_displacement == lay["mean_displacement"] == 0.0     # C = 0 at ν = ½
    assert abs(ref.approach - lay["approach"]) <= (ref.error_estimate["approach"]
                                                   + got.error_estimate["penetration"])


@pytest.mark.parametrize("layer, name", [
    ("thick", "layer"),
    ({"thickness": 1.0, "foundation": "bonded"}, "layer"),
    ({"thickness": 1.0, "thickness_over_wavelength": 0.2, "foundation": "bonded", "nu": 0.3},
     "layer"),
    ({"thickness": 1.0, "foundation": "bonded", "nu": 0.3, "E": 1.0}, "layer"),
    ({"thickness": -1.0, "foundation": "bonded", "nu": 0.3}, "layer['thickness']"),
    ({"thickness": math.inf, "foundation": "bonded", "nu": 0.3}, "layer['thickness']"),
    ({"thickness_over_wavelength": 0.0, "foundation": "bonded", "nu": 0.3},
     "layer['thickness_over_wavelength']"),
    ({"thickness_over_wavelength": 1e-120, "foundation": "bonded", "nu": 0.5},
     "layer['thickness_over_wavelength']"),
    ({"thickness": 1.0, "foundation": "glued", "nu": 0.3}, "layer['foundation']"),
    ({"thickness": 1.0, "foundation": "bonded", "nu": 0.7}, "layer['nu']"),
    ({"thickness": 1.0, "foundation": "bonded", "nu": "half"}, "layer['nu']"),
])
def test_bad_layers_are_refused_by_name(layer, name):
    import re
    with pytest.raises(ValueError, match=rf"^{re.escape(name)}=.* is not allowed: "):
        sr.solve(load=0.3, speed=1.0, heights=BISINUSOID, nodes=(16, 32), layer=layer)


def test_a_penetration_through_the_layer_is_refused():
    """The approach is at least Δ: Δ/h_ref ≥ k d/(k h_ref) puts the crest on the foundation."""
    layer = {"thickness": 0.5, "foundation": "bonded", "nu": 0.5}     # k h_ref = 2
    with pytest.raises(ValueError, match=r"^penetration=0\.3 is not allowed: "):
        sr.solve(penetration=0.3, speed=1.0, heights=BISINUSOID, nodes=(16, 32), layer=layer)
    res = sr.solve(penetration=0.2, speed=1.0, heights=BISINUSOID, nodes=(16, 32), layer=layer)
    assert res.success and res.approach == res.penetration
