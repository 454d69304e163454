"""A joint's data for the compiled core: kind, places and the orientation data measured in the
reference configuration (docs/derivations/systems.md section 3).

Axes are given in world coordinates in the reference configuration and stored in the frames of
the places (``fa``, ``fb``: the rows of each place's frame at the reference; one row, the
tangent, for a cable node; none for a point mass), so every joint holds exactly there.  What each
kind stores is its own (:mod:`rancf.system.parts.joint_kinds`); this module checks what all
kinds share (the axis, the driving angle, the places' orientation) and fills the record.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, ClassVar, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.kernels.records import JointRecord, floats

__all__ = ["JointFields", "JointKindData", "joint_data", "normals"]


class JointFields(Protocol):
    """The fields of a joint the record is made from (:class:`rancf.system.parts.joint.Joint`)."""

    @property
    def kind(self) -> str: ...

    @property
    def between(self) -> tuple[Any, Any]: ...

    @property
    def axis(self) -> Sequence[float] | None: ...

    @property
    def angle(self) -> Any: ...

    @property
    def name(self) -> str: ...

    @property
    def position(self) -> Sequence[float] | None: ...

    @property
    def entry(self) -> JointKindData:
        """Its kind."""
        ...


class JointKindData(Protocol):
    """What the record takes of a joint's kind
    (:class:`rancf.system.parts.joint_kinds.JointKind`)."""

    name: ClassVar[str]
    drivable: ClassVar[bool]
    slides: ClassVar[bool]

    def axis_required(self, dim: int) -> bool: ...

    def needs_orientation(self, fa: NDArray, fb: NDArray, dim: int, driven: bool) -> bool: ...

    def planar(self, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None: ...

    def spatial(
        self, j: Any, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray
    ) -> None: ...


def normals(e: NDArray) -> tuple[NDArray, NDArray]:
    """Two unit vectors normal to ``e`` and to each other."""
    e = e / np.linalg.norm(e)
    helper = np.eye(3)[int(np.argmin(np.abs(e)))]
    n1 = np.cross(e, helper)
    n1 /= np.linalg.norm(n1)
    return n1, np.cross(e, n1)


def _axis(j: JointFields, kind: JointKindData, d: int) -> NDArray | None:
    if j.axis is None:
        if kind.axis_required(d):
            raise InputError("joints.axis", None, f"required for a {j.kind} joint")
        return None
    axis = np.r_[np.asarray(j.axis, dtype=float), np.zeros(3)][:3]
    if np.asarray(j.axis).size != d or not np.linalg.norm(axis) > 0:
        raise InputError("joints.axis", list(j.axis), f"a nonzero vector of {d} numbers")
    return axis / np.linalg.norm(axis)


def _record(info: dict[str, Any]) -> JointRecord:
    vectors = ("rel", "axis_a", "normals_b", "w_a", "w_b")
    fields: dict[str, Any] = {k: floats(v) if k in vectors else v for k, v in info.items()}
    return JointRecord(**fields)


def joint_data(
    j: JointFields,
    kind: JointKindData,
    a: int,
    b: int,
    fa: NDArray,
    fb: NDArray,
    d: int,
    angle: int,
) -> JointRecord:
    """The core's record of joint ``j`` of the kind ``kind`` between the places ``a`` and ``b``
    (their indices among the system's place records) whose reference frames are ``fa``, ``fb``
    ``(k, 3)``, in dimension ``d``; ``angle``: the time function of a driven joint (-1: none)."""
    info: dict = {
        "kind": kind.name,
        "a": a,
        "b": b,
        "driven": False,
        "angle": -1,
        "beta0": 0.0,
        "rel": np.zeros(9),
        "axis_a": np.zeros(3),
        "normals_b": np.zeros(6),
        "w_a": np.zeros(3),
        "w_b": np.zeros(3),
    }
    axis = _axis(j, kind, d)
    if kind.needs_orientation(fa, fb, d, j.angle is not None):
        raise InputError(
            "joints.between",
            [str(x) for x in j.between],
            "places with an orientation for this joint (not a point mass)",
        )
    if j.angle is not None:
        if not kind.drivable:
            raise InputError("joints.angle", "set", "a pin or revolute joint")
        if j.angle.size != 1:
            raise InputError("joints.angle", j.angle.size, "a scalar time function [rad]")
        info["driven"], info["angle"] = True, angle
    if d == 2:
        kind.planar(info, axis, fa, fb)
    else:
        kind.spatial(j, info, axis, fa, fb)
    return _record(info)
