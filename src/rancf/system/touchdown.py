"""The touchdown point of a line on a seabed: where, walking along the line from its start, it
leaves a plane obstacle (the ``touchdown`` sensor, :mod:`rancf.system.sensors`).

The centreline is sampled at ``SAMPLES`` points per element (its exact RANCF shape functions);
the gap of a sample is its height above the plane less the line's tube radius
``sqrt(A / pi)`` (the contact's own geometry, :mod:`rancf.system.contact`).  A sample touches
where its gap is below ``tol`` (default a twentieth of the tube radius: above the ripple of a
line lying between its contact points); the touchdown point is interpolated linearly between
the last sample of the first touching stretch and the next one.
A line whose start does not touch the plane has no touchdown point (NaN).

The point so found lies where the line has risen ``tol`` off the plane: on a catenary of
radius ``a = H / w`` at the seabed that is ``sqrt(2 a tol)`` beyond the point where it leaves
the bed, the value a refined mesh converges to (the shipped 330 m chain, ``a = 215`` m, ``tol =
5.4`` mm: 1.5 m; -198.64 m at 60 elements and -198.48 m at 120 against the catenary's -200.04
m).  The catenary's curvature jumps at the touchdown point, which cubic elements spread over
the element holding it; at 30 elements that happens to cancel part of it (1 m from the
catenary's, ``tests/system/test_fluid_physics.py``).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import cable_shape_functions

__all__ = ["SAMPLES", "touchdown_point"]

#: Sample points per element.
SAMPLES = 16


def _centreline(model: Any, q: NDArray, xi: NDArray) -> NDArray[np.float64]:
    """Points ``(n_el * len(xi), dim)`` of the centreline at ``xi`` in every element from the
    body's full nodal coordinates ``q``."""
    mesh, d = model.mesh, model.dim
    n0 = cable_shape_functions(mesh.weights, mesh.scales, xi)[0]  # (n_el, n_xi, 4)
    nodes = np.asarray(q, dtype=float).reshape(model.n_nodes, model.dpn)
    pos, grad = nodes[:, :d], nodes[:, d : 2 * d]
    blocks = np.stack([pos[:-1], grad[:-1], pos[1:], grad[1:]], axis=1)  # (n_el, 4, dim)
    return np.einsum("eqk,ekd->eqd", n0, blocks).reshape(-1, d)


def touchdown_point(
    model: Any, q: NDArray, point: NDArray, normal: NDArray, tol: float | None = None
) -> NDArray[np.float64]:
    """The touchdown point ``(dim,)`` of the flexible body ``model`` (cable or rod elements) at
    its full nodal coordinates ``q`` on the plane through ``point`` with outward ``normal``
    (module docstring); NaN where the line's start does not touch."""
    radius = float(np.sqrt(model.section.area / np.pi))
    tol = 5e-2 * radius if tol is None else tol
    xi = np.arange(SAMPLES + 1) / SAMPLES
    r = _centreline(model, q, xi)
    n = np.asarray(normal, dtype=float)
    gap = (r - np.asarray(point, dtype=float)) @ (n / np.linalg.norm(n)) - radius
    off = np.flatnonzero(gap > tol)
    if gap[0] > tol:
        return np.full(model.dim, np.nan)
    if off.size == 0:
        return r[-1].copy()
    k = off[0]
    f = (tol - gap[k - 1]) / (gap[k] - gap[k - 1])
    return r[k - 1] + f * (r[k] - r[k - 1])
