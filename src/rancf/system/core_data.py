"""The compiled core's :class:`rancf.kernels._core.System` of a system's bodies and the named
records of its parts: one :class:`~rancf.kernels.records.SystemModel`, which the constructor
(``src/cpp/bindings/bindings_system_model.cpp``) reads field by field, every part at once."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.kernels import _core
from rancf.kernels.contact_records import ContactRecord
from rancf.kernels.records import (
    FluidRecord,
    JointRecord,
    LinearTerm,
    LineRecord,
    LoadRecord,
    PlaceRecord,
    PrescribedRecord,
    RigidRecord,
    SlidingRecord,
    SpringRecord,
    SystemModel,
    TimeFunctionRecord,
    WinchRecord,
    vec3,
)

__all__ = [
    "SystemRecords",
    "Attached",
    "system_model",
    "build_core",
    "PlaceFrames",
    "rigid_record",
]


@dataclass(frozen=True)
class SystemRecords:
    """The parts of a system as the core takes them (:mod:`rancf.kernels.records`): places,
    joints, springs, loads, the time functions they and the prescribed motions refer to (by
    position), and the linear rows that close closed flexible bodies."""

    places: tuple[PlaceRecord, ...] = ()
    joints: tuple[JointRecord, ...] = ()
    springs: tuple[SpringRecord, ...] = ()
    loads: tuple[LoadRecord, ...] = ()
    time_functions: tuple[TimeFunctionRecord, ...] = ()
    prescribed: tuple[PrescribedRecord, ...] = ()
    linear: tuple[LinearTerm, ...] = ()


def rigid_record(b: RigidBody | PointMass) -> RigidRecord:
    """The core's record of a rigid body or point mass."""
    inertia = b.inertia_vector() if isinstance(b, RigidBody) else np.zeros(3)
    return RigidRecord(b.dim, isinstance(b, PointMass), float(b.mass), vec3(inertia))


@dataclass(frozen=True)
class Attached:
    """The parts beside the records of :class:`SystemRecords` the core is built with: the fluid
    and the flexible bodies in it, the contact, the winches and the bodies sliding joints run
    along (:mod:`rancf.kernels.records`)."""

    fluid: FluidRecord | None = None
    lines: tuple[LineRecord, ...] = ()
    contact: ContactRecord | None = None
    winches: tuple[WinchRecord, ...] = ()
    sliding: tuple[SlidingRecord, ...] = ()


def system_model(
    dim: int,
    flex: Sequence[Model],
    rigid: Sequence[RigidBody | PointMass],
    records: SystemRecords,
    gravity: NDArray,
    damping: float,
    y_ref: NDArray,
    stiffness_damping: float = 0.0,
    attached: Attached | None = None,
) -> SystemModel:
    """The model record of the bodies ``flex`` (their models' cores) and ``rigid`` in dimension
    ``dim`` with the parts ``records`` and ``attached``; ``gravity`` ``(3,)`` on rigid bodies and
    point masses, mass-proportional ``damping`` [1/s] of every body, ``y_ref`` the reference
    coordinates, ``stiffness_damping`` [s] of the flexible bodies."""
    attached = attached or Attached()
    return SystemModel(
        dim=dim,
        models=tuple(b.core for b in flex),
        y_ref=np.ascontiguousarray(y_ref, dtype=float),
        gravity=vec3(gravity),
        damping=float(damping),
        stiffness_damping=float(stiffness_damping),
        rigid=tuple(rigid_record(b) for b in rigid),
        **_by_name(records),
        **_by_name(attached),
    )


def _by_name(parts: SystemRecords | Attached) -> dict[str, Any]:
    """The fields of ``parts`` by name (not copied): each is the model record's field of that
    name, so a field added to :class:`SystemRecords` or :class:`Attached` reaches the core."""
    return {f.name: getattr(parts, f.name) for f in fields(parts)}


def build_core(model: SystemModel) -> _core.System:
    """The core system of a model record, every part at once."""
    return _core.System(model)


class PlaceFrames:
    """The places of a model's bodies in their reference configuration, evaluated as they are
    made (the joints' reference frames): built once from the bodies of ``model``
    (:class:`rancf.kernels._core.PlaceFrames`)."""

    def __init__(self, model: SystemModel) -> None:
        self._core = _core.PlaceFrames(model)
        self._y = np.ascontiguousarray(model.y_ref, dtype=float)

    def __call__(
        self, places: Sequence[PlaceRecord], time_functions: Sequence[TimeFunctionRecord]
    ) -> list[tuple[NDArray, NDArray]]:
        """``(position (3,), frame rows (k, 3))`` of each of ``places`` at ``t = 0``."""
        return [
            (np.asarray(x), np.asarray(f).reshape(-1, 3))
            for x, f in self._core(list(places), list(time_functions), self._y, 0.0)
        ]
