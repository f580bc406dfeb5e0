"""Surface benchmarks (`python -m comparisons bench --surfaces`): the cost of the surface BEM.

Printed, never asserted: on the bi-sinusoid k z = hk [cos kx + cos ky], hk = 1, at p̃ = 0.3,
V/V0 = 1, E∞/E0 = 3 (partial contact: p̃_FC is 1 at rest and 3 at high speed):

1. fixed grids N x N, N = 256 … 2^K: the wall time of the nested solve (N/8 … N) and of its
   finest grid, the FFT pairs of the finest grid and of all, the time per pair, the active-set
   steps, the traced peak memory per panel (tracemalloc: NumPy's buffers, which are the
   solve's memory), μ and its estimate;
2. beside it, in the same run, Tamaas's elastic Polonsky–Keer solve (tolerance 1e-8) of the
   same surface on the same grid (relaxed modulus) and the surface BEM's own elastic solve;
3. the adaptive default against the fixed grid that meets the same accuracy, on the
   bi-sinusoid and a self-affine surface.
"""
from __future__ import annotations

import os
import sys
import time
import tracemalloc

import numpy as np

POINT = {"load": 0.3, "speed": 1.0}
SELF_AFFINE = {"hurst": 0.8, "rolloff": 2.0, "short_cutoff": 8.0, "rms_slope": 0.2, "seed": 0}
SELF_AFFINE_LOAD = 0.05


def _load():
    try:
        return " / ".join(f"{x:.2f}" for x in os.getloadavg())
    except OSError:
        return "n/a"


def _traced(fn):
    """(result, seconds, traced peak bytes) of fn()."""
    tracemalloc.start()
    t0 = time.perf_counter()
    try:
        out = fn()
    finally:
        dt = time.perf_counter() - t0
        peak = tracemalloc.get_traced_memory()[1]
        tracemalloc.stop()
    return out, dt, peak


def fixed_grids(max_log2n=12, tamaas_max_log2n=10):
    """Table 1 and 2: fixed grids 2^8 … 2^max_log2n a side (Tamaas up to 2^tamaas_max_log2n)."""
    import bem
    surf = bem.bisinusoid(1.0)
    bem.solve_surface(**POINT, surface=surf, nodes=64)  # compile the kernels
    print(f"\n## Surface BEM, fixed grids (bi-sinusoid hk = 1, p̃ = 0.3, V/V0 = 1, E∞/E0 = 3; "
          f"load average {_load()})\n")
    print("| N | panels | nested solve [s] | finest grid [s] | FFT pairs (finest / all) | "
          "ms per pair | active-set steps | peak [B/panel] | mu | estimate mu | "
          "Tamaas elastic [s] (its. ) | BEM elastic [s] |")
    print("| ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |")
    rows = []
    for k in range(8, max_log2n + 1):
        n = 2 ** k
        times = {}

        def progress(text, t0=time.perf_counter()):
            times[len(times)] = time.perf_counter() - t0

        res, dt, peak = _traced(lambda: bem.solve_surface(**POINT, surface=surf, nodes=n,
                                                          progress=progress))
        marks = [times[i] for i in sorted(times)]
        finest = marks[-1] - (marks[-2] if len(marks) > 1 else 0.0)
        pairs = [lv[4] for lv in res.levels]
        tam = el = "—"
        if k <= tamaas_max_log2n:
            tam = _tamaas(surf.sample(n, n))
            t0 = time.perf_counter()
            bem.solve_surface(load=POINT["load"], speed=0.0, surface=surf, nodes=n)
            el = f"{time.perf_counter() - t0:.2f}"
        est = res.error_estimate["mu"] if res.error_estimate else float("nan")
        row = (n, n * n, dt, finest, pairs[-1], sum(pairs), 1e3 * finest / pairs[-1], res.nit,
               peak / (n * n), res.mu, est)
        rows.append(row)
        print(f"| {n} | {n * n} | {dt:.2f} | {finest:.2f} | {pairs[-1]:.1f} / {sum(pairs):.1f} | "
              f"{row[6]:.2f} | {res.nit} | {row[8]:.0f} | {res.mu:.8f} | {est:.1e} | {tam} | "
              f"{el} |", flush=True)
    print("\nnested solve: the grids N/8, N/4, N/2 and N (the estimate's), each started from the "
          "one before; FFT pairs: rfft2 + irfft2 of the finest grid (its active-set steps, "
          "Krylov products and preconditioner, and the measurements), and of all the grids; "
          "Tamaas: PolonskyKeerRey, tolerance 1e-8, the relaxed elastic contact of the same "
          "surface at the same load on the same grid (its iterations in brackets); BEM elastic: "
          "the same elastic contact by the surface BEM (V = 0), nested like the viscoelastic "
          "solve.")
    return rows


def _tamaas(heights):
    try:
        from ..peers import surfaces as peers
    except ImportError:
        return "not installed"
    try:
        rec = peers.tamaas_elastic(heights, load=POINT["load"], tolerance=1e-8)
    except ImportError:
        return "not installed"
    return f"{rec['wall_time']:.2f} ({rec['iterations']})"


def adaptive():
    """Table 3: the adaptive default against the fixed grid that meets the same accuracy."""
    import bem
    cases = [("bi-sinusoid hk = 1, p̃ = 0.3", bem.bisinusoid(1.0), POINT["load"]),
             ("self-affine H = 0.8, q_r = 2k, q_s = 8k, rms slope 0.2, p̃ = 0.05",
              bem.self_affine(**SELF_AFFINE), SELF_AFFINE_LOAD)]
    print(f"\n## Surface BEM, the adaptive default (rtol 1e-3) against the fixed grid it ends "
          f"on (V/V0 = 1, E∞/E0 = 3; load average {_load()})\n")
    print("| surface | adaptive [s] | its grid | estimate mu / Δ / contact (relative) | "
          "fixed grid [s] | "
          "ratio | mu |")
    print("| --- | ---: | ---: | --- | ---: | ---: | ---: |")
    for name, surf, load in cases:
        t0 = time.perf_counter()
        a = bem.solve_surface(load=load, speed=POINT["speed"], surface=surf,
                              progress=lambda text: print(f"  {text}", file=sys.stderr))
        ta = time.perf_counter() - t0
        t0 = time.perf_counter()
        f = bem.solve_surface(load=load, speed=POINT["speed"], surface=surf, nodes=a.nodes)
        tf = time.perf_counter() - t0
        e = a.error_estimate or {}
        print(f"| {name} | {ta:.1f} | {a.shape[0]} x {a.shape[1]} | "
              f"{e.get('mu', np.nan):.1e} / {e.get('penetration', np.nan):.1e} / "
              f"{e.get('contact_fraction', np.nan):.1e} | {tf:.1f} | {ta / tf:.2f} | "
              f"{a.mu:.6f} |", flush=True)
    print("\nadaptive: grids 32, 64, … a side until the estimates of mu and Δ/h_ref "
          "(relative) and of the contact fraction (absolute: the relative estimate shown times "
          "the fraction) meet rtol; fixed: nodes = that grid (its N/8 … N).")


def run(max_log2n=12):
    fixed_grids(max_log2n)
    adaptive()
