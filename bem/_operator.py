"""FFT circular convolution with the sliding operator, and a right-preconditioned GMRES.

Transform convention
--------------------
* Panels j = 0..N-1 are centred at ``X_j = j/N - 1/2`` (``X = x/lambda``); the
  collocation point i sits at the centre of panel i.
* Panel j acts on point i through ``C[(i - j) mod N]``:
  ``k v_i = sum_j C[(i - j) mod N] sigma_j``, where ``C_m`` is the response at the
  offset ``X = m/N`` (``m > N/2`` stands for the offset ``m/N - 1``, i.e. behind).
* Forward transform without a factor, ``Chat_k = sum_m C_m exp(-2 pi i k m/N)``
  (``scipy.fft.rfft``); the inverse ``irfft`` carries the 1/N.  So
  ``v = irfft(Chat * rfft(sigma))``.
* Sliding direction: material streams toward -x, so the delayed (memory) part of
  the response lies behind the load, at offsets X < 0 (m > N/2); the symbol is
  ``Chat_k ~ (2/k) J*(k) sinc(pi k/N)`` with ``J*(k) = J(0+) + sum J_i/(1 - i k w tau_i)``.
* Mode 0 carries nothing (the displacement is measured from the mean line of the
  deformed surface): ``Chat_0`` is set to exactly 0 (it is a sum of
  coefficients that vanishes up to rounding), and the pseudo-inverse maps the
  mean to 0 as well.
"""
from __future__ import annotations

import numpy as np
import scipy.fft as sfft


class CirculantOperator:
    """``v = C sigma`` and its pseudo-inverse by FFT, O(N log N).

    Parameters
    ----------
    column : ndarray, shape (N,)
        First column ``C_m`` of the circulant (see the module docstring).
    correction : ndarray, shape (N//2 + 1,), optional
        Added to the symbol of the column (a layer's, `bem._layer.symbol_correction`).
    """

    def __init__(self, column: np.ndarray, correction=None):
        self.n = int(column.size)
        sym = sfft.rfft(np.asarray(column, dtype=float))  # the column itself is not kept
        if correction is not None:
            sym += correction
        sym[0] = 0.0
        self.symbol = sym
        # the inverse is applied by division, not stored (memory at large N)
        self.max_inverse = float(1.0 / np.min(np.abs(sym[1:]))) if sym.size > 1 else 0.0

    def _through(self, f: np.ndarray, inverse: bool) -> np.ndarray:
        """The field of spectrum f after C (or C^+), in place: one spectrum alive at a time
        (memory at large N)."""
        if inverse:
            f[0] = 0.0
            f[1:] /= self.symbol[1:]
        else:
            f *= self.symbol
        return sfft.irfft(f, self.n, overwrite_x=True)

    def apply(self, sigma: np.ndarray) -> np.ndarray:
        """k v = C sigma (mean of the result exactly 0)."""
        return self._through(sfft.rfft(sigma), False)

    def pseudo_solve(self, v: np.ndarray) -> np.ndarray:
        """sigma with C sigma = v - mean(v) and mean(sigma) = 0."""
        return self._through(sfft.rfft(v), True)

    def apply_on(self, idx: np.ndarray, values: np.ndarray, inverse: bool = False,
                 whole: bool = False):
        """``(C z)[idx]`` (or ``(C^+ z)[idx]``) for ``z`` equal to `values` on `idx` and zero
        elsewhere, with at most two full-length work arrays alive at a time (memory at large
        N: the Krylov solves on an active or free set call nothing else).  ``whole``: the
        product on every panel (the caller gathers)."""
        z = np.zeros(self.n)
        z[idx] = values
        f = sfft.rfft(z)
        del z
        out = self._through(f, inverse)
        del f  # before the gather
        return out if whole else out[idx]


class WindowOperator:
    """``v = T sigma`` on a contact window of ``n`` panels of a grid too fine to be made.

    ``T`` is the Toeplitz block of the periodic operator, ``T_ij = C[i - j]`` for the signed
    offsets ``-(n - 1) .. n - 1``, applied through its circulant embedding of size 2n (whose
    column holds ``C_0 .. C_n`` and ``C_(-(n-1)) .. C_(-1)``): the product on the window is
    exact.  The "inverse" is only a preconditioner (the solver's Krylov solves use it as they
    use ``R C^+ R^T``): ``inverse_symbol``'s circulant of size 2n restricted to the window, by
    default the embedding's.

    Parameters
    ----------
    coefficients : ndarray, shape (2n + 1,)
        ``C_m`` for the signed offsets m = -n .. n.
    inverse_symbol : ndarray, shape (n + 1,), optional
        The symbol (``rfft`` convention) of the circulant whose inverse preconditions.
    """

    def __init__(self, coefficients: np.ndarray, inverse_symbol=None):
        c = np.asarray(coefficients, dtype=float)
        n = (c.size - 1) // 2
        self.n = n
        col = np.empty(2 * n)
        col[: n + 1] = c[n:]
        col[n + 1:] = c[1:n]
        self.symbol = sfft.rfft(col)
        self.inverse_symbol = self.symbol if inverse_symbol is None else inverse_symbol

    def _through(self, values: np.ndarray, idx, inverse: bool, whole=False) -> np.ndarray:
        z = np.zeros(2 * self.n)
        if idx is None:
            z[: self.n] = values
        else:
            z[idx] = values
        f = sfft.rfft(z)
        if inverse:
            f /= self.inverse_symbol
        else:
            f *= self.symbol
        out = sfft.irfft(f, 2 * self.n)
        return out[: self.n] if idx is None or whole else out[idx]

    def apply(self, sigma: np.ndarray) -> np.ndarray:
        """k v = T sigma on the window (from the mean line of the period's deformed surface)."""
        return self._through(sigma, None, False)

    def apply_on(self, idx: np.ndarray, values: np.ndarray, inverse: bool = False,
                 whole: bool = False):
        """``(T z)[idx]`` (or the preconditioner's) for ``z`` equal to `values` on `idx`;
        ``whole``: on every panel of the window."""
        return self._through(values, idx, inverse, whole)


def gmres(matvec, precond, b, x0, atol, restart, maxiter, keep=False):
    """Restarted GMRES with right preconditioning (true residuals are monitored).

    Solves ``A x = b`` as ``A M u = b``, ``x = M u``, until ``||b - A x||_2 <= atol``
    (an absolute bound: it bounds every entry of the residual).  Classical Gram-Schmidt with
    one reorthogonalisation; Givens rotations; at each restart the true residual
    ``b - A x`` is recomputed.  ``keep``: the preconditioned vectors ``M v_j`` are kept
    (``restart`` more vectors of b's size) and x is updated from them, one application of M
    fewer per cycle (M is linear: the same x to rounding).

    ``x0`` (the start) is updated in place when it is a float array.

    Returns
    -------
    x : ndarray
    iterations : int
        Products with ``A M``.
    resnorm : float
        ``||b - A x||_2`` (true residual at exit).
    converged : bool
    """
    x = np.asarray(x0, dtype=float)  # a float array x0 is overwritten: no copy at large N
    r = b - matvec(x)
    total = 0
    n = b.size
    m = max(1, min(restart, n))
    basis = np.empty((m + 1, n))
    kept = np.empty((m, n)) if keep else None
    while True:
        beta = float(np.linalg.norm(r))
        if beta <= atol:
            return x, total, beta, True
        if total >= maxiter:
            return x, total, beta, False
        hess = np.zeros((m + 1, m))
        cs = np.zeros(m)
        sn = np.zeros(m)
        g = np.zeros(m + 1)
        g[0] = beta
        basis[0] = r / beta
        k = 0
        for j in range(m):
            if keep:
                kept[j] = precond(basis[j])
                w = matvec(kept[j])
            else:
                w = matvec(precond(basis[j]))
            total += 1
            h = basis[: j + 1] @ w
            w -= basis[: j + 1].T @ h
            h2 = basis[: j + 1] @ w
            w -= basis[: j + 1].T @ h2
            h += h2
            hn = float(np.linalg.norm(w))
            hess[: j + 1, j] = h
            hess[j + 1, j] = hn
            for i in range(j):
                tmp = cs[i] * hess[i, j] + sn[i] * hess[i + 1, j]
                hess[i + 1, j] = -sn[i] * hess[i, j] + cs[i] * hess[i + 1, j]
                hess[i, j] = tmp
            den = np.hypot(hess[j, j], hess[j + 1, j])
            cs[j] = hess[j, j] / den
            sn[j] = hess[j + 1, j] / den
            hess[j, j] = den
            hess[j + 1, j] = 0.0
            g[j + 1] = -sn[j] * g[j]
            g[j] = cs[j] * g[j]
            k = j + 1
            if abs(g[j + 1]) <= atol or total >= maxiter or hn == 0.0:
                break
            basis[j + 1] = w / hn
        y = np.linalg.solve(np.triu(hess[:k, :k]), g[:k])
        x += kept[:k].T @ y if keep else precond(basis[:k].T @ y)
        r = b - matvec(x)
