"""Spatial Kirchhoff rods with torsion on the RANCF centerline: data, triads, mass and gravity.

The element (``src/cpp/elements/rod_kernel.hpp``, derivation in ``docs/derivations/rod-kernel.md``)
keeps the
cable's exact centerline — nodal ``r``, ``r_x``, weights and gradient scales — and adds one twist
``φ`` per node (7 coordinates per node: ``r, r_x, φ``).  Material triads follow Meier, Popp & Wall
(2014): node ``N`` has the triad ``m1 = cos φ u + sin φ t × u`` with ``u = SR(t_ref → t) m1_ref``
(smallest rotation of a reference triad onto the current tangent); inside an element the triad
is carried from node A by smallest rotations and turned by the interpolated relative twist.
Strain energy::

    U = ½ ∫ [EA ε² + GJ (K1 - K1⁰)² + EI2 (K2 - K2⁰)² + EI3 (K3 - K3⁰)²] |r0'| dξ

with the cable's Green–Lagrange ``ε``, the material curvatures ``K1`` (torsion), ``K2 = κ·m1``,
``K3 = κ·m2`` and ``K⁰`` evaluated on the reference with the reference triads, so any curved
reference is stress free.  This module prepares the data the core takes and holds, in NumPy,
the constant translational mass (the cable's) and gravity.  The rotary inertia depends on the
configuration and lives in the core (``src/cpp/elements/rod_inertia.hpp``,
``docs/derivations/rod-kernel.md``
§11): kinetic energy ``½ ∫ [ρ I_p s² + ρ I |ṫ|²] |r0'| dξ`` with the exact spin ``s = ω·t`` of the
material frame (``I_p = I_y + I_z``; the bending part ``ρ I`` only with
``section.rotary_inertia = "full"``).

Shapes: element coordinates ``(n_el, 14)`` ordered ``[rA, rA_x, φA, rB, rB_x, φB]``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.errors import InputError
from rancf.kernels import _core
from rancf.kernels.cable import CableKernel, CableProperties

__all__ = ["RodKernel", "initial_triads", "ROD_DOFS"]

#: Coordinates per node of a rod: position (3), gradient (3), twist (1).
ROD_DOFS = 7
#: Position of the cable's 12 element coordinates within the rod's 14.
_CABLE_IDX = np.r_[0:6, 7:13]


def _plane_normal(points: NDArray) -> NDArray | None:
    """Unit normal of the plane holding ``points`` (None if they are collinear or not planar)."""
    c = points - points.mean(axis=0)
    _, s, vt = np.linalg.svd(c, full_matrices=False)
    scale = s[0] if s.size else 0.0
    if scale == 0.0 or s[1] <= 1e-12 * scale or (s.size > 2 and s[2] > 1e-10 * scale):
        return None
    return vt[2]


def initial_triads(
    nodes: NDArray,
    tangents: NDArray,
    orientation: ArrayLike | None = None,
    closed_arc: NDArray | None = None,
) -> NDArray[np.float64]:
    """Reference directors ``m1`` of every node, ``(n_nodes, 3)`` (docs/derivations/rod.md §2).

    ``orientation`` (projected normal to the first tangent) fixes ``m1`` at the first node; without
    it a planar centerline gets ``m1 = e × t`` with ``e`` the plane normal (so ``m2 = e``, the
    in-plane bending axis), and a straight one the global axis least aligned with it.  The
    director is carried from node to node by smallest rotations of the tangent.

    Closed centrelines (``closed_arc``: the nodes' arc-length fractions, 0 to 1; the last node is
    the first): carried once around, the director comes back turned about the tangent by the
    holonomy ``h`` of the curve (zero for a planar one, not for a spatial one).  The section
    cannot jump at the seam, so each node's director is turned by ``h s_k`` (``s_k`` its
    arc-length fraction): a uniform twist of the reference that closes the material frame
    exactly (``m1`` of the last node is that of the first).  The reference is stress free
    whatever its twist (its curvatures are the reference values).
    """
    t = tangents / np.linalg.norm(tangents, axis=1, keepdims=True)
    if orientation is not None:
        o = np.asarray(orientation, dtype=float)
        m1 = o - (o @ t[0]) * t[0]
        if not np.linalg.norm(m1) > 1e-9 * max(float(np.linalg.norm(o)), 1e-300):
            raise InputError(
                "section.orientation", o.tolist(), "a vector not parallel to the first tangent"
            )
    else:
        e = _plane_normal(np.concatenate([nodes, nodes + t]))
        if e is None:  # straight (or not planar): the global axis least aligned with t0
            e = np.eye(3)[int(np.argmin(np.abs(t[0])))]
            e = e - (e @ t[0]) * t[0]
        m1 = np.cross(e, t[0])
    out = np.empty_like(t)
    out[0] = m1 / np.linalg.norm(m1)
    for k in range(1, len(t)):
        _, out[k] = _core.rod_nodal_triad(t[k - 1], out[k - 1], t[k], 0.0)
    if closed_arc is not None:
        a, b = out[-1], out[0]
        h = np.arctan2(np.cross(a, b) @ t[0], a @ b)  # the turn from the carried m1 to the first
        beta = h * np.asarray(closed_arc, dtype=float)[:, None]
        out = np.cos(beta) * out + np.sin(beta) * np.cross(t, out)
        out[-1] = out[0]
    return out


class RodKernel:
    """Quadrature data, nodal triads, mass and gravity of a rod mesh.

    Parameters
    ----------
    weights, scales, reference
        As :class:`~rancf.kernels.cable.CableKernel` (``reference``: ``(n_el, 4, 3)``).
    props : CableProperties
        ``EA``, ``EI`` (unused) and ``ρA``.
    rho_polar : float
        Rotary inertia per length about the tangent, ``ρ (I_y + I_z)``.
    rho_bend : float
        Rotary inertia per length about both bending axes, ``ρ I`` (0: not modelled).
    n_qp : int
        Gauss points per element.
    orientation : array_like, optional
        First principal axis at the first node (see :func:`initial_triads`).
    rho_bend : float
    closed_arc : ndarray, optional
        A closed centreline: the nodes' arc-length fractions (see :func:`initial_triads`).
    stress_free : {"reference", "straight"}
        As :class:`~rancf.kernels.cable.CableKernel`; ``"straight"`` also sets ``K⁰ = 0``.
    """

    def __init__(
        self,
        weights: ArrayLike,
        scales: ArrayLike,
        reference: ArrayLike,
        props: CableProperties,
        rho_polar: float,
        n_qp: int,
        orientation: ArrayLike | None = None,
        rho_bend: float = 0.0,
        closed_arc: NDArray | None = None,
        stress_free: str = "reference",
    ) -> None:
        self.cable = CableKernel(weights, scales, reference, props, n_qp, stress_free)
        self.straight = stress_free == "straight"
        c = self.cable
        self.n_el = c.n_el
        self.rho_polar = float(rho_polar)
        self.rho_bend = float(rho_bend)
        ref = c.reference
        nodes = np.concatenate([ref[:, 0], ref[-1:, 2]])
        grads = np.concatenate([ref[:, 1], ref[-1:, 3]])
        self.tref = np.ascontiguousarray(grads / np.linalg.norm(grads, axis=1, keepdims=True))
        self.m1ref = np.ascontiguousarray(initial_triads(nodes, grads, orientation, closed_arc))
        self.kref = np.zeros((self.n_el, c.n1.shape[1], 3))
        self.xi = np.ascontiguousarray(c.xi)

    def core_data(self) -> _core.RodData:
        """The data as the core's named structure (``tref``/``m1ref`` are updated in place)."""
        c = self.cable
        return _core.RodData(
            n1=c.n1,
            n2=c.n2,
            xi=self.xi,
            gw=c.gw,
            j0=c.j0,
            kref=self.kref,
            tref=self.tref,
            m1ref=self.m1ref,
        )

    def set_reference_curvatures(self, k: NDArray) -> None:
        """Store ``K⁰`` (computed by the core on the reference) in place; a straight stress-free
        state keeps ``K⁰ = 0`` (docs/derivations/variable-length.md §1)."""
        self.kref[...] = 0.0 if self.straight else k
        self._kref = self.kref.copy()

    def scale_length(self, scale: float) -> None:
        """The unloaded state stretched uniformly by ``scale``: the cable's data
        (:meth:`CableKernel.scale_length <rancf.kernels.cable.CableKernel.scale_length>`) and
        ``K⁰ → K⁰ / scale`` (docs/derivations/variable-length.md §2.1)."""
        self.cable.scale_length(scale)
        self.kref[...] = self._kref / scale

    def core_inertia(self) -> _core.SectionInertia:
        """The rotary inertia per length as the core's named structure."""
        return _core.SectionInertia(polar=self.rho_polar, bend=self.rho_bend)

    def mass_matrices(self) -> NDArray[np.float64]:
        """Constant element mass matrices ``(n_el, 14, 14)``: the cable's translation only.

        The rotary inertia depends on the configuration (the core's ``inertia``; the full mass
        matrix at a configuration is :meth:`rancf.bodies.flexible.Model.mass_matrix`).
        """
        m = np.zeros((self.n_el, 14, 14))
        m[:, _CABLE_IDX[:, None], _CABLE_IDX[None, :]] = self.cable.mass_matrices()
        return m

    def gravity_forces(self, g: ArrayLike) -> NDArray[np.float64]:
        """Element gravity forces ``(n_el, 14)`` (on positions and gradients, as the cable)."""
        f = np.zeros((self.n_el, 14))
        f[:, _CABLE_IDX] = self.cable.gravity_forces(g)
        return f
