"""The reference of a verification: the semi-analytic road where it applies (sinusoid on the
standard linear solid half-plane), else the BEM, a layer included (the suite's certified values
for ``--case``, on a layer checked against the Fourier reference there, else a
convergence study as the suite's; its fields on the user's grid at N = M·2^k ≥ 2^16); the report
says which, and the reference's own uncertainty.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .. import roads
from .. import suite as _suite
from ..fields import bem_fields
from ..suite_inputs import ProfileShape
from ._quantities import COMPARED_KEYS

#: the BEM reference's fields are solved on at least this many panels (N = M·2^k ≥ it)
REFERENCE_MIN_NODES = 1 << 16


@dataclass
class Reference:
    """The reference of a verification: scalars, patches and fields on any grid.

    ``road`` is ``"semi-analytic"`` or ``"BEM"``; ``scalars[key]`` = (value, uncertainty) with an
    absolute uncertainty; ``patches`` a list of dicts with ``trailing_edge``, ``leading_edge``.
    """

    road: str
    description: str
    point: dict
    scalars: dict
    patches: list
    full_contact: bool | None
    shape: object
    _analytic: object = None
    _bem_cache: dict = field(default_factory=dict)

    def fields(self, x):
        """(reference fields at x, their absolute uncertainty per column) as dicts of arrays."""
        x = np.asarray(x, float)
        if self._analytic is not None:
            f = self._analytic.fields(x)
            vals = {"pressure": np.asarray(f.pressure), "displacement": np.asarray(f.displacement),
                    "gap": np.asarray(f.gap)}
            unc = {k: np.full(x.size, 1e-12 * max(1.0, float(np.max(np.abs(a)))))
                   for k, a in vals.items()}
            return vals, unc
        m = x.size
        n_ref = m * 2
        while n_ref < REFERENCE_MIN_NODES:
            n_ref *= 2
        fine = self._bem_on(x, n_ref)
        coarse = self._bem_on(x, n_ref // 2)
        unc = {k: np.abs(fine[k] - coarse[k]) for k in fine}
        return fine, unc

    def _bem_on(self, x, n):
        if n not in self._bem_cache:
            res = _suite.bem_solution(self.point, n, base="/")
            if not res.success:
                raise RuntimeError(f"the reference BEM did not converge at N = {n}: "
                                   f"{res.message.splitlines()[0][:200]}")
            self._bem_cache[n] = bem_fields(res)
        X, p, v, g = self._bem_cache[n]
        # aligned grid points are panel centres; others are interpolated (σ² and gap^(2/3)
        # are the quantities that are smooth through an edge)
        pos = (np.asarray(x, float) + 0.5) * n
        idx = np.rint(pos)
        if np.all(np.abs(pos - idx) < 1e-6):
            j = idx.astype(np.int64) % n
            return {"pressure": p[j], "displacement": v[j], "gap": g[j]}
        xe = np.concatenate((X - 1.0, X, X + 1.0))
        xw = np.asarray(x, float) - np.floor(np.asarray(x, float) + 0.5)

        def lin(a):
            return np.interp(xw, xe, np.tile(a, 3))
        return {"pressure": np.sqrt(lin(p ** 2)), "displacement": lin(v),
                "gap": lin(np.abs(g) ** (2.0 / 3.0)) ** 1.5}


def reference_for(point, case=None) -> Reference:
    """The reference for an operating point: the semi-analytic road where it applies, else the
    suite's certified BEM values (``case``) or a BEM convergence study as the suite's."""
    shape = ProfileShape(point, base="/")
    if _suite.two_roads(point):
        sol = roads.analytic_solution(point)
        if not sol.success:
            raise RuntimeError(f"the semi-analytic reference failed: {sol.message}")
        sc = {}
        for k in COMPARED_KEYS:
            v = getattr(sol, k, None)
            if v is not None:
                sc[k] = (float(v), 1e-12 * abs(float(v)))
        if case is not None:  # the certified values carry the two roads' agreement
            for k, r in case["certified"]["scalars"].items():
                if r["value"] is not None and r["error"] is not None:
                    sc[k] = (float(r["value"]), float(r["error"]))
        patches = []
        if not sol.full_contact:
            patches = [{"trailing_edge": (sol.ke - sol.ka) / (2 * math.pi),
                        "leading_edge": (sol.ke + sol.ka) / (2 * math.pi)}]
        desc = ("the semi-analytic road (analytic/: Hunter's transformation, the closure "
                "(2.14)–(2.15), Appendix B in full contact)"
                + (f"; scalars as certified in the suite case {case['name']}" if case else ""))
        return Reference("semi-analytic", desc, point, sc, patches, bool(sol.full_contact),
                         shape, _analytic=sol)
    if case is None:
        nodes = [2 ** k for k in range(10, 19)]
        case = {"name": "reference", "title": "reference", "point": point, "nodes": nodes}
        cert, _ = _suite.compute(case, base="/")
        case = dict(case, certified=cert)
        desc = ("the BEM (bem/), a convergence study over N = 2^10 … 2^18 as the suite's "
                "(Richardson values; uncertainty 10 × the estimate)")
    else:
        desc = f"the BEM (bem/): the certified values of the suite case {case['name']}"
    cert = case["certified"]
    sc = {k: (float(r["value"]), float(r["error"]) if r["error"] is not None else math.inf)
          for k, r in cert["scalars"].items() if r["value"] is not None}
    full = bool(cert["exact"].get("full_contact"))
    for k in ("ka", "contact_fraction", "penetration", "separation"):
        if k in cert["exact"] and cert["exact"][k] is not None and k not in sc:
            sc[k] = (float(cert["exact"][k]), 0.0)
    if cert["patches"]:
        patches = [{"trailing_edge": p["trailing_edge"]["value"],
                    "leading_edge": p["leading_edge"]["value"]} for p in cert["patches"]]
    elif not full and "ka" in sc:
        s0 = shape.summit(-0.5, 0.5) if not shape.sinusoid else 0.0
        ka, ke = sc["ka"][0], sc["ke"][0]
        patches = [{"trailing_edge": s0 + (ke - ka) / (2 * math.pi),
                    "leading_edge": s0 + (ke + ka) / (2 * math.pi)}]
    else:
        patches = []
    return Reference("BEM", desc, point, sc, patches, full, shape)

