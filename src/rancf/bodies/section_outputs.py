"""Section quantities along the body: strain, axial force, curvatures and moments.

At sample points ``ξ`` of every element the compiled core evaluates the strain and curvatures
the element's strain energy uses (``src/cpp/bodies/sections.cpp``); the section forces are their
energy
conjugates (docs/derivations/cable.md §6, docs/derivations/rod.md §5).  The energy per reference
length is
``W = ½ EA ε² + ½ Σ C_i (κ_i - κ_i⁰)²`` with the Green–Lagrange strain ``ε``, the stretch
``λ = sqrt(1 + 2 ε)`` and curvatures ``κ_i`` per *current* arc length; with the curvatures per
reference length ``k_i = λ κ_i`` the conjugates of ``k_i`` and ``λ`` are the moments and the
tension (the forces of a cut section, as equilibrium sees them):

    M_i = ∂W/∂k_i = C_i (κ_i - κ_i⁰) / λ,        N = ∂W/∂λ = EA ε λ - Σ M_i κ_i

(a cable with ``material.axial_strain = "engineering"``: ``W = ½ EA (λ − 1)² + ...`` and
``N = EA (λ − 1) − Σ M_i κ_i``; with an axial law ``W = w(λ − 1) + ...`` and ``N = T(λ − 1) −
Σ M_i κ_i``, docs/derivations/axial-law.md; the ``strain`` output stays the Green–Lagrange ``ε``);

* cable: one curvature (planar: signed, about ``z``; spatial: the magnitude), ``C = EI``;
* beam: ``κ(ξ)`` of the co-rotational cubic per reference length, ``M = EI κ``, ``N = EA ε λ``;
* rod: the material curvatures ``K1`` (twist rate), ``K2``, ``K3`` (bending about ``m1``, ``m2``)
  with ``C = GJ, EI2, EI3``: the twisting moment and the two bending moments.

The rows of a run (:class:`rancf.system.outputs.SystemOutputs`) replace the axial force of
cables and rods by the one read from the nodal forces (:mod:`rancf.bodies.nodal_forces`): the
strain oscillates inside elements whose reference is far more curved than their shape.

``κ0`` and ``K⁰`` are the values at the sample points of the reference configuration, so all
moments vanish there.  Sample points: ``per_element`` equally spaced values ``ξ = k /
per_element`` in every element, and the end of the last one; ``s`` is the reference arc length.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.flexible_core import axial_law_record, section_stiffness
from rancf.elements.cable import cable_shape_functions
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels import _core
from rancf.mesh.mesh import CableMesh

__all__ = ["SectionSampler", "section_names"]


def section_names(model: Model) -> tuple[str, ...]:
    """Names of the quantities, in the column order of :meth:`SectionSampler.values`."""
    if model.family.has_triads:
        return (
            "strain",
            "axial_force",
            "twist_rate",
            "curvature_m1",
            "curvature_m2",
            "twisting_moment",
            "bending_moment_m1",
            "bending_moment_m2",
        )
    return ("strain", "axial_force", "curvature", "bending_moment")


def sample_points(model: Model, xi: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    """The section strains' sample data of a cable or rod model at parameters ``xi`` of every
    element (``sections.hpp``'s ``SamplePoints``): the shape functions' first and second
    derivatives ``(n_el, len(xi), 4)`` and the reference ``s0 = |r0'|²`` (cable) or
    ``j0 = |r0'|`` (rod), ``(n_el, len(xi))``."""
    mesh = model.mesh
    _, n1, n2 = cable_shape_functions(mesh.weights, mesh.scales, xi)
    a0 = np.einsum("eqk,ekd->eqd", n1, mesh.element_nodal())
    j0 = np.linalg.norm(a0, axis=-1)
    ref = j0 if model.family.has_triads else j0**2
    return np.ascontiguousarray(n1), np.ascontiguousarray(n2), np.ascontiguousarray(ref)


class SectionSampler:
    """Evaluates :func:`section_names` at the sample points of a model.

    Parameters
    ----------
    model : Model
    per_element : int
        Sample points per element (``ξ = 0, 1/k, ..., (k-1)/k``; plus the last element's end).
    """

    def __init__(self, model: Model, per_element: int = 4) -> None:
        self.model = model
        xi = np.arange(per_element + 1) / per_element
        self.xi = xi
        self.per_element = per_element
        n_el = model.n_el
        # point k of element e at row e * per_element + k; the last element keeps ξ = 1
        self._rows = np.r_[
            (np.arange(n_el)[:, None] * (per_element + 1) + np.arange(per_element)).ravel(),
            n_el * (per_element + 1) - 1,
        ]
        beam = model.family.beam_kernel(model.kernel)
        if beam is not None:
            l0 = beam.l0
            self.n1 = self.n2 = self.ref = np.zeros(0)
            s_el = l0[:, None] * xi[None, :]
            starts = np.r_[0.0, np.cumsum(l0)[:-1]]
        else:
            self.n1, self.n2, self.ref = sample_points(model, xi)
            s_el, starts = _arc_lengths(model.mesh, xi)
        self.s = (starts[:, None] + s_el).ravel()[self._rows]
        ref_vals = self._raw(model.y0)
        # the moments are relative to the stress-free curvature (zero for a straight one)
        self._k0 = ref_vals[:, 1:] * (model.stress_free != "straight")

    @property
    def n_points(self) -> int:
        """Number of sample points, ``per_element n_el + 1``."""
        return int(self._rows.size)

    def between_nodes(self, nodal: NDArray) -> NDArray[np.float64]:
        """Nodal values ``(..., n_nodes)`` at the sample points ``(..., n_points)``, linear in
        ``ξ`` inside every element (the axial force of :mod:`rancf.bodies.nodal_forces`)."""
        nodal = np.asarray(nodal, dtype=float)
        xi = self.xi[:-1]
        inner = (nodal[..., :-1, None] * (1.0 - xi) + nodal[..., 1:, None] * xi).reshape(
            nodal.shape[:-1] + (-1,)
        )
        return np.concatenate([inner, nodal[..., -1:]], axis=-1)

    def positions(self, y: NDArray) -> NDArray[np.float64]:
        """Positions ``(n_points, dim)`` of the sample points at model coordinates ``y`` (the
        element's curve; a beam's chord)."""
        m = self.model
        nodes = m.q_from_y(np.asarray(y, dtype=float)).reshape(m.n_nodes, m.dpn)
        if not m.family.gradient:
            x = nodes[:, :2]
            pts = x[:-1, None, :] + self.xi[None, :, None] * (x[1:] - x[:-1])[:, None, :]
        else:
            pts = m.mesh.evaluate(self.xi, nodes[:, : 2 * m.dim])
        return pts.reshape(-1, m.dim)[self._rows]

    def _raw(self, y: NDArray, factor: float = 1.0) -> NDArray[np.float64]:
        m = self.model
        width = 4 if m.family.has_triads else 2
        y = np.ascontiguousarray(y, dtype=float)
        lead = y.shape[:-1]  # k states (k, n) at once: (k, n_points, width)
        out = np.empty((*lead, m.n_el, self.xi.size, width))
        lam = _scale(m) * factor  # another unstretched length (rancf.bodies.length, winches)
        ref = self.ref * (lam if m.family.has_triads else lam * lam)
        m.core.section_strains(self.xi, self.n1, self.n2, ref, y, out)
        return out.reshape(*lead, -1, width)[..., self._rows, :]

    def values(self, y: NDArray, factor: float = 1.0) -> NDArray[np.float64]:
        """``(n_points, len(section_names))`` at model coordinates ``y`` (rods: with the nodal
        triads the model holds, i.e. those the solvers carried to ``y``); ``factor``: the
        body's unstretched length over the one its arrays hold (a winch's body at a time)."""
        return self.from_raw(self.raw(y, factor), factor)

    def raw(self, y: NDArray, factor: float = 1.0) -> NDArray[np.float64]:
        """Strain and curvatures ``(n_points, 2 or 4)`` at ``y`` (the first columns of
        :meth:`values`; :meth:`from_raw` makes the rest); ``(k, n_points, ...)`` for ``k``
        states ``y`` ``(k, n)``."""
        return self._raw(y, factor)

    def from_raw(self, raw: NDArray, factor: float | NDArray = 1.0) -> NDArray[np.float64]:
        """:meth:`values` from :meth:`raw`, for one state or a stack ``(..., n_points, w)``
        (``factor``: as :meth:`values`, or one a state, shaped to broadcast: ``(k, 1, 1)``);
        cables and rods by the core's ``section_forces`` (the module docstring's ``M_i`` and
        ``N``, ``src/cpp/bodies/sections.hpp``)."""
        m = self.model
        raw = np.ascontiguousarray(raw, dtype=float)
        if m.family.gradient:  # the core, every point of every state in one call
            st = section_stiffness(m)
            c = np.array([st.gj, st.ei2, st.ei3]) if m.family.has_triads else np.array([st.ei])
            k = int(np.prod(raw.shape[:-2]))
            scale = np.broadcast_to(_scale(m) * np.asarray(factor, dtype=float).ravel(), (k,))
            out = np.empty((*raw.shape[:-1], 2 * raw.shape[-1]))
            k0, scale = np.ascontiguousarray(self._k0), np.ascontiguousarray(scale)
            law = axial_law_record(m)
            ea, eng = float(m.props.ea), bool(st.engineering)
            _core.section_forces(raw, k0, c, ea, eng, scale, out, axial_law=law)
            return out
        eps, kappa = raw[..., 0], raw[..., 1:]  # a beam: per reference length already
        stretch = np.sqrt(np.clip(1.0 + 2.0 * eps, 0.0, None))
        moments = kappa * m.props.ei
        force = m.props.ea * eps * stretch
        return np.concatenate([eps[..., None], force[..., None], kappa, moments], axis=-1)


def _scale(model: Model) -> float:
    """The unstretched length over the reference's (:mod:`rancf.bodies.length`)."""
    k = model.kernel
    return float(getattr(getattr(k, "cable", k), "length_scale", 1.0))


def _arc_lengths(mesh: CableMesh, xi: NDArray, n_gauss: int = 12) -> tuple[NDArray, NDArray]:
    """Reference arc length from each element's start to ``ξ`` ``(n_el, n_xi)``, and the arc
    length at each element's start ``(n_el,)``; Gauss–Legendre on ``[0, ξ]``."""
    gp, gw = gauss_legendre(n_gauss)
    pts = (xi[:, None] * gp[None, :]).ravel()  # (n_xi * n_gauss)
    _, n1, _ = cable_shape_functions(mesh.weights, mesh.scales, pts)
    e0 = mesh.element_nodal()
    speed = np.linalg.norm(np.einsum("eqk,ekd->eqd", n1, e0), axis=-1)
    speed = speed.reshape(speed.shape[0], xi.size, n_gauss)
    s_el = np.einsum("exg,g->ex", speed, gw) * xi[None, :]
    total = s_el[:, -1] if xi[-1] == 1.0 else s_el[:, -1] / xi[-1]
    return s_el, np.r_[0.0, np.cumsum(total)[:-1]]
