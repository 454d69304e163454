"""The interface of a system's physical items (a spring, a joint, ...): a :class:`Part`.

A Part is one item of a :class:`rancf.system.System` in a module of its own
(:mod:`rancf.system.parts`): a flexible body, rigid body or point mass, a support, spring,
point load, distributed load, the fluid, a joint, winch, obstacle or pair in contact.  It knows
its name, what it reads (its fields, checked when it makes its record), the record it gives the
compiled core (:mod:`rancf.kernels.records`; the places and time functions it needs registered
in ``rows``), its output columns and their values at a state.  The System gathers its parts'
records into one model record and builds the core from it once (:attr:`System.parts`).

Sensors.  A part's class offers the sensor kinds it can give (:attr:`Part.sensor_kinds`: kind
name -> builder of the sensor's reader, :mod:`rancf.system.readers`); the sensors of a run find
every kind among the part classes of :mod:`rancf.system.parts.catalog`, so a new part brings its
sensors with it.

Output columns.  A part's :meth:`Part.sensors` are the one place that names its columns among
a run's reactions (``reactions.csv``): :class:`rancf.system.outputs.SystemOutputs` writes the
columns of every part in the order of :attr:`System.parts`, and a ``reaction`` sensor of a
joint or support takes its columns and their suffixes from there.  :meth:`Part.reactions`
gives their values at a static state; the outputs compute the same values for blocks of rows
in the core (a test holds the two equal).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, ClassVar, Protocol

from numpy.typing import NDArray

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["NoOutputs", "Part", "PartHost"]


class PartHost(Protocol):
    """What a part uses of the system it is built into (:class:`rancf.system.System`)."""

    @property
    def dim(self) -> int: ...

    @property
    def size(self) -> float: ...

    def resolve(self, spec: Any) -> Any: ...

    def reference_position(self, p: Any) -> NDArray: ...

    def place_pair(
        self, between: Sequence, rows: RecordRows, motion: int = -1, rotation: int = -1
    ) -> tuple[int, int]: ...

    def place_state(self, spec: Any, y: NDArray, t: float = 0.0) -> tuple[NDArray, NDArray]: ...


class Part(Protocol):
    """One physical item of a system (module docstring)."""

    #: The sensor kinds it offers: name -> ``build(host, sensor) -> Reader``
    #: (:data:`rancf.system.readers.SensorBuilder`).
    sensor_kinds: ClassVar[Mapping[str, Any]]

    @property
    def name(self) -> str:
        """Its name (its output columns start with it)."""
        ...

    def record(self, system: PartHost, rows: RecordRows) -> Any:
        """Its record for the core, its fields checked (one line naming the key on bad input),
        its places and time functions registered in ``rows``."""
        ...

    def sensors(self, system: Any) -> Sequence[str]:
        """Its output columns in ``system`` (module docstring), in order."""
        ...

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """Its output columns' values at the static state of coordinates ``y`` and multipliers
        ``lam``, the loads at the factor ``t`` (a load path's parameter, at most 1)."""
        ...


class NoOutputs:
    """The outputs of a part with no columns of its own: a load's force is an input, a body's
    outputs are its section values and sensors, and a contact pair's forces are in its
    obstacle's columns."""

    sensor_kinds: ClassVar[Mapping[str, Any]] = {}

    def sensors(self, system: Any) -> Sequence[str]:
        """None (class docstring)."""
        return ()

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """None (class docstring)."""
        return {}
