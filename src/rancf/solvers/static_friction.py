"""Seabed friction in statics (``[solver] static_friction``), as MoorPy's catenary has it.

Statics are frictionless by default: the contact's regularized Coulomb friction
(:mod:`rancf.system.contact`) needs a slip velocity, and a static state has none.  With
``static_friction`` the friction of every *seabed* (a fixed ``plane`` obstacle the body's weight
presses on, :func:`rancf.system.seabed.pressing_weight`) is fully mobilized toward the line's
anchor, as in MoorPy (``moorpy.Catenary.catenary`` with ``CB``): along the length ``L_B`` lying
on the seabed the tension drops by ``μ p`` per length (``p`` the contact pressure, the wet weight
``w`` on a flat bed), down to ``T_anchor = max(H − μ w L_B, 0)``; where it would go negative the
friction is only what keeps the tension at zero.

The anchor of a body is its end node lower along the plane's normal; the friction per length
``−μ p t̂`` (``t̂`` the line's tangent projected on the plane, pointing away from the anchor) is
the contact's own friction at a slip velocity ``10⁶ ε`` along ``t̂`` (``Contact.assemble``:
``μ p`` within 1e-12).  Walking from the touchdown toward the anchor, the nodes' shares of it are
cut once their sum reaches the axial force at the touchdown (the cap of ``T ≥ 0``).  The force is
a constant load of a fixed point: solve, evaluate the friction at the equilibrium, solve again
with it (Newton from the last state at the end of the load path), until it changes by less than
:data:`FRICTION_RTOL` of itself, or stalls below :data:`FRICTION_FLOOR` of itself (the change no
smaller than the last: where the friction takes the whole tension, the cut at the nodes follows
the touchdown's axial force, which the Newton tolerance leaves uncertain by ~1e-7 of it, e.g. a
500 m line with ``μ = 5``); :data:`MAX_FRICTION_ITERATIONS` at most, else
:class:`~rancf.errors.ConvergenceError`.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import ConvergenceError
from rancf.solvers.newton import newton
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system.seabed_friction import seabed_friction

__all__ = [
    "FRICTION",
    "with_friction",
    "seabed_friction",
    "FrictionEquilibrium",
    "solve_with_friction",
    "FRICTION_RTOL",
    "FRICTION_FLOOR",
    "MAX_FRICTION_ITERATIONS",
]

#: The fixed point stops when the friction force changes by less than this (relative).
FRICTION_RTOL = 1e-8
#: ... or stalls (changes no less than at the last iteration) below this (module docstring).
FRICTION_FLOOR = 1e-6
#: Fixed-point iterations at most.
MAX_FRICTION_ITERATIONS = 50


class FrictionEquilibrium(SystemEquilibrium):
    """:class:`SystemEquilibrium` with a constant generalized load ``load`` (the friction)."""

    def __init__(self, system, at_time: float | None, load: NDArray) -> None:
        super().__init__(system, at_time)
        self.load = np.r_[load, np.zeros(self.m)]

    def full_residual(self, z: NDArray, p: float) -> NDArray[np.float64]:
        return super().full_residual(z, p) - self.load

    def tangent(self, z: NDArray, p: float) -> tuple[NDArray, bool]:
        r, ok = super().tangent(z, p)
        r -= self.load
        r[self.fixed] = 0.0
        return r, ok


def solve_with_friction(
    system, z: NDArray, p: float, at_time: float | None, tol: float, max_iter: int
) -> tuple[NDArray, int]:
    """The equilibrium with seabed friction from the frictionless one ``z`` (``(y, μ)`` at path
    parameter ``p``, the end of the path): ``(z, Newton iterations)`` (module docstring)."""
    probe = SystemEquilibrium(system, at_time)
    stage = len(probe.stages) - 1
    load = np.zeros(system.n)
    its = 0
    last = np.inf
    for _ in range(MAX_FRICTION_ITERATIONS):
        new = seabed_friction(system, z[: system.n])
        change, size = float(np.linalg.norm(new - load)), float(np.linalg.norm(new))
        stalled = last <= change <= FRICTION_FLOOR * size
        if change <= FRICTION_RTOL * size or stalled or not np.any(new):
            return z, its
        load, last = new, change
        problem = FrictionEquilibrium(system, at_time, load)
        problem.stage = stage
        out = newton(problem, z, p, tol, max_iter)
        its += out.iterations
        if not out.converged:
            raise ConvergenceError(
                "static equilibrium with seabed friction (solver.static_friction) not found: "
                "Newton failed under the friction of the last state",
                reached=p,
            )
        z = out.y
        problem.accept(z)
    raise ConvergenceError(
        f"static equilibrium with seabed friction (solver.static_friction) not found: the friction "
        f"still changed by {change / max(float(np.linalg.norm(new)), 1e-300):.2g} after "
        f"{MAX_FRICTION_ITERATIONS} iterations",
        reached=p,
    )


#: Appended to ``StaticResult.method`` when the seabeds' friction acted (``static_friction``).
FRICTION = "+friction"


def with_friction(
    system: Any,
    res: Any,
    at_time: float | None,
    tol: float,
    max_iter: int,
    on_step: Callable[[float, NDArray[np.float64]], None] | None,
) -> Any:
    """The frictionless equilibrium ``res`` (a :class:`~rancf.solvers.static.StaticResult`)
    carried to the equilibrium with seabed friction (:func:`solve_with_friction`), its
    ``method`` ending in :data:`FRICTION`, unchecked (``touchdowns`` None); ``res`` itself
    where the friction does not act."""
    p = float(res.load_factors[-1])
    z, its = solve_with_friction(system, np.r_[res.y, res.lam], p, at_time, tol, max_iter)
    if its == 0:
        return res
    system.static_friction = True
    n = system.n
    if on_step is not None:
        on_step(p, z[:n])
    return replace(
        res,
        q=system.q_from_y(z[:n]),
        y=z[:n],
        lam=z[n:],
        method=res.method + FRICTION,
        n_newton=res.n_newton + its,
        n_factorizations=res.n_factorizations + its,
        load_factors=np.r_[res.load_factors, p],
        touchdowns=None,  # a new state: checked again
    )
