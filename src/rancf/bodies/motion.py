"""Rigid-body motion of a whole model: initial velocity fields and angular momentum.

An initial motion ``[initial_motion]`` is the velocity field of a rigid body,

    v(x) = v₀ + ω × (x − c)                                                            (M.1)

(``c`` = ``about``; in 2D ``ω`` is the rate about ``z``).  It is given *exactly* to every nodal
coordinate: positions get (M.1); the gradients ``r_x`` turn with the body, ``ṙ_x = ω × r_x``; a
beam's rotation ``θ̇ = ω``; a rod's twist rate is the spin about its tangent, ``φ̇ = ω·t``
(at the reference the nodal triads are their own references, so ``φ̇`` is the spin).  The
interpolation is linear in the coordinates and reproduces rigid motions exactly, so the velocity
is (M.1) at every point of every element and the kinetic energy of a rigid rotation is
``½ ωᵀ I ω`` of the modelled body for any mesh (``I`` with the rod's rotary inertia;
``docs/derivations/rod-kernel.md`` §11).  The per-node ``[[initial_velocity]]``, by contrast,
moves one node's position and nothing else (not its neighbours, gradients or twist): a localized
velocity whose kinetic energy depends on the mesh.

Angular momentum about a point ``c`` (M.2)::

    L = ∫ ρA (r − c) × ṙ |r0'| dξ  [+ rods: ∫ (ρ I_p s t + ρ I t × ṫ) |r0'| dξ]

the translational part from the element's scalar mass blocks ``m_kl = ρA ∫ S_k S_l |r0'| dξ``
(``L = Σ m_kl (q_k − c δ_k) × q̇_l``, ``δ_k = 1`` for position blocks), the rotary part by the
core.  A beam adds its lumped rotary inertia ``ρ I l₀ / 2`` per element end.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.layout import BodyLayout
from rancf.errors import InputError

__all__ = [
    "RigidMotion",
    "rigid_velocity",
    "check_supports_at_rest",
    "angular_momentum",
    "initial_velocity",
]


class MovingBody(BodyLayout, Protocol):
    """What rigid motions read of a flexible body (:class:`rancf.bodies.flexible.Model`)."""

    @property
    def fixed(self) -> NDArray[np.bool_]: ...

    @property
    def q0(self) -> NDArray[np.float64]: ...

    @property
    def kernel(self) -> Any: ...

    @property
    def core(self) -> Any: ...

    def y_from_q(self, q: ArrayLike) -> NDArray[np.float64]: ...


@dataclass(frozen=True)
class RigidMotion:
    """An initial rigid-body velocity field ``v = v₀ + ω × (x − about)`` (M.1).

    ``angular_velocity``: 3 components in 3D, one (the rate about ``z``) in 2D.
    """

    velocity: Sequence[float] | None = None
    angular_velocity: Sequence[float] | float | None = None
    about: Sequence[float] | None = None


def _vector(key: str, value: ArrayLike | None, size: int) -> NDArray[np.float64]:
    v = np.zeros(size) if value is None else np.atleast_1d(np.asarray(value, dtype=float))
    if v.shape != (size,) or not np.all(np.isfinite(v)):
        raise InputError(key, np.asarray(value).tolist(), f"{size} finite number(s)")
    return v


def _omega_cross(w: NDArray, r: NDArray) -> NDArray:
    """``ω × r`` for rows ``r`` (2D: ``ω`` the rate about z)."""
    if r.shape[-1] == 2:
        return w[0] * np.stack([-r[..., 1], r[..., 0]], axis=-1)
    return np.cross(w, r)


def rigid_velocity(model: MovingBody, motion: RigidMotion) -> NDArray[np.float64]:
    """Velocities ``q̇`` (full nodal coordinates) of the rigid motion (M.1) at the reference."""
    dim = model.dim
    v0 = _vector("initial_motion.velocity", motion.velocity, dim)
    w = _vector("initial_motion.angular_velocity", motion.angular_velocity, 1 if dim == 2 else 3)
    c = _vector("initial_motion.about", motion.about, dim)
    q = model.q0.reshape(model.n_nodes, model.dpn)
    out = np.zeros_like(q)
    out[:, :dim] = v0 + _omega_cross(w, q[:, :dim] - c)
    if not model.family.gradient:
        out[:, 2] = w[0]
    else:
        grad = q[:, dim : 2 * dim]
        out[:, dim : 2 * dim] = _omega_cross(w, grad)
        if model.family.has_triads:
            out[:, 6] = grad @ w / np.linalg.norm(grad, axis=1)
    return out.ravel()


def check_supports_at_rest(model: MovingBody, v: NDArray) -> None:
    """Raise unless the velocity field ``v`` (model coordinates) leaves held coordinates at rest."""
    scale = max(float(np.abs(v).max(initial=0.0)), 1e-300)
    bad = np.flatnonzero(model.fixed & (np.abs(v) > 1e-12 * scale))
    if bad.size:
        node = int(bad[0] // model.dpn)
        raise InputError(
            "initial_motion",
            f"supported node {node} moving",
            "a rigid motion that leaves the supports at rest (about = a pinned point; a clamp "
            "cannot turn)",
        )


def _scalar_mass_blocks(model: MovingBody) -> NDArray[np.float64]:
    """``m_kl = ρA ∫ S_k S_l |r0'| dξ`` per element ``(n_el, 4, 4)``, blocks rA, r_xA, rB, r_xB."""
    c = model.family.centre_line(model.kernel)
    assert c is not None  # cables and rods only: beams have their own (angular_momentum)
    return c.props.rho_a * np.einsum("eq,eqk,eql->ekl", c.wj, c.n0, c.n0)


def angular_momentum(
    model: MovingBody, q: ArrayLike, v: ArrayLike, about: ArrayLike | None = None
) -> NDArray[np.float64]:
    """Angular momentum (M.2) about ``about`` of states ``q``, ``v`` ``(n_t, n)`` (full coords).

    Returns ``(n_t, 3)`` in 3D and ``(n_t, 1)`` (the ``z`` component) in 2D.  Rods: the states
    must be re-referenced ones (every stored output is), so the twist rate is the nodal spin.
    """
    qq, vv = np.atleast_2d(np.asarray(q, dtype=float)), np.atleast_2d(np.asarray(v, dtype=float))
    dim, n_t = model.dim, qq.shape[0]
    c = _vector("sensors.about", about, dim)
    nodes_q = qq.reshape(n_t, model.n_nodes, model.dpn)
    nodes_v = vv.reshape(n_t, model.n_nodes, model.dpn)
    if not model.family.gradient:  # consistent linear mass ρA l0/6 [2 1; 1 2], lumped ρ I l0 / 2
        k = model.kernel
        xs, vs2 = nodes_q[..., :2] - c, nodes_v[..., :2]
        mt = k.props.rho_a * k.l0 / 6.0
        lz = np.zeros(n_t)
        for a, b, f in ((0, 0, 2.0), (0, 1, 1.0), (1, 0, 1.0), (1, 1, 2.0)):
            p, u = xs[:, a : a + model.n_el], vs2[:, b : b + model.n_el]
            lz += ((p[..., 0] * u[..., 1] - p[..., 1] * u[..., 0]) * f * mt).sum(axis=1)
        th = nodes_v[..., 2]
        lz += (0.5 * k.rho_i * k.l0 * (th[:, :-1] + th[:, 1:])).sum(axis=1)
        return lz[:, None]
    m4 = _scalar_mass_blocks(model)
    g = slice(dim, 2 * dim)
    pos = [
        nodes_q[:, :-1, :dim] - c,
        nodes_q[:, :-1, g],
        nodes_q[:, 1:, :dim] - c,
        nodes_q[:, 1:, g],
    ]
    vel = [nodes_v[:, :-1, :dim], nodes_v[:, :-1, g], nodes_v[:, 1:, :dim], nodes_v[:, 1:, g]]
    out = np.zeros((n_t, 3 if dim == 3 else 1))
    for k in range(4):
        for m in range(4):
            if dim == 3:
                cr = np.cross(pos[k], vel[m])
            else:
                cr = (pos[k][..., 0] * vel[m][..., 1] - pos[k][..., 1] * vel[m][..., 0])[..., None]
            out += np.einsum("e,tei->ti", m4[:, k, m], cr)
    if model.family.has_triads:
        ys, vs = model.y_from_q(qq), model.y_from_q(vv)
        for i in range(n_t):
            out[i] += model.core.rotary_angular_momentum(ys[i], vs[i], True)
    return out


class StartingBody(MovingBody, Protocol):
    """What the initial velocity reads of a flexible body, besides :class:`MovingBody`."""

    @property
    def closed(self) -> bool: ...

    @property
    def reduction(self) -> Any: ...

    @property
    def n(self) -> int: ...

    def check_node(self, node: int, key: str) -> int: ...

    def _own_blocks(self, q: NDArray) -> NDArray[np.float64]: ...


def initial_velocity(
    model: StartingBody,
    initial_velocities: dict[int, ArrayLike] | None,
    initial_motion: RigidMotion | None,
) -> NDArray[np.float64]:
    """The initial velocity in model coordinates, held entries at rest.

    Single nodes' position velocities (``initial_velocities``; nothing else moves, C²: their own
    blocks) or a rigid motion given exactly to every coordinate (M.1), not both.
    """
    v0 = np.zeros(model.n)
    for node, vel in (initial_velocities or {}).items():
        nd = model.check_node(node, "initial_velocity.at")
        vv = np.asarray(vel, dtype=float)
        if vv.size != model.dim:
            raise InputError("initial_velocity.value", vv.tolist(), f"{model.dim} components")
        v0[nd * model.dpn : nd * model.dpn + model.dim] = vv
        if model.closed and nd == 0:  # the stored repeat of node 0 moves with it
            v0[model.n - model.dpn : model.n - model.dpn + model.dim] = vv
    if initial_motion is not None:
        if initial_velocities:
            raise InputError("initial_motion", "with initial_velocity", "one of the two, not both")
        v0 = rigid_velocity(model, initial_motion)
    if model.reduction is None or initial_motion is not None:  # C²: rigid motions are exact
        out = model.y_from_q(v0)
    else:  # single nodes: their own blocks, nothing else moves
        out = model._own_blocks(v0)
    if initial_motion is not None:
        check_supports_at_rest(model, out)
    out[model.fixed] = 0.0
    return out
