"""RANCF Kirchhoff–Love shell elements: the record the core reads and a thin wrapper.

The energy, forces, tangent, mass and area loads live once, in the compiled core
(``src/cpp/elements/shell.cpp``; docs/derivations/shell.md sec. 3–6).  Interface::

    record = ShellRecord(connectivity, weights_u, weights_v, scales, q0, thickness,
                         youngs_modulus, poisson_ratio, density, gauss=5, membrane="projected")
    kernel = ShellKernel(record)              # or ShellKernel.from_mesh(mesh, t, E, nu, rho)
    kernel.energy(q) -> float                 # strain energy W (eq. 4.7)
    kernel.forces(q) -> (n,)                  # dW/dq (eq. 4.8)
    kernel.tangent(q) -> scipy.sparse.csr_matrix (n, n)   # d2W/dq2 (eq. 4.9)
    kernel.mass() -> csr_matrix (n, n)        # consistent, constant (sec. 6)
    kernel.area_load(p) -> (n,)               # a constant force p (3) per reference area
    kernel.gravity(g) -> (n,)                 # area_load(density * thickness * g)
    kernel.pressure(q, p) -> (n,)             # follower pressure p along a3 (sec. 6)
    kernel.pressure_tangent(q, p) -> csr_matrix   # its dQ/dq (not symmetric)
    kernel.core                               # rancf.kernels._core.ShellKernel: the same
                                              # methods, matrices as (rows, cols, values)

Coordinates run node by node, 12 a node ``[r, r_x, r_y, r_xy]`` (eq. 3.1), as
:attr:`rancf.mesh.surfaces.SurfaceMesh.q0`; ``connectivity[e, i + 2 j]`` is the node of corner
``(i, j)`` of element ``e`` (``i`` along ``u``, ``j`` along ``v``).  ``membrane``:
``"full"`` (the Green–Lagrange membrane strains as they are), ``"projected"`` (their
element-local L²(dA) projections, the assumed membrane strains of eq. 5.1 against membrane
locking) or ``"reduced"`` (the membrane term on a 3 × 3 Gauss rule, bending on the full one).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

import numpy as np
import scipy.sparse as sp
from numpy.typing import ArrayLike, NDArray

from rancf.kernels import _core

__all__ = ["MEMBRANE", "ShellRecord", "ShellKernel", "surface_connectivity"]

#: Treatments of the membrane strains (``MembraneStrains``, ``src/cpp/elements/shell.hpp``).
MEMBRANE = ("full", "projected", "reduced")


@dataclass(frozen=True, eq=False)
class ShellRecord:
    """A mesh of shell elements and its material (``ShellInput``, ``src/cpp/elements/shell.hpp``).

    Attributes
    ----------
    connectivity : ndarray of int64, shape (n_el, 4)
        Node of corner ``i + 2 j`` of each element.
    weights_u, weights_v : ndarray, shape (n_el, 4)
        Cubic weights of each element along ``u`` and ``v`` (eq. 2.2).
    scales : ndarray, shape (n_el, 2)
        Gradient scales ``l_u, l_v`` (eq. 3.4).
    q0 : ndarray, shape (12 n_nodes,)
        Reference coordinates (stress free).
    thickness, youngs_modulus, poisson_ratio, density : float
    gauss : int
        Gauss points per direction (``gauss × gauss`` an element; at least 4 for
        ``"projected"``).
    membrane : str
        One of :data:`MEMBRANE`.
    """

    connectivity: NDArray[np.int64]
    weights_u: NDArray[np.float64]
    weights_v: NDArray[np.float64]
    scales: NDArray[np.float64]
    q0: NDArray[np.float64]
    thickness: float
    youngs_modulus: float
    poisson_ratio: float
    density: float
    gauss: int = 5
    membrane: str = "projected"


class _Direction(Protocol):
    @property
    def weights(self) -> NDArray[np.float64]: ...

    @property
    def scales(self) -> NDArray[np.float64]: ...

    @property
    def n(self) -> int: ...


class SurfaceLike(Protocol):
    """What :meth:`ShellKernel.from_mesh` reads of a :class:`rancf.mesh.surfaces.SurfaceMesh`."""

    @property
    def u(self) -> _Direction: ...

    @property
    def v(self) -> _Direction: ...

    @property
    def q0(self) -> NDArray[np.float64]: ...


def surface_connectivity(nu: int, nv: int) -> NDArray[np.int64]:
    """Corner nodes ``(nu nv, 4)`` of a tensor-product mesh, elements ``j nu + i`` (u fastest),
    nodes ``j (nu + 1) + i`` (docs/derivations/shell.md sec. 3)."""
    i, j = np.meshgrid(np.arange(nu), np.arange(nv))
    first = (j * (nu + 1) + i).ravel()
    return np.stack([first, first + 1, first + nu + 1, first + nu + 2], axis=1).astype(np.int64)


def _coo(t: tuple[NDArray, NDArray, NDArray], n: int) -> sp.csr_matrix:
    rows, cols, values = t
    return sp.csr_matrix(sp.coo_matrix((values, (rows, cols)), shape=(n, n)))


class ShellKernel:
    """The shell elements of one :class:`ShellRecord` (module docstring)."""

    def __init__(self, record: ShellRecord) -> None:
        self.record = record
        self.core = _core.ShellKernel(record)
        self.n = int(self.core.n)

    @classmethod
    def from_mesh(
        cls,
        mesh: SurfaceLike,
        thickness: float,
        youngs_modulus: float,
        poisson_ratio: float,
        density: float,
        gauss: int = 5,
        membrane: str = "projected",
    ) -> ShellKernel:
        """The elements of a surface mesh (:func:`rancf.mesh.surface_kinds.mesh_surface`), its
        reference ``mesh.q0`` stress free; elements ``j nu + i``."""
        nu, nv = mesh.u.n, mesh.v.n
        record = ShellRecord(
            connectivity=surface_connectivity(nu, nv),
            weights_u=np.ascontiguousarray(np.tile(mesh.u.weights, (nv, 1))),
            weights_v=np.ascontiguousarray(np.repeat(mesh.v.weights, nu, axis=0)),
            scales=np.stack(
                [np.tile(mesh.u.scales, nv), np.repeat(mesh.v.scales, nu)], axis=1
            ).copy(),
            q0=np.ascontiguousarray(mesh.q0, dtype=float),
            thickness=float(thickness),
            youngs_modulus=float(youngs_modulus),
            poisson_ratio=float(poisson_ratio),
            density=float(density),
            gauss=int(gauss),
            membrane=str(membrane),
        )
        return cls(record)

    def _q(self, q: ArrayLike) -> NDArray[np.float64]:
        return np.ascontiguousarray(q, dtype=float)

    def energy(self, q: ArrayLike) -> float:
        """Strain energy ``W(q)`` (docs/derivations/shell.md eq. 4.7)."""
        return float(self.core.energy(self._q(q)))

    def forces(self, q: ArrayLike) -> NDArray[np.float64]:
        """Internal forces ``dW/dq`` (eq. 4.8)."""
        return np.asarray(self.core.forces(self._q(q)))

    def tangent(self, q: ArrayLike) -> sp.csr_matrix:
        """Tangent stiffness ``d²W/dq²`` (eq. 4.9), sparse ``(n, n)``."""
        return _coo(self.core.tangent(self._q(q)), self.n)

    def mass(self) -> sp.csr_matrix:
        """Consistent mass matrix ``∫ ρ t Sᵀ S dA`` (sec. 6), sparse ``(n, n)``."""
        return _coo(self.core.mass(), self.n)

    def area_load(self, p: ArrayLike) -> NDArray[np.float64]:
        """Consistent nodal forces ``∫ Sᵀ p dA`` of a constant force ``p`` (3) per reference
        area (sec. 6)."""
        return np.asarray(self.core.area_load(np.ascontiguousarray(p, dtype=float)))

    def pressure(self, q: ArrayLike, p: float) -> NDArray[np.float64]:
        """Forces ``∫ p Sᵀ ã3 dξ dη`` of a follower pressure ``p`` along the current normal
        ``a3`` (per current area; sec. 6)."""
        return np.asarray(self.core.pressure(self._q(q), float(p)))

    def pressure_tangent(self, q: ArrayLike, p: float) -> sp.csr_matrix:
        """``∂Q/∂q = ∫ p Sᵀ ∂ã3/∂q dξ dη`` of :meth:`pressure` (not symmetric), sparse."""
        return _coo(self.core.pressure_tangent(self._q(q), float(p)), self.n)

    def gravity(self, g: ArrayLike) -> NDArray[np.float64]:
        """Weight ``∫ ρ t Sᵀ g dA`` (sec. 6)."""
        r = self.record
        return self.area_load(r.density * r.thickness * np.asarray(g, dtype=float))
