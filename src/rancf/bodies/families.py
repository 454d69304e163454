"""Element families: one object per element kind, found by its name in :data:`FAMILIES`.

A family knows what differs between the element kinds of a flexible body: its nodal layout
(coordinates per node, the position entries), the geometries and options it accepts, and how it
builds its element kernel (shape functions, mass, forces and tangents, evaluated by the core) from
a mesh.  Code outside this module asks the family (``family("rod").has_triads``,
``model.family.rod_kernel(model.kernel)``) instead of comparing kind names or kernel classes.

* ``"rancf"``, ``"ancf"``: gradient-deficient cable elements, ``[r, r_x]`` per node
  (:mod:`rancf.kernels.cable`); ``"ancf"`` converts an exact mesh to polynomial elements.
* ``"rod"``: the cable coordinates plus a twist angle, ``[r, r_x, φ]`` (:mod:`rancf.kernels.rod`).
* ``"beam"``: the planar Euler-Bernoulli beam, ``[x, y, θ]`` (:mod:`rancf.kernels.beam`).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Literal, cast

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.closure import arc_fractions
from rancf.errors import InputError
from rancf.kernels.beam import BeamKernel
from rancf.kernels.cable import CableKernel, CableProperties
from rancf.kernels.rod import ROD_DOFS, RodKernel
from rancf.mesh.factories import to_ancf
from rancf.mesh.mesh import CableMesh

__all__ = ["Built", "ElementFamily", "ElementKind", "FAMILIES", "SHELL", "family", "framed"]

ElementKind = Literal["rancf", "ancf", "beam", "rod"]

Kernel = CableKernel | BeamKernel | RodKernel


@dataclass(frozen=True)
class Built:
    """What a family builds from a mesh: the kernel, the mesh it uses, the reference ``q0``."""

    kernel: Kernel
    mesh: CableMesh
    q0: NDArray[np.float64]


@dataclass(frozen=True)
class ElementFamily:
    """One element kind: its layout, what it accepts, and its kernel's builder.

    Attributes
    ----------
    name : str
        The kind's name in ``mesh.element``.
    dims : tuple of int
        The geometry dimensions it accepts.
    gradient : bool
        Nodal coordinates hold the position gradient ``r_x`` (cables and rods): C² continuity,
        straight stress-free states and clamped gradients apply.
    has_triads : bool
        Nodes carry a material frame (rods): point moments, rotary inertia, nodal directors.
    engineering_strain : bool
        The engineering axial strain is built for it.
    build : callable
        ``build(mesh, section, props, rho, n_qp, stress_free) -> Built``.
    surface : bool
        A two-dimensional element (the shell, :data:`SHELL`): four nodes an element, gathered
        through a connectivity; no line sections, centre line or node places.
    """

    name: str
    dims: tuple[int, ...]
    gradient: bool
    has_triads: bool
    engineering_strain: bool
    build: Callable[..., Built]
    surface: bool = False

    @property
    def cable(self) -> bool:
        """A cable element (``rancf``, ``ancf``): position and gradient per node, no frame."""
        return self.gradient and not self.has_triads

    @property
    def place_kind(self) -> str:
        """The core's kind of a place at one of its nodes: ``cable``, ``rod`` or ``beam``."""
        return "rod" if self.has_triads else "cable" if self.gradient else "beam"

    @property
    def core_kind(self) -> int:
        """The core's element kind of a flexible body: 0 cable, 1 beam, 2 rod, 3 shell."""
        if self.surface:
            return 3
        return 2 if self.has_triads else 0 if self.gradient else 1

    def cable_kernel(self, kernel: Kernel) -> CableKernel | None:
        """Its kernel as the cable element's (``rancf``, ``ancf``); None for the other kinds."""
        return cast(CableKernel, kernel) if self.cable else None

    def rod_kernel(self, kernel: Kernel) -> RodKernel | None:
        """Its kernel as the rod element's; None for the other kinds."""
        return cast(RodKernel, kernel) if self.has_triads else None

    def beam_kernel(self, kernel: Kernel) -> BeamKernel | None:
        """Its kernel as the beam element's; None for the other kinds."""
        return None if self.gradient or self.surface else cast(BeamKernel, kernel)

    def centre_line(self, kernel: Kernel) -> CableKernel | None:
        """The cable kernel of its centre line ``r(ξ)``: a cable's own, a rod's (its ``cable``);
        None for a beam."""
        rod = self.rod_kernel(kernel)
        return rod.cable if rod is not None else self.cable_kernel(kernel)

    def dofs_per_node(self, dim: int) -> int:
        """Coordinates per node: ``2 dim`` (cables), 7 (rods), 3 (beams)."""
        if self.has_triads:
            return ROD_DOFS
        return 2 * dim if self.gradient else 3

    def check_dim(self, dim: int) -> None:
        """A clear error when the geometry's dimension is not one the family accepts."""
        if dim not in self.dims:
            plane = "planar (2D geometry)" if self.dims == (2,) else "spatial (3D geometry)"
            raise InputError("mesh.element", self.name, f"the {self.name} element is {plane}")


def _n_qp(mesh: CableMesh, n_qp: int | None) -> int:
    """Gauss points per element: 6 for polynomial (all weights 1) elements, else 10."""
    if n_qp is not None:
        return n_qp
    return 6 if np.all(mesh.weights == 1.0) else 10


def _beam(
    mesh: CableMesh, section: Any, props: CableProperties, rho: float, n_qp: int | None, sf: str
) -> Built:
    t = mesh.nodes[:, 1]
    kernel = BeamKernel(
        mesh.nodes[:, 0], np.arctan2(t[:, 1], t[:, 0]), props, rho * section.inertia
    )
    q0 = np.concatenate([mesh.nodes[:, 0], np.zeros((mesh.n_nodes, 1))], axis=1).ravel()
    return Built(kernel, mesh, q0)


def _cable(polynomial: bool) -> Callable[..., Built]:
    def build(
        mesh: CableMesh,
        section: Any,
        props: CableProperties,
        rho: float,
        n_qp: int | None,
        sf: str,
    ) -> Built:
        m = to_ancf(mesh) if (polynomial and mesh.kind != "ancf") else mesh
        kernel = CableKernel(m.weights, m.scales, m.element_nodal(), props, _n_qp(m, n_qp), sf)
        return Built(kernel, m, m.q0)

    return build


def _rod(
    mesh: CableMesh, section: Any, props: CableProperties, rho: float, n_qp: int | None, sf: str
) -> Built:
    kernel = RodKernel(
        mesh.weights,
        mesh.scales,
        mesh.element_nodal(),
        props,
        rho * section.polar,
        _n_qp(mesh, n_qp),
        section.orientation,
        section.bending_rotary(rho),
        arc_fractions(mesh) if mesh.closed else None,
        sf,
    )
    n = mesh.n_nodes
    q0 = np.concatenate([mesh.nodes.reshape(n, 6), np.zeros((n, 1))], axis=1).ravel()
    return Built(kernel, mesh, q0)


#: The element families by name.
FAMILIES: dict[str, ElementFamily] = {
    "rancf": ElementFamily("rancf", (2, 3), True, False, True, _cable(False)),
    "ancf": ElementFamily("ancf", (2, 3), True, False, True, _cable(True)),
    "rod": ElementFamily("rod", (3,), True, True, False, _rod),
    "beam": ElementFamily("beam", (2,), False, False, False, _beam),
}


def _no_line(*args: Any) -> Built:
    raise InputError("mesh.element", "shell", "a surface [geometry] (a shell is no line body)")


#: The shell family (:mod:`rancf.bodies.shell_model`): Kirchhoff-Love RANCF shells, 12
#: coordinates ``[r, r_x, r_y, r_xy]`` a node; built from a surface, not by ``mesh.element``.
SHELL = ElementFamily("shell", (3,), False, False, False, _no_line, surface=True)


def framed(kind: str | None) -> bool:
    """Whether ``kind`` (an element kind, or ``"rigid"``, ``"mass"``, None) names an element
    family whose nodes carry a material frame (rods)."""
    fam = FAMILIES.get(kind or "")
    return fam is not None and fam.has_triads


def family(name: str) -> ElementFamily:
    """The family called ``name``; a clear error naming the known ones otherwise."""
    try:
        return FAMILIES[name]
    except (KeyError, TypeError):
        raise InputError("mesh.element", name, 'one of "rancf", "ancf", "beam", "rod"') from None
