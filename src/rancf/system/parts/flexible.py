"""Flexible bodies in a system, a :class:`~rancf.system.part.Part`.

A flexible body is its :class:`rancf.bodies.flexible.Model`: what it reads (its table's mesh,
section, material, supports and loads) is checked when the model is made, and its record for
the compiled core is the model's own (``_core.Model``, ``src/cpp/bodies/model.hpp``), which
the core's system holds by reference.  Its supports and its point loads with a time function
are Parts of their own (:mod:`rancf.system.parts.support`, :mod:`rancf.system.parts.load`),
which it lists; a point load without a time function is the model's own load vector.  A
closed body's seam is held by linear rows (:func:`rancf.bodies.closure.closure_terms`).  Its
outputs are its section values (:mod:`rancf.bodies.section_outputs`) and its supports'
reactions: no columns of its own.  Its sensor kinds: ``twist`` at a rod's node (its twist
coordinate ``φ`` [rad]) and ``axial_force`` (or ``tension``) at a node (the section value ``N``);
with ``at_point``: at the material point nearest to a fixed point (:mod:`rancf.system.at_point`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

from rancf.bodies.flexible import Model
from rancf.errors import InputError
from rancf.system.at_point import at_point_reader
from rancf.system.part import NoOutputs
from rancf.system.parts.load import Load
from rancf.system.parts.support import Support
from rancf.system.places import Place
from rancf.system.readers import Reader, SensorBuilder, SensorHost, sensor_places

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["FlexibleBody"]


def twist_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``twist`` sensor: the twist coordinate ``φ`` [rad] of a rod's node."""
    if getattr(sen, "point", None) is not None:
        return at_point_reader(host.out, sen)
    s = host.system
    p = host.place(sen, sensor_places(sen)[0])
    body = p.body_name()
    b = s.bodies[body]
    if not (isinstance(b, Model) and b.family.has_triads):
        raise InputError(f"sensors.{sen.name}.at", str(p), "a node of a rod")
    i = s.offsets[body] + p.node() * b.dpn + 6
    return lambda blk: blk[1][:, i]


def axial_force_reader(host: SensorHost, sen: Any) -> Reader:
    """An ``axial_force`` (or ``tension``: a line's tension is its axial force) sensor: the
    section value ``N`` at a node (:mod:`rancf.bodies.section_outputs`; of cables and rods from
    the nodal forces, :mod:`rancf.bodies.nodal_forces`)."""
    if getattr(sen, "point", None) is not None:
        return at_point_reader(host.out, sen)
    p = host.place(sen, sensor_places(sen)[0])
    name = p.body_name()
    if not isinstance(host.system.bodies[name], Model):
        raise InputError(f"sensors.{sen.name}.at", str(p), "a node of a flexible body")
    out = host.out
    sp = out.samplers[name]
    point = min(p.node() * sp.per_element, sp.n_points - 1)
    return lambda blk: out.body_along(blk[3]["s"], name)[:, point, 1]


@dataclass(frozen=True, eq=False)
class FlexibleBody(NoOutputs):
    """The flexible body ``name`` of a system, its model ``model`` (module docstring)."""

    name: str
    model: Model
    #: Its sensor kinds (module docstring).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {
        "twist": twist_reader,
        "axial_force": axial_force_reader,
        "tension": axial_force_reader,
    }

    def record(self, system: Any = None, rows: RecordRows | None = None) -> Any:
        """The core's model of the body (``rancf.kernels._core.Model``)."""
        return self.model.core

    def supports(self, labels: Any = None) -> list[Support]:
        """Its supports, in the model's order; ``labels``: their ``at`` as the user wrote it
        (default ``BODY:AT``, :func:`rancf.system.output_columns.support_labels`)."""
        return [
            Support(self.name, i, int(sup.node), None if labels is None else labels[i])
            for i, sup in enumerate(self.model.supports)
        ]

    def loads(self) -> list[Load]:
        """Its point forces (and rods' moments) times a time function, as point loads."""
        b = self.model
        return [
            Load(
                Place(self.name, b.check_node(p.node, "loads.point.at")), p.force, p.moment, p.time
            )
            for p in b.point_loads
            if p.time is not None
        ]
