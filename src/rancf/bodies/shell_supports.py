"""A shell's supports as linear constraint rows ``C q = C q0`` (docs/derivations/shell.md sec. 7).

On an edge the edge curve is ``Σ_b M_b(η) [r, r_along]_nodes`` and the cross derivative along it
``Σ_b M_b(η) [r_cross, r_xy]_nodes``, so conditions on those nodal vectors hold along the whole
edge.  Each support fixes components of them, in a rotated basis where needed:

========== ==================================================================================
pin        ``r``, ``r_along`` (all components)
clamp      every nodal vector of the edge's nodes: the tangent plane is fixed along the edge
diaphragm  the components of ``r``, ``r_along`` in the plane of the (planar, curved) edge
symmetry   ``n · r``, ``n · r_along`` and the in-plane components of ``r_cross``, ``r_xy``
           (the reference cross tangent must be parallel to ``n``)
roller     the two components of ``r``, ``r_along`` across ``axis``
========== ==================================================================================

At a surface point ``[u, v]`` (eq. 3.2): a pin fixes ``S q``, a roller the components of
``S q`` across its axis, a clamp ``S q`` and both tangents ``S_ξ q``, ``S_η q`` (at a node: all
twelve nodal coordinates).  A closed direction ties its repeated last nodes to its first.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

if TYPE_CHECKING:
    from rancf.bodies.shell import ShellBody, ShellSupport

__all__ = [
    "constraint_rows",
    "support_rows",
    "closure_rows",
    "independent_rows",
    "edge_plane",
    "PLANE_RTOL",
]

#: Relative size of the out-of-plane extent of an edge (or of the misalignment of a cross
#: tangent with a symmetry normal) above which the support is refused.
PLANE_RTOL = 1e-9


def _unit(v: ArrayLike | None, key: str) -> NDArray[np.float64]:
    if v is None:
        raise InputError(key, v, "a nonzero vector [x, y, z] (required for this support)")
    a = np.asarray(v, dtype=float).ravel()
    n = float(np.linalg.norm(a))
    if a.size != 3 or not n > 0.0:
        raise InputError(key, v, "a nonzero vector [x, y, z]")
    return a / n


def _across(n: NDArray[np.float64]) -> NDArray[np.float64]:
    """Two unit vectors ``(2, 3)`` perpendicular to the unit vector ``n`` and to each other."""
    basis = np.linalg.svd(n[None, :])[2]
    return basis[1:]


class _Rows:
    """Rows ``Σ_c dirs[c] q[dof(node, k, c)]`` gathered into a sparse matrix."""

    def __init__(self, n_dofs: int) -> None:
        self.n_dofs = n_dofs
        self.r: list[NDArray] = []
        self.c: list[NDArray] = []
        self.v: list[NDArray] = []
        self.count = 0

    def add(self, cols: NDArray, vals: NDArray) -> None:
        """One row per leading index of ``cols``/``vals`` ``(m, k)``."""
        m = cols.shape[0]
        self.r.append(np.repeat(np.arange(self.count, self.count + m), cols.shape[1]))
        self.c.append(cols.ravel())
        self.v.append(vals.ravel())
        self.count += m

    def matrix(self) -> sp.csr_matrix:
        if not self.r:
            return sp.csr_matrix((0, self.n_dofs))
        data = (np.concatenate(self.v), (np.concatenate(self.r), np.concatenate(self.c)))
        return sp.csr_matrix(data, (self.count, self.n_dofs))


def _fix(rows: _Rows, body: ShellBody, nodes: NDArray, vectors: tuple, dirs: NDArray) -> None:
    """Rows ``d · q_k`` of every node, nodal vector ``k`` in ``vectors`` and direction ``d`` in
    ``dirs`` ``(m, 3)``."""
    for k in vectors:
        for d in dirs:
            cols = np.stack([body.dof(nodes, k, c) for c in range(3)], axis=1)
            rows.add(cols, np.broadcast_to(d, cols.shape).copy())


def edge_plane(body: ShellBody, edge: str, key: str = "at") -> NDArray[np.float64]:
    """The unit normal of the plane of a planar, curved edge (nodes and tangents along it);
    a straight or non-planar edge is refused (its plane is not one)."""
    nodes = body.mesh.edge_nodes(edge)
    nd = body.mesh.nodes.reshape(-1, 4, 3)[nodes]
    along = EDGE_ALONG[edge]
    pts = nd[:, 0] - nd[:, 0].mean(axis=0)
    size = float(np.abs(pts).max()) + 1e-300
    tang = nd[:, along] / np.linalg.norm(nd[:, along], axis=1, keepdims=True) * size
    s, vt = np.linalg.svd(np.vstack([pts, tang]))[1:]
    if s[1] <= PLANE_RTOL * s[0]:
        raise InputError(key, edge, "a curved edge for a diaphragm (a straight one has no plane)")
    if len(s) > 2 and s[2] > PLANE_RTOL * s[0]:
        raise InputError(key, edge, "a planar edge for a diaphragm")
    return vt[2]


#: The nodal vector along each edge (1 ``r_x``, 2 ``r_y``) and the one across it.
EDGE_ALONG = {"u0": 2, "u1": 2, "v0": 1, "v1": 1}


def _edge(rows: _Rows, body: ShellBody, s: ShellSupport, edge: str) -> None:
    nodes = body.mesh.edge_nodes(edge)
    along = EDGE_ALONG[edge]
    cross = 3 - along
    eye = np.eye(3)
    if s.kind == "pin":
        _fix(rows, body, nodes, (0, along), eye)
    elif s.kind == "clamp":
        _fix(rows, body, nodes, (0, 1, 2, 3), eye)
    elif s.kind == "diaphragm":
        _fix(rows, body, nodes, (0, along), _across(edge_plane(body, edge)))
    elif s.kind == "roller":
        _fix(rows, body, nodes, (0, along), _across(_unit(s.axis, "axis")))
    elif s.kind == "symmetry":
        n = _unit(s.normal, "normal")
        a = body.mesh.nodes.reshape(-1, 4, 3)[nodes, cross]
        off = np.linalg.norm(np.cross(a, n), axis=1) / np.linalg.norm(a, axis=1)
        if off.max() > PLANE_RTOL:
            raise InputError(
                "normal",
                s.normal,
                f"the direction across edge {edge} (the surface meets the plane)",
            )
        _fix(rows, body, nodes, (0, along), n[None, :])
        _fix(rows, body, nodes, (cross, 3), _across(n))
    else:
        raise InputError("kind", s.kind, '"pin", "clamp", "diaphragm", "symmetry" or "roller"')


def _node_at(body: ShellBody, uv: tuple[float, float]) -> int | None:
    """The node at the surface point ``uv``, or None."""
    iu = np.flatnonzero(np.abs(body.mesh.u.breaks - uv[0]) <= 1e-12)
    iv = np.flatnonzero(np.abs(body.mesh.v.breaks - uv[1]) <= 1e-12)
    if iu.size and iv.size:
        return int(iv[0]) * body.mesh.nodes.shape[1] + int(iu[0])
    return None


def _point(rows: _Rows, body: ShellBody, s: ShellSupport, uv: tuple[float, float]) -> None:
    node = _node_at(body, uv)
    if s.kind == "clamp" and node is not None:
        _fix(rows, body, np.array([node]), (0, 1, 2, 3), np.eye(3))
        return
    orders = [(0, 0), (1, 0), (0, 1)] if s.kind == "clamp" else [(0, 0)]
    if s.kind == "roller":
        dirs = _across(_unit(s.axis, "axis"))
    elif s.kind in ("pin", "clamp"):
        dirs = np.eye(3)
    else:
        raise InputError("kind", s.kind, '"pin", "clamp" or "roller" at a point (others: an edge)')
    for order in orders:
        idx, f = body.shape_row(uv, order)
        for d in dirs:
            rows.add(idx.reshape(1, -1), (f[:, None] * d[None, :]).reshape(1, -1))


def support_rows(body: ShellBody, s: ShellSupport) -> sp.csr_matrix:
    """The rows ``C`` of one support (module docstring): ``C q = C q0`` holds it."""
    rows = _Rows(body.n_dofs)
    if isinstance(s.at, str):
        if s.at not in EDGE_ALONG:
            raise InputError("at", s.at, 'an edge "u0", "u1", "v0", "v1" or a point [u, v]')
        _edge(rows, body, s, s.at)
    else:
        _point(rows, body, s, (float(s.at[0]), float(s.at[1])))
    return rows.matrix()


def closure_rows(body: ShellBody) -> sp.csr_matrix:
    """The seam of a closed direction: the repeated last nodes equal the first, their gradient
    across the seam scaled by the reference ratio of the two elements' scales (eq. 3.4)."""
    rows = _Rows(body.n_dofs)
    idx = np.arange(body.n_nodes).reshape(body.mesh.nodes.shape[:2])
    nd = body.mesh.nodes.reshape(-1, 4, 3)
    for closed, first, last, grads in (
        (body.mesh.u.closed, idx[:, 0], idx[:, -1], (1, 3)),
        (body.mesh.v.closed, idx[0, :], idx[-1, :], (2, 3)),
    ):
        if not closed:
            continue
        a, b = nd[first, grads[0]], nd[last, grads[0]]
        scale = np.einsum("nc,nc->n", a, b) / np.einsum("nc,nc->n", a, a)
        for k in range(4):
            ratio = scale if k in grads else np.ones(len(first))
            for c in range(3):
                cols = np.stack([body.dof(last, k, c), body.dof(first, k, c)], axis=1)
                rows.add(cols, np.stack([np.ones_like(ratio), -ratio], axis=1))
    return rows.matrix()


#: Singular values of a node's rows below this fraction of the largest are dependent rows.
RANK_RTOL = 1e-10


def independent_rows(c: sp.csr_matrix, node_dofs: int = 12) -> sp.csr_matrix:
    """Rows with the row space of ``c`` and no dependent ones: two supports meeting at a corner
    hold some coordinates twice (a diaphragm and a symmetry plane both hold ``x · r``).  The
    rows within one node's coordinates are replaced, node by node, by an orthonormal basis of
    their span (SVD); the rows over several nodes (points between nodes, a seam), less their
    parts in those spans, by an orthonormal basis of what is left."""
    c = sp.csr_matrix(c)
    nodes = [
        np.unique(c.indices[c.indptr[i] : c.indptr[i + 1]] // node_dofs) for i in range(c.shape[0])
    ]
    owner = np.array([n[0] if n.size == 1 else -1 for n in nodes], dtype=np.int64)
    rows = _Rows(c.shape[1])
    bases: dict[int, NDArray] = {}
    for node in np.unique(owner[owner >= 0]):
        cols = node_dofs * node + np.arange(node_dofs)
        bases[int(node)] = _basis(c[np.flatnonzero(owner == node)][:, cols].toarray())
        rows.add(np.broadcast_to(cols, bases[int(node)].shape).copy(), bases[int(node)])
    multi = np.flatnonzero(owner < 0)
    if multi.size:
        touched = np.unique(c[multi].indices // node_dofs)
        cols = (node_dofs * touched[:, None] + np.arange(node_dofs)).ravel()
        block = c[multi][:, cols].toarray()
        for k, node in enumerate(touched):
            b = bases.get(int(node))
            if b is not None and b.size:
                sl = slice(node_dofs * k, node_dofs * (k + 1))
                block[:, sl] -= (block[:, sl] @ b.T) @ b
        basis = _basis(block, float(np.abs(c[multi]).max()))
        rows.add(np.broadcast_to(cols, basis.shape).copy(), basis)
    return rows.matrix()


def _basis(block: NDArray, scale: float | None = None) -> NDArray:
    """An orthonormal basis (rows) of the row space of ``block``: singular values below
    :data:`RANK_RTOL` of ``scale`` (default the largest) are dependence."""
    if block.size == 0:
        return block[:0]
    _, s, vt = np.linalg.svd(block, full_matrices=False)
    ref = s[0] if scale is None else scale
    return vt[s > RANK_RTOL * ref]


def constraint_rows(body: ShellBody) -> tuple[sp.csr_matrix, NDArray[np.float64]]:
    """All supports of ``body`` (and the seam of a closed direction) as independent rows
    ``C q = d`` with ``d = C q0`` (module docstring): ``(C, d)``; where supports meet, the
    coordinates they both hold are held once (:func:`independent_rows`)."""
    blocks = [support_rows(body, s) for s in body.supports] + [closure_rows(body)]
    c = independent_rows(sp.vstack(blocks, format="csr"), 12)
    return c, c @ body.q0
