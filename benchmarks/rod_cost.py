"""Cost of the rod element against the 3D cable, per element and Newton iteration.

Times ``Model.core.internal_force_and_tangent`` (element forces and tangents plus banded
assembly: the per-element work of one Newton iteration) on the same mesh for the spatial RANCF
cable and the rod, interleaved cable/rod, and a whole time loop (generalized-α, full Newton:
assembly, band LU and solve) per Newton iteration.  Prints a table; ``--quick`` for a smoke run.

    python benchmarks/rod_cost.py [--elements 64] [--repeats 300] [--quick]
"""

from __future__ import annotations

import argparse
import platform
import time

import numpy as np

from rancf.bodies.flexible import Model
from rancf.bodies.properties import Material, Section, Support
from rancf.geometry.conic import conic_arc_through
from rancf.mesh.factories import mesh_conic, mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate

SEC = Section.circular(0.02)
MAT = Material(6000.0, 2.0e6, poisson_ratio=0.3)


def meshes(n: int) -> dict[str, object]:
    arc = conic_arc_through([0, 0, 0], [0.5, 0.1, 0.2], [35, 50], [0.2, 0.15, 0.05])
    return {"straight": mesh_line([0, 0, 0], [0.5, 0.1, 0.2], n), "conic arc": mesh_conic(arc, n)}


def assembly_time(model: Model, y: np.ndarray, repeats: int) -> float:
    """Median over 7 batches of the wall time of one force + tangent assembly [s]."""
    f, ab = np.empty(model.n), np.empty((2 * model.ku + 1, model.n))
    times = []
    for _ in range(7):
        t = time.perf_counter()
        for _ in range(repeats):
            model.core.internal_force_and_tangent(y, f, ab)
        times.append((time.perf_counter() - t) / repeats)
    return float(np.median(times))


def newton_time(model: Model, steps: int) -> float:
    """Wall time per Newton iteration of a pinned pendulum under gravity [s]."""
    res = integrate(model, DynamicOptions(t_end=steps * 1e-3, step=1e-3))
    return res.wall_time / res.n_newton


def measure(n: int, reps: int, steps: int) -> list[dict[str, object]]:
    """Rows ``{case, cable_us, rod_us, ratio}`` per mesh and quantity (per element)."""
    rng = np.random.default_rng(0)
    rows: list[dict[str, object]] = []
    for name, mesh in meshes(n).items():
        models = {
            el: Model(mesh, el, SEC, MAT, [Support(0)], gravity=[0.0, 0.0, -9.81])
            for el in ("rancf", "rod")
        }
        ys = {el: m.y0 + 1e-4 * rng.standard_normal(m.n) for el, m in models.items()}
        asm: dict[str, list[float]] = {el: [] for el in models}
        for _ in range(3):  # interleaved: cable, rod, cable, rod, ...
            for el, m in models.items():
                asm[el].append(assembly_time(m, ys[el], reps))
        t_a = {el: min(v) / n * 1e6 for el, v in asm.items()}
        t_n = {el: newton_time(m, steps) / n * 1e6 for el, m in models.items()}
        for label, t in (
            ("force+tangent per element", t_a),
            ("whole Newton iteration per element", t_n),
        ):
            rows.append(
                {
                    "case": f"rod vs 3D cable, {name}, {n} el: {label}",
                    "cable_us": t["rancf"],
                    "rod_us": t["rod"],
                    "ratio": t["rod"] / t["rancf"],
                }
            )
    return rows


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--elements", type=int, default=64)
    p.add_argument("--repeats", type=int, default=300)
    p.add_argument("--quick", action="store_true")
    a = p.parse_args()
    n, reps, steps = (8, 5, 5) if a.quick else (a.elements, a.repeats, 500)
    print(f"{platform.processor() or platform.machine()}, {n} elements")
    print(f"{'case':75s} {'cable us':>9s} {'rod us':>9s} {'rod/cable':>9s}")
    for r in measure(n, reps, steps):
        print(f"{r['case']:75s} {r['cable_us']:9.3f} {r['rod_us']:9.3f} {r['ratio']:9.2f}")


if __name__ == "__main__":
    main()
