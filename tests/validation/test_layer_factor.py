"""The layer factor S(t, nu) of `bem/_layer.py` against solutions built here (docs/layers.md).

Two references solve the boundary-value problem of one mode independently of the closed forms:

- ``navier_reference``: Navier's equations as a first-order system in depth (Hooke's law and
  equilibrium only, no assumed form of the solution), integrated by the matrix exponential in
  60-digit decimal arithmetic; good for every t here, thin layers and ν = 1/2 included.
- ``general_solution_reference``: the general solution in exponentials that decay from each
  face, its displacements and stresses assembled and the 4 x 4 system solved by
  numpy.linalg.solve; well conditioned for t >= 0.1 only (its four functions merge as t -> 0).

Units: z in 1/|k| (so the layer is 0 <= z <= t), μ = 1, p^ = 1; then the half-space's top
displacement is (1 - ν), and S = W(0)/(1 - ν).  State ``y = (U, W, Sx, Sz)`` with
``u_x = i U e^{ikx}``, ``u_z = W e^{ikx}``, ``σ_xz = i Sx e^{ikx}``, ``σ_zz = Sz e^{ikx}``.
"""
import math
from decimal import Decimal, localcontext

import numpy as np
import pytest

from bem._layer import layer_factor, uniform_compliance
from conftest import ROUNDOFF

FOUNDATIONS = ("bonded", "frictionless")
#: the components of y that vanish at the foundation
BOTTOM = {"bonded": (0, 1), "frictionless": (1, 2)}
#: decimal digits of the Navier reference: t = 50 spends about 24 of them on e^t
DIGITS = 60
#: the accuracy docs/layers.md states for layer_factor (2 ulp measured), with a margin of 4
ULPS = 8 * np.finfo(float).eps


def _navier_matrix(nu):
    """dy/dz = M y for one mode (k = 1, μ = 1) in plane strain.

    U' = Sx - W (from σ_xz = u_x,z + u_z,x); W' = a U + b Sz (from σ_zz, eliminating ε_xx);
    Sx' = c U - a Sz and Sz' = Sx (equilibrium, σ_xx written with U and Sz), where
    a = ν/(1 - ν), b = (1 - 2ν)/(2(1 - ν)) and c = 2/(1 - ν), finite for -1 < ν <= 1/2.
    """
    a = nu / (1 - nu)
    b = (1 - 2 * nu) / (2 * (1 - nu))
    c = 2 / (1 - nu)
    zero = Decimal(0)
    return [[zero, Decimal(-1), Decimal(1), zero],
            [a, zero, zero, b],
            [c, zero, zero, -a],
            [zero, zero, Decimal(1), zero]]


def _matmul(x, y):
    return [[sum(x[i][k] * y[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def _expm(m):
    """exp(m) by scaling, Taylor series and squaring, in the current decimal context."""
    norm = max(sum(abs(v) for v in row) for row in m)
    squarings = 0
    while norm > Decimal("0.5"):
        norm /= 2
        squarings += 1
    scale = Decimal(2) ** squarings
    a = [[v / scale for v in row] for row in m]
    out = [[Decimal(int(i == j)) for j in range(4)] for i in range(4)]
    term = [row[:] for row in out]
    tiny = Decimal(10) ** -(DIGITS + 5)
    n = 0
    while True:
        n += 1
        term = [[v / n for v in row] for row in _matmul(term, a)]
        out = [[u + v for u, v in zip(r, s)] for r, s in zip(out, term)]
        if max(abs(v) for row in term for v in row) < tiny:
            break
    for _ in range(squarings):
        out = _matmul(out, out)
    return out


def navier_reference(t, nu, foundation):
    """S from y(t) = exp(M t) y(0), y(0) = (U0, W0, 0, -1), two components of y(t) zero."""
    with localcontext() as ctx:
        ctx.prec = DIGITS
        dt, dnu = Decimal(t), Decimal(nu)
        p = _expm([[v * dt for v in row] for row in _navier_matrix(dnu)])
        (r1, r2) = BOTTOM[foundation]
        # p[r][0] U0 + p[r][1] W0 + p[r][3] (-1) = 0 for both rows r, by Cramer's rule
        det = p[r1][0] * p[r2][1] - p[r1][1] * p[r2][0]
        w0 = (p[r1][0] * p[r2][3] - p[r2][0] * p[r1][3]) / det
        return float(w0 / (1 - dnu))


def _state_of_constants(z, t, nu):
    """The 4 x 4 map from (A, B, C, D) to y(z) for the stress function
    F = A e^-z + B z e^-z + C e^(z-t) + D (t-z) e^(z-t) (σ_zz = -F, σ_xx = F'', σ_xz = -i F')."""
    e1, e3, s = math.exp(-z), math.exp(z - t), t - z
    d = np.array([  # rows: F, F', F'', F'''; columns: the four functions
        [e1, z * e1, e3, s * e3],
        [-e1, (1 - z) * e1, e3, (s - 1) * e3],
        [e1, (z - 2) * e1, e3, (s - 2) * e3],
        [-e1, (3 - z) * e1, e3, (s - 3) * e3]])
    u = -((1 - nu) * d[2] + nu * d[0]) / 2  # 2μ ε_xx = (1-ν)σ_xx - νσ_zz, ε_xx = i k u_x
    w = ((1 - nu) * d[3] - (2 - nu) * d[1]) / 2  # then u_z from 2 ε_xz = σ_xz/μ
    return np.array([u, w, -d[1], -d[0]])


def general_solution_reference(t, nu, foundation):
    top, bottom = _state_of_constants(0.0, t, nu), _state_of_constants(t, t, nu)
    rows = np.array([top[2], top[3], bottom[BOTTOM[foundation][0]], bottom[BOTTOM[foundation][1]]])
    constants = np.linalg.solve(rows, [0.0, -1.0, 0.0, 0.0])
    return top[1] @ constants / (1 - nu)


def _samples(seed, count, t_low):
    """(t, ν): log-uniform t in [t_low, 50]; ν uniform, at 1/2, just below 1/2, near -1."""
    rng = np.random.default_rng(seed)
    out = [(t_low, 0.5), (50.0, 0.5), (t_low, -1 + 1e-9), (1.0, -0.999999)]
    for _ in range(count):
        t = float(10 ** rng.uniform(math.log10(t_low), math.log10(50.0)))
        kind = rng.integers(4)
        nu = [float(rng.uniform(-1, 0.5)), 0.5, 0.5 - float(10 ** rng.uniform(-12, -1)),
              -1 + float(10 ** rng.uniform(-9, -1))][kind]
        out.append((t, nu))
    return out


# --------------------------------------------------------------------------------------------
# (a) against the two references
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("foundation", FOUNDATIONS)
def test_against_navier_in_60_digits(foundation):
    worst = 0.0
    for t, nu in _samples(11, 150, 1e-4):
        ref = navier_reference(t, nu, foundation)
        got = layer_factor(t, nu, foundation)
        assert got == pytest.approx(ref, rel=ROUNDOFF, abs=0.0), (t, nu)
        worst = max(worst, abs(got / ref - 1))
    assert worst <= ULPS, worst  # the stated accuracy, not only the tier


@pytest.mark.parametrize("foundation", FOUNDATIONS)
def test_against_the_general_solution_solved_by_numpy(foundation):
    for t, nu in _samples(12, 150, 0.1):
        got = layer_factor(t, nu, foundation)
        assert got == pytest.approx(general_solution_reference(t, nu, foundation),
                                    rel=ROUNDOFF, abs=0.0), (t, nu)


def test_the_two_references_agree():
    """Each reference checks the other's construction where both are accurate."""
    for t, nu in _samples(13, 20, 0.1):
        for foundation in FOUNDATIONS:
            assert general_solution_reference(t, nu, foundation) == pytest.approx(
                navier_reference(t, nu, foundation), rel=ROUNDOFF, abs=0.0)


def test_the_frictionless_factor_does_not_depend_on_nu():
    t = np.logspace(-4, 1.5, 57)
    base = layer_factor(t, 0.0, "frictionless")
    for nu in (-0.999, 0.3, 0.5):
        np.testing.assert_array_equal(layer_factor(t, nu, "frictionless"), base)
        assert navier_reference(0.7, nu, "frictionless") == pytest.approx(
            layer_factor(0.7, 0.0, "frictionless"), rel=ROUNDOFF)  # the physics, not the code


def test_a_softer_foundation_is_softer():
    """The frictionless foundation lets the layer slip, so it is more compliant than the bonded
    one, and any layer is stiffer than the half-space: 0 < S_B <= S_F < 1."""
    t = np.logspace(-3, 1.2, 200)
    for nu in (-0.9, 0.0, 0.3, 0.5):
        s_b, s_f = layer_factor(t, nu, "bonded"), layer_factor(t, nu, "frictionless")
        assert np.all(s_b > 0) and np.all(s_b <= s_f) and np.all(s_f < 1)


# --------------------------------------------------------------------------------------------
# (b) the thick limit
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("foundation", FOUNDATIONS)
def test_thick_layers_are_the_half_space_to_rounding(foundation):
    """1 exactly beyond t = 22.55 (bonded, ν = 1/2, the worst) and 20.94 (frictionless)."""
    beyond = np.array([22.6, 23.0, 25.0, 30.0, 100.0, 1e3, 1e300, np.inf])
    for nu in (0.5, 0.3, 0.0, -0.999999):
        np.testing.assert_array_equal(layer_factor(beyond, nu, foundation), 1.0)
    assert layer_factor(np.inf, 0.3, foundation) == 1.0
    assert layer_factor(20.0, 0.5, foundation) < 1.0  # not switched off before the limit


@pytest.mark.parametrize("nu", [0.5, 0.3, -0.9])
def test_the_thick_layer_rates(nu):
    """1 - S_B ~ ((1 + 2t)^2 + κ^2)/κ e^{-2t}, 1 - S_F ~ 2 (1 + 2t) e^{-2t}."""
    kappa = 3 - 4 * nu
    for t in (12.0, 15.0):
        q = math.exp(-2 * t)
        assert 1 - layer_factor(t, nu, "bonded") == pytest.approx(
            ((1 + 2 * t) ** 2 + kappa ** 2) / kappa * q, rel=1e-5)
        assert 1 - layer_factor(t, nu, "frictionless") == pytest.approx(2 * (1 + 2 * t) * q,
                                                                        rel=1e-5)


# --------------------------------------------------------------------------------------------
# (c) the thin limit
# --------------------------------------------------------------------------------------------
def test_the_incompressible_bonded_layer_stiffens_like_t_cubed():
    """S_B(t, 1/2) = (2/3) t^3 (1 - (9/5) t^2 + ...): v^ = k^2 d^3/(3μ) p^, a squeezed film."""
    t1, t2 = 1e-3, 1e-4
    s1, s2 = layer_factor(t1, 0.5, "bonded"), layer_factor(t2, 0.5, "bonded")
    assert math.log(s1 / s2) / math.log(t1 / t2) == pytest.approx(3.0, abs=1e-5)
    for t, s in ((t1, s1), (t2, s2)):
        assert s / t ** 3 == pytest.approx(2 / 3, rel=2 * t * t)
        assert (s / (2 / 3 * t ** 3) - 1) / t ** 2 == pytest.approx(-9 / 5, rel=1e-4)


@pytest.mark.parametrize("nu", [-0.999, -0.9, 0.0, 0.3, 0.45, 0.49])
def test_the_compressible_bonded_layer_is_a_winkler_foundation(nu):
    """S_B = s1 t + s3 t^3 + O(t^5): s1 = (1 - 2ν)/(2(1 - ν)^2) (uniaxial strain),
    s3 = ν(4ν - 1)/(6(1 - ν)^3)."""
    s1 = (1 - 2 * nu) / (2 * (1 - nu) ** 2)
    s3 = nu * (4 * nu - 1) / (6 * (1 - nu) ** 3)
    t1, t2 = 1e-3, 1e-4
    v1, v2 = layer_factor(t1, nu, "bonded"), layer_factor(t2, nu, "bonded")
    assert math.log(v1 / v2) / math.log(t1 / t2) == pytest.approx(1.0, abs=1e-6 / (1 - 2 * nu))
    for t, v in ((t1, v1), (t2, v2)):
        assert v == pytest.approx(s1 * t + s3 * t ** 3, rel=t * t / 10)
    assert (v1 - s1 * t1) / t1 ** 3 == pytest.approx(s3, rel=1e-4, abs=5e-6)


def test_the_frictionless_layer_spreads_freely():
    """S_F = t/2 - t^5/90 + O(t^7): v^ = (1 - ν^2) d/E p^, plane strain with σ_xx = 0."""
    for t in (1e-3, 1e-4, 1e-8, 1e-200):
        assert layer_factor(t, 0.3, "frictionless") / t == pytest.approx(0.5, rel=ROUNDOFF)
    t = 1e-2
    assert (layer_factor(t, 0.3, "frictionless") - t / 2) / t ** 5 == pytest.approx(-1 / 90,
                                                                                   rel=1e-3)


@pytest.mark.parametrize("foundation", FOUNDATIONS)
def test_zero_thickness(foundation):
    assert layer_factor(0.0, 0.5, foundation) == 0.0
    assert layer_factor(0, 0.3, foundation) == 0.0


def _compression(nu, held):
    """Uniform σ_zz = -1 on a layer: ε_zz from the isotropic compliance matrix (E = 1), plane
    strain (ε_yy = 0) and ε_xx = 0 (held) or σ_xx = 0 (free); unknowns σ_xx, σ_yy, ε_zz."""
    compliance = np.array([[1, -nu, -nu], [-nu, 1, -nu], [-nu, -nu, 1]], float)
    if held:  # rows ε_xx = 0, ε_yy = 0: solve for σ_xx, σ_yy
        sxx, syy = np.linalg.solve(compliance[:2, :2], -compliance[:2, 2] * -1.0)
    else:
        sxx, syy = 0.0, -compliance[1, 2] * -1.0 / compliance[1, 1]
    return -(compliance[2] @ [sxx, syy, -1.0])  # compression, positive into the body


@pytest.mark.parametrize("nu", [-0.999, -0.5, 0.0, 0.3, 0.49, 0.5])
def test_the_uniform_mode(nu):
    """C (1 - ν^2) d/E is the layer's compression per unit pressure; bonded and frictionless-free
    continue the modes (C = lim 2S/t)."""
    c_held = _compression(nu, held=True) / (1 - nu ** 2)
    c_free = _compression(nu, held=False) / (1 - nu ** 2)
    assert c_free == pytest.approx(1.0, rel=ROUNDOFF)
    for lateral in ("free", "held"):
        assert uniform_compliance(nu, "bonded", lateral) == pytest.approx(c_held, rel=ROUNDOFF,
                                                                          abs=ROUNDOFF)
    assert uniform_compliance(nu, "frictionless") == pytest.approx(c_free, rel=ROUNDOFF)
    assert uniform_compliance(nu, "frictionless", "held") == pytest.approx(c_held, rel=ROUNDOFF,
                                                                           abs=ROUNDOFF)
    t = 1e-7
    for foundation in FOUNDATIONS:
        assert 2 * layer_factor(t, nu, foundation) / t == pytest.approx(
            uniform_compliance(nu, foundation), rel=1e-12, abs=1e-12)


# --------------------------------------------------------------------------------------------
# shapes
# --------------------------------------------------------------------------------------------
def test_shapes():
    t = np.array([[0.0, 0.5], [2.0, np.inf]])
    out = layer_factor(t, 0.3, "bonded")
    assert out.shape == (2, 2)
    assert out[0, 1] == layer_factor(0.5, 0.3, "bonded")
    assert isinstance(layer_factor(1.0, 0.3, "bonded"), float)
    assert layer_factor([1.0, 2], 0.3, "frictionless").shape == (2,)
    assert layer_factor(np.array([]), 0.3, "bonded").shape == (0,)


# --------------------------------------------------------------------------------------------
# (d) refusals
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("nu", [0.5000001, 0.6, -1.0, -1.5, float("nan"), float("inf"), "0.3",
                                True, None])
def test_bad_nu(nu):
    with pytest.raises(ValueError, match=r"^nu=.* is not allowed: .*Poisson ratio in \(-1, 0\.5\]"):
        layer_factor(1.0, nu, "bonded")
    with pytest.raises(ValueError, match=r"^nu="):
        uniform_compliance(nu, "bonded")


@pytest.mark.parametrize("foundation", ["free", "Bonded", "", None, 3])
def test_bad_foundation(foundation):
    with pytest.raises(ValueError, match=r"^foundation=.* is not allowed: 'bonded' .* or "
                                         r"'frictionless'"):
        layer_factor(1.0, 0.3, foundation)
    with pytest.raises(ValueError, match=r"^foundation="):
        uniform_compliance(0.3, foundation)


@pytest.mark.parametrize("t, pattern", [
    (-1e-3, r"^t=-0\.001 is not allowed: .*\|k\| d >= 0"),
    (float("nan"), r"^t=nan is not allowed: .*NaN and negative values are refused"),
    (-np.inf, r"^t=-inf is not allowed"),
    ([1.0, -2.0], r"^t=-2\.0 is not allowed: .*\(element 1 of the array\)"),
    (np.array([[0.5], [np.nan]]), r"^t=nan is not allowed: .*\(element 1 of the array\)"),
    ("1", r"^t='1' is not allowed: real numbers"),
    ([1.0, "a"], r"^t=\[1\.0, 'a'\] is not allowed: real numbers")])
def test_bad_t(t, pattern):
    with pytest.raises(ValueError, match=pattern):
        layer_factor(t, 0.3, "bonded")


def test_bad_lateral():
    with pytest.raises(ValueError, match=r"^lateral='fixed' is not allowed: 'free' .* or 'held'"):
        uniform_compliance(0.3, "frictionless", "fixed")
