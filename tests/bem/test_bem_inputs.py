"""Bad input is a ValueError naming the parameter, its value and what is allowed;
the file formats of bem.read_profile and bem.read_prony."""
from __future__ import annotations

import numpy as np
import pytest

import bem

SLS = bem.Prony.standard_linear_solid(3.0)
SIN = bem.Sinusoid(1.0)


def _solve(**kw):
    args = dict(profile=SIN, material=SLS, speed=1.0, nodes=64, load=0.3)
    args.update(kw)
    return bem.solve(**args)


@pytest.mark.parametrize("kw,pattern", [
    (dict(nodes=7), r"nodes=7 .*integer .*\[8, "),
    (dict(nodes=64.0), r"nodes=64\.0 .*integer"),
    (dict(nodes=True), r"nodes=True .*integer"),
    (dict(nodes="64"), r"nodes='64' .*integer"),
    (dict(speed=-1.0), r"speed=-1\.0 .*equal to 0 .*or in \[1e-30"),
    (dict(speed=float("nan")), r"speed=nan .*finite"),
    (dict(speed=float("inf")), r"speed=inf .*finite"),
    (dict(load=0.0), r"load=0\.0 .*p̃∞/\(hk\) in \[1e-08"),
    (dict(load=-0.2), r"load=-0\.2 .*p̃∞/\(hk\) in \[1e-08"),
    (dict(load=float("nan")), r"load=nan .*finite"),
    (dict(load=None, penetration=0.0), r"penetration=0\.0 .*Δ/h in \[1e-07, 1\]"),
    (dict(load=None, penetration=1.5), r"penetration=1\.5 .*Δ/h in \[1e-07, 1\]"),
    (dict(load=None, penetration=float("nan")), r"penetration=nan"),
    (dict(load=0.3, penetration=0.5), r"exactly one of load and penetration"),
    (dict(load=None), r"exactly one of load and penetration"),
    (dict(tol=0.0), r"tol=0\.0"),
    (dict(material="sls"), r"material='sls' .*Prony"),
    (dict(profile=np.ones(8)), r"profile=.*Sinusoid"),
])
def test_solve_bad_input(kw, pattern):
    with pytest.raises(ValueError, match=pattern):
        _solve(**kw)


@pytest.mark.parametrize("make,pattern", [
    (lambda: bem.Prony(1.0, (-0.1,), (1.0,)), r"J=\(-0\.1,\) .*J_i >= 0"),
    (lambda: bem.Prony(1.0, (0.5,), (0.0,)), r"tau=\(0\.0,\) .*tau_i > 0"),
    (lambda: bem.Prony(1.0, (0.5,), (-2.0,)), r"tau=\(-2\.0,\)"),
    (lambda: bem.Prony(1.0, (1.0,), (1.0,)), r"J0=1\.0 .*J\(0\+\)"),
    (lambda: bem.Prony(0.5, (0.3, 0.4), (1.0, 2.0)), r"J0=0\.5 .*J\(0\+\)"),
    (lambda: bem.Prony(float("nan")), r"J0=nan .*finite"),
    (lambda: bem.Prony(1.0, (float("inf"),), (1.0,)), r"J=\(inf,\)"),
    (lambda: bem.Prony(1.0, (0.1, 0.2), (1.0,)), r"J=\(0\.1, 0\.2\) .*one amplitude per"),
    (lambda: bem.Prony.standard_linear_solid(0.5), r"ratio=0\.5 .*>= 1"),
    (lambda: bem.Prony.standard_linear_solid(float("nan")), r"ratio=nan"),
    (lambda: bem.Sinusoid(0.0), r"hk=0\.0 .*hk > 0"),
    (lambda: bem.Sinusoid(float("inf")), r"hk=inf"),
    (lambda: bem.Harmonics([1.0, float("nan")], [0.0, 0.0]), r"amplitudes=.*finite"),
    (lambda: bem.Harmonics([0.0, 0.0], [0.0, 0.0]), r"amplitudes=.*not all zero"),
    (lambda: bem.Harmonics([1.0, 0.5], [0.0]), r"phases=\[0\.0\] .*2 finite phases"),
    (lambda: bem.SampledProfile(np.ones(7)), r"heights=.*7 samples.*at least 8"),
    (lambda: bem.SampledProfile(np.ones(16)), r"heights=.*constant.*not flat"),
    (lambda: bem.SampledProfile(np.r_[np.arange(15.0), np.nan]), r"heights=.*non-finite"),
    (lambda: bem.SampledProfile(np.ones((4, 4))), r"heights=.*shape \(4, 4\).*one-dimensional"),
])
def test_material_and_profile_bad_input(make, pattern):
    with pytest.raises(ValueError, match=pattern):
        make()


def test_read_profile_formats(tmp_path):
    m = 32
    x = np.arange(m) / m - 0.5
    ky = np.cos(2 * np.pi * x) + 0.2 * np.cos(6 * np.pi * x)
    one = tmp_path / "one.txt"
    one.write_text("# k*y over one period\nky\n" + "\n".join(f"{float(v)!r}" for v in ky) + "\n")
    two = tmp_path / "two.csv"
    two.write_text("x_over_lambda,ky\n" + "\n".join(f"{float(a)!r},{float(b)!r}  # c" for a, b in zip(x, ky)))
    for path in (one, two):
        prof = bem.read_profile(path)
        assert np.array_equal(prof.heights, ky) and np.allclose(prof.sample(m), ky - ky.mean())
    shifted = tmp_path / "shifted.csv"
    shifted.write_text("\n".join(f"{float(a) + 0.01!r},{float(b)!r}" for a, b in zip(x, ky)))
    with pytest.raises(ValueError, match=r"profile=.*shifted\.csv.*x_over_lambda = j/M - 1/2"):
        bem.read_profile(shifted)
    closed = tmp_path / "closed.csv"
    xc = np.linspace(-0.5, 0.5, m + 1)
    closed.write_text("\n".join(f"{float(a)!r},{float(b)!r}" for a, b in zip(xc, np.cos(2 * np.pi * xc))))
    with pytest.raises(ValueError, match=r"profile=.*exactly one period"):
        bem.read_profile(closed)
    bad = tmp_path / "bad.txt"
    bad.write_text("1 2 3\n" * 10)
    with pytest.raises(ValueError, match=r"profile=.*one column"):
        bem.read_profile(bad)
    short = tmp_path / "short.txt"
    short.write_text("1\n2\n3\n")
    with pytest.raises(ValueError, match=r"heights=.*3 samples"):
        bem.read_profile(short)


def test_read_prony_formats(tmp_path):
    good = tmp_path / "sls.txt"
    good.write_text("# standard linear solid, ratio 3\nJ0 1.0\n0.6666666666666666, 1.0  # J_1 tau_1\n")
    mat = bem.read_prony(good)
    assert mat == bem.Prony(1.0, (0.6666666666666666,), (1.0,))
    elastic = tmp_path / "elastic.txt"
    elastic.write_text("J0 2.0\n")
    assert bem.read_prony(elastic) == bem.Prony(2.0)
    nohead = tmp_path / "nohead.txt"
    nohead.write_text("0.5 1.0\n")
    with pytest.raises(ValueError, match=r"prony=.*nohead\.txt.*J0"):
        bem.read_prony(nohead)
    three = tmp_path / "three.txt"
    three.write_text("J0 1\n0.5 1.0 2.0\n")
    with pytest.raises(ValueError, match=r"prony=.*two numbers"):
        bem.read_prony(three)
    negative = tmp_path / "negative.txt"
    negative.write_text("J0 1\n0.5 -1.0\n")
    with pytest.raises(ValueError, match=r"tau=\(-1\.0,\)"):
        bem.read_prony(negative)


def test_result_is_frozen_and_reports_its_inputs():
    r = _solve(nodes=256)
    with pytest.raises(AttributeError):
        r.ka = 0.0
    with pytest.raises(ValueError):
        r.pressure[0] = 1.0
    with pytest.raises(TypeError):
        r.residuals["krylov"] = 0.0
    assert r.nodes == 256 and r.speed == 1.0 and r.material == SLS and r.profile == SIN
    assert set(r.scalars()) == {"full_contact", "contact_fraction", "ka", "ke", "ke_hat",
                                "penetration", "tau_f", "mu"}
    assert r.x_over_lambda[0] == -0.5 and r.x_over_lambda[128] == 0.0
