"""A validated scenario turned into a mesh and a model; geometry errors name scenario keys.

Errors of the geometry and meshing functions name their own arguments (``angles (theta1)``,
``knots``, ``k``); here they are re-raised as :class:`~rancf.errors.ScenarioError` naming the
scenario key the user wrote (``geometry.angles_deg[1]``, ``geometry.knots``, ``mesh.k``), and a
geometry whose arc length cannot be integrated is a geometry error, not a solver failure.
"""

from __future__ import annotations

from dataclasses import replace
from typing import TYPE_CHECKING, Any

import numpy as np

from rancf.errors import ConvergenceError, InputError, ScenarioError
from rancf.model.system import Material, Model, PointLoad, RigidMotion, Section, Support

if TYPE_CHECKING:
    from rancf.model.scenario import Scenario

__all__ = ["build_model", "scenario_key"]

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


def scenario_key(parameter: str, sc: Scenario) -> str:
    """The scenario key behind a geometry function's argument name."""
    if parameter == "geometry":  # a joint or a degenerate element of the chain
        fixed_k = sc.data["geometry"]["kind"] == "conic" and sc.data["mesh"]["k"] != "opt"
        if fixed_k:
            return "mesh.k"
        return "geometry.control_points" if sc.data["geometry"]["kind"] == "nurbs" else "geometry"
    return _KEYS.get(parameter, parameter)


def _value(v: Any) -> str:
    if isinstance(v, float):
        return f"{v:.6g}"
    if isinstance(v, np.ndarray):
        return np.array2string(v, precision=6, separator=", ").replace("\n", "")
    return v if isinstance(v, str) else repr(v)


def _mesh(sc: Scenario) -> Any:
    from rancf.geometry.conic import conic_arc_through
    from rancf.geometry.nurbs import NurbsCurve
    from rancf.model.mesh import mesh_conic, mesh_line
    from rancf.model.nurbs_mesh import mesh_nurbs
    from rancf.model.scenario_tables import MAX_ELEMENTS

    g, m = sc.data["geometry"], sc.data["mesh"]
    if g["kind"] == "conic":
        conic = conic_arc_through(g["start"], g["end"], g["angles_deg"], g["point"])
        return mesh_conic(conic, m["elements"], m["k"], m["spacing"])
    if g["kind"] == "line":
        return mesh_line(g["start"], g["end"], m["elements"])
    if g["kind"] == "cad":
        from rancf.model.cad_geometry import mesh_curve_chain

        return mesh_curve_chain(g["curves"], g["labels"], m["elements"])
    pts = np.array(g["control_points"])
    w = np.ones(len(pts)) if g["weights"] is None else np.array(g["weights"])
    curve = NurbsCurve(g["degree"], np.array(g["knots"]), pts, w)
    spans = len(curve.bezier_segments()[0]) - 1
    if spans * m["elements"] > MAX_ELEMENTS:
        raise ScenarioError(
            sc.path,
            "mesh.elements",
            f"{m['elements']} per knot span x {spans} spans is more than {MAX_ELEMENTS} elements",
        )
    return mesh_nurbs(curve, m["elements"])


def _geometry_mesh(sc: Scenario) -> Any:
    try:
        return _mesh(sc)
    except InputError as exc:
        key = scenario_key(exc.parameter, sc)
        raise ScenarioError(sc.path, key, f"{exc.allowed} (got {_value(exc.value)})") from None
    except ConvergenceError as exc:
        raise ScenarioError(
            sc.path, "geometry", f"is too extreme to measure its arc length ({exc})"
        ) from None


def build_model(sc: Scenario) -> Model:
    """Mesh the scenario's geometry and assemble its model (errors name the scenario key)."""
    d = sc.data
    mesh = _geometry_mesh(sc)
    n_nodes = mesh.n_nodes
    # node references are checked against the mesh first, naming the scenario key
    supported = set()
    for i, t in enumerate(d["supports"]):
        supported.add(_check_node(sc, n_nodes, f"supports[{i}].at", t["at"]))
    for i, t in enumerate(d["loads"]["point"]):
        _check_node(sc, n_nodes, f"loads.point[{i}].at", t["at"])
    for sn in sc.sensors:
        for nd in sn.nodes:
            _check_node(sc, n_nodes, f"sensors.{sn.name}", nd)
    v0 = {}
    for i, t in enumerate(d["initial_velocity"]):
        node = _check_node(sc, n_nodes, f"initial_velocity[{i}].at", t["at"])
        if node in supported and any(x != 0.0 for x in t["value"]):
            raise ScenarioError(
                sc.path,
                f"initial_velocity[{i}].at",
                f"node {t['at']} is supported (its position is fixed), so it cannot start "
                "with a velocity",
            )
        v0[node] = t["value"]
    s, mat = d["section"], d["material"]
    if s["radius"] is not None:
        section = Section.circular(s["radius"])
        section = replace(section, torsion_constant=s["torsion_constant"])
    else:
        inertia = s["inertia"] if s["inertia"] is not None else s["inertia_y"]
        orient = None if s["orientation"] is None else tuple(s["orientation"])
        section = Section(s["area"], inertia, s["inertia_z"], s["torsion_constant"], orient)
    if s["rotary_inertia"] is not None:
        section = replace(section, rotary_inertia=s["rotary_inertia"])
    loads = [
        PointLoad(
            t["at"],
            None if t["force"] is None else tuple(t["force"]),
            t["frequency_hz"],
            None if t["moment"] is None else tuple(t["moment"]),
        )
        for t in d["loads"]["point"]
    ]
    try:
        return Model(
            mesh,
            d["mesh"]["element"],
            section,
            Material(
                mat["density"], mat["youngs_modulus"], mat["shear_modulus"], mat["poisson_ratio"]
            ),
            [_support(t) for t in d["supports"]],
            d["loads"]["gravity"],
            loads,
            d["damping"]["mass_proportional"],
            v0,
            d["mesh"]["quadrature_points"],
            None if d["initial_motion"] is None else RigidMotion(**d["initial_motion"]),
        )
    except InputError as exc:
        raise ScenarioError(
            sc.path, exc.parameter, f"{exc.allowed} (got {_value(exc.value)})"
        ) from None


def _support(t: dict[str, Any]) -> Support:
    def vec(v: list[float] | None) -> tuple[float, ...] | None:
        return None if v is None else tuple(v)

    return Support(
        t["at"], t["kind"], t["fix_twist"], vec(t["position"]), vec(t["direction"]), vec(t["axis"])
    )


def _check_node(sc: Scenario, n_nodes: int, key: str, node: int) -> int:
    if not -n_nodes <= node < n_nodes:
        raise ScenarioError(
            sc.path, key, f"node {node} does not exist (the mesh has nodes 0..{n_nodes - 1})"
        )
    return node % n_nodes
