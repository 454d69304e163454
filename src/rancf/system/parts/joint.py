"""Joints: a joint between two places, a :class:`~rancf.system.part.Part`.

Joint kinds (docs/derivations/systems.md section 3), one class each in
:mod:`rancf.system.parts.joint_kinds`: ``"pin"`` (positions coincide: revolute in 2D,
spherical in 3D), ``"revolute"`` (3D: positions, and the ``axis`` of the first place normal to the
second's frame's normals of it), ``"fixed"`` (positions and orientations: a cable end's tangent
direction, a rod end's material frame, a rigid body's frame), ``"slider"`` (the first place moves
along ``axis`` through the second, orientation free), ``"sliding"`` (a flexible body, the first
entry, runs through the second place without friction: :mod:`rancf.system.sliding`; to the ground
at ``position``). A pin or revolute with ``angle`` is driven: the relative rotation from the
reference follows the time function [rad]. A joint to the ground may move its ground point
(``motion``, a displacement) and a fixed one turn its ground frame (``rotation``: 2D the angle
about z, 3D the rotation vector [rad]; a turning clamp, ``docs/derivations/clamp-paths.md``).
Axes are given in world coordinates in the reference configuration.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels.records import JointRecord
from rancf.system.joint_data import joint_data
from rancf.system.parts.joint_kinds import KINDS, JointKind, joint_kind
from rancf.system.parts.support import reaction_reader
from rancf.system.places import Place
from rancf.system.readers import SensorBuilder

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["Joint", "JOINT_KINDS"]

JOINT_KINDS = tuple(KINDS)


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
    #: A fixed joint to the ground: the ground's frame turns by this rotation from the world
    #: axes (2D the angle about z, 3D the rotation vector [rad]; a turning clamp).
    rotation: TimeFunction | None = None
    #: Its sensor kinds: its ``reaction`` (:func:`rancf.system.parts.support.reaction_reader`).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {"reaction": reaction_reader}

    @property
    def entry(self) -> JointKind:
        """Its kind (:mod:`rancf.system.parts.joint_kinds`); an unknown one is one line naming
        ``joints.kind``."""
        return joint_kind(self.kind)

    def record(self, system: Any, rows: RecordRows) -> JointRecord:
        """The core's record: its places (and a moving ground's time function) registered in
        ``rows`` with a driven joint's angle, its orientation data measured in their reference
        frames (``system.reference_frames``, its kind's, :mod:`rancf.system.joint_data`); a kind
        with a record of its own gives it (a body through a place)."""
        kind = self.entry
        own = kind.record(self, system, rows)
        if own is not None:
            return own
        motion, angle = rows.tf(self.motion), rows.tf(self.angle)
        a, b = system.place_pair(self.between, rows, motion, self._rotation(system.dim, rows))
        fa = fb = np.zeros((0, 3))  # a pin reads no frames
        if kind.uses_frames(self.angle is not None):
            frames = system.reference_frames(rows)
            fa, fb = frames[a][1], frames[b][1]
            if self.rotation is not None:  # measured against the unturned axes
                fb = np.eye(3)
        return joint_data(self, kind, a, b, fa, fb, system.dim, angle)

    def _rotation(self, dim: int, rows: RecordRows) -> int:
        """The time function of the ground frame's rotation registered in ``rows`` (-1: none),
        its kind and size checked."""
        if self.rotation is None:
            return -1
        if not self.entry.turns:
            raise InputError("supports.rotation", self.kind, "a clamp (a fixed joint)")
        size = 1 if dim == 2 else 3
        if self.rotation.size != size or (dim == 3) != self.rotation.vector:
            what = "the angle about z (a scalar)" if dim == 2 else "a rotation vector of 3"
            raise InputError("supports.rotation", self.rotation.size, f"{what} [rad]")
        return rows.tf(self.rotation)

    def reference_gap(self, g: NDArray, dim: int) -> float:
        """How far apart its places are, from its constraint rows ``g`` (from its first row on)
        at the reference: its position rows' norm (a slider's ``dim - 1`` rows across its axis);
        a sliding joint's place is checked on its body instead
        (:func:`rancf.system.sliding.sliding_starts`), and a moving ground point is the body's
        place's reference point moved by its motion at ``t = 0`` (a static start installs it
        there; a jump from rest is warned about or refused where the motion is read)."""
        if self.motion is not None:
            return 0.0
        return float(np.linalg.norm(g[: self.entry.gap_rows(dim)]))

    def transmits_moment(self, dim: int) -> bool:
        """Whether it transmits a moment (``fixed``, a 3D ``revolute``, a driven joint)."""
        return self.entry.transmits_moment(dim, self.angle is not None)

    def label(self, system: Any) -> str:
        """Its name, or ``jointK`` (its position ``K`` among the system's joints)."""
        return self.name or f"joint{_index(system, self)}"

    def sensors(self, system: Any) -> Sequence[str]:
        """Its reaction columns: the force it exerts on its first place ``LABEL_fx, _fy[,
        _fz]``, its moment where it transmits one (``LABEL_mz``; 3D ``LABEL_mx, _my, _mz``),
        a sliding joint's arc length ``LABEL_s`` (:mod:`rancf.system.sliding`)."""
        lab, dim = self.label(system), system.dim
        cols = [f"{lab}_f{a}" for a in "xyz"[:dim]]
        if self.transmits_moment(dim):
            cols += [f"{lab}_mz"] if dim == 2 else [f"{lab}_m{a}" for a in "xyz"]
        return cols + self.entry.columns(lab)

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """Its force and moment on its first place's body (world axes) and a sliding joint's
        arc length at ``(y, λ, t)`` (:meth:`sensors`)."""
        k, dim = _index(system, self), system.dim
        force, moment = system.core.joint_reaction(k, y, t, lam)
        values = [*np.asarray(force)[:dim]]
        if self.transmits_moment(dim):
            values += [*(np.asarray(moment)[2:] if dim == 2 else np.asarray(moment))]
        values += self.entry.values(system, k, y, lam)
        return dict(zip(self.sensors(system), map(float, values), strict=True))


def _index(system: Any, joint: Joint) -> int:
    """The position of ``joint`` among the system's joints."""
    return next(k for k, j in enumerate(system.joints) if j is joint)
