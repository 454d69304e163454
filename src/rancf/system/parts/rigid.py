"""Rigid bodies in a system, a :class:`~rancf.system.part.Part`.

A rigid body (:class:`rancf.bodies.rigid.RigidBody`: mass, principal inertia, reference pose,
named points, initial velocities, all checked when it is made) gives the compiled core its
inertia (:class:`rancf.kernels.records.RigidRecord`, ``src/cpp/system/rigid.hpp``); its
coordinates follow the flexible bodies' in ``y`` (:mod:`rancf.system.stack`).  Its outputs
are sensors of its own kinds (``angle``, ``center_of_mass``, ``momentum``,
:mod:`rancf.system.sensors`): no columns of its own.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rancf.bodies.rigid import RigidBody
from rancf.kernels.records import RigidRecord, vec3
from rancf.system.part import NoOutputs

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["RigidBodyPart"]


@dataclass(frozen=True, eq=False)
class RigidBodyPart(NoOutputs):
    """The rigid body ``name`` of a system, ``body`` (module docstring)."""

    name: str
    body: RigidBody

    def record(self, system: Any = None, rows: RecordRows | None = None) -> RigidRecord:
        """Its mass and principal moments of inertia (2D: ``(J, 0, 0)``)."""
        b = self.body
        return RigidRecord(b.dim, False, float(b.mass), vec3(b.inertia_vector()))
