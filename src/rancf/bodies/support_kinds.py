"""The kinds of a flexible body's support (:class:`rancf.bodies.properties.Support`): one small
class each, found by name in :data:`KINDS`.

A kind says how it holds its node's position (:mod:`rancf.bodies.support_layout`: a pin and a
clamp hold all of it, a roller its components normal to its ``axis``), whether it also holds
the direction (a clamp: the tangent, a beam's rotation, a rod's twist, and so it reports a
moment), whether its held position may follow a motion, and the joint to the ground that stands
for it at a rigid body's place or as a turning clamp (:mod:`rancf.system.parts.joint_kinds`).
A new kind is one class here with its entry in :data:`KINDS`.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import ClassVar

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError

__all__ = ["Held", "KINDS", "SupportKind", "orthonormal_basis", "support_kind"]


def orthonormal_basis(t: NDArray) -> NDArray:
    """Columns ``(t, n0[, n1])``: an orthonormal basis whose first vector is ``t / |t|``."""
    t = np.asarray(t, dtype=float)
    t = t / np.linalg.norm(t)
    if t.size == 2:
        return np.array([[t[0], -t[1]], [t[1], t[0]]])
    helper = np.eye(3)[int(np.argmin(np.abs(t)))]
    n0 = np.cross(t, helper)
    n0 /= np.linalg.norm(n0)
    n1 = np.cross(t, n0)
    return np.stack([t, n0, n1], axis=1)


@dataclass
class Held:
    """What the supports hold, filled kind by kind: held entries of ``y``, rotated blocks
    ``(offset, basis)`` and installed values
    (:class:`rancf.bodies.support_layout.SupportLayout`)."""

    fixed: NDArray[np.bool_]
    rotations: list[tuple[int, NDArray]] = field(default_factory=list)
    installed: dict[int, float] = field(default_factory=dict)


class SupportKind:
    """A support kind; the defaults are a pin's: its position held, not its direction."""

    name: ClassVar[str] = "pin"
    #: It takes an ``axis`` (a roller's line of motion; required).
    takes_axis: ClassVar[bool] = False
    #: It holds the direction too (takes a ``direction``; reports a moment).
    holds_direction: ClassVar[bool] = False
    #: Its held position may follow a ``motion``.
    moves: ClassVar[bool] = True
    #: The joint kind to the ground that stands for it at a rigid place.
    joint: ClassVar[str] = "pin"

    def hold_position(self, held: Held, base: int, target: NDArray, axis: NDArray | None) -> None:
        """Hold the position entries from ``base`` at ``target``."""
        dim = target.size
        held.fixed[base : base + dim] = True
        for i in range(dim):
            held.installed[base + i] = float(target[i])

    def hold_direction(
        self,
        held: Held,
        base: int,
        gradient: bool,
        q0: NDArray,
        tangent: NDArray,
        direction: NDArray | None,
    ) -> None:
        """Hold the direction at the node whose entries start at ``base`` (reference
        coordinates ``q0``, reference tangent ``tangent``; ``gradient``: the nodes hold ``r_x``,
        else a beam's ``θ``) along ``direction`` (None: the reference); a pin holds none."""


class Roller(SupportKind):
    """A roller: the node moves along its ``axis`` only; the position block is rotated into the
    basis ``(a, n0[, n1])`` of the axis and the normal components are held at ``target``'s."""

    name = "roller"
    takes_axis = True
    moves = False
    joint = "slider"

    def hold_position(self, held: Held, base: int, target: NDArray, axis: NDArray | None) -> None:
        assert axis is not None  # required (takes_axis)
        dim = target.size
        basis = orthonormal_basis(axis)
        held.rotations.append((base, basis))
        held.fixed[base + 1 : base + dim] = True
        for i in range(1, dim):
            held.installed[base + i] = float(basis[:, i] @ target)


class Clamp(SupportKind):
    """A clamp: position and direction held.  A beam holds its rotation ``θ`` (the rotation
    from the reference tangent); a cable or rod rotates its gradient block into the basis of the
    held tangent and holds its normal components at zero, so the gradient may still stretch."""

    name = "clamp"
    holds_direction = True
    joint = "fixed"

    def hold_direction(
        self,
        held: Held,
        base: int,
        gradient: bool,
        q0: NDArray,
        tangent: NDArray,
        direction: NDArray | None,
    ) -> None:
        dim = tangent.size
        if not gradient:
            held.fixed[base + 2] = True
            t0 = tangent
            d = t0 if direction is None else direction
            held.installed[base + 2] = float(
                np.arctan2(t0[0] * d[1] - t0[1] * d[0], t0 @ d) + q0[base + 2]
            )
            return
        grad = q0[base + dim : base + 2 * dim]
        basis = orthonormal_basis(grad if direction is None else direction)
        held.rotations.append((base + dim, basis))
        held.fixed[base + dim + 1 : base + 2 * dim] = True
        for i in range(1, dim):
            held.installed[base + dim + i] = 0.0


#: The support kinds by name.
KINDS: dict[str, SupportKind] = {k.name: k for k in (SupportKind(), Clamp(), Roller())}


def support_kind(name: str, key: str = "supports.kind") -> SupportKind:
    """The support kind called ``name``; an unknown name is one line naming ``key``."""
    try:
        return KINDS[name]
    except KeyError:
        allowed = ", ".join(f'"{k}"' for k in KINDS)
        raise InputError(key, name, f"one of {allowed}") from None
