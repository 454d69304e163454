"""The keys of each ``[geometry]`` kind: curves (a line body) and surfaces (a shell)."""

from __future__ import annotations

from rancf.mesh.surface_kinds import SURFACE_KEYS

__all__ = ["GEOMETRY_KEYS"]

#: Keys of ``[geometry]`` for each kind.
GEOMETRY_KEYS = {
    "conic": ("start", "end", "angles_deg", "point"),
    "line": ("start", "end", "length"),
    "nurbs": ("degree", "knots", "control_points", "weights"),
    "cad": ("file", "curve"),
    "ellipse": ("center", "semi_axes", "rotation_deg", "axes", "start_deg"),
    **SURFACE_KEYS,
}
