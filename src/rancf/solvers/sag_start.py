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
body's gravity).  Where that catenary dips below a fixed plane facing up against gravity that
the body touches (a seabed), the shape is instead two catenaries from the ends down to
touchdown points, where they are tangent to the plane, and the line straight on the plane
between them (no friction: one horizontal tension ``H = w a`` throughout); the centerline lies
one tube radius ``sqrt(A / π)`` above the plane.  Each node is placed at the point of the shape
at its unstretched arc length, its gradient ``r_x`` along the shape's tangent with the length
of its unstretched gradient (``λ |r0_x|``, the element's gradient scale times the length
scale ``λ`` of docs/derivations/variable-length.md §2.1).
A line shorter than that chord (installed stretched) starts straight between its held ends,
stretched evenly (its gradients too).  Other bodies keep their reference.  From there Newton's
method at the full load with the supports installed (the last stage's end), and relaxation
(:func:`rancf.solvers.relaxation.relax`, at most :data:`RELAX_STEPS` steps) if Newton fails.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.length import length_scale
from rancf.solvers.newton import newton
from rancf.solvers.relaxation import relax
from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = [
    "SAG_START",
    "catenary_shape",
    "sag_state",
    "solve_from_sag",
    "clamped_lines",
    "touchdown_radius",
]

#: ``StaticResult.method`` of an equilibrium found from the sagged start shape.
SAG_START = "sag start+newton"
#: Pseudo-time steps of the relaxation from the sagged start (a line coming to rest on a seabed
#: through its touchdowns, e.g. 625 steps for a 500 m line of 80 elements; the load path's
#: relaxation keeps :data:`rancf.solvers.relaxation.MAX_STEPS`).
RELAX_STEPS = 2000
#: A line within this (relative) of its chord keeps its reference: no start shape.
SLACK_RTOL = 1e-9


def _bisect(f: Any, lo: float, hi: float, n: int = 200) -> float:
    """A root of ``f`` in ``[lo, hi]`` (``f(lo) > 0 >= f(hi)``) by bisection in ``log``."""
    for _ in range(n):
        mid = math.sqrt(lo * hi)
        if f(mid) > 0.0:
            lo = mid
        else:
            hi = mid
        if hi / lo - 1.0 < 1e-14:
            break
    return math.sqrt(lo * hi)


def _free(span: float, rise: float, length: float) -> tuple[float, float]:
    """``(a, x_v)`` of the catenary ``z = z_v + a (cosh((x - x_v)/a) - 1)`` of ``length``
    from ``(0, 0)`` to ``(span, rise)``: ``sqrt(L² - rise²) = 2 a sinh(span / (2 a))``,
    ``x_v = span/2 - a atanh(rise / L)``."""
    c = math.sqrt(length**2 - rise**2)

    def f(a: float) -> float:  # positive while a is too small (too long a curve)
        u = span / (2.0 * a)
        return 2.0 * a * math.sinh(u) - c if u < 700.0 else math.inf

    a = _bisect(f, span * 1e-6, span * 1e6)
    return a, span / 2.0 - a * math.atanh(rise / length)


def _grounded(span: float, h1: float, h2: float, length: float) -> float | None:
    """``a`` of the line touching down on a plane ``h1``, ``h2`` below its ends (module
    docstring), or None where the free catenary does not reach the plane or the line is longer
    than ``h1 + h2 + span`` (no touchdown shape: it would pile up)."""
    if length >= h1 + h2 + span:
        return None

    def parts(a: float) -> tuple[float, float]:  # suspended lengths, horizontal extents
        s = [math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2)]
        return sum(s), sum(a * math.asinh(si / a) for si in s)

    a_hi = _bisect(lambda a: span - parts(a)[1], span * 1e-9, span * 1e9)  # no grounded length
    if parts(a_hi)[0] >= length:
        return None  # the hanging line does not reach the plane
    return _bisect(lambda a: parts(a)[0] + span - parts(a)[1] - length, span * 1e-9, a_hi)


def catenary_shape(
    span: float, rise: float, length: float, s: NDArray, floor: float | None = None
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Points ``(x, z)`` and unit tangents of the inextensible catenary of ``length`` from
    ``(0, 0)`` to ``(span, rise)`` (``span > 0``, ``length`` above the chord) at the arc lengths
    ``s`` from its start, lying on the line ``z = floor`` where it would dip below it (module
    docstring); ``(n, 2)`` each."""
    s = np.clip(np.asarray(s, dtype=float), 0.0, length)
    a = None
    if floor is not None:
        h1, h2 = max(-floor, 0.0), max(rise - floor, 0.0)
        a = _grounded(span, h1, h2, length)
    if a is None or floor is None:
        a, xv = _free(span, rise, length)
        u1 = -xv / a
        u = np.arcsinh(math.sinh(u1) + s / a)
        x = xv + a * u
        z = a * (np.cosh(u) - math.cosh(u1))
        return np.c_[x, z], np.c_[1.0 / np.cosh(u), np.tanh(u)]
    s1, s2 = (math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2))
    x1, x2 = (a * math.asinh(si / a) for si in (s1, s2))
    u = np.zeros_like(s)  # on the plane: u = 0, the tangent horizontal
    first, last = s < s1, s > length - s2
    u[first] = -np.arcsinh((s1 - s[first]) / a)
    u[last] = np.arcsinh((s[last] - (length - s2)) / a)
    x = np.where(first, x1 + a * u, np.where(last, span - x2 + a * u, x1 + s - s1))
    z = floor + a * (np.cosh(u) - 1.0)
    return np.c_[x, z], np.c_[1.0 / np.cosh(u), np.tanh(u)]


def _held_position(model: Model, node: int) -> bool:
    b = model.node_base(node)
    return bool(np.all(model.fixed[b : b + model.dim]))


def _floor(system: Any, name: str, model: Model, up: NDArray, p1: NDArray) -> float | None:
    """The height above ``p1`` (along ``up``) of the centerline resting on the highest fixed
    plane facing ``up`` that body ``name`` touches, or None."""
    best, pairs = None, set(getattr(system, "contact_pairs", ()))
    for ob, oname in zip(system.obstacles, system.obstacle_names, strict=False):
        if ob.kind != "plane" or ob.body is not None or (name, oname) not in pairs:
            continue
        n = np.asarray(ob.normal, dtype=float)
        n = n / np.linalg.norm(n)
        if n @ up < 1.0 - 1e-9:
            continue
        h = float((np.asarray(ob.point, dtype=float) - p1) @ up) + model.section.radius
        best = h if best is None else max(best, h)
    return best


def _clamped(model: Model, node: int) -> bool:
    b = model.node_base(node) + model.dim
    return bool(np.any(model.fixed[b : b + model.dim]))


def _line_geometry(system: Any, name: str, model: Model, pinned: bool = False) -> Any:
    """``(q, up, p1, chord, s_nodes, span, rise)`` of a cable body whose two end nodes hold
    their positions (installed; ``q`` the installed nodal coordinates ``(n_nodes, dpn)``, ``up``
    against gravity, ``p1`` the start, ``s_nodes`` the nodes' reference arc lengths), or None
    (no such line; ``pinned``: None also where an end holds its direction)."""
    if not model.family.cable or model.closed or model.gravity is None:
        return None
    ends = (0, model.n_nodes - 1)
    if not all(_held_position(model, k) for k in ends):
        return None
    if pinned and any(_clamped(model, k) for k in ends):
        return None
    g = np.asarray(model.gravity, dtype=float)
    if not np.linalg.norm(g) > 0.0:
        return None
    up = -g / np.linalg.norm(g)
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
    floor = _floor(system, name, model, up, p1)
    if floor is None:
        return None
    h1, h2 = max(-floor, 0.0), max(rise - floor, 0.0)
    a = _grounded(span, h1, h2, length)
    if a is None:
        return None
    s1, s2 = (math.sqrt(h * h + 2.0 * a * h) for h in (h1, h2))
    return a, [s for s, h in ((s1, h1), (length - s2, h2)) if h > 0.0]


def _body_sag(
    system: Any, name: str, model: Model, pinned: bool = False
) -> NDArray[np.float64] | None:
    """The sagged start of one body's model coordinates (module docstring), or None;
    ``pinned``: None also where an end holds its direction (a clamp)."""
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
        floor = _floor(system, name, model, up, p1)
        pts, tan = catenary_shape(span, rise, length, s_nodes, floor)
        out[:, :dim] = p1 + pts[:, :1] * ex + pts[:, 1:] * up
        out[:, dim:] = grad[:, None] * (tan[:, :1] * ex + tan[:, 1:] * up)
    y = model.y_from_q(out.ravel())
    y[model.fixed] = model.y_installed[model.fixed]
    return y


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
    system = problem.system
    z = problem.start()
    changed = False
    for name, model in zip(system.names, system.flex, strict=False):
        y = _body_sag(system, name, model, pinned)
        if y is not None:
            z[system.body_slice(name)] = y
            changed = True
    return z if changed else None


def solve_from_sag(
    system: Any, at_time: float | None, tol: float, max_iter: int, pinned: bool = False
) -> tuple[NDArray[np.float64], float, int, int, int, int] | None:
    """The equilibrium ``z`` from the sagged start shape (module docstring; ``pinned``: of the
    lines without a clamped end only) with the last stage's end ``p``, Newton's iterations, the
    factorizations, the extra residuals and the relaxation's steps; None when no body has a
    sagged shape or neither Newton nor relaxation converges from it."""
    system.reset_triads()
    problem = SystemEquilibrium(system, at_time)
    z = sag_state(problem, pinned)
    if z is None:
        return None
    problem.stage = len(problem.stages) - 1
    end = problem.stages[-1][1]
    problem.place_supports(z, end)
    out = newton(problem, z, end, tol, max_iter)
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
