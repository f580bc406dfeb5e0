"""DMA master curves: `MasterCurve` and the physical checks a measured curve must pass."""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..checks import bad, real, reals

#: fewest points of a DMA curve (and of a shift table's pair of columns) that are accepted
MIN_POINTS = 5


def _loss_bound(omega, loss):
    """Largest rise of E' each interval of data can have: the integral of E'' over ln w.

    For any relaxation spectrum ``dE'/dln w <= E''`` (kernels ``2x^2/(1 + x^2)^2 <=
    x/(1 + x^2)``), and between data points ``w_a < w_a lam < w_b = c w_a`` each kernel gives
    ``E''(w_a lam) <= min(lam E''_a, (c/lam) E''_b)``; the integral of that bound over ln lam
    in [0, ln c] is returned.
    """
    a, b = loss[:-1], loss[1:]
    c = omega[1:] / omega[:-1]
    cross = np.clip(np.sqrt(c * b / a), 1.0, c)   # where lam a = (c/lam) b
    return a * (cross - 1.0) + b * (c / cross - 1.0)


def _check_curve(omega, storage, loss, noise, where):
    """Refuse a curve that no linear viscoelastic solid could give; ``where(j)`` names row j."""
    if omega.size < MIN_POINTS:
        raise ValueError(where(None, f"at least {MIN_POINTS} points (got {omega.size})"))
    for name, arr in (("frequency", omega), ("storage", storage), ("loss", loss)):
        wrong = ~np.isfinite(arr)
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, f"finite values ({name} is {float(arr[j])!r})"))
    checks = [
        (omega <= 0.0, lambda j: f"frequencies > 0 (frequency {float(omega[j])!r})"),
        (storage <= 0.0, lambda j: f"a storage modulus > 0 (storage {float(storage[j])!r})"),
        (loss <= 0.0, lambda j: f"a loss modulus > 0: a solid that dissipates "
                                f"(loss {float(loss[j])!r})"),
    ]
    for wrong, text in checks:
        if wrong.any():
            j = int(np.flatnonzero(wrong)[0])
            raise ValueError(where(j, text(j)))
    step = np.diff(omega)
    if (step <= 0.0).any():
        j = int(np.flatnonzero(step <= 0.0)[0]) + 1
        kind = "a duplicate" if step[j - 1] == 0.0 else "out of order"
        raise ValueError(where(j, f"frequencies strictly increasing (frequency "
                         f"{float(omega[j])!r} after {float(omega[j - 1])!r}: {kind})"))
    drop = storage[1:] < storage[:-1] * (1.0 - noise)
    if drop.any():
        j = int(np.flatnonzero(drop)[0]) + 1
        raise ValueError(where(j, f"a storage modulus that does not decrease with frequency "
                         f"(storage {float(storage[j])!r} after {float(storage[j - 1])!r}; every "
                         "relaxation mode stiffens with frequency)"))
    rise = np.diff(storage)
    bound = _loss_bound(omega, loss)
    over = rise > bound * (1.0 + noise) + noise * storage[1:]
    if over.any():
        j = int(np.flatnonzero(over)[0]) + 1
        raise ValueError(where(j, f"a loss tangent at least the slope of ln E' against ln w "
                         f"(E' rises by {rise[j - 1]:.4g} from the previous point, more than "
                         f"the loss can allow, {bound[j - 1]:.4g}: tan δ = "
                         f"{loss[j] / storage[j]:.4g} is too small for any relaxation "
                         "spectrum, Kramers-Kronig; check the columns and units)"))


@dataclass(frozen=True, eq=False)
class MasterCurve:
    """A DMA master curve in tensile form: ``E'(w)``, ``E''(w)`` at a reference temperature.

    Parameters
    ----------
    omega : array_like
        Angular frequencies, strictly increasing, > 0, in rad per time unit.
    storage, loss : array_like
        ``E'`` and ``E''`` (> 0), in any one modulus unit.
    noise : float
        Relative scatter tolerated by the physical checks (0: none).
    source : str, optional
        Where the data came from (a file name), for provenance.
    modulus_unit : str, optional
        The unit of ``storage`` and ``loss`` (``"MPa"``), when known; see `PASCALS`.

    Raises
    ------
    ValueError
        Fewer than `MIN_POINTS` points, non-finite or non-positive values, frequencies not
        strictly increasing, a storage modulus that decreases with frequency, or a loss too
        small for the rise of the storage modulus (no relaxation spectrum gives it).
    """

    omega: np.ndarray
    storage: np.ndarray
    loss: np.ndarray
    noise: float = 0.0
    source: str | None = None
    modulus_unit: str | None = None

    def __post_init__(self):
        noise = real("noise", self.noise, "a relative scatter in [0, 1)", lambda v: 0.0 <= v < 1.0)
        arrays = {}
        for name in ("omega", "storage", "loss"):
            value = getattr(self, name)
            arr = reals(name, value, "a 1-D sequence of numbers").ravel()
            arr.flags.writeable = False
            arrays[name] = arr
        sizes = [a.size for a in arrays.values()]
        if len(set(sizes)) != 1:
            raise bad("storage", self.storage, "as many values as omega and loss (sizes of "
                      f"omega, storage, loss: {sizes})")

        def where(j, text):
            if j is None:
                return str(bad("omega", self.omega, text))
            return f"omega[{j}]={float(arrays['omega'][j])!r} is not allowed: {text}"
        _check_curve(arrays["omega"], arrays["storage"], arrays["loss"], noise, where)
        for name, arr in arrays.items():
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "noise", noise)

    @property
    def tan_delta(self) -> np.ndarray:
        """Loss tangent ``E''/E'``."""
        return self.loss / self.storage

    @property
    def window(self) -> tuple:
        """``(w_min, w_max)``: the measured frequencies."""
        return float(self.omega[0]), float(self.omega[-1])


