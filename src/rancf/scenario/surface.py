"""A shell's ``[geometry]``: the five surface kinds (docs/derivations/shell.md sec. 2).

A flexible body whose ``geometry.kind`` is ``cylinder``, ``sphere``, ``cone``, ``rectangle`` or
``nurbs_surface`` is a shell: its mesh is an exact RANCF surface mesh
(:func:`rancf.mesh.surface_kinds.mesh_surface`), its parameters ``(u, v) ∈ [0, 1]²`` name its
edges ``"u0"``, ``"u1"``, ``"v0"``, ``"v1"`` and its points ``[u, v]``.  The tables check the
types here; the surface itself (angle ranges, poles, product weights, knots) is checked with the
mesh by :func:`rancf.scenario.shell_checks.check_shell`.
"""

from __future__ import annotations

from typing import Any, ClassVar, Literal

from pydantic import Field

from rancf.mesh.surface_kinds import SURFACE_KEYS
from rancf.scenario.base import Integer, Number, Point, Positive, Table, Vector2, Vector3
from rancf.scenario.geometry_keys import GEOMETRY_KEYS

__all__ = [
    "SURFACE_KINDS",
    "CylinderGeometry",
    "SphereGeometry",
    "ConeGeometry",
    "RectangleGeometry",
    "NurbsSurfaceGeometry",
    "SURFACE_TABLES",
    "is_surface",
]

#: The geometry kinds that make a flexible body a shell.
SURFACE_KINDS: tuple[str, ...] = tuple(SURFACE_KEYS)


class _Surface(Table):
    """Keys of another geometry kind are refused as not applying to this one."""

    KIND: ClassVar[str] = ""

    @classmethod
    def unknown_key_message(cls, key: str) -> str:
        if any(key in keys for keys in GEOMETRY_KEYS.values()):
            own = ", ".join(SURFACE_KEYS[cls.KIND])
            return f"does not apply to kind = {cls.KIND!r} (its keys: {own})"
        return super().unknown_key_message(key)

    @property
    def dim(self) -> int:
        """A shell is spatial: 3."""
        return 3

    def spec(self) -> dict[str, Any]:
        """The table as :func:`rancf.mesh.surface_kinds.mesh_surface` reads it."""
        return {k: v for k, v in self.plain().items() if v is not None}


class CylinderGeometry(_Surface):
    """A circular cylinder sector, axis +y, angle in the x-z plane from +x toward +z."""

    KIND: ClassVar[str] = "cylinder"
    kind: Literal["cylinder"] = Field(description="a circular cylinder (a shell)")
    radius: Positive = Field(description="radius R [m]")
    length: Positive = Field(description="length along +y [m]")
    angles_deg: Vector2 = Field(
        description="[a0, a1]: the angle range in the x-z plane from +x toward +z [deg] (u)"
    )


class ConeGeometry(_Surface):
    """A cone frustum, axis +y, radius r0 at y = 0 and r1 at y = length."""

    KIND: ClassVar[str] = "cone"
    kind: Literal["cone"] = Field(description="a cone frustum (a shell)")
    radius: Vector2 = Field(description="[r0, r1]: radii at y = 0 and y = length [m], > 0")
    length: Positive = Field(description="length along +y [m]")
    angles_deg: Vector2 = Field(
        description="[a0, a1]: the angle range in the x-z plane from +x toward +z [deg] (u)"
    )


class SphereGeometry(_Surface):
    """A spherical patch about the origin (no pole: polar angles inside (0, 180))."""

    KIND: ClassVar[str] = "sphere"
    kind: Literal["sphere"] = Field(description="a spherical patch (a shell)")
    radius: Positive = Field(description="radius R [m]")
    azimuth_deg: Vector2 = Field(description="[phi0, phi1]: azimuth about z from +x [deg] (u)")
    polar_deg: Vector2 = Field(description="[theta0, theta1]: polar angle from +z [deg] (v)")


class RectangleGeometry(_Surface):
    """A flat rectangle in the x-y plane."""

    KIND: ClassVar[str] = "rectangle"
    kind: Literal["rectangle"] = Field(description="a flat rectangle (a shell)")
    corner: Point = Field(description="the corner at u = v = 0 [m]")
    size: Vector2 = Field(description="[a, b]: side lengths along x (u) and y (v) [m]")


class NurbsSurfaceGeometry(_Surface):
    """A NURBS surface patch with product weights (docs/derivations/shell.md eq. 2.3)."""

    KIND: ClassVar[str] = "nurbs_surface"
    kind: Literal["nurbs_surface"] = Field(description="a NURBS surface (a shell)")
    degree: list[Integer] = Field(description="[p, q]: degrees along u and v, each 1, 2 or 3")
    knots_u: list[Number] = Field(description="knot vector along u, non-decreasing")
    knots_v: list[Number] = Field(description="knot vector along v, non-decreasing")
    control_points: list[Vector3] = Field(description="control points [x, y, z] [m], u fastest")
    weights: list[Number] | None = Field(
        None, description="weights > 0, u fastest, of product form a_i b_j (default all 1)"
    )

    def spec(self) -> dict[str, Any]:
        out = super().spec()
        out.setdefault("weights", [1.0] * len(self.control_points))
        return out


#: The surface tables by kind.
SURFACE_TABLES: dict[str, type[_Surface]] = {
    "cylinder": CylinderGeometry,
    "sphere": SphereGeometry,
    "cone": ConeGeometry,
    "rectangle": RectangleGeometry,
    "nurbs_surface": NurbsSurfaceGeometry,
}


def is_surface(geometry: Any) -> bool:
    """Whether a ``[geometry]`` table is a surface (its body a shell)."""
    return isinstance(geometry, _Surface)
