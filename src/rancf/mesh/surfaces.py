"""Exact surface meshes for RANCF shells: tensor products of RANCF cable elements.

Every element is a bicubic rational Bézier patch with product weights ``w_ab = w^u_a w^v_b``, so
its rational basis factors (docs/derivations/shell.md eq. 2.2) and its shape functions are the
products of the cable element's (eq. 3.2).  Each node carries ``[r, r_x, r_y, r_xy]``
(eq. 3.1); nodes are numbered ``j (nu + 1) + i`` (u fastest), coordinates node by node.  The
gradient scales of each direction follow the cable's walk, run on every control row at once
(eq. 3.4), which makes every shared nodal vector consistent: the assembled reference is the
geometry to round-off, C⁰ and G¹ (in the scaled parameters C¹) across every element edge.

The five kinds and their parameters are built in :mod:`rancf.mesh.surface_kinds`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions, control_to_nodal_matrix
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre
from rancf.mesh.mesh import GRADIENT_SPAN_WARNING

__all__ = ["EDGES", "Direction", "SurfaceMesh", "mesh_from_patches", "scale_walk"]

#: Edge names: ``"u0"`` is the edge ``u = 0`` (nodes ``i = 0``), ``"v1"`` the edge ``v = 1``.
EDGES = ("u0", "u1", "v0", "v1")
#: Relative mismatch of the nodal data two elements give a shared node above which the patches
#: do not join tangent-continuously (a kink, or a cross-derivative ratio that varies along an
#: edge, eq. 3.5).
JOIN_RTOL = 1e-9


@dataclass(frozen=True)
class Direction:
    """One parameter direction of a tensor-product mesh (docs/derivations/shell.md sec. 3).

    Attributes
    ----------
    weights : ndarray, shape (n, 4)
        The cubic weights ``w^u_a`` (or ``w^v_b``) of each element, end weight ``w_0 = 1``.
    scales : ndarray, shape (n,)
        Gradient scales ``l_e`` (eq. 3.4).
    breaks : ndarray, shape (n + 1,)
        Surface parameter (``u`` or ``v`` in [0, 1]) of the element ends.
    k : ndarray, shape (n,)
        Mapping factor of each element (NaN: a straight or NURBS direction).
    half_angle : ndarray, shape (n,)
        Half the angle a circular element turns through (NaN: the element's parameter is an
        affine image of the surface parameter).
    closed : bool
        The direction closes on itself (a full 360° turn): the last node repeats the first.
    """

    weights: NDArray[np.float64]
    scales: NDArray[np.float64]
    breaks: NDArray[np.float64]
    k: NDArray[np.float64]
    half_angle: NDArray[np.float64]
    closed: bool = False

    @property
    def n(self) -> int:
        """Number of elements along this direction."""
        return int(self.weights.shape[0])

    def locate(self, s: float) -> tuple[int, float]:
        """Element and element parameter ``ξ`` of the surface parameter ``s ∈ [0, 1]`` (eq. 3.6).

        Affine elements: ``ξ = (s - s_e) / (s_{e+1} - s_e)``.  Circular elements (half angle
        ``α``, Möbius factor ``ρ = (K / (1 - K))^(1/3)``): the angle ``ψ = 2 α f`` along the
        element, the quadratic parameter ``t = (1 + tan((ψ - α)/2) / tan(α/2)) / 2`` and
        ``ξ = t / (ρ (1 - t) + t)``.
        """
        e = int(np.clip(np.searchsorted(self.breaks, s, side="right") - 1, 0, self.n - 1))
        f = (s - self.breaks[e]) / (self.breaks[e + 1] - self.breaks[e])
        alpha = self.half_angle[e]
        if not np.isfinite(alpha):
            return e, float(f)
        t = 0.5 * (1.0 + np.tan((2.0 * f - 1.0) * alpha / 2.0) / np.tan(alpha / 2.0))
        rho = np.cbrt(self.k[e] / (1.0 - self.k[e]))
        return e, float(t / (rho * (1.0 - t) + t))


@dataclass(frozen=True)
class SurfaceMesh:
    """A tensor-product mesh of ``nu × nv`` RANCF shell elements (module docstring).

    Attributes
    ----------
    nodes : ndarray, shape (nv + 1, nu + 1, 4, 3)
        Reference nodal vectors ``[r, r_x, r_y, r_xy]`` of node ``(i, j)`` at ``[j, i]``.
    u, v : Direction
        The two directions' element data.
    kind : str
        The geometry kind it was made from.
    """

    nodes: NDArray[np.float64]
    u: Direction
    v: Direction
    kind: str = "nurbs_surface"

    @property
    def shape(self) -> tuple[int, int]:
        """``(nu, nv)``: elements along ``u`` and along ``v``."""
        return self.u.n, self.v.n

    @property
    def n_nodes(self) -> int:
        """Number of stored nodes ``(nu + 1)(nv + 1)`` (a closed direction repeats its first)."""
        return int(self.nodes.shape[0] * self.nodes.shape[1])

    @property
    def q0(self) -> NDArray[np.float64]:
        """The reference nodal coordinates, node by node (12 per node)."""
        return self.nodes.reshape(-1).copy()

    def element_nodal(self, q: ArrayLike | None = None) -> NDArray[np.float64]:
        """Element nodal coordinates ``E[j, i, a, b]`` ``(nv, nu, 4, 4, 3)`` (eq. 3.1).

        ``a`` runs over ``(rA, rA_x, rB, rB_x)`` along ``u``, ``b`` likewise along ``v``; node
        data ``k = g_u + 2 g_v`` (``g`` = 1 for a gradient) give ``r, r_x, r_y, r_xy``.
        """
        nd = self.nodes if q is None else np.asarray(q, dtype=float).reshape(self.nodes.shape)
        out = np.empty((self.v.n, self.u.n, 4, 4, 3))
        for nj in (0, 1):
            for ni in (0, 1):
                block = nd[nj : nj + self.v.n, ni : ni + self.u.n]
                for gu in (0, 1):
                    for gv in (0, 1):
                        out[:, :, 2 * ni + gu, 2 * nj + gv] = block[:, :, gu + 2 * gv]
        return out

    def evaluate(
        self, xi: ArrayLike, eta: ArrayLike, q: ArrayLike | None = None, order: tuple = (0, 0)
    ) -> NDArray[np.float64]:
        """``∂^(m+n) r / ∂ξ^m ∂η^n`` on the grid ``xi × eta`` of every element, ``order = (m, n)``
        (each at most 2), shape ``(nv, nu, n_xi, n_eta, 3)`` (eq. 3.2)."""
        nu = cable_shape_functions(self.u.weights, self.u.scales, xi)[order[0]]
        nv = cable_shape_functions(self.v.weights, self.v.scales, eta)[order[1]]
        return np.einsum("ipa,jqb,jiabd->jipqd", nu, nv, self.element_nodal(q))

    def locate(self, at: ArrayLike) -> tuple[int, int, float, float]:
        """Element ``(i, j)`` and ``(ξ, η)`` of the surface point ``at = [u, v]`` in [0, 1]²."""
        a = np.asarray(at, dtype=float).ravel()
        if a.size != 2 or not np.all((a >= 0.0) & (a <= 1.0)):
            raise InputError("at", at, "a surface point [u, v] with 0 <= u, v <= 1")
        i, xi = self.u.locate(float(a[0]))
        j, eta = self.v.locate(float(a[1]))
        return i, j, xi, eta

    def point(self, at: ArrayLike, q: ArrayLike | None = None) -> NDArray[np.float64]:
        """The position of the surface point ``at = [u, v]`` (configuration ``q``)."""
        i, j, xi, eta = self.locate(at)
        return self._at(i, j, xi, eta, q, (0, 0))

    def normal(self, at: ArrayLike, q: ArrayLike | None = None) -> NDArray[np.float64]:
        """The unit normal ``a3 = a1 × a2 / |a1 × a2|`` at ``at = [u, v]`` (eq. 4.2)."""
        i, j, xi, eta = self.locate(at)
        n = np.cross(self._at(i, j, xi, eta, q, (1, 0)), self._at(i, j, xi, eta, q, (0, 1)))
        return n / np.linalg.norm(n)

    def _at(
        self, i: int, j: int, xi: float, eta: float, q: ArrayLike | None, order: tuple
    ) -> NDArray[np.float64]:
        nu = cable_shape_functions(self.u.weights[i : i + 1], self.u.scales[i : i + 1], xi)
        nv = cable_shape_functions(self.v.weights[j : j + 1], self.v.scales[j : j + 1], eta)
        e = self.element_nodal(q)[j, i]
        return np.einsum("a,b,abd->d", nu[order[0]][0, 0], nv[order[1]][0, 0], e)

    def normals(self, xi: ArrayLike, eta: ArrayLike) -> NDArray[np.float64]:
        """Unit normals ``a3`` on the grid ``xi × eta`` of every element ``(nv, nu, n_xi,
        n_eta, 3)`` (eq. 4.2)."""
        n = np.cross(self.evaluate(xi, eta, order=(1, 0)), self.evaluate(xi, eta, order=(0, 1)))
        return n / np.linalg.norm(n, axis=-1, keepdims=True)

    def element_areas(self, points: int = 16) -> NDArray[np.float64]:
        """Reference area of each element ``(nv, nu)``: ``∫∫ |a1 × a2| dξ dη`` by a
        ``points × points`` Gauss–Legendre rule (eq. 4.3)."""
        x, w = gauss_legendre(points)
        j = np.cross(self.evaluate(x, x, order=(1, 0)), self.evaluate(x, x, order=(0, 1)))
        return np.einsum("p,q,jipq->ji", w, w, np.linalg.norm(j, axis=-1))

    def edge_nodes(self, edge: str) -> NDArray[np.int64]:
        """Indices of the nodes on an edge (``"u0"``, ``"u1"``, ``"v0"``, ``"v1"``), in order."""
        idx = np.arange(self.n_nodes).reshape(self.nodes.shape[:2])
        rows = {"u0": idx[:, 0], "u1": idx[:, -1], "v0": idx[0, :], "v1": idx[-1, :]}
        if edge not in rows:
            raise InputError("at", edge, 'an edge "u0", "u1", "v0" or "v1"')
        return rows[edge].copy()

    def control_points(self) -> NDArray[np.float64]:
        """Bézier control points of every element ``(nv, nu, 4, 4, 3)`` (inverse of eq. 3.3)."""
        from rancf.elements.cable import nodal_to_control_matrix

        tu = np.array([nodal_to_control_matrix(w, s) for w, s in _pairs(self.u)])
        tv = np.array([nodal_to_control_matrix(w, s) for w, s in _pairs(self.v)])
        return np.einsum("iac,jbd,jicdx->jiabx", tu, tv, self.element_nodal())


def _pairs(d: Direction) -> zip:
    return zip(d.weights, d.scales, strict=True)


def scale_walk(d0: NDArray, d1: NDArray, key: str) -> NDArray[np.float64]:
    """Gradient scales ``l_e`` of one direction from the end derivatives of its control rows
    (eq. 3.4): ``d0``, ``d1`` ``(n_el, n_rows, 3)`` at ``ξ = 0`` and ``ξ = 1``.

    Across joint ``e`` the ratio ``l_e / l_{e-1} = |d0_e| / |d1_{e-1}|`` must be one number for
    every row (eq. 3.5); it is its least-squares value, checked to :data:`JOIN_RTOL`.  The
    common factor makes the mean nodal gradient 1.
    """
    num = np.einsum("erx,erx->e", d0[1:], d1[:-1])
    den = np.einsum("erx,erx->e", d1[:-1], d1[:-1])
    if np.any(den <= 0.0):
        raise InputError(key, "a vanishing derivative", "a regular surface (no collapsed edge)")
    ratio = num / den
    miss = np.linalg.norm(d0[1:] - ratio[:, None, None] * d1[:-1], axis=-1)
    size = float(np.linalg.norm(d0, axis=-1).max())
    if miss.size and miss.max() > JOIN_RTOL * size:
        e = int(np.argmax(miss.max(axis=1)))
        raise InputError(
            key,
            f"joint {e + 1}: tangent mismatch {float(miss[e].max() / size):.3g}",
            "a tangent-continuous surface (one gradient ratio along each element edge)",
        )
    scales = np.concatenate([[1.0], np.cumprod(ratio)])
    mags = np.linalg.norm(d0, axis=-1) / scales[:, None]
    _warn_span(float(mags.max() / mags.min()), len(scales))
    return scales * float(np.mean(mags))


def _warn_span(span: float, n_el: int) -> None:
    """The cable mesher's warning (:data:`rancf.mesh.mesh.GRADIENT_SPAN_WARNING`): one fixed K
    far from Kopt makes the consistent nodal gradients grow geometrically along a direction
    (docs/derivations/shell.md sec. 9, the mapping factor K on shells)."""
    if span > GRADIENT_SPAN_WARNING:
        import logging  # only for this warning (logging is a start-up cost of every run)

        logging.getLogger(__name__).warning(
            "nodal gradient magnitudes span a factor %.3g over %d elements along one direction "
            "of the surface: the model is badly conditioned; use k='opt' or fewer elements",
            span,
            n_el,
        )


def mesh_from_patches(
    points: NDArray, u: Direction, v: Direction, kind: str, key: str = "geometry"
) -> SurfaceMesh:
    """A mesh from each element's bicubic control points ``(nv, nu, 4, 4, 3)`` (``[j, i, a,
    b]``, ``a`` along ``u``) and the directions' weights, breaks and factors (their scales
    are set here by :func:`scale_walk`; eqs. 3.3–3.5).

    The cable's map ``T(w, 1)`` along one index gives each control row's end derivatives
    ``d/dξ`` for the walk; ``T(w, l) = diag(1, 1/l, 1, 1/l) T(w, 1)`` then gives eq. 3.3.
    """
    tu = np.array([control_to_nodal_matrix(w, 1.0) for w in u.weights])
    tv = np.array([control_to_nodal_matrix(w, 1.0) for w in v.weights])
    along_u = np.einsum("iac,jicbx->jiabx", tu, points)  # rows 1, 3: d/dξ of each control row
    along_v = np.einsum("jbd,jiadx->jiabx", tv, points)
    su = scale_walk(_rows(along_u[:, :, 1], 1), _rows(along_u[:, :, 3], 1), key)
    sv = scale_walk(_rows(along_v[:, :, :, 1], 0), _rows(along_v[:, :, :, 3], 0), key)
    u = Direction(u.weights, su, u.breaks, u.k, u.half_angle, u.closed)
    v = Direction(v.weights, sv, v.breaks, v.k, v.half_angle, v.closed)
    gu = np.stack([np.ones_like(su), 1.0 / su, np.ones_like(su), 1.0 / su], axis=1)  # T(w, l)
    gv = np.stack([np.ones_like(sv), 1.0 / sv, np.ones_like(sv), 1.0 / sv], axis=1)
    e = np.einsum("ia,jb,jiabx->jiabx", gu, gv, np.einsum("jbd,jiadx->jiabx", tv, along_u))
    nodes = np.empty((v.n + 1, u.n + 1, 4, 3))
    for nj in (1, 0):  # corners of the last row/column first, then every element's first
        for ni in (1, 0):
            for k in range(4):
                nodes[nj : nj + v.n, ni : ni + u.n, k] = e[:, :, 2 * ni + k % 2, 2 * nj + k // 2]
    mesh = SurfaceMesh(nodes, u, v, kind)
    _check_joins(mesh, e, key)
    return mesh


def _rows(d: NDArray, axis: int) -> NDArray:
    """End derivatives ``(nv, nu, 4, 3)`` as ``(n_el, n_rows, 3)`` along ``u`` (axis 1) or
    ``v`` (axis 0): all control rows of every element in that direction's column."""
    return np.moveaxis(d, axis, 0).reshape(d.shape[axis], -1, 3)


def _check_joins(mesh: SurfaceMesh, e: NDArray, key: str) -> None:
    """Every element's corner data equal the shared node's (eq. 3.5), or an InputError."""
    back = mesh.element_nodal()
    size = np.abs(mesh.nodes).reshape(-1, 4, 3).max(axis=(0, 2))  # per kind of nodal data
    for k in range(4):
        sl = (..., slice(k % 2, 4, 2), slice(k // 2, 4, 2), slice(None))
        miss = float(np.abs(back[sl] - e[sl]).max())
        if miss > JOIN_RTOL * max(float(size[k]), float(size[0])):
            raise InputError(
                key,
                f"nodal data mismatch {miss:.3g} between neighbouring elements",
                "a tangent-continuous surface (shared nodes consistent to 1e-9)",
            )


def regular_or_raise(mesh: SurfaceMesh, key: str) -> None:
    """Refuse a surface whose normal vanishes somewhere (a pole or collapsed edge, eq. 4.2)."""
    x = np.linspace(0.0, 1.0, 5)
    a1, a2 = mesh.evaluate(x, x, order=(1, 0)), mesh.evaluate(x, x, order=(0, 1))
    jac = np.linalg.norm(np.cross(a1, a2), axis=-1)
    ref = np.linalg.norm(a1, axis=-1) * np.linalg.norm(a2, axis=-1)
    if np.any(jac <= 1e-9 * ref) or not np.all(np.isfinite(jac)):
        raise InputError(
            key, "a vanishing normal", "a regular surface (no pole, no collapsed edge)"
        )
