"""Exudyn's ``ANCFCable2D`` with a curved reference, as an optional comparison column.

Exudyn is optional (``pip install 'rancf[bench]'``); :data:`AVAILABLE` says whether it imported.
The model mirrors ``benchmarks/exudyn_cases.py`` (``curved_pendulum``): one ``Cable2D`` per
element between ``NodePoint2DSlope1`` nodes at the exact node positions and unit tangents of the
conic, ``length`` the element's arc length, ``strainIsRelativeToReference = 1`` (the
Hermite cubic through the nodes is the stress-free reference), gravity as a mass-proportional
load, the first node pinned.  Exudyn uses the axial strain ``|r'| - 1`` and the curvature
``(r' × r'')_z / |r'|²`` (rancf: Green–Lagrange strain, ``/ |r'|³``), so its converged answer
differs from ours where the cable stretches noticeably; the study therefore measures it against
its own converged solution.
"""

from __future__ import annotations

from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.exudyn_compat import cable2d, dynamic_settings

try:
    import exudyn as exu

    AVAILABLE = True
    VERSION: str | None = exu.__version__
except ImportError:  # pragma: no cover - optional
    AVAILABLE = False
    VERSION = None

__all__ = ["AVAILABLE", "VERSION", "curved_pendulum_tip"]


def curved_pendulum_tip(
    nodes: NDArray,
    lengths: NDArray,
    solver: dict[str, Any],
    area: float,
    inertia: float,
    density: float,
    youngs: float,
    gravity: float = 9.81,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Simulate the pinned curved cable; returns the output times and the tip positions.

    Parameters
    ----------
    nodes : ndarray, shape (n_nodes, 2, 2)
        ``[position, unit tangent]`` per node.
    lengths : ndarray, shape (n_el,)
        Element arc lengths.
    solver : dict
        A scenario's ``[solver]`` table (``t_end``, ``step``, ``rho_inf``, ``output_step``).
    area, inertia, density, youngs : float
        Section and material.
    gravity : float
        Along ``-y``.

    Returns
    -------
    t : ndarray, shape (n_t,)
    tip : ndarray, shape (n_t, 2)
    """
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadMassProportional,
        MarkerBodyMass,
        MarkerNodeCoordinate,
        NodePoint2DSlope1,
        NodePointGround,
        SensorNode,
    )

    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    ids = [
        mbs.AddNode(NodePoint2DSlope1(referenceCoordinates=[*p, *s])) for p, s in np.asarray(nodes)
    ]
    for i, length in enumerate(lengths):
        obj = mbs.AddObject(
            cable2d(
                length=float(length),
                massPerLength=density * area,
                bendingStiffness=youngs * inertia,
                axialStiffness=youngs * area,
                strainIsRelativeToReference=1.0,
                nodeNumbers=[ids[i], ids[i + 1]],
            )
        )
        marker = mbs.AddMarker(MarkerBodyMass(bodyNumber=obj))
        mbs.AddLoad(LoadMassProportional(markerNumber=marker, loadVector=[0, -gravity, 0]))
    ground = mbs.AddNode(NodePointGround(referenceCoordinates=[0, 0, 0]))
    mg = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground, coordinate=0))
    for c in (0, 1):
        mn = mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ids[0], coordinate=c))
        mbs.AddObject(CoordinateConstraint(markerNumbers=[mg, mn]))
    sensor = mbs.AddSensor(
        SensorNode(
            nodeNumber=ids[-1],
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    mbs.Assemble()
    ss = dynamic_settings(
        solver["t_end"],
        solver["step"],
        solver["rho_inf"],
        sensors_write_period=solver["output_step"],
    )
    mbs.SolveDynamic(ss)
    data = np.asarray(mbs.GetSensorStoredData(sensor))
    return data[:, 0], data[:, 1:3]
