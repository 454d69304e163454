"""Planar co-rotational Euler–Bernoulli beam element (the conventional baseline).

Crisfield, *Non-linear Finite Element Analysis of Solids and Structures*, vol. 1, sec. 7.3: nodal
coordinates ``(x, y, θ)`` per node, ``θ`` the rotation of the node from its reference orientation.
With current chord ``d = x2 - x1``, length ``L``, chord rotation ``α`` from the reference chord
(unwrapped near the mean nodal rotation) the local deformations are

    ε = (L² - L0²) / (2 L0²),    θ̄_i = θ_i - α

so a polygonal reference with any nodal tangent angles is stress free.  The axial strain is the
Green–Lagrange strain of the chord — the same measure as the cable elements, so that the three
element types model the same material at large strain.  Energy ``½ EA ε² L0 + (EI / L0)(2θ̄1² +
2θ̄1θ̄2 + 2θ̄2²)``; chord force ``N = EA ε L / L0``, ``[M1, M2] = (EI / L0) [[4, 2], [2, 4]]
[θ̄1, θ̄2]``; global force ``f = Bᵀ [N, M1, M2]`` and tangent ``K = Bᵀ D B + (N / L) z zᵀ +
((M1 + M2) / L²)(r zᵀ + z rᵀ)`` with ``D = diag(EA (L²/L0³ + ε/L0), (EI/L0)[[4, 2], [2, 4]])``,
``r = [-c, -s, 0, c, s, 0]``, ``z = [s, -c, 0, -s, c, 0]``.

The mass matrix is constant: consistent linear interpolation of the translations (exact for the
rigid motion of the straight chord) plus the section's rotary inertia ``ρ I L0 / 2`` lumped at each
node.  Shape conventions: element coordinates ``(n_el, 6)``; matrices ``(n_el, 6, 6)``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.elements.cable_mechanics import CableProperties

__all__ = ["BeamKernel"]


class BeamKernel:
    """Co-rotational 2-node beam elements on a polygon of reference nodes.

    Parameters
    ----------
    positions : ndarray, shape (n_nodes, 2)
        Reference node positions.
    angles : ndarray, shape (n_nodes,)
        Reference tangent angles ψ_i0 of the nodes (radians).
    props : CableProperties
    rho_i : float
        Rotary inertia per length ``ρ I``.
    """

    dim = 2
    n_dof_el = 6

    def __init__(
        self, positions: ArrayLike, angles: ArrayLike, props: CableProperties, rho_i: float
    ) -> None:
        x = np.asarray(positions, dtype=float)
        self.props = props
        self.rho_i = float(rho_i)
        self.n_el = x.shape[0] - 1
        d0 = x[1:] - x[:-1]
        self.l0 = np.linalg.norm(d0, axis=1)
        self.d0 = d0
        self.psi0 = np.asarray(angles, dtype=float)

    def _local(self, e: NDArray) -> tuple[NDArray, ...]:
        e = np.asarray(e, dtype=float).reshape(self.n_el, 6)
        d = e[:, 3:5] - e[:, 0:2]
        length = np.linalg.norm(d, axis=1)
        c, s = d[:, 0] / length, d[:, 1] / length
        th1, th2 = e[:, 2], e[:, 5]
        tm = 0.5 * (th1 + th2)
        cr, sr = np.cos(tm), np.sin(tm)
        rd0 = np.stack(
            [cr * self.d0[:, 0] - sr * self.d0[:, 1], sr * self.d0[:, 0] + cr * self.d0[:, 1]], 1
        )
        alpha = tm + np.arctan2(rd0[:, 0] * d[:, 1] - rd0[:, 1] * d[:, 0], np.sum(rd0 * d, axis=1))
        eps = (length**2 - self.l0**2) / (2.0 * self.l0**2)
        t1, t2 = th1 - alpha, th2 - alpha
        return length, c, s, eps, t1, t2

    def energies(self, e: ArrayLike) -> NDArray[np.float64]:
        """Strain energy per element ``(n_el,)``."""
        _, _, _, eps, t1, t2 = self._local(np.asarray(e))
        ea, ei = self.props.ea, self.props.ei
        return 0.5 * ea * eps**2 * self.l0 + 2.0 * ei / self.l0 * (t1**2 + t1 * t2 + t2**2)

    def _bmat(self, length: NDArray, c: NDArray, s: NDArray) -> tuple[NDArray, NDArray, NDArray]:
        z0 = np.zeros_like(c)
        r = np.stack([-c, -s, z0, c, s, z0], axis=1)
        z = np.stack([s, -c, z0, -s, c, z0], axis=1)
        b = np.zeros((self.n_el, 3, 6))
        b[:, 0] = r
        b[:, 1] = -z / length[:, None]
        b[:, 2] = -z / length[:, None]
        b[:, 1, 2] += 1.0
        b[:, 2, 5] += 1.0
        return b, r, z

    def _local_forces(self, length: NDArray, eps: NDArray, t1: NDArray, t2: NDArray) -> NDArray:
        ea, ei = self.props.ea, self.props.ei
        n = ea * eps * length / self.l0
        m1 = ei / self.l0 * (4.0 * t1 + 2.0 * t2)
        m2 = ei / self.l0 * (2.0 * t1 + 4.0 * t2)
        return np.stack([n, m1, m2], axis=1)

    def forces(self, e: ArrayLike) -> NDArray[np.float64]:
        """Elastic forces ``(n_el, 6)``."""
        length, c, s, eps, t1, t2 = self._local(np.asarray(e))
        b, _, _ = self._bmat(length, c, s)
        return np.einsum("eij,ei->ej", b, self._local_forces(length, eps, t1, t2))

    def forces_and_stiffness(self, e: ArrayLike) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Elastic forces ``(n_el, 6)`` and tangent stiffness ``(n_el, 6, 6)``."""
        length, c, s, eps, t1, t2 = self._local(np.asarray(e))
        b, r, z = self._bmat(length, c, s)
        fl = self._local_forces(length, eps, t1, t2)
        ea, ei = self.props.ea, self.props.ei
        d = np.zeros((self.n_el, 3, 3))
        d[:, 0, 0] = ea * (length**2 / self.l0**3 + eps / self.l0)
        d[:, 1:, 1:] = (ei / self.l0)[:, None, None] * np.array([[4.0, 2.0], [2.0, 4.0]])
        k = np.einsum("eia,eij,ejb->eab", b, d, b)
        k += (fl[:, 0] / length)[:, None, None] * np.einsum("ea,eb->eab", z, z)
        k += ((fl[:, 1] + fl[:, 2]) / length**2)[:, None, None] * (
            np.einsum("ea,eb->eab", r, z) + np.einsum("ea,eb->eab", z, r)
        )
        return np.einsum("eij,ei->ej", b, fl), k

    def mass_matrices(self) -> NDArray[np.float64]:
        """Constant element mass matrices ``(n_el, 6, 6)``."""
        m = np.zeros((self.n_el, 6, 6))
        mt = self.props.rho_a * self.l0 / 6.0
        for i in (0, 1):
            m[:, i, i] = m[:, 3 + i, 3 + i] = 2.0 * mt
            m[:, i, 3 + i] = m[:, 3 + i, i] = mt
        m[:, 2, 2] = m[:, 5, 5] = 0.5 * self.rho_i * self.l0
        return m

    def gravity_forces(self, g: ArrayLike) -> NDArray[np.float64]:
        """Element gravity forces ``(n_el, 6)``."""
        g = np.asarray(g, dtype=float)
        f = np.zeros((self.n_el, 6))
        half = 0.5 * self.props.rho_a * self.l0
        f[:, 0:2] = half[:, None] * g
        f[:, 3:5] = half[:, None] * g
        return f
