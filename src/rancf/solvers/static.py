"""Static equilibrium along the load path: adaptive load increments or arc length, and
relaxation where the path cannot go on.

The problem is :class:`~rancf.solvers.system_equilibrium.SystemEquilibrium` (a one-body
:class:`~rancf.bodies.flexible.Model` is solved as the system of that one body): the path parameter
``p`` runs from 0 to 1 with the loads at ``p`` times their amplitude (harmonic loads count with
their amplitude), then, with installed supports, from 1 to 2 while the supports move to their
installed places.  Each stage is followed by one of two methods (``method``), or none:

* ``"load"`` (default): load increments, each solved by Newton with a line search
  (:func:`rancf.solvers.newton.newton`).  The first increment is ``1 / load_steps``; an
  increment that converges in at most 5 iterations lets the next one double, one that needs
  more than 12 halves it, and a failed one is retried at a quarter of its size (from the last
  converged state).  The last increment ends exactly at the end of the stage.  The predictor
  extrapolates the last converged increment of the stage (secant)
  (:func:`rancf.solvers.load_control.load_control_path`).
* ``"arc_length"``: Crisfield's cylindrical arc-length method
  (:func:`rancf.solvers.arc_length.arc_length_path`), which passes limit points (snap-through)
  where load control cannot: the step length ``Δs`` in the scaled displacement norm adapts to
  the iterations of the last step; the last step is corrected back to exactly the end of the
  stage.
* ``"linear"``: no path; the small-displacement answer of the linear benchmarks, one Newton
  step from the reference at the end of the path (:mod:`rancf.solvers.linear_static`), not
  checked as a nonlinear equilibrium.

A structure that is a mechanism at its reference, where the loads meet no stiffness
(:meth:`~rancf.solvers.system_equilibrium.SystemEquilibrium.mechanism`: a pinned pendulum drawn
horizontal under gravity), gives the load path nothing to start from: its loads stage goes to
relaxation directly.  When the method cannot start or stalls (a slack rope whose reference is
far from its sag), the stage is finished by pseudo-transient continuation at its end
(:func:`rancf.solvers.relaxation.relax`: the state follows the physics to rest, then Newton
polishes it), from the last converged state; the
result's ``method`` is then ``"relaxation+newton"``.  When that fails too (a body with no
equilibrium at all), :class:`~rancf.errors.ConvergenceError` carries the load factor reached,
and every converged step has been passed to ``on_step`` (the command line keeps them).

Every result is checked (:mod:`rancf.solvers.static_checks`).  With ``"load"`` (``"arc_length"``
traces the path), a line longer than the chord between its pinned ends starts from its sagged
shape (:mod:`rancf.solvers.sag_start`; ``method`` ``"sag start+newton"``): the catenary it hangs
in, lying on a seabed where it touches one, is far closer to its equilibrium than its reference
(a straight or flared line), whose load path needed relaxation or ended in a compressive loop.
Where that start fails (Newton and relaxation find no equilibrium, or one that fails the
checks) the load path is followed.  Where the path fails or ends in a state that fails the
checks or is unstable (:func:`~rancf.solvers.static_checks.instability`), lines with a
clamped end (and, after an arc-length path, all lines) are started again from their sagged
shape before the path's failure is raised.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass, replace
from typing import Literal

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.errors import ConvergenceError, InputError
from rancf.solvers.arc_length import arc_length_path
from rancf.solvers.curved_cable import curved_cable_causes
from rancf.solvers.drum_statics import free_drums
from rancf.solvers.linear_static import LINEAR, solve_linear
from rancf.solvers.load_control import load_control_path
from rancf.solvers.load_path import PathState
from rancf.solvers.relaxation import relax
from rancf.solvers.sag_start import SAG_START, clamped_lines, solve_from_sag, touchdown_causes
from rancf.solvers.static_checks import check_state, instability
from rancf.solvers.static_friction import with_friction
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import System, as_system
from rancf.system.drums import hold_drums, refuse_static_drums

__all__ = ["StaticResult", "solve_static", "solve_equilibrium", "StaticMethod"]

StaticMethod = Literal["load", "arc_length", "linear"]

#: ``StaticResult.method`` when a stage was finished by relaxation.
RELAXED = "relaxation+newton"


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
        Newton iterations, factorizations (one per Newton iteration and per pseudo-time step of
        a relaxation) and extra residual evaluations (line searches, relaxation).
    wall_time : float
    method : str
        ``"load"``, ``"arc_length"``, ``"linear"`` (:mod:`rancf.solvers.linear_static`), or
        ``"relaxation+newton"`` when a stage was finished by relaxation and Newton (its path
        then ends with the load factor the method reached and the stage's end).
    relaxation_steps : int
        Pseudo-time steps of the relaxation (0 without).
    """

    q: NDArray[np.float64]
    y: NDArray[np.float64]
    load_factors: NDArray[np.float64]
    n_newton: int
    n_factorizations: int
    wall_time: float
    n_residuals: int = 0
    method: str = "load"
    #: The joints' multipliers at the end of the path (``-Gᵀ λ``: their reactions); empty
    #: without joints.
    lam: NDArray[np.float64] | None = None
    relaxation_steps: int = 0
    #: Per line touching a seabed, the largest ratio of an element's length to the bend radius
    #: at a touchdown in it and that element's length
    #: (:attr:`~rancf.solvers.static_checks.StateCheck.touchdowns`), once the state has passed
    #: the checks (None before).
    touchdowns: dict[str, tuple[float, float]] | None = None
    #: Warning lines of the solve (without ``rancf: warning:``): an arc-length path that ends
    #: in an unstable state; ``rancf static`` prints them as its other warnings.
    warnings: tuple[str, ...] = ()


def solve_static(
    model: Model | System,
    load_steps: int = 10,
    tol: float = 1e-10,
    max_iter: int = 30,
    on_step: Callable[[float, NDArray[np.float64]], None] | None = None,
    method: StaticMethod = "load",
    at_time: float | None = None,
    static_friction: bool = False,
) -> StaticResult:
    """Static equilibrium under the model's loads and installed supports (a model: of the
    system of that one body, :func:`rancf.system.as_system`).

    ``at_time``: loads as they act at that time (the start of a dynamic run, ``0``) instead of
    their amplitudes.

    ``static_friction``: the seabeds' friction fully mobilized toward the anchors, as MoorPy's
    (:mod:`rancf.solvers.static_friction`); default frictionless.

    ``on_step(λ, y)`` is called with the reference (``λ = 0``) and after every converged step,
    with the model coordinates ``y`` (the load path; rods: the model's triads are those of ``y``
    at the call).

    Raises
    ------
    ConvergenceError
        With the load factor reached, if the method fails and relaxation finds no rest either
        (a body with no equilibrium: a pendulum without its pin).
    """
    if isinstance(load_steps, bool) or int(load_steps) != load_steps or load_steps < 1:
        raise InputError("solver.load_steps", load_steps, "an integer >= 1")
    if method not in ("load", "arc_length", "linear"):
        raise InputError("solver.static_method", method, 'one of "load", "arc_length", "linear"')
    start = time.perf_counter()
    system = as_system(model)
    system.reset_triads()
    system.static_friction = False  # type: ignore[attr-defined]  # the outputs' reactions
    system.linear_reference = None  # type: ignore[attr-defined]  # (set by a linear solve)
    if method == "linear":  # one step from the reference (rancf.solvers.linear_static)
        z, end, said = solve_linear(system, at_time, on_step, static_friction)
        n = system.n
        y, lam, dt = z[:n], z[n:], time.perf_counter() - start
        q, path = system.q_from_y(y), np.array([0.0, end])
        return StaticResult(q, y, path, 1, 1, dt, method=LINEAR, lam=lam, warnings=said)
    if static_friction:
        if getattr(system, "drums", None):
            raise InputError("solver.static_friction", True, "false with drums")
        res = solve_static(system, load_steps, tol, max_iter, on_step, method, at_time)
        return _checked(system, with_friction(system, res, at_time, tol, max_iter, on_step))
    if not getattr(system, "drums", None):
        first = None
        rejected: list[str] = []  # what the sagged start found, said if nothing else converges
        if method == "load":
            first = _sagged(system, at_time, tol, max_iter, on_step, start, True, rejected)
        if first is not None:
            return _checked(system, first)
        again = method != "load" or clamped_lines(system)  # a start not tried yet
        try:
            res = solve_equilibrium(
                SystemEquilibrium(system, at_time),
                load_steps,
                tol,
                max_iter,
                on_step,
                method,
                start,
            )
        except ConvergenceError as exc:
            late = _sagged(system, at_time, tol, max_iter, on_step, start) if again else None
            if late is None:
                why = [str(exc), *rejected[:1], *touchdown_causes(system)]
                why += curved_cable_causes(system)
                raise ConvergenceError("; ".join(why), exc.reached) from exc
            return _checked(system, late)
        if again:
            report = check_state(system, res.q)
            if not report.problems and not instability(system, res.y, res.lam):
                return replace(res, touchdowns=report.touchdowns)  # checked, and stable
            res = _sagged(system, at_time, tol, max_iter, on_step, start) or res
        return _checked(system, res)
    hold_drums(system, True)  # driven drums: the line loaded at their start lengths first
    try:
        held = solve_equilibrium(
            SystemEquilibrium(system, at_time), load_steps, tol, max_iter, on_step, method, start
        )
    finally:
        hold_drums(system, False)
    scale = SystemEquilibrium(system, at_time).scale  # then the lengths where r T = torque
    held_lam = np.zeros(0) if held.lam is None else held.lam  # no constraints: none
    y, lam, ok, its = free_drums(system, held.y, held_lam, at_time, scale, tol, max_iter)
    refuse_static_drums(system, y if ok else None, at_time)
    done = replace(
        held,
        q=system.q_from_y(y),
        y=y,
        lam=lam,
        n_newton=held.n_newton + its,
        n_factorizations=held.n_factorizations + its,
        wall_time=time.perf_counter() - start,
    )
    return _checked(system, done)


def _sagged(
    system: System,
    at_time: float | None,
    tol: float,
    max_iter: int,
    on_step: Callable[[float, NDArray[np.float64]], None] | None,
    start: float,
    pinned: bool = False,
    rejected: list[str] | None = None,
) -> StaticResult | None:
    """The equilibrium from a sagged start shape (:mod:`rancf.solvers.sag_start`; ``pinned``:
    of the lines without a clamped end only), or None when no line has one or none is found
    from it that passes the checks (the first problem of a state it found then goes to
    ``rejected``)."""
    found = solve_from_sag(system, at_time, tol, max_iter, pinned)
    if found is None:
        return None
    z, end, its, facts, resid, steps = found
    n = system.n
    res = StaticResult(
        system.q_from_y(z[:n]),
        z[:n],
        np.array([0.0, end]),
        its,
        facts,
        time.perf_counter() - start,
        resid,
        SAG_START,
        z[n:],
        steps,
    )
    report = check_state(system, res.q)
    if report.problems:
        if rejected is not None:
            rejected.append(
                f"from its sagged start shape it came to a state that is no "
                f"equilibrium: {report.problems[0]}"
            )
        return None
    if on_step is not None:
        on_step(float(res.load_factors[-1]), res.y)
    return replace(res, touchdowns=report.touchdowns)


def _checked(system: System, res: StaticResult) -> StaticResult:
    """``res`` with its touchdowns if its state passes
    :func:`~rancf.solvers.static_checks.check_state` (a result that has them passed already);
    else :class:`~rancf.errors.ConvergenceError` naming the first problem (one line).  Then
    its stability (:func:`~rancf.solvers.static_checks.instability`): an unstable state is
    refused the same way, or, at the end of an arc-length path (which passes unstable states
    on purpose), kept with a warning line (:attr:`StaticResult.warnings`)."""
    lam = float(res.load_factors[-1])
    if res.touchdowns is None:
        report = check_state(system, res.q)
        if report.problems:
            raise ConvergenceError(
                f"static equilibrium not found: the {res.method} path ended at load factor "
                f"{lam:.4g} in a state that is no equilibrium: {report.problems[0]}",
                reached=lam,
            )
        res = replace(res, touchdowns=report.touchdowns)
    why = instability(system, res.y, res.lam)
    if why and res.method == "arc_length":  # a path traced past a limit point: said, kept
        why = why.split("; try")[0]  # the hints: load steps, imperfection, arc length
        res = replace(res, warnings=(*res.warnings, f"the arc-length path ends in an {why}"))
    elif why:
        raise ConvergenceError(
            f"static equilibrium not found: the {res.method} path ended at load factor "
            f"{lam:.4g} in an {why}",
            reached=lam,
        )
    return res


def solve_equilibrium(
    problem: SystemEquilibrium,
    load_steps: int = 10,
    tol: float = 1e-10,
    max_iter: int = 30,
    on_step: Callable[[float, NDArray[np.float64]], None] | None = None,
    method: StaticMethod = "load",
    start: float | None = None,
) -> StaticResult:
    """The path of a static ``problem`` (its system's rod triads reset before it was built),
    by the method of :func:`solve_static`, timed from ``start`` (default now)."""
    start = time.perf_counter() if start is None else start
    system = problem.system
    path = PathState(problem, on_step)
    used: str = method
    for stage, (_, end) in enumerate(problem.stages):
        problem.stage = stage
        path.prev = None  # no predictor across the stages' kink
        if stage == 0 and problem.mechanism(path.y):
            _relax(problem, path, end, tol, max_iter, None)
            used = RELAXED
            continue
        try:
            if method == "load":
                load_control_path(problem, path, end, 1.0 / load_steps, tol, max_iter)
            else:
                arc_length_path(problem, path, end, 1.0 / load_steps, tol, max_iter)
        except ConvergenceError as exc:
            _relax(problem, path, end, tol, max_iter, exc)
            used = RELAXED
    z = path.y
    return StaticResult(
        system.q_from_y(z[: system.n]),
        z[: system.n],
        np.array(path.factors),
        path.n_newton,
        path.n_newton + path.n_relax_factorizations,  # one per Newton iteration or Δτ step
        time.perf_counter() - start,
        path.n_residuals,
        used,
        z[system.n :],
        path.n_relax,
    )


def _relax(
    problem: SystemEquilibrium,
    path: PathState,
    end: float,
    tol: float,
    max_iter: int,
    failed: ConvergenceError | None,
) -> None:
    """Finish a stage the path method gave up on (``failed``; None: a mechanism at its reference,
    the path not tried) by relaxation at its end (module docstring)."""
    out = relax(problem, path.y, end, tol, max_iter, polish_at_start=failed is not None)
    path.count(out.newton_iterations, out.residuals)
    path.n_relax += out.steps
    path.n_relax_factorizations += out.factorizations - out.newton_iterations
    if not out.converged:
        raise ConvergenceError(
            f"static equilibrium not found: the load path stopped at load factor "
            f"{path.lam:.4g}, and relaxation under the full load found no rest: {out.reason}",
            reached=path.lam,
        ) from failed
    path.accept(out.z, end)
