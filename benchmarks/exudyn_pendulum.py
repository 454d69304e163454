"""The straight pendulum of the issue as a stand-alone Exudyn script (the peer of `rancf simulate`).

    python benchmarks/exudyn_pendulum.py --elements N [--solver dense|sparse] [--output-step DT]
        [--newton-rel-tol TOL]

L = 1.2 m, circular section r = 0.02 m, rho = 6000 kg/m^3, E = 2e8 Pa, pinned at x = 0, released
horizontal under gravity; generalized-alpha rho_inf = 0.9, h = 1 ms, 1 s.  The outputs are
matched to `rancf simulate`'s: the tip's position sensor, stored in memory every DT (default:
every step, as rancf's default output), no solution file.  Prints one JSON line:
set-up time (model building and assembly), solve time, steps and the tip position.  Like
`rancf simulate`, the time counts from the start of this script's own code (imports included in
the whole-process time measured outside).  The chain is ``exudyn_cases.straight_cable``, Exudyn's
names for this version come from ``rancf.exudyn_compat``, which imports no other part of rancf
(about 1 ms).
"""

from __future__ import annotations

import argparse
import json
import math
import time

T0 = time.perf_counter()

import exudyn as exu  # noqa: E402
from exudyn_cases import straight_cable  # noqa: E402

from rancf.exudyn_compat import dynamic_settings  # noqa: E402

LENGTH, RADIUS, DENSITY, YOUNGS = 1.2, 0.02, 6000.0, 2.0e8


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--elements", type=int, required=True)
    p.add_argument("--solver", choices=["dense", "sparse"], default="dense")
    p.add_argument("--t-end", type=float, default=1.0)
    p.add_argument("--step", type=float, default=1e-3)
    p.add_argument("--output-step", type=float, default=None, help="sensor period (default: step)")
    p.add_argument(
        "--newton-rel-tol",
        type=float,
        default=None,
        help="timeIntegration.newton.relativeTolerance (default: Exudyn's, 1e-8)",
    )
    a = p.parse_args()
    area, inertia = math.pi * RADIUS**2, math.pi * RADIUS**4 / 4.0
    sc, mbs, nodes = straight_cable(
        a.elements,
        LENGTH,
        DENSITY * area,
        YOUNGS * inertia,
        YOUNGS * area,
        [1, 1, 0, 0],
        [0, -9.81, 0],
    )
    sensor = mbs.AddSensor(
        exu.itemInterface.SensorNode(
            nodeNumber=nodes[-1],
            writeToFile=False,
            storeInternal=True,
            outputVariableType=exu.OutputVariableType.Position,
        )
    )
    mbs.Assemble()
    period = a.output_step if a.output_step is not None else a.step
    ss = dynamic_settings(
        a.t_end, a.step, 0.9, sparse=a.solver == "sparse", sensors_write_period=period
    )
    if a.newton_rel_tol is not None:
        ss.timeIntegration.newton.relativeTolerance = a.newton_rel_tol
    t1 = time.perf_counter()
    mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    tip = mbs.GetNodeOutput(nodes[-1], exu.OutputVariableType.Position)
    stored = mbs.GetSensorStoredData(sensor)
    out = {
        "sensor_rows": len(stored),
        "setup_s": t1 - T0,
        "solve_s": t2 - t1,
        "steps": ss.timeIntegration.numberOfSteps,
        "tip": [float(tip[0]), float(tip[1])],
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
