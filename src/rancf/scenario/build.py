"""A validated scenario turned into a mesh and a model; geometry errors name scenario keys.

Errors of the geometry and meshing functions name their own arguments (``angles (theta1)``,
``knots``, ``k``); here they are re-raised as :class:`~rancf.errors.ScenarioError` naming the
scenario key the user wrote (``geometry.angles_deg[1]``, ``geometry.knots``, ``mesh.k``; with a
prefix such as ``bodies[2].`` for a body of a system), and a geometry whose arc length cannot be
integrated is a geometry error, not a solver failure.  Node indices are checked against the mesh
here.

Systems (``[[bodies]]``, ``[[joints]]``, ``[[springs]]``), prescribed support motion
(``supports.motion``), time functions of point loads (``loads.point.time``) and the sensors the
system solver computes are refused with one line until the system solver takes them.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rancf.bodies.flexible import Material, Model, PointLoad, RigidMotion, Section, Support
from rancf.bodies.properties import StrainRateDamping
from rancf.errors import ConvergenceError, InputError, ScenarioError
from rancf.scenario.geometry import MAX_ELEMENTS, CadGeometry, ConicGeometry, NurbsGeometry
from rancf.scenario.surface import is_surface
from rancf.scenario.view import ScenarioView

if TYPE_CHECKING:
    from rancf.scenario.geometry import MeshTable

__all__ = [
    "build_model",
    "flexible_model",
    "mesh_geometry",
    "scenario_key",
    "body_model",
    "SYSTEM_KEYS",
]

#: Argument names of the geometry functions -> scenario keys.
_KEYS = {
    "angles (theta0)": "geometry.angles_deg[0]",
    "angles (theta1)": "geometry.angles_deg[1]",
    "angles": "geometry.angles_deg",
    "point": "geometry.point",
    "chord": "geometry.end",
    "end": "geometry.end",
    "start/end": "geometry.end",
    "start/end/point": "geometry.point",
    "knots": "geometry.knots",
    "weights": "geometry.weights",
    "points": "geometry.control_points",
    "degree": "geometry.degree",
    "k": "mesh.k",
    "elements": "mesh.elements",
    "elements per span": "mesh.elements",
}


def scenario_key(parameter: str, geometry: Any, mesh: MeshTable) -> str:
    """The scenario key behind a geometry function's argument name."""
    if parameter == "geometry":  # a joint or a degenerate element of the chain
        if isinstance(geometry, ConicGeometry) and mesh.k != "opt":
            return "mesh.k"
        return "geometry.control_points" if isinstance(geometry, NurbsGeometry) else "geometry"
    return _KEYS.get(parameter, parameter)


def _value(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, np.ndarray):
        return np.array2string(v, precision=6, separator=", ").replace("\n", "")
    return v if isinstance(v, str) else repr(v)


def _mesh(path: str, g: Any, m: MeshTable, prefix: str) -> Any:
    from rancf.geometry.conic import conic_arc_through
    from rancf.geometry.nurbs import NurbsCurve
    from rancf.mesh.factories import mesh_conic, mesh_line
    from rancf.mesh.nurbs_mesh import mesh_nurbs

    if g.kind == "conic":
        conic = conic_arc_through(g.start, g.end, g.angles_deg, g.point)
        return mesh_conic(conic, m.count, m.k, m.spacing)
    if g.kind == "line":
        return mesh_line(g.start, g.end, m.count)
    if g.kind == "ellipse":
        from rancf.mesh.ellipse_mesh import mesh_ellipse

        return mesh_ellipse(g.ellipse(), m.count, m.k, m.spacing, g.start_deg)
    if isinstance(g, CadGeometry):
        from rancf.mesh.cad_geometry import mesh_curve_chain

        return mesh_curve_chain(g.curves, g.labels, m.count, g.notes)
    pts = np.array(g.control_points)
    w = np.ones(len(pts)) if g.weights is None else np.array(g.weights)
    curve = NurbsCurve(g.degree, np.array(g.knots), pts, w)
    spans = len(curve.bezier_segments()[0]) - 1
    if spans * m.count > MAX_ELEMENTS:
        raise ScenarioError(
            path,
            f"{prefix}mesh.elements",
            f"{m.count} per knot span x {spans} spans is more than {MAX_ELEMENTS} elements",
        )
    return mesh_nurbs(curve, m.count)


def mesh_geometry(path: str, geometry: Any, mesh: MeshTable, prefix: str = "") -> Any:
    """The mesh of a flexible body's ``geometry`` and ``mesh`` tables; errors name the keys
    (after ``prefix``, e.g. ``"bodies[2]."``)."""
    try:
        return _mesh(path, geometry, mesh, prefix)
    except InputError as exc:
        key = scenario_key(exc.parameter, geometry, mesh)
        raise ScenarioError(
            path, prefix + key, f"{exc.allowed} (got {_value(exc.value)})"
        ) from None
    except ConvergenceError as exc:
        raise ScenarioError(
            path, f"{prefix}geometry", f"is too extreme to measure its arc length ({exc})"
        ) from None


#: The tables that make a scenario a system of parts rather than one flexible body.
SYSTEM_KEYS = (
    "bodies",
    "joints",
    "springs",
    "obstacles",
    "body_contacts",
    "fluid",
    "hydro",
    "winches",
)


def build_model(sc: ScenarioView) -> Model:
    """The flexible body of a scenario of one flexible body (errors name the scenario key); a
    scenario with more parts (:data:`SYSTEM_KEYS`) is refused in one line that points to its
    system."""
    many = len(sc.body_tables) != 1 or sc.body_tables[0][1].kind != "flexible"
    for k in SYSTEM_KEYS:
        if (k == "bodies" and many) or (k != "bodies" and sc[k]):
            raise ScenarioError(
                sc.path,
                k,
                "makes this scenario a system of parts, not one "
                "flexible body: Scenario.build_system() builds it",
            )
    if sc.loads.distributed:
        raise ScenarioError(
            sc.path,
            "loads.distributed",
            "act on the scenario's system: Scenario.build_system() builds it",
        )
    return body_model(sc, 0)


def body_model(sc: ScenarioView, i: int) -> Model:
    """The model of the flexible body ``i`` of the scenario's ``body_tables``
    (:func:`rancf.scenario.data.body_tables`): its tables, and the supports, point loads,
    initial velocities and sensor nodes at its places (moving supports included), as the
    scenario's system holds it."""
    key, b = sc.body_tables[i]
    if is_surface(b.geometry):  # a shell (docs/derivations/shell.md sec. 8)
        from rancf.scenario.shell_build import shell_model

        return shell_model(sc, i)
    d = sc.data

    def at(rows: list[dict[str, Any]], what: str) -> list[tuple[str, int, dict[str, Any]]]:
        out = []
        for k, t in enumerate(rows):
            p = sc.place(t["at"])
            turning = t.get("rotation") is not None  # a joint to a turning frame (system_build)
            if p.where == "node" and p.body == b.name and p.node is not None and not turning:
                out.append((f"{what}[{k}]", p.node, t))
        return out

    nodes = [
        (f"sensors.{sn.name}", p.node)
        for sn in sc.sensors
        for p in map(sc.place, sn.places)
        if p.where == "node" and p.body == b.name and p.node is not None
    ]
    model = flexible_model(
        sc,
        key,
        (b.geometry, b.mesh, b.section, b.material),
        at(d["supports"], "supports"),
        at(d["loads"]["point"], "loads.point"),
        at(d["initial_velocity"], "initial_velocity"),
        d["bodies"][i]["initial_motion"],
        nodes,
        ("", sc.damping) if b.damping is None else (key, b.damping),
    )
    length = sc.body_length(b.name)  # a [form] not found yet is refused there
    if length is not None:  # the material stretched or compressed onto its reference
        from rancf.bodies.length import set_unstretched_length

        set_unstretched_length(model, length)
    return model


def flexible_model(
    sc: ScenarioView,
    prefix: str,
    tables: tuple[Any, Any, Any, Any],
    supports: list[tuple[str, int, dict[str, Any]]],
    loads: list[tuple[str, int, dict[str, Any]]],
    velocities: list[tuple[str, int, dict[str, Any]]],
    initial_motion: dict[str, Any] | None,
    sensor_nodes: Sequence[tuple[str, int]] = (),
    damping: tuple[str, Any] | None = None,
) -> Model:
    """The model of one flexible body: its ``geometry``, ``mesh``, ``section`` and ``material``
    tables (keys after ``prefix``, e.g. ``bodies[2].``), and the supports, point loads and
    initial velocities at its nodes as ``(key, node, table)`` (node indices are checked against
    the mesh here, naming the key); ``damping``: the table of its strain-rate damping keys and
    that table's prefix (``""``: ``[damping]``; ``"bodies[2]."``: the body's own)."""
    geometry, mesh_table, section, material = tables
    kv_prefix, kv = damping if damping is not None else (prefix, None)
    mesh = mesh_geometry(sc.path, geometry, mesh_table, prefix)
    n_nodes = mesh.n_nodes
    supported = {_check_node(sc, n_nodes, f"{key}.at", node) for key, node, _ in supports}
    supports = [(key, node, _path(sc, key, t, mesh.nodes[node, 0])) for key, node, t in supports]
    for key, node, _ in loads:
        _check_node(sc, n_nodes, f"{key}.at", node)
    for key, node in sensor_nodes:
        _check_node(sc, n_nodes, key, node)
    _one_support_per_node(sc, n_nodes, supports)
    v0 = {}
    for key, at, t in velocities:
        node = _check_node(sc, n_nodes, f"{key}.at", at)
        if node in supported and any(x != 0.0 for x in t["value"]):
            raise ScenarioError(
                sc.path,
                f"{key}.at",
                f"node {at} is supported (its position is fixed), so it "
                "cannot start with a velocity",
            )
        v0[node] = t["value"]
    try:
        model = Model(
            mesh,
            mesh_table.element,
            section_of(section),
            Material(
                material.density,
                material.youngs_modulus,
                material.shear_modulus,
                material.poisson_ratio,
                material.axial_strain,
                None if material.axial_law is None else material.axial_law.law(),
            ),
            [_support(node, t) for _, node, t in supports],
            sc.loads.gravity,
            [_load(node, t) for _, node, t in loads],
            sc.damping.mass_proportional,
            v0,
            mesh_table.quadrature_points,
            None if initial_motion is None else RigidMotion(**initial_motion),
            mesh_table.continuity,
            mesh_table.stress_free,
            None if kv is None else StrainRateDamping(kv.axial, kv.bending, kv.torsion),
        )
    except InputError as exc:
        pre = kv_prefix if exc.parameter.startswith("damping.") else prefix
        raise ScenarioError(
            sc.path, pre + exc.parameter, f"{exc.allowed} (got {_value(exc.value)})"
        ) from None
    return model


def section_of(s: Any) -> Section:
    """The :class:`~rancf.bodies.flexible.Section` of a ``[section]`` table."""
    if s.radius is not None:
        section = Section.circular(s.radius)
        section = replace(section, torsion_constant=s.torsion_constant)
    else:
        inertia = s.inertia if s.inertia is not None else s.inertia_y
        orient = None if s.orientation is None else tuple(s.orientation)
        section = Section(s.area, inertia, s.inertia_z, s.torsion_constant, orient)
    if s.rotary_inertia is not None:
        section = replace(section, rotary_inertia=s.rotary_inertia)
    return section


def _vec(v: list[float] | None) -> tuple[float, ...] | None:
    return None if v is None else tuple(v)


def _path(sc: ScenarioView, key: str, t: dict[str, Any], reference: Any) -> dict[str, Any]:
    """A support's table ``t`` with a motion of absolute positions made the displacement from
    the support's ``reference`` point (:func:`rancf.scenario.motions.absolute_motion`)."""
    if not t.get("absolute"):
        return t
    from rancf.scenario.motions import absolute_motion

    static = sc.solver.initial_state == "static"
    try:
        motion = absolute_motion(t["motion"], reference, f"{key}.motion", static)
    except InputError as exc:
        raise ScenarioError(sc.path, exc.parameter, f"{exc.allowed} (got {exc.value})") from None
    return {**t, "motion": motion}


def _support(node: int, t: dict[str, Any]) -> Support:
    return Support(
        node,
        t["kind"],
        t["fix_twist"],
        _vec(t["position"]),
        _vec(t["direction"]),
        _vec(t["axis"]),
        t["motion"],
    )


def _load(node: int, t: dict[str, Any]) -> PointLoad:
    return PointLoad(node, _vec(t["force"]), t["frequency_hz"], _vec(t["moment"]), t["time"])


def _one_support_per_node(
    sc: ScenarioView, n_nodes: int, supports: list[tuple[str, int, dict[str, Any]]]
) -> None:
    """Refuse a second support at a node, naming its key: the two would each report the whole
    reaction (their sum twice the load) and the later one's position, direction or motion would
    silently replace the earlier one's."""
    seen: dict[int, str] = {}
    for key, at, _ in supports:
        node = _check_node(sc, n_nodes, f"{key}.at", at)
        if node in seen:
            raise ScenarioError(
                sc.path,
                f"{key}.at",
                f"node {at}{'' if at == node else f' (node {node})'} is held by {seen[node]} "
                "already: one support per node (a clamp holds the position too; give one "
                "support its position or motion)",
            )
        seen[node] = key


def _check_node(sc: ScenarioView, n_nodes: int, key: str, node: int) -> int:
    if not -n_nodes <= node < n_nodes:
        raise ScenarioError(
            sc.path, key, f"node {node} does not exist (the mesh has nodes 0..{n_nodes - 1})"
        )
    return node % n_nodes
