"""The records of a system's prescribed motions and point loads for the compiled core
(:mod:`rancf.kernels.records`), made from the parts as :class:`rancf.system.system.System`
gathers them (``system``: the system being built).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import RigidBody
from rancf.errors import InputError
from rancf.kernels.records import LoadRecord, PrescribedRecord, vec3
from rancf.system.connections import Load
from rancf.system.places import Place
from rancf.system.record_rows import RecordRows

__all__ = ["motion_records", "all_loads", "load_record"]


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


def load_record(system: Any, ld: Load, rows: RecordRows) -> LoadRecord:
    """The record of a point load (force and moment times its time function)."""
    p = system.resolve(ld.at)
    if p.body is None:
        raise InputError("loads.point.at", "ground", "a place on a body")
    f = np.zeros(3) if ld.force is None else np.asarray(ld.force, dtype=float)
    t = np.zeros(3) if ld.torque is None else np.asarray(ld.torque, dtype=float)
    if ld.force is not None and f.size != system.dim:
        raise InputError("loads.point.force", list(f), f"{system.dim} components")
    b = system.bodies[p.body]
    rod = isinstance(b, Model) and b.family.has_triads
    if ld.torque is not None and not (isinstance(b, RigidBody) or rod):
        raise InputError("loads.point.moment", list(t), "a rigid body or a rod's node")
    tt = np.r_[np.zeros(2), t] if t.size == 1 else np.r_[t, np.zeros(3 - t.size)]
    if ld.time is not None and ld.time.size != 1:
        raise InputError("loads.point.time", ld.time.size, "a scalar time function (a factor)")
    place = system.place_index(p, rows)
    force = vec3(np.r_[f, np.zeros(3 - f.size)])
    return LoadRecord(place, force, vec3(tt), rows.tf(ld.time))
