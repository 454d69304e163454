"""Winches: a cable paid out of (or reeled onto) a drum at one end of a flexible body, a
:class:`~rancf.system.part.Part`.

Its length law ``L(t)`` and what follows from it (the start for statics, the ``winch`` sensor,
a driven drum's coordinate) are in :mod:`rancf.system.winches`, which builds its ``winch``
sensor; here: what it reads and its
record for the compiled core (``src/cpp/system/winch.hpp``): its body, the index of its
``L(t)``, the length the body's arrays hold, the convective matrices of
:mod:`rancf.bodies.winch_inertia` and a driven drum's record (:mod:`rancf.system.drums`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.reactions import has_moment
from rancf.bodies.time_function import TimeFunction
from rancf.bodies.winch_inertia import convective_matrices
from rancf.errors import InputError
from rancf.kernels.records import WinchRecord
from rancf.system.drums import drum_record, drum_torque
from rancf.system.readers import Reader, SensorBuilder, SensorHost

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["Winch"]


def winch_sensor(host: SensorHost, sen: Any) -> Reader:
    """The columns of a ``winch`` sensor (``NAME_length``, ``NAME_speed``, ``NAME_tension``):
    ``L(t)``, ``L'(t)`` and the magnitude of the force of the winch's support on the line
    (:class:`rancf.system.outputs.SystemOutputs`' reaction columns)."""
    outputs, s = host.out, host.system
    found = [w for w in getattr(s, "winches", ()) if w.name == sen.winch]
    if not found:
        names = ", ".join(w.name for w in getattr(s, "winches", ())) or "none"
        raise InputError(f"sensors.{sen.name}.winch", sen.winch, f"a winch: {names}")
    w = found[0]
    name, node = w.node(s)
    f = s.winch_lengths[w.name]
    start, d, cols = 0, s.dim, slice(0, 0)
    for body_name, b in outputs.flex:
        for sup in b.supports:
            width = d + (0 if not has_moment(b, sup.kind) else (1 if d == 2 else 3))
            if body_name == name and b.check_node(sup.node, "supports.at") == node:
                cols = slice(start, start + d)
            start += width

    drum = getattr(s, "drums", {}).get(w.name)

    def read(blk: Any) -> np.ndarray:
        t = blk[0]
        if drum is not None:  # a driven drum: L and L' are the state's (rows of y, v)
            length, rate = blk[1][:, drum], blk[2][:, drum]
        else:
            length = np.array([float(np.ravel(f.value(x))[0]) for x in t])
            rate = np.array([float(np.ravel(f.rate(x))[0]) for x in t])
        tension = np.linalg.norm(blk[3]["r"][:, cols], axis=1)
        return np.column_stack([length, rate, tension])

    return read


@dataclass(frozen=True)
class Winch:
    """A winch (:mod:`rancf.system.winches`).

    Parameters
    ----------
    name : str
    at : str
        ``"BODY:start"`` or ``"BODY:end"``: the end of a cable body at the drum.
    length : TimeFunction or float, optional
        The unstretched length outside the winch [m] as a function of time.
    speed : TimeFunction or float, optional
        The pay-out rate [m/s] (reeling in: negative); one of ``length``, ``speed`` and
        ``torque``.
    torque : TimeFunction or float, optional
        A driven drum: the torque on it [N m], positive reeling in; with ``radius`` [m] and
        ``inertia`` [kg m²] (the drum's, with the rope on it at ``t = 0``): the length follows
        from the drum's balance (:mod:`rancf.system.drums`).
    """

    name: str
    at: str
    length: TimeFunction | float | None = None
    speed: TimeFunction | float | None = None
    torque: TimeFunction | float | None = None
    radius: float | None = None
    inertia: float | None = None
    #: Its sensor kind: ``winch`` (module docstring).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {"winch": winch_sensor}

    @property
    def driven(self) -> bool:
        """Whether the winch is a driven drum (its length a coordinate of the system)."""
        return self.torque is not None

    def body_and_end(self) -> tuple[str, Literal["start", "end"]]:
        """The body's name and the end at the drum."""
        body, _, end = self.at.rpartition(":")
        if body and end == "start":
            return body, "start"
        if body and end == "end":
            return body, "end"
        raise InputError(f"winches.{self.name}.at", self.at, '"BODY:start" or "BODY:end"')

    def node(self, system: Any) -> tuple[str, int]:
        """The body and the node at the drum."""
        name, end = self.body_and_end()
        return name, 0 if end == "start" else self.body(system).n_nodes - 1

    def body(self, system: Any) -> Model:
        """Its body: a flexible body whose end at the drum is held by a support."""
        name, end = self.body_and_end()
        body = system.bodies.get(name)
        if not isinstance(body, Model):
            raise InputError(
                f"winches.{self.name}.at", self.at, "the end of a flexible (cable) body"
            )
        node = 0 if end == "start" else body.n_nodes - 1
        if not any(body.check_node(s.node, "supports.at") == node for s in body.supports):
            raise InputError(
                f"winches.{self.name}.at",
                self.at,
                "an end held by a support (pin or clamp) where the line leaves the drum",
            )
        return body

    def record(self, system: Any, rows: RecordRows) -> WinchRecord:
        """The core's record (module docstring): its ``L(t)``, ``system.winch_lengths``
        (:func:`rancf.system.winches.winch_functions`), and a driven drum's torque registered
        in ``rows``; the length the body's arrays hold is ``L(0)`` (equal to the body's to
        ``LENGTH_RTOL``, so the body is exactly at its length at the start)."""
        f = system.winch_lengths[self.name]
        length = rows.tf(f)
        torque = drum_torque(self, rows.tf) if self.driven else -1
        name, end = self.body_and_end()
        body = self.body(system)
        if self.driven and body.material.axial_law is not None:
            raise InputError(
                f"winches.{self.name}.torque",
                "a driven drum",
                f"a length or speed for a line with an axial_law ({name}): a drum's balance "
                "takes the energy of a linear EA (docs/derivations/variable-length.md §3.3)",
            )
        c1, c2, d2 = convective_matrices(body, end)
        node = 0 if end == "start" else body.n_nodes - 1
        length_set = float(np.ravel(f.value(0.0))[0])
        return WinchRecord(
            body=system.names.index(name),  # flexible bodies come first
            length=length,
            length_set=length_set,
            c1=np.ascontiguousarray(c1, dtype=float),
            c2=np.ascontiguousarray(c2, dtype=float),
            d2=np.ascontiguousarray(d2, dtype=float),
            drum=None if torque < 0 else drum_record(self, body, node, torque, length_set),
        )

    def sensors(self, system: Any) -> Sequence[str]:
        """None among the outputs' columns: the ``winch`` sensor reads its length, rate and
        the line's pull (:func:`winch_sensor`)."""
        return ()

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """None (:meth:`sensors`)."""
        return {}
