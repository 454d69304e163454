"""Contact forces of the obstacles at a state and over stored states (:mod:`rancf.system.contact`).

The compiled core evaluates them (``src/cpp/contact/contact.hpp``) as in the time step: the
normal and friction forces per obstacle, their moment, the contact length and the penetration.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.kernels import _core
from rancf.system.contact_view import ContactSystem

__all__ = ["ContactState", "contact_outputs", "contact_history"]


@dataclass(frozen=True)
class ContactState:
    """Contact of one obstacle at a state: the forces the obstacle exerts on the bodies (normal
    and friction parts, ``dim`` components), their moment about the obstacle's point (2D: a
    number; 3D: 3 components), the contact length (current arc length of the points in contact,
    resolved to the points' spacing) and the largest penetration."""

    normal: NDArray[np.float64]
    friction: NDArray[np.float64]
    moment: NDArray[np.float64] | float
    length: float
    penetration: float


def contact_outputs(
    system: ContactSystem, y: NDArray, v: NDArray | None = None, y1: NDArray | None = None
) -> dict[str, ContactState]:
    """Per obstacle (by name), its contact at model coordinates ``y`` (and velocities ``v``: the
    friction; without them none).  Stored results hold ``q``: pass ``system.y_from_q(q)``.

    With ``y1``, ``(y, v)`` is a time step's generalized-α point ``(y_{n+1-α_f},
    v_{n+1-α_f})`` and ``y1`` its end: the forces are those the step applied (the pressure the
    step's mean over its gaps, module docstring), where the state at the step's end alone would
    sample the penalty's unresolved vibration."""
    names = system.obstacle_names
    if not names:
        return {}
    out = np.empty((len(names), _core.CONTACT_OUTPUTS))
    y = np.ascontiguousarray(y, dtype=float)
    vv = None if v is None else np.ascontiguousarray(v, dtype=float)
    yy1 = None if y1 is None else np.ascontiguousarray(y1, dtype=float)
    system.contact.outputs(y, vv, out, yy1)
    d = system.dim
    return {
        name: ContactState(
            row[:d].copy(),
            row[3 : 3 + d].copy(),
            float(row[8]) if d == 2 else row[6:9].copy(),
            float(row[9]),
            float(row[10]),
        )
        for name, row in zip(names, out, strict=True)
    }


def contact_history(system: ContactSystem, q: NDArray, v: NDArray | None = None) -> dict[str, dict]:
    """:func:`contact_outputs` over stored states ``q`` (``(n_t, n)``, full coordinates as in a
    :class:`rancf.solvers.dynamic.DynamicResult`) and velocities: per obstacle the arrays
    ``normal`` and ``friction`` ``(n_t, dim)``, ``moment``, ``length`` and ``penetration``."""
    ys = system.y_from_q(np.atleast_2d(q))
    vs = None if v is None else system.y_from_q(np.atleast_2d(v))
    rows = [contact_outputs(system, ys[i], None if vs is None else vs[i]) for i in range(len(ys))]
    return {
        name: {
            key: np.array([getattr(r[name], key) for r in rows])
            for key in ("normal", "friction", "moment", "length", "penetration")
        }
        for name in system.obstacle_names
    }
