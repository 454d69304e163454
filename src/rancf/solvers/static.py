"""Static equilibrium ``f_int(y) = λ f_ext`` by Newton with load stepping.

The Newton iterations (exact tangent, band LU with partial pivoting) run in the compiled core.

The load factor ``λ`` rises from 0 to 1 in ``load_steps`` equal increments; an increment whose
Newton iteration fails is halved (down to ``1e-4`` of the nominal increment).  Loads are gravity
and every point load at its amplitude ``F0`` (harmonic loads count with their amplitude).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.errors import ConvergenceError, InputError
from rancf.model.system import Model

__all__ = ["StaticResult", "solve_static"]


@dataclass(frozen=True)
class StaticResult:
    """Equilibrium configuration and counters."""

    q: NDArray[np.float64]
    y: NDArray[np.float64]
    load_factors: NDArray[np.float64]
    n_newton: int
    n_factorizations: int
    wall_time: float


def solve_static(
    model: Model,
    load_steps: int = 10,
    tol: float = 1e-10,
    max_iter: int = 25,
    on_step: Callable[[float, NDArray[np.float64]], None] | None = None,
) -> StaticResult:
    """Static equilibrium under the model's loads.

    ``on_step(λ, y)`` is called with the reference (``λ = 0``) and after every converged load
    increment, with the model coordinates ``y`` (the load path; rods: the model's triads are
    those of ``y`` at the call).

    Raises
    ------
    ConvergenceError
        With the load factor reached, if an increment fails even when halved repeatedly (for
        example a mechanism: a pendulum has no static equilibrium near its reference).
    """
    if int(load_steps) != load_steps or load_steps < 1:
        raise InputError("solver.load_steps", load_steps, "an integer >= 1")
    start = time.perf_counter()
    model.reset_triads()
    size = float(np.ptp(model.node_positions(model.q0), axis=0).max()) or 1.0
    y = model.y0.copy()
    lam, dlam = 0.0, 1.0 / load_steps
    factors = [0.0]
    n_newton = 0
    if on_step is not None:
        on_step(0.0, y)
    while lam < 1.0 - 1e-12:
        target = min(1.0, lam + dlam)
        if target > 1.0 - 1e-12:
            target = 1.0  # the last increment ends at the full load, not 1 - rounding
        trial = y.copy()
        converged, n_iter, _ = model.core.static_newton(trial, target, tol * size, max_iter)
        n_newton += n_iter
        if converged:
            y, lam = trial, target
            factors.append(lam)
            if on_step is not None:
                on_step(lam, y)
            continue
        dlam *= 0.5
        if dlam < 1e-4 / load_steps:
            raise ConvergenceError(
                f"static Newton iteration did not converge beyond load factor {lam:.4g} "
                "(is the model a mechanism, or the load beyond a limit point?)",
                reached=lam,
            )
    return StaticResult(
        model.q_from_y(y),
        y,
        np.array(factors),
        n_newton,
        n_newton,  # one band LU factorization per Newton iteration
        time.perf_counter() - start,
    )
