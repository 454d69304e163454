"""rancf: rational ANCF conic-section cable elements — geometry, CAD conversions and dynamics.

The public API, in pipeline order (geometry → mesh → model → solvers → results and plots), is
importable from the package itself, e.g. ``from rancf import conic_arc, mesh_conic, Model``.
Names are loaded on first use, so ``import rancf`` (and the command line's start) stays fast.
"""

from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.2.0"  # the single source of the version (pyproject reads it)

#: Public name -> module that defines it.
_API = {
    # geometry
    "conic_arc": "rancf.geometry.conic",
    "conic_arc_through": "rancf.geometry.conic",
    "circular_arc": "rancf.geometry.conic",
    "Conic": "rancf.geometry.conic_curve",
    "NurbsCurve": "rancf.geometry.nurbs",
    "RationalBezier": "rancf.geometry.bezier",
    # elements and conversions
    "kopt": "rancf.elements.mapping",
    "gradient_ratio": "rancf.elements.mapping",
    "conic_element": "rancf.elements.mapping",
    "bspline_to_ancf": "rancf.elements.cad",
    "nurbs_to_rancf": "rancf.elements.cad",
    "chain_to_nurbs": "rancf.elements.cad",
    # meshes
    "CableMesh": "rancf.mesh.mesh",
    "mesh_conic": "rancf.mesh.factories",
    "mesh_line": "rancf.mesh.factories",
    "mesh_nurbs": "rancf.mesh.nurbs_mesh",
    "to_ancf": "rancf.mesh.factories",
    # models and scenarios
    "Model": "rancf.bodies.flexible",
    "Section": "rancf.bodies.flexible",
    "Material": "rancf.bodies.flexible",
    "Support": "rancf.bodies.flexible",
    "PointLoad": "rancf.bodies.flexible",
    "StrainRateDamping": "rancf.bodies.properties",
    "Sensor": "rancf.scenario.sensors",
    "Scenario": "rancf.scenario",
    "load_scenario": "rancf.scenario",
    "parse_scenario": "rancf.scenario",
    "scenario_schema": "rancf.scenario",
    "TimeFunction": "rancf.bodies.time_function",
    # solvers
    "DynamicOptions": "rancf.solvers.dynamic",
    "DynamicResult": "rancf.solvers.dynamic",
    "DynamicStatus": "rancf.solvers.dynamic",
    "integrate": "rancf.solvers.dynamic",
    "DynamicState": "rancf.solvers.state",
    "simulate": "rancf.runs.simulate",
    "System": "rancf.system",
    "Joint": "rancf.system",
    "Spring": "rancf.system",
    "Load": "rancf.system",
    "RigidBody": "rancf.bodies.rigid",
    "PointMass": "rancf.bodies.rigid",
    "solve_static": "rancf.solvers.static",
    "find_form": "rancf.solvers.form",
    "natural_modes": "rancf.solvers.modal",
    # results and plots
    "sensor_table": "rancf.post.results",
    "write_run": "rancf.post.results",
    "load_results": "rancf.post.results",
    "plot_modes": "rancf.post.plots",
    "plot_conic": "rancf.post.conic_plots",
    # errors
    "RancfError": "rancf.errors",
    "InputError": "rancf.errors",
    "ScenarioError": "rancf.errors",
    "ConvergenceError": "rancf.errors",
}

__all__ = ["__version__", *_API]


def __getattr__(name: str) -> Any:
    if name in _API:
        value = getattr(importlib.import_module(_API[name]), name)
        globals()[name] = value
        return value
    raise AttributeError(f"module 'rancf' has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted(__all__)
