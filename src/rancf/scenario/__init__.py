"""Typed models of the scenario format: one description for TOML files and Python.

``Scenario`` (:mod:`rancf.scenario.scenario`) holds the tables, one module per family:
:mod:`~rancf.scenario.geometry` (geometry, mesh), :mod:`~rancf.scenario.section` (section,
material),
:mod:`~rancf.scenario.loads` (supports, loads, time functions, damping, initial motion),
:mod:`~rancf.scenario.bodies` (flexible, rigid and point-mass bodies),
:mod:`~rancf.scenario.joints` (joints and springs), :mod:`~rancf.scenario.solver` (solver,
modes), :mod:`~rancf.scenario.sensors`; places in :mod:`~rancf.scenario.places`, the checks
across tables in :mod:`~rancf.scenario.checks`, errors in :mod:`~rancf.scenario.messages`, the
model builder in :mod:`~rancf.scenario.build`, the JSON Schema in
:mod:`~rancf.scenario.schema`, and a one-body file written as one ``[[bodies]]`` table in
:mod:`~rancf.scenario.convert`.
"""

from rancf.bodies.time_function import TimeFunction
from rancf.scenario.bodies import FlexibleBody, PointMass, RigidBody
from rancf.scenario.convert import as_bodies
from rancf.scenario.damping import DampingTable, StrainRateDampingTable
from rancf.scenario.geometry import (
    CadGeometry,
    ConicGeometry,
    LineGeometry,
    MeshTable,
    NurbsGeometry,
)
from rancf.scenario.joints import JointTable, SpringTable
from rancf.scenario.loads import (
    InitialMotionTable,
    InitialVelocityTable,
    LoadsTable,
    PointLoadTable,
    SupportTable,
)
from rancf.scenario.places import ResolvedPlace
from rancf.scenario.scenario import Scenario, load_scenario, parse_scenario
from rancf.scenario.schema import scenario_schema
from rancf.scenario.section import MaterialTable, SectionTable
from rancf.scenario.sensors import Sensor, SensorTable
from rancf.scenario.solver import ModesTable, SolverTable
from rancf.scenario.time_functions import (
    HarmonicFunction,
    RampFunction,
    SpinUpFunction,
    TableFunction,
)

__all__ = [
    "Scenario",
    "load_scenario",
    "parse_scenario",
    "as_bodies",
    "scenario_schema",
    "TimeFunction",
    "Sensor",
    "ResolvedPlace",
    "ConicGeometry",
    "LineGeometry",
    "NurbsGeometry",
    "CadGeometry",
    "MeshTable",
    "SectionTable",
    "MaterialTable",
    "FlexibleBody",
    "RigidBody",
    "PointMass",
    "JointTable",
    "SpringTable",
    "SupportTable",
    "LoadsTable",
    "PointLoadTable",
    "DampingTable",
    "StrainRateDampingTable",
    "InitialVelocityTable",
    "InitialMotionTable",
    "TableFunction",
    "RampFunction",
    "HarmonicFunction",
    "SpinUpFunction",
    "SolverTable",
    "ModesTable",
    "SensorTable",
]
