"""Supports of flexible bodies in a system, a :class:`~rancf.system.part.Part`.

A flexible body's supports are its model's own (held coordinates, :mod:`rancf.bodies.properties`
``Support``).  In a system, a support with a ``motion`` makes its held position follow the time
function: the core's prescribed records, one per held position coordinate, each the
coordinate's installed value plus that component of the motion (``src/cpp/system/system.hpp``).
A support without a motion needs no record.  Its reaction is the held rows of the balance
residual, read with every support's by the outputs (:mod:`rancf.bodies.reactions`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.kernels.records import PrescribedRecord

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["Support", "supports_of"]


@dataclass(frozen=True)
class Support:
    """The support number ``index`` of the flexible body ``body``, at its node ``node`` (module
    docstring)."""

    body: str
    index: int
    node: int
    #: Its place as the user wrote it (its output columns' label); None: ``BODY:AT``.
    label: int | str | None = None

    @property
    def name(self) -> str:
        """``BODY:NODE``: its body and node."""
        return f"{self.body}:{self.node}"

    def held(self, system: Any) -> Any:
        """The model's support (:class:`rancf.bodies.properties.Support`)."""
        return system.bodies[self.body].supports[self.index]

    def record(self, system: Any, rows: RecordRows) -> tuple[PrescribedRecord, ...]:
        """The core's prescribed records of a moving support (its motion registered in
        ``rows``); none for a support that stays."""
        b, sup = system.bodies[self.body], self.held(system)
        if sup.motion is None:
            return ()
        if sup.kind == "roller":
            raise InputError("supports.motion", "roller", "a pin or clamp (moving supports)")
        if sup.motion.size != system.dim:
            raise InputError("supports.motion", sup.motion.size, f"{system.dim} components")
        k = rows.tf(sup.motion)
        base = b.node_base(b.check_node(sup.node, "supports.at"))
        start = system.offsets[self.body] + base
        return tuple(
            PrescribedRecord(start + i, k, i, float(b.y_installed[base + i]))
            for i in range(system.dim)
        )

    def sensors(self) -> Sequence[str]:
        """None of its own: its reaction is among the outputs' support reactions (module
        docstring)."""
        return ()

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """None (:meth:`sensors`)."""
        return {}


def supports_of(system: Any) -> list[Support]:
    """The supports of the system's flexible bodies, body by body in file order."""
    return list(system.supports)
