"""Sensors (``[[sensors]]``): the :class:`SensorTable` of a file and the :class:`Sensor` record
the solvers and post-processing use.

A sensor names one monitored quantity.  Kinds and their keys:

* ``position`` (``at``), ``distance`` (``between``), ``twist`` (``at``, rods: the nodal twist
  angle [rad], cumulative);
* of the whole model: ``angular_momentum`` (about ``about``, default the origin; 3 columns in 3D,
  the ``z`` component in 2D) and ``energy`` (kinetic + strain + gravitational [J]);
* of systems: ``reaction`` (the force of the joint ``joint = NAME``, or of the
  support at ``at``) [N], ``axial_force`` or ``tension`` (the axial force at a place of a
  flexible body; in a fluid the effective tension) [N], ``angle`` (of the
  rigid body ``body``: [rad] in 2D, the rotation vector in 3D), ``center_of_mass`` [m] and
  ``momentum`` (linear momentum [kg m/s]) of the body ``body`` or, without it, of the whole
  system;
* of contact: ``contact_force`` (the force of the obstacle ``obstacle = NAME`` on
  the bodies, normal and friction parts together) [N];
* ``touchdown`` (``obstacle = NAME``, a plane; ``body``, default the only flexible body): where
  the line, walked from its start, leaves the plane (:mod:`rancf.system.touchdown`) [m];
* of a fluid: ``fluid_force`` (buoyancy, drag and the waves' Froude-Krylov force on the body
  ``body``, default every flexible body; the added-mass force, which needs the accelerations,
  is left out) [N]; ``wave_elevation`` (``at_point``: the free surface's height above that
  point's horizontal position, the still surface plus the waves' elevation) [m];
* of a winch (``winch = NAME``): ``winch``, its line's unstretched length outside the drum
  ``NAME_length`` [m], pay-out rate ``NAME_speed`` [m/s] and tension ``NAME_tension`` [N] (the
  force of the winch's support on the line).

``position``, ``twist``, ``axial_force`` and ``tension`` take ``at_point = [x, y(, z)]`` instead
of ``at``: they read the material point nearest to that fixed point in space, found anew at every
output (a belt's span, a line running through a guide: :mod:`rancf.system.at_point`).

Column names: ``NAME`` for one number, ``NAME_x``, ``NAME_y`` (, ``NAME_z``) for vectors.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import NDArray
from pydantic import Field, model_validator

from rancf.errors import InputError
from rancf.scenario.base import Name, Table, Vector23, fail
from rancf.scenario.place_types import PlacePair, PlaceValue

__all__ = ["Sensor", "SensorTable", "SENSOR_KINDS", "SYSTEM_SENSOR_KINDS", "AT_POINT_KINDS"]

#: Sensor kinds.
SensorKind = Literal[
    "distance",
    "position",
    "twist",
    "angular_momentum",
    "energy",
    "reaction",
    "axial_force",
    "tension",
    "angle",
    "center_of_mass",
    "momentum",
    "contact_force",
    "fluid_force",
    "wave_elevation",
    "touchdown",
    "winch",
]
SENSOR_KINDS: tuple[str, ...] = get_args(SensorKind)
#: The kinds the system solver computes (not from node positions).
SYSTEM_SENSOR_KINDS = (
    "reaction",
    "axial_force",
    "tension",
    "angle",
    "center_of_mass",
    "momentum",
    "contact_force",
    "fluid_force",
    "wave_elevation",
    "touchdown",
    "winch",
)
_SCALAR = ("distance", "twist", "energy", "axial_force", "tension", "wave_elevation")
#: The kinds that take ``at_point`` (a material point found anew at every output).
AT_POINT_KINDS = ("position", "twist", "axial_force", "tension")


@dataclass(frozen=True)
class Sensor:
    """A monitored quantity (module docstring) as the solvers and result files use it.

    ``nodes``: the node indices of ``at``/``between`` in a one-body model; ``places``: the places
    as written (systems); ``about``: the point of an angular momentum; ``joint``, ``body``: what
    a reaction, angle, centre of mass or momentum is of (with ``point``: the flexible body
    searched); ``point``: ``at_point``, the fixed point whose nearest material point is read.
    """

    name: str
    kind: str
    nodes: tuple[int, ...] = ()
    about: tuple[float, ...] | None = None
    places: tuple[int | str, ...] = ()
    joint: str | None = None
    body: str | None = None
    obstacle: str | None = None
    point: tuple[float, ...] | None = None
    winch: str | None = None

    def columns(self, dim: int) -> list[str]:
        """CSV column names of the sensor's scalars."""
        if self.kind == "winch":
            return [f"{self.name}_{c}" for c in ("length", "speed", "tension")]
        one = self.kind in _SCALAR or (self.kind in ("angular_momentum", "angle") and dim == 2)
        return [self.name] if one else [f"{self.name}_{c}" for c in "xyz"[:dim]]

    def evaluate(self, positions: NDArray, twists: NDArray | None = None) -> NDArray[np.float64]:
        """Values ``(n_t, n_columns)`` from node positions ``(n_t, n_nodes, dim)`` and, for
        ``twist``, the nodal twists ``(n_t, n_nodes)``."""
        if self.kind in SYSTEM_SENSOR_KINDS:
            raise InputError(f"sensors.{self.name}", self.kind, "computed by the system solver")
        if self.kind == "distance":
            d = positions[:, self.nodes[1]] - positions[:, self.nodes[0]]
            return np.linalg.norm(d, axis=1)[:, None]
        if self.kind == "twist":
            if twists is None:
                raise InputError(f"sensors.{self.name}", "twist", "a rod model (nodal twists)")
            return twists[:, self.nodes[0], None]
        return positions[:, self.nodes[0]]


class SensorTable(Table):
    """One ``[[sensors]]`` table."""

    name: Name = Field(description="column name (letters, digits, _), unique, not t")
    kind: SensorKind = Field(
        description="what is measured (the sensor kinds: docs/guide/outputs.md)"
    )
    between: PlacePair | None = Field(None, description="distance: the two places")
    at: PlaceValue | None = Field(
        None,
        description="position, twist (rods), axial_force, tension: the place; reaction: a "
        "support's place",
    )
    about: Vector23 | None = Field(
        None, description="angular_momentum: the point [m] (default the origin)"
    )
    at_point: Vector23 | None = Field(
        None,
        description="position, twist (rods), axial_force: instead of at, the material point "
        "nearest to this fixed point in space [m], found anew at every output; "
        "wave_elevation: the point whose horizontal position is read",
    )
    joint: Name | None = Field(None, description="reaction: the joint's name")
    obstacle: Name | None = Field(
        None, description="contact_force, touchdown: the obstacle's name (touchdown: a plane)"
    )
    winch: Name | None = Field(None, description="winch: the winch's name")
    body: Name | None = Field(
        None,
        description="angle: the rigid body; center_of_mass, momentum, fluid_force: the body "
        "(default: the whole system); touchdown: the line (default: the only flexible body)",
    )

    @model_validator(mode="after")
    def _kind_keys(self) -> SensorTable:
        kd = self.kind
        if self.about is not None and kd != "angular_momentum":
            raise fail("about", "applies to angular_momentum sensors only")
        if self.joint is not None and kd != "reaction":
            raise fail("joint", "applies to reaction sensors only")
        if self.obstacle is not None and kd not in ("contact_force", "touchdown"):
            raise fail("obstacle", "applies to contact_force and touchdown sensors only")
        if (self.winch is not None) != (kd == "winch"):
            raise fail("winch", "a winch sensor needs winch = NAME (and only it has one)")
        if kd == "winch":
            for k in ("at", "between", "body", "at_point"):
                if self[k] is not None:
                    raise fail(k, "not for a winch sensor (the winch's line)")
            return self
        if kd in ("contact_force", "touchdown"):
            if self.obstacle is None:
                raise fail("obstacle", f"a {kd} sensor needs obstacle = NAME")
            for k in ("at", "between"):
                if self[k] is not None:
                    raise fail(k, f"not for a {kd} sensor (of the obstacle)")
            if kd == "contact_force" and self.body is not None:
                raise fail("body", "not for a contact_force sensor (the obstacle's total force)")
            return self
        if kd == "wave_elevation":
            if self.at_point is None:
                raise fail("at_point", "a wave_elevation sensor needs at_point = [x, y(, z)]")
            for k in ("at", "between", "body"):
                if self[k] is not None:
                    raise fail(k, "not for a wave_elevation sensor (of the fluid at at_point)")
            return self
        if self.at_point is not None:
            if kd not in AT_POINT_KINDS:
                raise fail("at_point", f"applies to {', '.join(AT_POINT_KINDS)} sensors only")
            if self.at is not None or self.between is not None:
                raise fail("at_point", "instead of at (not both)")
            return self  # body = NAME: the flexible body searched (default all)
        if self.body is not None and kd not in (
            "angle",
            "center_of_mass",
            "momentum",
            "fluid_force",
        ):
            raise fail(
                "body",
                "applies to angle, center_of_mass, momentum, fluid_force and "
                "touchdown sensors only",
            )
        if kd in (
            "angular_momentum",
            "energy",
            "angle",
            "center_of_mass",
            "momentum",
            "fluid_force",
        ):
            for k in ("at", "between"):
                if self[k] is not None:
                    what = "whole model" if kd in ("angular_momentum", "energy") else "a body"
                    raise fail(k, f"not for a {kd} sensor ({what})")
            if kd == "angle" and self.body is None:
                raise fail("body", "an angle sensor needs body = NAME (a rigid body)")
        elif kd == "distance":
            if self.at is not None or self.between is None:
                raise fail("between", "a distance sensor needs between = [A, B]")
        elif kd == "reaction":
            if self.between is not None:
                raise fail("between", "not for a reaction sensor")
            if (self.joint is None) == (self.at is None):
                raise fail(
                    "joint",
                    "a reaction sensor needs joint = NAME or at = a support's place (one of them)",
                )
        elif self.between is not None or self.at is None:
            raise fail("at", f"a {kd} sensor needs at = PLACE")
        return self

    def places(self) -> tuple[Any, ...]:
        """The places the sensor reads (``between`` or ``at``)."""
        if self.between is not None:
            return tuple(self.between)
        return () if self.at is None else (self.at,)

    def record(self, nodes: tuple[int, ...] = ()) -> Sensor:
        """The :class:`Sensor` of this table (``nodes``: its places as node indices)."""
        about = None if self.about is None else tuple(self.about)
        point = None if self.at_point is None else tuple(self.at_point)
        return Sensor(
            self.name,
            self.kind,
            nodes,
            about,
            self.places(),
            self.joint,
            self.body,
            self.obstacle,
            point,
            self.winch,
        )
