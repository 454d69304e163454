"""Exudyn's belt drive test ``TestModels/ANCFgeneralContactCircle.py`` (Exudyn 1.13.6), the peer
of ``belt_bench.py``: its model and settings as its test suite runs them, timed.

    python benchmarks/exudyn_belt.py [--t-end T] [--output-step S]

A closed belt of 32 ANCF cable elements (8 per half circle and per span; E = 1e10 Pa,
rho = 1000 kg/m^3, a 2 x 2 mm section, axial damping 1e-2 EA, pre-stretch 0.002, straight
reference elements, gravity) over two wheels of radius 0.5 m, 2 m apart (2 kg each, on
revolute joints): the left one driven by a torque of -20 N m, the right one braked by a
rotational damper of 1 N m s; GeneralContact between the cable and the wheels (stiffness 1e5
and damping 1e2 on each side, 8 segments per element, friction 0.5 with a proportional zone of
1 m/s); h = 1 ms, modified Newton, the sparse solver, one thread, as in the test (its test
length is 0.1 s).  Added for the comparison only: sensors of both wheels' angle and angular
velocity stored in memory every ``--output-step`` (rancf's output interval), no file output.

Prints one JSON line: ``setup_s`` (process start to the end of ``Assemble``), ``solve_s``,
``steps``, the test's own result (the belt's first node's x + y at the end: -0.58165 at
0.1 s in its test suite) and the wheels' final angles and angular velocities.
"""

from __future__ import annotations

import argparse
import json
import time
import warnings

T0 = time.perf_counter()

import exudyn as exu  # noqa: E402
import numpy as np  # noqa: E402
from exudyn.beams import (  # noqa: E402
    GenerateCircularArcANCFCable2D,
    GenerateStraightLineANCFCable2D,
)
from exudyn.itemInterface import (  # noqa: E402
    Cable2D,
    CoordinateSpringDamper,
    LoadTorqueVector,
    MarkerBodyRigid,
    MarkerNodeCoordinate,
    MarkerNodeRigid,
    NodePointGround,
    NodeRigidBody2D,
    ObjectGround,
    ObjectRigidBody2D,
    RevoluteJoint2D,
    SensorNode,
)
from exudyn.rigidBodyUtilities import InertiaCylinder  # noqa: E402


def build(mbs) -> tuple[list[int], int]:  # noqa: ANN001
    """The test's model (its variable values); the wheels' sensors and the belt's first node."""
    ground = mbs.AddObject(ObjectGround(referencePosition=[0, 0, 0]))
    n_ground = mbs.AddNode(NodePointGround())
    m_coord_ground = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=n_ground, coordinate=0))
    k, d, mu = 1e5, 1e-3 * 1e5, 0.5
    contact = mbs.AddGeneralContact()
    contact.verboseMode = 1
    contact.frictionProportionalZone = 1
    contact.ancfCableUseExactMethod = False
    contact.ancfCableNumberOfContactSegments = 8
    contact.SetSearchTreeCellSize(numberOfCells=[16, 8, 1])
    n_el, e_mod, rho, b, h = 8, 1e10, 1000.0, 0.002, 0.002
    area, inertia = b * h, b * h**3 / 12
    template = Cable2D(
        physicsMassPerLength=rho * area,
        physicsBendingStiffness=e_mod * inertia,
        physicsAxialStiffness=e_mod * area,
        physicsBendingDamping=0.0,
        physicsAxialDamping=1e-2 * e_mod * area,
        physicsReferenceAxialStrain=-0.002,
    )
    c0, c1, r0 = np.array([0.0, 0, 0]), np.array([2.0, 0, 0]), 0.5
    y = np.array([0, 1.0, 0])
    g = [0, -9.81, 0]
    parts = [
        GenerateCircularArcANCFCable2D(
            mbs,
            c0 - r0 * y,
            r0,
            -np.pi,
            -np.pi,
            n_el,
            template,
            massProportionalLoad=g,
            setCurvedReferenceConfiguration=False,
        )
    ]
    parts.append(
        GenerateStraightLineANCFCable2D(
            mbs,
            parts[-1][3][-1],
            c1 + r0 * y,
            n_el,
            template,
            massProportionalLoad=g,
            nodeNumber0=parts[-1][0][-1],
        )
    )
    parts.append(
        GenerateCircularArcANCFCable2D(
            mbs,
            parts[-1][3][-1],
            r0,
            0,
            -np.pi,
            n_el,
            template,
            massProportionalLoad=g,
            setCurvedReferenceConfiguration=False,
            nodeNumber0=parts[-1][0][-1],
        )
    )
    parts.append(
        GenerateStraightLineANCFCable2D(
            mbs,
            parts[-1][3][-1],
            parts[0][3][0],
            n_el,
            template,
            massProportionalLoad=g,
            nodeNumber0=parts[-1][0][-1],
            nodeNumber1=parts[0][0][0],
        )
    )
    sensors = []
    for i, centre in enumerate((c0, c1)):
        inertia_w = InertiaCylinder(2.0 / (r0**2 * np.pi * b), b, r0, axis=2)
        node = mbs.AddNode(
            NodeRigidBody2D(
                referenceCoordinates=[centre[0], centre[1], 0], initialVelocities=[0, 0, 0]
            )
        )
        mbs.AddObject(
            ObjectRigidBody2D(
                physicsMass=inertia_w.mass,
                physicsInertia=inertia_w.GetInertia6D()[2],
                nodeNumber=node,
            )
        )
        m_node = mbs.AddMarker(MarkerNodeRigid(nodeNumber=node))
        m_ground = mbs.AddMarker(MarkerBodyRigid(bodyNumber=ground, localPosition=centre))
        mbs.AddObject(RevoluteJoint2D(markerNumbers=[m_ground, m_node]))
        if i == 0:
            mbs.AddLoad(LoadTorqueVector(markerNumber=m_node, loadVector=[0, 0, -20]))
        else:
            m_coord = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=2))
            mbs.AddObject(
                CoordinateSpringDamper(markerNumbers=[m_coord_ground, m_coord], damping=1.0)
            )
        contact.AddSphereWithMarker(
            m_node, radius=r0, contactStiffness=k, contactDamping=d, frictionMaterialIndex=0
        )
        for kind in (exu.OutputVariableType.Rotation, exu.OutputVariableType.AngularVelocity):
            sensors.append(
                mbs.AddSensor(
                    SensorNode(nodeNumber=node, storeInternal=True, outputVariableType=kind)
                )
            )
    for part in parts:
        for obj in part[1]:
            contact.AddANCFCable(
                objectIndex=obj,
                halfHeight=0.0,
                contactStiffness=k,
                contactDamping=d,
                frictionMaterialIndex=0,
            )
    contact.SetFrictionPairings(np.array([[mu]]))
    return sensors, parts[0][0][0]


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--t-end", type=float, default=0.1)
    p.add_argument("--output-step", type=float, default=0.01)
    a = p.parse_args()
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    sensors, node0 = build(mbs)
    mbs.Assemble()
    ss = exu.SimulationSettings()
    h = 1e-3
    with warnings.catch_warnings():  # the name the test uses (deprecated since)
        warnings.simplefilter("ignore", DeprecationWarning)
        ss.linearSolverType = exu.LinearSolverType.EigenSparse
        ss.solutionSettings.writeSolutionToFile = False
        ss.solutionSettings.sensorsWritePeriod = a.output_step
    ss.parallel.numberOfThreads = 1
    ss.timeIntegration.endTime = a.t_end
    ss.timeIntegration.numberOfSteps = round(a.t_end / h)
    ss.timeIntegration.verboseMode = 0
    ss.timeIntegration.newton.useModifiedNewton = True
    t1 = time.perf_counter()
    mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    pos = mbs.GetNodeOutput(node0, variableType=exu.OutputVariableType.Position)
    last = [float(mbs.GetSensorStoredData(s)[-1, -1]) for s in sensors]
    print(
        json.dumps(
            {
                "setup_s": t1 - T0,
                "solve_s": t2 - t1,
                "steps": ss.timeIntegration.numberOfSteps,
                "node0_x_plus_y": float(pos[0] + pos[1]),
                "angles": [last[0], last[2]],
                "rates": [last[1], last[3]],
            }
        )
    )


if __name__ == "__main__":
    main()
