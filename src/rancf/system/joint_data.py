"""A joint's data for the compiled core: kind, places and the orientation data measured in the
reference configuration (docs/derivations/systems.md section 3).

Axes are given in world coordinates in the reference configuration and stored in the frames of
the places (``fa``, ``fb``: the rows of each place's frame at the reference; one row, the
tangent, for a cable node; none for a point mass), so every joint holds exactly there:

* 2D ``fixed`` or driven pin: the reference relative angle ``β0``; 2D ``slider``: the normal of
  the axis in the second place's frame;
* 3D ``fixed`` between two frames: their relative rotation ``Fa Fbᵀ``; between a cable tangent
  and a frame (``tangent`` rows): two normals of the tangent in the frame;
* 3D ``slider``: two normals of the axis in the second frame; 3D ``revolute``: the axis in the
  first frame and two normals of it in the second (a driven one also the reference normals
  ``w_a``, ``w_b`` whose angle is the joint angle).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.kernels.records import JointRecord, floats

__all__ = ["JointFields", "joint_data", "normals", "uses_frames"]


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


def normals(e: NDArray) -> tuple[NDArray, NDArray]:
    """Two unit vectors normal to ``e`` and to each other."""
    e = e / np.linalg.norm(e)
    helper = np.eye(3)[int(np.argmin(np.abs(e)))]
    n1 = np.cross(e, helper)
    n1 /= np.linalg.norm(n1)
    return n1, np.cross(e, n1)


def _axis(j: JointFields, d: int) -> NDArray | None:
    if j.axis is None:
        if j.kind in ("revolute", "slider") and not (d == 2 and j.kind == "revolute"):
            raise InputError("joints.axis", None, f"required for a {j.kind} joint")
        return None
    axis = np.r_[np.asarray(j.axis, dtype=float), np.zeros(3)][:3]
    if np.asarray(j.axis).size != d or not np.linalg.norm(axis) > 0:
        raise InputError("joints.axis", list(j.axis), f"a nonzero vector of {d} numbers")
    return axis / np.linalg.norm(axis)


def _between(j: JointFields) -> list[str]:
    return [str(x) for x in j.between]


def _record(info: dict[str, Any]) -> JointRecord:
    vectors = ("rel", "axis_a", "normals_b", "w_a", "w_b")
    fields: dict[str, Any] = {k: floats(v) if k in vectors else v for k, v in info.items()}
    return JointRecord(**fields)


def uses_frames(j: JointFields) -> bool:
    """Whether the record of ``j`` reads its places' reference frames: a fixed, slider or
    revolute joint, or a driven one (a pin's positions need none)."""
    return j.kind in ("fixed", "slider", "revolute") or j.angle is not None


def joint_data(
    j: JointFields, a: int, b: int, fa: NDArray, fb: NDArray, d: int, angle: int
) -> JointRecord:
    """The core's record of joint ``j`` between the places ``a`` and ``b`` (their indices among
    the system's place records) whose reference frames are ``fa``, ``fb`` ``(k, 3)``, in
    dimension ``d``; ``angle``: the time function of a driven joint (-1: none)."""
    info: dict = {
        "kind": j.kind,
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
    axis = _axis(j, d)
    need = {"fixed": True, "slider": True}.get(j.kind, j.angle is not None)
    if need and (len(fb) < 3 or (j.kind != "slider" and len(fa) < 3 and d == 2)):
        raise InputError(
            "joints.between",
            _between(j),
            "places with an orientation for this joint (not a point mass)",
        )
    if j.angle is not None:
        if j.kind not in ("pin", "revolute"):
            raise InputError("joints.angle", "set", "a pin or revolute joint")
        if j.angle.size != 1:
            raise InputError("joints.angle", j.angle.size, "a scalar time function [rad]")
        info["driven"], info["angle"] = True, angle
    if d == 2:
        if j.kind == "revolute":
            info["kind"] = "pin"
        if j.kind == "fixed" or j.angle is not None:
            info["beta0"] = float(np.arctan2(fa[0] @ fb[1], fa[0] @ fb[0]))
        if j.kind == "slider":
            assert axis is not None  # required (_axis)
            normal = np.array([-axis[1], axis[0], 0.0])
            info["normals_b"][:3] = fb @ normal
        return _record(info)
    if j.kind == "fixed":
        if len(fa) == 3 and len(fb) == 3:
            info["rel"] = (fa @ fb.T).ravel()
            return _record(info)
        if len(fa) == 1 and len(fb) == 3:
            info["kind"] = "tangent"
            n1, n2 = normals(fa[0])
            info["normals_b"] = np.r_[fb @ n1, fb @ n2]
            return _record(info)
        raise InputError(
            "joints.kind",
            "fixed",
            "a frame on at least one side (a 3D cable has only a tangent: use rods)",
        )
    if j.kind == "slider":
        if len(fb) < 3:
            raise InputError("joints.between", str(j.between[1]), "a place with a frame")
        assert axis is not None  # required (_axis)
        n1, n2 = normals(axis)
        info["normals_b"] = np.r_[fb @ n1, fb @ n2]
        return _record(info)
    if j.kind == "revolute":
        if len(fa) < 3 or len(fb) < 3:
            raise InputError(
                "joints.between",
                _between(j),
                "places with a frame (a 3D cable node has only a tangent: a rod)",
            )
        assert axis is not None  # required in 3D (_axis)
        n1, n2 = normals(axis)
        info["axis_a"], info["normals_b"] = fa @ axis, np.r_[fb @ n1, fb @ n2]
        if j.angle is not None:
            info["w_a"], info["w_b"] = fa @ n1, fb @ n1
        return _record(info)
    if j.angle is not None:
        raise InputError("joints.angle", "pin", "a revolute joint in 3D (it needs an axis)")
    return _record(info)
