"""Newton's method with a line search for ``r(y, λ) = 0`` at a fixed load factor.

Each iteration solves ``K d = -r`` with the exact tangent and moves to ``y + s d``.  The step
length ``s`` comes from the line search of Crisfield (*Non-linear Finite Element Analysis of
Solids and Structures*, vol. 1, 1991, sec. 9.5): ``s`` is a root of the directional residual

    g(s) = dᵀ r(y + s d),

which for conservative loads is the derivative of the potential energy along ``d``.  ``s = 1``
(plain Newton) is kept whenever ``|g(1)| <= η |g(0)|`` (η = 0.5) or ``g`` does not change sign
on ``(0, 1]``; otherwise the root is bracketed by decades (``s = 0.1, 0.01, ...``: the
first Newton step from a tension-free straight cable can overshoot by six orders of magnitude,
its transverse stiffness then being the bending stiffness alone) and refined by the Illinois
variant of regula falsi.  Each trial costs one residual (no tangent).

Convergence: the scaled increment ``|s d|`` (positions relative to the model size) at most
``tol``, as in the time integrator.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = ["NewtonOutcome", "newton", "line_search"]

#: Accept a step length once ``|g(s)| <= ETA |g(0)|``.
ETA = 0.5


@dataclass(frozen=True)
class NewtonOutcome:
    """How a Newton solve ended: the last iterate, counters and the last scaled increment."""

    converged: bool
    y: NDArray[np.float64]
    iterations: int
    residuals: int
    increment: float


def line_search(g: Callable[[float], float], g0: float, max_evals: int = 30) -> tuple[float, int]:
    """Step length ``s ∈ (0, 1]`` along a Newton direction (module docstring).

    Parameters
    ----------
    g : callable
        ``g(s) = dᵀ r(y + s d)``.
    g0 : float
        ``g(0)`` (negative along a descent direction).

    Returns
    -------
    s, evaluations
    """
    g1 = g(1.0)
    evals = 1
    if not np.isfinite(g1):
        g1 = np.inf  # treat as far past the root
    if g0 == 0.0 or g1 * g0 > 0.0 or abs(g1) <= ETA * abs(g0):
        return 1.0, evals
    b, gb = 1.0, g1
    a, ga = 0.1, g(0.1)
    evals += 1
    while (not np.isfinite(ga) or ga * g0 < 0.0) and a > 1e-14:  # bracket by decades
        b, gb = a, (ga if np.isfinite(ga) else np.inf)
        a *= 0.1
        ga = g(a)
        evals += 1
    if not np.isfinite(ga) or ga * g0 < 0.0:
        return a, evals
    if abs(ga) <= ETA * abs(g0) or not np.isfinite(gb):
        return a, evals
    s = a
    while evals < max_evals:  # Illinois: [a, b] brackets the root, g(a) on g0's side
        s = b - gb * (b - a) / (gb - ga)
        gs = g(s)
        evals += 1
        if abs(gs) <= ETA * abs(g0):
            break
        if gs * gb < 0.0:
            a, ga = b, gb
        else:
            ga *= 0.5
        b, gb = s, gs
    return s, evals


def newton(
    problem: SystemEquilibrium, y: NDArray, lam: float, tol: float, max_iter: int
) -> NewtonOutcome:
    """Solve ``r(y, λ) = 0`` from ``y`` (held entries already placed) by Newton with a line
    search; ``y`` is not modified."""
    y = np.array(y, dtype=float)
    residuals = 0
    inc = np.inf
    for it in range(1, max_iter + 1):
        r, ab = problem.tangent(y, lam)
        d = problem.solve(ab, -r)
        if d is None or not np.all(np.isfinite(r)):
            return NewtonOutcome(False, y, it, residuals, inc)
        g0 = float(d @ r)

        def g(s: float, d: NDArray = d, y: NDArray = y) -> float:
            return float(d @ problem.residual(y + s * d, lam))

        s, evals = line_search(g, g0)
        residuals += evals
        step = s * d
        y += step
        inc = float(np.max(np.abs(step * problem.scale)))
        if not np.isfinite(inc):
            return NewtonOutcome(False, y, it, residuals, inc)
        if inc <= tol and s == 1.0:
            return NewtonOutcome(True, y, it, residuals, inc)
    return NewtonOutcome(False, y, max_iter, residuals, inc)
