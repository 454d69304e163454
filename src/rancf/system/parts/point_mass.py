"""Point masses in a system, a :class:`~rancf.system.part.Part`.

A point mass (:class:`rancf.bodies.rigid.PointMass`: mass, reference position, initial
velocity) gives the compiled core its mass (:class:`rancf.kernels.records.RigidRecord` with
``point_mass``, no inertia; ``src/cpp/system/rigid.hpp``).  It has no columns of its own.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rancf.bodies.rigid import PointMass
from rancf.kernels.records import RigidRecord
from rancf.system.part import NoOutputs

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["PointMassPart"]


@dataclass(frozen=True, eq=False)
class PointMassPart(NoOutputs):
    """The point mass ``name`` of a system, ``body`` (module docstring)."""

    name: str
    body: PointMass

    def record(self, system: Any = None, rows: RecordRows | None = None) -> RigidRecord:
        """Its mass."""
        return RigidRecord(self.body.dim, True, float(self.body.mass))
