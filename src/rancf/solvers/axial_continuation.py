"""Newton's method for stiff slack lines by continuation in their axial stiffness.

A line whose axial stiffness ``EA`` is many orders above its tension is nearly inextensible: a
transverse move ``δ`` of a node stretches its elements (length ``ℓ``) by about ``δ² / 2ℓ²``,
which costs the axial force ``EA δ² / 2ℓ²``.  Newton's method converges quadratically only
within ``δ ≈ ℓ sqrt(2T / EA)`` of the equilibrium (``T`` the tension); farther away each step
along the tangent of the nearly inextensible shapes leaves them and the next step mostly undoes
that.  MoorPy's U-shaped line (130 m, 100 N/m, ``EA = 1e12`` N, ``T`` 263 to 2260 N,
``EA / T = 4e9``; docs/guide/statics.md, "Static solve time per case") starts from its
catenary 4 cm from its equilibrium (the heavy elastica of its bending stiffness) and needs
about 200 Newton iterations from there at 320 elements, whatever the mesh; with ``EA`` a
hundred times lower, 23, and with ``1e4`` times lower, 12.

So the sagged start (:mod:`rancf.solvers.sag_start`) of a system with a slack line whose
``EA`` exceeds :data:`STIFF_RATIO` times its weight ``W`` (its elements' weights in the start
shape, buoyancy counted where they are under water: :func:`rancf.system.seabed.element_weights`)
solves with the ``EA`` of every such
line lowered to :data:`START_RATIO` ``W`` first, then raises it :data:`RISE` times per Newton
solve, each from the last state, to its own value: the equilibria of neighbouring stiffnesses
lie within each other's quadratic convergence.  The intermediate solves stop at the scaled increment
:data:`STAGE_TOL` (the next one goes on from there), the last at the solver's tolerance; each has at
most :data:`STAGE_ITERATIONS` iterations, and a failed one ends the continuation (the caller then
goes on from the start shape without it).  The model's ``EA`` is restored in every case.
Equilibria are those of the line's own ``EA``: the continuation is a path to them, not a
change of the model.
"""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.length import unstretched_length
from rancf.solvers.newton import NewtonOutcome, newton
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system.seabed import element_weights

__all__ = [
    "STIFF_RATIO",
    "START_RATIO",
    "RISE",
    "STAGE_TOL",
    "STAGE_ITERATIONS",
    "stiff_lines",
    "continued_newton",
]

#: A line whose ``EA`` exceeds this multiple of its weight is continued in ``EA``.
STIFF_RATIO = 1.0e6
#: The first solve's ``EA``: this multiple of the line's weight.
START_RATIO = 1.0e4
#: ``EA`` grows by this factor per solve (a factor 100 failed on MoorPy's half U).
RISE = 10.0
#: Scaled increment at which an intermediate solve stops.
STAGE_TOL = 1.0e-6
#: Newton's iterations per solve at most.
STAGE_ITERATIONS = 40


def _weight(system: Any, name: str, z: NDArray[np.float64]) -> float:
    """The weight [N] of body ``name`` in the system's state ``z``: the magnitudes of its
    elements' weights per length (:func:`rancf.system.seabed.element_weights`, buoyancy counted
    where they are under water) times their unstretched lengths."""
    model = system.bodies[name]
    q = model.q_from_y(z[system.body_slice(name)])
    w = np.linalg.norm(element_weights(system, name, q), axis=1)
    ell = model.mesh.arc_lengths()
    return float(w @ ell) * unstretched_length(model) / float(ell.sum())


def stiff_lines(
    system: Any, names: list[str], z: NDArray[np.float64]
) -> list[tuple[Any, float, float]]:
    """``(core, EA, W)`` of every body in ``names`` whose ``EA`` exceeds :data:`STIFF_RATIO`
    times its weight ``W`` in the state ``z`` (module docstring)."""
    out = []
    for name in names:
        model = system.bodies[name]
        w = _weight(system, name, z)
        ea = float(model.core.axial_stiffness)
        if w > 0.0 and ea > STIFF_RATIO * w:
            out.append((model.core, ea, w))
    return out


@contextmanager
def _lowered(lines: list[tuple[Any, float, float]]) -> Iterator[None]:
    """The lines' ``EA`` restored however the block ends."""
    try:
        yield
    finally:
        for core, ea, _ in lines:
            core.axial_stiffness = ea


def continued_newton(
    problem: SystemEquilibrium,
    z: NDArray[np.float64],
    p: float,
    tol: float,
    lines: list[tuple[Any, float, float]],
) -> NewtonOutcome:
    """Newton's method for ``r(z, p) = 0`` from ``z`` with the ``lines``' axial stiffness
    continued from :data:`START_RATIO` times their weight to their own (each at most its own;
    module docstring): the outcome of the last solve with the iterations and residuals of all
    of them."""
    level = START_RATIO  # EA over weight of the solve, each line at most its own
    iterations = residuals = 0
    with _lowered(lines):
        while True:
            last = all(level * w >= ea for _, ea, w in lines)
            for core, ea, w in lines:
                core.axial_stiffness = min(ea, level * w)
            out = newton(problem, z, p, tol if last else max(tol, STAGE_TOL), STAGE_ITERATIONS)
            iterations += out.iterations
            residuals += out.residuals
            if last or not out.converged:
                return NewtonOutcome(out.converged, out.y, iterations, residuals, out.increment)
            z = out.y
            level *= RISE
