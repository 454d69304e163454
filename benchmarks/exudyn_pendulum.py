"""The straight pendulum of the issue as a stand-alone Exudyn script (the peer of `rancf simulate`).

    python benchmarks/exudyn_pendulum.py --elements N [--solver dense|sparse]

L = 1.2 m, circular section r = 0.02 m, rho = 6000 kg/m^3, E = 2e8 Pa, pinned at x = 0, released
horizontal under gravity; generalized-alpha rho_inf = 0.9, h = 1 ms, 1 s.  Prints one JSON line:
set-up time (model building and assembly), solve time, steps and the tip position.  Like
`rancf simulate`, the time counts from the start of this script's own code (imports included in
the whole-process time measured outside).
"""

from __future__ import annotations

import argparse
import json
import math
import time
import warnings

T0 = time.perf_counter()
warnings.filterwarnings("ignore", category=DeprecationWarning)  # Exudyn's renamed settings

import exudyn as exu  # noqa: E402
from exudyn.beams import GenerateStraightLineANCFCable2D  # noqa: E402
from exudyn.itemInterface import Cable2D  # noqa: E402

LENGTH, RADIUS, DENSITY, YOUNGS = 1.2, 0.02, 6000.0, 2.0e8


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--elements", type=int, required=True)
    p.add_argument("--solver", choices=["dense", "sparse"], default="dense")
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--step", type=float, default=1e-3)
    a = p.parse_args()
    area, inertia = math.pi * RADIUS**2, math.pi * RADIUS**4 / 4.0
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    cable = Cable2D(
        physicsMassPerLength=DENSITY * area,
        physicsBendingStiffness=YOUNGS * inertia,
        physicsAxialStiffness=YOUNGS * area,
    )
    nodes = GenerateStraightLineANCFCable2D(
        mbs=mbs,
        positionOfNode0=[0, 0, 0],
        positionOfNode1=[LENGTH, 0, 0],
        numberOfElements=a.elements,
        cableTemplate=cable,
        massProportionalLoad=[0, -9.81, 0],
        fixedConstraintsNode0=[1, 1, 0, 0],
    )[0]
    mbs.Assemble()
    ss = exu.SimulationSettings()
    if a.solver == "sparse":
        ss.linearSolverType = exu.LinearSolverType.EigenSparse
    ss.timeIntegration.numberOfSteps = int(round(a.t_end / a.step))
    ss.timeIntegration.endTime = a.t_end
    ss.timeIntegration.generalizedAlpha.spectralRadius = 0.9
    ss.timeIntegration.verboseMode = 0
    ss.solutionSettings.writeSolutionToFile = False
    ss.displayComputationTime = False
    ss.displayStatistics = False
    t1 = time.perf_counter()
    mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    tip = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)
    out = {
        "setup_s": t1 - T0,
        "solve_s": t2 - t1,
        "steps": ss.timeIntegration.numberOfSteps,
        "tip": [float(tip[0]), float(tip[1])],
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
