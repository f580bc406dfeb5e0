"""ContactMechanics as a third code for the elastic layer (comparisons.peers.contactmechanics):
its layer operator mode by mode against `bem.Layer.factor`, and its contact solver against
`bem.solve(speed=0, layer=...)` (the relaxed elastic solid) on the same grid.

The two discretisations differ: `bem` has panels of constant pressure, integrated exactly and
collocated at their centres; ContactMechanics has point pressures at the same positions with
the continuum's symbol on the modes |n| ≤ N/2.  Each difference is therefore bounded by a law
in N measured with ContactMechanics 1.8.3 at N = 256 … 4096 (p̃ = 0.1, 0.3; the half-space,
k d = 1 at ν = ½ and k d = 0.3 at ν = 0.45), written next to its assertion, and asserted at
N = 256 and 2048.  Runtime: about 10 s on two loaded cores.
"""
from __future__ import annotations

import math
import sys

import numpy as np
import pytest

# the test extra installs it; its version from the distribution (ContactMechanics.__version__
# is discovered from git, and inside the project's checkout it is the project's commit)
cmech = pytest.importorskip("ContactMechanics")

import bem  # noqa: E402
from comparisons._errors import MissingPackage  # noqa: E402
from comparisons.peers import contactmechanics as peer  # noqa: E402
from viscosine import Fields  # noqa: E402

EPS = np.finfo(float).eps


# ----------------------------------------------------------------------------- (i) S per mode
KDS = [float(t) for t in np.geomspace(0.01, 30.0, 13)]


@pytest.mark.parametrize("nu", [0.0, 0.3, 0.45])
def test_layer_factor_is_the_bonded_one(nu):
    """Every mode of N = 256 along x: ContactMechanics's S is S_B of docs/layers.md (measured
    at most 1.1e-15 relative, 5 ulp, over k d = 0.01 … 30, i.e. t = |n| k d up to 3840) and its
    uniform mode the bonded C = (1 − 2ν)/(1 − ν)² (to 3.3e-16).  S_F is another curve: on
    mode 1 they differ by 2.8e-10 (k d = 0.01, ν = 0: both are t/2 + O(t³) there) to 2e-7
    (k d = 10) and 67 % (k d ≤ 0.3, ν = 0.45)."""
    for kd in KDS:
        c = peer.compliance(thickness=kd, nu=nu, nodes=256)
        assert c.modes[0] == 0 and c.modes[-1] == 128
        bonded = bem.Layer(thickness=kd, foundation="bonded", nu=nu)
        s_b = bonded.factor(c.modes[1:])
        assert np.max(np.abs(c.factor[1:] / s_b - 1.0)) <= 2e-15, kd
        np.testing.assert_allclose(c.compliance[1:], 2.0 * s_b / c.modes[1:], rtol=2e-15)
        assert c.uniform == pytest.approx(bonded.uniform, rel=1e-15)
        # and not S_F: wherever the two differ (beyond 1e-12), ContactMechanics is that far
        s_f = bem.Layer(thickness=kd, foundation="frictionless", nu=nu).factor(c.modes[1:])
        apart = np.abs(s_b / s_f - 1.0)
        far = apart > 1e-12
        assert np.all(np.abs(c.factor[1:] / s_f - 1.0)[far] >= 0.99 * apart[far])
        if kd <= 10.0:
            assert far[0]


def test_incompressible_layer_and_half_space_operator():
    """ν = ½ (passed to ContactMechanics as a NumPy float, see below): uniform compliance 0, the
    modes S_B to 1.3e-15 from k d = 0.3 on; thinner, its hyperbolic form cancels (measured 2e-14
    at k d = 0.05, 4e-13 at 0.01).  The half-space: 2/|n| to round-off."""
    for kd, tol in ((0.01, 1e-12), (0.05, 5e-14), (0.3, 2e-15), (1.0, 2e-15), (10.0, 2e-15)):
        c = peer.compliance(thickness=kd, nu=0.5, nodes=256)
        s_b = bem.Layer(thickness=kd, foundation="bonded", nu=0.5).factor(c.modes[1:])
        assert np.max(np.abs(c.factor[1:] / s_b - 1.0)) <= tol, kd
        assert c.uniform == 0.0 and c.compliance[0] == 0.0
    hs = peer.compliance(nodes=64)
    assert math.isnan(hs.uniform) and math.isnan(hs.compliance[0])
    assert np.max(np.abs(hs.factor[1:] - 1.0)) <= 2 * EPS
    # thick: S = 1 for every mode (1 − S_B(30) ≈ 4e-23)
    assert np.max(np.abs(peer.compliance(thickness=30.0, nu=0.3, nodes=64).factor[1:] - 1.0)) \
        <= 2 * EPS


def test_what_contactmechanics_does_not_do():
    """The limits the adapter works around (ContactMechanics 1.8.3): a 1-D grid ignores
    ``thickness``; ν = ½ as a Python float divides by zero in the uniform stiffness; the
    half-space on an N × 1 grid needs ``stiffness_q0``."""
    half = cmech.PeriodicFFTElasticHalfSpace
    one_d = [np.asarray(half((64,), 1.0, physical_sizes=(2 * math.pi,), thickness=t,
                             poisson=0.3).greens_function) for t in (None, 0.3)]
    assert np.array_equal(one_d[0], one_d[1])
    with pytest.raises(ZeroDivisionError):
        half((64, 1), 0.75, physical_sizes=(2 * math.pi,) * 2, thickness=1.0, poisson=0.5)
    with pytest.raises(IndexError):
        half((64, 1), 1.0, physical_sizes=(2 * math.pi,) * 2)


# ----------------------------------------------------------------------------- (ii) contact
# (k d or None, ν); the half-space is case (iii)
CASES = [(None, 0.3), (1.0, 0.5), (0.3, 0.45)]
LOADS = (0.1, 0.3)
NODES = (256, 2048)


def _layer(kd, nu):
    return None if kd is None else bem.Layer(thickness=kd, foundation="bonded", nu=nu)


@pytest.fixture(scope="module")
def pairs():
    """(kd, ν, p̃, N) -> (ContactMechanics's result, bem's result)."""
    out = {}
    for kd, nu in CASES:
        for load in LOADS:
            for n in NODES:
                cm = peer.solve(load=load, thickness=kd, nu=nu, nodes=n)
                b = bem.solve(load=load, speed=0.0, ratio=3.0, nodes=n, layer=_layer(kd, nu))
                out[kd, nu, load, n] = cm, b
    return out


@pytest.mark.parametrize("kd, nu", CASES)
@pytest.mark.parametrize("load", LOADS)
@pytest.mark.parametrize("n", NODES)
def test_contact_scalars_agree(pairs, kd, nu, load, n):
    """Relative difference of Δ/h below 10/N² (measured N²·|δ| 0.34–1.7 on the half-space,
    1.4–3.0 at k d = 1, 3.0–8.6 at k d = 0.3), of the approach below 1.5/N² (measured at most
    1.02/N²); contact fractions within 0.5/N (ContactMechanics's edges, placed from its nodal
    gaps, are within a quarter of a cell: measured at most 0.36/N)."""
    cm, b = pairs[kd, nu, load, n]
    assert cm.success and b.success, (cm.message, b.message)
    assert cm.diagnostics["complementarity"] <= 1e-10  # measured ≤ 1.2e-12
    assert cm.load == pytest.approx(load, rel=1e-12)
    assert not cm.full_contact and cm.n_patches == 1
    assert abs(cm.penetration / b.penetration - 1.0) <= 10.0 / n ** 2
    assert abs(cm.contact_fraction - b.contact_fraction) <= 0.5 / n
    assert abs(cm.contact_nodes - cm.contact_fraction) <= 1.0 / n
    if kd is None:
        assert cm.approach is None and cm.mean_displacement is None
    else:
        lay = b.diagnostics["layer"]
        assert abs(cm.approach - lay["approach"]) <= 1.5 / n ** 2
        # the uniform compression C kd p̃/hk is exact on both (ContactMechanics's q = 0 mode)
        assert cm.mean_displacement == pytest.approx(lay["mean_displacement"], rel=1e-10,
                                                     abs=1e-15)


@pytest.mark.parametrize("kd, nu", CASES)
@pytest.mark.parametrize("load", LOADS)
@pytest.mark.parametrize("n", NODES)
def test_contact_fields_agree(pairs, kd, nu, load, n):
    """The pressure on the same grid, relative to bem's peak: largest difference below
    0.06/√N (at the edges, where σ ~ √distance; measured 0.016–0.050/√N), below 8/N² over the
    middle half of the contact (measured 0.95–6.7/N²), L2 norm (relative to bem's) below 0.3/N
    (measured 0.055–0.244/N).  Displacement v/h within 0.04/N (measured ≤ 0.031/N)."""
    cm, b = pairs[kd, nu, load, n]
    f = cm.fields()
    assert isinstance(f, Fields)
    np.testing.assert_array_equal(f.x_over_lambda, b.fields().x_over_lambda)
    peak = b.max_pressure
    d = np.abs(f.pressure - b.pressure)
    assert d.max() <= 0.06 * peak / math.sqrt(n)
    core = np.abs(f.x_over_lambda) <= 0.25 * b.contact_fraction
    assert core.sum() >= 0.2 * b.contact_fraction * n
    assert d[core].max() <= 8.0 * peak / n ** 2
    assert math.sqrt(np.mean(d ** 2)) <= 0.3 / n * math.sqrt(np.mean(b.pressure ** 2))
    assert np.max(np.abs(f.displacement - b.displacement)) <= 0.04 / n


@pytest.mark.parametrize("kd, nu", CASES)
def test_differences_fall_with_n(pairs, kd, nu):
    """From N = 256 to 2048 (8×): the Δ/h difference falls by ≥ 20 (N⁻²: measured 42–90), the
    L2 pressure difference by ≥ 5 (N⁻¹: measured 7–9)."""
    for load in LOADS:
        (c1, b1), (c2, b2) = (pairs[kd, nu, load, n] for n in NODES)
        dpen = [abs(c.penetration / b.penetration - 1) for c, b in ((c1, b1), (c2, b2))]
        assert dpen[1] * 20 <= dpen[0]
        l2 = [math.sqrt(np.mean((c.fields().pressure - b.pressure) ** 2))
              for c, b in ((c1, b1), (c2, b2))]
        assert l2[1] * 5 <= l2[0]


def test_field_conventions(pairs):
    """Load, deformed mean line, complementarity, and v/h = cos(2πx/λ) − s/h in contact."""
    cm, _ = pairs[1.0, 0.5, 0.3, 256]
    f = cm.fields()
    assert f.x_over_lambda[0] == -0.5 and f.x_over_lambda[128] == 0.0
    assert cm.x_max_pressure == 0.0
    assert np.mean(f.pressure) == pytest.approx(0.3, rel=1e-12)
    assert abs(np.mean(f.displacement)) <= 1e-15
    assert np.all(f.pressure >= 0.0) and np.all(f.gap >= 0.0)
    inside = f.pressure > 0.0
    assert np.all(f.gap[inside] == 0.0)
    np.testing.assert_allclose(f.displacement[inside],
                               np.cos(2 * np.pi * f.x_over_lambda[inside]) - cm.separation,
                               atol=1e-11)
    assert cm.separation == pytest.approx(np.mean(f.gap), rel=1e-15)
    assert cm.penetration + cm.separation == 1.0
    # the approach: Δ/h plus the uniform compression, 0 for a bonded incompressible layer
    assert abs(cm.mean_displacement) <= 1e-15   # the mean of u: 0 up to its round-off
    assert cm.approach == pytest.approx(cm.penetration, abs=1e-15)


@pytest.mark.parametrize("kd, nu", CASES)
def test_full_contact(kd, nu):
    """Above the full-contact load hk/(2 S(kd)) both are in full contact (Δ/h = 1).
    ContactMechanics's pressure is the continuum's p̃ + (hk/2S) cos(2πx/λ) to its tolerance
    (measured 1.6e-10 of the amplitude); bem's panel pressure exceeds it by the panel's
    1/sinc(π/N) − 1 ≈ π²/6N² of the amplitude (measured 1.40–1.64/N²)."""
    n = 256
    layer = _layer(kd, nu)
    amplitude = 0.5 / (1.0 if layer is None else float(layer.factor([1])[0]))
    load = 1.2 * amplitude
    cm = peer.solve(load=load, thickness=kd, nu=nu, nodes=n)
    b = bem.solve(load=load, speed=0.0, ratio=3.0, nodes=n, layer=layer)
    assert cm.success and cm.full_contact and b.full_contact
    assert cm.contact_fraction == 1.0 and cm.n_patches == 1
    assert cm.penetration == pytest.approx(1.0, abs=1e-12)
    x = cm.fields().x_over_lambda
    exact = load + amplitude * np.cos(2 * np.pi * x)
    assert np.max(np.abs(cm.fields().pressure - exact)) <= 1e-9 * amplitude
    d = np.max(np.abs(b.pressure - cm.fields().pressure))
    assert 1.3 * amplitude / n ** 2 <= d <= (math.pi ** 2 / 6) * amplitude / n ** 2
    if layer is not None:
        assert cm.approach == pytest.approx(b.diagnostics["layer"]["approach"], rel=1e-12)


# ----------------------------------------------------------------------------- (iii) half-space
def _westergaard(load, hk=1.0):
    s = load / (hk / 2.0)
    return 2.0 * math.asin(math.sqrt(s)) / math.pi, s * (1.0 - math.log(s))


@pytest.mark.parametrize("load", LOADS)
@pytest.mark.parametrize("n", NODES)
def test_half_space_is_westergaard(pairs, load, n):
    """ContactMechanics's half-space against the closed form (eq. 3.1): Δ/h within 5/N²
    relative (measured 0.6–4.2/N²), the contact fraction within 0.5/N."""
    cm, _ = pairs[None, 0.3, load, n]
    fraction, penetration = _westergaard(load)
    assert abs(cm.penetration / penetration - 1.0) <= 5.0 / n ** 2
    assert abs(cm.contact_fraction - fraction) <= 0.5 / n


def test_thick_layer_is_the_half_space(pairs):
    """k d = 30: every mode has S = 1, so ContactMechanics's layer gives its half-space's
    contact (measured: pressures 5e-11 of the peak apart, the iterations differ) and only
    adds the uniform compression C kd p̃/hk."""
    hs, _ = pairs[None, 0.3, 0.3, 256]
    thick = peer.solve(load=0.3, thickness=30.0, nu=0.3, nodes=256)
    assert thick.penetration == pytest.approx(hs.penetration, rel=1e-12)
    np.testing.assert_allclose(thick.fields().pressure, hs.fields().pressure,
                               atol=1e-9 * hs.max_pressure)
    c = (1 - 2 * 0.3) / (1 - 0.3) ** 2
    assert thick.mean_displacement == pytest.approx(c * 30.0 * 0.3, rel=1e-12)


# ----------------------------------------------------------------------------- input
def test_profile_object_and_heights():
    """A `bem` profile and its heights give the same answer; hk with a profile is refused."""
    prof = bem.Harmonics([1.0, 0.6], [0.0, 0.0])
    a = peer.solve(load=0.05, profile=prof, thickness=1.0, nu=0.3, nodes=256)
    b = peer.solve(load=0.05, profile=prof.sample(256), thickness=1.0, nu=0.3, nodes=256)
    assert a.success and a.hk == 1.6 and b.hk == pytest.approx(1.6)
    assert a.penetration == pytest.approx(b.penetration, rel=1e-12)
    with pytest.raises(ValueError, match="^hk=2.0 is not allowed"):
        peer.solve(load=0.05, profile=prof, hk=2.0)
    with pytest.raises(ValueError, match="^profile="):
        peer.solve(load=0.05, profile=np.zeros(256), nodes=256)


@pytest.mark.parametrize("kwargs, name", [
    ({"load": -1.0}, "load"), ({"load": "x"}, "load"), ({"nodes": 255}, "nodes"),
    ({"nodes": 8}, "nodes"), ({"nodes": 64.0}, "nodes"), ({"nu": 0.6}, "nu"),
    ({"nu": -1.0}, "nu"), ({"thickness": 0.0}, "thickness"),
    ({"thickness": math.inf}, "thickness"), ({"tolerance": 1.0}, "tolerance"),
])
def test_bad_input_names_parameter(kwargs, name):
    args = {"load": 0.1, "nodes": 64, **kwargs}
    with pytest.raises(ValueError) as err:
        peer.solve(**args)
    assert str(err.value) == f"{name}={kwargs[name]!r} is not allowed: {peer.ACCEPTED[name][2]}"


def test_missing_contactmechanics_says_how_to_install(monkeypatch):
    monkeypatch.setitem(sys.modules, "ContactMechanics", None)  # its import now raises
    for call in (lambda: peer.solve(load=0.1, nodes=64), lambda: peer.compliance(nodes=64)):
        with pytest.raises(MissingPackage, match=r"pip install 'viscosine\[peers\]'"):
            call()
    with pytest.raises(ValueError):  # bad input is still refused first
        peer.solve(load=-1.0, nodes=64)


def test_the_pinned_release_is_the_one_checked():
    """The figures of this file are ContactMechanics 1.8.3's (the peers extra pins it); the
    adapter reports the distribution's version, not the git-discovered one."""
    from importlib.metadata import version
    assert version("ContactMechanics") == "1.8.3"
    assert peer.compliance(thickness=1.0, nu=0.3, nodes=64).version == "1.8.3"
