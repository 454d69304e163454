"""The place and time-function records of a system as they are made, numbered by position."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from rancf.bodies.time_function import TimeFunction
from rancf.bodies.time_record import core_record
from rancf.errors import InputError
from rancf.kernels.records import PlaceRecord, TimeFunctionRecord
from rancf.system.places import Place

__all__ = ["RecordRows"]


class RecordRows:
    """The place and time function records as they are made (numbered by position); a place
    made twice (the same key) is one record."""

    def __init__(self, horizon: float | None) -> None:
        self.places: list[PlaceRecord] = []
        self.tfs: list[TimeFunctionRecord] = []
        self.horizon = horizon
        self._known: dict[Place | PlaceRecord, int] = {}

    def place(self, key: Place | PlaceRecord, make: Callable[[], PlaceRecord]) -> int:
        if key not in self._known:
            self.places.append(make())
            self._known[key] = len(self.places) - 1
        return self._known[key]

    def tf(self, f: TimeFunction | None) -> int:
        """The index of the core's record of ``f`` (a callable sampled on the horizon); -1 for
        None."""
        if f is None:
            return -1
        if f.kind == "callable":
            if self.horizon is None or not self.horizon > 0:
                raise InputError(
                    "horizon",
                    self.horizon,
                    "the run's end time t_end [s] > 0 (a "
                    "Python time function is sampled on [0, t_end])",
                )
            f = f.sampled(float(self.horizon))
        self.tfs.append(core_record(f))
        return len(self.tfs) - 1

    def fields(self, **parts: Any) -> dict[str, Any]:
        """The fields of the model record (:class:`rancf.kernels.records.SystemModel`, by
        name): the places and time functions so far, and ``parts`` (sequences as tuples)."""
        out = {k: tuple(v) if isinstance(v, list | tuple) else v for k, v in parts.items()}
        return {"places": tuple(self.places), "time_functions": tuple(self.tfs), **out}
