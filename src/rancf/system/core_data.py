"""The compiled core's :class:`rancf.kernels._core.System` of a system's bodies and the named
records of its parts (:mod:`rancf.kernels.records`), which the constructor
(``src/cpp/bindings/bindings_system.cpp``) reads field by field."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.kernels import _core
from rancf.kernels.records import (
    JointRecord,
    LinearTerm,
    LoadRecord,
    PlaceRecord,
    PrescribedRecord,
    RigidRecord,
    SpringRecord,
    TimeFunctionRecord,
    floats,
    vec3,
)

__all__ = ["SystemRecords", "build_core", "rigid_record"]


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


def build_core(
    dim: int,
    flex: Sequence[Model],
    rigid: Sequence[RigidBody | PointMass],
    records: SystemRecords,
    gravity: NDArray,
    damping: float,
    y_ref: NDArray,
    stiffness_damping: float = 0.0,
) -> _core.System:
    """The core system of the bodies ``flex`` (their models' cores) and ``rigid`` in dimension
    ``dim`` with the parts ``records``; ``gravity`` ``(3,)`` on rigid bodies and point masses,
    mass-proportional ``damping`` [1/s] of every body, ``y_ref`` the reference coordinates,
    ``stiffness_damping`` [s] of the flexible bodies."""
    core = _core.System(
        dim=dim,
        models=[b.core for b in flex],
        rigid=[rigid_record(b) for b in rigid],
        places=list(records.places),
        joints=list(records.joints),
        springs=list(records.springs),
        loads=list(records.loads),
        time_functions=list(records.time_functions),
        prescribed=list(records.prescribed),
        linear=list(records.linear),
        gravity=floats(gravity),
        damping=damping,
        y_ref=y_ref,
    )
    core.stiffness_damping = float(stiffness_damping)
    return core
