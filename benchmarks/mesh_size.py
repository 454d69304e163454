"""Time to mesh a conic arc into many elements (equal arc length, Kopt per element).

Meshes the paper's Example 1 arc into 1 000, 10 000 and 100 000 elements and prints the wall
time of each (median of ``--repeats``) and the CPU. The exactness of such a mesh is a test
(tests/geometry/test_robust_geometry.py); its speed is measured here.

    python benchmarks/mesh_size.py [--repeats 3]
"""

from __future__ import annotations

import argparse
import statistics
import time

from mooring.provenance import machine  # benchmarks/ is the script's folder

from rancf.geometry.conic import conic_arc
from rancf.mesh.factories import mesh_conic

#: Paper Example 1: chord, end-tangent angles [deg], interior point.
EXAMPLE1 = (0.5, (30.0, 40.0), (0.315, 0.077))


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--repeats", type=int, default=3)
    args = ap.parse_args(argv)
    c = conic_arc(*EXAMPLE1)
    print(f"meshing a conic arc; {machine()}")
    for n in (1_000, 10_000, 100_000):
        times = []
        for _ in range(args.repeats):
            t0 = time.perf_counter()
            mesh_conic(c, n)
            times.append(time.perf_counter() - t0)
        print(f"  {n:7d} elements  {statistics.median(times):8.3f} s")


if __name__ == "__main__":
    main()
