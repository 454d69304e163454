"""The benchmark problems built in Exudyn (optional: ``pip install .[bench]``).

Exudyn's ``ObjectANCFCable2D`` uses the axial strain ``|r'| - 1`` and the material curvature
``(r' x r'')_z / |r'|^2``; rancf uses the Green–Lagrange strain and the geometric curvature
``(r' x r'')_z / |r'|^3``.  At small strain they agree; the soft pendulum (E = 0.7 MPa) reaches
about 20 % strain, where they are different materials, so converged tip positions differ.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from typing import Any

import numpy as np

from rancf.exudyn_compat import cable2d, dynamic_settings, quiet_settings, straight_cable2d

try:
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadForceVector,
        LoadMassProportional,
        MarkerBodyMass,
        MarkerNodeCoordinate,
        MarkerNodePosition,
        NodePoint2DSlope1,
        NodePointGround,
    )

    AVAILABLE = True
    VERSION = exu.__version__
except ImportError:  # pragma: no cover - optional
    AVAILABLE = False
    VERSION = None


def _spin_up(t: Any, omega_s: float, t_s: float, m: Any) -> tuple[Any, Any]:
    """The spin-up law on numbers (``m = math``) or on Exudyn's symbolic reals (``exu.symbolic``).

    theta = (Os/Ts) [t^2/2 + (Ts/2pi)^2 (cos(2pi t/Ts) - 1)] for t <= Ts, Os (t - Ts/2) after;
    the rate rises smoothly from 0 to Os (zero acceleration at 0 and Ts).
    """
    c = t_s / (2.0 * math.pi)
    select = getattr(m, "IfThenElse", lambda cond, a, b: a if cond else b)
    angle = select(
        t <= t_s,
        omega_s / t_s * (0.5 * t * t + c * c * (m.cos(t / c) - 1.0)),
        omega_s * (t - 0.5 * t_s),
    )
    rate = select(t <= t_s, omega_s / t_s * (t - c * m.sin(t / c)), omega_s + 0.0 * t)
    return angle, rate


def spin_up(t: float, omega_s: float, t_s: float) -> tuple[float, float]:
    """Angle [rad] and angular velocity [rad/s] of the spin-up (Kane, Ryan & Banerjee 1987)."""
    return _spin_up(t, omega_s, t_s, math)


def spin_up_drive(mbs: Any, omega_s: float, t_s: float, symbolic: bool) -> tuple[Any, Any]:
    """``offsetUserFunction`` and ``offsetUserFunction_t`` of a ``CoordinateConstraint`` that
    drives a coordinate by the spin-up angle: Python functions, or (``symbolic``) Exudyn's
    symbolic user functions, evaluated in C++ without calling Python (``exudyn.advancedUtilities
    .CreateSymbolicUserFunction``; keep them alive as long as ``mbs``)."""
    if not symbolic:
        return (
            lambda mbs, t, item, offset: spin_up(t, omega_s, t_s)[0],
            lambda mbs, t, item, offset: spin_up(t, omega_s, t_s)[1],
        )
    from exudyn.advancedUtilities import CreateSymbolicUserFunction

    def component(k: int) -> Any:  # Exudyn checks the user function's exact arguments
        return lambda mbs, t, itemNumber, lOffset: _spin_up(t, omega_s, t_s, exu.symbolic)[k]

    return tuple(
        CreateSymbolicUserFunction(
            mbs, component(k), name, itemTypeName="ObjectConnectorCoordinate"
        )
        for k, name in enumerate(("offsetUserFunction", "offsetUserFunction_t"))
    )


def hold(mbs: Any, node: int, coordinate: int, drive: tuple[Any, Any] | None = None) -> None:
    """Hold ``coordinate`` of ``node`` at its reference value, or move it by ``drive``.

    ``drive``: the offset user function and its time derivative (:func:`spin_up_drive`) of a
    ``CoordinateConstraint`` to the ground (Exudyn's coordinate constraints act on the
    displacement from the reference value, not on the value).
    """
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    markers = [
        mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0)),
        mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=node, coordinate=coordinate)),
    ]
    if drive is None:
        mbs.AddObject(CoordinateConstraint(markerNumbers=markers))
        return
    mbs.AddObject(
        CoordinateConstraint(
            markerNumbers=markers, offsetUserFunction=drive[0], offsetUserFunction_t=drive[1]
        )
    )


def straight_cable(
    n: int,
    length: float,
    rho_a: float,
    ei: float,
    ea: float,
    fixed: list[int],
    gravity: Sequence[float] = (0.0, 0.0, 0.0),
) -> tuple[object, object, list[int]]:
    """A straight ANCFCable2D chain along x; ``fixed`` constrains node 0 (x, y, x', y').

    The system container is returned too: it must outlive the system.
    """
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    cable = cable2d(massPerLength=rho_a, bendingStiffness=ei, axialStiffness=ea)
    nodes = straight_cable2d(mbs, [0, 0, 0], [length, 0, 0], n, cable, gravity, fixed)
    return sc, mbs, nodes


def straight_pendulum(
    n: int,
    t_end: float,
    step: float,
    rho_inf: float = 0.9,
    length: float = 1.2,
    area: float = 0.0018,
    inertia: float = 1.215e-8,
    density: float = 5540.0,
    youngs: float = 0.7e6,
    sparse: bool = False,
) -> tuple[float, np.ndarray]:
    """Pinned pendulum released horizontal; returns (wall time of the solve, tip position).

    ``sparse`` selects Exudyn's EigenSparse linear solver instead of its dense default.
    """
    sc, mbs, nodes = straight_cable(
        n, length, density * area, youngs * inertia, youngs * area, [1, 1, 0, 0], [0, -9.81, 0]
    )
    mbs.Assemble()
    ss = dynamic_settings(t_end, step, rho_inf, sparse)
    t0 = time.perf_counter()
    mbs.SolveDynamic(ss)
    wall = time.perf_counter() - t0
    return wall, np.array(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position))[:2]


def static_cantilever(
    n: int,
    force: float,
    load_steps: int,
    length: float,
    area: float,
    inertia: float,
    youngs: float,
) -> tuple[float, np.ndarray]:
    """Clamped cantilever (position and slope direction fixed) with a vertical tip load."""
    sc, mbs, nodes = straight_cable(n, length, 1.0, youngs * inertia, youngs * area, [1, 1, 0, 1])
    marker = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1]))
    mbs.AddLoad(LoadForceVector(markerNumber=marker, loadVector=[0, -force, 0]))
    mbs.Assemble()
    ss = quiet_settings()
    ss.staticSolver.numberOfLoadSteps = load_steps
    ss.staticSolver.verboseMode = 0
    t0 = time.perf_counter()
    mbs.SolveStatic(ss)
    wall = time.perf_counter() - t0
    return wall, np.array(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position))[:2]


def curved_pendulum(
    points: Sequence[Sequence[float]],
    slopes: Sequence[Sequence[float]],
    lengths: Sequence[float],
    t_end: float,
    step: float,
    rho_inf: float,
    area: float,
    inertia: float,
    density: float,
    youngs: float,
) -> tuple[float, np.ndarray]:
    """A pinned cable whose stress-free reference is given by node points and unit slopes.

    Uses Exudyn's curved-reference option ``strainIsRelativeToReference = 1``.
    """
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    nodes = [
        mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[p[0], p[1], s[0], s[1]]))
        for p, s in zip(points, slopes, strict=True)
    ]
    for i, length in enumerate(lengths):
        obj = mbs.AddObject(
            cable2d(
                length=length,
                massPerLength=density * area,
                bendingStiffness=youngs * inertia,
                axialStiffness=youngs * area,
                strainIsRelativeToReference=1.0,
                nodeNumbers=[nodes[i], nodes[i + 1]],
            )
        )
        mbs.AddLoad(
            LoadMassProportional(
                markerNumber=mbs.AddMarker(MarkerBodyMass(bodyNumber=obj)), loadVector=[0, -9.81, 0]
            )
        )
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for c in (0, 1):
        mn = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=nodes[0], coordinate=c))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mn]))
    mbs.Assemble()
    ss = dynamic_settings(t_end, step, rho_inf)
    t0 = time.perf_counter()
    mbs.SolveDynamic(ss)
    wall = time.perf_counter() - t0
    return wall, np.array(mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position))[:2]
