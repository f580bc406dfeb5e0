"""`bem.solve_surface`: steady sliding of a rigid periodic surface (three-dimensional contact).

Checked here: the surfaces (exact sampling, refinement, rotation), the operator (its symbol is
the line contact's J* at the frequency q.V; a real, mirror-symmetric operator), the surface
uniform in y against the line contact (both roads) and sliding along its ridges (relaxed
Westergaard, no friction), the oblique extruded surface's exact law, full contact in closed
form, the elastic limits, quarter-turn and mirror symmetry, the energy identity converging, the
scaling of the dimensionless groups, Hertz at vanishing load, a thick layer, and bad input.
Tolerances of the discretisation come from the measurements written beside them.
"""
import math
import re

import numpy as np
import pytest

import analytic
import bem
from bem._surface_operator import SpectralOperator, surface_symbol
from conftest import ROUNDOFF

SLS3 = bem.Prony.standard_linear_solid(3.0)


# --------------------------------------------------------------------------------------------
# Surfaces
# --------------------------------------------------------------------------------------------
def test_bisinusoid_samples_and_amplitude():
    s = bem.bisinusoid(0.7, 0.2, aspect=2.0)
    nx, ny = 16, 32
    x = np.arange(nx) / nx - 0.5
    y = (np.arange(ny) / ny - 0.5) * 2.0
    want = 0.7 * np.cos(2 * np.pi * x)[:, None] + 0.2 * np.cos(2 * np.pi * y / 2.0)[None, :]
    assert np.max(np.abs(s.sample(nx, ny) - want)) < ROUNDOFF
    assert s.amplitude == pytest.approx(0.9, abs=ROUNDOFF)
    gx, gy = s.gradient(nx, ny)
    assert np.max(np.abs(gx + 0.7 * np.sin(2 * np.pi * x)[:, None])) < ROUNDOFF
    assert np.max(np.abs(gy + 0.2 / 2.0 * np.sin(np.pi * y)[None, :])) < ROUNDOFF


def test_self_affine_is_seeded_band_limited_and_normalised():
    kw = dict(hurst=0.8, rolloff=4, short_cutoff=16, rms_slope=0.1, seed=3)
    a, b = bem.self_affine(**kw), bem.self_affine(**kw)
    assert np.array_equal(a.sample(64, 64), b.sample(64, 64))
    c = bem.self_affine(**dict(kw, seed=4))
    assert not np.allclose(a.sample(64, 64), c.sample(64, 64))
    # refinement samples the same surface: every second centre of 2N is a centre of N
    assert np.max(np.abs(a.sample(128, 128)[::2, ::2] - a.sample(64, 64))) < ROUNDOFF
    z = a.sample(64, 64)
    gx, gy = a.gradient(64, 64)
    assert math.sqrt(np.mean(gx ** 2 + gy ** 2)) == pytest.approx(0.1, rel=1e-12)
    assert a.rms()["slope"] == pytest.approx(0.1, rel=1e-12)
    assert a.rms()["height"] == pytest.approx(float(np.std(z)), rel=1e-12)
    assert a.amplitude >= z.max() - z.mean() - ROUNDOFF
    q = np.hypot(a.modes[:, 0], a.modes[:, 1])
    assert q.min() >= 1.0 and q.max() <= 16.0


def test_sampled_surface_round_trip_and_rotation():
    s = bem.self_affine(hurst=0.5, rolloff=2, short_cutoff=6, rms_height=0.3, seed=1)
    z = s.sample(32, 32)
    t = bem.sampled_surface(z)
    assert np.max(np.abs(t.sample(32, 32) - z)) < ROUNDOFF
    assert np.max(np.abs(t.sample(64, 64) - s.sample(64, 64))) < ROUNDOFF
    # a quarter turn counter-clockwise: z'(x, y) = z(y, -x); index i <-> x = i/N - 1/2
    r = s.rotated_quarter(1).sample(32, 32)
    i, j = np.meshgrid(np.arange(32), np.arange(32), indexing="ij")
    assert np.max(np.abs(r - z[j, (32 - i) % 32])) < ROUNDOFF


# --------------------------------------------------------------------------------------------
# The operator
# --------------------------------------------------------------------------------------------
@pytest.mark.parametrize("theta", [0.0, 0.4, 2.0])
def test_symbol_is_the_line_compliance_at_q_dot_v(theta):
    mat = bem.Prony(1.0, (0.3, 0.4), (0.1, 3.0))
    nx, ny, aspect, w = 16, 8, 0.5, 2.3
    sym = surface_symbol(nx, ny, aspect, mat.j_plus, mat.terms, w, theta)
    m = np.fft.fftfreq(nx, 1.0 / nx)
    for a in range(1, nx // 2):  # away from the Nyquist modes
        for b in range(0, ny // 2):
            q = (m[a], b / aspect)
            freq = q[0] * math.cos(theta) + q[1] * math.sin(theta)
            want = 2.0 / math.hypot(*q) * complex(mat.jstar([freq], w)[0])
            assert abs(sym[a, b] - want) < ROUNDOFF * abs(want)
    assert sym[0, 0] == 0.0


def test_operator_is_real_and_mirror_symmetric():
    """Sliding along x, the operator commutes with the mirror y -> -y (the Nyquist modes are
    averaged over both signs, so this holds on even grids exactly)."""
    nx = ny = 16
    sym = surface_symbol(nx, ny, 1.0, SLS3.j_plus, SLS3.terms, 1.0, 0.0)
    op = SpectralOperator(sym, (nx, ny))
    rng = np.random.default_rng(0)
    f = rng.standard_normal((nx, ny))
    mirror = lambda a: a[:, (-np.arange(ny)) % ny]
    u = op.apply(f.reshape(-1)).reshape(nx, ny)
    um = op.apply(mirror(f).reshape(-1)).reshape(nx, ny)
    assert np.max(np.abs(um - mirror(u))) < ROUNDOFF
    back = op.pseudo_solve(u.reshape(-1)).reshape(nx, ny)
    assert np.max(np.abs(back - (f - f.mean()))) < 1e-11


def test_fft_threads_change_no_bit_and_a_bad_setting_is_refused(monkeypatch):
    """The tests and the commands' process pools run the surface FFTs on one thread
    (VISCOSINE_FFT_THREADS=1), a user's single solve on two: the same bits either way, on a
    grid large enough for pocketfft to split the work (the refused value names the variable)."""
    from bem import _surface_operator as S
    nx, ny = 256, 128
    symbol = surface_symbol(nx, ny, 1.0, SLS3.j_plus, SLS3.terms, 1.0, 0.3)
    f = np.random.default_rng(1).standard_normal(nx * ny)
    got = {}
    for n in ("1", "2", "3"):
        monkeypatch.setenv(S.THREADS_VARIABLE, n)
        op = SpectralOperator(symbol.copy(), (nx, ny))  # read when the operator is made
        assert op.threads == int(n)
        got[n] = (op.apply(f.copy()), op.pseudo_solve(f.copy()))
    for n in ("2", "3"):
        assert all(np.array_equal(a, b) for a, b in zip(got["1"], got[n])), n
    monkeypatch.delenv(S.THREADS_VARIABLE)
    assert SpectralOperator(symbol.copy(), (nx, ny)).threads == S.WORKERS == 2
    for bad in ("0", "-1", "two", "1.5", ""):
        monkeypatch.setenv(S.THREADS_VARIABLE, bad)
        with pytest.raises(ValueError, match=rf"^VISCOSINE_FFT_THREADS='{re.escape(bad)}' is "
                                             r"not allowed: a whole number >= 1$"):
            bem.solve_surface(load=0.3, speed=1.0, surface=bem.bisinusoid(1.0), nodes=16)


# --------------------------------------------------------------------------------------------
# The line contact, extruded
# --------------------------------------------------------------------------------------------
def test_uniform_in_y_is_the_line_contact():
    """z = h cos(kx) sliding along x against both line-contact roads, within the sum of the
    estimates (512 panels a side: measured |mu - analytic| = 1.2e-5 relative against an
    estimate of 1.8e-4, contact fraction 4.4e-5 against 5.5e-4, absolute; the estimates are
    relative)."""
    s = bem.solve_surface(load=0.3, speed=1.0, surface=bem.bisinusoid(1.0, 0.0), nodes=512)
    a = analytic.solve(load=0.3, speed=1.0)
    line = bem.solve(load=0.3, speed=1.0, nodes=4096)
    assert s.success and s.n_patches == 1
    est = s.error_estimate
    assert abs(s.mu - a.mu) <= est["mu"] * s.mu
    assert abs(s.penetration - a.penetration) <= est["penetration"] * s.penetration
    assert abs(s.contact_fraction - a.contact_fraction) <= \
        est["contact_fraction"] * s.contact_fraction
    lest = line.error_estimate
    assert abs(s.mu - line.mu) <= est["mu"] * s.mu + lest["mu"] * line.mu
    assert abs(s.contact_fraction - line.contact_fraction) <= \
        est["contact_fraction"] * s.contact_fraction + \
        lest["contact_fraction"] * line.contact_fraction
    assert s.mu_lateral == pytest.approx(0.0, abs=ROUNDOFF)
    # the contact leads: its centre ahead of the crest (e > 0), the pressure's further (ê > e)
    p = s.patches[0]
    assert 0 < p.eccentricity < p.pressure_eccentricity
    # measured: k ê 0.3821445 against 0.3821465, k e 0.28225 against 0.28325 (panel centroid)
    assert p.pressure_eccentricity * 2 * math.pi == pytest.approx(a.ke_hat, abs=1e-4)
    assert p.eccentricity * 2 * math.pi == pytest.approx(a.ke, abs=4 * math.pi / 512)


def test_sliding_along_the_ridges_is_relaxed_and_frictionless():
    """Every mode of a surface uniform in y has q.V = 0 when it slides along y: the relaxed
    elastic contact (Westergaard with E0) and no friction, exactly."""
    s = bem.solve_surface(load=0.3, speed=5.0, surface=bem.bisinusoid(1.0, 0.0), direction=90,
                          nodes=256)
    w = analytic.solve(load=0.3, speed=0.0)
    assert s.success
    assert abs(s.mu) < ROUNDOFF and abs(s.mu_lateral) < ROUNDOFF
    assert abs(s.penetration - w.penetration) <= s.error_estimate["penetration"] * w.penetration
    assert abs(s.contact_fraction - w.contact_fraction) <= \
        s.error_estimate["contact_fraction"] * s.contact_fraction


@pytest.mark.parametrize("theta", [30.0, -60.0])
def test_oblique_extruded_surface_obeys_the_line_law(theta):
    """A surface uniform in y at angle theta: only the x-modes see the motion, at the speed
    w cos(theta), and the force they feel lies along -x: mu = cos(theta) mu_line(w cos(theta)),
    mu_lateral = sin(theta) mu_line(w cos(theta)) (to the left of V for theta > 0)."""
    surf = bem.bisinusoid(1.0, 0.0)
    w = 2.0
    c, s_ = math.cos(math.radians(theta)), math.sin(math.radians(theta))
    r = bem.solve_surface(load=0.2, speed=w, surface=surf, direction=theta, nodes=64)
    ref = bem.solve_surface(load=0.2, speed=w * c, surface=surf, direction=0.0, nodes=64)
    assert r.mu == pytest.approx(c * ref.mu, rel=1e-10)
    assert r.mu_lateral == pytest.approx(s_ * ref.mu, rel=1e-10)
    assert r.contact_fraction == pytest.approx(ref.contact_fraction, rel=1e-12)


# --------------------------------------------------------------------------------------------
# Full contact, elastic limits, symmetry, energy, scaling
# --------------------------------------------------------------------------------------------
def _closed_form(surface, material, speed, theta, load, n):
    sym = surface_symbol(n, n, surface.aspect, material.j_plus, material.terms, speed,
                         math.radians(theta))
    zq = surface.spectrum(n, n) / (n * n)
    sq = np.zeros_like(zq)
    sq[sym != 0] = zq[sym != 0] / sym[sym != 0]
    sigma = np.fft.irfft2(sq * n * n, s=(n, n)) + load
    return sigma


@pytest.mark.parametrize("theta", [0.0, 35.0])
def test_full_contact_is_the_closed_form(theta):
    surf = bem.bisinusoid(1.0, 0.5, aspect=1.0)
    mat = bem.Prony(1.0, (0.5, 0.2), (1.0, 0.05))
    n = 32
    # closed form: per mode sigma_q = z_q / C(q); mu from each mode's dissipation
    sigma = _closed_form(surf, mat, 1.5, theta, 4.0, n)
    assert sigma.min() > 0
    r = bem.solve_surface(load=4.0, speed=1.5, surface=surf, material=mat, direction=theta,
                          nodes=n)
    assert r.success and r.full_contact and r.contact_fraction == 1.0
    assert np.max(np.abs(r.pressure - sigma)) < 1e-12 * sigma.max()
    t = math.radians(theta)
    e, ep = np.array([math.cos(t), math.sin(t)]), np.array([-math.sin(t), math.cos(t)])
    tau = lat = 0.0
    for (m, k), hk in (((1, 0), 1.0), ((0, 1), 0.5)):
        q = np.array([m, k], dtype=float)
        jj = complex(mat.jstar([q @ e], 1.5)[0])
        c = 2.0 / np.linalg.norm(q) * jj
        amp2 = 2 * abs(hk / 2 / c) ** 2  # the mode and its conjugate
        tau += (q @ e) * c.imag * amp2
        lat -= (q @ ep) * c.imag * amp2
    assert r.mu == pytest.approx(tau / 4.0, rel=1e-12)
    assert r.mu_lateral == pytest.approx(lat / 4.0, rel=1e-12, abs=1e-15)
    assert r.penetration == 1.0


def test_elastic_limits_are_the_relaxed_and_glassy_contacts():
    """V -> 0 is the relaxed contact; V -> infinity the glassy one where every mode moves: a
    mode with q.V = 0 stays relaxed at any speed (sliding along x the modes (0, n), at 45
    degrees (1, -1), ...), so the fast one slides at 37 degrees, where no mode of the grid is
    perpendicular to V; along x the fast contact lies between the two."""
    surf = bem.bisinusoid(1.0)
    slow = bem.solve_surface(load=0.3, speed=1e-12, surface=surf, nodes=64)
    fast = bem.solve_surface(load=0.3, speed=1e12, surface=surf, nodes=64, direction=37)
    along_x = bem.solve_surface(load=0.3, speed=1e12, surface=surf, nodes=64)
    relaxed = bem.solve_surface(load=0.3, speed=0.0, surface=surf, nodes=64,
                                material=bem.Prony(1.0))
    glassy = bem.solve_surface(load=0.3, speed=0.0, surface=surf, nodes=64,
                               material=bem.Prony(SLS3.j_plus))
    for v, e in ((slow, relaxed), (fast, glassy)):
        assert v.penetration == pytest.approx(e.penetration, rel=1e-9)
        assert v.contact_fraction == pytest.approx(e.contact_fraction, abs=1e-9)
        assert v.mu < 1e-9
    assert relaxed.mu == 0.0
    assert glassy.penetration < along_x.penetration < relaxed.penetration


def test_quarter_turn_and_mirror_symmetry():
    """Sliding at theta over a surface equals sliding at 0 over it turned by -theta, exactly for
    quarter turns on a square grid; an anisotropic surface symmetric in y at +theta and -theta
    has the same mu and opposite lateral force."""
    surf = bem.self_affine(hurst=0.7, rolloff=2, short_cutoff=5, rms_slope=0.4, seed=7)
    a = bem.solve_surface(load=0.1, speed=1.0, surface=surf, direction=90, nodes=64)
    b = bem.solve_surface(load=0.1, speed=1.0, surface=surf.rotated_quarter(-1), direction=0,
                          nodes=64)
    assert a.success and b.success
    assert a.mu == pytest.approx(b.mu, rel=1e-10)
    assert a.mu_lateral == pytest.approx(b.mu_lateral, rel=1e-8, abs=1e-12)
    assert a.contact_fraction == pytest.approx(b.contact_fraction, rel=1e-10)
    # b's field, turned back by a quarter turn: index (i, j) of b is (j, -i) of a
    i, j = np.meshgrid(np.arange(64), np.arange(64), indexing="ij")
    assert np.max(np.abs(b.pressure - a.pressure[(-j) % 64, i])) < 1e-9 * a.max_pressure
    aniso = bem.bisinusoid(1.0, 0.4, aspect=0.5)
    p = bem.solve_surface(load=0.2, speed=1.0, surface=aniso, direction=30, nodes=64)
    m = bem.solve_surface(load=0.2, speed=1.0, surface=aniso, direction=-30, nodes=64)
    assert p.mu == pytest.approx(m.mu, rel=1e-10)
    assert p.mu_lateral == pytest.approx(-m.mu_lateral, rel=1e-8)
    assert abs(p.mu_lateral) > 1e-3 * p.mu  # oblique on an anisotropic surface: not zero


def test_energy_identity_converges():
    """The friction from the pressure spectrum (what the modes dissipate) and the direct form
    −mean(σ ∂z/∂e) (the surface's slope under the pressure) agree to the discretisation error:
    their mismatch falls faster than 1/N^2 (measured 2.0e-3, 2.8e-4, 2.4e-5 on 32, 64, 128
    panels a side: orders 2.8 and 3.5)."""
    mis = [bem.solve_surface(load=0.3, speed=1.0, nodes=n).residuals["friction_mismatch"]
           for n in (32, 64, 128)]
    orders = [math.log2(mis[i] / mis[i + 1]) for i in range(2)]
    assert min(orders) > 2.0, (mis, orders)


def test_dimensionless_groups_scale_exactly():
    """A modulus c times smaller (compliances times c) under a load c times smaller, and times
    c times longer at a speed c times smaller, give the same contact and friction."""
    surf = bem.bisinusoid(0.5)
    base = bem.solve_surface(load=0.2, speed=1.0, surface=surf, nodes=64)
    c = 7.0
    soft = bem.Prony(c * SLS3.J0, tuple(c * j for j in SLS3.J), SLS3.tau)
    slow = bem.Prony(SLS3.J0, SLS3.J, tuple(c * t for t in SLS3.tau))
    for r in (bem.solve_surface(load=0.2 / c, speed=1.0, surface=surf, material=soft, nodes=64),
              bem.solve_surface(load=0.2, speed=1.0 / c, surface=surf, material=slow, nodes=64)):
        assert r.mu == pytest.approx(base.mu, rel=1e-9)
        assert r.penetration == pytest.approx(base.penetration, rel=1e-9)
        assert r.contact_fraction == pytest.approx(base.contact_fraction, rel=1e-9)


def test_hertz_at_vanishing_load():
    """At light load each crest of the bi-sinusoid is a Hertz contact of a sphere of radius
    R = 1/(h k^2) on the relaxed half-space: a = (3 P R/(4 E*))^(1/3) with P the load per cell
    (over Lx: P/E* = p~).  Measured contact fraction over pi a^2: 1.0078 at p~ = 1e-3 and
    1.0021 at 1e-4 (512 panels a side, the Hertz radius 25 and 12 panels): the departure
    falls with the load, like the periodic images' share (a/Lx)^2."""
    hk = 1.0
    radius = 1.0 / (hk * 2 * math.pi)  # over Lx
    ratios = []
    for load in (1e-3, 1e-4):
        r = bem.solve_surface(load=load, speed=0.0, surface=bem.bisinusoid(hk), nodes=512,
                              material=bem.Prony(1.0))
        a = (3 * load * radius / 4) ** (1 / 3)
        ratios.append(r.contact_fraction / (math.pi * a * a))
    assert abs(ratios[1] - 1) < abs(ratios[0] - 1) < 0.01, ratios


def test_thick_layer_is_the_half_space():
    surf = bem.bisinusoid(1.0)
    half = bem.solve_surface(load=0.3, speed=1.0, surface=surf, nodes=32)
    thick = bem.solve_surface(load=0.3, speed=1.0, surface=surf, nodes=32,
                              layer=bem.Layer(thickness=30.0, foundation="bonded", nu=0.5))
    assert thick.mu == half.mu and thick.contact_fraction == half.contact_fraction
    thin = bem.solve_surface(load=0.3, speed=1.0, surface=surf, nodes=32,
                             layer=bem.Layer(thickness=3.0, foundation="bonded", nu=0.5))
    assert thin.success and thin.contact_fraction < half.contact_fraction
    assert "layer" in thin.diagnostics


# --------------------------------------------------------------------------------------------
# The result protocol and bad input
# --------------------------------------------------------------------------------------------
def test_result_protocol_and_fields(tmp_path):
    r = bem.solve_surface(load=0.3, speed=1.0, nodes=32)
    d = r.as_dict()
    for k in ("mu", "mu_lateral", "contact_fraction", "penetration", "n_patches",
              "max_pressure", "error_estimate", "nodes", "success", "message"):
        assert k in d
    f = r.fields()
    path = f.save(tmp_path / "f.npz")
    data = np.load(path)
    assert data["pressure"].shape == (32, 32) and data["x"][0] == -0.5
    assert float(data["load"]) == 0.3
    assert np.mean(data["pressure"]) == pytest.approx(0.3, rel=1e-12)
    assert np.min(data["gap"]) >= 0.0
    assert abs(np.mean(data["displacement"])) < ROUNDOFF


@pytest.mark.parametrize("kwargs, name", [
    (dict(surface=bem.bisinusoid(1.0), hk=1.0), "hk"),
    (dict(direction=float("nan")), "direction"),
    (dict(nodes=2), "nodes"),
    (dict(nodes=2 ** 17), "nodes"),
    (dict(surface="bisinusoid"), "surface"),
    (dict(rtol=0.5), "rtol"),
])
def test_bad_input_is_refused_by_name(kwargs, name):
    with pytest.raises(ValueError, match=rf"^{name}="):
        bem.solve_surface(load=0.3, speed=1.0, **kwargs)


def test_bad_surfaces_are_refused(tmp_path):
    with pytest.raises(ValueError, match="non-finite height"):
        bem.sampled_surface(np.array([[1.0, np.nan, 0, 0]] * 4))
    with pytest.raises(ValueError, match="relief"):
        bem.sampled_surface(np.ones((8, 8)))
    p = tmp_path / "ragged.txt"
    p.write_text("1 2 3 4\n1 2 3\n1 2 3 4\n1 2 3 4\n")
    with pytest.raises(ValueError, match="rectangular"):
        bem.read_surface(p)
    p = tmp_path / "cut.txt"
    x = np.linspace(0, 1, 16)
    np.savetxt(p, np.add.outer(x, 0 * x))  # a ramp: its edges jump by the whole relief
    with pytest.raises(ValueError, match="periodic"):
        bem.read_surface(p)
    p = tmp_path / "ok.txt"
    z = bem.bisinusoid(1.0).sample(16, 16)
    np.savetxt(p, z)
    assert np.max(np.abs(bem.read_surface(p).sample(16, 16) - z)) < 1e-12


def test_the_readme_surface_example_prints_what_it_says():
    """The README's surface example, run as written, prints the line it promises (its digits
    come from the code, not from a past run)."""
    import re
    from pathlib import Path
    text = (Path(__file__).resolve().parents[2] / "README.md").read_text(encoding="utf-8")
    block = next(b for b in re.findall(r"```python\n(.*?)```", text, re.S)
                 if "solve_surface" in b)
    code, promised = block.split("# ", 1)
    namespace = {"bem": bem}
    import contextlib
    import io
    out = io.StringIO()
    with contextlib.redirect_stdout(out):
        exec(code, namespace)
    assert out.getvalue().strip() == promised.strip()


def test_a_grid_too_coarse_for_the_contact_gives_no_answer():
    """A light load on a coarse fixed grid: the contact is a panel or two, whose area and
    friction are the grid's: not a success, and the message says why and what to do."""
    r = bem.solve_surface(load=1e-4, speed=1.0, nodes=32)
    assert not r.success and "too coarse for the contact" in r.message
    assert "32 x 32" in r.message


def test_an_isotropic_spectrum_gives_the_same_friction_in_every_direction():
    """Isotropy is a property of the ensemble: over eight seeded self-affine surfaces of one
    isotropic spectrum the mean mu is the same at 0, 22.5, 45 and 67.5 degrees (measured within
    0.55 %), while a single realisation's mu depends on the direction by up to 17 %."""
    dirs = (0.0, 22.5, 45.0, 67.5)
    mu = np.array([[bem.solve_surface(load=0.05, speed=1.0, direction=theta, nodes=64,
                                      surface=bem.self_affine(hurst=0.8, rolloff=2,
                                                              short_cutoff=8, rms_slope=0.2,
                                                              seed=seed)).mu
                    for theta in dirs] for seed in range(8)])
    means = mu.mean(axis=0)
    spread = means.max() / means.min() - 1.0
    assert spread < 0.01, means
    single = np.max(mu.max(axis=1) / mu.min(axis=1) - 1.0)
    assert single > 2 * spread, (single, spread)


def test_contact_fraction_estimate_is_relative_and_the_target_absolute():
    """The surface BEM's estimate of the contact fraction is relative (docs/conventions.md), as
    Δ/h_ref's and μ's; the adaptive target stays on its absolute error (docs/surfaces.md §3.9)."""
    from bem import _surface_solver as S
    base = dict(penetration=0.5, tau_f=0.1, mu=0.2, max_pressure=1.0, mu_lateral=0.0)
    # fine to coarse, converging at first order to 0.05: 0.05 + 1e-3 * 32/n
    run = [dict(base, contact_fraction=0.05 + 1e-3 * 32 / n) for n in (128, 64, 32)]
    est, reason = S._estimate(run)
    assert reason is None
    bound = 1.5 * 0.375e-3  # 1.5 x the largest of the three differences
    assert est["contact_fraction"] == pytest.approx(bound / run[0]["contact_fraction"],
                                                    rel=1e-12)
    frac = run[0]["contact_fraction"]
    assert S._met(est, 1.01 * bound, frac) and not S._met(est, 0.99 * bound, frac)
