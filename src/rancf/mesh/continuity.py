"""C² reduced coordinates: the cubic (rational) B-spline of a mesh as its generalized coordinates.

Sanborn & Shabana (2009, sec. 6): a cubic B-spline of ``n`` spans is a chain of ``n`` ANCF cable
elements whose nodal coordinates satisfy linear C² conditions at the ``n - 1`` inner nodes; its
``n + 3`` control points per coordinate are the generalized coordinates, and every element's
nodal coordinates are a linear map of four of them.  The same holds for rational elements with
fixed weights (``docs/derivations/cable.md`` sec. 3): ``r(ξ) = S(ξ) e`` is linear in ``e``, so the
condition

    r_R''(0) = α² r_L''(1) + β r_L'(1),      α = l_R / l_L                        (C2)

at the node shared by a left element ``L`` and a right element ``R`` is linear in their nodal
coordinates.  ``α`` is the ratio of the parametric speeds of the consistent shared node
(``r' = l r_x``); ``β`` is read from the reference curve (``(r0_R'' - α² r0_L'')·r0_L' /
|r0_L'|²``), so the reference satisfies (C2) exactly whenever its curvature is continuous at the
node (G²: every inner node of a conic, an ellipse or a cubic NURBS with simple knots).  With
``β = 0`` and ``α`` the ratio of knot spans this is the parametric C² of a B-spline.  (C2) acts
on every coordinate alike (``α``, ``β`` are scalars), so one scalar spline space serves all.

**Basis.**  Nodes where (C2) is not imposed are *C¹ nodes*: the ends of the chain (a closed
chain's first and stored last node, tied by the seam rows of :mod:`rancf.bodies.closure`),
supported nodes (a support holds a node's own coordinates) and nodes where the reference
curvature jumps.  At a C¹ node the generalized coordinates are the node's own ``[r, r_x]`` (the
two Hermite functions: value or slope one there, the rest of the spline as smooth as allowed);
between two C¹ nodes ``a`` and ``b`` (``m = b - a`` elements) the ``m - 1`` functions that vanish
with their slope at both ends are the cubic B-splines ``N_2 … N_m`` of the clamped knot vector:
each is found as the one-dimensional null space of its conditions on its support (at most four
elements; the knots' multiplicities say where it vanishes to second order), and all are scaled
so that the functions sum to one.  For a B-spline input the functions are its B-splines and the
coordinates its control points ``P_2 … P_n``; ``[r, r_x]`` of an end node are the first two
control points in other words (``r = P_0``, ``r' = 3 (P_1 - P_0) / Δ``).  Per coordinate: two
per C¹ node plus ``m - 1`` per segment: ``n + 3`` for an open chain.

**Layout.**  ``y`` holds the functions in their order along the chain (a C¹ node's block is
``[r, r_x]``, and ``φ`` for rods; an inner function's block is ``d`` coordinates, followed for
rods by the twist of the node it is centred on), then zeros held fixed up to the size of the
full coordinates, so that a model keeps one size for ``y`` and ``q``.  Element ``e``'s
coordinates ``E_e y[s_e : s_e + w]`` depend on a window of ``w`` consecutive coordinates
(at most 22: four functions of a rod, two of them a C¹ node's block), so assembled matrices
are banded with half bandwidth ``w - 1``.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import TYPE_CHECKING, Literal

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.mesh.mesh import CableMesh
from rancf.mesh.spline_basis import G2_RTOL, conditions, element_ends, scalar_basis

if TYPE_CHECKING:  # scipy.sparse is imported where a C2 mesh needs it (0.1 s at start-up)
    import scipy.sparse as sp
    from scipy.sparse.linalg import SuperLU

__all__ = [
    "Continuity",
    "Reduction",
    "jump_note",
    "reduction",
    "rotated",
    "reduced_band",
    "seam_curvature_rows",
]

Continuity = Literal["C1", "C2"]


@dataclass(frozen=True)
class Reduction:
    """The linear map ``q = T y`` of a C² model and its element and node windows.

    Attributes
    ----------
    n_y : int
        Size of ``y`` (padded with held zeros to the number of full coordinates).
    n_real : int
        Number of generalized coordinates (before the padding).
    ku, width, node_width : int
        Half bandwidth, element window and node window.
    el_start : ndarray, shape (n_el,)
    el_map : ndarray, shape (n_el, nde, width)
    node_start : ndarray, shape (n_nodes,)
    node_map : ndarray, shape (n_nodes, dpn, node_width)
    twist : ndarray, shape (n_nodes,)
        Rods: index of each node's twist in ``y`` (else empty).
    node_base : ndarray, shape (n_nodes,)
        First index in ``y`` of a C¹ node's own block ``[r, r_x(, φ)]``; -1 elsewhere.
    t : scipy.sparse.csr_matrix, shape (n_q, n_y)
    """

    n_y: int
    n_real: int
    ku: int
    width: int
    el_start: NDArray[np.int64]
    el_map: NDArray[np.float64]
    node_width: int
    node_start: NDArray[np.int64]
    node_map: NDArray[np.float64]
    twist: NDArray[np.int64]
    node_base: NDArray[np.int64]
    t: sp.csr_matrix
    #: Inner nodes kept C¹ because the reference curvature jumps there.
    jumps: tuple[int, ...] = ()

    def q_from_y(self, y: NDArray) -> NDArray[np.float64]:
        """``T y`` on ``(..., n_y)``."""
        y = np.asarray(y, dtype=float)
        return np.asarray((self.t @ y.reshape(-1, y.shape[-1]).T).T).reshape(y.shape)

    def forces_to_y(self, f: NDArray) -> NDArray[np.float64]:
        """``Tᵀ f`` on ``(..., n_q)`` (a force, or the rows of a constraint)."""
        f = np.asarray(f, dtype=float)
        return np.asarray((self.t.T @ f.reshape(-1, f.shape[-1]).T).T).reshape(f.shape)

    @functools.cached_property
    def _lu(self) -> SuperLU:
        """The LU factors of the normal equations ``Tᵣᵀ Tᵣ`` of :meth:`y_from_q`."""
        import scipy.sparse.linalg as spla

        tr = self.t[:, : self.n_real].tocsc()
        return spla.splu((tr.T @ tr).tocsc())

    def y_from_q(self, q: NDArray) -> NDArray[np.float64]:
        """Least-squares ``y`` with ``T y ≈ q`` (exact for ``q`` in the C² space)."""
        q = np.asarray(q, dtype=float)
        flat = q.reshape(-1, q.shape[-1])
        rhs = np.asarray(self.t[:, : self.n_real].T @ flat.T)
        out = np.zeros((flat.shape[0], self.n_y))
        tr = self.t[:, : self.n_real]
        x = self._lu.solve(rhs)
        for _ in range(2):  # refinement: the normal equations square the condition number
            x = x + self._lu.solve(np.asarray(tr.T @ (flat.T - tr @ x)))
        out[:, : self.n_real] = x.T
        return out.reshape(q.shape[:-1] + (self.n_y,))


def reduction(
    mesh: CableMesh,
    dpn: int,
    rod: bool,
    c1_nodes: set[int],
    q0: NDArray,
) -> tuple[Reduction, NDArray[np.float64]]:
    """The :class:`Reduction` of a mesh and the reference ``y0`` (least squares of ``q0``).

    Parameters
    ----------
    mesh : CableMesh
    dpn : int
        Coordinates per node (``2 dim``, or 7 for rods).
    rod : bool
        Rods: one twist per node besides the spline.
    c1_nodes : set of int
        Nodes held by supports (C¹ nodes besides the ends and the curvature jumps).
    q0 : ndarray, shape (n_nodes dpn,)

    Raises
    ------
    InputError
        Naming ``mesh.continuity`` if the reference is not in the C² space.
    """
    import scipy.sparse as sp
    import scipy.sparse.linalg as spla

    d, n_el, nn = mesh.dim, mesh.n_elements, mesh.n_nodes
    _, smooth = conditions(mesh)
    c1 = {0, n_el} | {int(k) for k in c1_nodes} | {int(k) + 1 for k in np.flatnonzero(~smooth)}
    funcs, ends = scalar_basis(mesh, c1)
    # partition of unity: scale the inner functions so that all functions sum to one
    inner = [i for i, f in enumerate(funcs) if f[0] == "inner"]
    ones = np.zeros((nn, 2))
    ones[:, 0] = 1.0
    for kind, _, lo, u in funcs:
        if kind == "value":
            ones[lo : lo + u.shape[0]] -= u
    if inner:
        rows, cols, vals = [], [], []
        for c, i in enumerate(inner):
            _, _, lo, u = funcs[i]
            rows.append(np.arange(2 * lo, 2 * lo + u.size))
            cols.append(np.full(u.size, c))
            vals.append(u.ravel())
        a = sp.csc_matrix(
            (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
            shape=(2 * nn, len(inner)),
        )
        lu = spla.splu((a.T @ a).tocsc())  # banded normal equations: linear in the mesh
        b = ones.ravel()
        scale = lu.solve(np.asarray(a.T @ b))
        scale += lu.solve(np.asarray(a.T @ (b - a @ scale)))  # one refinement
        for c, i in enumerate(inner):
            kind, node, lo, u = funcs[i]
            funcs[i] = (kind, node, lo, u * scale[c])
    # layout of y
    col: list[int] = []  # first y index of each function's d-block
    twist = np.full(nn, -1, dtype=np.int64)
    node_base = np.full(nn, -1, dtype=np.int64)
    pos = 0
    for kind, node, _, _ in funcs:
        if kind == "value":
            node_base[node] = pos
            col.append(pos)
            pos += d
        elif kind == "slope":
            col.append(pos)
            pos += d
            if rod:
                twist[node] = pos
                pos += 1
        else:
            col.append(pos)
            pos += d
            if rod:
                twist[node] = pos
                pos += 1
    n_real, n_q = pos, nn * dpn
    if n_real > n_q:  # pragma: no cover - fewer functions than nodal coordinates
        raise InputError("mesh.continuity", "C2", "a mesh with at least one inner node")
    rr, cc, vv = [], [], []
    for (_, _, lo, u), c0 in zip(funcs, col, strict=True):
        for j in range(u.shape[0]):
            k = lo + j
            for i in range(d):
                for o, val in ((i, u[j, 0]), (d + i, u[j, 1])):
                    if val != 0.0:
                        rr.append(k * dpn + o)
                        cc.append(c0 + i)
                        vv.append(val)
    if rod:
        for k in range(nn):
            rr.append(k * dpn + 6)
            cc.append(int(twist[k]))
            vv.append(1.0)
    t = sp.csr_matrix((vv, (rr, cc)), shape=(n_q, n_q))
    red = _windows_of(t, n_el, nn, dpn, n_real, twist if rod else np.zeros(0, np.int64), node_base)
    red = dataclasses.replace(red, jumps=tuple(int(k) + 1 for k in np.flatnonzero(~smooth)))
    y0 = red.y_from_q(q0)
    for c1_node in np.flatnonzero(node_base >= 0):  # a C¹ node's block is its own coordinates
        b0 = node_base[c1_node]
        y0[b0 : b0 + dpn] = q0[c1_node * dpn : (c1_node + 1) * dpn]
    err = np.abs(red.q_from_y(y0) - q0).max()
    if not err <= 1e-10 * max(np.abs(q0).max(), 1.0):
        raise InputError(
            "mesh.continuity", "C2", f"a reference in the C² space (it misses by {err:.3g})"
        )
    return red, y0


def _windows_of(
    t: sp.csr_matrix, n_el: int, nn: int, dpn: int, n_real: int, twist: NDArray, node_base: NDArray
) -> Reduction:
    """Element and node windows of ``T`` (module docstring)."""
    n_y = t.shape[1]
    nde = 2 * dpn
    dense_rows = []
    starts = np.zeros(n_el, dtype=np.int64)
    width = 1
    for e in range(n_el):
        blk = t[e * dpn : e * dpn + nde]
        nz = blk.indices
        starts[e] = nz.min()
        width = max(width, int(nz.max() - nz.min() + 1))
        dense_rows.append(blk)
    starts = np.minimum(starts, n_y - width)
    el_map = np.zeros((n_el, nde, width))
    for e, blk in enumerate(dense_rows):
        el_map[e] = blk[:, starts[e] : starts[e] + width].toarray()
    node_start = np.zeros(nn, dtype=np.int64)
    node_width = 1
    for k in range(nn):
        nz = t[k * dpn : (k + 1) * dpn].indices
        node_start[k] = nz.min()
        node_width = max(node_width, int(nz.max() - nz.min() + 1))
    node_start = np.minimum(node_start, n_y - node_width)
    node_map = np.zeros((nn, dpn, node_width))
    for k in range(nn):
        s = node_start[k]
        node_map[k] = t[k * dpn : (k + 1) * dpn, s : s + node_width].toarray()
    return Reduction(
        n_y,
        n_real,
        width - 1,
        width,
        starts,
        el_map,
        node_width,
        node_start,
        node_map,
        twist,
        node_base,
        t,
    )


def seam_curvature_rows(mesh: CableMesh, dpn: int) -> NDArray[np.float64]:
    """A closed mesh: (C2) across the seam (left: the last element, right: the first) as ``d``
    rows over the full coordinates ``(d, n_q)``; empty if the reference is not G² there."""
    d, n_el = mesh.dim, mesh.n_elements
    sdd0, sdd1, d1, d2 = element_ends(mesh)
    ratio = mesh.seam_ratio
    alpha = mesh.scales[0] / (mesh.scales[-1] * ratio)  # r_0'(0) = l_0 r_x,0 = l_0 r_x,n / ratio
    t = d1[-1, 1]
    diff = d2[0, 0] - alpha**2 * d2[-1, 1]
    beta = float(diff @ t / (t @ t))
    scale = np.linalg.norm(d2[0, 0]) + alpha**2 * np.linalg.norm(d2[-1, 1])
    if np.linalg.norm(diff - beta * t) > G2_RTOL * (scale + float(t @ t)):
        return np.zeros((0, mesh.n_nodes * dpn))
    out = np.zeros((d, mesh.n_nodes * dpn))
    last = n_el - 1
    for i in range(d):
        for j, (node, o) in enumerate(((0, i), (0, d + i), (1, i), (1, d + i))):
            out[i, node * dpn + o] += sdd0[0, j]
        for j, (node, o) in enumerate(((last, i), (last, d + i), (n_el, i), (n_el, d + i))):
            out[i, node * dpn + o] -= alpha**2 * sdd1[last, j]
        out[i, n_el * dpn + d + i] -= beta * mesh.scales[-1]
    return out


def rotated(red: Reduction, rotations: list[tuple[int, NDArray]], dim: int) -> Reduction:
    """The reduction with supports' rotated blocks of ``y`` folded into its maps: ``T R`` with
    ``R`` block diagonal (``z[o : o + dim] = basis y[o : o + dim]``, as for C¹ models)."""
    if not rotations:
        return red
    import scipy.sparse as sp

    n = red.n_y
    r = sp.lil_matrix((n, n))
    r.setdiag(1.0)
    for off, basis in rotations:
        r[off : off + dim, off : off + dim] = basis
    t = (red.t @ r.tocsr()).tocsr()
    t.eliminate_zeros()
    nn = red.node_base.size
    dpn = red.t.shape[0] // nn
    out = _windows_of(t, red.el_start.size, nn, dpn, red.n_real, red.twist, red.node_base)
    return dataclasses.replace(out, jumps=red.jumps)


def reduced_band(red: Reduction, ke: NDArray) -> NDArray[np.float64]:
    """``Σ_e E_eᵀ k_e E_e`` of element matrices ``(n_el, nde, nde)`` in band storage
    ``(2 ku + 1, n_y)`` (``ab[ku + i - j, j] = A[i, j]``)."""
    ku, w = red.ku, red.width
    ab = np.zeros((2 * ku + 1, red.n_y))
    loc = np.einsum("eai,eab,ebj->eij", red.el_map, ke, red.el_map)
    for e, s in enumerate(red.el_start):
        for i in range(w):
            for j in range(w):
                ab[ku + i - j, s + j] += loc[e, i, j]
    return ab


def jump_note(red: Reduction, n_el: int) -> tuple[str, ...]:
    """A remark for the user when inner nodes stay C¹ (the reference curvature jumps there)."""
    if not red.jumps:
        return ()
    nodes = ", ".join(str(k) for k in red.jumps[:5]) + (", ..." if len(red.jumps) > 5 else "")
    return (
        f"mesh.continuity: C2 holds at {n_el - 1 - len(red.jumps)} of {n_el - 1} inner nodes; "
        f"the reference curvature jumps at node(s) {nodes}, which stay C1 (a Hermite reference "
        '(element = "ancf") of a curved geometry has such jumps at every node; "rancf" keeps '
        "conics and NURBS exact)",
    )
