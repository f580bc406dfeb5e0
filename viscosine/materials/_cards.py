"""Prony series as finite-element programs and other tools write them (read and write).

Every card here is a relaxation (generalised Maxwell) series written with normalised weights and
the instantaneous (glassy) modulus M0:

    M(t) = M0 [1 - sum_i g_i (1 - exp(-t/tau_i))],   g_i >= 0, sum_i g_i < 1

(M = E or the shear modulus G).  `read_card` turns it into a tensile `Maxwell`: E_i = E0 g_i and
E_r = E0 (1 - sum g_i) (the sum exact, `math.fsum`), with E0 = 2 (1 + nu) G0 for a shear card.
Using the shear weights for E(t) assumes a Poisson ratio that does not relax (the bulk modulus
relaxing alike): the half-space solution depends on E/(1 - nu^2) only, so nu is that of the
card's elastic constants.  The relaxed modulus keeps about 16 - log10(E0/E_r) digits (it is a
difference): a card of glassy/relaxed 1e7 fixes E_r to about 1e-9.

Forms read (docs/materials.md shows one example of each):

* ``ansys``: APDL ``TB,PRONY`` (``TB,PRON``) with ``TBOPT`` SHEAR (or BULK, ignored), ``TBDATA``
  lines holding ``a_1, tau_1, a_2, tau_2, ...`` from the given start index; the instantaneous
  modulus from ``MP,EX`` and ``MP,PRXY`` (or ``MP,NUXY``).  ``!`` starts a comment.
* ``abaqus``: ``*ELASTIC, MODULI=INSTANTANEOUS`` (a data line ``E0, nu``) and
  ``*VISCOELASTIC, TIME=PRONY`` (data lines ``g_i, k_i, tau_i``; k_i, the bulk weights, are
  ignored).  ``**`` starts a comment.
* ``lsdyna``: ``*MAT_GENERAL_VISCOELASTIC`` (``*MAT_076``): card 1 ``MID, RO, BULK, PCF, ...``,
  card 2 ``LCID, NT, ...`` (LCID 0: the terms are given), then one card per term ``GI, BETAI,
  KI, BETAKI``: G(t) = sum_i G_i exp(-beta_i t) (a term with beta = 0 is the relaxed modulus;
  no normalised weights here); nu = (3K - 2 G0)/(2 (3K + G0)) from BULK and G0 = sum G_i.
  Fields are comma-separated or in 10-character columns; ``$`` starts a comment.
* ``pyvisco``: the Prony table pyvisco (NREL) downloads: a header ``i, tau_i, alpha_i, E_0,
  E_i`` (or ``G_0, G_i``), a row of units (``-, s, -, MPa, MPa``), then one row per term; alpha_i
  are the g_i.  A shear table needs ``nu``.
"""
from __future__ import annotations

import math
from pathlib import Path

from ..checks import bad
from ._files import _data_lines
from ._series import Maxwell
from ._units import poisson

FORMS = ("ansys", "abaqus", "lsdyna", "pyvisco")


def _text_lines(path, option, comment):
    """``(number, line)`` of the non-blank lines with ``comment`` stripped (raw text, not cut
    at '#': a card's own comment marker)."""
    where = str(path)
    try:
        data = Path(path).read_bytes()
    except OSError as exc:
        raise bad(option, where, f"a readable file ({exc.strerror or exc})") from None
    try:
        text = data.decode("utf-8").lstrip("\ufeff")
    except UnicodeDecodeError as exc:
        raise bad(option, where, f"a UTF-8 text file (byte {exc.start} is not UTF-8)") from None
    out = []
    for n, raw in enumerate(text.splitlines(), start=1):
        line = raw
        for c in comment:
            if line.lstrip().startswith(c):
                line = ""
            elif c != "$" and c in line:
                line = line.split(c, 1)[0]
        if line.strip():
            out.append((n, line.rstrip()))
    return out


def _num(tok, where, number):
    try:
        v = float(tok.strip().replace("D", "e").replace("d", "e"))
    except ValueError:
        raise bad("card", where, f"numbers (line {number}: {tok.strip()!r})") from None
    if not math.isfinite(v):
        raise bad("card", where, f"finite numbers (line {number}: {tok.strip()!r})")
    return v


def card_form(path):
    """Which of `FORMS` a file is (its keywords), or None."""
    try:
        lines = _text_lines(path, "material", ())
    except ValueError:
        return None
    return lines_form([line for _, line in lines])


def lines_form(lines):
    """Which of `FORMS` the text lines hold (their keywords), or None."""
    text = "\n".join(line.upper() for line in lines[:400])
    if "TB,PRON" in text.replace(" ", ""):
        return "ansys"
    if "*VISCOELASTIC" in text.replace(" ", ""):
        return "abaqus"
    if "*MAT_GENERAL_VISCOELASTIC" in text or "*MAT_076" in text:
        return "lsdyna"
    low = text.lower().replace(" ", "")
    if "tau_i" in low and "alpha_i" in low:
        return "pyvisco"
    return None


def _normalised(e0, g, tau, where, nu=None, shear=False):
    if shear:
        nu = poisson(nu, f"the shear moduli of the card {where!r}")
        e0 = 2.0 * (1.0 + nu) * e0
    if not e0 > 0.0:
        raise bad("card", where, f"an instantaneous modulus > 0 (got {e0!r})")
    if any(not v >= 0.0 for v in g) or any(not t > 0.0 for t in tau):
        raise bad("card", where, "weights g_i >= 0 and times tau_i > 0")
    rest = math.fsum([1.0] + [-v for v in g])
    if not rest > 0.0:
        raise bad("card", where, f"normalised weights summing below 1 (1 - sum g_i = {rest!r}: "
                  "no relaxed modulus, a fluid)")
    return Maxwell(e0 * rest, tuple(e0 * v for v in g), tuple(tau))


def read_card(path, form=None, *, nu=None) -> Maxwell:
    """A tensile relaxation series from an FE card or a pyvisco table (module docstring).

    Parameters
    ----------
    path : str or Path
    form : {"ansys", "abaqus", "lsdyna", "pyvisco"}, optional
        Default: told from the file's keywords (`card_form`).
    nu : float, optional
        Poisson ratio for a shear pyvisco table; for an LS-DYNA card (whose nu is fixed by
        BULK and G0) a check: one farther than `NU_AGREE` from the card's is refused; unused by
        ANSYS and Abaqus (they give the tensile E0).

    Returns
    -------
    Maxwell
        Moduli in the card's unit, times in its time unit.

    Raises
    ------
    ValueError
        ``card='path' is not allowed: ...`` naming the line: a missing keyword or modulus, a
        non-number, weights summing to 1 or more, a time <= 0.
    """
    where = str(path)
    form = form or card_form(path)
    if form not in FORMS:
        raise bad("card", where, "an ANSYS TB,PRONY, Abaqus *VISCOELASTIC, LS-DYNA "
                  "*MAT_GENERAL_VISCOELASTIC card or a pyvisco Prony table")
    return {"ansys": _ansys, "abaqus": _abaqus, "lsdyna": _lsdyna,
            "pyvisco": _pyvisco}[form](path, where, nu)


def _ansys(path, where, nu):
    lines = _text_lines(path, "card", ("!",))
    props, data, active = {}, {}, False
    for n, line in lines:
        f = [t.strip() for t in line.split(",")]
        key = f[0].upper()
        if key == "MP" and len(f) >= 4:
            props[f[1].upper()] = _num(f[3], where, n)
        elif key == "TB":
            active = f[1].upper().startswith("PRON")
            if active and len(f) > 5 and f[5].upper().startswith("BULK"):
                active = False                   # a bulk table: not the shear weights
        elif key == "TBDATA" and active:
            start = int(_num(f[1], where, n))
            for k, tok in enumerate(t for t in f[2:] if t):
                data[start + k] = _num(tok, where, n)
    if not data:
        raise bad("card", where, "a TB,PRONY,...,SHEAR table with TBDATA lines")
    if "EX" not in props:
        raise bad("card", where, "the instantaneous modulus MP,EX,mat,E0 (and MP,PRXY)")
    vals = [data[k] for k in sorted(data)]
    if len(vals) % 2:
        raise bad("card", where, f"pairs a_i, tau_i in TBDATA (got {len(vals)} values)")
    g, tau = vals[0::2], vals[1::2]
    # the weights are the shear modulus's; at a Poisson ratio that does not relax they are
    # E(t)'s too, with E0 = EX (MP,PRXY is then not needed)
    return _normalised(props["EX"], g, tau, where)


def _data_after(lines, keyword, where):
    """The option text of ``*keyword`` and its data lines (until the next ``*`` line)."""
    out, opts, inside = [], None, False
    for n, line in lines:
        s = line.strip()
        if s.startswith("*"):
            head = s[1:].split(",")
            inside = head[0].strip().upper().replace(" ", "") == keyword
            if inside:
                opts = ",".join(head[1:]).upper().replace(" ", "")
            continue
        if inside:
            out.append((n, [t for t in s.split(",") if t.strip()]))
    if opts is None:
        raise bad("card", where, f"a *{keyword} keyword")
    return opts, out


def _abaqus(path, where, nu):
    lines = [(n, l) for n, l in _text_lines(path, "card", ()) if not l.strip().startswith("**")]
    opts, visco = _data_after(lines, "VISCOELASTIC", where)
    if "TIME=PRONY" not in opts:
        raise bad("card", where, f"*VISCOELASTIC, TIME=PRONY (got options {opts!r})")
    eopts, elastic = _data_after(lines, "ELASTIC", where)
    if "MODULI=INSTANTANEOUS" not in eopts:
        raise bad("card", where, "*ELASTIC, MODULI=INSTANTANEOUS (long-term moduli would make "
                  "the weights relative to the relaxed modulus)")
    if not elastic:
        raise bad("card", where, "a data line 'E0, nu' after *ELASTIC")
    n0, first = elastic[0]
    e0 = _num(first[0], where, n0)
    g, tau = [], []
    for n, f in visco:
        if len(f) < 3:
            raise bad("card", where, f"'g_i, k_i, tau_i' per *VISCOELASTIC line (line {n})")
        g.append(_num(f[0], where, n))
        tau.append(_num(f[2], where, n))
    return _normalised(e0, g, tau, where)


def _fields(line):
    if "," in line:
        return [t.strip() for t in line.split(",")]
    return [line[i:i + 10].strip() for i in range(0, len(line), 10)]


#: how far a given nu may lie from the one an LS-DYNA card implies (BULK and G0) and still be
#: taken as the same (a ν typed to three decimals): beyond it the input contradicts itself
NU_AGREE = 1e-3


def _lsdyna(path, where, nu):
    bulk, g0, gi, beta, nu0 = _lsdyna_terms(path, where)
    if nu is not None and not abs(poisson(nu, f"the shear moduli of the card {where!r}")
                                  - nu0) <= NU_AGREE:
        raise bad("nu", nu, f"the LS-DYNA card's own nu = {nu0:.6g} (from BULK = {bulk:.6g} and "
                  f"G0 = sum G_i = {g0:.6g}) within {NU_AGREE:g}, or None: the card fixes it")
    factor = 2.0 * (1.0 + nu0)
    relaxed = math.fsum(g for g, b in zip(gi, beta) if b == 0.0)
    if not relaxed > 0.0:
        raise bad("card", where, "a term with BETAI = 0 (the relaxed modulus; without it the "
                  "material is a fluid)")
    terms = [(g * factor, 1.0 / b) for g, b in zip(gi, beta) if b > 0.0]
    return Maxwell(relaxed * factor, tuple(t[0] for t in terms), tuple(t[1] for t in terms))


def card_nu(path, form=None, *, nu=None):
    """The Poisson ratio that turned a shear card's moduli into tensile ones: LS-DYNA's own,
    (3K - 2 G0)/(2 (3K + G0)) from BULK and G0 = sum G_i; ``nu`` for a pyvisco table of G_0,
    G_i; None for a tensile card (ANSYS and Abaqus give E0 itself)."""
    where = str(path)
    form = form or card_form(path)
    if form == "lsdyna":
        return _lsdyna_terms(path, where)[4]
    if form == "pyvisco" and _pyvisco_kind(path, where) == "G":
        return nu
    return None


def _lsdyna_terms(path, where):
    """``(BULK, G0, [G_i], [BETA_i], nu)`` of a *MAT_GENERAL_VISCOELASTIC card."""
    lines = [(n, l) for n, l in _text_lines(path, "card", ()) if not l.lstrip().startswith("$")]
    start = None
    for i, (n, line) in enumerate(lines):
        up = line.strip().upper()
        if up.startswith("*MAT_GENERAL_VISCOELASTIC") or up.startswith("*MAT_076"):
            start = i
            break
    if start is None:
        raise bad("card", where, "a *MAT_GENERAL_VISCOELASTIC (*MAT_076) keyword")
    cards = []
    for n, line in lines[start + 1:]:
        if line.lstrip().startswith("*"):
            break
        cards.append((n, _fields(line)))
    if len(cards) < 3:
        raise bad("card", where, "card 1 (MID, RO, BULK, ...), card 2 (LCID, NT, ...) and "
                  "one card 'GI, BETAI' per term")
    n1, c1 = cards[0]
    bulk = _num(c1[2], where, n1)
    n2, c2 = cards[1]
    if c2 and c2[0] and _num(c2[0], where, n2) != 0.0:
        raise bad("card", where, f"LCID = 0 (terms given on cards, line {n2}: a fit to a load "
                  "curve is LS-DYNA's own)")
    gi, beta = [], []
    for n, f in cards[2:]:
        if not f or not f[0]:
            continue
        gi.append(_num(f[0], where, n))
        beta.append(_num(f[1], where, n) if len(f) > 1 and f[1] else 0.0)
    g0 = math.fsum(gi)
    if not (g0 > 0.0 and bulk > 0.0):
        raise bad("card", where, f"BULK > 0 and G_i summing > 0 (BULK {bulk!r}, sum {g0!r})")
    nu0 = (3.0 * bulk - 2.0 * g0) / (2.0 * (3.0 * bulk + g0))
    return bulk, g0, gi, beta, nu0


def _pyvisco_kind(path, where):
    """"G" for a pyvisco table of shear moduli (G_0), else "E"."""
    for _, f in _data_lines(path, "card"):
        names = [t.strip().lower() for t in f]
        if "tau_i" in names and "alpha_i" in names:
            return "G" if "g_0" in names else "E"
    return "E"


def _pyvisco(path, where, nu):
    rows = _data_lines(path, "card")
    head = None
    for i, (n, f) in enumerate(rows):
        names = [t.strip().lower() for t in f]
        if "tau_i" in names and "alpha_i" in names:
            head, body = names, rows[i + 1:]
            break
    if head is None:
        raise bad("card", where, "a header naming tau_i and alpha_i (pyvisco's Prony table)")
    kind = "G" if "g_0" in head else "E"
    key0 = f"{kind.lower()}_0"
    if key0 not in head:
        raise bad("card", where, "a column E_0 (or G_0): the instantaneous modulus")
    it, ia, i0 = head.index("tau_i"), head.index("alpha_i"), head.index(key0)
    g, tau, e0 = [], [], None
    for n, f in body:
        try:
            vals = [float(t) for t in f]
        except ValueError:
            continue                         # the row of units
        if len(vals) < len(head):
            continue
        tau.append(vals[it])
        g.append(vals[ia])
        e0 = vals[i0]
    if e0 is None:
        raise bad("card", where, "rows of numbers under the header")
    return _normalised(e0, g, tau, where, nu=nu, shear=kind == "G")


# --------------------------------------------------------------------------
# Writers (a series written as each tool reads it)
# --------------------------------------------------------------------------
def _weights(model: Maxwell):
    e0 = model.glassy
    return e0, [e / e0 for e in model.E]


def write_card(path, model: Maxwell, form, *, nu=0.5, material_id=1, unit="MPa"):
    """Write ``model`` (tensile, moduli in ``unit``) as a card of ``form`` (`FORMS`).

    The FE cards get shear weights (the same as the tensile ones at a Poisson ratio that does
    not relax) and ``nu``; LS-DYNA gets G_i = E_i/(2 (1 + nu)), beta_i = 1/tau_i, the relaxed
    term with beta = 0, BULK = E0/(3 (1 - 2 nu)) (nu < 0.5 there).
    """
    if form not in FORMS:
        raise bad("form", form, f"one of {', '.join(FORMS)}")
    e0, g = _weights(model)
    r = repr
    lines = []
    if form == "ansys":
        lines += [f"! Prony series, instantaneous modulus {r(e0)} {unit}", f"MP,EX,{material_id},{r(e0)}",
                  f"MP,PRXY,{material_id},{r(nu)}",
                  f"TB,PRONY,{material_id},1,{len(g)},SHEAR"]
        flat = [v for gi, th in zip(g, model.theta) for v in (gi, th)]
        for k in range(0, len(flat), 6):
            lines.append(f"TBDATA,{k + 1}," + ",".join(r(v) for v in flat[k:k + 6]))
    elif form == "abaqus":
        lines += [f"** Prony series, instantaneous modulus in {unit}",
                  "*ELASTIC, MODULI=INSTANTANEOUS", f"{r(e0)}, {r(nu)}",
                  "*VISCOELASTIC, TIME=PRONY"]
        lines += [f"{r(gi)}, {r(gi)}, {r(th)}" for gi, th in zip(g, model.theta)]
    elif form == "lsdyna":
        if not nu < 0.5:
            raise bad("nu", nu, "below 0.5 for LS-DYNA (BULK = E0/(3 (1 - 2 nu)))")
        f = 2.0 * (1.0 + nu)
        bulk = e0 / (3.0 * (1.0 - 2.0 * nu))
        lines += ["$ Prony series", "*MAT_GENERAL_VISCOELASTIC",
                  f"{material_id},1.0,{r(bulk)}", "0,0"]
        lines += [f"{r(model.E_r / f)},0.0"]
        lines += [f"{r(e / f)},{r(1.0 / th)}" for e, th in zip(model.E, model.theta)]
        lines += ["*END"]
    else:
        lines += ["i,tau_i,alpha_i,E_0,E_i", f"-,s,-,{unit},{unit}"]
        lines += [f"{k + 1},{r(th)},{r(gi)},{r(e0)},{r(e0 * gi)}"
                  for k, (gi, th) in enumerate(zip(g, model.theta))]
    Path(path).write_text("\n".join(lines) + "\n", encoding="utf-8")
