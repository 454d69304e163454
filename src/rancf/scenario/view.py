"""What the builders and the checks across tables read of a scenario.

:class:`~rancf.scenario.scenario.Scenario` calls them (its validation runs the checks, its
``build_model`` and ``build_system`` the builders), so they see it through this protocol
rather than importing the class that imports them.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

from rancf.scenario.places import ResolvedPlace
from rancf.scenario.sensors import Sensor

__all__ = ["ScenarioView"]


class ScenarioView(Protocol):
    """The tables of a scenario (:class:`~rancf.scenario.scenario.Scenario`), as read by
    :mod:`~rancf.scenario.checks`, :mod:`~rancf.scenario.build` and
    :mod:`~rancf.scenario.system_build`."""

    path: str
    dim: int
    data: dict[str, Any]
    geometry: Any
    mesh: Any
    section: Any
    material: Any
    supports: Sequence[Any]
    loads: Any
    fluid: Any
    hydro: Any
    damping: Any
    solver: Any
    initial_velocity: Sequence[Any]
    initial_motion: Any
    bodies: Sequence[Any]
    joints: Sequence[Any]
    springs: Sequence[Any]
    obstacles: Sequence[Any]
    contacts: Any
    contact_points: int
    body_contacts: Any
    body_friction: float
    sensor_tables: Sequence[Any]
    sensors: tuple[Sensor, ...]
    support_labels: list[int | str]

    def __getitem__(self, key: str) -> Any: ...

    def place(self, value: int | str) -> ResolvedPlace: ...

    def support_place(self, i: int) -> ResolvedPlace: ...
