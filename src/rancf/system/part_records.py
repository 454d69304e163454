"""The records of a system's prescribed motions, and its point loads for the compiled core
(:mod:`rancf.kernels.records`), made from the parts as :class:`rancf.system.system.System`
gathers them (``system``: the system being built).
"""

from __future__ import annotations

from typing import Any

from rancf.errors import InputError
from rancf.kernels.records import PrescribedRecord
from rancf.system.parts.load import Load
from rancf.system.places import Place
from rancf.system.record_rows import RecordRows

__all__ = ["motion_records", "all_loads"]


def motion_records(system: Any, rows: RecordRows) -> list[PrescribedRecord]:
    """The prescribed records: held positions of flexible bodies that follow their support's
    motion."""
    out = []
    for name, b in zip(system.names, system.flex, strict=False):
        for sup in b.supports:
            if sup.motion is None:
                continue
            if sup.kind == "roller":
                raise InputError("supports.motion", "roller", "a pin or clamp (moving supports)")
            if sup.motion.size != system.dim:
                raise InputError("supports.motion", sup.motion.size, f"{system.dim} components")
            k = rows.tf(sup.motion)
            base = b.node_base(b.check_node(sup.node, "supports.at"))
            for i in range(system.dim):
                coord = system.offsets[name] + base + i
                out.append(PrescribedRecord(coord, k, i, float(b.y_installed[base + i])))
    return out


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
