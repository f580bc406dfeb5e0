"""Scalars and contact patches from fields over one period (documented, deterministic).

On the user's grid x_j (spacing 1/M), every mean the grid's own quadrature
(`viscosine.Fields.mean`: the plain mean on a uniform grid, Σ width_j f_j on a non-uniform one):

- load p̃∞ = mean σ_j (rectangle rule, exact for a trigonometric polynomial);
- τ̃f = −(1/2π) mean σ_j (ky)′(x_j): eq. (3.1), τf = −(1/λ)∫σ ∂v/∂x dx, with ∂v/∂x = ∂y/∂x on
  the contact (the only place where σ ≠ 0) and the profile's exact slope; μ = τ̃f/p̃∞;
- s/h = mean gap_j when the gap is given, else the mean over the contact points of
  y/h − v_j (in contact gap = v − y + s = 0); Δ/h = 1 − s/h;
- contact points: σ_j > 1e-9 max σ; patches are the cyclic runs of contact points;
- each edge (`edge_offset`, verify's own fit): σ² at the contact points and, when the gap is
  given, gap^(2/3) at the free points are analytic with a simple zero at the edge (σ ∝ d^½ and
  gap ∝ d^(3/2)); each side is fitted by a cubic plus a discretisation tail b h/d over the points
  ~√M/16 … ~√M/4 from the edge and again over ~√M/16 … ~√M/2 (a side cut short by the next
  edge: over the first half of its points, then all of them; too short for that, it has no
  such fit).  The sides whose zero moves by at most 2e-3 h between the two windows give the
  edge, their first zeros averaged (viscosine's BEM places its own edges so: its fields give
  back its edges).  Without such a side, the zeros of plain cubics over ~√M/16 … ~√M/2 are
  averaged over the sides whose two zeros agree to 0.1 h (a side that moves more has another
  scale next to the edge, such as a relaxation layer, which bends a plain fit by up to half a
  spacing), else over every side (fewer points on short sides; with no zero at all, σ²
  extrapolated linearly from the last two contact points).  On a non-uniform grid the fit runs
  on the cells of the edge's own width (1/M read as that width), up to the first cell of
  another width;
- per patch: ka = π·width, ke = 2π(centre − summit), kê = 2π(centroid − summit) with the centroid
  Σw_jσ_j x_j/Σw_jσ_j over the patch (w_j the cell widths) and the summit the highest profile
  point inside it (the crest 0 for the sinusoid); with several patches the top-level ka, ke, kê
  are not defined;
- full contact (every point in contact): ka = π, ke undefined, kê the phase by which the pressure
  leads the profile in the profile's dominant mode n: arg(ŷ_n/σ̂_n)/n.

References
----------
Menga, Putignano, Carbone & Demelio, Proc. R. Soc. A 470, 20140392, 2014 (eq. 3.1 for the
friction).
"""
from __future__ import annotations

import math

import numpy as np

from ..fields import as_grid, true_runs, wrap
from ._edges import edge_offset

CONTACT = 1e-9          # contact points: σ > CONTACT · max σ


def scalars_from_fields(fields, shape):
    """Scalars and contact patches computed from fields over one period.

    Parameters
    ----------
    fields : dict
        ``x_over_lambda``, ``pressure`` and optionally ``displacement``, ``gap`` (conventions
        units; x uniform over one period, increasing) and ``width`` (the cells of a non-uniform
        grid; see `comparisons.verify._inputs`).
    shape : comparisons.suite_inputs.ProfileShape
        The indenter (k·y and its slope anywhere).

    Returns
    -------
    (dict, list of dict)
        The scalars (keys of COMPARED_KEYS plus ``full_contact``; a key is absent when the fields
        cannot give it) and the patches (``trailing_edge``, ``leading_edge``, ``load``,
        ``centroid``, ``summit``, ``ka``, ``ke``, ``ke_hat``).  The method is in the module
        docstring.
    """
    grid = as_grid(fields)
    p = grid.pressure
    pmax = float(np.max(p))
    contact = p > CONTACT * pmax if pmax > 0.0 else np.zeros(p.size, bool)
    out = _means(grid, fields, contact, shape)
    full = bool(contact.all())
    out["full_contact"] = full
    if full:
        out.update(ka=math.pi, contact_fraction=1.0, ke_hat=_phase(grid, shape))
        return out, []
    runs = true_runs(contact)
    patches = [_patch(grid, fields.get("gap"), runs, i, shape) for i in range(len(runs))]
    patches.sort(key=lambda r: wrap(0.5 * (r["trailing_edge"] + r["leading_edge"])))
    out["contact_fraction"] = float(sum(r["leading_edge"] - r["trailing_edge"] for r in patches))
    if len(patches) == 1:
        out.update(ka=patches[0]["ka"], ke=patches[0]["ke"], ke_hat=patches[0]["ke_hat"])
    return out, patches


def _means(grid, fields, contact, shape):
    """The load, τ̃f (eq. 3.1) and μ and, from the gap or else from v on the contact, s/h and
    Δ/h."""
    x = grid.x_over_lambda
    p = grid.pressure
    v = fields.get("displacement")
    out = {}
    load = grid.mean("pressure")
    out["load"] = load
    tau = -grid.mean(p * shape(x, 1)) / (2.0 * math.pi)
    out["tau_f"] = tau
    if load != 0.0:
        out["mu"] = tau / load
    hk = shape.amplitude
    if fields.get("gap") is not None:
        sep = grid.mean("gap")
    elif v is not None and contact.any():
        rest = (shape(x) / hk - np.asarray(v, float))[contact]
        w_cells = grid.widths
        sep = (float(np.mean(rest)) if grid.uniform else  # the mean over the contact's own cells
               float(np.sum(w_cells[contact] * rest) / np.sum(w_cells[contact])))
    else:
        sep = None
    if sep is not None:
        out["separation"] = sep
        out["penetration"] = 1.0 - sep
    return out


def _phase(grid, shape):
    """kê in full contact: the phase by which the pressure leads the profile in the profile's
    dominant mode n, arg(ŷ_n/σ̂_n)/n."""
    x = grid.x_over_lambda
    p = grid.pressure
    if grid.uniform:
        yh = np.fft.rfft(shape(x))
        sh = np.fft.rfft(p)
        n = int(np.argmax(np.abs(yh[1:]))) + 1
        return float(np.angle(yh[n] / sh[n])) / n
    # the dominant mode of the profile, then both coefficients by the grid's quadrature
    w_cells = grid.widths
    n = int(np.argmax(np.abs(np.fft.rfft(shape(np.arange(4096) / 4096 - 0.5))[1:]))) + 1
    phase = np.exp(-2j * math.pi * n * x)
    yn = np.sum(w_cells * shape(x) * phase)
    sn = np.sum(w_cells * p * phase)
    return float(np.angle(yn / sn)) / n


def _patch(grid, gap, runs, i, shape):
    """The patch of the i-th run of contact points (``runs``: `true_runs`): its edges, load,
    centroid and summit, ka, ke and kê, unwrapped so that its centre is within ½ of the summit."""
    x = grid.x_over_lambda
    p = grid.pressure
    m = x.size
    h = 1.0 / m
    widths = None if grid.uniform else grid.widths
    first, length = runs[i]
    nxt = runs[(i + 1) % len(runs)][0]
    prv_first, prv_len = runs[i - 1]
    free_after = (nxt - (first + length)) % m
    free_before = (first - (prv_first + prv_len)) % m
    if len(runs) == 1:
        free_after = free_before = m - length
    half = (length - 1) // 2 + 1
    last = first + length - 1
    lead_offset = _edge(p, gap, widths, (last - np.arange(half)) % m,
                        (last + 1 + np.arange(free_after // 2)) % m, last % m)
    trail_offset = _edge(p, gap, widths, (first + np.arange(half)) % m,
                         (first - 1 - np.arange(free_before // 2)) % m, first)
    x_first = x[first]
    ids = (first + np.arange(length)) % m
    if widths is None:
        x_last = x_first + (length - 1) * h  # unwrapped across the end of the period
        xs = x_first + h * np.arange(length)
        w = p[ids]
    else:
        xs = x_first + np.mod(x[ids] - x_first, 1.0)
        x_last = float(xs[-1])
        w = p[ids] * widths[ids] * m  # the pressures weighed by their cells (over 1/M)
    lead = x_last + lead_offset
    trail = x_first - trail_offset
    centroid = float(np.dot(w, xs) / w.sum()) if w.sum() > 0 else 0.5 * (trail + lead)
    summit = shape.summit(trail, lead)
    shift = -math.floor(0.5 * (trail + lead) - summit + 0.5)
    return {"trailing_edge": trail + shift, "leading_edge": lead + shift,
            "load": float(w.sum()) / m, "centroid": centroid + shift,
            "summit": summit, "ka": math.pi * (lead - trail),
            "ke": math.pi * (trail + lead) - 2.0 * math.pi * summit,
            "ke_hat": 2.0 * math.pi * (centroid - summit)}


def _edge(p, gap, widths, inside, outside, cell):
    """`edge_offset` of one edge: σ² at the contact points ``inside`` (from the edge inward) and
    gap^(2/3) at the free points ``outside`` (outward); on a non-uniform grid (``widths``) over
    the cells of the width of ``cell`` only."""
    m = p.size
    h = 1.0 / m
    if widths is not None:  # each edge is fitted on the cells of its own width, read as 1/M
        h = float(widths[cell])
        m = int(round(1.0 / h))
        inside, outside = (_same_width(k, widths, h) for k in (inside, outside))
    outside_23 = (np.abs(np.asarray(gap, float))[outside] ** (2.0 / 3.0) if gap is not None
                  else np.zeros(0))
    return edge_offset(p[inside] ** 2, outside_23, h, m)


def _same_width(idx, w, h):
    """The leading indices of ``idx`` whose cells have the width h (the edge fit's spacing)."""
    same = np.abs(w[idx] - h) <= 1e-9 * h
    return idx if same.all() else idx[:int(np.argmin(same))]
