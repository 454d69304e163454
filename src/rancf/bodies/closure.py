"""Closed bodies (rings): the seam as linear constraint rows.

A closed mesh (:attr:`rancf.mesh.mesh.CableMesh.closed`) is stored as an open chain whose last
node repeats the first, so every matrix keeps the band of a chain.  The two copies of the seam
node are tied by linear rows ``g = A y = 0`` with constant coefficients, carried by a system with
Lagrange multipliers like its joints (docs/derivations/systems.md sec. 4: a closed ring is "one
joint"):

* positions ``r_n - r_0 = 0``;
* gradients ``r_x,n - c r_x,0 = 0`` with ``c`` the mesh's :attr:`seam_ratio` (a consistent chain
  of rational elements need not return to the gradient magnitude it started with; the tangent
  direction is the same, and the ratio is only a parameter scale);
* a rod's twist ``φ_n - φ_0 = 0``: its reference triads at the two copies are equal (the
  holonomy of a spatial centreline is spread over the ring by
  :func:`rancf.kernels.rod.initial_triads`, and re-referencing copies node 0's triad onto the
  last node), so equal twists mean one material frame;
* a beam's rotation ``θ_n - θ_0 = 0`` (both measured from the same reference tangent).

A clamp or roller at node 0 rotates its blocks of ``y`` (``q = T y``), and a C² model's
coordinates are spline coefficients (:mod:`rancf.mesh.continuity`; it adds the (C2) condition
across the seam): the rows act on ``q`` and are mapped by ``T`` (``A_y = A_q T``).  The rows are
linear, so their Jacobian is exact and constant.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.kernels.records import LinearTerm

if TYPE_CHECKING:  # lower layers, for annotations only
    from rancf.mesh.continuity import Reduction
    from rancf.mesh.mesh import CableMesh

__all__ = ["arc_fractions", "closure_matrix", "closure_rows", "closure_terms", "seam_scales"]


class SeamedBody(Protocol):
    """What the seam rows read of a flexible body (:class:`rancf.bodies.flexible.Model`)."""

    n: int
    n_nodes: int
    dim: int
    dpn: int
    element: str
    family: Any  # rancf.bodies.families.ElementFamily (which reads this module)
    closed: bool
    mesh: CableMesh
    supports: Sequence[Any]
    reduction: Reduction | None

    def check_node(self, node: int, key: str) -> int: ...

    def to_y(self, f: ArrayLike) -> NDArray[np.float64]: ...


def arc_fractions(mesh: CableMesh) -> NDArray[np.float64]:
    """Arc length from node 0 to every node over the total length, ``(n_nodes,)``."""
    s = np.concatenate([[0.0], np.cumsum(mesh.arc_lengths())])
    return s / s[-1]


def seam_scales(model: SeamedBody) -> NDArray[np.float64]:
    """``s_i`` of the rows ``q_n[i] - s_i q_0[i] = 0`` over one node's coordinates ``(dpn,)``."""
    d = model.dim
    s = np.ones(model.dpn)
    if model.family.gradient:
        s[d : 2 * d] = model.mesh.seam_ratio
    return s


def closure_matrix(model: SeamedBody) -> NDArray[np.float64]:
    """The seam's rows ``A`` of a closed model over its model coordinates ``(m, n)``; ``(0, n)``
    for an open one.

    ``dpn`` rows, one per coordinate of the seam node (module docstring); a C² model
    (:mod:`rancf.mesh.continuity`) adds ``dim`` rows: its (C2) condition across the seam, unless
    a support holds the seam node (a supported node is a C¹ node).
    """
    if not model.closed:
        return np.zeros((0, model.n))
    dpn, nq = model.dpn, model.n_nodes * model.dpn
    last = nq - dpn
    a = np.zeros((dpn, nq))
    a[np.arange(dpn), last + np.arange(dpn)] = 1.0
    a[np.arange(dpn), np.arange(dpn)] = -seam_scales(model)
    held = any(model.check_node(sup.node, "supports.at") == 0 for sup in model.supports)
    if model.reduction is not None and not held:  # a supported node stays C¹, the seam too
        from rancf.mesh.continuity import seam_curvature_rows

        a = np.concatenate([a, seam_curvature_rows(model.mesh, dpn)])
    return model.to_y(a)  # A_y = A_q T: each row a becomes Tᵀ a


def closure_rows(
    model: SeamedBody,
) -> tuple[NDArray[np.int64], NDArray[np.int64], NDArray[np.float64]]:
    """The rows of :func:`closure_matrix` as terms ``(row, column, coefficient)``."""
    a = closure_matrix(model)
    a[np.abs(a) <= 1e-15 * np.abs(a).max(initial=0.0)] = 0.0
    rows, cols = np.nonzero(a)
    return rows.astype(np.int64), cols.astype(np.int64), a[rows, cols]


def closure_terms(
    names: Sequence[str], flex: Sequence[Any], offsets: dict[str, int]
) -> list[LinearTerm]:
    """The seams of the closed flexible bodies ``flex`` (named ``names``, their first
    coordinates ``offsets``) as the terms of a system's linear rows
    (:class:`rancf.kernels.records.LinearTerm`, :func:`closure_rows`), in system coordinates."""
    out: list[LinearTerm] = []
    m = 0
    for name, b in zip(names, flex, strict=False):
        r, c, v = closure_rows(b)
        o = offsets[name]
        out += [
            LinearTerm(int(i) + m, int(j) + o, float(x)) for i, j, x in zip(r, c, v, strict=True)
        ]
        m += closure_matrix(b).shape[0]
    return out
