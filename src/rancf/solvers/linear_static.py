"""Linear (small-displacement) statics: ``solver.static_method = "linear"``.

The answer of the linear benchmarks (MacNeal & Harder's Scordelis-Lo roof, pinched cylinder and
hemisphere, run with Abaqus' ``NLGEOM=OFF``): the one solution of

    K(z₀) Δz = -r(z₀, p_end),

``z₀`` the reference (zero multipliers), ``r`` and ``K`` the residual and tangent of the static
problem (:class:`~rancf.solvers.system_equilibrium.SystemEquilibrium`: the same assembly as the
nonlinear path, with the joints' constraints) at the end of the load path ``p_end`` (the full
loads; with installed supports, the held coordinates at their installed values).  It is one
Newton step of the ordinary static solver (:func:`rancf.solvers.newton.newton`) from the
reference, without its line search and without stabilizing a singular tangent.  The state is
``z₀ + Δz``: positions, sensors and the reactions (the multipliers of that solve, the linear
reactions ``-Gᵀ μ``) follow from it.

The state is no equilibrium of the nonlinear balance, so the nonlinear checks (residual,
folds, stability) are not applied.  A structure that is a mechanism at its reference
(:meth:`~rancf.solvers.system_equilibrium.SystemEquilibrium.mechanism`: a straight cable with
no bending stiffness, a pendulum) or whose tangent is singular has no linear answer: one line
says so.  Where the displacement is large for a linear analysis (a rotation above
:data:`LARGE_ROTATION` or a deflection beyond the section's size: a shell's thickness, a line's
diameter), a warning says that the nonlinear solve differs.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.shell_model import ShellModel
from rancf.errors import InputError
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system import System

__all__ = ["solve_linear", "LARGE_ROTATION", "LINEAR", "refuse_linear_start"]

#: ``StaticResult.method`` of a linear analysis.
LINEAR = "linear"

#: A rotation [rad] beyond which a linear answer is warned of (small-angle error ~ θ²/6).
LARGE_ROTATION = 0.1
#: A rotation [rad] beyond which a linear answer is refused: a gradient of unit length turned by
#: as much as itself is no small displacement (a slack line's reference, not its sag).
NO_LINEAR_ROTATION = 1.0

_NONLINEAR = 'use the nonlinear statics (solver.static_method = "load")'


def solve_linear(
    system: System,
    at_time: float | None,
    on_step: Callable[[float, NDArray[np.float64]], None] | None,
    static_friction: bool = False,
) -> tuple[NDArray[np.float64], float, tuple[str, ...]]:
    """The linear static state of ``system`` (module docstring): ``(z, p_end, warnings)``,
    ``z`` its model coordinates and multipliers.  ``on_step`` is called with the reference and
    the solution.

    Raises
    ------
    InputError
        With ``static_friction`` or drums (the nonlinear solve's), or
        ``solver.static_method = "linear"`` where the structure is a mechanism at its reference
        or its tangent is singular.
    """
    if static_friction:
        raise InputError("solver.static_friction", True, f'false with static_method = "{LINEAR}"')
    if getattr(system, "drums", None):
        raise InputError("solver.static_method", LINEAR, '"load" or "arc_length" with drums')
    problem = SystemEquilibrium(system, at_time)
    z0 = problem.start()
    n = system.n
    if on_step is not None:
        on_step(0.0, z0[:n])
    if problem.mechanism(z0):
        raise InputError(
            "solver.static_method",
            LINEAR,
            "a structure that is stiff at its reference; the loads meet no stiffness there (a "
            f"mechanism, or a straight line without bending stiffness): {_NONLINEAR}",
        )
    problem.stage = len(problem.stages) - 1
    end = problem.stages[-1][1]
    z = z0.copy()
    problem.place_supports(z, end)
    r, ok = problem.exact_tangent(z, end)
    dz = problem.solve(ok, -r)
    if dz is None or not np.all(np.isfinite(r)):
        raise InputError(
            "solver.static_method",
            LINEAR,
            f"a structure whose tangent stiffness at its reference is regular; it is singular "
            f"there: {_NONLINEAR}",
        )
    z += dz
    problem.accept(z)
    system.linear_reference = (z0, problem.scale)  # type: ignore[attr-defined]  # the outputs' reactions
    if on_step is not None:
        on_step(end, z[:n])
    return z, end, large_displacement(system, z0[:n], z[:n])


def large_displacement(
    system: System, y0: NDArray[np.float64], y: NDArray[np.float64]
) -> tuple[str, ...]:
    """Warning lines where the linear displacement ``y - y0`` (model coordinates) of a flexible
    body is large: its largest position change beyond its section's size (a shell's thickness,
    a line's diameter), or its largest change of a gradient (of unit length at the reference:
    the rotation, to first order) beyond :data:`LARGE_ROTATION`.

    Raises
    ------
    InputError
        Where a rotation exceeds :data:`NO_LINEAR_ROTATION`: the linear answer means nothing.
    """
    out = []
    for name, body in zip(system.names, system.flex, strict=False):
        sl = system.body_slice(name)
        d = np.asarray(y[sl] - y0[sl])
        pos = body.position_mask()
        shell = isinstance(body, ShellModel)
        if isinstance(body, ShellModel):
            size = float(body.body.thickness)
        else:
            size = 2.0 * float(body.section.radius)
        x = d[pos].reshape(-1, system.dim)
        moved = float(np.max(np.linalg.norm(x, axis=1), initial=0.0))
        gradients = shell or body.family.gradient  # else rotation parameters, not checked
        turn = float(np.max(np.abs(d[~pos]), initial=0.0)) if gradients else 0.0
        if turn > NO_LINEAR_ROTATION:
            raise InputError(
                "solver.static_method",
                LINEAR,
                f"small displacements: body {name!r} turns by about {turn:.3g} rad and moves "
                f"{moved:.4g} m in the linear answer, which means nothing there: {_NONLINEAR}",
            )
        if moved > size or turn > LARGE_ROTATION:
            out.append(
                f"body {name!r}: the linear displacement is large (deflection {moved:.4g} m, "
                f"{moved / size:.3g} times the section's size {size:.4g} m; rotation about "
                f'{turn:.3g} rad): a nonlinear solve (solver.static_method = "load") differs'
            )
    return tuple(out)


def refuse_linear_start(options: dict[str, object], what: str) -> None:
    """Refuse a linear static state (``options``: the keywords of
    :func:`~rancf.solvers.static.solve_static`) as the start of ``what`` (a dynamic run,
    modes or buckling about the static equilibrium): it is no equilibrium of the nonlinear
    balance, which those analyses start from (a run would start with a jolt)."""
    if options.get("method") == LINEAR:
        raise InputError(
            "solver.static_method",
            LINEAR,
            f'"load" or "arc_length" for {what}: the linear state is no equilibrium of the '
            "nonlinear balance they start from",
        )
