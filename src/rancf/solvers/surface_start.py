"""The sagged start of a hanging line crossing the free surface (:mod:`rancf.solvers.sag_start`).

Above the still surface a line weighs its weight in air, below it its weight in water: its start
is the catenary of each element's weight with its share under water
(:func:`rancf.system.seabed.element_weights`, the one formula of the weight per length), solved
by :func:`rancf.solvers.static_catenary.weighted_catenary`, and the shares taken again in that
shape until they repeat (:func:`across_surface`).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.solvers.static_catenary import weighted_catenary
from rancf.system.seabed import element_weights

__all__ = ["SURFACE_PASSES", "still_surface", "place_shape", "across_surface"]

#: Passes of a hanging line's start crossing the free surface at most (shares under water,
#: then the catenary of their weights).
SURFACE_PASSES = 10


def still_surface(system: Any) -> float | None:
    """The still free surface's height of the system's fluid, or None (none)."""
    fluid = getattr(system, "fluid", None)
    return None if fluid is None else fluid.surface


def place_shape(
    out: NDArray, p1: NDArray, ex: NDArray, up: NDArray, grad: NDArray, pts: NDArray, tan: NDArray
) -> None:
    """Nodes at the shape's points ``(x, z)`` (``x`` along ``ex`` from ``p1``, ``z`` along
    ``up``), gradients along its tangents with the lengths ``grad``, in place."""
    dim = p1.size
    out[:, :dim] = p1 + pts[:, :1] * ex + pts[:, 1:] * up
    out[:, dim : 2 * dim] = grad[:, None] * (tan[:, :1] * ex + tan[:, 1:] * up)


def across_surface(
    system: Any, name: str, out: NDArray, geo: Any, grad: NDArray, floor: Any
) -> None:
    """The start of a hanging line whose weight per length changes along it where it crosses
    the free surface (its buoyancy only under water): the weight of each element with its
    share under water in the shape (:func:`rancf.system.seabed.element_weights`, the one
    formula), the catenary of those weights
    (:func:`rancf.solvers.static_catenary.weighted_catenary`) and again, until the shares
    repeat (at most :data:`SURFACE_PASSES` times); in place.  Kept where no such shape is found
    or it dips below the ``floor``."""
    q, up, p1, chord, s_nodes, span, rise = geo
    up3 = np.r_[up, np.zeros(3 - up.size)]
    ex = (chord - rise * up) / span
    last, guess = None, None
    for _ in range(SURFACE_PASSES):
        w = element_weights(system, name, out.ravel()) @ -up3
        if np.ptp(w) == 0.0 or (last is not None and np.array_equal(w, last)):
            return
        found = weighted_catenary(span, rise, s_nodes, w, guess)
        if found is None or (floor is not None and np.min(found[0][:, 1]) < floor):
            return
        pts, tan, guess = found
        place_shape(out, p1, ex, up, grad, pts, tan)
        last = w
