"""Rod dynamics with rotary inertia against Exudyn, side by side in one run.

    python benchmarks/rod_dynamics.py [--quick] [--no-exudyn] [--out DIR]

Cases (r = 0.02 m, ρ = 6000 kg/m³, E = 2e8 Pa, ν = 0.3, gravity −z, pinned at the start):

* **heavy top**: a straight rod (L = 0.5 m along x) spinning at 100 rad/s about its axis
  (``[initial_motion]``), released horizontally: tip y at 0.25 / 0.5 / 0.75 / 1 s against
  Exudyn's ``ObjectBeamGeometricallyExact`` (``exudyn_rod.py``) and the rigid Lagrange top
  (``scipy.integrate.solve_ivp``, the same inertia); rancf at E = 2e10 tends to the rigid top.
  Rotary inertia "torsion" (Exudyn's bending rotary inertia scaled by 1e-3) and "full" (1).
* **swung arc**: the paper's 6.2 arc as a rod swung at 2 rad/s about the vertical through A:
  tip at 0.5 and 1 s, the angular momentum about that axis with ρ∞ = 1, 0.9, 0.5.
* **forced arc**: the same arc from rest, F = 4 sin(2πt) N along +y at B: tip distance.
* **energy**: kinetic energy of a rigid rotation against ½ ωᵀ I ω (adaptive quadrature).
* **cost**: per element, the rod's force + tangent (today's rod, the elastic kernel) and the
  rotary inertia's force + tangent (``Model.core.inertia``), straight and curved, 64 elements.

rancf runs through its Python API (``Model``, ``integrate``), Exudyn through ``SolveDynamic``;
the solve wall times of both are printed for orientation (speed claims: ``benchmarks/run.py``).
Writes ``rod_dynamics.json`` to ``--out`` (default ``benchmarks/results``).
"""

from __future__ import annotations

import argparse
import json
import platform
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import exudyn_rod as exr  # noqa: E402

from rancf.bodies.flexible import Model, RigidMotion  # noqa: E402
from rancf.bodies.motion import angular_momentum  # noqa: E402
from rancf.bodies.properties import Material, PointLoad, Section, Support  # noqa: E402
from rancf.geometry.conic import conic_arc_through  # noqa: E402
from rancf.mesh.factories import (
    mesh_conic,
    mesh_line,  # noqa: E402
)
from rancf.solvers.dynamic import DynamicOptions, integrate  # noqa: E402

R, RHO, E, NU = 0.02, 6000.0, 2e8, 0.3
TIMES = (0.25, 0.5, 0.75, 1.0)
ARC = conic_arc_through([0, 0, 0], [0.5, 0, 0], [60, 30], [0.264, 0, 0.069])
#: the issue's Exudyn reference of the swung arc [m]
ARC_ISSUE = {0.5: [-0.46378, -0.10247, -0.16032], 1.0: [-0.08607, -0.33606, -0.36346]}


def section(rotary: str) -> Section:
    s = Section.circular(R)
    return Section(s.area, s.inertia, rotary_inertia=rotary)  # type: ignore[arg-type]


def rancf_run(mesh, rotary: str, youngs: float, h: float, rho_inf: float, **kw) -> tuple:
    """A pinned rod under gravity; returns (model, result, solve wall time)."""
    m = Model(
        mesh,
        "rod",
        section(rotary),
        Material(RHO, youngs, poisson_ratio=NU),
        [Support(0)],
        gravity=[0, 0, -9.81],
        **kw,
    )
    r = integrate(m, DynamicOptions(t_end=1.0, step=h, rho_inf=rho_inf, output_step=0.05))
    return m, r, r.wall_time


def at(result_t: np.ndarray, values: np.ndarray, t: float) -> np.ndarray:
    return values[int(np.argmin(np.abs(result_t - t)))]


def rigid_top(rotary: str) -> np.ndarray:
    """Tip positions of the rigid Lagrange top at TIMES (the rod's inertia about the pin)."""
    from scipy.integrate import solve_ivp

    s, length = section(rotary), 0.5
    mass = RHO * s.area * length
    trans = mass * length**2 / 3 + (RHO * s.inertia * length if rotary == "full" else 0.0)
    inertia = np.diag([RHO * s.polar * length, trans, trans])
    arm, weight = np.array([length / 2, 0, 0]), mass * np.array([0, 0, -9.81])

    def rhs(_t: float, z: np.ndarray) -> np.ndarray:
        rot, w = z[:9].reshape(3, 3), z[9:]
        skew = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        wdot = np.linalg.solve(inertia, np.cross(arm, rot.T @ weight) - np.cross(w, inertia @ w))
        return np.concatenate([(rot @ skew).ravel(), wdot])

    z0 = np.concatenate([np.eye(3).ravel(), [100.0, 0, 0]])
    sol = solve_ivp(rhs, (0, 1), z0, t_eval=TIMES, rtol=1e-11, atol=1e-12)
    return np.array([sol.y[:9, k].reshape(3, 3) @ [length, 0, 0] for k in range(len(TIMES))])


def exudyn_line(n: int, h: float, rho_inf: float, rot_scale: float) -> tuple[float, np.ndarray]:
    pts = np.outer(np.linspace(0, 0.5, n + 1), [1.0, 0, 0])
    _, mbs, _, sensor = exr.beam_chain(
        pts,
        np.tile([1.0, 0, 0], (n + 1, 1)),
        [0, 1.0, 0],
        RHO,
        E,
        NU,
        R,
        [0, 0, -9.81],
        omega=[100.0, 0, 0],
        rot_scale=rot_scale,
    )
    return exr.solve(mbs, sensor, 1.0, h, rho_inf, 0.05)


def exudyn_arc(n: int, h: float, rho_inf: float, **kw: Any) -> tuple[float, np.ndarray]:
    s = np.linspace(0, ARC.arc_length(), n + 1)
    u = ARC.parameters_at_arc_lengths(s)
    _, mbs, _, sensor = exr.beam_chain(
        ARC.derivatives(u, 1)[0], ARC.tangent(u), [0, 1.0, 0], RHO, E, NU, R, [0, 0, -9.81], **kw
    )
    return exr.solve(mbs, sensor, 1.0, h, rho_inf, 0.05)


def top_case(quick: bool, exudyn: bool) -> list[dict[str, Any]]:
    n, h, ne, he = (8, 1e-3, 8, 1e-3) if quick else (16, 5e-4, 32, 5e-4)
    rows = []
    for rotary, scale in (("torsion", 1e-3), ("full", 1.0)):
        motion = RigidMotion(angular_velocity=(100.0, 0.0, 0.0))
        mesh = mesh_line([0, 0, 0], [0.5, 0, 0], n)
        m, r, wall = rancf_run(mesh, rotary, E, h, 1.0, initial_motion=motion)
        tip = np.array([at(r.t, m.node_positions(r.q)[:, -1], t) for t in TIMES])
        mom = angular_momentum(m, r.q, r.v)
        m2, r2, _ = rancf_run(mesh, rotary, 2e10, h, 1.0, initial_motion=motion)
        stiff = np.array([at(r2.t, m2.node_positions(r2.q)[:, -1], t) for t in TIMES])
        row = {
            "case": f"heavy top, {rotary}",
            "rancf": f"{n} el, h = {h:g} s, rho_inf = 1",
            "rancf_tip_y_mm": (tip[:, 1] * 1e3).tolist(),
            "rancf_wall_s": wall,
            "rigid_top_tip_y_mm": (rigid_top(rotary)[:, 1] * 1e3).tolist(),
            "rancf_E2e10_tip_y_mm": (stiff[:, 1] * 1e3).tolist(),
            "rancf_E2e10_to_rigid_mm": float(
                np.linalg.norm(stiff - rigid_top(rotary), axis=1).max() * 1e3
            ),
            "Lz_drift_rel": float(np.abs(mom[:, 2]).max() / np.linalg.norm(mom, axis=1).max()),
            "energy_drift_rel": float(
                np.abs(r.total_energy - r.total_energy[0]).max() / r.total_energy[0]
            ),
        }
        if exudyn:
            wall_e, d = exudyn_line(ne, he, 0.9, scale)
            ex = np.array([at(d[:, 0], d[:, 1:], t) for t in TIMES])
            row.update(
                exudyn=f"{ne} el, h = {he:g} s, rho_inf = 0.9, bending rotary x {scale:g}",
                exudyn_tip_y_mm=(ex[:, 1] * 1e3).tolist(),
                exudyn_wall_s=wall_e,
                distance_mm=(np.linalg.norm(ex - tip, axis=1) * 1e3).tolist(),
            )
        rows.append(row)
    return rows


def arc_case(quick: bool, exudyn: bool, ne: int = 16, he: float = 1e-3) -> list[dict[str, Any]]:
    n, h = (8, 1e-3) if quick else (16, 5e-4)
    ne, he = (8, 1e-3) if quick else (ne, he)
    motion = RigidMotion(angular_velocity=(0.0, 0.0, 2.0))
    rows = []
    m, r, wall = rancf_run(mesh_conic(ARC, n), "torsion", E, h, 1.0, initial_motion=motion)
    tip = {t: at(r.t, m.node_positions(r.q)[:, -1], t) for t in (0.5, 1.0)}
    row: dict[str, Any] = {
        "case": "swung arc (2 rad/s)",
        "rancf": f"{n} el, h = {h:g} s, rho_inf = 1",
        "rancf_tip": {t: v.tolist() for t, v in tip.items()},
        "rancf_wall_s": wall,
        "issue_exudyn_tip": ARC_ISSUE,
        "to_issue_mm": {t: float(np.linalg.norm(tip[t] - ARC_ISSUE[t]) * 1e3) for t in tip},
    }
    for rho_inf in (1.0, 0.9, 0.5):
        mm, rr, _ = rancf_run(
            mesh_conic(ARC, 8), "torsion", E, 1e-3, rho_inf, initial_motion=motion
        )
        lz = angular_momentum(mm, rr.q, rr.v)[:, 2]
        row[f"Lz_change_rel_rho{rho_inf:g}_8el_1ms"] = float((lz[-1] - lz[0]) / lz[0])
    if exudyn:
        wall_e, d = exudyn_arc(ne, he, 0.9, omega=[0, 0, 2.0])
        ex = {t: at(d[:, 0], d[:, 1:], t) for t in (0.5, 1.0)}
        row.update(
            exudyn=f"{ne} el, h = {he:g} s, rho_inf = 0.9",
            exudyn_wall_s=wall_e,
            exudyn_tip={t: v.tolist() for t, v in ex.items()},
            distance_mm={t: float(np.linalg.norm(ex[t] - tip[t]) * 1e3) for t in tip},
        )
    rows.append(row)
    # from rest, F = 4 sin(2 pi t) N along +y at B
    force = [PointLoad(-1, (0.0, 4.0, 0.0), 1.0)]
    m, r, wall = rancf_run(mesh_conic(ARC, n), "torsion", E, h, 1.0, point_loads=force)
    tip_f = np.array([at(r.t, m.node_positions(r.q)[:, -1], t) for t in TIMES])
    row = {
        "case": "forced arc (4 sin 2 pi t N, +y at B)",
        "rancf": f"{n} el, h = {h:g} s",
        "rancf_tip": tip_f.tolist(),
        "rancf_wall_s": wall,
    }
    if exudyn:
        wall_e, d = exudyn_arc(ne, he, 0.9, tip_force=lambda t: [0.0, 4 * np.sin(2 * np.pi * t), 0])
        ex = np.array([at(d[:, 0], d[:, 1:], t) for t in TIMES])
        row.update(
            exudyn=f"{ne} el, h = {he:g} s",
            exudyn_wall_s=wall_e,
            distance_mm=(np.linalg.norm(ex - tip_f, axis=1) * 1e3).tolist(),
        )
    rows.append(row)
    return rows


def energy_case() -> dict[str, Any]:
    """Relative error of the kinetic energy of a rigid rotation, 4 to 64 elements."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from tests.kernels.test_rod_inertia import C, W, _exact_energy

    out: dict[str, Any] = {}
    for element, rotary in (("rancf", None), ("rod", "torsion"), ("rod", "full")):
        sec = section(rotary or "torsion")
        exact = _exact_energy(ARC, sec, RHO, W, C, rotary)
        errs = []
        for n in (4, 8, 16, 32, 64):
            m = Model(
                mesh_conic(ARC, n),
                element,
                sec,
                Material(RHO, E, poisson_ratio=NU),
                initial_motion=RigidMotion(angular_velocity=W, about=C),
            )
            errs.append(abs(m.kinetic_energy(m.v0) / exact - 1))
        out[f"{element} {rotary or ''}".strip()] = errs
    return out


def cost_case(quick: bool) -> list[dict[str, Any]]:
    """µs per element: elastic force + tangent, inertia force + tangent (best of 5 x reps)."""
    n, reps = (16, 20) if quick else (64, 300)
    rows = []
    meshes = {
        "straight (6 qp)": mesh_line([0, 0, 0], [0.5, 0.1, 0.2], n),
        "conic arc (10 qp)": mesh_conic(ARC, n),
    }
    rng = np.random.default_rng(0)
    for name, mesh in meshes.items():
        for rotary in ("torsion", "full"):
            m = Model(mesh, "rod", section(rotary), Material(RHO, E, poisson_ratio=NU))
            y = m.y0 + 1e-4 * rng.standard_normal(m.n)
            v, a = rng.standard_normal(m.n), rng.standard_normal(m.n)
            f, ab = np.empty(m.n), np.empty((2 * m.ku + 1, m.n))

            def best(fn: Any) -> float:
                times = []
                for _ in range(5):
                    t0 = time.perf_counter()
                    for _ in range(reps):
                        fn()
                    times.append((time.perf_counter() - t0) / reps / n * 1e6)
                return min(times)

            el = best(lambda m=m, y=y, f=f, ab=ab: m.core.internal_force_and_tangent(y, f, ab))
            ine = best(
                lambda m=m, y=y, v=v, a=a, f=f, ab=ab: m.core.inertia(
                    y, v, a, 0.0, 0.5, 100.0, 1e5, f, ab
                )
            )
            rows.append(
                {
                    "mesh": f"{name}, {n} el",
                    "rotary": rotary,
                    "elastic_us": el,
                    "inertia_us": ine,
                    "ratio": (el + ine) / el,
                }
            )
    return rows


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--quick", action="store_true", help="coarse meshes and steps (smoke run)")
    p.add_argument("--no-exudyn", action="store_true")
    p.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"))
    p.add_argument("--cases", default="top,arc,energy,cost", help="comma-separated subset")
    p.add_argument("--exudyn-arc", default="16,1e-3", help="Exudyn's arc elements,step")
    a = p.parse_args()
    cases = set(a.cases.split(","))
    ne, he = a.exudyn_arc.split(",")
    exudyn = exr.AVAILABLE and not a.no_exudyn
    print(
        f"{platform.processor() or platform.machine()}, Exudyn: "
        f"{__import__('exudyn').__version__ if exudyn else 'not used'}"
    )
    res: dict[str, Any] = {}
    if "top" in cases:
        res["top"] = top_case(a.quick, exudyn)
    if "arc" in cases:
        res["arc"] = arc_case(a.quick, exudyn, int(ne), float(he))
    if "energy" in cases:
        res["energy"] = energy_case()
    if "cost" in cases:
        res["cost"] = cost_case(a.quick)
    for row in res.get("top", []) + res.get("arc", []):
        print()
        for k, v in row.items():
            print(f"  {k:28s} {np.round(v, 5).tolist() if isinstance(v, list) else v}")
    print("\nkinetic energy of a rigid rotation, relative error at 4/8/16/32/64 elements:")
    for k, v in res.get("energy", {}).items():
        print(f"  {k:14s} " + " ".join(f"{e:.1e}" for e in v))
    print("\ncost per element [us]: elastic force+tangent, inertia force+tangent, ratio")
    for r in res.get("cost", []):
        print(
            f"  {r['mesh']:28s} {r['rotary']:8s} {r['elastic_us']:7.3f} {r['inertia_us']:7.3f}"
            f" {r['ratio']:6.2f}"
        )
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    name = (
        "rod_dynamics.json" if len(cases) == 4 else f"rod_dynamics_{'_'.join(sorted(cases))}.json"
    )
    (out / name).write_text(json.dumps(res, indent=1, default=str) + "\n")


if __name__ == "__main__":
    main()
