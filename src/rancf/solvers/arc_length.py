"""Crisfield's cylindrical arc-length method for the static load path.

Crisfield, "A fast incremental/iterative solution procedure that handles snap-through",
Computers & Structures 13 (1981) 55–62.  The unknowns are the configuration ``y`` and the load
factor ``λ``; each step keeps the scaled displacement increment on a cylinder of radius ``Δs``::

    |Δy|² = Δs²        (norm: positions relative to the model size, the held entries excluded)

With ``q = -∂r/∂λ`` (:meth:`SystemEquilibrium.load_vector`) and the tangent ``K`` at the current
iterate, every corrector iteration solves ``K δy_r = -r`` and ``K δy_t = q`` and takes
``δy = δy_r + δλ δy_t`` with the root ``δλ`` of the quadratic constraint whose new increment
makes the smaller angle with the previous one.  The predictor follows the tangent, its sign set
by the previous increment, so the path turns at limit points.  ``Δs`` starts as the length of a
first load-controlled increment and adapts to the iterations of each step
(``Δs ← Δs min(2, max(0.5, sqrt(6 / n)))``); a failed step is retried with half the length.
When a step passes the end of the stage (``p = 1``, or ``2`` while installing supports) the end
point is solved there by Newton from the point interpolated on that step.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from rancf.solvers.load_path import MIN_INCREMENT, PathState
from rancf.solvers.newton import newton

if TYPE_CHECKING:
    from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = ["arc_length_path"]

#: Largest number of arc-length steps before the path is abandoned.
MAX_STEPS = 2000
#: Iterations per step the step length adapts to.
DESIRED_ITERATIONS = 6


def arc_length_path(
    problem: SystemEquilibrium,
    path: PathState,
    end: float,
    first: float,
    tol: float,
    max_iter: int,
) -> None:
    """Follow one stage of the path from ``path.lam`` to ``end`` (module docstring), accepting
    into ``path``."""
    dlam = min(first, end - path.lam)
    while True:  # a first load-controlled increment sets the arc length
        p1 = path.lam + dlam
        trial = path.y.copy()
        problem.place_supports(trial, p1)
        out = newton(problem, trial, p1, tol, max_iter)
        path.count(out.iterations, out.residuals)
        if out.converged:
            break
        dlam *= 0.25
        if dlam < MIN_INCREMENT * first:
            raise path.fail("arc-length path")
    y0 = path.y
    path.accept(out.y, p1)
    if p1 >= end:
        return
    prev = out.y - y0
    ds = _norm(problem, prev)
    ds_min = 1e-8 * ds
    for _ in range(MAX_STEPS):
        step = _step(problem, path.y, path.lam, prev, ds, tol, max_iter, path)
        if step is None:
            ds *= 0.5
            if ds < ds_min:
                raise path.fail("arc-length path")
            continue
        dy, dl, iterations = step
        if path.lam + dl >= end and dl > 0.0:
            frac = (end - path.lam) / dl
            trial = path.y + frac * dy
            problem.place_supports(trial, end)
            out = newton(problem, trial, end, tol, max_iter)
            path.count(out.iterations, out.residuals)
            if out.converged:
                path.accept(out.y, end)
                return
            ds *= 0.5  # the end point did not converge: approach it with shorter steps
            continue
        y_new = path.y + dy
        problem.place_supports(y_new, path.lam + dl)
        path.accept(y_new, path.lam + dl)
        prev = dy
        ds *= min(2.0, max(0.5, np.sqrt(DESIRED_ITERATIONS / max(iterations, 1))))
    raise path.fail(f"arc-length path (after {MAX_STEPS} steps; largest p {max(path.factors):.4g})")


def _norm(problem: SystemEquilibrium, dy: NDArray) -> float:
    return float(np.linalg.norm((dy * problem.scale)[problem.free]))


def _dot(problem: SystemEquilibrium, a: NDArray, b: NDArray) -> float:
    s2 = problem.scale**2
    return float(np.sum((a * b * s2)[problem.free]))


def _step(
    problem: SystemEquilibrium,
    y: NDArray,
    lam: float,
    prev: NDArray,
    ds: float,
    tol: float,
    max_iter: int,
    path: PathState,
) -> tuple[NDArray, float, int] | None:
    """One arc-length step from ``(y, λ)``: ``(Δy, Δλ, iterations)`` or None if it failed."""
    _, k = problem.tangent(y, lam)
    dyt = problem.solve(k, problem.load_vector(y, k))
    path.count(1, 0)
    if dyt is None or not _norm(problem, dyt) > 0.0:
        return None
    sign = 1.0 if _dot(problem, dyt, prev) >= 0.0 else -1.0
    dl = sign * ds / _norm(problem, dyt)
    dy = dl * dyt
    for it in range(1, max_iter + 1):
        trial = y + dy
        problem.place_supports(trial, lam + dl)
        r, k = problem.tangent(trial, lam + dl)
        path.count(1, 0)
        dyr = problem.solve(k, -r)
        dyt = problem.solve(k, problem.load_vector(trial, k))
        if dyr is None or dyt is None:
            return None
        base = dy + dyr
        a = _dot(problem, dyt, dyt)
        b = 2.0 * _dot(problem, base, dyt)
        c = _dot(problem, base, base) - ds * ds
        disc = b * b - 4.0 * a * c
        if not (a > 0.0 and disc >= 0.0):
            return None
        roots = [(-b + sgn * np.sqrt(disc)) / (2.0 * a) for sgn in (1.0, -1.0)]
        # the root whose increment turns least from the current one (Crisfield 1981)
        cosines = [_dot(problem, base + x * dyt, dy) for x in roots]
        root = roots[int(np.argmax(cosines))]
        delta = dyr + root * dyt
        dy = dy + delta
        dl += root
        inc = float(np.max(np.abs(delta * problem.scale)))
        if not np.isfinite(inc):
            return None
        if inc <= tol:
            return dy, dl, it
    return None
