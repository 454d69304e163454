"""Newton's method as a pure function (the SciPy ``_ivp`` / diffrax pattern)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

__all__ = ["NewtonResult", "newton"]


@dataclass(frozen=True)
class NewtonResult:
    """Outcome of :func:`newton`: the last iterate and how it got there."""

    x: NDArray[np.float64]
    converged: bool
    n_iter: int
    increment_norm: float


def newton(
    x0: NDArray[np.float64],
    step: Callable[[NDArray[np.float64]], NDArray[np.float64]],
    tol: float,
    max_iter: int,
) -> NewtonResult:
    """Iterate ``x ← x - Δ(x)`` until ``max |Δ| <= tol``.

    ``step(x)`` returns the Newton increment ``J(x)⁻¹ R(x)`` (assembling and factoring the exact
    tangent).  The iteration stops early, unconverged, on a non-finite increment or after
    ``max_iter`` steps; the caller then shrinks its step.
    """
    x = np.array(x0, dtype=float)
    norm = np.inf
    for it in range(1, max_iter + 1):
        dx = step(x)
        norm = float(np.max(np.abs(dx))) if dx.size else 0.0
        if not np.isfinite(norm):
            return NewtonResult(x, False, it, norm)
        x -= dx
        if norm <= tol:
            return NewtonResult(x, True, it, norm)
    return NewtonResult(x, False, max_iter, norm)
