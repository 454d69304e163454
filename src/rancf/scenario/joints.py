"""``[[joints]]`` and ``[[springs]]``: connections between two places.

Joints (``between = [A, B]``, places of :mod:`rancf.scenario.places`, ``"ground"`` included):

* ``pin``: the positions coincide (a revolute joint in 2D, a spherical one in 3D);
* ``revolute`` (3D): positions coincide, the bodies turn about ``axis`` only;
* ``fixed``: positions and orientations coincide (a cable end's tangent, a rod end's material
  frame, a rigid body's frame);
* ``slider``: ``A`` moves along ``axis`` through ``B``, orientation free;
* ``sliding``: the flexible body ``A`` (its name: ``"rope"``; ``"body"`` in a file without
  ``[[bodies]]``) runs through the place ``B`` without friction (a guide, fairlead, sheave point;
  to the ground at ``position``): :mod:`rancf.system.sliding`.

``axis`` (global components in the reference configuration) is required for ``revolute`` and
``slider`` and refused otherwise; ``angle`` (a scalar TIME_FUNCTION, the relative rotation from
the reference [rad]) drives a ``pin`` (2D) or ``revolute`` joint with a rigid body on one side.

Springs: a spring-damper along the line between two places, force ``stiffness (d − length) +
damping ḋ`` (``d`` the distance; ``length`` defaults to the reference distance).
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from rancf.scenario.base import (
    Name,
    NonNegative,
    Positive,
    Table,
    Vector23,
    fail,
    show,
)
from rancf.scenario.place_types import PlacePair
from rancf.scenario.time_functions import TimeFunctionValue, check_scalar
from rancf.system.parts.joint_kinds import KINDS

__all__ = ["JointTable", "SpringTable", "JOINT_KINDS"]

#: Joint kinds (:mod:`rancf.system.parts.joint_kinds`; the schema's list is the same).
JOINT_KINDS = tuple(KINDS)


def _kinds(has: str) -> str:
    """The joint kinds with the flag ``has``, as ``"a and b"``."""
    return " and ".join(k.name for k in KINDS.values() if getattr(k, has))


class JointTable(Table):
    """One joint between two places."""

    name: Name = Field(description="the joint's name (reaction columns and sensors), unique")
    kind: Literal["pin", "revolute", "fixed", "slider", "sliding"] = Field(
        description='"pin" (positions coincide) | "revolute" (3D, about axis) | "fixed" '
        '(positions and orientations coincide) | "slider" (A moves along axis through B) | '
        '"sliding" (the flexible body A runs through B without friction)'
    )
    between: PlacePair = Field(description="the two places joined [A, B]")
    axis: Vector23 | None = Field(
        None, description="revolute: the rotation axis; slider: the line of motion (global)"
    )
    position: Vector23 | None = Field(
        None, description="sliding to the ground: the guide's position (global) [m]"
    )
    angle: TimeFunctionValue | None = Field(
        None,
        description="a driven pin (2D) or revolute joint: the relative rotation from the "
        "reference [rad], a scalar TIME_FUNCTION",
    )

    @model_validator(mode="after")
    def _kind_keys(self) -> JointTable:
        kind = KINDS[self.kind]
        if kind.takes_axis and self.axis is None:
            raise fail("axis", f"required for a {self.kind} joint")
        if not kind.takes_axis and self.axis is not None:
            raise fail("axis", f"applies to {_kinds('takes_axis')} joints only, not {self.kind!r}")
        if self.axis is not None and not any(x != 0.0 for x in self.axis):
            raise fail("axis", "must be a nonzero vector")
        if self.angle is not None and not kind.drivable:
            raise fail("angle", f"drives {_kinds('drivable')} joints only, not {self.kind!r}")
        check_scalar("angle", self.angle)
        if self.position is not None and not kind.slides:
            raise fail("position", f"applies to {_kinds('slides')} joints only, not {self.kind!r}")
        a, b = self.between
        if a == b:
            raise fail("between", f"must be two different places, got {show(a)} twice")
        return self


class SpringTable(Table):
    """A spring-damper between two places."""

    name: Name | None = Field(None, description="optional name")
    between: PlacePair = Field(description="the two places [A, B]")
    stiffness: NonNegative = Field(description="axial stiffness [N/m]")
    damping: NonNegative = Field(0.0, description="axial damping [N s/m]")
    length: Positive | None = Field(
        None, description="rest length [m] (default: the reference distance)"
    )

    @model_validator(mode="after")
    def _something(self) -> SpringTable:
        if self.stiffness == 0.0 and self.damping == 0.0:
            raise fail("stiffness", "stiffness and damping are both 0: the spring does nothing")
        a, b = self.between
        if a == b:
            raise fail("between", f"must be two different places, got {show(a)} twice")
        return self
