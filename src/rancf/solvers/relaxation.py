"""Pseudo-transient continuation: the equilibrium a structure comes to rest in, where Newton's
method along the load path cannot start or stalls (a mechanism under gravity, a slack rope).

The derivation is in ``docs/derivations/relaxation.md``.  With the loads at the end of the
stage (``p``), the state follows the motion whose damping overwhelms its inertia,

    M dz/dτ = -r(z, p),        g(z) = 0        (the multipliers: the joints' forces),

along which the potential energy falls (``dV/dτ = -żᵀ M ż``), so it ends in a stable
equilibrium.  Each pseudo-time step is a backward Euler step linearized at ``z_k``
(Kelley & Keyes, "Convergence analysis of pseudo-transient continuation", SIAM J. Numer.
Anal. 35 (1998) 508–523, eq. 1.3):

    [M/Δτ + K   Gᵀ] [Δy]     [r_y]
    [G          0 ] [Δμ] = - [g  ],

the bordered tangent of the statics with ``M/Δτ`` added
(:meth:`~rancf.solvers.system_equilibrium.SystemEquilibrium.damped_tangent`).  The pseudo-time
step grows as the residual falls (switched evolution relaxation, Mulder & van Leer, "Experiments
with implicit upwind methods for the Euler equations", J. Comput. Phys. 59 (1985) 232–246):
``Δτ_{k+1} = Δτ_k |r_k| / |r_{k+1}|`` (balance rows), so the steps become Newton's steps near the
equilibrium; a step that moves any coordinate by more than :data:`MAX_MOVE` of the model size
(scaled norm) is taken again with a shorter ``Δτ``.  Whenever the residual has fallen by
:data:`POLISH_DROP` since the last try, Newton's method (:func:`rancf.solvers.newton.newton`)
polishes the state at the full load to the solver's tolerance.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from rancf.solvers.newton import newton

if TYPE_CHECKING:
    from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = ["RelaxationOutcome", "relax", "MAX_STEPS", "MAX_MOVE", "DRIFT"]

#: Largest number of pseudo-time steps.
MAX_STEPS = 500
#: Largest scaled increment of a pseudo-time step (positions relative to the model size).
MAX_MOVE = 0.1
#: A state this many model sizes away from its start has no equilibrium to come to rest in.
DRIFT = 10.0
#: Newton polishes once the residual has fallen by this factor since its last try.
POLISH_DROP = 1e-2
#: The first ``1/Δτ`` relative to the largest stiffness-to-mass ratio of the diagonals.
FIRST_RATE = 1e-6


@dataclass(frozen=True)
class RelaxationOutcome:
    """How a relaxation ended: the last state, whether Newton polished it, the pseudo-time
    steps taken, Newton's iterations, the factorizations (pseudo-time steps taken again with a
    shorter ``Δτ`` and Newton's included), the extra residuals and, on failure, why (one
    line)."""

    converged: bool
    z: NDArray[np.float64]
    steps: int
    newton_iterations: int
    factorizations: int
    residuals: int
    reason: str = ""


def relax(
    problem: SystemEquilibrium,
    z: NDArray,
    p: float,
    tol: float,
    max_iter: int,
    polish_at_start: bool = True,
    max_steps: int = MAX_STEPS,
) -> RelaxationOutcome:
    """Follow ``M dz/dτ = -r(z, p)`` from ``z`` to rest, then polish by Newton (module
    docstring).  ``z`` is not modified; the supports are placed at ``p``.

    ``polish_at_start``: Newton's first try is at ``z`` (where a load path stalled: the
    equilibrium may be near); False: only once the residual has fallen by
    :data:`POLISH_DROP` (a mechanism's reference, whose tangent is singular: Newton's step
    there is round-off's).  ``max_steps``: the pseudo-time steps before giving up."""
    z = np.array(z, dtype=float)
    problem.place_supports(z, p)
    start = z.copy()
    n = problem.n
    free = problem.free[:n]

    def balance(r: NDArray) -> float:
        return float(np.linalg.norm(r[:n][free]))

    rate = FIRST_RATE * problem.stiffness_scale(z)  # 1/Δτ
    r = problem.residual(z, p)
    norm = balance(r)
    tried = np.inf if polish_at_start else norm  # the residual at the last Newton try
    steps = iterations = factorizations = residuals = 0
    for _ in range(4 * max_steps):
        if norm <= POLISH_DROP * tried or not norm > 0.0:
            out = newton(problem, z, p, tol, max_iter)
            iterations += out.iterations
            factorizations += out.iterations
            residuals += out.residuals
            if out.converged:
                return RelaxationOutcome(True, out.y, steps, iterations, factorizations, residuals)
            tried = norm
        if steps >= max_steps:
            break
        r, ok = problem.damped_tangent(z, p, rate)
        factorizations += 1
        dz = problem.solve(ok, -r)
        move = np.inf if dz is None else float(np.max(np.abs(dz * problem.scale)))
        if not move <= MAX_MOVE:  # too long (or singular): a shorter pseudo-time step
            rate *= 4.0 if not np.isfinite(move) else 1.5 * move / MAX_MOVE
            continue
        z += dz
        problem.accept(z)
        steps += 1
        if float(np.max(np.abs((z - start) * problem.scale))) > DRIFT:
            return RelaxationOutcome(
                False,
                z,
                steps,
                iterations,
                factorizations,
                residuals,
                (
                    f"it moved more than {DRIFT:g} times its size without coming to rest: a "
                    "mechanism with no equilibrium, add a support"
                ),
            )
        new = balance(problem.residual(z, p))
        residuals += 1
        if not np.isfinite(new):
            return RelaxationOutcome(
                False, z, steps, iterations, factorizations, residuals, "the residual is not finite"
            )
        rate *= min(new / norm, 2.0) if norm > 0.0 else 0.5  # SER: Δτ ∝ 1/|r|
        if move < 0.25 * MAX_MOVE:
            rate *= 0.5  # a short step: the pseudo-time step may grow
        norm = new
    why = f"it did not come to rest in {max_steps} pseudo-time steps"
    return RelaxationOutcome(False, z, steps, iterations, factorizations, residuals, why)
