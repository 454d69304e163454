"""Supports as eliminated coordinates: which model coordinates are held, the rotated blocks, and
where the held coordinates sit once the supports are installed.

A support acts on one node (``Support``; its kind: :mod:`rancf.bodies.support_kinds`).
Coordinates ``q = T y`` with ``T`` block diagonal:

* pin: the node's position entries of ``y`` are held;
* roller: the position block is rotated into the basis ``(a, n0[, n1])`` of its ``axis`` and the
  normal components are held (the node slides along the axis);
* clamp: the position is held and the gradient block is rotated into the basis of the held
  tangent (the ``direction``, default the reference tangent) and its normal components held, so
  the gradient may still stretch along the tangent; a beam holds its rotation ``θ``; a rod its
  twist ``φ`` (also a pin or roller with ``fix_twist``).

Installation.  The held entries of ``y`` take the values of the installed supports
(:attr:`SupportLayout.installed`): ``position`` for the position (a roller: the normal
components of its point), zero normal components of a clamp's gradient in the basis of its
``direction``.  Without ``position`` and ``direction`` these are the reference values.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.families import family, framed
from rancf.bodies.properties import Support
from rancf.bodies.support_kinds import Held, orthonormal_basis, support_kind
from rancf.errors import InputError

__all__ = ["SupportLayout", "orthonormal_basis", "support_layout"]


@dataclass(frozen=True)
class SupportLayout:
    """Held coordinates, rotated blocks ``(offset, basis)`` and installed values of ``y``."""

    fixed: NDArray[np.bool_]
    rotations: tuple[tuple[int, NDArray[np.float64]], ...]
    installed: dict[int, float]


def _vector(key: str, v: Sequence[float] | None, dim: int) -> NDArray | None:
    if v is None:
        return None
    a = np.asarray(v, dtype=float)
    if a.shape != (dim,) or not np.all(np.isfinite(a)):
        raise InputError(key, list(v), f"{dim} finite numbers")
    return a


def support_layout(
    supports: Sequence[Support],
    element: str,
    dim: int,
    dpn: int,
    q0: NDArray,
    tangents: NDArray,
    check_node: Callable[[int, str], int],
    node_base: Callable[[int], int] | None = None,
) -> SupportLayout:
    """The :class:`SupportLayout` of ``supports`` on a chain with reference coordinates ``q0``
    and reference nodal tangents ``tangents (n_nodes, dim)``.  ``node_base``: the first index of
    a node's own coordinates in ``q0`` and ``y`` (default ``node dpn``; C² models: the node's
    block among the spline coordinates, :mod:`rancf.mesh.continuity`).

    Raises
    ------
    InputError
        Naming ``supports.kind``, ``supports.axis``, ``supports.position``,
        ``supports.direction`` or ``supports.fix_twist``.
    """
    held = Held(np.zeros(q0.size, dtype=bool))
    for sup in supports:
        node = check_node(sup.node, "supports.at")
        base = node * dpn if node_base is None else node_base(node)
        kind = support_kind(sup.kind)
        pos = _vector("supports.position", sup.position, dim)
        axis = _vector("supports.axis", sup.axis, dim)
        direction = _vector("supports.direction", sup.direction, dim)
        if (axis is None) == kind.takes_axis:
            raise InputError("supports.axis", sup.axis, "given for a roller support only")
        if direction is not None and not kind.holds_direction:
            raise InputError("supports.direction", sup.direction, "given for a clamp only")
        for key, v in (("supports.axis", axis), ("supports.direction", direction)):
            if v is not None and not np.linalg.norm(v) > 0.0:
                raise InputError(key, v.tolist(), "a nonzero vector")
        target = q0[base : base + dim] if pos is None else pos
        kind.hold_position(held, base, target, axis)
        gradient = family(element).gradient
        kind.hold_direction(held, base, gradient, q0, tangents[node], direction)
        if framed(element) and (kind.holds_direction or sup.fix_twist):
            held.fixed[base + 6] = True  # the twist: the cross-section's orientation
            held.installed[base + 6] = 0.0
        elif sup.fix_twist:
            raise InputError("supports.fix_twist", True, "rod elements (they have a twist)")
    return SupportLayout(held.fixed, tuple(held.rotations), held.installed)
