"""The checks of a shell body: its tables together, and its surface meshed once to check it.

A flexible body is a shell when its ``[geometry]`` is a surface (:mod:`rancf.scenario.surface`).
Its keys: ``[mesh] elements = [nu, nv]`` (and ``k``, ``quadrature_points``), ``[section]
thickness``, ``[material] youngs_modulus, poisson_ratio, density``.  A key of a line body (a
cable's ``section.radius``, a rod's ``material.shear_modulus``, ``mesh.continuity``, ``[form]``)
is refused in one line naming it; so is a surface the mesher refuses (an angle range over 360°,
a pole, non-product NURBS weights), with the geometry key it names.
"""

from __future__ import annotations

from typing import Any

from rancf.errors import InputError
from rancf.scenario.base import fail, show
from rancf.scenario.surface import is_surface

__all__ = ["check_shell", "shell_mesh"]

#: The keys of a line body's tables that a shell refuses, with their defaults (None: unset).
_LINE_ONLY: dict[str, dict[str, Any]] = {
    "section": {
        k: None
        for k in (
            "radius",
            "area",
            "inertia",
            "inertia_y",
            "inertia_z",
            "orientation",
            "torsion_constant",
            "rotary_inertia",
        )
    },
    "material": {"shear_modulus": None, "axial_strain": "green_lagrange", "axial_law": None},
    "mesh": {"element": "rancf", "spacing": "arc", "continuity": "C1", "stress_free": "auto"},
}
_SHELL = "applies to line bodies (cables, beams, rods), not to a shell (a surface [geometry])"


def shell_mesh(geometry: Any, mesh: Any) -> Any:
    """The :class:`~rancf.mesh.surfaces.SurfaceMesh` of a shell's ``[geometry]`` and ``[mesh]``
    (docs/derivations/shell.md sec. 2-3); the mesher's errors as :func:`fail` naming the key."""
    from rancf.mesh.surface_kinds import mesh_surface

    try:
        return mesh_surface(geometry.spec(), list(mesh.pair), mesh.k)
    except InputError as exc:
        raise fail(exc.parameter, f"must be {exc.allowed}, got {show(exc.value)}") from None


def check_shell(geometry: Any, mesh: Any, section: Any, material: Any, form: Any = None) -> None:
    """The checks of a shell body across its tables (module docstring); keys relative to the
    body (``section.radius``, ``mesh.elements``)."""
    tables = {"section": section, "material": material, "mesh": mesh}
    for name, keys in _LINE_ONLY.items():
        for k, default in keys.items():
            v = tables[name][k]
            if v != default:
                raise fail(f"{name}.{k}", f"{_SHELL}; got {show(v)}")
    if form is not None:
        raise fail("form", f"{_SHELL}: it finds a line's unstretched length")
    if isinstance(mesh.elements, int):
        raise fail(
            "mesh.elements",
            f"must be [nu, nv] for a shell (elements along u and v), got {show(mesh.elements)}",
        )
    if section.thickness is None:
        raise fail("section.thickness", "required for a shell (the wall thickness t [m])")
    if material.poisson_ratio is None:
        raise fail("material.poisson_ratio", "required for a shell (plane stress), in (-1, 0.5)")
    shell_mesh(geometry, mesh)


def _surface(b: Any) -> bool:
    return is_surface(b.geometry)


def _shell_place(p: Any) -> bool:
    return p.where in ("edge", "surface")


def _supports(c: Any) -> None:
    for i, s in enumerate(c.sc.supports):
        key = f"supports[{i}]"
        p = c.place(f"{key}.at", s.at)
        if not _shell_place(p):
            if s.kind in ("diaphragm", "symmetry"):
                raise fail(f"{key}.kind", f"{s.kind!r} holds a shell's edge, not {show(s.at)}")
            continue
        if p.where == "surface" and s.kind in ("diaphragm", "symmetry"):
            raise fail(
                f"{key}.at",
                f'a {s.kind} holds an edge ("u0", "u1", "v0", "v1"), got the point {show(s.at)}',
            )
        for k in ("position", "direction", "motion"):
            if s[k] is not None:
                raise fail(f"{key}.{k}", "not for a shell's support (it holds the reference)")


#: Why a shell's loads take no time function yet.
_CONSTANT = (
    "not for a load on a shell: its loads are constant (statics: scaled along the load path; "
    "dynamics: constant in time)"
)


def _constant(key: str, table: Any, fields: tuple[str, ...]) -> None:
    for k in fields:
        if table[k] is not None:
            raise fail(f"{key}.{k}", f"{_CONSTANT}; got {show(table[k])}")


def _loads(c: Any) -> None:
    shells = {n for n, b in (c.bodies or {}).items() if b.kind == "flexible" and _surface(b)}
    for i, d in enumerate(c.sc.loads.distributed):
        if d.body in shells or (d.body is None and (shells or c.shell)):
            _constant(f"loads.distributed[{i}]", d, ("time",))
    for i, e in enumerate(c.sc.loads.edge):
        _constant(f"loads.edge[{i}]", e, ("time",))
    for i, pl in enumerate(c.sc.loads.point):
        if _shell_place(c.place(f"loads.point[{i}].at", pl.at)):
            _constant(f"loads.point[{i}]", pl, ("time", "frequency_hz", "moment"))
        if c.place(f"loads.point[{i}].at", pl.at).where == "edge":
            raise fail(
                f"loads.point[{i}].at",
                f"a point load on a shell acts at a point [u, v], not the edge {show(pl.at)} "
                "(spread along an edge: [[loads.edge]])",
            )
    for i, e in enumerate(c.sc.loads.edge):
        if c.place(f"loads.edge[{i}].at", e.at).where != "edge":
            raise fail(
                f"loads.edge[{i}].at",
                f'must be an edge of a shell ("u0", "u1", "v0", "v1"), got {show(e.at)}',
            )


def _sensors(c: Any) -> None:
    for i, s in enumerate(c.sc.sensor_tables):
        places = [c.place(f"sensors[{i}].at", p) for p in s.places()]
        if not any(_shell_place(p) for p in places):
            continue
        if s.kind != "position":
            raise fail(
                f"sensors[{i}].kind",
                f"a sensor on a shell is a position (at = [u, v]), not {s.kind!r}",
            )
        if places[0].where != "surface":
            raise fail(f"sensors[{i}].at", f"must be a surface point [u, v], got {show(s.at)}")


def _motion(c: Any) -> None:
    """A shell starts at rest: its initial velocities are not built yet."""
    for i, iv in enumerate(c.sc.initial_velocity):
        if _shell_place(c.place(f"initial_velocity[{i}].at", iv.at)):
            raise fail(
                f"initial_velocity[{i}].at",
                f"a node of a line body, not a shell's {show(iv.at)} (a shell starts at rest)",
            )
    if c.shell and c.sc.initial_motion is not None:
        raise fail("initial_motion", "not for a shell yet (a shell starts at rest)")
    for i, b in enumerate((c.bodies or {}).values()):
        shell = b.kind == "flexible" and _surface(b)
        if shell and getattr(b, "initial_motion", None) is not None:
            raise fail(
                f"bodies[{i}].initial_motion", "not for a shell yet (a shell starts at rest)"
            )


def check_shell_uses(c: Any) -> None:
    """The supports, loads and sensors on shells (``c``: the scenario checks' context with its
    ``sc``, ``place`` and ``element``): a diaphragm or symmetry on an edge of a shell only, a
    point load at a surface point, an edge load on an edge, a position sensor at a point."""
    _supports(c)
    _loads(c)
    _sensors(c)
    _motion(c)
