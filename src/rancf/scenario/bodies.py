"""``[[bodies]]``: flexible bodies, rigid bodies and point masses, each named.

* A flexible body (``kind = "flexible"``, the default) has the sub-tables ``geometry``, ``mesh``,
  ``section`` and ``material`` of a one-body file (``[bodies.geometry]``, ...) and optionally its
  own ``initial_motion`` and ``damping`` (strain-rate damping: ``axial``, ``bending``,
  ``torsion``, in place of those keys of ``[damping]``).
* A rigid body (``kind = "rigid"``): ``mass``, ``inertia`` (2D: a number, about the centre of
  mass; 3D: ``[Ixx, Iyy, Izz]``, principal, in the body frame), ``position`` (the centre of mass),
  ``orientation_deg`` (2D: the angle of the body frame) or ``orientation`` (3D: the rotation
  matrix's rows, body frame to global), optional ``velocity`` and ``angular_velocity`` (2D: a
  number; 3D: global components), and ``points = { NAME = [x, y(, z)] }`` in the body frame.
* A point mass (``kind = "mass"``): ``mass``, ``position`` and optional ``velocity``.

Names are simple names (letters, digits, ``_``), unique, and not ``ground``; the places
``"BODY..."`` of joints, supports, loads and sensors refer to them (:mod:`rancf.scenario.places`).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

import numpy as np
from pydantic import Field, Tag, model_validator
from pydantic_core import PydanticCustomError

from rancf.scenario.base import (
    KindOf,
    Name,
    Number,
    NumberOrVector3,
    Positive,
    Table,
    Vector3,
    Vector23,
    fail,
    show,
    under,
)
from rancf.scenario.damping import StrainRateDampingTable
from rancf.scenario.fluid import HydroTable
from rancf.scenario.form import FormTable
from rancf.scenario.geometry import Geometry, MeshTable
from rancf.scenario.loads import InitialMotionTable
from rancf.scenario.section import MaterialTable, SectionTable, check_flexible

__all__ = ["FlexibleBody", "RigidBody", "PointMass", "Body", "ORTHONORMAL_TOL"]

#: Largest deviation of ``orientation`` from a rotation matrix: ``|R Rᵀ − I|``, ``|det R − 1|``.
ORTHONORMAL_TOL = 1e-6

_NAME = 'the body\'s name (letters, digits, _), unique, not "ground"'


def _dim_of(key: str, v: list[float] | None, dim: int) -> None:
    if v is not None and len(v) != dim:
        raise fail(key, f"must be a list of {dim} numbers, got {show(v)}")


def _rate(key: str, w: Any, dim: int) -> None:
    if dim == 2 and isinstance(w, list):
        raise fail(key, f"must be a number in 2D (the rate about z), got {show(w)}")
    if dim == 3 and w is not None and not isinstance(w, list):
        raise fail(key, f"must be a list of 3 numbers in 3D, got {show(w)}")


class FlexibleBody(Table):
    """A cable, beam or rod on any geometry rancf meshes."""

    name: Name = Field(description=_NAME)
    kind: Literal["flexible"] = Field("flexible", description="a flexible body (the default)")
    geometry: Geometry
    mesh: MeshTable = Field(description="the elements")
    section: SectionTable = Field(description="the cross-section")
    material: MaterialTable = Field(description="the material")
    initial_motion: InitialMotionTable | None = Field(
        None, description="this body's initial rigid-body velocity field"
    )
    hydro: HydroTable | None = Field(
        None, description="hydrodynamic coefficients (the body is in the [fluid])"
    )
    damping: StrainRateDampingTable | None = Field(
        None,
        description="this body's strain-rate damping (axial, bending, torsion), in place "
        "of those keys of [damping]",
    )
    form: FormTable | None = Field(
        None,
        description="form-finding: the unstretched length found to meet a sag, horizontal "
        "tension or end tension in statics",
    )

    @model_validator(mode="after")
    def _together(self) -> FlexibleBody:
        check_flexible(self.geometry, self.mesh, self.section, self.material, self.form)
        if self.initial_motion is not None:
            try:
                self.initial_motion.check_dim(self.dim)
            except PydanticCustomError as exc:
                raise under("initial_motion", exc) from None
        return self

    @property
    def dim(self) -> int:
        """2 (planar) or 3 (spatial)."""
        return int(self.geometry.dim)


class RigidBody(Table):
    """A rigid body: mass, principal inertia, frame, velocities and named points."""

    name: Name = Field(description=_NAME)
    kind: Literal["rigid"] = Field(description="a rigid body")
    mass: Positive = Field(description="mass [kg]")
    inertia: NumberOrVector3 = Field(
        description="2D: moment of inertia about the centre of mass [kg m^2]; 3D: principal "
        "[Ixx, Iyy, Izz] in the body frame"
    )
    position: Vector23 = Field(description="centre of mass [m]; 2 coordinates: planar")
    orientation_deg: Number | None = Field(
        None, description="2D: angle of the body frame [deg] (default 0)"
    )
    orientation: list[Vector3] | None = Field(
        None,
        description="3D: the rotation matrix's rows (body frame to global; default identity)",
    )
    velocity: Vector23 | None = Field(None, description="velocity of the centre [m/s]")
    angular_velocity: NumberOrVector3 | None = Field(
        None, description="[rad/s]: a number in 2D, global components in 3D"
    )
    points: dict[Name, Vector23] = Field(
        {}, description="named points in the body frame [m] (places BODY:POINT)"
    )

    @model_validator(mode="after")
    def _consistent(self) -> RigidBody:
        dim = self.dim
        i = self.inertia
        if dim == 2:
            if isinstance(i, list):
                raise fail("inertia", f"must be a number in 2D, got {show(i)}")
            if not i > 0:
                raise fail("inertia", f"must be > 0, got {show(i)}")
            if self.orientation is not None:
                raise fail("orientation", "is 3D: give orientation_deg in 2D")
        else:
            if not isinstance(i, list) or len(i) != 3:
                raise fail("inertia", f"must be [Ixx, Iyy, Izz] in 3D, got {show(i)}")
            if not all(x > 0 for x in i):
                raise fail("inertia", f"must be > 0 each, got {show(i)}")
            a, b, c = sorted(i)
            if c > a + b:
                raise fail(
                    "inertia",
                    f"principal moments must satisfy Ixx <= Iyy + Izz (and cyclic), got {show(i)}",
                )
            if self.orientation_deg is not None:
                raise fail("orientation_deg", "is 2D: give orientation (3 rows) in 3D")
            if self.orientation is not None:
                _rotation(self.orientation)
        _dim_of("velocity", self.velocity, dim)
        _rate("angular_velocity", self.angular_velocity, dim)
        for n, p in self.points.items():
            _dim_of(f"points.{n}", p, dim)
        return self

    @property
    def dim(self) -> int:
        """2 (planar) or 3 (spatial)."""
        return len(self.position)


def _rotation(rows: list[list[float]]) -> None:
    r = np.array(rows)
    if r.shape != (3, 3):
        raise fail("orientation", f"must be 3 rows of 3 numbers, got {show(rows)}")
    dev = max(float(np.abs(r @ r.T - np.eye(3)).max()), abs(float(np.linalg.det(r)) - 1.0))
    if dev > ORTHONORMAL_TOL:
        raise fail(
            "orientation",
            f"must be a rotation matrix (orthonormal rows, det = +1; "
            f"deviation {dev:.3g} > {ORTHONORMAL_TOL:g}), got {show(rows)}",
        )


class PointMass(Table):
    """A point mass."""

    name: Name = Field(description=_NAME)
    kind: Literal["mass"] = Field(description="a point mass")
    mass: Positive = Field(description="mass [kg]")
    position: Vector23 = Field(description="position [m]; 2 coordinates: planar")
    velocity: Vector23 | None = Field(None, description="initial velocity [m/s]")

    @model_validator(mode="after")
    def _consistent(self) -> PointMass:
        _dim_of("velocity", self.velocity, self.dim)
        return self

    @property
    def dim(self) -> int:
        """2 (planar) or 3 (spatial)."""
        return len(self.position)


def _body_kind(v: Any) -> str | None:
    k = v.get("kind", "flexible") if isinstance(v, dict) else getattr(v, "kind", None)
    return f"[{k}]" if k in ("flexible", "rigid", "mass") else None


#: One of ``[[bodies]]``, chosen by ``kind`` (default ``"flexible"``).
Body = Annotated[
    Annotated[FlexibleBody, Tag("[flexible]")]
    | Annotated[RigidBody, Tag("[rigid]")]
    | Annotated[PointMass, Tag("[mass]")],
    KindOf(
        _body_kind,
        custom_error_type="choice",
        custom_error_message="must be one of the body kinds",
        custom_error_context={"key": "kind", "allowed": "'flexible', 'rigid', 'mass'"},
    ),
]
