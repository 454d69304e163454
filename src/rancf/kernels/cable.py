"""Cable elements (ANCF and RANCF): quadrature data, constant mass and gravity.

Conic-section paper sec. 5 (eqs. 34–41); docs/derivations/cable.md sec. 6.  The elastic forces,
tangent stiffness
and strain energy live once, in the compiled core (``src/cpp/elements/cable.cpp``): with ``a =
r_ξ`` and ``b = r_ξξ`` at a Gauss point and the reference ``a0`` (``J0 = |a0|``, ``s0 = J0²``),

* axial strain (Green–Lagrange, relative to the reference): ``ε = (a·a - s0) / (2 s0)``;
* curvature: planar (signed) ``κ = (a × b)_z / |a|³``; spatial ``κ = |a × b| / |a|³`` on a
  straight reference and, at curved reference points, the regularized magnitude
  ``κr = sqrt(κ² + η² κ0²)`` with energy ``½ EI (1 + η²)(κr - κ0 sqrt(1 + η²))²``
  (η = :data:`ETA` = 0.05): zero at the reference, the same linearized stiffness as ``|κ|``, and
  smooth where the plain magnitude has a cusp at κ = 0;
* strain energy per unit ξ: ``W = ½ [EA ε² + EI (κ - κ0)²] J0``.

This module computes what the core takes as data: shape-function derivatives at the Gauss points,
the reference ``s0, J0, κ0`` (by the core's own ``|r'|²`` and curvature routine) and the
regularization ``η² κ0²``; and, in NumPy, the constant mass matrix ``M = ∫ ρA Sᵀ S J0 dξ`` and
gravity ``Q_g = ∫ ρA Sᵀ g J0 dξ`` (their single implementation), all over the true reference arc
length so that the reference configuration is exactly stress-free.

Shape conventions: element nodal coordinates ``(n_el, 4, dim)``; quadrature data
``(n_el, n_qp, ...)``; element vectors ``(n_el, 4 dim)`` and matrices ``(n_el, 4 dim, 4 dim)``
with the coordinate ``i`` of node block ``k`` at index ``k dim + i``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels import _core

__all__ = ["CableKernel", "CableProperties", "ETA", "qp_geometry"]

#: Regularization of the spatial magnitude curvature at curved reference points.
ETA: float = _core.CABLE_ETA


@dataclass(frozen=True)
class CableProperties:
    """Section and material of a cable: ``EA``, ``EI`` and mass per length ``ρA``."""

    ea: float
    ei: float
    rho_a: float


def qp_geometry(n1: NDArray, n2: NDArray, e: ArrayLike) -> tuple[NDArray, NDArray]:
    """``|r_ξ|²`` and the curvature at the Gauss points, each ``(n_el, n_qp)``.

    Parameters
    ----------
    n1, n2 : ndarray, shape (n_el, n_qp, 4)
        First and second ξ-derivatives of the shape functions.
    e : array_like, shape (n_el, 4, dim)
        Element nodal coordinates.
    """
    e = np.ascontiguousarray(e, dtype=float)
    aa = np.empty(n1.shape[:2])
    kappa = np.empty(n1.shape[:2])
    _core.cable_qp_geometry(
        np.ascontiguousarray(n1), np.ascontiguousarray(n2), e, e.shape[-1], aa, kappa
    )
    return aa, kappa


class CableKernel:
    """Quadrature data, mass and gravity of a cable mesh.

    Parameters
    ----------
    weights : ndarray, shape (n_el, 4)
    scales : ndarray, shape (n_el,)
    reference : ndarray, shape (n_el, 4, dim)
        Element nodal coordinates of the stress-free reference configuration.
    props : CableProperties
    n_qp : int
        Gauss–Legendre points per element (see the quadrature convergence test).
    stress_free : {"reference", "straight"}
        The unloaded state: the reference itself, or the straight line of the same arc length
        (``κ0 = 0`` with the reference metric ``J0``: docs/derivations/variable-length.md §1).
    """

    def __init__(
        self,
        weights: ArrayLike,
        scales: ArrayLike,
        reference: ArrayLike,
        props: CableProperties,
        n_qp: int,
        stress_free: str = "reference",
    ) -> None:
        self.weights = np.asarray(weights, dtype=float)
        self.scales = np.asarray(scales, dtype=float)
        self.reference = np.asarray(reference, dtype=float)
        self.props = props
        self.n_el, _, self.dim = self.reference.shape
        xi, gw = gauss_legendre(n_qp)
        self.xi, self.gw = xi, np.ascontiguousarray(gw)
        n0, n1, n2 = cable_shape_functions(self.weights, self.scales, xi)
        self.n0 = n0
        self.n1, self.n2 = np.ascontiguousarray(n1), np.ascontiguousarray(n2)
        self.s0, self.kappa0 = qp_geometry(self.n1, self.n2, self.reference)
        self.j0 = np.sqrt(self.s0)
        # spatial: η² κ0² at curved reference points (κ0 J0 above round-off), zero elsewhere
        self.qreg = np.zeros_like(self.s0)
        if self.dim == 3:
            curved = self.kappa0 * self.j0 > _core.CABLE_STRAIGHT
            self.qreg = np.where(curved, (ETA * self.kappa0) ** 2, 0.0)
        self.wj = gw[None, :] * self.j0  # (n_el, n_qp): dξ weight times reference speed
        #: The unstretched length over the reference's (:meth:`scale_length`).
        self.length_scale = 1.0
        self._unscaled = (self.s0.copy(), self.kappa0.copy(), self.qreg.copy())
        if stress_free == "straight":
            self.straighten()

    def straighten(self) -> None:
        """Make the unloaded state straight: the same arc length element by element (``J0``
        kept), no curvature (``κ0 = 0``, no regularization).  In place, before the core is
        built (:func:`rancf.bodies.stress_free.resolve_stress_free`)."""
        for k0, qr in ((self.kappa0, self.qreg), self._unscaled[1:]):
            k0[...] = 0.0
            qr[...] = 0.0

    def scale_length(self, scale: float) -> None:
        """Make the unloaded state the reference stretched uniformly by ``scale`` (an unstretched
        length ``scale`` times the reference's): ``s0 → scale² s0``, ``J0 → scale J0``,
        ``κ0 → κ0 / scale`` (docs/derivations/variable-length.md §2.1).  In place: the compiled
        core reads these arrays; the mass and gravity of a model follow from ``wj``.
        """
        s0, k0, qr = self._unscaled
        self.s0[...] = scale * scale * s0
        self.j0[...] = scale * np.sqrt(s0)
        self.kappa0[...] = k0 / scale
        self.qreg[...] = qr / (scale * scale)
        self.wj[...] = self.gw[None, :] * self.j0
        self.length_scale = float(scale)

    @property
    def reference_speed(self) -> NDArray[np.float64]:
        """``|r0'|`` of the reference at the Gauss points ``(n_el, n_qp)``, whatever
        :meth:`scale_length` did."""
        return np.sqrt(self._unscaled[0])

    @property
    def n_dof_el(self) -> int:
        """Coordinates per element, ``4 dim``."""
        return 4 * self.dim

    def core_data(self) -> _core.CableData:
        """The quadrature data as the compiled core's named structure."""
        return _core.CableData(
            n1=self.n1,
            n2=self.n2,
            gw=self.gw,
            s0=self.s0,
            k0=self.kappa0,
            j0=self.j0,
            qr=self.qreg,
        )

    def mass_matrices(self) -> NDArray[np.float64]:
        """Element mass matrices ``ρA ∫ Sᵀ S J0 dξ``, shape ``(n_el, 4 dim, 4 dim)``."""
        m4 = self.props.rho_a * np.einsum("eq,eqk,eql->ekl", self.wj, self.n0, self.n0)
        return np.einsum("ekl,ij->ekilj", m4, np.eye(self.dim)).reshape(
            self.n_el, self.n_dof_el, self.n_dof_el
        )

    def gravity_forces(self, g: ArrayLike) -> NDArray[np.float64]:
        """Element gravity forces ``ρA ∫ Sᵀ g J0 dξ``, shape ``(n_el, 4 dim)``."""
        g = np.asarray(g, dtype=float)
        n = self.props.rho_a * np.einsum("eq,eqk->ek", self.wj, self.n0)
        return (n[:, :, None] * g[None, None, :]).reshape(self.n_el, self.n_dof_el)

    def curvatures(self, e: ArrayLike) -> NDArray[np.float64]:
        """Curvature at the Gauss points, ``(n_el, n_qp)``."""
        return qp_geometry(self.n1, self.n2, np.asarray(e).reshape(self.reference.shape))[1]
