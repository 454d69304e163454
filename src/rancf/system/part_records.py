"""A system's point loads as Parts (:class:`~rancf.system.parts.load.Load`): its own and its
flexible bodies' point loads with a time function, as :class:`rancf.system.system.System`
gathers them (``system``: the system being built).
"""

from __future__ import annotations

from typing import Any

from rancf.system.parts.load import Load
from rancf.system.places import Place

__all__ = ["all_loads"]


def all_loads(system: Any) -> list[Load]:
    """The loads, and flexible bodies' point forces (and rods' moments) times a time
    function."""
    out = list(system.loads)
    for name, b in zip(system.names, system.flex, strict=False):
        for p in b.point_loads:
            if p.time is None:
                continue
            out.append(
                Load(
                    Place(name, b.check_node(p.node, "loads.point.at")),
                    p.force,
                    p.moment,
                    p.time,
                )
            )
    return out
