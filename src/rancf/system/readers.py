"""What a sensor reads: a function of a block of output rows, returning its columns."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from numpy.typing import NDArray

__all__ = ["Block", "Reader", "NamedReader", "SensorBuilder", "SensorHost", "sensor_places"]

#: Rows of outputs: ``(t, q, v, derived, energy)``.
Block = tuple[NDArray, NDArray, NDArray, dict[str, NDArray], NDArray]
#: A sensor's columns ``(k, n_columns)`` of a block of ``k`` rows.
Reader = Callable[[Block], NDArray]


@dataclass(frozen=True)
class NamedReader:
    """A reader that names its own columns (other sensors' columns are named by their table)."""

    read: Reader
    columns: list[str]

    def __call__(self, blk: Block) -> NDArray:
        return self.read(blk)


class SensorHost(Protocol):
    r"""What a sensor kind's builder reads (:class:`rancf.system.sensors.SensorReader`): the
    run's derived ``out``\ puts, its ``system``, and a sensor's places."""

    out: Any
    system: Any

    def place(self, sen: Any, spec: Any) -> Any:
        """The place ``spec`` of sensor ``sen`` on a body (one line naming the sensor if not)."""
        ...


#: A sensor kind's builder: ``build(host, sensor) -> Reader`` (a Part's ``sensor_kinds``).
SensorBuilder = Callable[[Any, Any], Reader]


def sensor_places(sen: Any) -> tuple[Any, ...]:
    """The places a sensor names (``places``, or ``nodes``)."""
    return tuple(getattr(sen, "places", ()) or getattr(sen, "nodes", ()))
