"""The flexible slider-crank in Exudyn (the peer of rancf's).

    python benchmarks/exudyn_slider_crank.py --elements N [--step H] [--t-end T]
        [--element ancf|beam] [--rho-inf R] [--crank-mass M] [--crank-inertia J]
        [--user-functions symbolic|python]

A rigid crank of 0.15 m turns about the origin with the prescribed angle
(``exudyn_cases.spin_up``, Os = 150 rad/s, Ts = 0.05 s); a flexible steel connecting rod of
0.30 m (E = 2e11 Pa, rho = 7870 kg/m^3, circular section of diameter 6 mm) is pinned to the crank
tip and to a slider of 0.033 kg that moves on the x axis; no gravity; at t = 0 everything is at
rest, the crank along +x and the rod straight from (0.15, 0) to (0.45, 0).  Generalized-alpha
with rho_inf = 0.9 (``--rho-inf``), fixed step.

The crank is an ``ObjectRigidBody2D`` whose node sits at the pivot (the origin) with its position
held and its angle prescribed (``CoordinateConstraint`` with offset user functions: Exudyn's
symbolic user functions by default, Python callbacks with ``--user-functions python``): its motion
is given, so its mass and inertia (``--crank-mass``, ``--crank-inertia``, default 1 kg and
1 kg m^2, not given by the issue) change only the motor torque, not the motion (check: run with
other values).  The rod is ``ObjectANCFCable2D`` (``--element ancf``, default) or Exudyn's
geometrically exact beam (``--element beam``, shear stiffness ``--shear-stiffness``, default
k G A with k = 0.9 and nu = 0.3); it is pinned to the crank tip and to the slider
(``ObjectJointRevolute2D``); the slider is an ``ObjectMassPoint2D`` whose y is held at 0.
Newton: absolute tolerance 1e-13 * EA * elements [N] (above the residual's round-off; Exudyn's
default does not converge on stiff rods, see ``exudyn_spinup.py``), no adaptive step.

Convergence (ANCF, rho_inf = 0.9; slider x [m] and midpoint deflection [m] at 0.05 .. 0.2 s):

    16 el, h = 1e-5   0.1643942  0.3002164  0.4489003  0.3336058
                      -4.77887e-4  -2.73077e-3  -5.92989e-4  3.44866e-3
    16 el, h = 5e-6   -4.77885e-4  -2.73074e-3  -5.93014e-4  3.44862e-3
    32 el, h = 5e-6   -4.77885e-4  -2.73075e-3  -5.93009e-4  3.44863e-3

16 elements and h = 1e-5 s are within 4e-8 m of the finest run (8 elements: 1.2e-7 m; 4
elements and h = 1e-4 s: 2e-6 m); rho_inf = 0.6 moves them by 3e-8 m; another crank mass and
inertia (0.5 kg, 0.004 kg m^2) by less than 1e-12 m.  The geometrically exact beam
(``--element beam``; 32, 64, 128 elements, h = 1e-5 s, second order in n) extrapolates to
deflections within 0.2 % of these, mostly from its shear flexibility: 100 times the shear
stiffness moves its deflections at 64 elements by up to 0.15 % toward the ANCF values.

Prints one JSON line: ``setup_s``, ``solve_s``, ``steps``, and at t = 0.05, 0.1, 0.15, 0.2 s
(``--t-end`` permitting; linear interpolation where a time is not a step) the slider's x and the
rod midpoint's deflection from the chord of the rod's ends, positive to the left of the chord
from the crank end to the slider end: ``d = (r_mid - (r_A + r_B) / 2) . e_z x (r_B - r_A) / |r_B -
r_A|`` (needs an even number of elements).
"""

from __future__ import annotations

import argparse
import json
import math
import time

T0 = time.perf_counter()

import exudyn as exu  # noqa: E402
import numpy as np  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    MarkerBodyPosition,
    MarkerNodePosition,
    NodePoint2D,
    NodePoint2DSlope1,
    NodeRigidBody2D,
    ObjectJointRevolute2D,
    SensorNode,
)
from exudyn_cases import hold, spin_up_drive  # noqa: E402

from rancf.exudyn_compat import dynamic_settings, item  # noqa: E402

CRANK, ROD = 0.15, 0.30
YOUNGS, DENSITY, DIAMETER = 2.0e11, 7870.0, 0.006
SLIDER_MASS = 0.033
OMEGA_S, T_S = 150.0, 0.05
TIMES = (0.05, 0.1, 0.15, 0.2)
#: Newton's absolute tolerance on the residual [N] per unit of EA * elements (EA / le * L).
NEWTON_TOL = 1e-13


def build(a: argparse.Namespace) -> tuple[object, object, list[int], int, float, tuple]:
    """The mechanism: the container, the system, the rod's nodes, the slider's node, the rod's
    EA and the drive's user functions (they must outlive the system)."""
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    drive = spin_up_drive(mbs, OMEGA_S, T_S, a.user_functions == "symbolic")
    area = math.pi * DIAMETER**2 / 4.0
    inertia = math.pi * DIAMETER**4 / 64.0
    ea, ei, rho_a = YOUNGS * area, YOUNGS * inertia, DENSITY * area

    crank_node = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
    crank = mbs.AddObject(
        item(
            "ObjectRigidBody2D",
            nodeNumber=crank_node,
            mass=a.crank_mass,
            inertia=a.crank_inertia,
        )
    )
    hold(mbs, crank_node, 0)
    hold(mbs, crank_node, 1)
    hold(mbs, crank_node, 2, drive)

    n, le = a.elements, ROD / a.elements
    xs = [CRANK + i * le for i in range(n + 1)]
    if a.element == "beam":
        rod = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0, 0])) for x in xs]
        params = dict(
            length=le,
            massPerLength=rho_a,
            crossSectionInertia=DENSITY * inertia,
            bendingStiffness=ei,
            axialStiffness=ea,
            shearStiffness=a.shear_stiffness or 0.9 * YOUNGS / 2.6 * area,
        )
        name = "ObjectBeamGeometricallyExact2D"
    else:
        rod = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[x, 0, 1, 0])) for x in xs]
        params = dict(length=le, massPerLength=rho_a, bendingStiffness=ei, axialStiffness=ea)
        name = "Cable2D"
    for p, q in zip(rod[:-1], rod[1:], strict=True):
        mbs.AddObject(item(name, nodeNumbers=[p, q], **params))

    slider = mbs.AddNode(NodePoint2D(referenceCoordinates=[CRANK + ROD, 0]))
    mbs.AddObject(item("ObjectMassPoint2D", nodeNumber=slider, mass=SLIDER_MASS))
    hold(mbs, slider, 1)

    tip = mbs.AddMarker(MarkerBodyPosition(bodyNumber=crank, localPosition=[CRANK, 0, 0]))
    for pair in (
        [tip, mbs.AddMarker(MarkerNodePosition(nodeNumber=rod[0]))],
        [
            mbs.AddMarker(MarkerNodePosition(nodeNumber=rod[-1])),
            mbs.AddMarker(MarkerNodePosition(nodeNumber=slider)),
        ],
    ):
        mbs.AddObject(ObjectJointRevolute2D(markerNumbers=pair))
    return sc, mbs, rod, slider, ea, drive


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--elements", type=int, required=True)
    p.add_argument("--step", type=float, default=1e-5)
    p.add_argument("--t-end", type=float, default=0.2)
    p.add_argument("--element", choices=["ancf", "beam"], default="ancf")
    p.add_argument("--rho-inf", type=float, default=0.9)
    p.add_argument("--crank-mass", type=float, default=1.0)
    p.add_argument("--crank-inertia", type=float, default=1.0)
    p.add_argument("--shear-stiffness", type=float, default=None)
    p.add_argument("--solver", choices=["dense", "sparse"], default="dense")
    p.add_argument("--output-step", type=float, default=None, help="sensor interval (every step)")
    p.add_argument("--newton-tol", type=float, default=None)
    p.add_argument("--user-functions", choices=["symbolic", "python"], default="symbolic")
    a = p.parse_args()
    if a.elements < 2 or a.elements % 2:
        p.error(f"--elements {a.elements}: an even number >= 2 (the rod's midpoint is a node)")
    sc, mbs, rod, slider, ea, drive = build(a)
    watched = [rod[0], rod[len(rod) // 2], rod[-1], slider]
    sensors = [
        mbs.AddSensor(
            SensorNode(
                nodeNumber=node,
                storeInternal=True,
                writeToFile=False,
                outputVariableType=exu.OutputVariableType.Position,
            )
        )
        for node in watched
    ]
    mbs.Assemble()
    sparse = a.solver == "sparse"
    every = a.output_step or a.step
    ss = dynamic_settings(a.t_end, a.step, a.rho_inf, sparse, sensors_write_period=every)
    ss.timeIntegration.newton.absoluteTolerance = a.newton_tol or NEWTON_TOL * ea * a.elements
    ss.timeIntegration.adaptiveStep = False
    t1 = time.perf_counter()
    ok = mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    data = [np.asarray(mbs.GetSensorStoredData(s)) for s in sensors]
    t = data[0][:, 0]
    start, mid, end, slide = (d[:, 1:3] for d in data)
    chord = end - start
    normal = np.column_stack([-chord[:, 1], chord[:, 0]]) / np.linalg.norm(chord, axis=1)[:, None]
    deflection = np.einsum("ij,ij->i", mid - 0.5 * (start + end), normal)
    times = [s for s in TIMES if s <= t[-1] + 1e-12]
    out = {
        "element": a.element,
        "elements": a.elements,
        "step": a.step,
        "rho_inf": a.rho_inf,
        "crank_mass": a.crank_mass,
        "crank_inertia": a.crank_inertia,
        "user_functions": a.user_functions,
        "converged": bool(ok),
        "setup_s": t1 - T0,
        "solve_s": t2 - t1,
        "steps": int(ss.timeIntegration.numberOfSteps),
        "times": times,
        "slider_x": [float(np.interp(s, t, slide[:, 0])) for s in times],
        "deflection": [float(np.interp(s, t, deflection)) for s in times],
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
