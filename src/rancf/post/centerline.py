"""A flexible body's centreline sampled densely from its elements, in one stored configuration.

:func:`sample_centerline` evaluates the *exact* element interpolation, not the node polyline:
for cable elements ``r(ξ) = Σ N_k(ξ) e_k`` with the rational shape functions of
:mod:`rancf.elements.cable` (conic-section paper eqs. 17–22), and the fields

* axial strain (Green–Lagrange, as in the element) ``ε = (|r'|² − |r0'|²) / (2 |r0'|²)``;
* curvature ``κ = (r' × r'')·e_z / |r'|³`` (planar, signed) or ``|r' × r''| / |r'|³`` (spatial);
* displacement ``r − r0`` and velocity ``Σ N_k(ξ) ė_k``.

Rod elements (nodal ``r, r_x, φ``) have the cable's centreline; their runs also store the nodal
directors ``m1`` (:attr:`rancf.post.run_data.RunData.directors`), which with the tangent give
each node's material frame (:func:`nodal_frames`).

Beam elements (nodal ``x, y, θ``) are drawn as the cubic Hermite curve through the nodes with end
tangents ``L (cos ψ, sin ψ)``, ``ψ = ψ0 + θ``, ``L`` the current chord; their axial strain is the
element's chord strain ``(L² − L0²) / (2 L0²)``.

Shape conventions: states ``q``, ``v`` ``(n_t, n_dofs)``; sampled fields ``(n_points, ...)``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from rancf.elements.cable import axial_strain, cable_shape_functions
from rancf.errors import InputError
from rancf.post.run_data import RunData

__all__ = ["Centerline", "NodalFrames", "sample_centerline", "centerline_nodes", "nodal_frames"]


@dataclass(frozen=True)
class Centerline:
    """Dense samples of the centreline in one configuration.

    Attributes
    ----------
    points, reference, displacement, velocity : ndarray, shape (n_points, dim)
    axial_strain, curvature : ndarray, shape (n_points,)
    element : ndarray of int, shape (n_points,)
        Element each sample belongs to (a shared node counts for the element it starts).
    """

    points: NDArray[np.float64]
    reference: NDArray[np.float64]
    displacement: NDArray[np.float64]
    velocity: NDArray[np.float64]
    axial_strain: NDArray[np.float64]
    curvature: NDArray[np.float64]
    element: NDArray[np.int64]


def _join(a: NDArray) -> NDArray:
    """``(n_el, n_xi, ...)`` samples with shared element ends → ``(n_el (n_xi-1) + 1, ...)``."""
    return np.concatenate([a[:, :-1].reshape((-1,) + a.shape[2:]), a[-1:, -1]], axis=0)


def _curvature(d1: NDArray, d2: NDArray) -> NDArray:
    speed = np.linalg.norm(d1, axis=-1)
    if d1.shape[-1] == 2:
        cross = d1[..., 0] * d2[..., 1] - d1[..., 1] * d2[..., 0]
    else:
        cross = np.linalg.norm(np.cross(d1, d2), axis=-1)
    return cross / speed**3


def centerline_nodes(run: RunData, x: NDArray) -> NDArray[np.float64]:
    """Nodal position and gradient ``(n_nodes, 2, dim)`` of a cable or rod state ``x``
    (coordinates or velocities); a rod's twist ``φ`` is left out."""
    if not run.family.gradient:
        raise ValueError("beam elements have no nodal gradients")
    nodes = np.asarray(x, dtype=float).reshape(run.n_nodes, -1)
    return nodes[:, : 2 * run.dim].reshape(run.n_nodes, 2, run.dim)


def _cable_fields(run: RunData, q: NDArray, v: NDArray, xi: NDArray) -> tuple[NDArray, ...]:
    n, n1, n2 = cable_shape_functions(run.weights, run.scales, xi)

    def element_nodal(x: NDArray) -> NDArray:
        nodes = centerline_nodes(run, x)
        return np.concatenate([nodes[:-1], nodes[1:]], axis=1)  # (n_el, 4, dim)

    e, e0, ev = element_nodal(q), element_nodal(run.reference), element_nodal(v)
    r, r0 = np.einsum("eqk,ekd->eqd", n, e), np.einsum("eqk,ekd->eqd", n, e0)
    d1, d10 = np.einsum("eqk,ekd->eqd", n1, e), np.einsum("eqk,ekd->eqd", n1, e0)
    d2 = np.einsum("eqk,ekd->eqd", n2, e)
    vel = np.einsum("eqk,ekd->eqd", n, ev)
    return r, r0, vel, axial_strain(d1, d10), _curvature(d1, d2)


def _hermite(xi: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """Cubic Hermite basis ``[H0, H1, H2, H3]`` and its derivatives, each ``(n_xi, 4)``."""
    x = xi
    h = np.stack(
        [1 - 3 * x**2 + 2 * x**3, x - 2 * x**2 + x**3, 3 * x**2 - 2 * x**3, x**3 - x**2], 1
    )
    h1 = np.stack([-6 * x + 6 * x**2, 1 - 4 * x + 3 * x**2, 6 * x - 6 * x**2, 3 * x**2 - 2 * x], 1)
    h2 = np.stack([-6 + 12 * x, -4 + 6 * x, 6 - 12 * x, 6 * x - 2], 1)
    return h, h1, h2


def _beam_fields(run: RunData, q: NDArray, v: NDArray, xi: NDArray) -> tuple[NDArray, ...]:
    nodes, vel_n = q.reshape(run.n_nodes, 3), v.reshape(run.n_nodes, 3)
    ref = run.reference.reshape(run.n_nodes, 3)
    x, x0, xd = nodes[:, :2], ref[:, :2], vel_n[:, :2]
    chord0 = x0[1:] - x0[:-1]
    if run.tangent_angles is not None:
        psi0 = run.tangent_angles
    else:  # chord directions averaged at interior nodes
        a = np.arctan2(chord0[:, 1], chord0[:, 0])
        psi0 = np.concatenate([[a[0]], 0.5 * (a[:-1] + a[1:]), [a[-1]]])
    h, h1, h2 = _hermite(xi)

    def curve(pos: NDArray, psi: NDArray) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        d = pos[1:] - pos[:-1]
        length = np.linalg.norm(d, axis=1)
        t = np.stack([np.cos(psi), np.sin(psi)], axis=1)
        e = np.stack([pos[:-1], length[:, None] * t[:-1], pos[1:], length[:, None] * t[1:]], 1)
        return tuple(np.einsum("qk,ekd->eqd", b, e) for b in (h, h1, h2)) + (e,)

    r, d1, d2, _ = curve(x, psi0 + nodes[:, 2])
    r0 = curve(x0, psi0)[0]
    # time derivative of the Hermite data: L' = d·d'/L, t' = ψ' (-sin ψ, cos ψ)
    psi = psi0 + nodes[:, 2]
    d, dd = x[1:] - x[:-1], xd[1:] - xd[:-1]
    length = np.linalg.norm(d, axis=1)
    ldot = np.sum(d * dd, axis=1) / length
    t = np.stack([np.cos(psi), np.sin(psi)], axis=1)
    tdot = vel_n[:, 2:3] * np.stack([-np.sin(psi), np.cos(psi)], axis=1)
    ev = np.stack(
        [
            xd[:-1],
            ldot[:, None] * t[:-1] + length[:, None] * tdot[:-1],
            xd[1:],
            ldot[:, None] * t[1:] + length[:, None] * tdot[1:],
        ],
        1,
    )
    vel = np.einsum("qk,ekd->eqd", h, ev)
    strain = np.repeat(axial_strain(d, chord0)[:, None], xi.size, axis=1)
    return r, r0, vel, strain, _curvature(d1, d2)


def sample_centerline(run: RunData, i: int, per_element: int = 16) -> Centerline:
    """The centreline of stored state ``i`` at ``per_element`` equal ξ-steps per element."""
    if isinstance(per_element, bool) or not isinstance(per_element, int) or per_element < 1:
        raise InputError("per_element", per_element, "an integer >= 1")
    xi = np.linspace(0.0, 1.0, per_element + 1)
    fields = _beam_fields if not run.family.gradient else _cable_fields
    r, r0, vel, strain, kappa = fields(run, run.q[i], run.v[i], xi)
    el = np.repeat(np.arange(r.shape[0])[:, None], xi.size, axis=1)
    r, r0 = _join(r), _join(r0)
    return Centerline(
        points=r,
        reference=r0,
        displacement=r - r0,
        velocity=_join(vel),
        axial_strain=_join(strain),
        curvature=_join(kappa),
        element=_join(el),
    )


@dataclass(frozen=True)
class NodalFrames:
    """A rod's nodes in one configuration with their material frames.

    Attributes
    ----------
    points, displacement, velocity : ndarray, shape (n_nodes, 3)
    tangent, m1, m2 : ndarray, shape (n_nodes, 3)
        Unit tangent and the two material axes of the cross-section (``m2 = t × m1``).
    twist : ndarray, shape (n_nodes,)
        The nodal twist coordinate ``φ`` [rad] (cumulative, as the ``twist`` sensor).
    """

    points: NDArray[np.float64]
    displacement: NDArray[np.float64]
    velocity: NDArray[np.float64]
    tangent: NDArray[np.float64]
    m1: NDArray[np.float64]
    m2: NDArray[np.float64]
    twist: NDArray[np.float64]


def nodal_frames(run: RunData, i: int) -> NodalFrames:
    """The nodes and material frames of stored state ``i`` of a rod run (the stored directors
    ``m1``; the tangent is the nodal gradient's direction)."""
    if not run.family.has_triads or run.directors is None:
        raise InputError("RUN_DIR", str(run.path), "a run of rod elements (with stored directors)")
    nodes, ref = centerline_nodes(run, run.q[i]), centerline_nodes(run, run.reference)
    vel = centerline_nodes(run, run.v[i])
    t = nodes[:, 1] / np.linalg.norm(nodes[:, 1], axis=1, keepdims=True)
    m1 = np.asarray(run.directors[i], dtype=float)
    twist = np.asarray(run.q[i], dtype=float).reshape(run.n_nodes, -1)[:, 6]
    return NodalFrames(
        points=nodes[:, 0],
        displacement=nodes[:, 0] - ref[:, 0],
        velocity=vel[:, 0],
        tangent=t,
        m1=m1,
        m2=np.cross(t, m1),
        twist=twist,
    )
