"""The coordinates of a model: nodes, and the map between model and nodal coordinates.

A model's coordinates ``y`` map to the full nodal coordinates ``q`` (``dpn`` per node, node by
node) linearly, ``q = T y``: for C¹ models ``T`` is block diagonal and orthogonal (the rotated
blocks of clamps and rollers, :mod:`rancf.bodies.support_layout`), for C² models the spline map of
:mod:`rancf.mesh.continuity` (with the supports' rotations folded in).  :class:`Coordinates`
is the part of :class:`~rancf.bodies.flexible.Model` that applies ``T``, its transpose (forces)
and its inverse (least squares for C²), and resolves node indices.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError

if TYPE_CHECKING:
    from rancf.mesh.continuity import Reduction

__all__ = ["Coordinates"]


class Coordinates:
    """Node indices and the map ``q = T y`` of a model (module docstring).

    The model sets ``n``, ``n_nodes``, ``dim``, ``dpn``, ``ku``, ``closed``, ``reduction`` and
    ``rotations``: the rotated blocks of clamped nodes, ``(first index in y, basis (dim, dim))``
    each, whose coordinates are ``z = basis y``.
    """

    n: int
    n_nodes: int
    dim: int
    dpn: int
    ku: int
    closed: bool
    reduction: Reduction | None
    rotations: list[tuple[int, NDArray[np.float64]]]

    def check_node(self, node: int, key: str) -> int:
        """Resolve a node index (negative counts from the end) or raise naming ``key``.

        A ring's last stored node is its first: that index (``-1``, the end) resolves to 0.
        """
        n = self.n_nodes
        try:
            i = int(node)
        except (TypeError, ValueError):
            raise InputError(key, node, f"a node index in [-{n}, {n - 1}]") from None
        if not -n <= i < n or i != node:
            raise InputError(key, node, f"a node index in [-{n}, {n - 1}]")
        i %= n
        return 0 if self.closed and i == n - 1 else i

    def node_base(self, node: int) -> int:
        """First index in ``y`` of a node's own coordinates (C² models: its C¹ block)."""
        if self.reduction is None:
            return node * self.dpn
        return int(self.reduction.node_base[node])

    def q_from_y(self, y: ArrayLike) -> NDArray[np.float64]:
        """Full nodal coordinates from model coordinates (``q = T y``; works on ``(..., n)``)."""
        if self.reduction is not None:
            return self.reduction.q_from_y(np.asarray(y, dtype=float))
        q = np.array(y, dtype=float)
        for off, basis in self.rotations:
            q[..., off : off + self.dim] = q[..., off : off + self.dim] @ basis.T
        return q

    def y_from_q(self, q: ArrayLike) -> NDArray[np.float64]:
        """Inverse of :meth:`q_from_y` (``y = Tᵀ q``; C²: least squares, exact for ``q`` in the
        C² space)."""
        if self.reduction is not None:
            return self.reduction.y_from_q(np.asarray(q, dtype=float))
        y = np.array(q, dtype=float)
        for off, basis in self.rotations:
            y[..., off : off + self.dim] = y[..., off : off + self.dim] @ basis
        return y

    def to_y(self, f: ArrayLike) -> NDArray[np.float64]:
        """Generalized forces (or constraint rows) from full to model coordinates: ``Tᵀ f``."""
        if self.reduction is not None:
            return self.reduction.forces_to_y(np.asarray(f, dtype=float))
        return self.y_from_q(f)  # T orthogonal

    def forces_at_nodes(self, f: ArrayLike) -> NDArray[np.float64]:
        """A generalized force on the model coordinates as forces on the nodal coordinates of
        the nodes that own theirs (every node; C²: the supported ones), ``(n_nodes dpn,)`` (``(...,
        n_nodes dpn)`` for ``(..., n)``)."""
        f = np.asarray(f, dtype=float)
        if self.reduction is None:
            return self.q_from_y(f)
        if f.ndim > 1:  # a stack of forces (..., n), one by one
            rows = [self.forces_at_nodes(x) for x in f.reshape(-1, f.shape[-1])]
            return np.reshape(rows, f.shape[:-1] + (-1,))
        out = np.zeros(self.n_nodes * self.dpn)
        for k, b in enumerate(self.reduction.node_base):
            if b >= 0:
                blk = self.reduction.t[k * self.dpn : (k + 1) * self.dpn, b : b + self.dpn]
                out[k * self.dpn : (k + 1) * self.dpn] = blk.toarray() @ f[b : b + self.dpn]
        return out

    def node_positions(self, q: ArrayLike) -> NDArray[np.float64]:
        """Node positions ``(..., n_nodes, dim)`` from full coordinates."""
        q = np.asarray(q, dtype=float)
        return q.reshape(q.shape[:-1] + (self.n_nodes, self.dpn))[..., : self.dim]

    def dense(self, ab: NDArray) -> NDArray[np.float64]:
        """A band-stored matrix as a dense ``(n, n)`` array."""
        out = np.zeros((self.n, self.n))
        for k in range(2 * self.ku + 1):
            off = self.ku - k  # column - row
            i = np.arange(max(0, -off), min(self.n, self.n - off))
            out[i, i + off] = ab[k, i + off]
        return out

    def position_mask(self) -> NDArray[np.bool_]:
        """Model coordinates that are positions (lengths): ``r`` of every node (C¹), or the
        control points and the C¹ nodes' ``r`` (C²); for the scaling of Newton's norms."""
        if self.reduction is None:
            nodal = np.zeros((self.n_nodes, self.dpn), dtype=bool)
            nodal[:, : self.dim] = True
            return nodal.ravel()
        t = self.reduction.t.tocsc()
        mask = np.zeros(self.n, dtype=bool)
        for j in range(self.reduction.n_real):
            rows = t.indices[t.indptr[j] : t.indptr[j + 1]]
            vals = np.abs(t.data[t.indptr[j] : t.indptr[j + 1]])
            mask[j] = rows.size > 0 and rows[np.argmax(vals)] % self.dpn < self.dim
        return mask

    def twist_indices(self) -> NDArray[np.int64]:
        """Rods: the index of each node's twist ``φ`` in ``y`` ``(n_nodes,)``."""
        if self.reduction is None:
            return np.arange(self.n_nodes) * self.dpn + 6
        return np.asarray(self.reduction.twist, dtype=np.int64)

    def band_times(self, ab: NDArray, v: NDArray) -> NDArray[np.float64]:
        """``A v`` of a band-stored matrix (``ab[ku + i - j, j] = A[i, j]``), diagonal by
        diagonal."""
        out = np.zeros(self.n)
        for k in range(2 * self.ku + 1):
            off = self.ku - k  # column - row
            i = np.arange(max(0, -off), min(self.n, self.n - off))
            out[i] += ab[k, i + off] * v[i + off]
        return out

    def _own_blocks(self, q: NDArray) -> NDArray[np.float64]:
        """C²: ``y`` with the C¹ nodes' blocks of full coordinates ``q``, zero elsewhere."""
        red = self.reduction
        assert red is not None
        y = np.zeros(self.n)
        for k in np.flatnonzero(red.node_base >= 0):
            b, rows = red.node_base[k], slice(k * self.dpn, (k + 1) * self.dpn)
            y[b : b + self.dpn] = np.linalg.solve(red.t[rows, b : b + self.dpn].toarray(), q[rows])
        return y
