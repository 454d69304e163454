"""Mass, gravity and elastic forces of ANCF/RANCF cable elements (NumPy reference kernels).

Conic-section paper sec. 5 (eqs. 34–41); math note sec. 6.  With ``a = r_ξ`` and ``b = r_ξξ``
at a quadrature point and the reference ``a0 = r0_ξ`` (``J0 = |a0|``, ``s0 = J0²``):

* axial strain (Green–Lagrange, relative to the reference): ``ε = (a·a - s0) / (2 s0)``;
* curvature: planar (signed) ``κ = (a × b)_z / |a|³``; spatial ``κ = |a × b| / |a|³`` on a
  straight reference, and at curved reference points the regularized magnitude
  ``κr = sqrt(κ² + η² κ0²)`` with energy ``½ EI (1 + η²)(κr - κ0 sqrt(1 + η²))²`` (η = ``ETA``
  = 0.05): zero at the reference, the same linearized stiffness as ``|κ|``, and smooth everywhere,
  whereas the plain magnitude has a cusp at κ = 0 that stops Newton's method when a curved cable
  passes through a straight shape in 3D; the difference from ``(|κ| - κ0)²`` is confined to
  ``|κ| ≲ η κ0``;
* strain energy per unit ξ: ``W = ½ [EA ε² + EI (κ - κ0)²] J0``;
* mass ``M = ∫ ρA Sᵀ S J0 dξ``, gravity ``Q_g = ∫ ρA Sᵀ g J0 dξ``; all integrals over the true
  reference arc length, so the reference configuration is exactly stress-free.

``W`` is differentiated by hand with respect to ``z = (a, b)``; forces and tangent stiffness follow
by the chain rule with ``∂a/∂e_k = N'_k I``, ``∂b/∂e_k = N''_k I``.

Shape conventions: element nodal coordinates ``E`` ``(n_el, 4, dim)``; quadrature data
``(n_el, n_qp, ...)``; element force vectors ``(n_el, 4 dim)`` and matrices
``(n_el, 4 dim, 4 dim)`` with the coordinate ``i`` of node block ``k`` at index ``k dim + i``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable import cable_shape_functions
from rancf.geometry.quadrature import gauss_legendre

__all__ = ["CableKernel", "energy_density_derivatives"]

#: Below this relative curvature a spatial reference point counts as straight (κ0 = 0 branch).
_STRAIGHT = 1e-12
#: Regularization of the spatial magnitude curvature at curved reference points (see CableKernel).
ETA = 0.05


def energy_density_derivatives(
    a: NDArray,
    b: NDArray,
    s0: NDArray,
    kappa0: NDArray,
    j0: NDArray,
    ea: float,
    ei: float,
    hessian: bool = True,
    qreg: NDArray | None = None,
) -> tuple[NDArray, NDArray, NDArray | None]:
    """Energy density ``W`` and its gradient and Hessian in ``z = (a, b)``.

    Parameters
    ----------
    a, b : ndarray, shape (..., dim)
        ``r_ξ`` and ``r_ξξ`` at the quadrature points.
    s0, kappa0, j0 : ndarray, shape (...)
        Reference ``|r0_ξ|²``, curvature and ``|r0_ξ|``.
    ea, ei : float
        Axial and bending stiffness.
    qreg : ndarray, shape (...), optional
        Spatial only: ``η² κ0²`` at curved reference points (zero elsewhere), the regularization
        of the magnitude curvature.

    Returns
    -------
    w : ndarray, shape (...)
    grad : ndarray, shape (..., 2 dim)
    hess : ndarray, shape (..., 2 dim, 2 dim) or None
    """
    dim = a.shape[-1]
    eye = np.eye(dim)
    aa = np.einsum("...i,...i->...", a, a)
    eps = (aa - s0) / (2.0 * s0)
    w = 0.5 * ea * eps**2 * j0
    ga = (ea * j0 * eps / s0)[..., None] * a
    gb = np.zeros_like(b)
    if hessian:
        haa = (ea * j0 / s0**2)[..., None, None] * np.einsum("...i,...j->...ij", a, a) + (
            ea * j0 * eps / s0
        )[..., None, None] * eye
        hab = np.zeros(a.shape + (dim,))
        hbb = np.zeros(a.shape + (dim,))
    outer = np.einsum  # alias for brevity below

    if dim == 2:
        c = a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]
        p = aa**-1.5
        kappa = c * p
        delta = kappa - kappa0
        c_a = np.stack([b[..., 1], -b[..., 0]], axis=-1)
        c_b = np.stack([-a[..., 1], a[..., 0]], axis=-1)
        p_a = (-3.0 * aa**-2.5)[..., None] * a
        k_a = p[..., None] * c_a + c[..., None] * p_a
        k_b = p[..., None] * c_b
        w = w + 0.5 * ei * delta**2 * j0
        f = (ei * j0 * delta)[..., None]
        ga = ga + f * k_a
        gb = gb + f * k_b
        if hessian:
            p_aa = (-3.0 * aa**-2.5)[..., None, None] * eye + (15.0 * aa**-3.5)[
                ..., None, None
            ] * outer("...i,...j->...ij", a, a)
            c_ab = np.array([[0.0, 1.0], [-1.0, 0.0]])
            k_aa = (
                outer("...i,...j->...ij", c_a, p_a)
                + outer("...i,...j->...ij", p_a, c_a)
                + c[..., None, None] * p_aa
            )
            k_ab = p[..., None, None] * c_ab + outer("...i,...j->...ij", p_a, c_b)
            s = (ei * j0)[..., None, None]
            d = delta[..., None, None]
            haa = haa + s * (outer("...i,...j->...ij", k_a, k_a) + d * k_aa)
            hab = hab + s * (outer("...i,...j->...ij", k_a, k_b) + d * k_ab)
            hbb = hbb + s * outer("...i,...j->...ij", k_b, k_b)
    else:
        # u = κ² = |a × b|² / |a|⁶ is smooth; at curved reference points the bending term is
        # ½ EI (1 + η²) (κr - κr0)² with κr = sqrt(u + η² κ0²), κr0 = κ0 sqrt(1 + η²)
        # (qreg = η² κ0², zero where the reference is straight).
        bb = np.einsum("...i,...i->...", b, b)
        ab = np.einsum("...i,...i->...", a, b)
        cr = np.cross(a, b)
        q = np.einsum("...i,...i->...", cr, cr)  # = aa bb - ab², without the cancellation
        s_ = aa**-3.0
        q_a = 2.0 * bb[..., None] * a - 2.0 * ab[..., None] * b
        q_b = 2.0 * aa[..., None] * b - 2.0 * ab[..., None] * a
        s_a = (-6.0 * aa**-4.0)[..., None] * a
        u = q * s_
        u_a = q_a * s_[..., None] + q[..., None] * s_a
        u_b = q_b * s_[..., None]
        c = np.zeros_like(u) if qreg is None else qreg
        curved = c > 0.0
        fac = np.where(curved, 1.0 + ETA**2, 1.0)
        kr = np.sqrt(u + c)
        kr0 = kappa0 * np.sqrt(1.0 + ETA**2)
        ratio = np.where(curved, kr0 / np.where(curved, kr, 1.0), 0.0)  # κr0 / κr
        half = 0.5 * ei * j0 * fac
        w = w + half * (u + c - 2.0 * kr0 * kr * curved + kr0**2 * curved)
        gfac = (half * (1.0 - ratio))[..., None]
        ga = ga + gfac * u_a
        gb = gb + gfac * u_b
        if hessian:
            o = lambda x, y: outer("...i,...j->...ij", x, y)  # noqa: E731
            q_aa = 2.0 * bb[..., None, None] * eye - 2.0 * o(b, b)
            q_bb = 2.0 * aa[..., None, None] * eye - 2.0 * o(a, a)
            q_ab = 4.0 * o(a, b) - 2.0 * o(b, a) - 2.0 * ab[..., None, None] * eye
            s_aa = (-6.0 * aa**-4.0)[..., None, None] * eye + (48.0 * aa**-5.0)[
                ..., None, None
            ] * o(a, a)
            sx = s_[..., None, None]
            u_aa = q_aa * sx + o(q_a, s_a) + o(s_a, q_a) + q[..., None, None] * s_aa
            u_ab = q_ab * sx + o(s_a, q_b)
            u_bb = q_bb * sx
            h1 = gfac[..., None]
            h2 = (half * ratio / (2.0 * np.where(curved, u + c, 1.0)))[..., None, None]
            haa = haa + h1 * u_aa + h2 * o(u_a, u_a)
            hab = hab + h1 * u_ab + h2 * o(u_a, u_b)
            hbb = hbb + h1 * u_bb + h2 * o(u_b, u_b)
    grad = np.concatenate([ga, gb], axis=-1)
    if not hessian:
        return w, grad, None
    hess = np.concatenate(
        [
            np.concatenate([haa, hab], axis=-1),
            np.concatenate([np.swapaxes(hab, -1, -2), hbb], axis=-1),
        ],
        axis=-2,
    )
    return w, grad, hess


@dataclass(frozen=True)
class CableProperties:
    """Section and material of a cable: ``EA``, ``EI`` and mass per length ``ρA``."""

    ea: float
    ei: float
    rho_a: float


class CableKernel:
    """Precomputed quadrature data of a cable mesh and its element force kernels.

    Parameters
    ----------
    weights : ndarray, shape (n_el, 4)
    scales : ndarray, shape (n_el,)
    reference : ndarray, shape (n_el, 4, dim)
        Element nodal coordinates of the stress-free reference configuration.
    props : CableProperties
    n_qp : int
        Gauss–Legendre points per element (default 10; see the convergence test).
    """

    def __init__(
        self,
        weights: ArrayLike,
        scales: ArrayLike,
        reference: ArrayLike,
        props: CableProperties,
        n_qp: int = 10,
    ) -> None:
        self.weights = np.asarray(weights, dtype=float)
        self.scales = np.asarray(scales, dtype=float)
        self.reference = np.asarray(reference, dtype=float)
        self.props = props
        self.n_el, _, self.dim = self.reference.shape
        xi, gw = gauss_legendre(n_qp)
        self.xi, self.gw = xi, gw
        self.n0, self.n1, self.n2 = cable_shape_functions(self.weights, self.scales, xi)
        a0 = np.einsum("eqk,ekd->eqd", self.n1, self.reference)
        b0 = np.einsum("eqk,ekd->eqd", self.n2, self.reference)
        self.s0 = np.einsum("eqd,eqd->eq", a0, a0)
        self.j0 = np.sqrt(self.s0)
        self.kappa0 = self._curvature(a0, b0)
        # spatial: η² κ0² at curved reference points (κ0 J0 above round-off), zero elsewhere
        self.qreg = np.zeros_like(self.s0)
        if self.dim == 3:
            curved = self.kappa0 * self.j0 > _STRAIGHT
            self.qreg = np.where(curved, (ETA * self.kappa0) ** 2, 0.0)
        self.wj = gw[None, :] * self.j0  # (n_el, n_qp): dξ weight times reference speed

    def _curvature(self, a: NDArray, b: NDArray) -> NDArray:
        aa = np.einsum("...i,...i->...", a, a)
        if self.dim == 2:
            return (a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]) * aa**-1.5
        return np.linalg.norm(np.cross(a, b), axis=-1) * aa**-1.5

    @property
    def n_dof_el(self) -> int:
        """Coordinates per element, ``4 dim``."""
        return 4 * self.dim

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

    def _ab(self, e: NDArray) -> tuple[NDArray, NDArray]:
        e = np.asarray(e, dtype=float).reshape(self.n_el, 4, self.dim)
        return np.einsum("eqk,ekd->eqd", self.n1, e), np.einsum("eqk,ekd->eqd", self.n2, e)

    def energies(self, e: ArrayLike) -> NDArray[np.float64]:
        """Strain energy of every element, shape ``(n_el,)``."""
        a, b = self._ab(e)
        w, _, _ = energy_density_derivatives(
            a, b, self.s0, self.kappa0, self.j0, self.props.ea, self.props.ei, False, self.qreg
        )
        return np.einsum("q,eq->e", self.gw, w)

    def forces(self, e: ArrayLike) -> NDArray[np.float64]:
        """Generalized elastic forces ``∂U/∂e``, shape ``(n_el, 4 dim)``."""
        a, b = self._ab(e)
        _, g, _ = energy_density_derivatives(
            a, b, self.s0, self.kappa0, self.j0, self.props.ea, self.props.ei, False, self.qreg
        )
        return self._force_from_grad(g)

    def _force_from_grad(self, g: NDArray) -> NDArray:
        d = self.dim
        f = np.einsum("q,eqk,eqi->eki", self.gw, self.n1, g[..., :d]) + np.einsum(
            "q,eqk,eqi->eki", self.gw, self.n2, g[..., d:]
        )
        return f.reshape(self.n_el, self.n_dof_el)

    def forces_and_stiffness(self, e: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Elastic forces ``(n_el, 4 dim)`` and tangent ``∂²U/∂e²`` ``(n_el, 4 dim, 4 dim)``."""
        a, b = self._ab(e)
        _, g, h = energy_density_derivatives(
            a, b, self.s0, self.kappa0, self.j0, self.props.ea, self.props.ei, True, self.qreg
        )
        d = self.dim
        # B_q: (n_el, n_qp, 2 dim, 4 dim) maps element coordinates to z = (a, b)
        eye = np.eye(d)
        bmat = np.concatenate(
            [
                np.einsum("eqk,ij->eqikj", self.n1, eye).reshape(self.n_el, -1, d, 4 * d),
                np.einsum("eqk,ij->eqikj", self.n2, eye).reshape(self.n_el, -1, d, 4 * d),
            ],
            axis=2,
        )
        k = np.einsum("q,eqzm,eqzy,eqyn->emn", self.gw, bmat, h, bmat, optimize=True)
        return self._force_from_grad(g), k

    def curvatures(self, e: ArrayLike) -> NDArray[np.float64]:
        """Curvature at the quadrature points, ``(n_el, n_qp)``."""
        return self._curvature(*self._ab(e))

    def strains(self, e: ArrayLike) -> NDArray[np.float64]:
        """Axial Green–Lagrange strain at the quadrature points, ``(n_el, n_qp)``."""
        a, _ = self._ab(e)
        return (np.einsum("eqd,eqd->eq", a, a) - self.s0) / (2.0 * self.s0)
