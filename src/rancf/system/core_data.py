"""The compiled core's :class:`rancf.kernels._core.System` of a :class:`rancf.system.System`:
its bodies and the named records of its parts (:mod:`rancf.kernels.records`), which the
constructor (``src/cpp/bindings_system.cpp``) reads field by field."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

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
)
from rancf.system.contact import Obstacle, build_contact

if TYPE_CHECKING:
    from rancf.system.system import System

__all__ = ["SystemRecords", "build_core", "rigid_record", "attach_contact"]


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
    return RigidRecord(b.dim, isinstance(b, PointMass), float(b.mass), floats(inertia))  # type: ignore[arg-type]


def build_core(system: System, records: SystemRecords) -> _core.System:
    """The core system of ``system``'s bodies (its public ``dim``, ``flex``, ``rigid``,
    ``gravity``, ``damping`` and reference ``y0``) with the parts ``records``."""
    return _core.System(
        dim=system.dim,
        models=[b.core for b in system.flex],
        rigid=[rigid_record(b) for b in system.rigid],
        places=list(records.places),
        joints=list(records.joints),
        springs=list(records.springs),
        loads=list(records.loads),
        time_functions=list(records.time_functions),
        prescribed=list(records.prescribed),
        linear=list(records.linear),
        gravity=floats(system.gravity),
        damping=system.damping,
        y_ref=system.y0,
    )


def attach_contact(
    system: System,
    obstacles: Sequence[Obstacle],
    contacts: Sequence[tuple[str, str]] | None,
    n_c: int,
    body_contacts: Sequence[tuple[str, str]] = (),
    body_friction: float = 0.0,
) -> tuple[_core.Contact | None, list[str], list[tuple[str, str]]]:
    """The contact data of ``system`` (:func:`rancf.system.contact.build_contact`: the core's
    :class:`rancf.kernels._core.Contact`, obstacle names, pairs) attached to its core; ``(None,
    [], [])`` without obstacles."""
    if not obstacles and not contacts and not body_contacts:
        return None, [], []
    contact, names, pairs = build_contact(
        system, obstacles, contacts, n_c, body_contacts, body_friction
    )
    system.core.attach_contact(contact)
    return contact, names, pairs
