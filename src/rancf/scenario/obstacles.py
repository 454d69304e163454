"""``[[obstacles]]`` and ``contacts``: rigid obstacles the flexible bodies touch.

An obstacle is a ``plane`` (``point``, outward ``normal``), a ``cylinder`` (``center``,
``radius``; in 3D also ``axis``; in 2D a circle) or a ``sphere`` (3D: ``center``, ``radius``),
fixed, or carried by a rigid body (``body = NAME``: its geometry then in the body's frame,
relative to its centre of mass, like the body's ``points``).  ``friction`` is the Coulomb
coefficient; ``stiffness`` [N/m²], ``onset`` [m], ``damping`` [s/m] and ``slip_velocity``
[m/s] tune the penalty contact (:mod:`rancf.system.contact`; defaults from each body's section
and material).  Every flexible body touches every obstacle, as a tube of its section's radius,
unless the top-level ``contacts = [[BODY, OBSTACLE], ...]`` lists the pairs.
"""

from __future__ import annotations

from typing import Literal

from pydantic import Field, model_validator

from rancf.scenario.base import Name, NonNegative, Positive, Table, Vector3, Vector23, fail

__all__ = ["ObstacleTable", "OBSTACLE_KEYS"]

#: The geometry keys of each kind.
OBSTACLE_KEYS = {
    "plane": ("point", "normal"),
    "cylinder": ("center", "radius", "axis"),
    "sphere": ("center", "radius"),
}


class ObstacleTable(Table):
    """One ``[[obstacles]]`` table: a rigid ``plane``, ``cylinder`` (in 2D a circle) or
    ``sphere``, fixed or carried by a rigid body (``body = NAME``), that the flexible bodies touch
    with friction."""

    name: Name = Field(description="the obstacle's name (reaction columns, sensors), unique")
    kind: Literal["plane", "cylinder", "sphere"] = Field(
        description='"plane" | "cylinder" (a circle in 2D) | "sphere" (3D)'
    )
    point: Vector23 | None = Field(None, description="plane: a point of it [m]")
    normal: Vector23 | None = Field(None, description="plane: its outward normal")
    center: Vector23 | None = Field(None, description="cylinder, sphere: the centre [m]")
    radius: Positive | None = Field(None, description="cylinder, sphere: the radius [m]")
    axis: Vector3 | None = Field(None, description="cylinder in 3D: its axis")
    body: Name | None = Field(
        None, description="the rigid body carrying it (geometry in the body's frame)"
    )
    friction: NonNegative = Field(0.0, description="Coulomb friction coefficient mu")
    stiffness: Positive | None = Field(
        None,
        description="penalty stiffness [N/m^2] (default: on a seabed, a fixed plane "
        "facing up against gravity in a [fluid], k = w_n / (0.01 D): the body's wet weight per "
        "length w_n presses it in by 1 % of its diameter D; else a tenth of Young's modulus)",
    )
    onset: Positive | None = Field(
        None, description="depth of the pressure's smooth onset [m] (default: 1e-3 r)"
    )
    damping: NonNegative = Field(0.0, description="Hunt-Crossley damping factor [s/m]")
    damping_normal: NonNegative = Field(
        0.0,
        description="linear normal damping per unit contact area while in contact "
        "[Pa s/m] (MoorDyn's cBot): a force per length c D (-g') over the tube's diameter D; "
        "never pulls",
    )
    slip_velocity: Positive = Field(
        1e-3, description="regularization velocity of the friction [m/s]"
    )

    @model_validator(mode="after")
    def _kind_keys(self) -> ObstacleTable:
        own = OBSTACLE_KEYS[self.kind]
        for keys in OBSTACLE_KEYS.values():
            for k in keys:
                if k not in own and self[k] is not None:
                    raise fail(
                        k, f"does not apply to kind = {self.kind!r} (its keys: {', '.join(own)})"
                    )
        for k in own:
            if k != "axis" and self[k] is None:
                raise fail(k, f"required for a {self.kind}")
        for k in ("normal", "axis"):
            if self[k] is not None and not any(x != 0.0 for x in self[k]):
                raise fail(k, "must be a nonzero vector")
        return self
