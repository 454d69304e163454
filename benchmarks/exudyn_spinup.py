"""The spin-up of a flexible beam (Kane, Ryan & Banerjee 1987) in Exudyn (the peer of rancf's).

    python benchmarks/exudyn_spinup.py --elements N [--step H] [--t-end T]
        [--element ancf|beam] [--rho-inf R] [--solver dense|sparse]
        [--user-functions symbolic|python]

L = 10 m, EA = 2.8e7 N, EI = 1.4e4 N m^2, rhoA = 1.2 kg/m, no gravity.  The root is clamped to a
hub at the origin whose angle is prescribed (``exudyn_cases.spin_up``, Os = 6 rad/s, Ts = 15 s);
the beam is straight along x and at rest at t = 0.  Generalized-alpha with rho_inf = 0.9
(``--rho-inf``).

``--element ancf`` (default): ``ObjectANCFCable2D``; the hub is a ``NodeRigidBody2D`` whose angle
a ``CoordinateConstraint`` with offset user functions prescribes (``--user-functions symbolic``,
default: Exudyn's symbolic user functions, evaluated in C++; ``python``: Python callbacks, same
results, slower), and the cable's first node is
held at the origin (two ``CoordinateConstraint``) with its slope direction locked to the hub's
frame (``ObjectJointGeneric``, rotation about z only): a clamp that leaves the root's axial strain
free.  ``--element beam``: Exudyn's geometrically exact 2D beam (``ObjectBeamGeometricallyExact2D``,
shear stiffness ``--shear-stiffness``, default EA), whose first node's angle is prescribed directly.

Newton: Exudyn's default tolerances (relative 1e-8 of the first residual of a step, absolute 1e-10)
are below the round-off of this stiff problem's residual (about 1e-8 N at 8 elements), so Newton
"fails" and Exudyn's adaptive step silently halves the step (about 80,000 steps instead of 2,000 at
h = 0.01 s, 30 times slower).  Here the absolute tolerance is 1e-13 EA n [N] (n elements: 4.5e-5 N
at 16; it moves the results by < 1e-10 m against 1e-6 N) and the step is fixed
(``adaptiveStep = False``): a failing step stops the run instead of changing the step.

Convergence (ANCF, rho_inf = 0.9; v_5, v_10, min v [m], its time [s]):

    16 el, h = 2e-3     -0.468444  -0.362800  -0.573800  6.7620
    16 el, h = 1e-3     -0.468442  -0.362773  -0.573790  6.7619
    16 el, h = 5e-4     -0.468442  -0.362767  -0.573787  6.7618
    16 el, h = 2.5e-4   -0.468442  -0.362765  -0.573787  6.7618
    32 el, h = 2.5e-4   -0.468442  -0.362766  -0.573787  6.7618

The step dominates (second order); 8 elements are 2e-5 m off 16.  The geometrically exact beam
(``--element beam``, 128 elements, h = 1e-3; linear elements converge slowly in n) gives
-0.468457, -0.362799, -0.573812, 6.7620: within 5e-5 relative (its shear and rotary inertia).

Prints one JSON line: ``setup_s`` (script start, imports included, to the end of ``Assemble``),
``solve_s`` (``SolveDynamic``), ``steps``, and the results from the tip's position stored at every
step: the deflection from the rotating chord ``v = -sin(theta) x + cos(theta) y`` at 5 s and 10 s
(linear interpolation between steps where 5 or 10 s is not a step; null after the end), its
minimum and the minimum's time (the parabola through the smallest stored value and its two
neighbours; the value itself at an end of the run), and at the end of the run the
elongation of the beam (the integral of the axial strain, Gauss points; ``stretch``) and the radial
tip displacement ``|r_tip| - L`` against the quasi-static rhoA Os^2 L^3 / (3 EA) = 5.143e-4 m.
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
    MarkerNodeRigid,
    NodePoint2DSlope1,
    NodeRigidBody2D,
    ObjectJointGeneric,
    SensorNode,
)
from exudyn_cases import hold, spin_up, spin_up_drive  # noqa: E402

from rancf.exudyn_compat import dynamic_settings, item  # noqa: E402

LENGTH, EA, EI, RHO_A = 10.0, 2.8e7, 1.4e4, 1.2
OMEGA_S, T_S = 6.0, 15.0
#: Newton's absolute tolerance on the residual [N] per unit of EA * elements (EA / le * L).
NEWTON_TOL = 1e-13


def theta(t: float) -> tuple[float, float]:
    """Hub angle and rate at ``t``: the spin-up law with Os = 6 rad/s, Ts = 15 s."""
    return spin_up(t, OMEGA_S, T_S)


def build(
    n: int, element: str, shear_stiffness: float, symbolic: bool
) -> tuple[object, object, list[int], list, tuple]:
    """The beam of ``n`` elements clamped to the driven hub.

    Returns the container, the system, the nodes, the elements and the drive's user functions
    (they must outlive the system).
    """
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    drive = spin_up_drive(mbs, OMEGA_S, T_S, symbolic)
    le = LENGTH / n
    xs = [i * le for i in range(n + 1)]
    if element == "beam":
        nodes = [mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[x, 0, 0])) for x in xs]
        params = dict(
            length=le,
            massPerLength=RHO_A,
            crossSectionInertia=RHO_A * EI / EA,  # rho I = rhoA * I / A
            bendingStiffness=EI,
            axialStiffness=EA,
            shearStiffness=shear_stiffness,
        )
        objs = [
            mbs.AddObject(item("ObjectBeamGeometricallyExact2D", nodeNumbers=[a, b], **params))
            for a, b in zip(nodes[:-1], nodes[1:], strict=True)
        ]
        hold(mbs, nodes[0], 0)
        hold(mbs, nodes[0], 1)
        hold(mbs, nodes[0], 2, drive)
    else:
        nodes = [mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[x, 0, 1, 0])) for x in xs]
        params = dict(length=le, massPerLength=RHO_A, bendingStiffness=EI, axialStiffness=EA)
        objs = [
            mbs.AddObject(item("Cable2D", nodeNumbers=[a, b], **params))
            for a, b in zip(nodes[:-1], nodes[1:], strict=True)
        ]
        hub = mbs.AddNode(NodeRigidBody2D(referenceCoordinates=[0, 0, 0]))
        # the hub's mass and inertia do not matter: all its coordinates are prescribed
        mbs.AddObject(item("ObjectRigidBody2D", nodeNumber=hub, mass=1.0, inertia=1.0))
        for c in (0, 1):
            hold(mbs, hub, c)
            hold(mbs, nodes[0], c)
        hold(mbs, hub, 2, drive)
        markers = [
            mbs.AddMarker(MarkerNodeRigid(nodeNumber=hub)),
            mbs.AddMarker(MarkerNodeRigid(nodeNumber=nodes[0])),
        ]
        mbs.AddObject(ObjectJointGeneric(markerNumbers=markers, constrainedAxes=[0, 0, 0, 0, 0, 1]))
    return sc, mbs, nodes, objs, drive


def elongation(mbs: object, objs: list, le: float) -> float:
    """The integral of the axial strain over the beam (5 Gauss points per element) [m]."""
    xg, wg = np.polynomial.legendre.leggauss(5)
    total = 0.0
    for obj in objs:
        # the cable's local x runs over [0, le], the geometrically exact beam's over [-le/2, le/2]
        x0 = 0.0 if "ANCF" in str(mbs.GetObject(obj)["objectType"]) else -0.5 * le
        for x, w in zip(xg, wg, strict=True):
            local = [x0 + 0.5 * le * (x + 1.0), 0.0, 0.0]
            strain = mbs.GetObjectOutputBody(obj, exu.OutputVariableType.StrainLocal, local)
            total += 0.5 * le * w * float(np.ravel(strain)[0])
    return total


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--elements", type=int, required=True)
    p.add_argument("--step", type=float, default=1e-3)
    p.add_argument("--t-end", type=float, default=20.0)
    p.add_argument("--element", choices=["ancf", "beam"], default="ancf")
    p.add_argument("--rho-inf", type=float, default=0.9)
    p.add_argument("--shear-stiffness", type=float, default=EA)
    p.add_argument("--solver", choices=["dense", "sparse"], default="dense")
    p.add_argument("--output-step", type=float, default=None, help="sensor interval (every step)")
    p.add_argument("--newton-tol", type=float, default=None)
    p.add_argument("--user-functions", choices=["symbolic", "python"], default="symbolic")
    a = p.parse_args()
    symbolic = a.user_functions == "symbolic"
    sc, mbs, nodes, objs, drive = build(a.elements, a.element, a.shear_stiffness, symbolic)
    tip = mbs.AddSensor(
        SensorNode(
            nodeNumber=nodes[-1],
            storeInternal=True,
            writeToFile=False,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    mbs.Assemble()
    sparse = a.solver == "sparse"
    every = a.output_step or a.step
    ss = dynamic_settings(a.t_end, a.step, a.rho_inf, sparse, sensors_write_period=every)
    ss.timeIntegration.newton.absoluteTolerance = a.newton_tol or NEWTON_TOL * EA * a.elements
    ss.timeIntegration.adaptiveStep = False
    t1 = time.perf_counter()
    ok = mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    data = np.asarray(mbs.GetSensorStoredData(tip))
    t, x, y = data[:, 0], data[:, 1], data[:, 2]
    th = np.array([theta(ti)[0] for ti in t])
    v = -np.sin(th) * x + np.cos(th) * y
    k = int(np.argmin(v))
    if 0 < k < len(v) - 1:  # the parabola through the smallest value and its neighbours
        c2, c1, c0 = np.polyfit(t[k - 1 : k + 2] - t[k], v[k - 1 : k + 2], 2)
        t_min, v_min = t[k] - c1 / (2.0 * c2), c0 - c1 * c1 / (4.0 * c2)
    else:  # at an end of the run
        t_min, v_min = t[k], v[k]
    out = {
        "element": a.element,
        "elements": a.elements,
        "step": a.step,
        "rho_inf": a.rho_inf,
        "user_functions": a.user_functions,
        "converged": bool(ok),
        "t_end": float(t[-1]),
        "setup_s": t1 - T0,
        "solve_s": t2 - t1,
        "steps": int(ss.timeIntegration.numberOfSteps),
        "v_5": float(np.interp(5.0, t, v)) if t[-1] >= 5.0 else None,
        "v_10": float(np.interp(10.0, t, v)) if t[-1] >= 10.0 else None,
        "v_min": float(v_min),
        "t_min": float(t_min),
        "stretch": elongation(mbs, objs, LENGTH / a.elements),
        "tip_radial": float(math.hypot(x[-1], y[-1]) - LENGTH),
        "stretch_quasi_static": RHO_A * OMEGA_S**2 * LENGTH**3 / (3.0 * EA),
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
