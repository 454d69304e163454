"""Load control: the ``"load"`` method of the static load path
(:func:`rancf.solvers.static.solve_static`).

Adaptive load increments, each solved by Newton with a line search
(:func:`rancf.solvers.newton.newton`): an increment that converges in at most 5 iterations lets
the next one double, one that needs more than 12 halves it, and a failed one is retried at a
quarter of its size (from the last converged state); the last increment ends exactly at the end
of the stage.  The predictor extrapolates the last converged increment of the stage (secant);
a failed predicted step is retried once from the last converged state.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from rancf.solvers.load_path import MIN_INCREMENT, PathState
from rancf.solvers.newton import newton

if TYPE_CHECKING:
    from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = ["load_control_path"]


def load_control_path(
    problem: SystemEquilibrium,
    path: PathState,
    end: float,
    first: float,
    tol: float,
    max_iter: int,
) -> None:
    """Adaptive load increments of ``path`` to the stage's ``end``, the first ``first``
    (module docstring); raises :class:`~rancf.errors.ConvergenceError` where the path stalls."""
    dlam = first
    while path.lam < end:
        target = min(end, path.lam + dlam)
        if target > end - 1e-12:
            target = end  # the last increment ends at the stage's end, not end - rounding
        trial = path.y.copy()
        if path.prev is not None and path.lam > path.prev_lam:  # secant predictor
            trial += (path.y - path.prev) * ((target - path.lam) / (path.lam - path.prev_lam))
        problem.place_supports(trial, target)
        out = newton(problem, trial, target, tol, max_iter)
        if not out.converged and path.prev is not None:  # retry without the predictor
            path.count(out.iterations, out.residuals)
            trial = path.y.copy()
            problem.place_supports(trial, target)
            out = newton(problem, trial, target, tol, max_iter)
        path.count(out.iterations, out.residuals)
        if out.converged:
            path.accept(out.y, target)
            if out.iterations <= 5:
                dlam = min(2.0 * dlam, 1.0)
            elif out.iterations > 12:
                dlam *= 0.5
        else:
            dlam *= 0.25
        if dlam < MIN_INCREMENT * first:  # failed or crawling: the path stalls here
            raise path.fail("Newton iteration")
