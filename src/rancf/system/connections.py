"""Joints, springs and loads of a system: Parts (:mod:`rancf.system.part`), one module a kind in
:mod:`rancf.system.parts` (:mod:`~rancf.system.parts.joint`, :mod:`~rancf.system.parts.spring`,
:mod:`~rancf.system.parts.load`), gathered here.

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

from rancf.system.parts.joint import JOINT_KINDS, Joint
from rancf.system.parts.load import Load
from rancf.system.parts.spring import Spring

__all__ = ["Joint", "Spring", "Load", "JOINT_KINDS"]
