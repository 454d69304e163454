"""A static state as ``rancf static --json`` gives it: the bodies' positions
(:func:`positions_json`) and the reactions at the full loads (:func:`reactions_json`); the
static analysis itself is :func:`rancf.runs.static.run_static`."""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.system.outputs import SystemOutputs

__all__ = ["positions_json", "reactions_json"]


def reactions_json(outputs: SystemOutputs, y: NDArray, lam: NDArray | None) -> list[dict[str, Any]]:
    """``static --json``'s ``"reactions"`` at the full loads: one object per support (in file
    order, flexible body by body) and per joint, ``{"at", "force", "moment"}`` (``moment`` for
    clamps, rods and joints that transmit one), whatever the sensors
    (:meth:`rancf.system.outputs.SystemOutputs.static_reactions`)."""
    assert lam is not None  # a system's solution has its multipliers (empty: no joints)
    out = []
    for r in outputs.static_reactions(y, lam):
        item: dict[str, Any] = {"at": r.at, "force": r.force.tolist()}
        if r.moment is not None:
            item["moment"] = r.moment.tolist()
        out.append(item)
    return out


def positions_json(system: Any, q: NDArray) -> dict[str, Any]:
    """``static --json``'s ``"positions"``: per body name, a flexible body's nodes ``[[x, y(,
    z)], ...]``, a rigid body's or point mass's centre ``[x, y(, z)]``."""
    out: dict[str, Any] = {}
    for name in system.names:
        b, qb = system.bodies[name], np.asarray(q)[system.body_slice(name)]
        out[name] = (
            b.node_positions(qb).tolist()
            if hasattr(b, "node_positions")
            else qb[: system.dim].tolist()
        )
    return out
