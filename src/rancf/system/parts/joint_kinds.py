"""The kinds of a :class:`~rancf.system.parts.joint.Joint`: one small class each, found by name in
:data:`KINDS` (docs/derivations/systems.md section 3).

A kind says what a joint of it reads (an ``axis``, a driving ``angle``, a guide ``position``, a
turning ground ``rotation``), whether it reads its places' reference frames, how many position
rows it holds, whether it transmits a moment, its output columns beyond the force and moment, and
the orientation data of its record measured in the places' reference frames (``fa``, ``fb``: the
rows of each place's frame; one row, the tangent, for a cable node; none for a point mass):

* ``pin``: positions coincide (revolute in 2D, spherical in 3D); driven in 2D: the reference
  relative angle ``β0``;
* ``revolute``: 3D: positions, and the ``axis`` in the first frame normal to two normals of it in
  the second (a driven one also the reference normals ``w_a``, ``w_b`` whose angle is the joint
  angle); 2D: a pin;
* ``fixed``: positions and orientations; 2D the reference relative angle ``β0``; 3D between two
  frames their relative rotation ``Fa Fbᵀ``, between a cable tangent and a frame (the core's
  ``tangent`` rows) two normals of the tangent in the frame;
* ``slider``: the first place moves along ``axis`` through the second, orientation free: the
  normal of the axis (2D) or two normals of it (3D) in the second place's frame;
* ``sliding``: a flexible body, the first entry, runs through the second place without friction
  (:mod:`rancf.system.sliding`).

A new kind is one class here with its entry in :data:`KINDS` (the core's joint rows are in
``src/cpp/system/joints.cpp``).
"""

from __future__ import annotations

from typing import Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.system.joint_data import normals
from rancf.system.sliding import sliding_joint, sliding_values

__all__ = ["JointKind", "KINDS", "joint_kind"]


def _between(j: Any) -> list[str]:
    return [str(x) for x in j.between]


class JointKind:
    """A joint kind (module docstring); the defaults are a pin's."""

    name: ClassVar[str] = "pin"
    #: It takes an ``axis`` (in the scenario: required, and read by no other kind).
    takes_axis: ClassVar[bool] = False
    #: An ``angle`` may drive it.
    drivable: ClassVar[bool] = True
    #: A flexible body runs through its place (a guide ``position`` to the ground).
    slides: ClassVar[bool] = False
    #: Its ground frame may turn (``rotation``: a turning clamp).
    turns: ClassVar[bool] = False
    #: Its places' positions coincide (a point mass on it goes where its other place goes).
    joins_positions: ClassVar[bool] = True

    def axis_required(self, dim: int) -> bool:
        """Whether its record needs an ``axis`` in dimension ``dim``."""
        return False

    def uses_frames(self, driven: bool) -> bool:
        """Whether its record reads its places' reference frames (a pin's positions need none;
        a driven joint measures its angle in them)."""
        return driven

    def needs_orientation(self, fa: NDArray, fb: NDArray, dim: int, driven: bool) -> bool:
        """Whether its places lack the orientation it holds (a point mass has none)."""
        return driven and (len(fb) < 3 or (len(fa) < 3 and dim == 2))

    def gap_rows(self, dim: int) -> int:
        """How many of its first constraint rows measure how far apart its places are."""
        return 2 if dim == 2 else 3

    def transmits_moment(self, dim: int, driven: bool) -> bool:
        """Whether it transmits a moment (a driven joint does)."""
        return driven

    def columns(self, label: str) -> list[str]:
        """Its output columns after the force and moment."""
        return []

    def values(self, system: Any, k: int, y: NDArray, lam: NDArray) -> list[float]:
        """The values of :meth:`columns` for joint ``k`` at ``(y, λ)``."""
        return []

    def record(self, j: Any, system: Any, rows: Any) -> Any:
        """The core's record of joint ``j`` (None: the places and frames of
        :meth:`rancf.system.parts.joint.Joint.record`)."""
        return None

    def planar(self, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        """Its 2D orientation data into ``info`` (a driven joint: ``β0``)."""
        if info["driven"]:
            info["beta0"] = float(np.arctan2(fa[0] @ fb[1], fa[0] @ fb[0]))

    def spatial(self, j: Any, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        """Its 3D orientation data into ``info`` (a pin: none; it cannot be driven)."""
        if info["driven"]:
            raise InputError("joints.angle", "pin", "a revolute joint in 3D (it needs an axis)")


class Revolute(JointKind):
    """``revolute`` (module docstring)."""

    name = "revolute"
    takes_axis = True

    def axis_required(self, dim: int) -> bool:
        return dim == 3

    def uses_frames(self, driven: bool) -> bool:
        return True

    def transmits_moment(self, dim: int, driven: bool) -> bool:
        return driven or dim == 3

    def planar(self, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        info["kind"] = "pin"
        super().planar(info, axis, fa, fb)

    def spatial(self, j: Any, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        if len(fa) < 3 or len(fb) < 3:
            raise InputError(
                "joints.between",
                _between(j),
                "places with a frame (a 3D cable node has only a tangent: a rod)",
            )
        assert axis is not None  # required in 3D
        n1, n2 = normals(axis)
        info["axis_a"], info["normals_b"] = fa @ axis, np.r_[fb @ n1, fb @ n2]
        if info["driven"]:
            info["w_a"], info["w_b"] = fa @ n1, fb @ n1


class Fixed(JointKind):
    """``fixed`` (module docstring)."""

    name = "fixed"
    drivable = False
    turns = True

    def uses_frames(self, driven: bool) -> bool:
        return True

    def needs_orientation(self, fa: NDArray, fb: NDArray, dim: int, driven: bool) -> bool:
        return len(fb) < 3 or (len(fa) < 3 and dim == 2)

    def transmits_moment(self, dim: int, driven: bool) -> bool:
        return True

    def planar(self, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        info["beta0"] = float(np.arctan2(fa[0] @ fb[1], fa[0] @ fb[0]))

    def spatial(self, j: Any, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        if len(fa) == 3 and len(fb) == 3:
            info["rel"] = (fa @ fb.T).ravel()
        elif len(fa) == 1 and len(fb) == 3:
            info["kind"] = "tangent"
            n1, n2 = normals(fa[0])
            info["normals_b"] = np.r_[fb @ n1, fb @ n2]
        else:
            raise InputError(
                "joints.kind",
                "fixed",
                "a frame on at least one side (a 3D cable has only a tangent: use rods)",
            )


class Slider(JointKind):
    """``slider`` (module docstring)."""

    name = "slider"
    takes_axis = True
    drivable = False
    joins_positions = False

    def axis_required(self, dim: int) -> bool:
        return True

    def uses_frames(self, driven: bool) -> bool:
        return True

    def needs_orientation(self, fa: NDArray, fb: NDArray, dim: int, driven: bool) -> bool:
        return len(fb) < 3

    def gap_rows(self, dim: int) -> int:
        return dim - 1

    def planar(self, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        assert axis is not None  # required
        normal = np.array([-axis[1], axis[0], 0.0])
        info["normals_b"][:3] = fb @ normal

    def spatial(self, j: Any, info: dict, axis: NDArray | None, fa: NDArray, fb: NDArray) -> None:
        if len(fb) < 3:
            raise InputError("joints.between", str(j.between[1]), "a place with a frame")
        assert axis is not None  # required
        n1, n2 = normals(axis)
        info["normals_b"] = np.r_[fb @ n1, fb @ n2]


class Sliding(JointKind):
    """``sliding`` (module docstring): its record and arc length are
    :mod:`rancf.system.sliding`'s; its place is checked on its body, not by a gap."""

    name = "sliding"
    drivable = False
    slides = True
    joins_positions = False

    def gap_rows(self, dim: int) -> int:
        return 0

    def columns(self, label: str) -> list[str]:
        """The arc length ``LABEL_s`` of its place along the body."""
        return [f"{label}_s"]

    def values(self, system: Any, k: int, y: NDArray, lam: NDArray) -> list[float]:
        return [sliding_values(system, k, y, lam)]

    def record(self, j: Any, system: Any, rows: Any) -> Any:
        return sliding_joint(system, j, rows)


#: The joint kinds by name, in the scenario's order.
KINDS: dict[str, JointKind] = {
    k.name: k for k in (JointKind(), Revolute(), Fixed(), Slider(), Sliding())
}


def joint_kind(name: str, key: str = "joints.kind") -> JointKind:
    """The joint kind called ``name``; an unknown name is one line naming ``key``."""
    try:
        return KINDS[name]
    except KeyError:
        raise InputError(key, name, f"one of {', '.join(KINDS)}") from None
