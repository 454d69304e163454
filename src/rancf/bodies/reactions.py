"""Support reactions: the forces and moments the supports exert on the body.

A support holds coordinates that are eliminated from the equations
(:mod:`rancf.bodies.support_layout`), so its reaction is the residual of the held rows.  With
the residual of the equations of motion

    R = M a + c M v + f_int(y) - f_ext(t, y)        (statics: R = f_int(y) - λ f_ext(y))

zero on the free rows, ``R`` on a supported node's rows is what the support adds to the
balance: the reaction.  In full coordinates (``R_q = T R_y``, ``T`` orthogonal):

* force: ``R`` on the node's position;
* moment of a clamped cable end: the gradient's generalized force ``Q`` does virtual work
  ``Q · δr_x`` and a rotation ``δθ`` moves ``δr_x = δθ × r_x``, so ``M = r_x × Q``
  (planar: the ``z`` component);
* rods add the twist's generalized force ``Q_φ``, the moment about the tangent
  (docs/derivations/rod.md §5): ``M = r_x × Q + Q_φ t``; a beam's clamp moment is its rotation row.

The sum of the reactions and of the applied loads (weight included) vanishes at a static
equilibrium; in a dynamic run it equals the rate of change of the body's momentum.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.support_kinds import support_kind

__all__ = ["Reaction", "support_reactions", "has_moment", "support_label"]


@dataclass(frozen=True)
class Reaction:
    """The reaction of one support: ``force (dim,)`` and, for clamps and rods, ``moment``
    (``(1,)``: about ``z`` in a planar model; ``(3,)`` in space); ``extra``: values reported
    after them (a sliding joint's arc length ``s``)."""

    at: int | str
    force: NDArray[np.float64]
    moment: NDArray[np.float64] | None
    extra: NDArray[np.float64] | None = None


def has_moment(model: Model, kind: str) -> bool:
    """Whether the reaction of a support of this kind reports a moment."""
    return model.family.has_triads or support_kind(kind).holds_direction


def support_label(at: int | str) -> str:
    """A support's label in its column names: its place as written, a node index as
    ``nodeK``."""
    return at if isinstance(at, str) else f"node{at}"


def support_reactions(
    model: Model, y: NDArray, residual: NDArray, labels: Sequence[int | str] | None = None
) -> list[Reaction]:
    """Reactions of every support, in the order of ``model.supports``.

    Parameters
    ----------
    model : Model
    y : ndarray, shape (n,) or (k, n)
        Model coordinates (for the nodal gradients); ``k`` states give forces and moments
        ``(k, ...)``.
    residual : ndarray, shape (n,) or (k, n)
        ``M a + c M v + f_int - f_ext`` (or the static ``f_int - λ f_ext``) on every model
        coordinate, held rows included.
    labels : list, optional
        The supports' ``at`` as written in the scenario.
    """
    rq = model.forces_at_nodes(residual)
    q = model.q_from_y(y)
    dim, dpn = model.dim, model.dpn
    out = []
    for i, sup in enumerate(model.supports):
        node = model.check_node(sup.node, "supports.at")
        base = node * dpn
        force = rq[..., base : base + dim].copy()
        moment = None
        if has_moment(model, sup.kind):
            if not model.family.gradient:
                moment = rq[..., base + 2 : base + 3].copy()
            else:
                rx = q[..., base + dim : base + 2 * dim]
                qg = rq[..., base + dim : base + 2 * dim]
                if dim == 2:
                    moment = (rx[..., 0] * qg[..., 1] - rx[..., 1] * qg[..., 0])[..., None]
                else:
                    moment = np.cross(rx, qg)
                    if model.family.has_triads:
                        t = rx / np.linalg.norm(rx, axis=-1, keepdims=True)
                        moment = moment + rq[..., base + 6, None] * t
        out.append(Reaction(labels[i] if labels is not None else sup.node, force, moment))
    return out


def reaction_row(reactions: list[Reaction]) -> NDArray[np.float64]:
    """The reactions flattened: each one's force, moment and extra values, in order (the
    order of their parts' columns, :meth:`rancf.system.parts.support.Support.sensors`)."""
    parts = []
    for r in reactions:
        parts.append(r.force)
        if r.moment is not None:
            parts.append(r.moment)
        if r.extra is not None:
            parts.append(r.extra)
    return np.concatenate(parts, axis=-1) if parts else np.empty(0)
