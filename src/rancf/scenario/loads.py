"""``[[supports]]``, ``[loads]`` (gravity, ``[[loads.point]]``),
``[[initial_velocity]]`` and ``[initial_motion]`` (``[damping]``: ``rancf.scenario.damping``).

TIME_FUNCTION values are those of :mod:`rancf.scenario.time_functions`.

Rules besides the types (each violation names its key):

* ``[[supports]]``: ``axis`` for rollers only (and required there), ``direction`` for clamps
  only, both nonzero; ``fix_twist = true`` (rods) also holds the twist of a pin; ``motion`` is a
  displacement vector from the reference position (not with ``position``).
* ``[[loads.point]]``: ``force``, ``moment`` or both; ``time`` (a factor on both) or the older
  ``frequency_hz`` (``sin(2π f t)``), not both.
* ``[initial_motion]``: ``velocity`` and/or ``angular_velocity`` (3 numbers in 3D, one in 2D)
  and ``about`` (default the origin): the rigid-body velocity field ``v = velocity + ω × (x −
  about)`` (:mod:`rancf.bodies.motion`).
"""

from __future__ import annotations

from typing import Any, Literal

from pydantic import Field, model_validator

from rancf.scenario.base import (
    Flag,
    Name,
    NumberOrVector3,
    NumberOrVector123,
    Positive,
    Table,
    Vector3,
    Vector23,
    fail,
    show,
    to_number,
)
from rancf.scenario.place_types import PlaceValue
from rancf.scenario.time_functions import TimeFunctionValue, check_scalar, time_size

__all__ = [
    "DistributedLoadTable",
    "SupportTable",
    "PointLoadTable",
    "EdgeLoadTable",
    "LoadsTable",
    "InitialVelocityTable",
    "InitialMotionTable",
]

Amount = NumberOrVector123


class SupportTable(Table):
    """``[[supports]]``: a place held fixed, or moved along a prescribed path."""

    at: PlaceValue = Field(description="the supported place")
    kind: Literal["pin", "clamp", "roller", "diaphragm", "symmetry"] = Field(
        "pin",
        description='"pin" (position fixed) | "clamp" (position and direction) | "roller" '
        '(moves along axis only) | shells: "diaphragm" (an edge\'s displacements in its plane '
        'fixed) | "symmetry" (an edge on the plane with normal `normal`)',
    )
    fix_twist: Flag = Field(
        False, description="rods: also hold the twist (a clamp holds it anyway)"
    )
    position: Vector23 | None = Field(
        None, description="installed position [m] (default: the reference; see Equilibrium)"
    )
    direction: Vector23 | None = Field(
        None, description="clamps: the installed tangent direction (default: the reference)"
    )
    axis: Vector23 | None = Field(None, description="rollers: the line it moves along")
    normal: Vector3 | None = Field(
        None, description="symmetry (shells): the normal of the plane of symmetry"
    )
    motion: TimeFunctionValue | None = Field(
        None,
        description="prescribed displacement from the reference position [m]: a vector "
        "TIME_FUNCTION",
    )

    @model_validator(mode="after")
    def _kinds(self) -> SupportTable:
        if self.kind == "roller" and self.axis is None:
            raise fail("axis", "required for a roller (the direction it moves along)")
        if self.kind != "roller" and self.axis is not None:
            raise fail("axis", f'applies to kind = "roller" only, not {self.kind!r}')
        if (self.kind == "symmetry") != (self.normal is not None):
            raise fail("normal", 'required for kind = "symmetry" and only there')
        if self.kind != "clamp" and self.direction is not None:
            raise fail("direction", f'applies to kind = "clamp" only, not {self.kind!r}')
        for k in ("direction", "axis", "normal"):
            if self[k] is not None and not any(x != 0.0 for x in self[k]):
                raise fail(k, "must be a nonzero vector")
        if self.motion is not None:
            if time_size(self.motion) is None:
                raise fail("motion", "must be a vector time function (a displacement [m])")
            if self.position is not None:
                raise fail("motion", "give position (installed) or motion (prescribed), not both")
        return self


class PointLoadTable(Table):
    """``[[loads.point]]``: a force and/or a moment at a place."""

    at: PlaceValue = Field(description="where the load acts")
    force: Vector23 | None = Field(None, description="force [N]")
    moment: NumberOrVector3 | None = Field(
        None,
        description="moment [N m]: [mx, my, mz] (rods, 3D rigid bodies); a number (the "
        "torque about z) on a 2D rigid body",
    )
    frequency_hz: Positive | None = Field(
        None, description="a harmonic load F sin(2 pi f t) [Hz] (or time)"
    )
    time: TimeFunctionValue | None = Field(
        None, description="a scalar TIME_FUNCTION multiplying force and moment"
    )

    @model_validator(mode="after")
    def _given(self) -> PointLoadTable:
        if self.force is None and self.moment is None:
            raise fail("force", "required key is missing (give force, moment or both)")
        if self.time is not None and self.frequency_hz is not None:
            raise fail("time", "give time or frequency_hz, not both")
        check_scalar("time", self.time)
        return self


class DistributedLoadTable(Table):
    """``[[loads.distributed]]``: a force per reference length on flexible bodies
    (:mod:`rancf.scenario.fluid`)."""

    force: Vector23 = Field(
        description="force per reference length, global axes [N/m] (shells: per reference "
        "area [N/m^2])"
    )
    body: Name | None = Field(None, description="the flexible body (default: every one)")
    time: TimeFunctionValue | None = Field(
        None, description="a scalar TIME_FUNCTION multiplying the force"
    )

    @model_validator(mode="after")
    def _scalar(self) -> DistributedLoadTable:
        check_scalar("time", self.time)
        return self


class EdgeLoadTable(Table):
    """``[[loads.edge]]``: a total force and/or moment spread evenly along a shell's edge
    (docs/derivations/shell.md sec. 6)."""

    at: PlaceValue = Field(description='the edge: "u0", "u1", "v0", "v1" ("BODY:u1" with bodies)')
    force: Vector3 | None = Field(None, description="total force on the edge [N]")
    moment: Vector3 | None = Field(
        None,
        description="total moment [N m]: its component along the edge bends, the one across "
        "it twists (a component along the normal is refused)",
    )
    time: TimeFunctionValue | None = Field(
        None, description="a scalar TIME_FUNCTION multiplying force and moment"
    )

    @model_validator(mode="after")
    def _given(self) -> EdgeLoadTable:
        if self.force is None and self.moment is None:
            raise fail("force", "required key is missing (give force, moment or both)")
        check_scalar("time", self.time)
        return self


class LoadsTable(Table):
    """``[loads]``: gravity on every body, point loads and distributed loads."""

    gravity: Vector23 | None = Field(None, description="gravitational acceleration [m/s^2]")
    point: list[PointLoadTable] = Field([], description="point forces and moments")
    distributed: list[DistributedLoadTable] = Field(
        [], description="forces per length on flexible bodies [N/m] (shells: per area [N/m^2])"
    )
    edge: list[EdgeLoadTable] = Field(
        [], description="shells: a total force or moment spread along an edge"
    )


class InitialVelocityTable(Table):
    """``[[initial_velocity]]``: the velocity of one node's position (nothing else moves)."""

    at: PlaceValue = Field(description="the node")
    value: Vector23 = Field(description="velocity [m/s]")


class InitialMotionTable(Table):
    """``[initial_motion]``: a rigid-body velocity field ``v = velocity + ω × (x − about)``."""

    velocity: Vector23 | None = Field(None, description="translation velocity [m/s]")
    angular_velocity: NumberOrVector3 | None = Field(
        None, description="[rad/s]: 3 components in 3D, the rate about z in 2D"
    )
    about: Vector23 | None = Field(
        None, description="the point omega turns about [m] (default: the origin)"
    )

    @model_validator(mode="after")
    def _some(self) -> InitialMotionTable:
        if self.velocity is None and self.angular_velocity is None:
            raise fail("", "needs velocity and/or angular_velocity")
        return self

    def check_dim(self, dim: int) -> None:
        """Raise unless the vectors have ``dim`` components (keys relative to the table)."""
        for k in ("velocity", "about"):
            v = self[k]
            if v is not None and len(v) != dim:
                raise fail(k, f"must be a list of {dim} numbers, got {show(v)}")
        w = self.angular_velocity
        if dim == 2 and isinstance(w, list):
            raise fail(
                "angular_velocity", f"must be a number in 2D (the rate about z), got {show(w)}"
            )
        if dim == 3 and w is not None and not isinstance(w, list):
            raise fail("angular_velocity", f"must be a list of 3 numbers, got {show(w)}")

    def as_dict(self) -> dict[str, Any]:
        """The table with ``angular_velocity`` as a list (one number in 2D)."""
        w = self.angular_velocity
        return {
            "velocity": self.velocity,
            "angular_velocity": w if w is None or isinstance(w, list) else [to_number(w)],
            "about": self.about,
        }
