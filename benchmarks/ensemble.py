"""An ensemble of runs on the cores of one process against the same runs one after another.

    python benchmarks/ensemble.py [--runs 64] [--elements 32] [--pairs 3] [--threads 2]

64 straight pendulums of 32 elements (the pendulum of ``cli_cases.py``, 1 s at h = 1 ms,
outputs every step), each with its own Young's modulus (1e8 to 4e8 Pa), built and integrated
(:func:`rancf.sweep.threads.run_ensemble`) on ``--threads`` threads and on one, in pairs
(A B A B ...; the ratio taken pair by pair, the median printed, with the load average).  Every
ensemble's answers are checked against those of the serial runs (1e-12 of the size).
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import time

import numpy as np

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions
from rancf.sweep.threads import run_ensemble
from rancf.system import as_system

LENGTH = 1.2


def pendulum(youngs: float, n: int):
    """The straight pendulum of the benchmark runner with Young's modulus ``youngs``."""
    model = Model(
        mesh_line([0.0, 0.0], [LENGTH, 0.0], n),
        "ancf",
        Section.circular(0.02),
        Material(6000.0, youngs),
        [Support(0, "pin")],
        gravity=[0.0, -9.81],
    )
    return as_system(model)


def ensemble(youngs: np.ndarray, n: int, threads: int) -> tuple[float, list]:
    """Wall time of building and integrating every run on ``threads`` threads; the results."""
    opts = DynamicOptions(t_end=1.0, step=1e-3, rho_inf=0.9)
    t0 = time.perf_counter()
    out = run_ensemble([pendulum(e, n) for e in youngs], opts, threads=threads)
    return time.perf_counter() - t0, out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", type=int, default=64)
    ap.add_argument("--elements", type=int, default=32)
    ap.add_argument("--pairs", type=int, default=3)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    youngs = np.linspace(1e8, 4e8, a.runs)
    ensemble(youngs[:2], a.elements, a.threads)  # warm-up
    ratios, serial, parallel, worst = [], [], [], 0.0
    load = [os.getloadavg()[0]]
    for _ in range(a.pairs):
        ts, ref = ensemble(youngs, a.elements, 1)
        tp, got = ensemble(youngs, a.elements, a.threads)
        worst = max(
            worst, max(float(np.abs(x.q - y.q).max()) for x, y in zip(ref, got, strict=True))
        )
        serial.append(ts)
        parallel.append(tp)
        ratios.append(tp / ts)
        load.append(os.getloadavg()[0])
    row = {
        "runs": a.runs,
        "elements": a.elements,
        "threads": a.threads,
        "serial_s": statistics.median(serial),
        "ensemble_s": statistics.median(parallel),
        "ratio": statistics.median(ratios),
        "ratios": ratios,
        "largest_difference_m": worst,
        "load_average_1min": load,
        "cpus": os.cpu_count(),
    }
    print(json.dumps(row, indent=1))
    assert worst <= 1e-12 * LENGTH, worst


if __name__ == "__main__":
    main()
