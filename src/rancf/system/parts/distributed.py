"""Distributed loads: a force per reference length on flexible bodies, a
:class:`~rancf.system.part.Part`.

The force ``force`` [N/m] (world axes) acts on the flexible body ``body`` (None: every flexible
body), times the time function ``time`` (None: constant), integrated over each element at the
Gauss points of its elastic forces with the fluid's loads (``src/cpp/fluid/fluid.hpp``;
docs/derivations/fluid.md section 3; :mod:`rancf.system.fluid` gathers the records per body).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from rancf.errors import InputError
from rancf.kernels.records import DistributedRecord, vec3
from rancf.system.part import NoOutputs

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["DistributedLoad"]


@dataclass(frozen=True)
class DistributedLoad(NoOutputs):
    """A force per reference length ``force`` [N/m] (world axes) on the flexible body ``body``
    (None: every flexible body), times the time function ``time`` (None: constant)."""

    force: tuple[float, ...]
    body: str | None = None
    time: Any = None

    @property
    def name(self) -> str:
        """Its body (``*``: every flexible body)."""
        return self.body or "*"

    def record(self, system: Any, rows: RecordRows, index: int = 0) -> DistributedRecord:
        """The core's record: the force (3 components) and its time function, registered in
        ``rows``; ``index``: its position among the system's distributed loads (errors name
        it)."""
        dim, flex_names = system.dim, list(system.names[: len(system.flex)])
        if len(self.force) != dim:
            raise InputError(
                f"loads.distributed[{index}].force", list(self.force), f"{dim} components"
            )
        if self.body is not None and self.body not in flex_names:
            raise InputError(
                f"loads.distributed[{index}].body",
                self.body,
                f"a flexible body (one of {flex_names})",
            )
        return DistributedRecord(vec3(list(self.force) + [0.0] * (3 - dim)), rows.tf(self.time))
