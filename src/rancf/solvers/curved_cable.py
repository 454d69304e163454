"""Spatial cables drawn curved: their bending energy's kink where they lie straight.

A spatial cable element's bending energy is ``½ EI (|κ| - |κ0|)²`` (docs/derivations/cable.md
sec. 6): it takes the magnitude of the curvature, so about a curved stress-free reference
(``κ0 ≠ 0``) it has a kink at ``κ = 0``, where the line lies straight (on a seabed, pulled
taut).  Newton's method may not settle there (the straight state is ill-posed:
docs/derivations/cable.md sec. 8): the 330 m chain of
``benchmarks/mooring/mooring-surge-3d.toml`` (drawn as a conic) unloaded as drawn fails at
160 elements, its residual stalling at 1 N with 1 µm steps of the grounded nodes, while the
same chain drawn straight, or unloaded straight (``[mesh] stress_free = "straight"``, or
``"auto"``, the default, for a line whose rest curvature's moment is negligible:
:mod:`rancf.bodies.stress_free`), converges in 7 Newton iterations.  A failed static solve
names such bodies (:func:`curved_cable_causes`); ``rancf static`` and ``simulate`` note them
before any solve (:func:`rancf.post.checks.element_notes`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

__all__ = ["CURVED_TANGENTS", "curved_spatial_cable", "curved_cable_causes"]

#: Smallest difference of two unit nodal tangents that makes a reference curved.
CURVED_TANGENTS = 1e-9


def curved_spatial_cable(model: Any) -> bool:
    """Whether ``model`` is a spatial cable body whose stress-free reference is curved (nodal
    tangents not all parallel; ``stress_free = "reference"``)."""
    if model.dim != 3 or not model.family.cable or model.stress_free != "reference":
        return False
    t = np.asarray(model.mesh.nodes[:, 1], dtype=float)
    t = t / np.linalg.norm(t, axis=1)[:, None]
    return float(np.max(np.linalg.norm(t - t[0], axis=1))) > CURVED_TANGENTS


def curved_cable_causes(system: Any) -> list[str]:
    """A possible cause of a failed static solve, one line per spatial cable body of ``system``
    drawn curved (module docstring)."""
    return [
        f"body {name!r} is a spatial cable with a curved stress-free reference, whose bending "
        f"energy has a kink where it lies straight (on a seabed), where Newton's method may not "
        f"settle: if it has no rest curvature (a chain, a rope), set [mesh] stress_free = "
        f'"straight"'
        for name, model in zip(system.names, system.flex, strict=False)
        if curved_spatial_cable(model)
    ]
