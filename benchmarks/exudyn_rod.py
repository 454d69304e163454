"""The rod benchmark problems in Exudyn: a chain of ``ObjectBeamGeometricallyExact`` (3D
Simo–Reissner beam on Euler-parameter rigid-body nodes), the independent peer of rancf's rod.

The beam has shear deformation; a shear stiffness ``shear`` times ``G A`` (default 100) makes it
nearly a Kirchhoff rod.  Its section inertia is ``ρ diag(I_p, s I, s I)``: ``rot_scale`` ``s``
= 1 is the full rotary inertia (rancf's ``rotary_inertia = "full"``), a small ``s`` (default
1e-3) leaves the spin only (rancf's default ``"torsion"``; ``s = 0`` would make the nodes'
rotational mass singular).  A curved reference is given by the nodes (points and local frames
``(t, n, t × n)``); the elements are 2-node, so gravity is lumped (consistent for them).
"""

from __future__ import annotations

import inspect
import time
from collections.abc import Callable, Sequence

import numpy as np

from rancf.exudyn_compat import dynamic_settings

try:
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadForceVector,
        MarkerNodeCoordinate,
        MarkerNodePosition,
        NodePointGround,
        NodeRigidBodyEP,
        ObjectBeamGeometricallyExact,
        SensorNode,
    )
    from exudyn.rigidBodyUtilities import (
        AngularVelocity2EulerParameters_t,
        RotationMatrix2EulerParameters,
    )

    AVAILABLE = True
except ImportError:  # pragma: no cover - optional
    AVAILABLE = False


def _length_key() -> str:
    """``length`` (Exudyn 1.12.258 on) or ``physicsLength`` (before)."""
    params = inspect.signature(ObjectBeamGeometricallyExact.__init__).parameters
    return "length" if "length" in params else "physicsLength"


def beam_chain(
    points: np.ndarray,
    tangents: np.ndarray,
    normal: Sequence[float],
    density: float,
    youngs: float,
    poisson: float,
    radius: float,
    gravity: Sequence[float],
    omega: Sequence[float] = (0.0, 0.0, 0.0),
    about: Sequence[float] = (0.0, 0.0, 0.0),
    rot_scale: float = 1e-3,
    shear: float = 100.0,
    tip_force: Callable[[float], list[float]] | None = None,
) -> tuple[object, object, list[int], int]:
    """A pinned (node 0, positions) chain of beams through ``points``; every node moves with the
    rigid velocity ``ω × (x − about)``.  Returns the system container, the system, the nodes and
    a sensor of the last node's position (stored internally)."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    area, inertia = np.pi * radius**2, np.pi * radius**4 / 4
    g_mod = youngs / (2 * (1 + poisson))
    sec = exu.BeamSection()
    sec.stiffnessMatrix = np.diag(
        [
            youngs * area,
            shear * g_mod * area,
            shear * g_mod * area,
            g_mod * 2 * inertia,
            youngs * inertia,
            youngs * inertia,
        ]
    )
    sec.inertia = density * np.diag([2 * inertia, rot_scale * inertia, rot_scale * inertia])
    sec.massPerLength = density * area
    w, c = np.asarray(omega, dtype=float), np.asarray(about, dtype=float)
    nodes = []
    for p, t in zip(points, tangents, strict=True):
        frame = np.column_stack([t, normal, np.cross(t, normal)])
        ep = RotationMatrix2EulerParameters(frame)
        vel = list(np.cross(w, p - c)) + list(AngularVelocity2EulerParameters_t(w, ep))
        node = NodeRigidBodyEP(referenceCoordinates=list(p) + list(ep), initialVelocities=vel)
        nodes.append(mbs.AddNode(node))
    seg = np.linalg.norm(np.diff(points, axis=0), axis=1)
    key = _length_key()
    for k, ln in enumerate(seg):
        beam = {"nodeNumbers": [nodes[k], nodes[k + 1]], key: float(ln), "sectionData": sec}
        mbs.AddObject(ObjectBeamGeometricallyExact(**beam))
    lumped = 0.5 * np.concatenate([[0.0], seg]) + 0.5 * np.concatenate([seg, [0.0]])
    for node, ln in zip(nodes, lumped, strict=True):
        mk = mbs.AddMarker(MarkerNodePosition(nodeNumber=node))
        load = list(density * area * ln * np.asarray(gravity))
        mbs.AddLoad(LoadForceVector(markerNumber=mk, loadVector=load))
    if tip_force is not None:
        mk = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1]))
        mbs.AddLoad(
            LoadForceVector(
                markerNumber=mk,
                loadVector=[0, 0, 0],
                loadVectorUserFunction=lambda _mbs, t, _load: tip_force(t),
            )
        )
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for i in range(3):
        mn = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=i))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mn]))
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=nodes[-1],
            outputVariableType=exu.OutputVariableType.Position,
            storeInternal=True,
        )
    )
    mbs.Assemble()
    return sc, mbs, nodes, sensor


def solve(
    mbs: object, sensor: int, t_end: float, step: float, rho_inf: float, out_step: float
) -> tuple[float, np.ndarray]:
    """Generalized-α (EigenSparse); returns the solve wall time and the sensor's ``(t, x, y, z)``
    rows at the output times."""
    ss = dynamic_settings(t_end, step, rho_inf, sparse=True, sensors_write_period=out_step)
    ss.timeIntegration.newton.relativeTolerance = 1e-8
    ss.timeIntegration.newton.absoluteTolerance = 1e-9
    t0 = time.perf_counter()
    mbs.SolveDynamic(ss)
    wall = time.perf_counter() - t0
    return wall, np.asarray(mbs.GetSensorStoredData(sensor))
