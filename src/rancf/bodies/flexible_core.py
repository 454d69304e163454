"""The assembled model as the compiled core's named structure (:class:`rancf.kernels._core.Model`).

:func:`core_model` gathers what a :class:`~rancf.bodies.flexible.Model` has assembled (kernel data,
stiffness, support rotations, loads, mass) into the one structure on which the core evaluates
forces, tangents and energies.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np

from rancf.bodies.layout import BodyLayout
from rancf.kernels import _core
from rancf.kernels.beam import BeamKernel
from rancf.kernels.cable import CableKernel
from rancf.kernels.rod import RodKernel

__all__ = ["axial_law_record", "core_model", "section_stiffness"]


class AssembledBody(BodyLayout, Protocol):
    """What the core's structure is made of (:class:`rancf.bodies.flexible.Model`)."""

    @property
    def closed(self) -> bool: ...

    @property
    def kernel(self) -> CableKernel | BeamKernel | RodKernel: ...

    @property
    def section(self) -> Any: ...

    @property
    def material(self) -> Any: ...

    @property
    def props(self) -> Any: ...

    @property
    def reduction(self) -> Any: ...

    @property
    def point_loads(self) -> Sequence[Any]: ...

    @property
    def strain_rate_damping(self) -> Any: ...

    @property
    def rotations(self) -> list[tuple[int, np.ndarray]]: ...

    @property
    def fixed(self) -> np.ndarray: ...

    @property
    def f_gravity(self) -> np.ndarray: ...

    @property
    def mass_band(self) -> np.ndarray: ...

    @property
    def y0(self) -> np.ndarray: ...

    def check_node(self, node: int, key: str) -> int: ...


def section_stiffness(model: AssembledBody) -> _core.Stiffness:
    """``EA``, ``EI`` and, for rods, ``GJ``, ``EI2 = E I_y`` (about ``m1``) and ``EI3 = E I_z``;
    the Kelvin-Voigt coefficients of :attr:`Model.strain_rate_damping
    <rancf.bodies.flexible.Model.strain_rate_damping>`."""
    sec, mat = model.section, model.material
    kv = model.strain_rate_damping
    rates = {
        "damping_axial": kv.axial,
        "damping_bending": kv.bending,
        "damping_torsion": kv.torsion,
    }
    if not model.family.has_triads:
        law = model.material.axial_law  # its table is in the engineering strain
        engineering = model.material.axial_strain == "engineering" or law is not None
        return _core.Stiffness(
            ea=model.props.ea, ei=model.props.ei, engineering=engineering, **rates
        )
    e_mod = mat.youngs_modulus
    return _core.Stiffness(
        ea=model.props.ea,
        ei=model.props.ei,
        gj=mat.shear * sec.torsion,
        ei2=e_mod * sec.inertia,
        ei3=e_mod * sec.inertia_2,
        **rates,
    )


def core_model(model: AssembledBody) -> _core.Model:
    """The model as the compiled core's named structure (arrays shared, not copied).

    Parameters
    ----------
    model : Model
        An assembled model: kernel, section and material, supports, loads and mass in place.

    Returns
    -------
    rancf.kernels._core.Model
        The structure kept as :attr:`Model.core <rancf.bodies.flexible.Model.core>`.
    """

    fam, k = model.family, model.kernel
    as_cable, as_beam, as_rod = fam.cable_kernel(k), fam.beam_kernel(k), fam.rod_kernel(k)
    cable = as_cable.core_data() if as_cable is not None else _empty_cable()
    beam = as_beam.core_data() if as_beam is not None else _empty_beam()
    rod = as_rod.core_data() if as_rod is not None else _empty_rod()
    stiffness = section_stiffness(model)
    rot_of_node = np.full((model.n_nodes, 2), -1, dtype=np.int64)
    rot = np.zeros((max(len(model.rotations), 1), model.dim, model.dim))
    for i, (off, basis) in enumerate(model.rotations):  # block 0: position, 1: gradient
        rot_of_node[off // model.dpn, (off % model.dpn) // model.dim] = i
        rot[i] = basis
    base, f0, freq = _point_forces(model)
    moments = [p for p in model.point_loads if p.moment is not None and p.time is None]
    return _core.Model(
        kind=fam.core_kind,
        dim=model.dim,
        dpn=model.dpn,
        n_el=model.n_el,
        stiffness=stiffness,
        cable=cable,
        beam=beam,
        rod=rod,
        supports=_core.Supports(
            fixed=model.fixed.astype(np.uint8), rot_of_node=rot_of_node, rot=rot
        ),
        loads=_core.Loads(
            f_gravity=model.f_gravity,
            base=base,
            f0=f0,
            freq=freq,
            moment_node=np.array(
                [model.check_node(p.node, "loads.point.at") for p in moments], dtype=np.int64
            ),
            moment=np.array([p.moment for p in moments], dtype=float).reshape(-1, 3),
            moment_freq=np.array([p.frequency_hz or 0.0 for p in moments], dtype=float),
        ),
        mass_band=np.ascontiguousarray(model.mass_band),
        y_ref=np.ascontiguousarray(model.y0),
        rotary=as_rod.core_inertia() if as_rod is not None else _core.SectionInertia(),
        closed=model.closed,
        reduction=_reduction(model),
        axial_law=axial_law_record(model),
    )


def axial_law_record(model: AssembledBody) -> Any:
    """The core's record of the body's axial law (:mod:`rancf.bodies.axial_law`), or None."""
    law = model.material.axial_law
    return None if law is None else law.core


def no_reduction() -> _core.Reduction:
    """The empty reduction record: a body whose coordinates are its nodal ones (C¹, shells)."""
    zi, z = np.zeros(0, dtype=np.int64), np.zeros(0)
    return _core.Reduction(
        n_y=0,
        ku=0,
        width=0,
        node_width=0,
        el_start=zi,
        el_map=z,
        node_start=zi,
        node_map=z,
        twist=zi,
    )


def _reduction(model: AssembledBody) -> _core.Reduction:
    """A C² model's element and node maps (:mod:`rancf.mesh.continuity`); none for C¹."""
    red = model.reduction
    if red is None:
        return no_reduction()
    return _core.Reduction(
        n_y=red.n_y,
        ku=red.ku,
        width=red.width,
        node_width=red.node_width,
        el_start=red.el_start,
        el_map=red.el_map,
        node_start=red.node_start,
        node_map=red.node_map,
        twist=red.twist,
    )


def _point_forces(model: AssembledBody) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Point forces as ``(base index, F0, frequency)`` arrays (frequency 0: constant)."""
    # loads times a time function act through the system (rancf.system), not the chain
    forces = [p for p in model.point_loads if p.force is not None and p.time is None]
    base = np.array(
        [model.check_node(p.node, "loads.point.at") * model.dpn for p in forces], dtype=np.int64
    )
    f0 = np.array([p.force for p in forces], dtype=float).reshape(-1, model.dim)
    freq = np.array([p.frequency_hz or 0.0 for p in forces], dtype=float)
    return base, f0, freq


def _empty_cable() -> _core.CableData:
    z = np.zeros(0)
    return _core.CableData(n1=z, n2=z, gw=z, s0=z, k0=z, j0=z, qr=z)


def _empty_beam() -> _core.BeamData:
    z = np.zeros(0)
    return _core.BeamData(l0=z, d0=z)


def _empty_rod() -> _core.RodData:
    z = np.zeros(0)
    return _core.RodData(n1=z, n2=z, xi=z, gw=z, j0=z, kref=z, tref=np.zeros(0), m1ref=np.zeros(0))
