"""Supports as eliminated coordinates: which model coordinates are held, the rotated blocks, and
where the held coordinates sit once the supports are installed.

A support acts on one node (``Support``).  Coordinates ``q = T y`` with ``T`` block diagonal:

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
from rancf.errors import InputError

__all__ = ["SupportLayout", "orthonormal_basis", "support_layout"]


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
    fixed = np.zeros(q0.size, dtype=bool)
    rotations: list[tuple[int, NDArray]] = []
    installed: dict[int, float] = {}
    for sup in supports:
        node = check_node(sup.node, "supports.at")
        base = node * dpn if node_base is None else node_base(node)
        if sup.kind not in ("pin", "clamp", "roller"):
            raise InputError("supports.kind", sup.kind, 'one of "pin", "clamp", "roller"')
        pos = _vector("supports.position", sup.position, dim)
        axis = _vector("supports.axis", sup.axis, dim)
        direction = _vector("supports.direction", sup.direction, dim)
        if (axis is None) != (sup.kind != "roller"):
            raise InputError("supports.axis", sup.axis, "given for a roller support only")
        if direction is not None and sup.kind != "clamp":
            raise InputError("supports.direction", sup.direction, "given for a clamp only")
        for key, v in (("supports.axis", axis), ("supports.direction", direction)):
            if v is not None and not np.linalg.norm(v) > 0.0:
                raise InputError(key, v.tolist(), "a nonzero vector")
        target = q0[base : base + dim] if pos is None else pos
        if axis is not None:
            basis = orthonormal_basis(axis)
            rotations.append((base, basis))
            fixed[base + 1 : base + dim] = True
            for i in range(1, dim):
                installed[base + i] = float(basis[:, i] @ target)
        else:
            fixed[base : base + dim] = True
            for i in range(dim):
                installed[base + i] = float(target[i])
        if sup.kind == "clamp":
            if not family(element).gradient:  # θ is the rotation from the reference tangent
                fixed[base + 2] = True
                t0 = tangents[node]
                d = t0 if direction is None else direction
                installed[base + 2] = float(
                    np.arctan2(t0[0] * d[1] - t0[1] * d[0], t0 @ d) + q0[base + 2]
                )
            else:
                grad = q0[base + dim : base + 2 * dim]
                basis = orthonormal_basis(grad if direction is None else direction)
                rotations.append((base + dim, basis))
                fixed[base + dim + 1 : base + 2 * dim] = True
                for i in range(1, dim):
                    installed[base + dim + i] = 0.0
        if framed(element) and (sup.kind == "clamp" or sup.fix_twist):
            fixed[base + 6] = True  # the twist: the cross-section's orientation
            installed[base + 6] = 0.0
        elif sup.fix_twist:
            raise InputError("supports.fix_twist", True, "rod elements (they have a twist)")
    return SupportLayout(fixed, tuple(rotations), installed)
