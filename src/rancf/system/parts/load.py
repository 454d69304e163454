"""Point loads: a force (and, on rigid bodies and rod nodes, a torque) at a place, world axes,
times a time function; a :class:`~rancf.system.part.Part`."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import RigidBody
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels.records import LoadRecord, vec3
from rancf.system.part import NoOutputs
from rancf.system.places import Place

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["Load"]


@dataclass(frozen=True)
class Load(NoOutputs):
    """A force (and, on a rigid body, a torque) at a place, world axes, times ``time`` (a
    factor; None: constant)."""

    at: Place | str
    force: Sequence[float] | None = None
    torque: Sequence[float] | None = None
    time: TimeFunction | None = None

    @property
    def name(self) -> str:
        """Its place, as written."""
        return str(self.at)

    def record(self, system: Any, rows: RecordRows) -> LoadRecord:
        """The core's record: the force and moment times the time function (its place and time
        function registered in ``rows``)."""
        ld = self
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
