"""The shell body: a :class:`~rancf.mesh.surfaces.SurfaceMesh` as a body of the model.

Coordinates run node by node, twelve a node: ``[r, r_x, r_y, r_xy]`` (docs/derivations/shell.md
eq. 3.1), node ``j (nu + 1) + i`` (u fastest), so coordinate ``12 n + 3 k + c`` is component
``c`` of nodal vector ``k`` of node ``n``.  The body gives what every analysis needs besides the
element kernel: the shape-function rows of a surface point (eq. 3.2) and its ``position``
sensors; its supports as linear constraint rows ``C q = C q0`` (sec. 7) are made by
:func:`rancf.bodies.shell_supports.constraint_rows`, its loads as consistent nodal vectors
(sec. 6) by :mod:`rancf.bodies.shell_loads`.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.mesh.surfaces import SurfaceMesh

__all__ = ["ShellBody", "ShellSupport", "NODE_DOFS"]

#: Coordinates per node: ``r, r_x, r_y, r_xy``.
NODE_DOFS = 12


@dataclass(frozen=True)
class ShellSupport:
    """A support of a shell (docs/derivations/shell.md sec. 7).

    Attributes
    ----------
    kind : str
        ``"pin"``, ``"clamp"``, ``"diaphragm"``, ``"symmetry"`` or ``"roller"``.
    at : str or (u, v)
        An edge ``"u0"``, ``"u1"``, ``"v0"``, ``"v1"`` or a surface point.
    normal : array_like or None
        ``symmetry``: the normal of the plane of symmetry.
    axis : array_like or None
        ``roller``: the direction it moves along.
    """

    kind: str
    at: str | tuple[float, float]
    normal: tuple[float, ...] | None = None
    axis: tuple[float, ...] | None = None


@dataclass
class ShellBody:
    """A shell body (module docstring).

    Parameters
    ----------
    mesh : SurfaceMesh
        The exact surface mesh (:func:`rancf.mesh.surface_kinds.mesh_surface`).
    thickness, youngs_modulus, poisson_ratio, density : float
        ``t``, ``E``, ``ν``, ``ρ`` (eq. 4.6, sec. 6).
    name : str
        The body's name.
    """

    mesh: SurfaceMesh
    thickness: float
    youngs_modulus: float
    poisson_ratio: float
    density: float
    name: str = "body"
    supports: list[ShellSupport] = field(default_factory=list)

    @property
    def n_nodes(self) -> int:
        """Stored nodes ``(nu + 1)(nv + 1)``."""
        return self.mesh.n_nodes

    @property
    def n_dofs(self) -> int:
        """Coordinates of the body: 12 a node."""
        return NODE_DOFS * self.n_nodes

    @property
    def q0(self) -> NDArray[np.float64]:
        """The reference coordinates (eq. 3.1)."""
        return self.mesh.q0

    def dof(self, node: int | NDArray, vector: int, component: int | NDArray = 0) -> NDArray:
        """Coordinate index of ``component`` of nodal vector ``vector`` (0 ``r``, 1 ``r_x``,
        2 ``r_y``, 3 ``r_xy``) of ``node``."""
        return NODE_DOFS * np.asarray(node) + 3 * vector + np.asarray(component)

    def element_dofs(self, i: int, j: int) -> NDArray[np.int64]:
        """The 48 coordinates of element ``(i, j)`` as ``[a, b, c]`` ``(4, 4, 3)``: ``a`` along
        ``u`` over ``(rA, rA_x, rB, rB_x)``, ``b`` likewise along ``v`` (eq. 3.1)."""
        nu1 = self.mesh.nodes.shape[1]
        out = np.empty((4, 4, 3), dtype=np.int64)
        for ni in (0, 1):
            for nj in (0, 1):
                node = (j + nj) * nu1 + i + ni
                for gu in (0, 1):
                    for gv in (0, 1):
                        out[2 * ni + gu, 2 * nj + gv] = self.dof(node, gu + 2 * gv, np.arange(3))
        return out

    def shape_row(
        self, at: ArrayLike, order: tuple[int, int] = (0, 0)
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        """``∂^(m+n) r / ∂ξ^m ∂η^n`` at the surface point ``at = [u, v]`` as a linear map of the
        coordinates (eq. 3.2): the 16 coordinate indices ``(16, 3)`` and their factors ``(16,)``
        (component ``c`` of the result is ``Σ factors · q[indices[:, c]]``)."""
        i, j, xi, eta = self.mesh.locate(at)
        return self._row(i, j, xi, eta, order)

    def _row(
        self, i: int, j: int, xi: float, eta: float, order: tuple[int, int]
    ) -> tuple[NDArray[np.int64], NDArray[np.float64]]:
        u, v = self.mesh.u, self.mesh.v
        nu = cable_shape_functions(u.weights[i : i + 1], u.scales[i : i + 1], xi)[order[0]][0, 0]
        nv = cable_shape_functions(v.weights[j : j + 1], v.scales[j : j + 1], eta)[order[1]][0, 0]
        return self.element_dofs(i, j).reshape(16, 3), np.outer(nu, nv).ravel()

    def shape_matrix(self, at: ArrayLike, order: tuple[int, int] = (0, 0)) -> sp.csr_matrix:
        """The ``3 × n_dofs`` matrix ``S`` of :meth:`shape_row` (``r(at) = S q``)."""
        idx, f = self.shape_row(at, order)
        rows = np.repeat(np.arange(3)[None, :], 16, axis=0)
        vals = np.repeat(f[:, None], 3, axis=1)
        return sp.csr_matrix((vals.ravel(), (rows.ravel(), idx.ravel())), (3, self.n_dofs))

    def position(self, at: ArrayLike, q: ArrayLike | None = None) -> NDArray[np.float64]:
        """The ``position`` sensor: the point ``at = [u, v]`` in configuration ``q`` (default
        the reference)."""
        idx, f = self.shape_row(at)
        qq = self.q0 if q is None else np.asarray(q, dtype=float)
        if qq.shape != (self.n_dofs,):
            raise InputError("q", qq.shape, f"{self.n_dofs} coordinates of the shell")
        return np.einsum("k,kc->c", f, qq[idx])
