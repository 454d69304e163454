"""A shell's loads as consistent nodal vectors (docs/derivations/shell.md sec. 6).

With ``r(ξ, η) = S(ξ, η) q`` (eq. 3.2) a load does the virtual work ``δW = Qᵀ δq``:

* a point force ``F`` at ``[u, v]``: ``Q = S(ξ, η)ᵀ F``;
* a force per reference area ``p``: ``Q = ∫ Sᵀ p dA``, ``dA = |A1 × A2| dξ dη`` (eq. 4.3),
  Gauss-Legendre per element;
* a total edge force ``F`` spread evenly per reference length: ``Q = ∫ Sᵀ (F / L) ds``;
* a total edge moment ``M``: its component along the edge's reference tangent ``T`` bends,
  ``m = (M · T) / L`` per length working on the rotation ``θ`` of the cross tangent ``a_ν``
  about ``T``, ``δθ = δa_ν · (T × A_ν) / |A_ν|²`` at the reference; its component along the
  in-surface edge normal ``ν = T × a3`` twists, statically equivalent (Kirchhoff) to the forces
  ``± (M · ν) / L a3`` at the edge's ends; a component along ``a3`` (drilling) has no conjugate
  in Kirchhoff-Love theory and is refused.

The vectors are those of the reference configuration (dead loads); :func:`resultant` gives the
total force and moment a nodal vector carries (the work of rigid motions), which the checks
compare with the loads given.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre

if TYPE_CHECKING:
    from rancf.bodies.shell import ShellBody

__all__ = [
    "point_load",
    "distributed_load",
    "edge_load",
    "edge_frames",
    "resultant",
    "DRILLING_RTOL",
]

#: Largest component of an edge moment along the surface normal, relative to its size.
DRILLING_RTOL = 1e-9
#: Gauss points per element direction of the area and edge integrals (docs: 8 x 8 gives the
#: area of an 80° element to 2e-11, 16 x 16 to 1e-15).
LOAD_POINTS = 16


def _vector(v: ArrayLike, key: str) -> NDArray[np.float64]:
    a = np.asarray(v, dtype=float).ravel()
    if a.size != 3 or not np.all(np.isfinite(a)):
        raise InputError(key, v, "three finite numbers [x, y, z]")
    return a


def point_load(body: ShellBody, at: ArrayLike, force: ArrayLike) -> NDArray[np.float64]:
    """``Q = S(ξ, η)ᵀ F`` of a force at the surface point ``at = [u, v]``."""
    f = _vector(force, "force")
    idx, fac = body.shape_row(at)
    out = np.zeros(body.n_dofs)
    np.add.at(out, idx, fac[:, None] * f[None, :])
    return out


def _basis(body: ShellBody, x: NDArray) -> tuple[list[NDArray], list[NDArray]]:
    u, v = body.mesh.u, body.mesh.v
    return (
        cable_shape_functions(u.weights, u.scales, x),
        cable_shape_functions(v.weights, v.scales, x),
    )


def _scatter(body: ShellBody, qe: NDArray) -> NDArray[np.float64]:
    """Element vectors ``qe[j, i, a, b, c]`` added into the body's coordinates."""
    out = np.zeros(body.n_dofs)
    for j in range(body.mesh.v.n):
        for i in range(body.mesh.u.n):
            np.add.at(out, body.element_dofs(i, j), qe[j, i])
    return out


def distributed_load(
    body: ShellBody, force: ArrayLike, points: int = LOAD_POINTS
) -> NDArray[np.float64]:
    """``Q = ∫ Sᵀ p dA`` of a force ``p`` per reference area (eq. 4.3)."""
    p = _vector(force, "force")
    x, w = gauss_legendre(points)
    nu, nv = _basis(body, x)
    mesh = body.mesh
    da = np.linalg.norm(
        np.cross(mesh.evaluate(x, x, order=(1, 0)), mesh.evaluate(x, x, order=(0, 1))), axis=-1
    )
    qe = np.einsum("p,q,ipa,jqb,jipq->jiab", w, w, nu[0], nv[0], da)
    return _scatter(body, qe[..., None] * p)


def _edge_samples(body: ShellBody, edge: str, x: NDArray) -> list[tuple[int, int, NDArray]]:
    """Per element along ``edge``: ``(i, j, rows)`` with ``rows (3, n, 4, 4)`` the factors of
    ``r``, of ``∂r/∂(along)`` and of ``∂r/∂(across)`` at the Gauss points ``x`` of the edge."""
    u, v = body.mesh.u, body.mesh.v
    out = []
    if edge in ("v0", "v1"):
        j, eta = (0, 0.0) if edge == "v0" else (v.n - 1, 1.0)
        mv = cable_shape_functions(v.weights[j : j + 1], v.scales[j : j + 1], eta)
        for i in range(u.n):
            mu = cable_shape_functions(u.weights[i : i + 1], u.scales[i : i + 1], x)
            rows = [np.einsum("pa,b->pab", mu[a][0], mv[b][0, 0]) for a, b in _ORDERS_U]
            out.append((i, j, np.stack(rows)))
    else:
        i, xi = (0, 0.0) if edge == "u0" else (u.n - 1, 1.0)
        mu = cable_shape_functions(u.weights[i : i + 1], u.scales[i : i + 1], xi)
        for j in range(v.n):
            mv = cable_shape_functions(v.weights[j : j + 1], v.scales[j : j + 1], x)
            rows = [np.einsum("a,pb->pab", mu[a][0, 0], mv[b][0]) for a, b in _ORDERS_V]
            out.append((i, j, np.stack(rows)))
    return out


#: ``(order along u, order along v)`` of ``r``, the along and the across derivatives.
_ORDERS_U = ((0, 0), (1, 0), (0, 1))
_ORDERS_V = ((0, 0), (0, 1), (1, 0))


def edge_frames(body: ShellBody, edge: str, points: int) -> list[tuple]:
    """Per element along ``edge``: ``(dofs, rows, T, A_ν, a3, ds)`` at its Gauss points."""
    if edge not in ("u0", "u1", "v0", "v1"):
        raise InputError("at", edge, 'an edge "u0", "u1", "v0" or "v1"')
    x, w = gauss_legendre(points)
    out = []
    for i, j, rows in _edge_samples(body, edge, x):
        dofs = body.element_dofs(i, j)
        e = body.q0[dofs]
        tang, cross = (np.einsum("pab,abc->pc", rows[k], e) for k in (1, 2))
        a12 = (cross, tang) if edge in ("u0", "u1") else (tang, cross)
        a3 = np.cross(*a12)
        a3 /= np.linalg.norm(a3, axis=1, keepdims=True)
        ds = np.linalg.norm(tang, axis=1) * w
        t = tang / np.linalg.norm(tang, axis=1, keepdims=True)
        out.append((dofs, rows, t, cross, a3, ds))
    return out


def edge_load(
    body: ShellBody,
    edge: str,
    force: ArrayLike | None = None,
    moment: ArrayLike | None = None,
    points: int = LOAD_POINTS,
) -> NDArray[np.float64]:
    """``Q`` of a total ``force`` and/or ``moment`` spread evenly along ``edge`` (module
    docstring)."""
    frames = edge_frames(body, edge, points)
    length = float(sum(f[5].sum() for f in frames))
    out = np.zeros(body.n_dofs)
    f = None if force is None else _vector(force, "force")
    m = None if moment is None else _vector(moment, "moment")
    for dofs, rows, t, cross, a3, ds in frames:
        if f is not None:
            np.add.at(out, dofs, np.einsum("pab,p->ab", rows[0], ds)[..., None] * f / length)
        if m is not None:
            _check_drilling(m, a3, edge)
            per = np.einsum("c,pc->p", m, t) / length * ds
            g = per[:, None] * np.cross(t, cross) / np.einsum("pc,pc->p", cross, cross)[:, None]
            np.add.at(out, dofs, np.einsum("pab,pc->abc", rows[2], g))
    if m is not None:
        out += _twist(body, edge, m, length)
    return out


def _check_drilling(m: NDArray, a3: NDArray, edge: str) -> None:
    if np.abs(a3 @ m).max() > DRILLING_RTOL * float(np.linalg.norm(m)):
        raise InputError(
            "moment",
            m.tolist(),
            f"a moment without a component along the surface normal at edge {edge} "
            "(a drilling moment has no conjugate in a Kirchhoff-Love shell)",
        )


def _twist(body: ShellBody, edge: str, m: NDArray, length: float) -> NDArray[np.float64]:
    """The twisting part: ``∓ (M · ν) / L a3`` at the start and the end of the edge, with
    ``T``, ``a3`` and ``ν = T × a3`` at those points."""
    fixed = {"u0": 0.0, "u1": 1.0, "v0": 0.0, "v1": 1.0}[edge]
    along_v = edge in ("u0", "u1")
    out = np.zeros(body.n_dofs)
    for sign, s in ((-1.0, 0.0), (1.0, 1.0)):
        uv = (fixed, s) if along_v else (s, fixed)
        a1, a2 = (_at(body, uv, order) for order in ((1, 0), (0, 1)))
        t = a2 if along_v else a1
        t = t / np.linalg.norm(t)
        a3 = np.cross(a1, a2)
        a3 /= np.linalg.norm(a3)
        out += point_load(body, uv, sign * float(m @ np.cross(t, a3)) / length * a3)
    return out


def _at(body: ShellBody, uv: tuple[float, float], order: tuple[int, int]) -> NDArray:
    idx, fac = body.shape_row(uv, order)
    return np.einsum("k,kc->c", fac, body.q0[idx])


def resultant(
    body: ShellBody, load: ArrayLike, about: ArrayLike = (0.0, 0.0, 0.0)
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Total force and moment about ``about`` of a nodal vector ``Q``: its work on a rigid
    translation and on a rigid rotation, which turns every nodal vector, ``Σ Q_r`` and
    ``Σ (r − about) × Q_r + Σ_(gradients) e_k × Q_k``."""
    q = np.asarray(load, dtype=float).reshape(-1, 4, 3)
    e = body.q0.reshape(-1, 4, 3).copy()
    e[:, 0] -= np.asarray(about, dtype=float)
    return q[:, 0].sum(axis=0), np.cross(e, q).sum(axis=(0, 1))
