"""A cable falling onto a fixed circle in Exudyn (``ObjectContactFrictionCircleCable2D``), the
peer of ``contact_cost.py``'s rancf case.

    python benchmarks/exudyn_contact_circle.py --elements N [--t-end T] [--solver dense|sparse]

A 2 m steel cable (radius 2 mm, E = 2e11 Pa, rho = 7850 kg/m^3) along +x from the origin, pinned
there, falls under gravity onto a fixed circle of radius 0.2 m centred at (1, -0.3)
(frictionless, contact stiffness 1e7 N/m^2 per unit length, no damping), 1 ms steps,
generalized-alpha rho_inf = 0.6, Newton's absolute tolerance 1e-13 EA n_el [N].
``ObjectANCFCable2D`` elements, 8 contact segments per element, the circle's radius that of
the cable's centre line (R + r), as rancf's tube contact.

Prints one JSON line: ``setup_s`` (process start to the end of ``Assemble``), ``solve_s``,
``steps`` and the cable tip's final position ``tip``.
"""

from __future__ import annotations

import argparse
import json
import math
import time

T0 = time.perf_counter()

import exudyn as exu  # noqa: E402
from exudyn import beams  # noqa: E402
from exudyn.itemInterface import (  # noqa: E402
    MarkerBodyCable2DShape,
    MarkerBodyRigid,
    NodeGenericData,
    ObjectContactFrictionCircleCable2D,
    ObjectGround,
)

from rancf.exudyn_compat import cable2d, dynamic_settings  # noqa: E402

CASE = dict(
    length=2.0,
    r=0.002,
    center=(1.0, -0.3),
    radius=0.2,
    k=1e7,
    h=1e-3,
    rho_inf=0.6,
    density=7850.0,
    youngs=2e11,
    g=9.81,
)


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--elements", type=int, required=True)
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--solver", choices=("dense", "sparse"), default="dense")
    a = p.parse_args()
    c = CASE
    area, inertia = math.pi * c["r"] ** 2, math.pi * c["r"] ** 4 / 4
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    template = cable2d(
        massPerLength=c["density"] * area,
        bendingStiffness=c["youngs"] * inertia,
        axialStiffness=c["youngs"] * area,
    )
    made = beams.GenerateBeamElementsAlongLine(
        mbs,
        [0, 0, 0],
        [c["length"], 0, 0],
        a.elements,
        template,
        gravity=[0, -c["g"], 0],
        groundConstraintsStart=[1, 1, 0, 0],
        nodeNumberStart=-1,
        nodeNumberEnd=-1,
    )
    ground = mbs.AddObject(ObjectGround(referencePosition=[0, 0, 0]))
    centre = mbs.AddMarker(
        MarkerBodyRigid(bodyNumber=ground, localPosition=[c["center"][0], c["center"][1], 0])
    )
    segments = 8
    for el in made["elements"]:
        shape = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=el, numberOfSegments=segments))
        data = mbs.AddNode(
            NodeGenericData(
                initialCoordinates=[0.1] * segments + [-2] * segments + [0.0] * segments,
                numberOfDataCoordinates=3 * segments,
            )
        )
        mbs.AddObject(
            ObjectContactFrictionCircleCable2D(
                markerNumbers=[centre, shape],
                nodeNumber=data,
                numberOfContactSegments=segments,
                contactStiffness=c["k"],
                contactDamping=0.0,
                frictionCoefficient=0.0,
                circleRadius=c["radius"] + c["r"],
            )
        )
    mbs.Assemble()
    ss = dynamic_settings(a.t_end, c["h"], c["rho_inf"], sparse=a.solver == "sparse")
    # above the residual's round-off (Exudyn's default 1e-10 N is not reached on a steel cable:
    # Newton then fails and the step is cut), as exudyn_slider_crank.py
    ss.timeIntegration.newton.absoluteTolerance = 1e-13 * c["youngs"] * area * a.elements
    t1 = time.perf_counter()
    mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    tip = mbs.GetNodeOutput(made["nodes"][-1], exu.OutputVariableType.Position)
    print(
        json.dumps(
            {
                "setup_s": t1 - T0,
                "solve_s": t2 - t1,
                "steps": ss.timeIntegration.numberOfSteps,
                "tip": [float(tip[0]), float(tip[1])],
            }
        )
    )


if __name__ == "__main__":
    main()
