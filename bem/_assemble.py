"""Turning a solved discrete state into a `BemResult`: contact patches with sub-panel edges,
the friction, the scalars of the conventions, and the last physical-validity gate.

Units of :mod:`bem`; scalars, signs and patch keys as in ``docs/conventions.md``.  Nothing here
iterates on the contact problem: `build_result` measures what the solver found and refuses to
call it a success unless it is a physically valid answer.
"""
from __future__ import annotations

import math

import numpy as np

from viscosine import DEFAULT_RTOL

from . import _kernels
from ._edges import (_TWO_PI, ROUNDOFF, _full_patch, _patches, counted_contact, edge_lags,
                     fit_panels)
from ._inputs import Prony, Sinusoid
from ._layer import mean_displacement
from ._operator import WindowOperator
from ._result import CONVERGED, STATUS_INVALID, STATUS_TARGET, BemResult
#: mean σ = load, relative (the Krylov tolerance bounds the load equation well below this)
LOAD_MISMATCH = 1e-8
#: a contact narrower than this many panels carries an O(1) error in its edges
FEW_PANELS = 8


# --------------------------------------------------------------------------
# Friction (mean frictional stress, positive when it resists the motion)
# --------------------------------------------------------------------------
def _spectra(sigma, y):
    """(sigma_n, y_n, n, weight) for n = 0 … N/2: the pressure's point-value coefficients
    (the DFT times sinc(pi n/N), `_friction`), the profile's, and the weight of each mode in a
    sum over n > 0 (0 for n = 0, 1/2 at Nyquist)."""
    n = sigma.size
    sh = np.fft.rfft(sigma) / n
    yh = np.fft.rfft(y) / n
    modes = np.arange(sh.size, dtype=float)
    sh = sh * np.sinc(modes / n)
    weight = np.ones_like(modes)
    weight[0] = 0.0
    if n % 2 == 0:
        weight[-1] = 0.5  # Nyquist: +N/2 and -N/2 share one discrete mode
    return sh, yh, modes, weight


def _friction(sigma, y, material: Prony, speed: float, spectra=None, layer=None):
    """(dissipation estimate, direct estimate) of tau_f (1 - nu^2)/E_ref.

    tau_f = (1/lambda) int sigma dv/dx dx in the paper (eq. 3.1), negative when it
    resists; reported with the opposite sign (conventions.md).  With
    sigma = sum_n sigma_n e^{2 pi i n X} and v_n = (2/|n|) J*(n) sigma_n,
    -(1/lambda) int sigma v' dx = sum_{n>0} 4 Im J*(n) |sigma_n|^2 (the energy
    dissipated per unit sliding distance), insensitive to phase errors.
    Collocation makes the panel values exceed the point values: a mode n of
    piecewise-constant pressure displaces the collocation points by its symbol
    times sinc(pi n/N), so the solve returns sigma(X_j)/sinc mode by mode (in
    real space sigma_j = sigma - h^2 sigma''/24 + ..., the opposite of a panel
    average); hence sigma_n = DFT_n * sinc(pi n/N).  The direct estimate
    -(1/2 pi) int sigma d(ky)/dX dX = sum_{n>0} 2 n Im(conj(sigma_n) y_n) uses the
    profile instead of v (equal on the contact).  ``spectra``: `_spectra` of the same
    sigma and y, when already made.  On a ``layer`` (a `bem.Layer`) mode n dissipates
    S(|n| k d) times as much (its compliance is the half-space's times S).
    """
    sh, yh, modes, weight = _spectra(sigma, y) if spectra is None else spectra
    jim = material.jstar(modes, speed).imag
    if layer is not None:
        jim = jim * layer.factor(modes)
    diss = float(np.sum(weight * 4.0 * jim * np.abs(sh) ** 2))
    direct = float(np.sum(weight * 2.0 * modes * np.imag(np.conj(sh) * yh)))
    return diss, direct


def _lag_friction(sigma, y, material: Prony, speed: float, spectra=None):
    """(tau_f, L_eff): the friction of the first-order memory law, for memories far shorter
    than every distance that matters (the contact, the panels the edges are fitted over).

    To first order in the memory lengths ``L_i = w tau_i/(2 pi)`` the compliance is ``J_s -
    i omega sum J_i tau_i`` (``J_s = J(0+) + sum J_i``, the relaxed one): the contact is the
    elastic one of ``J_s`` with the pressure lagging the profile by ``delta = sum J_i L_i/J_s``
    (wavelengths).  In the direct form of `_friction`, ``sigma_n -> sigma_n exp(-2 pi i n
    delta)`` gives ``tau_f = 4 pi delta sum_{n>0} n^2 Re(conj(sigma_n) y_n)`` (the elastic part
    dissipates nothing), with this grid's pressure for the elastic one (the difference is second
    order).  Its pressure enters through its low modes only, which converge like N^-2, where the
    dissipation form of a memory far under a panel converges like N^-1.  The remainder is second
    order: relative to tau_f of the order of ``L_eff/a``, ``L_eff = sum J_i L_i^2/sum J_i L_i``
    and a the contact's half-width (measured on the standard linear solid against the
    semi-analytic road, E_inf/E0 = 1.5 ... 1000, p~ = 1e-3 ... 0.45, V/V0 = 1e-4 and 1e-3: at
    most 0.84 L/a, at the lightest load and softest material).  The paper's low-speed limit
    (§3), to first order for any Prony series.  ``spectra``: as for `_friction`."""
    sh, yh, modes, weight = _spectra(sigma, y) if spectra is None else spectra
    js = material.j_plus + sum(j for j, _ in material.terms)
    moment = sum(j * speed * t / _TWO_PI for j, t in material.terms)
    second = sum(j * (speed * t / _TWO_PI) ** 2 for j, t in material.terms)
    delta = moment / js
    tau = 4.0 * math.pi * delta * float(np.sum(weight * modes ** 2 * np.real(np.conj(sh) * yh)))
    return tau, (second / moment if moment > 0.0 else 0.0)


def _window_friction(sigma, grid, material: Prony, speed: float):
    """tau_f (1 - nu^2)/E_ref on a contact window, in the dissipation form.

    tau_f = -(1/2 pi) int sigma d(k v)/dX dX (eq. 3.1).  The elastic part of v adds nothing
    (its kernel is even), and a Prony term's part ``v_i = J_i M_i sigma`` has
    ``dM_i/dX = (M_i - c)/L_i`` (differentiate ``M_i(X) = (1/L_i) int_0^inf exp(-y/L_i)
    c(X + y) dy``; c the elastic panel influence, L_i the memory length in wavelengths), so
    with the midpoint rule over the panels::

        tau_f = (h/2 pi) sum_i (J_i/L_i) sigma^T (C - M_i) sigma  >= 0,

    a sum of positive dissipations, where the direct form -(1/2 pi) int sigma d(k y)/dX
    cancels between the two halves of the contact (at V/V0 = 100, p~ = 1e-8: mu is 4e-5 of
    each half).  At rest (``L_i = 0``) a term dissipates nothing.  A memory under 64 panels of
    the window's first grid (``grid.form_nodes``), which the midpoint rule does not resolve
    (and where C - M_i cancels), makes the whole the direct form
    (:func:`_window_direct_friction`).  C and M_i are the columns the window's operator was
    built from (``grid.columns``).
    """
    c_sigma = None
    total = 0.0
    for j_i, tau_i in material.terms:
        length = speed * tau_i / _TWO_PI
        if j_i == 0.0 or length == 0.0:  # no memory (at rest: relaxed), no dissipation
            continue
        if length < 64.0 / grid.form_nodes:
            # a memory under 64 panels (of the window's first grid: one form for all its
            # grids, whose differences make the estimate)
            return _window_direct_friction(sigma, grid)
        if c_sigma is None:
            c_sigma = _dot_window(grid.columns["elastic"], sigma)
        total += (j_i / length) * (c_sigma - _dot_window(grid.columns[length], sigma))
    return grid.h / _TWO_PI * total


def _window_direct_friction(sigma, grid):
    """The direct form of tau_f on a contact window, -(1/2 pi) int sigma d(k y)/dX dX, exact
    for piecewise-constant pressure: k y(X + h/2) - k y(X - h/2) = -2 h k sin(pi h) sin(2 pi X)."""
    return grid.amp * math.sin(math.pi * grid.h) / math.pi * \
        float(np.dot(sigma, np.sin(_TWO_PI * grid.x)))


def _dot_window(column, sigma):
    """sigma^T T sigma for the window Toeplitz matrix of ``column`` (offsets -n .. n)."""
    return float(np.dot(sigma, WindowOperator(column).apply(sigma)))


def _window_fields(sigma, gap, active, s, grid):
    """Fields over the period of a contact-window solve (over h; pressure as solved): the
    window's panels, on each side as many more of its grid as make two panels of its coarse
    periodic grid (no pressure there: their gaps come from the Toeplitz block of the wider
    window, exact), and beyond, the coarse grid's panels, whose displacement is that of the
    window's pressure gathered onto them (load kept; the gathering errs within two coarse
    panels of the window, which the margin covers).  Also the cell edges of that non-uniform
    grid (`viscosine.Fields`): each panel its own, but the coarse panel next to each end of the
    wider window cut or stretched to meet it (coarse edges fall between fine centres), so that
    the cells make the period and the window's panels keep their width 1/nodes."""
    cg = grid.coarse
    nc = cg.n
    x = grid.x
    j = np.rint((x + 0.5) * nc).astype(np.int64) % nc
    sc = np.bincount(j, weights=sigma, minlength=nc) * (nc / grid.nodes)
    uc = cg.op.apply(sc)
    gc = uc - cg.y + (grid.s_offset + s)
    xc = cg.x
    margin = int(math.ceil(2.0 * grid.nodes / nc)) + 1
    ext = grid.extended(margin)
    se = np.zeros(ext.n)
    se[margin:margin + grid.n] = sigma
    ue = ext.op.apply(se)
    ge = ue - ext.y + s
    ge[margin:margin + grid.n] = np.where(active, 0.0, gap)
    xe = ext.x
    left, right = xc < xe[0], xc > xe[-1]
    xs = np.concatenate((xc[left], xe, xc[right]))
    p = np.concatenate((np.zeros(int(left.sum())), se, np.zeros(int(right.sum()))))
    u = np.concatenate((uc[left], ue, uc[right])) / grid.amp
    g = np.concatenate((gc[left], ge, gc[right])) / grid.amp
    hc, hf = 1.0 / nc, 1.0 / grid.nodes
    lower = np.concatenate((xc[left] - 0.5 * hc, xe - 0.5 * hf, xc[right] - 0.5 * hc))
    if right.any():  # the first coarse cell after the window starts where the window ends
        lower[int(left.sum()) + ext.n] = xe[-1] + 0.5 * hf
    edges = np.append(lower, lower[0] + 1.0)  # the last cell closes the period
    return xs, p, u, g, edges


def _problems(sc, fields, load, asked_load, gap_roundoff=ROUNDOFF):
    """What makes a converged state not a physically valid answer (list of str, empty if valid).
    ``gap_roundoff``: the gap (over h) counted as zero, ROUNDOFF of the heights' scale (h; a
    contact window's drop)."""
    out = []
    for k, v in sc.items():
        if v is not None and not math.isfinite(v):
            out.append(f"{k} = {v!r} is not finite")
    for name, arr in fields.items():
        if not np.all(np.isfinite(arr)):
            out.append(f"the field {name} is not finite")
    if out:
        return out
    if not 0.0 < sc["penetration"] <= 1.0:
        out.append(f"penetration Δ/h = {sc['penetration']!r} is outside (0, 1]")
    if sc["ka"] is not None and not 0.0 < sc["ka"] <= math.pi:
        out.append(f"ka = {sc['ka']!r} is outside (0, π]")
    if not 0.0 < sc["contact_fraction"] <= 1.0:
        out.append(f"contact_fraction = {sc['contact_fraction']!r} is outside (0, 1] "
                   "(the patches overlap)")
    for k in ("tau_f", "mu"):
        if sc[k] < 0.0:
            out.append(f"{k} = {sc[k]!r} < 0 (friction must resist the motion)")
    p, g = fields["pressure"], fields["gap"]
    pmax = float(p.max()) if p.size else 0.0
    if not pmax > 0.0:
        out.append(f"max σ = {pmax!r}: no contact")
    elif float(p.min()) < -ROUNDOFF * pmax:
        out.append(f"negative pressure (min σ = {float(p.min()) / pmax:.3e} of max σ)")
    if float(g.min()) < -gap_roundoff:
        out.append(f"interpenetration (min gap = {float(g.min()):.3e} h)")
    if asked_load is not None and not abs(load - asked_load) <= LOAD_MISMATCH * asked_load:
        out.append(f"mean σ = {load!r} is not the load {asked_load!r} asked for")
    return out


def build_result(res, grid, profile, material, speed, amp, load, history, *, asked, control,
                 error_estimate=None, rtol=None, extra_diagnostics=None, on_layer=None,
                 memory_bound=0.0):
    """The `BemResult` of a solved grid, and the last physical-validity gate.

    Parameters
    ----------
    res : dict
        The solver's state on its finest grid: ``sigma``, ``s``, ``active``, ``gap``, ``nit``,
        ``inner``, ``relres``, ``status`` (0 converged), ``message``.
    grid
        That grid (``n``, ``h``, ``x``, ``y``, ``op``).
    profile, material, speed, amp
        The problem (amp = h k, the profile's amplitude).
    load : float or None
        The load asked for under load control (None under penetration control).
    history : sequence of (nodes, nit, inner iterations)
        The levels solved, coarse to fine.
    asked, control
        The value asked for and ``"load"`` or ``"penetration"``.
    error_estimate : mapping, optional
        The solver's estimate of the discretisation error of each scalar (absolute for ka, ke,
        kê; relative otherwise), or None.
    rtol : float, optional
        The accuracy target of an adaptive mesh (None when the mesh was fixed).
    extra_diagnostics : mapping, optional
        Anything else the solver reports (added to ``diagnostics``).
    on_layer : bem.Layer, optional
        The layer under the profile (None: the half-space): ``diagnostics["layer"]`` then describes it and gives the
        indenter's absolute approach (`_layer_diagnostics`).
    memory_bound : float
        What the memory lengths the grid does not resolve may shift μ by (relative), as the
        error estimate carries it: a pressure memory layer under a panel is a warning only
        where this exceeds the accuracy asked (``rtol``, else ``viscosine.DEFAULT_RTOL``).

    Returns
    -------
    BemResult
        ``success`` only when the solver converged and the answer is physically valid: every
        scalar finite, 0 < Δ/h ≤ 1, 0 < ka ≤ π, τf, μ ≥ 0, σ ≥ 0, gap ≥ 0 (to round-off),
        mean σ = load (relative 1e-8) and, on a layer, an approach short of the foundation
        (approach hk < k d); otherwise ``status`` 4 and a message naming what failed.
    """
    sigma = res["sigma"]
    n = grid.nodes
    mean_p = float(sigma.sum()) / n if grid.window else float(sigma.mean())
    tau_f, tau_direct = _result_friction(res, grid, material, speed)
    residuals = _residuals(res, grid, amp, load if load is not None else mean_p, mean_p, tau_f,
                           tau_direct)
    # panels across the thinnest pressure memory layer w τ_R (only reported, not a residual
    # that gates success): below one panel the edges carry an error of the order of the layer
    tau_r = material.relaxation_times
    layer = speed * min(tau_r) * n / _TWO_PI if (tau_r and speed > 0.0) else math.inf
    full, patches, frac, ka, ke, ke_hat, warnings = _contact(res, grid, profile, material,
                                                             speed, mean_p)
    penetration, separation = _penetration(grid, float(res["s"]), amp, full)
    x_out, p_out, disp, gap_out, edges = _result_fields(res, grid, amp)
    mu = tau_f / mean_p if mean_p > 0 else math.nan
    sc = {"contact_fraction": frac, "ka": ka, "ke": ke, "ke_hat": ke_hat,
          "penetration": penetration, "separation": separation, "tau_f": tau_f, "mu": mu,
          "load": mean_p}
    success, status, message = _verdict(
        res, n, residuals, sc, {"pressure": p_out, "displacement": disp, "gap": gap_out}, load,
        ROUNDOFF * (grid.scale / amp), (layer, memory_bound, rtol), full, warnings)
    ratio = getattr(material, "ratio", None)
    if on_layer is not None:
        extra_diagnostics = dict(extra_diagnostics or {})
        extra_diagnostics["layer"] = _layer_diagnostics(on_layer, material, mean_p, amp,
                                                        penetration)
        reach = _reaches_foundation(extra_diagnostics["layer"], amp)
        if reach and success:
            success, status, message = False, STATUS_INVALID, "invalid result: " + reach
    return BemResult(
        success=success, status=status, message=message, nit=int(res["nit"]),
        inner_iterations=tuple(res["inner"]), residuals=residuals, nodes=n, speed=speed,
        material=material, profile=profile, load=mean_p, full_contact=full,
        contact_fraction=frac, ka=ka, ke=ke, ke_hat=ke_hat,
        penetration=penetration, tau_f=tau_f, mu=mu,
        separation=separation, x_over_lambda=x_out, pressure=p_out, displacement=disp,
        gap=gap_out, patches=patches, levels=tuple(history), memory_layer_panels=layer,
        control=control, asked=asked, ratio=ratio,
        hk=profile.hk if isinstance(profile, Sinusoid) else None,
        warnings=tuple(warnings), error_estimate=error_estimate, rtol=rtol,
        extra_diagnostics=dict(extra_diagnostics or {}), edges=edges)


def _layer_diagnostics(layer, material, mean_p, amp, penetration):
    """The layer (`bem.Layer.describe`) with its uniform mode (``docs/layers.md``, "The
    indenter's approach"): ``mean_displacement`` the mean surface displacement over h (the
    uniform compression under the mean pressure, relaxed compliance J0) and ``approach`` the
    indenter's approach into the layer from the undeformed top face, over h: Δ/h plus it."""
    mean = mean_displacement(layer, material.J0, mean_p) / amp
    return {**layer.describe(), "mean_displacement": mean, "approach": penetration + mean}


def _reaches_foundation(described, amp):
    """Why an answer on a layer is no answer: the indenter's approach (over h) reaches the
    foundation, approach h >= d, i.e. approach hk >= k d (None when it does not).  Linear
    theory has no such limit; the body does."""
    kd = described["thickness"]
    if described["approach"] * amp >= kd:
        return (f"the indenter's approach {described['approach']:.4g} h reaches the foundation "
                f"at d = {kd / amp:.4g} h (k d = {kd:g}, hk = {amp:g})")
    return None


def _result_friction(res, grid, material, speed):
    """τf by the dissipation and by the direct form (their difference is a residual): the
    solver's, when it measured this grid's scalars (the same numbers, not made twice)."""
    sigma = res["sigma"]
    tau_f, tau_direct = res.get("friction") or (None, None)
    if grid.window:  # no spectrum of a window: the dissipation and the direct forms in real space
        if tau_f is None:
            tau_f = _window_friction(sigma, grid, material, speed)
        tau_direct = _window_direct_friction(sigma, grid)
    elif tau_f is None or tau_direct is None:
        tau_f, tau_direct = _friction(sigma, grid.y, material, speed,
                                      layer=grid.layer)
    return tau_f, tau_direct


def _residuals(res, grid, amp, target, mean_p, tau_f, tau_direct):
    """The residuals of `BemResult` (``target``: the load asked for, else the mean pressure)."""
    sigma = res["sigma"]
    out = np.empty(4)
    _kernels.contact_residuals(res["active"], sigma, res["gap"], out)
    smax = float(sigma.max()) if sigma.size else 0.0
    return {
        "complementarity": float(out[0]) / amp,
        "contact_gap": float(out[1]) / amp,
        "interpenetration": float(out[2]) / amp,
        "negative_pressure": float(out[3]) / smax if smax > 0 else float(out[3]),
        "load_balance": abs(mean_p - target) / target if target > 0 else abs(mean_p),
        "krylov": float(res["relres"]) / amp,
        "friction_mismatch": abs(tau_direct - tau_f) / abs(tau_f) if tau_f != 0 else 0.0,
    }


def _contact(res, grid, profile, material, speed, mean_p):
    """The contact patches and their scalars: (full contact?, patches, contact fraction, ka,
    ke, kê, warnings), ka, ke and kê None with several patches (no single patch describes the
    contact: conventions), ke None in full contact."""
    sigma, active = res["sigma"], res["active"]
    warnings = []
    if active.all():
        patches = (_full_patch(sigma, grid.y, profile, mean_p),)
        return True, patches, 1.0, math.pi, None, patches[0].ke_hat, warnings
    # round-off slivers are not patches (`counted_contact`), as for the estimate
    counted = counted_contact(sigma, res["gap"], active, grid.scale)
    fit = fit_panels(counted) if res.get("exact_gaps") else grid.n  # as `_level_scalars`
    patches = tuple(_patches(sigma, res["gap"], counted, grid.x, grid.h, profile, grid.y,
                             grid.window, edge_lags(material, speed, grid.h, fit), fit))
    frac = float(sum(p.width for p in patches))
    if len(patches) == 1:
        ka, ke, ke_hat = patches[0].ka, patches[0].ke, patches[0].ke_hat
    else:
        ka = ke = ke_hat = None
    narrow = min(p.panels for p in patches) if patches else 0
    if narrow < FEW_PANELS:
        warnings.append(f"a contact patch spans {narrow} panel(s): its edges, ka and ke "
                        "carry an error of the order of a panel (refine N)")
    return False, patches, frac, ka, ke, ke_hat, warnings


def _penetration(grid, s, amp, full):
    """(Δ/h, mean separation over h) of the solver's separation ``s``."""
    penetration = (amp - grid.s_offset - s) / amp
    separation = (grid.s_offset + s) / amp
    if full and abs(separation) <= ROUNDOFF:
        # in full contact s is the mean of the zero-mean samples of the profile, zero but for
        # rounding: Δ = h exactly (conventions)
        penetration, separation = 1.0, 0.0
    elif 1.0 < penetration <= 1.0 + ROUNDOFF:
        penetration, separation = 1.0, 0.0  # s within rounding of 0 just below the transition
    return penetration, separation


def _result_fields(res, grid, amp):
    """(x/λ, pressure, displacement over h, gap over h, cell edges or None) of the result."""
    sigma, gap, active, s = res["sigma"], res["gap"], res["active"], float(res["s"])
    if grid.window:
        return _window_fields(sigma, gap, active, s, grid)
    # the uniform grid of N panels
    disp = (gap + grid.y - s) / amp  # C sigma, as the solver's gap holds it
    return grid.x, sigma, disp, np.where(active, 0.0, gap) / amp, None


def _verdict(res, n, residuals, sc, fields, load, gap_roundoff, memory, full, warnings):
    """(success, status, message) of the result: the solver's status, with the residuals where
    it did not converge; a converged answer passed through the validity gate (`_problems`) or
    refused (STATUS_INVALID).  ``memory`` is (panels across the thinnest pressure memory layer,
    its bound on μ, the accuracy asked or None): a layer under a panel at the edges of a partial
    contact is added to the message and to ``warnings`` only where its bound on μ exceeds the
    accuracy asked (`_memory_note`)."""
    status = int(res["status"])
    success = status == CONVERGED
    message = res["message"]
    if status == STATUS_TARGET:
        message = (f"{message}; residuals of N={n}: "
                   + ", ".join(f"{k}={v:.3e}" for k, v in residuals.items()))
    elif not success:
        message = (f"not converged: {message}; residuals "
                   + ", ".join(f"{k}={v:.3e}" for k, v in residuals.items()))
    else:
        bad = _problems(sc, fields, sc["load"], load, gap_roundoff)
        if bad:
            success, status = False, STATUS_INVALID
            message = "invalid result: " + "; ".join(bad)
        elif not full:
            note = _memory_note(*memory)
            if note:
                message += "; " + note
                warnings.append(note)
    return success, status, message


def _memory_note(layer, bound, rtol):
    """The warning of a pressure memory layer under a panel (``layer`` panels across it), or
    None where it does not matter: its edge shift's bound on μ (``bound``, relative, already in
    the error estimate) within the accuracy asked (``rtol``; DEFAULT_RTOL on a fixed mesh)."""
    target = DEFAULT_RTOL if rtol is None else rtol
    if not (layer < 1.0 and bound > target):
        return None
    asked = f"rtol={target:g}" if rtol is not None else f"the default rtol={target:g}"
    return (f"the pressure memory layer spans {layer:.2g} panel: its shift of the contact edges "
            f"may move μ by up to {bound:.1e} (relative, in the error estimate), more than "
            f"{asked}; refine N (or ask for a looser rtol); docs/materials.md, 'The pressure "
            "memory layer'")
