"""Static equilibrium along the load path: adaptive load increments or arc length.

The problem is :class:`~rancf.solvers.equilibrium.EquilibriumProblem`: the path parameter ``p``
runs from 0 to 1 with the loads at ``p`` times their amplitude (harmonic loads count with their
amplitude), then, with installed supports, from 1 to 2 while the supports move to their
installed places.  Each stage is followed by one of two methods (``method``):

* ``"load"`` (default): load increments, each solved by Newton with a line search
  (:func:`rancf.solvers.newton.newton`).  The first increment is ``1 / load_steps``; an
  increment that converges in at most 5 iterations lets the next one double, one that needs
  more than 12 halves it, and a failed one is retried at a quarter of its size (from the last
  converged state).  The last increment ends exactly at the end of the stage.  The predictor
  extrapolates the last converged increment of the stage (secant).
* ``"arc_length"``: Crisfield's cylindrical arc-length method
  (:func:`rancf.solvers.arc_length.arc_length_path`), which passes limit points (snap-through)
  where load control cannot: the step length ``Δs`` in the scaled displacement norm adapts to
  the iterations of the last step; the last step is corrected back to exactly the end of the
  stage.

When a method still fails, :class:`~rancf.errors.ConvergenceError` carries the load factor
reached, and every converged step has been passed to ``on_step`` (the command line keeps them).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import ConvergenceError, InputError, ScenarioError
from rancf.solvers.equilibrium import EquilibriumProblem
from rancf.solvers.newton import newton
from rancf.system import System

__all__ = ["StaticResult", "solve_static", "StaticMethod", "start_state"]

StaticMethod = Literal["load", "arc_length"]

#: Smallest load increment, relative to the first one, before a load-controlled solve gives up.
MIN_INCREMENT = 1e-6


@dataclass(frozen=True)
class StaticResult:
    """Equilibrium configuration, the load path's factors and counters.

    Attributes
    ----------
    q, y : ndarray
        Full and model coordinates at ``λ = 1``.
    load_factors : ndarray
        The path parameter ``p`` of every converged step, from 0 to 1 (loads), then to 2 with
        installed supports.
    n_newton, n_factorizations, n_residuals : int
        Newton iterations (one tangent assembly and band LU each) and extra residual
        evaluations of the line searches.
    wall_time : float
    method : str
    """

    q: NDArray[np.float64]
    y: NDArray[np.float64]
    load_factors: NDArray[np.float64]
    n_newton: int
    n_factorizations: int
    wall_time: float
    n_residuals: int = 0
    method: str = "load"
    #: Systems: the joints' multipliers at the end of the path (``-Gᵀ λ``: their reactions).
    lam: NDArray[np.float64] | None = None


def solve_static(
    model: Model | System,
    load_steps: int = 10,
    tol: float = 1e-10,
    max_iter: int = 30,
    on_step: Callable[[float, NDArray[np.float64]], None] | None = None,
    method: StaticMethod = "load",
    at_time: float | None = None,
) -> StaticResult:
    """Static equilibrium under the model's loads and installed supports.

    ``at_time``: loads as they act at that time (the start of a dynamic run, ``0``) instead of
    their amplitudes.

    ``on_step(λ, y)`` is called with the reference (``λ = 0``) and after every converged step,
    with the model coordinates ``y`` (the load path; rods: the model's triads are those of ``y``
    at the call).

    Raises
    ------
    ConvergenceError
        With the load factor reached, if the method fails (for example a mechanism: a pendulum
        has no static equilibrium near its reference).
    """
    if isinstance(load_steps, bool) or int(load_steps) != load_steps or load_steps < 1:
        raise InputError("solver.load_steps", load_steps, "an integer >= 1")
    if method not in ("load", "arc_length"):
        raise InputError("solver.static_method", method, 'one of "load", "arc_length"')
    start = time.perf_counter()
    if isinstance(model, Model) and model.closed:  # the seam is a constraint: a system
        model = System({"body": model})
    model.reset_triads()
    if isinstance(model, System):
        from rancf.solvers.system_equilibrium import SystemEquilibrium

        problem: EquilibriumProblem | SystemEquilibrium = SystemEquilibrium(model, at_time)
    else:
        problem = EquilibriumProblem(model, at_time)
    path = _Path(problem, on_step)
    for stage, (_, end) in enumerate(problem.stages):
        problem.stage = stage
        path.prev = None  # no predictor across the stages' kink
        if method == "load":
            _load_control(problem, path, end, 1.0 / load_steps, tol, max_iter)
        else:
            from rancf.solvers.arc_length import arc_length_path

            arc_length_path(problem, path, end, 1.0 / load_steps, tol, max_iter)
    y = path.y
    lam = None
    if isinstance(model, System):
        y, lam = y[: model.n], y[model.n :]
    return StaticResult(
        model.q_from_y(y),
        y,
        np.array(path.factors),
        path.n_newton,
        path.n_newton,  # one band LU factorization per Newton iteration
        time.perf_counter() - start,
        path.n_residuals,
        method,
        lam,
    )


def _one_model(model: Model | System) -> Model | System:
    """A system of one flexible body without time functions as its model (the one-body
    equilibrium path, installation stages included); else the system (a ring's seam is a
    constraint of the system)."""
    if not isinstance(model, System) or model.single is None or len(model.flex) != 1:
        return model
    if model.m:
        return model
    body = model.flex[0]
    timed = any(s.motion is not None for s in body.supports) or any(
        p.time is not None for p in body.point_loads
    )
    return model if timed or model.loads else body


def start_state(
    sc: Any, model: Model | System
) -> tuple[NDArray[np.float64] | None, dict[str, Any]]:
    """Where a scenario's dynamic run starts: ``(None, info)`` from the reference, or the static
    equilibrium's model coordinates (``solver.initial_state = "static"``: loads as they act at
    ``t = 0``, supports installed) and the ``summary.json`` entries describing it.

    Raises
    ------
    ScenarioError
        A support installed away from its reference with ``initial_state = "reference"``.
    """
    key = sc.installed_support()
    if sc.solver["initial_state"] == "reference":
        if key is not None:
            raise ScenarioError(
                sc.path,
                key,
                "installs a support away from its reference, which needs solver.initial_state "
                '= "static" (the static solution moves it there before the run)',
            )
        return None, {"initial_state": "reference"}
    res = solve_static(
        _one_model(model), sc.solver["load_steps"], method=sc.solver["static_method"], at_time=0.0
    )
    info = {
        "initial_state": "static",
        "static": {
            "method": res.method,
            "load_steps": int(len(res.load_factors) - 1),
            "newton_iterations": res.n_newton,
            "wall_time_s": res.wall_time,
        },
    }
    return res.y, info


class _Path:
    """The converged states so far, with the counters and the ``on_step`` callback."""

    def __init__(
        self, problem: EquilibriumProblem, on_step: Callable[[float, NDArray], None] | None
    ) -> None:
        self.problem = problem
        self.y = problem.start()
        self.prev: NDArray | None = None  # the state before the last accepted one
        self.lam = 0.0
        self.prev_lam = 0.0
        self.factors = [0.0]
        self.n_newton = 0
        self.n_residuals = 0
        self.on_step = on_step
        if on_step is not None:
            on_step(0.0, self.y)

    def count(self, iterations: int, residuals: int) -> None:
        self.n_newton += iterations
        self.n_residuals += residuals

    def accept(self, y: NDArray, lam: float) -> None:
        self.problem.accept(y)
        self.prev, self.prev_lam = self.y, self.lam
        self.y, self.lam = y, lam
        self.factors.append(lam)
        if self.on_step is not None:
            self.on_step(lam, y)

    def fail(self, what: str) -> ConvergenceError:
        hint = (
            "is the model a mechanism, or the first arc too long? more solver.load_steps shorten it"
            if what.startswith("arc-length")
            else "is the model a mechanism, or the load beyond a limit point? solver.static_method"
            ' = "arc_length" passes limit points'
        )
        return ConvergenceError(
            f"static {what} did not converge beyond load factor {self.lam:.4g} ({hint})",
            reached=self.lam,
        )


def _load_control(
    problem: EquilibriumProblem,
    path: _Path,
    end: float,
    first: float,
    tol: float,
    max_iter: int,
) -> None:
    """Adaptive load increments to the stage's ``end`` (module docstring)."""
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
            continue
        dlam *= 0.25
        if dlam < MIN_INCREMENT * first:
            raise path.fail("Newton iteration")
