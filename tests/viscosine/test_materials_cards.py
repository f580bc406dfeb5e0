"""Prony cards of FE programs and tools, and E(t)/J(t) fits, against the series they came from.

Cards: a known series written as each tool writes it reads back to 1e-14 (the relaxed modulus
E0 (1 - sum g_i) to 1e-14 times glassy/relaxed, the digits a difference keeps); hand-written
cards in each tool's own layout read to the numbers on them.  Time data: E(t) and J(t) samples
of a known series (0 and 1 % scatter, seeded) fitted and judged against the truth.
"""
import numpy as np
import pytest

from viscosine.materials._cards import FORMS, card_form, read_card, write_card
from viscosine.materials._synthetic import lognormal_series, time_rows
from viscosine.materials._timedata import fit_time_data, read_time_data

KNOWN = lognormal_series(3.0, 10.0, centre=-2.0, decades=8.0, per_decade=1.0)


@pytest.mark.parametrize("form", FORMS)
def test_card_round_trip(tmp_path, form):
    path = tmp_path / f"card.{form}"
    write_card(path, KNOWN, form, nu=0.49)
    assert card_form(path) == form
    back = read_card(path)
    ratio = KNOWN.glassy / KNOWN.E_r
    assert back.E_r == pytest.approx(KNOWN.E_r, rel=1e-14 * ratio)
    assert np.allclose(back.E, KNOWN.E, rtol=1e-14, atol=0)
    assert np.allclose(back.theta, KNOWN.theta, rtol=1e-14, atol=0)


ANSYS = """! a material from a fit, two terms
MP,EX,1,2000.0
MP,PRXY,1,0.45
TB,PRONY,1,1,2,SHEAR
TBDATA,1,0.5,0.01,0.3,1.0
TB,PRONY,1,1,1,BULK
TBDATA,1,0.9,0.05
"""
ABAQUS = """** units MPa, s
*MATERIAL, NAME=RUBBER
*ELASTIC, MODULI=INSTANTANEOUS
2000.0, 0.45
*VISCOELASTIC, TIME=PRONY
0.5, 0.0, 0.01
0.3, 0.0, 1.0
"""
LSDYNA = """$ G(t) = sum G_i exp(-beta_i t)
*MAT_GENERAL_VISCOELASTIC
$      MID        RO      BULK       PCF        EF      TREF         A         B
         1    1.1E-9    1000.0
$     LCID        NT    BSTART     TRAMP     LCIDK       NTK   BSTARTK    TRAMPK
         0
$       GI     BETAI        KI    BETAKI
     100.0     100.0
      60.0       1.0
      40.0       0.0
*END
"""
PYVISCO = """i,tau_i,alpha_i,E_0,E_i
-,s,-,MPa,MPa
1,0.01,0.5,2000.0,1000.0
2,1.0,0.3,2000.0,600.0
"""


@pytest.mark.parametrize("form,text", [("ansys", ANSYS), ("abaqus", ABAQUS),
                                       ("pyvisco", PYVISCO)])
def test_hand_written_cards(tmp_path, form, text):
    path = tmp_path / "card.txt"
    path.write_text(text, encoding="utf-8")
    m = read_card(path)
    assert card_form(path) == form
    assert m.E_r == pytest.approx(400.0, rel=1e-15)
    assert m.E == pytest.approx((1000.0, 600.0), rel=1e-15)
    assert m.theta == (0.01, 1.0)


def test_lsdyna_card(tmp_path):
    path = tmp_path / "mat76.k"
    path.write_text(LSDYNA, encoding="utf-8")
    m = read_card(path)
    g0, k = 200.0, 1000.0
    nu = (3 * k - 2 * g0) / (2 * (3 * k + g0))
    f = 2 * (1 + nu)
    assert m.E_r == pytest.approx(40.0 * f, rel=1e-15)
    assert sorted(m.theta) == [0.01, 1.0]
    assert dict(zip(m.theta, m.E)) == pytest.approx({0.01: 100.0 * f, 1.0: 60.0 * f}, rel=1e-15)


def test_card_refusals(tmp_path):
    path = tmp_path / "card.txt"
    path.write_text(ABAQUS.replace("0.3, 0.0, 1.0", "0.6, 0.0, 1.0"), encoding="utf-8")
    with pytest.raises(ValueError, match="summing below 1"):
        read_card(path)
    path.write_text(ABAQUS.replace("MODULI=INSTANTANEOUS", "MODULI=LONG TERM"), encoding="utf-8")
    with pytest.raises(ValueError, match="MODULI=INSTANTANEOUS"):
        read_card(path)
    path.write_text(PYVISCO.replace("E_0,E_i", "G_0,G_i"), encoding="utf-8")
    with pytest.raises(ValueError, match="nu=None"):
        read_card(path)
    assert read_card(path, nu=0.5).glassy == pytest.approx(6000.0)


TRUTH = lognormal_series(2.0, 300.0, centre=0.0, width=1.5, decades=6.0, per_decade=2.0)
TIMES = np.logspace(-2, 3, 41)


def _fit(tmp_path, kind, noise):
    col = "E [MPa]" if kind == "relaxation" else "J [1/MPa]"
    path = tmp_path / "time.csv"
    rows = time_rows(TRUTH, TIMES, kind=kind, noise=noise, seed=3)
    path.write_text(f"time [s],{col}\n" + "".join(f"{a!r},{b!r}\n" for a, b in rows),
                    encoding="utf-8")
    data = read_time_data(path)
    assert data.kind == kind and data.modulus_unit == "MPa"
    return fit_time_data(data)


@pytest.mark.parametrize("kind", ["relaxation", "creep"])
@pytest.mark.parametrize("noise", [0.0, 0.01])
def test_time_data_fit_against_the_truth(tmp_path, kind, noise):
    m = _fit(tmp_path, kind, noise)
    assert m.fit.window == pytest.approx((1e-3, 1e2), rel=1e-12)
    # the fit meets the data to their scatter (a few per mille without scatter: the truth's
    # times below the first sample are not in the fit)
    assert m.fit.rms <= noise * 1.2 + 3e-4
    if kind == "relaxation":
        got, true = m.relaxation(TIMES), TRUTH.relaxation(TIMES)
    else:
        c, tc = m.creep(), TRUTH.creep()
        got = c.J0 - sum(j * np.exp(-TIMES / t) for j, t in zip(c.J, c.tau))
        true = tc.J0 - sum(j * np.exp(-TIMES / t) for j, t in zip(tc.J, tc.tau))
    assert np.max(np.abs(got / true - 1)) <= 3 * noise + 5e-3
    # |E*| a decade inside the window: the modulus the contact sees
    w = np.logspace(-2, 1, 20)
    assert np.max(np.abs(abs(m.modulus(w)) / abs(TRUTH.modulus(w)) - 1)) <= 3 * noise + 2e-3


def test_time_data_refusals(tmp_path):
    path = tmp_path / "t.csv"
    path.write_text("time [s],E [MPa],J [1/MPa]\n1,2,0.5\n", encoding="utf-8")
    with pytest.raises(ValueError, match="one modulus"):
        read_time_data(path)
    path.write_text("time [s],E [MPa]\n" + "".join(f"{t},{10 * 2.0 ** -t}\n" for t in range(1, 9)),
                    encoding="utf-8")
    with pytest.raises(ValueError, match="relaxed modulus"):
        fit_time_data(read_time_data(path))


def test_pyvisco_tables_as_pyvisco_wrote_them():
    """The Prony tables pyvisco 2.1.3 wrote (comparisons/data/materials_peers): E_0 and
    E_i = E_0 alpha_i as on the file, E_r = E_0 (1 - sum alpha_i)."""
    from pathlib import Path
    folder = Path(__file__).resolve().parents[2] / "comparisons" / "data" / "materials_peers"
    path = folder / "user-master.pyvisco-opt.csv"
    assert card_form(path) == "pyvisco"
    m = read_card(path)
    rows = [ln.split(",") for ln in path.read_text().splitlines()
            if ln and ln[0].isdigit()]
    assert len(m.E) == len(rows) == 19
    e0 = float(rows[0][3])
    assert m.glassy == pytest.approx(e0, rel=1e-14)
    by_tau = dict(zip(m.theta, m.E))
    for r in rows:
        assert by_tau[float(r[1])] == pytest.approx(float(r[4]), rel=1e-14)
