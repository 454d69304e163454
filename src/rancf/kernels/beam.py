"""Planar co-rotational Euler–Bernoulli beam element (the conventional baseline): data and mass.

The forces, tangent and energy below live once, in the compiled core
(``src/cpp/elements/beam.cpp``).

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

from rancf.kernels import _core
from rancf.kernels.cable import CableProperties

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

    def core_data(self) -> _core.BeamData:
        """The reference chords as the compiled core's named structure."""
        return _core.BeamData(l0=self.l0, d0=np.ascontiguousarray(self.d0))

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
