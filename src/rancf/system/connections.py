"""Joints, springs and loads of a system (frozen values; :class:`rancf.system.System` assembles;
a spring is a part of its own, :mod:`rancf.system.parts.spring`).

Joint kinds (docs/derivations/systems.md section 3): ``"pin"`` (positions coincide: revolute in 2D,
spherical in
3D), ``"revolute"`` (3D: positions, and the ``axis`` of the first place normal to the second's
frame's normals of it), ``"fixed"`` (positions and orientations: a cable end's tangent direction,
a rod end's material frame, a rigid body's frame), ``"slider"`` (the first place moves along
``axis`` through the second, orientation free), ``"sliding"`` (a flexible body, the first entry,
runs through the second place without friction: :mod:`rancf.system.sliding`; to the ground at
``position``).  A pin or revolute with ``angle`` is driven: the
relative rotation from the reference follows the time function [rad].  Axes are given in world
coordinates in the reference configuration.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

from rancf.bodies.time_function import TimeFunction
from rancf.system.parts.spring import Spring
from rancf.system.places import Place

__all__ = ["Joint", "Spring", "Load", "JOINT_KINDS"]

JOINT_KINDS = ("pin", "revolute", "fixed", "slider", "sliding")


@dataclass(frozen=True)
class Joint:
    """A joint between two places (module docstring)."""

    kind: str
    between: tuple[Place | str, Place | str]
    axis: Sequence[float] | None = None
    angle: TimeFunction | None = None
    name: str = ""
    #: A joint to the ground: the ground point moves by this displacement (a moving support).
    motion: TimeFunction | None = None
    #: A sliding joint to the ground: the guide's position (world, reference configuration).
    position: Sequence[float] | None = None


@dataclass(frozen=True)
class Load:
    """A force (and, on a rigid body, a torque) at a place, world axes, times ``time`` (a
    factor; None: constant)."""

    at: Place | str
    force: Sequence[float] | None = None
    torque: Sequence[float] | None = None
    time: TimeFunction | None = None
