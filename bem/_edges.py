"""Contact patches and their sub-panel edges: which panels are in contact (round-off gaps
counted as contact), the edges fitted inside their panels, the memory lags of the edges, and the
summit and the phase kê of each patch (conventions).  Measured on a solved discrete state by
`_assemble.build_result`; nothing here iterates on the contact problem.
"""
from __future__ import annotations

import math

import numpy as np

from ._inputs import Sinusoid, _direct
from ._result import Patch

_TWO_PI = 2.0 * math.pi
#: relative round-off allowed on σ ≥ 0 (over max σ), gap ≥ 0 (over h), Δ/h ≤ 1, ka ≤ π
ROUNDOFF = 1e-12


# --------------------------------------------------------------------------
# Contact patches and sub-panel edges
# --------------------------------------------------------------------------
def _runs(active: np.ndarray) -> list[tuple[int, int]]:
    """Cyclic runs of active panels as (first index, length)."""
    n = active.size
    if active.all():
        return [(0, n)]
    if not active.any():
        return []
    start = int(np.flatnonzero(~active)[0])  # rotate so that index `start` is free
    rolled = np.roll(active, -start)
    d = np.diff(np.concatenate(([0], rolled.astype(np.int8), [0])))
    firsts = np.flatnonzero(d == 1)
    lasts = np.flatnonzero(d == -1)
    return [((int(f) + start) % n, int(l - f)) for f, l in zip(firsts, lasts)]


#: a patch carrying at most this share of the load, separated from another patch by gaps
#: within the validity gate's round-off (ROUNDOFF of the heights' scale), is not a patch
#: (`counted_contact`); far below LOAD_MISMATCH, so that no checked quantity moves
SLIVER_SHARE = 1e-9


def counted_contact(sigma, gap, active, scale):
    """The active set as the patches are counted: ``active`` with its round-off slivers set
    free (a new array; ``active`` itself when there are none).

    A sliver is a run of contact panels carrying at most SLIVER_SHARE of the load next to a
    free run all of whose gaps are within the validity gate's round-off (``ROUNDOFF *
    scale``, ``scale`` the heights' scale: h k, a window's drop): the gate counts those gaps
    as zero, so the sliver and the patch beyond them are one contact to round-off.  Near
    full contact the edges of the gap sit where both the pressure and the gap are at
    round-off, and the solve leaves one- or two-panel runs there carrying 1e-12 of the load
    across gaps of 3e-13 h; counted, they change the number of patches from one grid to the
    next and withhold the estimate.  Setting them free keeps the patch's own edge fits
    (they reach √N/16 panels and more into the gap) and moves the load by at most
    SLIVER_SHARE; the result's fields are not changed.  The largest patch is never a sliver.
    """
    runs = _runs(active)
    if len(runs) < 2:
        return active
    n = active.size
    total = float(sigma[active].sum())
    allowance = ROUNDOFF * scale
    loads = [float(sigma[(f + np.arange(m)) % n].sum()) for f, m in runs]
    largest = int(np.argmax(loads))
    out = active
    for i, (first, length) in enumerate(runs):
        if i == largest or not (total > 0.0 and loads[i] <= SLIVER_SHARE * total):
            continue
        nxt_first = runs[(i + 1) % len(runs)][0]
        prv_first, prv_len = runs[i - 1]
        after = (first + length + np.arange((nxt_first - (first + length)) % n)) % n
        before = (prv_first + prv_len + np.arange((first - (prv_first + prv_len)) % n)) % n
        if any(ids.size and float(np.max(np.abs(gap[ids]))) <= allowance
               for ids in (after, before)):
            if out is active:
                out = active.copy()
            out[(first + np.arange(length)) % n] = False
    return out


#: after the gap step (just below full contact), one patch whose gap spans fewer than
#: 1/GAP_FIT_SCALE of the period has its edges fitted on windows that scale with
#: GAP_FIT_SCALE times the gap's panels instead of the period's (`fit_panels`; the other
#: grids keep the period's): windows of sqrt(N)/16 .. sqrt(N)/2 panels
#: reach across a gap of 177 panels at 2^20 (E_inf/E0 = 100, V/V0 = 24.7, 7e-8 below p_FC),
#: where the edge asymptotics do not hold (ke 2.4e-6 off there, 2e-7 at 2^19)
GAP_FIT_SCALE = 10


def fit_panels(counted):
    """The panels whose square root sizes the edge fits' windows (`edge_offset`): the
    period's, or for one patch with a narrow gap GAP_FIT_SCALE times the gap's panels."""
    n = counted.size
    runs = _runs(counted)
    if len(runs) != 1 or runs[0][1] == n:
        return n
    return min(n, GAP_FIT_SCALE * (n - runs[0][1]))


def _root_near_zero(pos, vals, deg):
    """Real root nearest 0 of the least-squares polynomial of degree deg through (pos, vals)."""
    scale = float(np.max(np.abs(pos)))
    c = np.polynomial.polynomial.polyfit(pos / scale, vals, deg)
    roots = np.polynomial.polynomial.polyroots(c)
    roots = roots[np.abs(roots.imag) < 1e-9].real * scale
    if roots.size == 0:
        return None
    return float(roots[np.argmin(np.abs(roots))])


def edge_offset(inside_sq, outside_23, h, nodes, lags=(0.0, 0.0)):
    """Offset of a contact edge beyond the centre of the last contact panel.

    inside_sq[m] = sigma^2 at the m-th contact panel counted inward from the edge
    (m = 0 is the last one, at offset -m h); outside_23[m] = gap^(2/3) at the m-th
    free panel outward (offset (m + 1) h; may be empty).  Near an edge sigma ~ d^(1/2) and
    gap ~ d^(3/2) with analytic corrections, so sigma^2 and gap^(2/3) are analytic
    with a simple zero at the edge.  The discretisation adds to them a tail that
    decays like h/d away from the edge (measured on Westergaard's solution: the
    panel pressures err by c h^(1/2) (d/h)^(-3/2), c depending on where the edge sits in
    its panel), which a plain polynomial fit mistakes for an edge shift that oscillates
    with that position.  So each side is fitted over panels at distances
    sqrt(N)/16 .. sqrt(N)/4 (growing with N, shrinking in wavelengths) by a cubic plus
    b h/d, d measured from the edge found so far (iterated from `edge_offset_plain`).  A side
    counts only if the same fit over sqrt(N)/16 .. sqrt(N)/2 finds its zero within
    EDGE_WINDOW_AGREEMENT h of it: where a relaxation layer or the recovery behind a trailing
    edge puts another scale inside the window, the model does not hold and the zero moves with
    the window (measured: 0.04 h for the gap behind the trailing edge of the standard linear
    solid at V/V0 = 0.1, N = 4096; 1e-4 h where the model holds).  A patch or gap cut short by
    the next edge is fitted over the first half of its panels and checked against all of them
    (never on two windows that hold the same panels); too short for that, it does not count.
    The zeros of the sides that count are averaged; with none, the plain fit is the answer.
    ``lags = (inside, outside)``: what each side's fit places the edge beyond the true one,
    subtracted from its zero (`edge_lags`: memory far shorter than the fitted distances).
    On Westergaard's solution the error of ka then falls smoothly (RMS 5e-9 at N = 2^16,
    observed order 1.7-1.8 over N = 2^12 .. 2^16), where the plain fit's error scatters by a
    factor of ten from one N to the next (1e-7 to 2e-7 at 2^16).
    """
    base = edge_offset_plain(inside_sq, outside_23, h, nodes, lags)
    m1 = max(1, int(round(math.sqrt(nodes) / 16.0)))
    m2 = max(m1 + TAIL_FIT_DEGREE + 4, int(round(math.sqrt(nodes) / 4.0)))
    est = []
    for vals, sign, shift, lag in ((inside_sq, -1.0, 0.0, lags[0]),
                                   (outside_23, 1.0, 1.0, lags[1])):
        # a side cut short by the next edge is checked on the windows it holds (the wide one
        # twice the narrow one), never on two windows holding the same panels
        mm = min(m2, (vals.size - 1) // 2)
        root = _tail_fit_root(vals, sign, shift, m1, mm, base, h)
        wide = _tail_fit_root(vals, sign, shift, m1, 2 * mm, base, h)
        if root is not None and wide is not None and \
                abs(root - wide) <= EDGE_WINDOW_AGREEMENT * h:
            est.append(root - lag)
    return sum(est) / len(est) if est else base


#: degree of the polynomial part of the edge fit with a discretisation tail
TAIL_FIT_DEGREE = 3
#: passes of the fixed point in d (the tail's distances from the zero found so far), stopped
#: once the zero moves by at most 1e-10 h.  It contracts by 0.1-0.3 per pass (measured on the
#: standard linear solid at V/V0 = 0.1, N = 2^14: 3 to 20 passes from a start up to 1 h off);
#: 40 allow a contraction up to 0.55, and a side that has not settled by then does not count
TAIL_FIT_PASSES = 40
#: ... a fixed point still moving after them gives its zero all the same when each of its last
#: TAIL_FIT_JITTER_PASSES passes moved it by at most TAIL_FIT_JITTER times the fit window's
#: extent: that is the rounding of the fit's zero, above 1e-10 h on fine grids (measured: a
#: zero converged to 0.2679535632 h jittering by 0.5-9e-10 h at N = 2^19, a 41-term spectrum;
#: its side was dropped by chance, and the edge fell back to the plain fit, 0.25 h off)
TAIL_FIT_JITTER = 1e-10
TAIL_FIT_JITTER_PASSES = 8
#: a side's zero may move by this many panels between the fit windows N^(1/2)/16..N^(1/2)/4 and
#: ..N^(1/2)/2 (where the model holds they agree to ~1e-4 h; where another scale sits in the
#: window they differ by 1e-2 h or more)
EDGE_WINDOW_AGREEMENT = 2e-3


def _tail_fit_root(vals, sign, shift, m1, m2, start, h):
    """Zero near `start` of the least-squares cubic + b h/|d| through vals[m] at offsets
    sign (m + shift) h, m = m1..m2 (d = offset - zero); None where too few panels are
    there, the zero leaves [-h/2, 3h/2] (the range of the edge offsets) or the fixed point
    has not settled after TAIL_FIT_PASSES passes (to 1e-10 h, or to the rounding of the fit:
    TAIL_FIT_JITTER).

    Only the tail column changes from pass to pass: the cubic's columns are factored once
    (QR), the tail column is projected off them for b, and the cubic's zero nearest the last
    one is polished by Newton's method."""
    hi = min(m2, vals.size - 1)
    if hi - m1 < TAIL_FIT_DEGREE + 4:
        return None
    m = np.arange(m1, hi + 1)
    pos = sign * (m + shift) * h
    scale = hi * h
    q, r = np.linalg.qr(np.vander(pos / scale, TAIL_FIT_DEGREE + 1, increasing=True))
    y = vals[m]
    qy = q.T @ y
    root = start
    moves = []
    for _ in range(TAIL_FIT_PASSES):
        prev = root
        # |d| >= h/2 for every panel fitted (m1 >= 1, root in [-h/2, 3h/2])
        tail = h / np.abs(pos - root)
        tq = q.T @ tail
        perp = tail - q @ tq
        b = float(perp @ y) / float(perp @ perp)
        c = np.linalg.solve(r, qy - b * tq)
        z = _cubic_zero_near(c, root / scale)
        if z is None:
            return None
        root = z * scale
        if not -0.5 * h <= root <= 1.5 * h:
            return None
        if abs(root - prev) <= 1e-10 * h:
            return root
        moves.append(abs(root - prev))
    recent = moves[-TAIL_FIT_JITTER_PASSES:]
    if len(recent) == TAIL_FIT_JITTER_PASSES and max(recent) <= TAIL_FIT_JITTER * scale:
        return root  # settled to the fit's rounding
    return None  # the fixed point did not settle: no zero to trust


def _cubic_zero_near(c, x):
    """Real zero of sum c_k x^k nearest x: Newton's method from x (the zeros a fit gives near
    an edge are simple), else the companion matrix's."""
    x0 = x
    for _ in range(30):
        f = ((c[3] * x + c[2]) * x + c[1]) * x + c[0]
        df = (3.0 * c[3] * x + 2.0 * c[2]) * x + c[1]
        if df == 0.0:
            break
        step = f / df
        x -= step
        if abs(step) <= 1e-15 * max(1.0, abs(x)):
            return float(x)
    roots = np.polynomial.polynomial.polyroots(c)
    roots = roots[np.abs(roots.imag) < 1e-9].real
    return float(roots[np.argmin(np.abs(roots - x0))]) if roots.size else None


#: a Prony term whose memory length is at most this fraction of the nearest fitted distance
#: (sqrt(N)/16 panels) counts in `edge_lags` (measured on the standard linear solid at N = 4096
#: and 16384: the fits' zeros move by whole multiples of the lag up to 0.1, not beyond 0.15)
LAG_FRACTION = 0.1


def edge_lag_reach(h, panels):
    """The longest memory length (wavelengths) that `edge_lags` counts on panels of width h."""
    return LAG_FRACTION * max(1, int(round(math.sqrt(panels) / 16.0))) * h


def edge_lags(material, speed, h, panels):
    """How far the edge fits of `edge_offset` place a contact edge beyond the true one, for the
    Prony terms whose memory length ``L_i = w tau_i/(2 pi)`` (wavelengths) is far below the
    distances fitted (LAG_FRACTION of sqrt(panels)/16 panels of width h).

    On scales much longer than ``L_i`` such a term acts as a compliance ``J_i`` applied a
    distance ``L_i`` downstream.  To first order the operator is then an elastic one with the
    compliance ``J_s = J(0+) + sum J_i`` shifted by ``delta = sum J_i L_i / J_s`` (sums over
    those terms): the gap outside a contact is the elastic one, and the pressure is the elastic
    one moved ``delta`` toward +x.  The true edges lie between: the trailing edge ``delta``
    inside the gap's, the leading edge ``delta`` inside the pressure's (their inner layers of
    width ``L_i``; for the standard linear solid at V -> 0 this is the paper's first-order
    retreat of the trailing edge, ka = ka_W - (1 - 1/rho) w/2 and ke = (1 - 1/rho) w/2).  A fit
    far outside those layers finds the outer fields' zeros: each side that carries the lag is
    corrected by ``delta``.  Returns ``delta`` (wavelengths).

    References
    ----------
    Eqs (2.4)-(2.5) of the paper (the steady-sliding kernel) and its low-speed limit (§3).
    """
    reach = edge_lag_reach(h, panels)
    j_s = material.j_plus
    moment = 0.0
    for j, t in sorted(material.terms, key=lambda jt: jt[1]):
        length = speed * t / _TWO_PI
        if length > reach:
            break
        j_s += j
        moment += j * length
    return moment / j_s if moment > 0.0 else 0.0


def edge_offset_plain(inside_sq, outside_23, h, nodes, lags=(0.0, 0.0)):
    """The edge offset of `edge_offset` from plain polynomial fits (its start).

    The panels right at the edge carry an O(1) relative discretisation error that does not
    shrink with h, so each side is fitted by a cubic over panels at distances
    sqrt(N)/16 .. sqrt(N)/2, and the two zeros are averaged (measured on Westergaard's
    solution: the error falls like N^-1.6, scattering with the edge's place in its panel).
    Short patches or gaps fall back to fewer points, and finally to extrapolating
    sigma^2 linearly from the last two contact panels.
    """
    m1 = max(1, int(round(math.sqrt(nodes) / 16.0)))
    m2 = max(m1 + 6, int(round(math.sqrt(nodes) / 2.0)))
    est = []
    for vals, sign, shift, lag in ((inside_sq, -1.0, 0.0, lags[0]),
                                   (outside_23, 1.0, 1.0, lags[1])):
        avail = vals.size
        lo, hi = m1, min(m2, avail - 1)
        if hi - lo < 5:
            lo, hi = 0, min(m2, avail - 1)
        if hi - lo < 3:
            continue
        m = np.arange(lo, hi + 1)
        deg = 3 if hi - lo >= 5 else 2
        root = _root_near_zero(sign * (m + shift) * h, vals[m], deg)
        if root is not None and -h <= root <= 2.0 * h:
            est.append(root - lag)
    if est:
        return min(max(sum(est) / len(est), -0.5 * h), 1.5 * h)
    if inside_sq.size >= 2 and inside_sq[1] > inside_sq[0]:
        return min(h, h * inside_sq[0] / (inside_sq[1] - inside_sq[0]))
    return 0.5 * h


def _patch_edges(sigma, gap, first, length, free_after, free_before, x, h, lag=0.0,
                 panels=None):
    """(trailing, leading) edges of one patch, unwrapped so that leading > trailing.  ``lag``:
    `edge_lags` (the pressure side of the leading edge and the gap side of the trailing edge
    lie that far outside the true edges); ``panels``: `fit_panels` (default the panels
    given)."""
    n = sigma.size
    last = first + length - 1
    half = (length - 1) // 2 + 1
    ins_lead = sigma[(last - np.arange(half)) % n] ** 2
    ins_trail = sigma[(first + np.arange(half)) % n] ** 2
    out_lead = np.abs(gap[(last + 1 + np.arange(max(free_after // 2, 0))) % n]) ** (2.0 / 3.0)
    out_trail = np.abs(gap[(first - 1 - np.arange(max(free_before // 2, 0))) % n]) ** (2.0 / 3.0)
    x_first = x[first]
    x_last = x_first + (length - 1) * h
    fit = n if panels is None else panels
    lead = x_last + edge_offset(ins_lead, out_lead, h, fit, (lag, 0.0))
    trail = x_first - edge_offset(ins_trail, out_trail, h, fit, (0.0, lag))
    return trail, lead


def _summit(profile, y, ids, xs, trail, lead):
    """x/λ of the summit a patch sits on: the local maximum of the profile reached by climbing
    from the highest point of the patch (unwrapped like the patch).  At high speed a contact
    moves ahead of its summit and may not contain it, so the summit is not sought inside
    [trail, lead] only.

    The sinusoid's crest nearest the patch centre is exact (X = 0 modulo 1); any other profile:
    the highest panel centre of the patch, moved uphill panel by panel (periodically) to a
    local maximum of the samples and polished by Newton's method on the trigonometric series.
    """
    if isinstance(profile, Sinusoid):
        return float(round(0.5 * (trail + lead)))
    n, c = profile._spectrum()
    size = y.size
    h = 1.0 / size

    def height(t, der=0):  # the series is in t = X + 1/2
        return float(_direct(n, c, t + 0.5, der)[0])

    j = int(np.argmax(y[ids]))
    i = int(ids[j])
    t = float(xs[j])
    for _ in range(size):  # discrete ascent over the periodic samples
        if y[(i + 1) % size] > y[i]:
            i, t = (i + 1) % size, t + h
        elif y[(i - 1) % size] > y[i]:
            i, t = (i - 1) % size, t - h
        else:
            break
    start = t
    for _ in range(40):
        d1, d2 = height(t, 1), height(t, 2)
        if d2 >= 0.0:
            break
        step = float(np.clip(-d1 / d2, -h, h))
        t = min(max(t + step, start - h), start + h)
        if abs(step) < 1e-16:
            break
    return t if height(t) >= height(start) else start


def _patches(sigma, gap, active, x, h, profile=None, y=None, window=False, lag=0.0,
             panels=None):
    """Contact patches of a partial contact (`Patch` with sub-panel edges).

    With ``profile`` (and its panel heights ``y``) each patch gets its summit and ka, ke, kê
    are measured from it; without (the solver's prolongation only needs the edges) the summit
    is the crest X = 0.  ``window``: the panels are a contact window, not a period (the free
    panels of each side end at the window's ends; a patch that reaches one is the caller's
    error).  The edge fit's panel distances scale with the square root of the panels given
    (`edge_offset`): a window's, whose patch spans a sixth to a third of them, as a period's;
    ``panels`` (`fit_panels`) stands for them where given.
    """
    out = []
    n = sigma.size
    runs = _runs(active)
    for i, (first, length) in enumerate(runs):
        nxt_first = runs[(i + 1) % len(runs)][0]
        prv_first, prv_len = runs[i - 1]
        free_after = (nxt_first - (first + length)) % n
        free_before = (first - (prv_first + prv_len)) % n
        if len(runs) == 1:
            free_after = free_before = n - length
        if window:
            if i == len(runs) - 1:
                free_after = n - first - length
            if i == 0:
                free_before = first
        trail, lead = _patch_edges(sigma, gap, first, length, free_after, free_before, x, h,
                                   lag, panels)
        shift = -math.floor(0.5 * (trail + lead) + 0.5)  # centre into [-1/2, 1/2)
        trail += shift
        lead += shift
        ids = (first + np.arange(length)) % n
        xs = x[first] + shift + h * np.arange(length)  # unwrapped centres
        if xs.mean() - 0.5 * (trail + lead) > 0.5:
            xs -= 1.0
        elif xs.mean() - 0.5 * (trail + lead) < -0.5:
            xs += 1.0
        w = sigma[ids]
        load = float(w.sum()) / round(1.0 / h)  # mean over the period (h = 1/N)
        centroid = float(np.dot(w, xs) / w.sum()) if w.sum() > 0 else 0.5 * (trail + lead)
        summit = 0.0 if profile is None else _summit(profile, y, ids, xs, trail, lead)
        width = lead - trail
        out.append(Patch(trailing_edge=trail, leading_edge=lead, width=width, load=load,
                         centroid=centroid, summit=summit, ka=math.pi * width,
                         ke=math.pi * (trail + lead) - _TWO_PI * summit,
                         ke_hat=_TWO_PI * (centroid - summit), panels=int(length)))
    return out


def _full_patch(sigma, y, profile, load):
    """The one patch of a full contact: the period, its summit (the highest profile point) and
    kê, the phase by which the pressure's dominant harmonic leads the profile's (conventions)."""
    n = y.size
    if isinstance(profile, Sinusoid):
        summit = 0.0
    else:
        ids = np.arange(n)
        summit = _summit(profile, y, ids, np.arange(n) / n - 0.5, -0.5, 0.5 - 1.0 / n)
    yh = np.fft.rfft(y)
    sh = np.fft.rfft(sigma)
    nstar = int(np.argmax(np.abs(yh[1:]))) + 1
    ke_hat = float(np.angle(yh[nstar] / sh[nstar])) / nstar
    centroid = summit + ke_hat / _TWO_PI
    centroid -= math.floor(centroid + 0.5)
    return Patch(trailing_edge=-0.5, leading_edge=0.5, width=1.0, load=load, centroid=centroid,
                 summit=summit, ka=math.pi, ke=None, ke_hat=ke_hat, panels=int(n))
