"""Flexible bodies in a system, a :class:`~rancf.system.part.Part`.

A flexible body is its :class:`rancf.bodies.flexible.Model`: what it reads (its table's mesh,
section, material, supports and loads) is checked when the model is made, and its record for
the compiled core is the model's own (``_core.Model``, ``src/cpp/bodies/model.hpp``), which
the core's system holds by reference.  Its supports and its point loads with a time function
are Parts of their own (:mod:`rancf.system.parts.support`, :mod:`rancf.system.parts.load`),
which it lists; a point load without a time function is the model's own load vector.  A
closed body's seam is held by linear rows (:func:`rancf.bodies.closure.closure_terms`).  Its
outputs are its section values (:mod:`rancf.bodies.section_outputs`) and its supports'
reactions: no columns of its own.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rancf.bodies.flexible import Model
from rancf.system.part import NoOutputs
from rancf.system.parts.load import Load
from rancf.system.parts.support import Support
from rancf.system.places import Place

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["FlexibleBody"]


@dataclass(frozen=True, eq=False)
class FlexibleBody(NoOutputs):
    """The flexible body ``name`` of a system, its model ``model`` (module docstring)."""

    name: str
    model: Model

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
