"""The static mooring lines in MoorPy (the peer of ``rancf static``).

    python benchmarks/mooring/moorpy_statics.py [--segments N]

Two lines from an anchor at (-300, 0, -100) on a seabed at z = -100 to a fairlead at (0, 0, 0),
seawater rho = 1025 kg/m^3, g = 9.81 m/s^2 (MoorPy's ``System(rho, g)``):

* ``chain``: 330 m, 288 kg/m in air, EA = 1.2326e9 N, volume-equivalent diameter 0.216 m; MoorPy
  weighs it in water as w = (m - rho pi d^2 / 4) g = 2456.8 N/m; the seabed has no friction
  (``cb = 0``).
* ``taut buoyant``: a synthetic line lighter than water, 315 m (shorter than the 316.2 m chord),
  20 kg/m in air, EA = 1.0e8 N, d = 0.2 m: w = (20 - 32.2) g = -119.7 N/m (it bows upwards).

Prints one JSON line: for each case the force the line puts on the fairlead [N] (MoorPy's
``Point.getForces(lines_only=True)``), the end tensions and MoorPy's wall time.  Needs
``pip install moorpy==1.3.*`` (a benchmark dependency, not one of rancf's).
"""

from __future__ import annotations

import argparse
import importlib.metadata
import json
import math
import time

import moorpy as mp
import numpy as np

RHO, G, DEPTH = 1025.0, 9.81, 100.0
ANCHOR, FAIRLEAD = (-300.0, 0.0, -100.0), (0.0, 0.0, 0.0)
#: name: (unstretched length [m], mass per length in air [kg/m], EA [N], diameter [m])
CASES = {
    "chain": (330.0, 288.0, 1.2326e9, 0.216),
    "taut buoyant": (315.0, 20.0, 1.0e8, 0.2),
}


def wet_weight(mass: float, diameter: float) -> float:
    """MoorPy's weight in water per length [N/m]: (m - rho pi d^2 / 4) g."""
    return (mass - RHO * math.pi * diameter**2 / 4.0) * G


def solve(name: str, segments: int) -> dict:
    """One line in MoorPy: the fairlead force, the end tensions and the wall time."""
    length, mass, ea, diameter = CASES[name]
    t0 = time.perf_counter()
    ms = mp.System(depth=DEPTH, rho=RHO, g=G)
    # MoorPy 1.3's setLineType needs a nominal diameter unless a whole dict is given
    ms.setLineType(
        lineType=dict(
            name=name, m=mass, d_vol=diameter, EA=ea, w=None, material="peer", d_nom=diameter
        ),
        name=name,
    )
    ms.addPoint(1, np.array(ANCHOR))
    ms.addPoint(-1, np.array(FAIRLEAD))
    ms.addLine(length, name, nSegs=segments, pointA=1, pointB=2)
    ms.initialize()
    ms.solveEquilibrium()
    wall = time.perf_counter() - t0
    line = ms.lineList[0]
    force = ms.pointList[1].getForces(lines_only=True, xyz=True)
    return {
        "length_m": length,
        "mass_kg_per_m": mass,
        "EA_N": ea,
        "diameter_m": diameter,
        "wet_weight_N_per_m": ms.lineTypes[name]["w"],
        "fairlead_force_N": [float(v) for v in force],
        "fairlead_tension_N": float(line.TB),
        "anchor_tension_N": float(line.TA),
        "seabed_length_m": float(getattr(line, "LBot", 0.0)),
        "wall_s": wall,
    }


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--segments", type=int, default=40, help="points MoorPy returns the profile at")
    a = p.parse_args()
    out = {
        "peer_version": importlib.metadata.version("moorpy"),
        "rho": RHO,
        "g": G,
        "cases": {name: solve(name, a.segments) for name in CASES},
    }
    print(json.dumps(out))


if __name__ == "__main__":
    main()
