"""The compiled core's :class:`rancf.kernels._core.System` of a system: built once from one
:class:`~rancf.kernels.records.SystemModel` (``src/cpp/bindings/bindings_system_model.cpp``
reads it field by field); the bodies as Parts, whose records are the model's ``models`` and
``rigid``; the places of the bodies alone in their reference configuration."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.kernels import _core
from rancf.kernels.records import PlaceRecord, SystemModel, TimeFunctionRecord
from rancf.system.parts.flexible import FlexibleBody
from rancf.system.parts.point_mass import PointMassPart
from rancf.system.parts.rigid import RigidBodyPart

__all__ = ["body_parts", "build_core", "PlaceFrames"]

BodyPart = FlexibleBody | RigidBodyPart | PointMassPart


def body_parts(
    names: Sequence[str], bodies: Mapping[str, Model | RigidBody | PointMass]
) -> list[BodyPart]:
    """The bodies ``names`` (in the order of ``y``) of ``bodies`` as Parts."""
    out: list[BodyPart] = []
    for name in names:
        b = bodies[name]
        if isinstance(b, Model):
            out.append(FlexibleBody(name, b))
        elif isinstance(b, RigidBody):
            out.append(RigidBodyPart(name, b))
        else:
            out.append(PointMassPart(name, b))
    return out


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
