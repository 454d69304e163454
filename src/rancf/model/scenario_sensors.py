"""Sensors of a scenario (``[[sensors]]``): the :class:`Sensor` record and its parser.

A sensor names one monitored quantity (of one or two nodes, or of the whole model: its angular
momentum or its mechanical energy); the solvers write its values as CSV columns and the
post-processing reads them back.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.model.scenario_checks import _REQ, _choice, _err, _place, _table, _vector

__all__ = ["Sensor", "SENSOR_KINDS", "parse_sensors"]


#: Sensor kinds (``twist``: rods only).
SENSOR_KINDS = ("distance", "position", "twist", "angular_momentum", "energy")


@dataclass(frozen=True)
class Sensor:
    """A monitored quantity of one or two nodes.

    ``distance`` between two nodes, ``position`` of one node, or (rods) ``twist`` of one node:
    its twist coordinate ``φ`` [rad], the rotation of the cross-section about the tangent
    relative to the reference director carried along with the tangent by smallest rotations
    (docs/rod-derivation.md; cumulative: it is not wrapped to ``(-π, π]``).  Of the whole model:
    ``angular_momentum`` about the point ``about`` (default the origin; :mod:`rancf.model.motion`;
    3 columns in 3D, the ``z`` component in 2D) and ``energy``, the total mechanical energy
    (kinetic + strain + gravitational) [J].
    """

    name: str
    kind: str
    nodes: tuple[int, ...]
    about: tuple[float, ...] | None = None

    def columns(self, dim: int) -> list[str]:
        """CSV column names of the sensor's scalars."""
        if self.kind in ("distance", "twist", "energy") or (
            self.kind == "angular_momentum" and dim == 2
        ):
            return [self.name]
        return [f"{self.name}_{c}" for c in "xyz"[:dim]]

    def evaluate(self, positions: NDArray, twists: NDArray | None = None) -> NDArray[np.float64]:
        """Values ``(n_t, n_columns)`` from node positions ``(n_t, n_nodes, dim)`` and, for
        ``twist``, the nodal twists ``(n_t, n_nodes)``."""
        if self.kind == "distance":
            d = positions[:, self.nodes[1]] - positions[:, self.nodes[0]]
            return np.linalg.norm(d, axis=1)[:, None]
        if self.kind == "twist":
            if twists is None:
                raise InputError(f"sensors.{self.name}", "twist", "a rod model (nodal twists)")
            return twists[:, self.nodes[0], None]
        return positions[:, self.nodes[0]]


def parse_sensors(path: str, raw: Any, element: str, dim: int = 3) -> tuple[Sensor, ...]:
    """Validate the ``[[sensors]]`` array of tables.

    Parameters
    ----------
    path : str
        The scenario's path (named in errors).
    raw : Any
        The array as read from the file (``[]`` when absent).
    element : str
        The mesh's element kind (``twist`` sensors need rods).
    dim : int
        The space dimension (size of ``about``).

    Returns
    -------
    tuple of Sensor
        The sensors in file order, with unique names.
    """
    if not isinstance(raw, list):
        raise _err(path, "sensors", "must be an array of tables [[sensors]]")
    sensors = []
    names: set[str] = set()
    for i, sn in enumerate(raw):
        t = _table(
            path,
            f"sensors[{i}]",
            sn,
            {"name": _REQ, "kind": _REQ, "between": None, "at": None, "about": None},
        )
        if not isinstance(t["name"], str) or not t["name"].isidentifier():
            raise _err(path, f"sensors[{i}].name", f"must be a simple name, got {t['name']!r}")
        if t["name"] in names or t["name"] == "t":
            raise _err(path, f"sensors[{i}].name", f"{t['name']!r} is used twice or reserved")
        names.add(t["name"])
        kd = _choice(path, f"sensors[{i}].kind", t["kind"], SENSOR_KINDS)
        if kd == "twist" and element != "rod":
            raise _err(
                path, f"sensors[{i}].kind", f"'twist' needs rod elements (mesh.element = \"rod\"), "
                f"not {element!r}",
            )  # fmt: skip
        if t["about"] is not None and kd != "angular_momentum":
            raise _err(path, f"sensors[{i}].about", "applies to angular_momentum sensors only")
        if kd in ("angular_momentum", "energy"):
            for k in ("at", "between"):
                if t[k] is not None:
                    raise _err(path, f"sensors[{i}].{k}", f"not for a {kd} sensor (whole model)")
            about = None
            if t["about"] is not None:
                about = tuple(_vector(path, f"sensors[{i}].about", t["about"], (dim,)))
            sensors.append(Sensor(t["name"], kd, (), about))
            continue
        if kd == "distance":
            b = t["between"]
            if t["at"] is not None or not isinstance(b, list) or len(b) != 2:
                raise _err(
                    path, f"sensors[{i}].between", "a distance sensor needs between = [A, B]"
                )
            nodes = tuple(_place(path, f"sensors[{i}].between[{j}]", x) for j, x in enumerate(b))
        else:
            if t["between"] is not None or t["at"] is None:
                raise _err(path, f"sensors[{i}].at", f"a {kd} sensor needs at = PLACE")
            nodes = (_place(path, f"sensors[{i}].at", t["at"]),)
        sensors.append(Sensor(t["name"], kd, nodes))
    return tuple(sensors)
