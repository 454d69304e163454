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

    # read-only members: the scenario is immutable once validated
    @property
    def path(self) -> str: ...

    @property
    def dim(self) -> int: ...

    @property
    def data(self) -> dict[str, Any]: ...

    @property
    def geometry(self) -> Any: ...

    @property
    def mesh(self) -> Any: ...

    @property
    def section(self) -> Any: ...

    @property
    def material(self) -> Any: ...

    @property
    def supports(self) -> Sequence[Any]: ...

    @property
    def loads(self) -> Any: ...

    @property
    def fluid(self) -> Any: ...

    @property
    def hydro(self) -> Any: ...

    @property
    def damping(self) -> Any: ...

    @property
    def solver(self) -> Any: ...

    @property
    def initial_velocity(self) -> Sequence[Any]: ...

    @property
    def initial_motion(self) -> Any: ...

    @property
    def bodies(self) -> Sequence[Any]: ...

    @property
    def body_tables(self) -> tuple[tuple[str, Any], ...]: ...

    @property
    def joints(self) -> Sequence[Any]: ...

    @property
    def springs(self) -> Sequence[Any]: ...

    @property
    def obstacles(self) -> Sequence[Any]: ...

    @property
    def winches(self) -> Sequence[Any]: ...

    @property
    def contacts(self) -> Any: ...

    @property
    def contact_points(self) -> int: ...

    @property
    def body_contacts(self) -> Any: ...

    @property
    def body_friction(self) -> float: ...

    @property
    def sensor_tables(self) -> Sequence[Any]: ...

    @property
    def sensors(self) -> tuple[Sensor, ...]: ...

    @property
    def support_labels(self) -> list[int | str]: ...

    def __getitem__(self, key: str) -> Any: ...

    def place(self, value: int | str) -> ResolvedPlace: ...

    def body_length(self, name: str) -> float | None: ...

    def support_place(self, i: int) -> ResolvedPlace: ...
