"""Meshes of rope routes made of straight spans and exact circular arcs: a rope over a pulley.

A circular arc of radius ``R`` from angle ``θ0`` to ``θ1`` is the rational quadratic with the
middle weight ``c = cos((θ1 − θ0)/2)`` (docs/derivations/cable.md §1), written as the rational
cubic of the element by degree elevation with K = 0.5 (§2): control points ``p0``,
``(p0 + 2c p1)/(1 + 2c)``, ``(2c p1 + p2)/(1 + 2c)``, ``p2`` with weights ``1, (1 + 2c)/3,
(1 + 2c)/3, 1``; a straight span is the cubic with equally spaced control points and unit weights.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError
from rancf.mesh.mesh import CableMesh, check_element_count, mesh_from_arrays

__all__ = ["rope_over_pulley"]


def _line(a: NDArray, b: NDArray) -> tuple[list[NDArray], list[float]]:
    return [a, a + (b - a) / 3, a + 2 * (b - a) / 3, b], [1.0, 1.0, 1.0, 1.0]


def _arc(center: NDArray, radius: float, t0: float, t1: float) -> tuple[list[NDArray], list]:
    c = np.cos((t1 - t0) / 2)
    p0, p2 = (center + radius * np.array([np.cos(t), np.sin(t)]) for t in (t0, t1))
    p1 = center + radius / c * np.array([np.cos((t0 + t1) / 2), np.sin((t0 + t1) / 2)])
    w = (1 + 2 * c) / 3
    pts = [p0, (p0 + 2 * c * p1) / (1 + 2 * c), (2 * c * p1 + p2) / (1 + 2 * c), p2]
    return pts, [1.0, w, w, 1.0]


def rope_over_pulley(
    radius: float, span: float, n_arc: int, n_span: int, center: ArrayLike = (0.0, 0.0)
) -> CableMesh:
    """A planar rope laid over the top half of a circle: a vertical span of length ``span`` up
    the left side (``n_span`` elements, from its lower end), the half turn of radius ``radius``
    (the rope's centre line: pulley radius plus rope radius) about ``center`` as ``n_arc``
    exact arcs, and the span down the right side (module docstring).

    Returns the mesh from the left span's lower end to the right span's lower end."""
    n_arc, n_span = check_element_count(n_arc), check_element_count(n_span)
    for key, value in (("radius", radius), ("span", span)):
        if not (np.isfinite(value) and value > 0.0):
            raise InputError(key, value, "a positive length [m]")
    o = np.asarray(center, dtype=float).ravel()
    if o.size != 2:
        raise InputError("center", o.tolist(), "a point [x, y]")
    ys = np.linspace(-span, 0.0, n_span + 1)
    left, right = np.array([-radius, 0.0]), np.array([radius, 0.0])
    els = [_line(o + left + [0, ys[i]], o + left + [0, ys[i + 1]]) for i in range(n_span)]
    th = np.linspace(np.pi, 0.0, n_arc + 1)
    els += [_arc(o, radius, th[i], th[i + 1]) for i in range(n_arc)]
    down = ys[::-1]
    els += [_line(o + right + [0, down[i]], o + right + [0, down[i + 1]]) for i in range(n_span)]
    return mesh_from_arrays(np.array([e[0] for e in els]), np.array([e[1] for e in els], float))
