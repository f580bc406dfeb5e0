"""Third codes on 2-D surfaces (comparisons.peers.surfaces): Tamaas and ContactMechanics in
elastic contact against each other, full contact and Hertz; Tamaas's viscoelastic transient
against its limits, its symmetries and the line adapter's verified 1-D run.

Tolerances are measured with Tamaas 2.9.0 and ContactMechanics 1.8.3 (each written next to its
measurement).  Runtime: about 15 s on two loaded cores.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

pytest.importorskip("tamaas", minversion="2.9")  # the test extra installs both codes
pytest.importorskip("ContactMechanics")

from comparisons.peers import surfaces  # noqa: E402
from comparisons.peers import tamaas as line  # noqa: E402

from conftest import ROUNDOFF  # noqa: E402

HK = 0.5  # the bi-sinusoid k z = hk [cos kx + cos ky]: full contact from p̃ = E* hk


def random_surface(shape, aspect, seed, modes=4):
    """A smooth periodic surface k z: a few Fourier modes (|m| ≤ modes) of random amplitude and
    phase on a grid of Ly/Lx = aspect."""
    rng = np.random.default_rng(seed)
    x, y = surfaces.grid(shape, aspect)
    z = np.zeros(shape)
    for mx in range(-modes, modes + 1):
        for my in range(0, modes + 1):
            if (mx, my) == (0, 0):
                continue
            amp = rng.normal() / (mx * mx + my * my)
            z += amp * np.cos(2 * math.pi * (mx * x[:, None] + my * y[None, :] / aspect)
                              + rng.uniform(0, 2 * math.pi))
    return 0.3 * z / np.max(np.abs(z))


# ----------------------------------------------------------------------------- elastic
@pytest.mark.parametrize("aspect, shape, modulus", [(1.0, (32, 32), "relaxed"),
                                                    (2.0, (32, 48), "glassy")])
def test_tamaas_and_contactmechanics_agree(aspect, shape, modulus):
    """The two codes on the same nodal grid solve the same discrete problem: they agree to their
    tolerance (1e-12 here; measured 3.6e-12 of the peak pressure and 3e-13 h_ref in the gap on
    the 32² case), both on the bi-sinusoid and on a rough surface on a 1 × 2 cell, glassy."""
    z = surfaces.bisinusoid(shape[0], HK) if aspect == 1.0 else random_surface(shape, aspect, 1)
    kw = dict(load=0.2, modulus=modulus, ratio=3.0, tolerance=1e-12)
    a = surfaces.tamaas_elastic(z, aspect, **kw)
    b = surfaces.contactmechanics_elastic(z, aspect, **kw)
    assert a["success"] and b["success"], (a["message"], b["message"])
    assert a["code"] == "tamaas" and b["code"] == "contactmechanics"
    assert 0.05 < a["contact_fraction"] < 0.95  # partial contact: the constraint is active
    for r in (a, b):
        assert r["fields"]["pressure"].shape == shape
        assert abs(r["load"] / 0.2 - 1.0) < 1e-10
        assert r["complementarity"] < 1e-9
        assert np.all(r["fields"]["pressure"] >= 0.0) and np.all(r["fields"]["gap"] >= 0.0)
        assert isinstance(r["iterations"], int) and r["iterations"] > 0
        assert r["wall_time"] > 0.0
    for key in ("pressure", "displacement", "gap"):
        scale = a["max_pressure"] if key == "pressure" else 1.0
        assert np.max(np.abs(a["fields"][key] - b["fields"][key])) <= 1e-9 * scale, key
    assert abs(a["penetration"] - b["penetration"]) <= 1e-9
    assert a["contact_fraction"] == b["contact_fraction"]
    assert a["n_patches"] == b["n_patches"]


def full_contact_pressure(z, aspect, load, modulus):
    """σ(1 − ν²)/E0 of full contact: u = z + c, and k û(q) = (2/|q|) σ̂(q)/E* mode by mode
    (q in units of k), so σ̂(q) = (|q|/2) E* k ẑ(q) for q ≠ 0 and σ̂(0) = p̃."""
    nx, ny = z.shape
    qx = np.fft.fftfreq(nx, 1.0 / nx)[:, None]
    qy = np.fft.fftfreq(ny, 1.0 / ny)[None, :] / aspect
    sigma_hat = 0.5 * modulus * np.hypot(qx, qy) * np.fft.fft2(z)
    return load + np.real(np.fft.ifft2(sigma_hat))


@pytest.mark.parametrize("solve", [surfaces.tamaas_elastic, surfaces.contactmechanics_elastic],
                         ids=["tamaas", "contactmechanics"])
def test_full_contact_is_the_closed_form(solve):
    """Full contact: σ = p̃ + (|q|/2) E* k z̃ per mode.  On the bi-sinusoid that is
    p̃ + (E*/2) hk (cos kx + cos ky), in full contact from p̃ = E* hk; with E0 (relaxed) and
    E∞ = 3 E0 (glassy); and on a rough 32 × 48 surface on a 1 × 2 cell, which fixes which
    array axis is x (|q| = (m, n Lx/Ly)).  Measured: Tamaas 9e-16, ContactMechanics 4e-12 of
    the mean pressure."""
    cases = [(surfaces.bisinusoid(32, HK), 1.0, "relaxed", 1.0, 0.8),
             (surfaces.bisinusoid(32, HK), 1.0, "glassy", 3.0, 2.0)]
    z = random_surface((32, 48), 2.0, 7)
    need = -np.min(full_contact_pressure(z, 2.0, 0.0, 1.0))
    cases.append((z, 2.0, "relaxed", 1.0, 1.2 * need))
    for z, aspect, modulus, estar, load in cases:
        r = solve(z, aspect, load=load, modulus=modulus, ratio=3.0, tolerance=1e-12)
        assert r["success"], r["message"]
        assert r["full_contact"] and r["contact_fraction"] == 1.0 and r["n_patches"] == 1
        exact = full_contact_pressure(z, aspect, load, estar)
        assert np.max(np.abs(r["fields"]["pressure"] - exact)) <= 1e-10 * load
        assert abs(r["penetration"] - 1.0) <= 1e-10
        h_ref = np.max(z) - np.mean(z)
        assert np.allclose(r["fields"]["displacement"], (z - np.mean(z)) / h_ref, rtol=0.0,
                           atol=1e-10)
        assert np.all(r["fields"]["gap"] == 0.0)


def test_small_load_is_hertz_at_each_crest():
    """At a small load each crest of the bi-sinusoid is a Hertz contact of radius
    R = 1/(h k²) in both directions: k a = (3 P k² R k/(4 E*))^(1/3) with P = p̃ (2π)² the force
    per cell, peak pressure 3P/(2πa²).

    Measured at p̃ = 0.005, hk = 0.5 (k a = 0.667, 7 to 27 nodes across the radius): the
    nodal contact area is 8.4 %, 4.5 %, 3.3 % above πa² at 64², 128², 256² (3.4 % at 512²),
    the rest being the crest's quartic term, O((k a)²) (about 0.075 (k a)² at p̃ = 0.005 and
    0.02); the peak pressure is 0.7–0.9 % below Hertz's at every grid.
    """
    load = 0.005
    force = load * (2.0 * math.pi) ** 2
    ka = (3.0 * force / (4.0 * HK)) ** (1.0 / 3.0)   # E* = 1, k R = 1/(hk)
    area = math.pi * ka * ka / (2.0 * math.pi) ** 2   # over the cell's
    peak = 3.0 * force / (2.0 * math.pi * ka * ka)
    errors = []
    for n in (64, 128, 256):
        r = surfaces.tamaas_elastic(surfaces.bisinusoid(n, HK), load=load, tolerance=1e-10)
        assert r["success"] and r["n_patches"] == 1
        p = r["fields"]["pressure"]
        assert np.unravel_index(np.argmax(p), p.shape) == (n // 2, n // 2)  # on the crest
        assert abs(r["max_pressure"] / peak - 1.0) < 0.01
        errors.append(r["contact_fraction"] / area - 1.0)
    assert errors[0] > errors[1] > errors[2] > 0.0
    assert errors[2] < 0.1 * ka * ka


def test_patches_are_counted_on_the_periodic_grid():
    """Four-connectivity, periodic in both directions."""
    c = np.zeros((8, 6), dtype=bool)
    assert surfaces.count_patches(c) == 0
    c[0, 0] = c[-1, 0] = c[0, -1] = True   # one patch across both edges
    assert surfaces.count_patches(c) == 1
    c[3, 3] = c[4, 4] = True               # diagonal neighbours are two patches
    assert surfaces.count_patches(c) == 3
    c[3, 4] = True
    assert surfaces.count_patches(c) == 2
    assert surfaces.count_patches(np.ones((8, 6), dtype=bool)) == 1
    stripes = np.zeros((8, 6), dtype=bool)
    stripes[::2, :] = True
    assert surfaces.count_patches(stripes) == 4


# ----------------------------------------------------------------------------- viscoelastic
@pytest.fixture(scope="module")
def sliding():
    """32² bi-sinusoid, hk = 0.5, p̃∞ = 0.3, V/V0 = 1, E∞/E0 = 3, steps of 4, 2, 1 cells."""
    z = surfaces.bisinusoid(32, HK)
    return z, surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0, ratio=3.0)


def test_sliding_reaches_steady_state_with_friction(sliding):
    """Steady in 3 periods at each step; μ extrapolated to dt → 0 = 0.10510 (measured; the
    steps give 0.0745, 0.0898, 0.0974: first order, observed order 0.99997, estimated error
    1.1e-7), resisting; no lateral force on the symmetric surface; constraints hold."""
    z, r = sliding
    assert r["success"], r["message"]
    assert [row["cells_per_step"] for row in r["rows"]] == [4.0, 2.0, 1.0]
    for row in r["rows"]:
        assert row["success"] and row["periods"] <= 10, row["message"]
        assert row["solver_error"] <= 1e-10 * (1.0 + 1e-6)
        assert row["complementarity"] < 1e-8
    mus = [row["mu"] for row in r["rows"]]
    assert 0.0 < mus[0] < mus[1] < mus[2] < r["mu"] < 0.2
    assert abs(r["order"]["mu"] - 1.0) < 0.05 and r["error"]["mu"] < 1e-5 * r["mu"]
    assert abs(r["mu_lateral"]) < ROUNDOFF
    assert not r["full_contact"] and r["n_patches"] == 1
    assert abs(r["load"] / 0.3 - 1.0) < 1e-9
    f = r["fields_finest"]
    assert f["pressure"].shape == (32, 32) and np.all(f["gap"] >= 0.0)
    assert np.all(f["pressure"] >= 0.0)
    assert abs(np.mean(f["displacement"])) < ROUNDOFF
    assert set(r["fields"]) >= {"x", "y", "pressure", "displacement", "gap", "load", "speed",
                                "direction"}
    assert r["steps"] == sum(row["steps"] for row in r["rows"]) == 168
    # the pressure leads the crest: its centroid along x lies ahead (toward +x) of the crest
    x = r["fields"]["x"]
    assert np.sum(f["pressure"] * x[:, None]) > 0.0


@pytest.mark.parametrize("direction", [90, 180, 270])
def test_direction_is_a_symmetry_of_the_bisinusoid(sliding, direction):
    """Sliding along +y, −x, −y is the same problem rotated or mirrored: the same μ and
    penetration, the fields transposed or mirrored (measured 1e-15; same Tamaas operations)."""
    z, _ = sliding
    ref = surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0, cells_per_step=1)
    r = surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0, cells_per_step=1,
                                             direction=direction)
    assert r["success"], r["message"]
    assert abs(r["mu"] - ref["mu"]) < ROUNDOFF and abs(r["mu_lateral"]) < ROUNDOFF
    assert abs(r["penetration"] - ref["penetration"]) < ROUNDOFF
    p, p0 = r["fields"]["pressure"], ref["fields"]["pressure"]
    mirror = (-np.arange(32)) % 32  # x → −x about the crest on node 16
    expected = {90: p0.T, 180: p0[mirror, :], 270: p0[mirror, :].T}[direction]
    assert np.max(np.abs(p - expected)) < ROUNDOFF


def test_speed_limits():
    """V/V0 = 1e-8: the relaxed elastic solution (Tamaas's elastic solver, E0), steady at once,
    μ = O(V/V0) (measured 1.3e-9; pressure 5.7e-9 of its peak off).  V/V0 = 1e8: the first
    periods are the glassy solution (E∞; 5.6e-7 off after four periods) with μ at round-off,
    but that is not the steady state in 2-D: the modes constant along V see no motion and
    relax over the creep time τ (1e7 periods here), and the run says it is not steady."""
    z = surfaces.bisinusoid(32, HK)
    slow = surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1e-8, cells_per_step=1)
    relaxed = surfaces.tamaas_elastic(z, load=0.3, modulus="relaxed", tolerance=1e-12)
    assert slow["success"] and slow["rows"][0]["periods"] == 2, slow["message"]
    assert abs(slow["mu"]) < 1e-8
    assert np.max(np.abs(slow["fields"]["pressure"] - relaxed["fields"]["pressure"])) \
        < 1e-7 * relaxed["max_pressure"]
    fast = surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1e8, cells_per_step=1,
                                                max_periods=4)
    glassy = surfaces.tamaas_elastic(z, load=0.3, modulus="glassy", ratio=3.0,
                                     tolerance=1e-12)
    assert not fast["success"] and "not steady" in fast["message"]
    assert abs(fast["mu"]) < 1e-8
    assert np.max(np.abs(fast["fields"]["pressure"] - glassy["fields"]["pressure"])) \
        < 1e-5 * glassy["max_pressure"]


def test_surface_uniform_in_y_is_the_line_adapters_run():
    """A profile uniform in y (64 × 4 nodes) is the line contact: the 2-D transient reproduces
    the line adapter's verified 1-D run on the same profile, grid and steps, including the
    sub-cell steps and the dt extrapolation (measured μ 1e-11 relative, pressure 3e-11 of its
    peak; bounded by 10× Tamaas's tolerance).  Then along y on a 4 × 64 grid of a 1 × 2 cell:
    the line of wavelength Ly, hk and V/V0 halved (measured 1e-15)."""
    n, kw = 64, dict(load=0.3, speed=1.0, ratio=3.0)
    x, y = surfaces.grid((n, 4))
    z = np.repeat(np.cos(2.0 * math.pi * x)[:, None], 4, axis=1)  # hk = 1, crest on node 32
    cells = (2, 1, 0.5)
    r = surfaces.tamaas_viscoelastic_surface(z, cells_per_step=cells, **kw)
    ref = line.dt_extrapolation(nodes=n, hk=1.0, cells_per_step=cells, **kw)
    assert r["success"] and ref.success, (r["message"], ref.message)
    assert [row["steps"] for row in r["rows"]] == [row["steps"] for row in ref.rows]
    for row, lrow in zip(r["rows"], ref.rows):
        assert abs(row["mu"] / lrow["mu"] - 1.0) < 1e-9
        assert abs(row["penetration"] - lrow["penetration"]) < 1e-9
    assert abs(r["mu"] / ref.richardson["mu"] - 1.0) < 1e-9
    assert abs(r["error"]["mu"] - ref.error["mu"]) < 1e-9 * r["mu"]
    p = r["fields"]["pressure"]
    assert np.max(np.abs(p - p[:, :1])) < ROUNDOFF  # uniform in y
    assert np.max(np.abs(p[:, 0] - ref.fields().pressure)) < 1e-9 * np.max(p)
    # along y: k_line = k/2, so hk_line = hk/2 and V/V0 (line) = V/V0/2
    aspect = 2.0
    x, y = surfaces.grid((4, n), aspect)
    z = np.repeat(np.cos(2.0 * math.pi * y / aspect)[None, :], 4, axis=0)
    r = surfaces.tamaas_viscoelastic_surface(z, aspect, direction=90, cells_per_step=1, **kw)
    ref = line.solve(load=0.3, speed=0.5, ratio=3.0, hk=0.5, nodes=n)
    assert r["success"] and ref.success
    assert abs(r["mu"] / ref.mu - 1.0) < 1e-9 and abs(r["mu_lateral"]) < ROUNDOFF
    assert np.max(np.abs(r["fields"]["pressure"][0, :] - ref.fields().pressure)) < 1e-9


@pytest.mark.parametrize("call, text", [
    (lambda z: surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0, direction=45),
     "direction=45 "),
    (lambda z: surfaces.tamaas_elastic(z[0], load=0.3), "heights="),
    (lambda z: surfaces.tamaas_elastic(z, load=0.3, modulus="soft"), "modulus='soft'"),
    (lambda z: surfaces.contactmechanics_elastic(z, load=-1.0), "load=-1.0"),
    (lambda z: surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0, ratio=1.0),
     "ratio=1.0"),
    (lambda z: surfaces.tamaas_viscoelastic_surface(z, load=0.3, speed=1.0,
                                                    cells_per_step=(1, 1)), "cells_per_step="),
    (lambda z: surfaces.tamaas_elastic(np.zeros((8, 8)), load=0.3), "heights="),
])
def test_bad_input_is_refused_before_any_work(call, text):
    with pytest.raises(ValueError, match="is not allowed") as info:
        call(surfaces.bisinusoid(8, HK))
    assert str(info.value).startswith(text)
