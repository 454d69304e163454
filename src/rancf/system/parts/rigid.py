"""Rigid bodies in a system, a :class:`~rancf.system.part.Part`.

A rigid body (:class:`rancf.bodies.rigid.RigidBody`: mass, principal inertia, reference pose,
named points, initial velocities, all checked when it is made) gives the compiled core its
inertia (:class:`rancf.kernels.records.RigidRecord`, ``src/cpp/system/rigid.hpp``); its
coordinates follow the flexible bodies' in ``y`` (:mod:`rancf.system.stack`).  Its outputs
are sensors: its ``angle`` [rad] (2D, continuous as integrated; 3D its rotation vector), and
with the system's ``center_of_mass`` and ``momentum`` (:mod:`rancf.system.sensors`): no columns
of its own.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from rancf.bodies.rigid import RigidBody
from rancf.errors import InputError
from rancf.kernels.records import RigidRecord, vec3
from rancf.system.part import NoOutputs
from rancf.system.readers import Reader, SensorBuilder, SensorHost

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["RigidBodyPart"]


def angle_reader(host: SensorHost, sen: Any) -> Reader:
    """An ``angle`` sensor of the rigid body ``sen.body`` (module docstring)."""
    s = host.system
    b = s.bodies.get(sen.body)
    if not isinstance(b, RigidBody):
        rigid = [n for n, x in s.bodies.items() if isinstance(x, RigidBody)]
        raise InputError(
            f"sensors.{sen.name}.body", sen.body, f"a rigid body: {', '.join(rigid) or 'none'}"
        )
    o = s.offsets[sen.body]
    if s.dim == 2:
        return lambda blk: blk[1][:, o + 2]
    from scipy.spatial.transform import Rotation

    return lambda blk: Rotation.from_quat(blk[1][:, o + 3 : o + 7][:, [1, 2, 3, 0]]).as_rotvec()


@dataclass(frozen=True, eq=False)
class RigidBodyPart(NoOutputs):
    """The rigid body ``name`` of a system, ``body`` (module docstring)."""

    name: str
    body: RigidBody
    #: Its sensor kinds (module docstring).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {"angle": angle_reader}

    def record(self, system: Any = None, rows: RecordRows | None = None) -> RigidRecord:
        """Its mass and principal moments of inertia (2D: ``(J, 0, 0)``)."""
        b = self.body
        return RigidRecord(b.dim, False, float(b.mass), vec3(b.inertia_vector()))
