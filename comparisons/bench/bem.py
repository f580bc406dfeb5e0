"""Benchmark tables of the BEM road: accuracy, iterations, time, memory, FFT count.

Run by ``python -m comparisons bench --bem`` (or ``--bem-only``; ``--max-log2n K`` sets the
large timing run, `tables`).  Tables go to standard output, progress to standard error.  Parameters: standard linear solid
with E_inf/E0 = 3, hk = 1 (conventions.md); every table states its own.
"""
from __future__ import annotations

import math
import platform
import resource
import sys
import time
import tracemalloc

import numpy as np

import bem

from ..convergence import observed_order
from ..progress import Progress


#: the study's progress line (in place on a terminal, a line every few seconds in a log)
_PROGRESS = Progress()


def _progress(msg: str) -> None:
    _PROGRESS.update(msg)


def _westergaard(load: float, hk: float, modulus: float) -> dict:
    """Westergaard (1939): load/p* = sin^2(pi a/lambda), p* = E* k h/2 (modulus E/E0),
    peak 2 load/sin(pi a/lambda), Delta/h = (load/p*)(1 - ln(load/p*))."""
    r = load / (modulus * hk / 2.0)
    psi = math.asin(math.sqrt(r))
    return {"ka": 2.0 * psi, "penetration": r * (1.0 - math.log(r)),
            "peak": 2.0 * load / math.sin(psi)}


def _appendix_b_mu(mat: bem.Prony, speed: float, load: float, hk: float) -> tuple:
    """Full contact (Appendix B, signs of conventions.md): mu and k e_hat = arg J*(1)."""
    js = complex(mat.jstar(1, speed))
    tau_f = hk**2 * js.imag / (4.0 * abs(js) ** 2)
    return tau_f / load, math.atan2(js.imag, js.real)


def _order(n1, e1, n2, e2):
    return observed_order((n1, n2), (e1, e2))


def table_elastic_limits(exponents, load, out) -> None:
    mat = bem.Prony.standard_linear_solid(3.0)
    print(f"\n## Elastic limits against Westergaard (SLS ratio 3, hk 1, load {load})", file=out)
    print("errors |BEM - Westergaard|; order = log2 of the error ratio to the previous N; "
          "fit = least-squares slope over all N", file=out)
    for speed, modulus in ((1e-6, 1.0), (1e6, 3.0)):
        ref = _westergaard(load, 1.0, modulus)
        print(f"\nspeed {speed:g} (modulus E{'0' if modulus == 1 else '_inf'}):  ka = {ref['ka']:.12f},"
              f" Delta/h = {ref['penetration']:.12f}, peak = {ref['peak']:.12f}", file=out)
        if speed < 1.0:  # the physical deviation of ka is first order in speed (DERIVATION.md §7)
            print(f"(the true ka is ka_W − (1 − 1/ρ) w/2 = ka_W − {(1 - 1 / 3) * speed / 2:.2e}; the "
                  f"memory layer w/ρ spans {speed / 3 * 2 ** exponents[-1] / (2 * math.pi):.1e} panel "
                  "at the finest N, so below that level this column measures the elastic edge)", file=out)
        print(f"{'N':>8} {'err ka':>10} {'order':>6} {'err Delta/h':>12} {'order':>6} "
              f"{'err peak':>10} {'order':>6} {'nit':>4} {'inner (finest)':>16}", file=out)
        rows = []
        for e in exponents:
            n = 2**e
            _progress(f"elastic limit speed {speed:g} N {n}")
            r = bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=n, load=load)
            if not r.success:
                print(f"{n:>8} NOT CONVERGED: {r.message}", file=out)
                continue
            err = (abs(r.ka - ref["ka"]), abs(r.penetration - ref["penetration"]),
                   abs(float(r.pressure.max()) - ref["peak"]))
            orders = ["" for _ in err]
            if rows:
                orders = [f"{_order(rows[-1][0], rows[-1][1][i], n, err[i]):6.2f}" for i in range(3)]
            rows.append((n, err))
            print(f"{n:>8} {err[0]:10.2e} {orders[0]:>6} {err[1]:12.2e} {orders[1]:>6} "
                  f"{err[2]:10.2e} {orders[2]:>6} {r.nit:>4} {str(r.inner_iterations):>16}",
                  file=out)
        if len(rows) >= 3:
            ns = np.array([r[0] for r in rows], float)
            fits = [observed_order(ns, [r[1][i] for r in rows]) for i in range(3)]
            print(f"{'fit':>8} {'':>10} {fits[0]:6.2f} {'':>12} {fits[1]:6.2f} {'':>10} "
                  f"{fits[2]:6.2f}", file=out)


def table_full_contact(nodes, out) -> None:
    mat = bem.Prony.standard_linear_solid(3.0)
    load = 2.0
    print(f"\n## Full contact against Appendix B (SLS ratio 3, hk 1, load {load}, N {nodes})",
          file=out)
    print(f"{'speed':>8} {'mu BEM':>20} {'mu Appendix B':>20} {'rel err':>10} "
          f"{'ke_hat err':>11}", file=out)
    for speed in (1e-3, 1e-2, 0.1, 1.0, 10.0, 100.0, 1e3):
        _progress(f"full contact speed {speed:g}")
        r = bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=nodes, load=load)
        mu, kehat = _appendix_b_mu(mat, speed, load, 1.0)
        if not (r.success and r.full_contact):
            print(f"{speed:>8g} unexpected: success={r.success} full={r.full_contact}", file=out)
            continue
        print(f"{speed:>8g} {r.mu:20.15e} {mu:20.15e} {abs(r.mu - mu) / mu:10.2e} "
              f"{abs(r.ke_hat - kehat):11.2e}", file=out)


def table_iterations(exponents, out) -> None:
    mat = bem.Prony.standard_linear_solid(3.0)
    speed, load = 1.0, 0.3
    print(f"\n## Iterations against N (SLS ratio 3, hk 1, speed {speed}, load {load}, tol 1e-10)",
          file=out)
    print("nested: outer steps / GMRES iterations per outer step on the finest grid; "
          "single grid: the same without nested iteration (initial active set from the "
          "full-contact pressure lowered to carry the load once clipped)", file=out)
    print(f"{'N':>8} {'nested nit':>10} {'inner per outer':>18} {'single nit':>10} "
          f"{'inner per outer (single grid)':>40}", file=out)
    for e in exponents:
        n = 2**e
        _progress(f"iterations N {n}")
        a = bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=n, load=load)
        b = bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=n, load=load, nested=False)
        print(f"{n:>8} {a.nit:>10} {str(a.inner_iterations):>18} {b.nit:>10} "
              f"{str(b.inner_iterations):>40}", file=out)


def _timed(n, speed, load):
    mat = bem.Prony.standard_linear_solid(3.0)
    t0 = time.perf_counter()
    r = bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=n, load=load)
    return time.perf_counter() - t0, r


def table_timing(big_exponent, out) -> None:
    print("\n## Time per operating point (influence coefficients of every grid included)",
          file=out)
    print(f"machine: {platform.processor() or platform.machine()}, Python "
          f"{platform.python_version()}; warm-up solve at N = 4096 first, so numba "
          "compilation and start-up are excluded", file=out)
    _timed(4096, 1.0, 0.3)  # warm-up (compilation, FFT plans)
    points = ((1e-6, 0.3), (1.0, 0.3), (1e6, 0.3), (1.0, 0.6), (1.0, 2.0))
    mat = bem.Prony.standard_linear_solid(3.0)
    for n in (2**16, 2**big_exponent):
        print(f"\nN = {n}", file=out)
        print(f"{'speed':>8} {'load':>6} {'time [s]':>9} {'coeff [s]':>9} {'full':>5} "
              f"{'nit':>4} {'inner':>10} {'peak traced [MiB]':>18}", file=out)
        for speed, load in points:
            _progress(f"timing N {n} speed {speed:g} load {load}")
            best = min(_timed(n, speed, load)[0] for _ in range(3 if n <= 2**16 else 1))
            t0 = time.perf_counter()
            bem.influence_coefficients(mat, speed, n)
            tc = time.perf_counter() - t0
            tracemalloc.start()
            _, r = _timed(n, speed, load)
            peak = tracemalloc.get_traced_memory()[1] / 2**20
            tracemalloc.stop()
            print(f"{speed:>8g} {load:>6g} {best:9.3f} {tc:9.3f} {str(r.full_contact):>5} "
                  f"{r.nit:>4} {str(r.inner_iterations):>10} {peak:18.0f}", file=out)
    rss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    print(f"\npeak traced = tracemalloc peak of one solve (NumPy buffers; best of 3 timings "
          f"is without tracemalloc). ru_maxrss of the whole process (interpreter, numba, "
          f"all tables so far): {rss:.0f} MiB", file=out)


class _FftCount:
    """Counts the real transforms bem makes (scipy.fft and numpy.fft rfft/irfft, which bem calls
    through their modules) while active, in pair equivalents of N: a transform of real length L
    counts L/(2N), so one rfft and one irfft of length N make 1.  Deterministic, unlike times."""

    def __init__(self, n):
        self.n, self.total, self._saved = n, 0.0, []

    def __enter__(self):
        import scipy.fft
        for mod in (scipy.fft, np.fft):
            for name in ("rfft", "irfft"):
                orig = getattr(mod, name)
                self._saved.append((mod, name, orig))
                setattr(mod, name, self._wrap(orig, name))
        return self

    def _wrap(self, orig, name):
        def counted(x, n=None, *args, **kwargs):
            length = n if n is not None else (
                np.shape(x)[-1] if name == "rfft" else 2 * (np.shape(x)[-1] - 1))
            self.total += length / (2.0 * self.n)
            return orig(x, n, *args, **kwargs)
        return counted

    def __exit__(self, *exc):
        for mod, name, orig in reversed(self._saved):
            setattr(mod, name, orig)
        return False


def _best_of_3(run) -> float:
    """The shortest of three timed calls of ``run`` (seconds)."""
    best = math.inf
    for _ in range(3):
        t0 = time.perf_counter()
        run()
        best = min(best, time.perf_counter() - t0)
    return best


def table_cost(big_exponent, out) -> None:
    mat = bem.Prony.standard_linear_solid(3.0)
    n, speed, load = 2**big_exponent, 1.0, 0.3
    print(f"\n## Cost of one fixed-N solve at the paper's point (SLS ratio 3, hk 1, speed {speed}, "
          f"load {load}, N = {n})", file=out)
    print("FFT pairs: real transforms counted in pair equivalents of N (an rfft and an irfft of "
          "length N make 1; coefficients, Krylov products, gaps, friction and fields "
          "included); time: best of 3 after a warm-up solve. nested: the estimate's grids N/8, "
          "N/4, N/2 and every fourth grid below them first; cold: nested=False, from the "
          "full-contact pressure lowered to carry the load once clipped",
          file=out)
    print(f"{'start':>7} {'FFT pairs':>10} {'time [s]':>9} {'nit':>4} {'inner (finest)':>40}",
          file=out)
    bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=4096, load=load)
    rows = {}
    for name, nested in (("nested", True), ("cold", False)):
        _progress(f"cost N {n} {name}")

        def run():
            return bem.solve(profile=bem.Sinusoid(1.0), material=mat, speed=speed, nodes=n,
                             load=load, nested=nested)

        with _FftCount(n) as count:
            r = run()
        best = _best_of_3(run)
        rows[name] = (count.total, best)
        print(f"{name:>7} {count.total:10.1f} {best:9.3f} {r.nit:>4} "
              f"{str(r.inner_iterations):>40}", file=out)
    print(f"cold/nested: {rows['cold'][0] / rows['nested'][0]:.2f} in FFT pairs, "
          f"{rows['cold'][1] / rows['nested'][1]:.2f} in time", file=out)


#: the mesh study's exponents: the certified suite's meshes, N = 2^10 … 2^18
STUDY_EXPONENTS = range(10, 19)


def table_study(load, out, exponents=STUDY_EXPONENTS) -> None:
    """A mesh study over N = 2^10 … 2^18 (the suite's): each fixed mesh solved on its own
    against ``bem.solve_meshes`` (the grids solved once), in FFT pairs, time and the answers'
    spread."""
    mat = bem.Prony.standard_linear_solid(3.0)
    nodes = [2 ** e for e in exponents]
    speed = 1.0
    kw = dict(profile=bem.Sinusoid(1.0), material=mat, speed=speed, load=load)
    print(f"\n## A mesh study, N = {nodes[0]} … {nodes[-1]} (SLS ratio 3, hk 1, speed {speed}, "
          f"load {load})", file=out)
    print(f"one by one: bem.solve(nodes=N) for each N; study: bem.solve_meshes(nodes=[...]). "
          f"FFT pairs in pair equivalents of N = {nodes[-1]}; time: best of 3 after a warm-up; "
          "spread: the largest relative difference of mu between the two on any mesh", file=out)
    print(f"{'how':>11} {'FFT pairs':>10} {'time [s]':>9}", file=out)
    bem.solve(nodes=4096, **kw)
    rows, answers = {}, {}
    for name in ("one by one", "study"):
        _progress(f"mesh study {name}")

        def run():
            if name == "study":
                return list(bem.solve_meshes(nodes=nodes, **kw))
            return [bem.solve(nodes=n, **kw) for n in nodes]

        with _FftCount(nodes[-1]) as count:
            answers[name] = run()
        best = _best_of_3(run)
        rows[name] = (count.total, best)
        print(f"{name:>11} {count.total:10.1f} {best:9.3f}", file=out)
    spread = max(abs(a.mu - b.mu) / abs(b.mu)
                 for a, b in zip(answers["study"], answers["one by one"]))
    print(f"study/one by one: {rows['study'][0] / rows['one by one'][0]:.2f} in FFT pairs, "
          f"{rows['study'][1] / rows['one by one'][1]:.2f} in time; spread of mu {spread:.1e}",
          file=out)


def tables(big_exponent=20, min_exponent=8, max_exponent=16, load=0.3, out=None) -> int:
    """Print every table: elastic limits (at ``load``: partial contact at both ends) and
    iterations on N = 2^min_exponent … 2^max_exponent, full contact at N = 1024, timing and
    cost at N = 2^big_exponent, a mesh study over the suite's meshes; exit status 0, or 2 for exponents outside [3, 22]."""
    if not 3 <= min_exponent <= max_exponent <= 22 or not 3 <= big_exponent <= 22:
        print("bench-bem: exponents must satisfy 3 <= min <= max <= 22 and 3 <= big <= 22",
              file=sys.stderr)
        return 2
    exps = range(min_exponent, max_exponent + 1)
    out = sys.stdout if out is None else out
    print("# BEM benchmark", file=out)
    table_elastic_limits(exps, load, out)
    table_full_contact(1024, out)
    table_iterations(exps, out)
    table_timing(big_exponent, out)
    table_cost(big_exponent, out)
    table_study(load, out)
    return 0
