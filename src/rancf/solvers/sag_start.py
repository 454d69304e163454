"""A sagged start shape for lines longer than the chord between their held ends, where the load
path ends in a state that is no equilibrium (a compressive loop, a folded element) or fails.

A line drawn straight and installed with its ends closer than its length, or drawn as a shape
far from its sag, may be led by the load path into a root of the residual no real line rests
in (:mod:`rancf.solvers.static_checks`).  :func:`solve_from_sag` starts again from the shape
the line would hang in: for every cable body (``"rancf"``/``"ancf"`` elements) whose two end
nodes hold their positions (supports, installed where they are installed) and whose reference
arc length ``L`` (its unstretched length: :func:`rancf.bodies.length.unstretched_length`)
exceeds the chord between them, the inextensible catenary of length ``L``
between the installed end positions in the vertical plane through them (vertical: against the
body's wet weight per length, its weight less its buoyancy in a ``[fluid]`` where it has
``hydro`` coefficients, :func:`rancf.system.seabed.wet_weight`: a buoyant line arches up, the
catenary flipped; a line as heavy as the water it displaces has none, unless it crosses the
free surface).  A hanging line crossing the free surface starts on the catenary of each
element's weight with its share under water (:func:`rancf.system.seabed.element_weights`,
:func:`rancf.solvers.static_catenary.weighted_catenary`), the shares taken again in that shape
until they repeat.  Where that
catenary dips below a fixed plane facing up (against that weight) that the body touches (a
seabed), the shape is instead two catenaries from the ends down to touchdown points, where
they are tangent to the plane, and the line straight on the plane between them (no friction: one
horizontal tension ``H = w a`` throughout); the centerline lies one tube radius ``sqrt(A / π)``
above the plane.  On a sloped plane (its normal within 60° of ``up``; MoorPy's ``alpha``) whose line
in that vertical plane rises by ``tan β`` per metre, a line with one end on the plane lies straight
on it from that end to a touchdown point, where the catenary to the other end leaves it tangent to
it (``sinh u = tan β`` there; MoorPy's frictionless sloped seabed: the grounded length and ``a``
from the two conditions that the catenary reaches the other end and the lengths add up;
:mod:`rancf.solvers.static_catenary`); a line with both ends above a sloped plane hangs free.  Each
node is placed at the point of the shape at its unstretched arc length
(:func:`rancf.bodies.length.unstretched_length`), its gradient ``r_x`` along the shape's tangent
with the length of its unstretched gradient (``λ |r0_x|``, the element's gradient scale times the
length scale ``λ`` of docs/derivations/variable-length.md §2.1).
A line shorter than that chord (installed stretched) starts straight between its held ends,
stretched evenly (its gradients too).  Other bodies keep their reference.  From there Newton's
method at the full load with the supports installed (the last stage's end): where a sagged line
is stiff (its ``EA`` above :data:`rancf.solvers.axial_continuation.STIFF_RATIO` times its
weight) first with the ``EA`` of such lines continued up to their own
(:func:`rancf.solvers.axial_continuation.continued_newton`), else or where that fails from the
start shape at their own ``EA`` (at least :data:`NEWTON_ITERATIONS` iterations); relaxation
(:func:`rancf.solvers.relaxation.relax`, at most :data:`RELAX_STEPS` steps) if Newton fails.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.length import length_scale
from rancf.solvers.axial_continuation import continued_newton, stiff_lines
from rancf.solvers.newton import NewtonOutcome, newton
from rancf.solvers.relaxation import relax
from rancf.solvers.static_catenary import catenary_shape, free_bend_radii, touchdowns
from rancf.solvers.surface_start import across_surface, place_shape, still_surface
from rancf.solvers.system_equilibrium import SystemEquilibrium
from rancf.system.parts.contact_pair import ContactPair
from rancf.system.seabed import pressing_weight, weight_per_length, wet_weight

__all__ = [
    "SAG_START",
    "catenary_shape",
    "sag_state",
    "solve_from_sag",
    "clamped_lines",
    "touchdown_radius",
    "start_touchdowns",
    "start_free_bends",
    "touchdown_causes",
]

#: ``StaticResult.method`` of an equilibrium found from the sagged start shape.
SAG_START = "sag start+newton"
#: Pseudo-time steps of the relaxation from the sagged start (a line coming to rest on a seabed
#: through its touchdowns, e.g. 625 steps for a 500 m line of 80 elements; the load path's
#: relaxation keeps :data:`rancf.solvers.relaxation.MAX_STEPS`).
RELAX_STEPS = 2000
#: Newton's iterations from the sagged start at least (the solver's ``max_iter`` if larger), at
#: the lines' own ``EA``.  A line whose ``EA`` is about 1e9 times its tension creeps along its
#: nearly inextensible shapes (the residual falls by about half per 25 iterations) before it
#: converges quadratically: MoorPy's sloped lines in 34 to 41 iterations (with the continuation
#: in ``EA`` of :mod:`rancf.solvers.axial_continuation` 25 to 35, taken first).  Not more: its U
#: on a mesh too coarse for its touchdowns (160 elements, 0.31 of the bend radius) creeps for
#: 182 iterations into one of the several states such a locked mesh holds.
NEWTON_ITERATIONS = 60
#: A line within this (relative) of its chord keeps its reference: no start shape.
SLACK_RTOL = 1e-9


def _held_position(model: Model, node: int) -> bool:
    b = model.node_base(node)
    return bool(np.all(model.fixed[b : b + model.dim]))


def _resting_height(system: Any, name: str, ob: Any, n: NDArray) -> float:
    """The height above the plane ``ob`` (unit normal ``n``) of body ``name``'s centerline
    resting on it under its wet weight: its tube radius less the penalty's sinking
    ``w_n / k + d / 2`` (:mod:`rancf.system.seabed`; ``k``, ``d`` the pair's stiffness and
    onset), at least 0.  Resting there, not touching at the onset, the grounded line has the
    contact's stiffness from the start: with no tension yet (the start is unstretched) its
    bending stiffness alone would hold it up, and Newton's first steps moved a 330 m chain on
    160 elements by kilometres."""
    radius = float(system.bodies[name].section.radius)
    law = ContactPair(name, ob, "").record(system)
    w_n = pressing_weight(system, name, np.r_[n, np.zeros(3 - n.size)])
    sink = max(w_n, 0.0) / law.stiffness + 0.5 * law.onset
    return max(radius - sink, 0.0)


def _floor(
    system: Any, name: str, model: Model, up: NDArray, p1: NDArray, chord: NDArray
) -> tuple[float, float] | None:
    """``(z0, slope)``: the line ``z = z0 + x slope`` (``x`` horizontal along the ``chord``
    from ``p1``, ``z`` along ``up``) of the centerline resting on the fixed plane facing up (its
    normal within 60° of ``up``) that body ``name`` touches, highest under the middle of the
    span of those, or None.  A sloped line is moved to pass through an end that is within a
    tube radius of it (an anchor on the seabed)."""
    best, pairs = None, set(getattr(system, "contact_pairs", ()))
    rise = float(chord @ up)
    ex = chord - rise * up
    span = float(np.linalg.norm(ex))
    ex = ex / span if span > 0.0 else ex
    for ob, oname in zip(system.obstacles, system.obstacle_names, strict=False):
        if ob.kind != "plane" or ob.body is not None or (name, oname) not in pairs:
            continue
        n = np.asarray(ob.normal, dtype=float)
        n = n / np.linalg.norm(n)
        if n @ up < 0.5:
            continue
        rest = np.asarray(ob.point, dtype=float) + _resting_height(system, name, ob, n) * n - p1
        z0, slope = float(rest @ n) / float(n @ up), -float(ex @ n) / float(n @ up)
        if abs(slope) < 1e-12:
            slope = 0.0
        if best is None or z0 + 0.5 * span * slope > best[0] + 0.5 * span * best[1]:
            best = (z0, slope)
    if best is not None and best[1] != 0.0:
        z0, slope = best
        near = model.section.radius
        if abs(z0) <= near:
            best = (0.0, slope)
        elif abs(rise - z0 - span * slope) <= near:
            best = (rise - span * slope, slope)
    return best


def _clamped(model: Model, node: int) -> bool:
    b = model.node_base(node) + model.dim
    return bool(np.any(model.fixed[b : b + model.dim]))


def _line_geometry(system: Any, name: str, model: Model, pinned: bool = False) -> Any:
    """``(q, up, p1, chord, s_nodes, span, rise)`` of a cable body whose two end nodes hold
    their positions (installed; ``q`` the installed nodal coordinates ``(n_nodes, dpn)``, ``up``
    against its wet weight (:func:`rancf.system.seabed.wet_weight`), ``p1`` the start,
    ``s_nodes`` the nodes' reference arc lengths), or None
    (no such line; ``pinned``: None also where an end holds its direction)."""
    if not model.family.cable or model.closed or model.gravity is None:
        return None
    ends = (0, model.n_nodes - 1)
    if not all(_held_position(model, k) for k in ends):
        return None
    if pinned and any(_clamped(model, k) for k in ends):
        return None
    w = wet_weight(system, name)[: model.dim]
    if not np.linalg.norm(w) > 0.0 and still_surface(system) is not None:
        w = weight_per_length(system, name, 0.0)[: model.dim]  # as heavy as water: its dry part
    if not np.linalg.norm(w) > 0.0:
        return None
    up = -w / np.linalg.norm(w)
    q = model.q_from_y(model.y_installed).reshape(model.n_nodes, model.dpn)
    p1 = q[0, : model.dim]
    chord = q[-1, : model.dim] - p1
    s_nodes = np.r_[0.0, np.cumsum(model.mesh.arc_lengths())] * length_scale(model)
    rise = float(chord @ up)
    span = float(np.linalg.norm(chord - rise * up))
    return q, up, p1, chord, s_nodes, span, rise


def touchdown_radius(system: Any, name: str, model: Model) -> tuple[float, list[float]] | None:
    """The bend radius ``a = H / w`` where body ``name``'s sagged start shape (module
    docstring) meets the seabed and the reference arc lengths of its touchdown points (where a
    hanging part meets it), or None (no sagged shape, or one that does not touch)."""
    geo = _line_geometry(system, name, model)
    if geo is None:
        return None
    q, up, p1, chord, s_nodes, span, rise = geo
    length = float(s_nodes[-1])
    stretch = float(np.linalg.norm(chord)) / length
    if stretch * (1.0 + SLACK_RTOL) >= 1.0 or span <= 1e-9 * length:
        return None
    found = _floor(system, name, model, up, p1, chord)
    if found is None:
        return None
    return touchdowns(span, rise, length, *found)


def start_touchdowns(system: Any) -> dict[str, tuple[float, float]]:
    """Per cable body whose sagged start shape meets a seabed, the largest ratio of the length
    of an element holding a touchdown point of that shape to its bend radius there
    (:func:`touchdown_radius`), and that element's length."""
    out = {}
    for name, model in zip(system.names, system.flex, strict=False):
        found = touchdown_radius(system, name, model)
        if found is None or not found[0] > 0.0 or not found[1]:
            continue
        ell = model.mesh.arc_lengths()
        starts = np.r_[0.0, np.cumsum(ell)]
        e = np.clip(np.searchsorted(starts, found[1], side="right") - 1, 0, ell.size - 1)
        out[name] = (float(ell[e].max()) / found[0], float(ell[e].max()))
    return out


def start_free_bends(system: Any) -> dict[str, tuple[float, float]]:
    """Per cable body whose sagged start shape hangs free (meets no seabed), the largest ratio
    of an element's length to the smallest bend radius of that shape along it
    (:func:`rancf.solvers.static_catenary.free_bend_radii`: ``H / w`` at the vertex, a buoyant
    line's crest), and that element's length."""
    out = {}
    for name, model in zip(system.names, system.flex, strict=False):
        geo = _line_geometry(system, name, model)
        if geo is None:
            continue
        q, up, p1, chord, s_nodes, span, rise = geo
        length = float(s_nodes[-1])
        if float(np.linalg.norm(chord)) * (1.0 + SLACK_RTOL) >= length or span <= 1e-9 * length:
            continue
        if touchdown_radius(system, name, model) is not None:
            continue  # on a seabed: start_touchdowns
        ell = np.diff(s_nodes)
        ratio = ell / free_bend_radii(span, rise, length, s_nodes)
        e = int(np.argmax(ratio))
        out[name] = (float(ratio[e]), float(ell[e]))
    return out


def touchdown_causes(system: Any) -> list[str]:
    """A cause of a failed static solve, one line per cable body whose sagged start shape meets
    a seabed with a bend radius ``H / w`` shorter than the element there
    (:func:`start_touchdowns`): a stiff line locks in such an element (docs/guide/statics.md,
    "Touchdown resolution")."""
    return [
        f"body {name!r}: its sagged start meets the seabed with the bend radius "
        f"H/w = {ell / ratio:.3g} m, shorter than its {ell:.3g} m elements there: refine the "
        f"mesh until they are shorter than it"
        for name, (ratio, ell) in start_touchdowns(system).items()
        if ratio > 1.0
    ]


def _body_sag(
    system: Any, name: str, model: Model, pinned: bool = False
) -> tuple[NDArray[np.float64], bool] | None:
    """The sagged start of one body's model coordinates (module docstring) and whether it is
    slack (sagged, not straight and stretched), or None; ``pinned``: None also where an end
    holds its direction (a clamp)."""
    geo = _line_geometry(system, name, model, pinned)
    if geo is None:
        return None
    q, up, p1, chord, s_nodes, span, rise = geo
    dim = model.dim
    length = float(s_nodes[-1])
    horiz = chord - rise * up
    # the mesh's gradients (a winch's anchored scaling leaves them; q0 it scales)
    grad = np.linalg.norm(model.mesh.nodes[:, 1], axis=1) * length_scale(model)
    out = q.copy()
    stretch = float(np.linalg.norm(chord)) / length
    if stretch > 1.0 + SLACK_RTOL:  # taut: straight, stretched evenly
        out[:, :dim] = p1 + np.outer(s_nodes / length, chord)
        out[:, dim:] = np.outer(grad * stretch, chord / np.linalg.norm(chord))
    elif stretch * (1.0 + SLACK_RTOL) >= 1.0 or span <= 1e-9 * length:
        return None
    else:
        ex = horiz / span
        found = _floor(system, name, model, up, p1, chord)
        floor, slope = (None, 0.0) if found is None else found
        pts, tan = catenary_shape(span, rise, length, s_nodes, floor, slope)
        place_shape(out, p1, ex, up, grad, pts, tan)
        if still_surface(system) is not None and slope == 0.0:
            across_surface(system, name, out, geo, grad, floor)
    y = model.y_from_q(out.ravel())
    y[model.fixed] = model.y_installed[model.fixed]
    return y, stretch < 1.0


def clamped_lines(system: Any) -> bool:
    """Whether a line with a sagged shape has a clamped end (left out of the first try)."""
    return any(
        _body_sag(system, name, model) is not None and _body_sag(system, name, model, True) is None
        for name, model in zip(system.names, system.flex, strict=False)
    )


def sag_state(problem: SystemEquilibrium, pinned: bool = False) -> NDArray[np.float64] | None:
    """The start ``z`` of :func:`solve_from_sag` (the problem's start with every line that has
    a sagged shape in it; ``pinned``: lines without a clamped end only), or None when no body
    has one."""
    return _sag_state(problem, pinned)[0]


def _sag_state(problem: SystemEquilibrium, pinned: bool) -> tuple[NDArray | None, list[str]]:
    """:func:`sag_state` and the names of the slack lines in it."""
    system = problem.system
    z = problem.start()
    changed, slack = False, []
    for name, model in zip(system.names, system.flex, strict=False):
        found = _body_sag(system, name, model, pinned)
        if found is not None:
            z[system.body_slice(name)] = found[0]
            changed = True
            slack += [name] if found[1] else []
    return (z if changed else None), slack


def solve_from_sag(
    system: Any, at_time: float | None, tol: float, max_iter: int, pinned: bool = False
) -> tuple[NDArray[np.float64], float, int, int, int, int] | None:
    """The equilibrium ``z`` from the sagged start shape (module docstring; ``pinned``: of the
    lines without a clamped end only) with the last stage's end ``p``, Newton's iterations, the
    factorizations, the extra residuals and the relaxation's steps; None when no body has a
    sagged shape or neither Newton nor relaxation converges from it."""
    system.reset_triads()
    problem = SystemEquilibrium(system, at_time)
    z, slack = _sag_state(problem, pinned)
    if z is None:
        return None
    problem.stage = len(problem.stages) - 1
    end = problem.stages[-1][1]
    problem.place_supports(z, end)
    stiff = stiff_lines(system, slack, z)
    tried = NewtonOutcome(False, z, 0, 0, np.inf)
    if stiff:
        tried = continued_newton(problem, z, end, tol, stiff)
        if tried.converged:
            problem.accept(tried.y)
            return tried.y, end, tried.iterations, tried.iterations, tried.residuals, 0
    out = newton(problem, z, end, tol, max(max_iter, NEWTON_ITERATIONS))
    out = replace(
        out, iterations=out.iterations + tried.iterations, residuals=out.residuals + tried.residuals
    )
    if out.converged:
        problem.accept(out.y)
        return out.y, end, out.iterations, out.iterations, out.residuals, 0
    rel = relax(problem, z, end, tol, max_iter, polish_at_start=False, max_steps=RELAX_STEPS)
    if not rel.converged:
        return None
    problem.accept(rel.z)
    return (
        rel.z,
        end,
        out.iterations + rel.newton_iterations,
        out.iterations + rel.factorizations,
        out.residuals + rel.residuals,
        rel.steps,
    )
