"""Cost of contact (issue 20): per-step times, rancf alone and side by side with Exudyn.

    python benchmarks/contact_cost.py [--quick] [--no-exudyn] [--repeats N] [--out DIR]

* ``ground``: a 1000-element steel cable (10 m, radius 2 mm) lying on the ground, against the
  same cable hanging free from a pin (no obstacle): per-step time of the compiled loop, Newton
  iterations per step, and their ratio (the issue asks for at most 1.5).
* ``circle``: a 2 m cable pinned at one end falls onto a fixed circle (frictionless, the same
  penalty stiffness 1e7 N/m^2 in both codes), 1 s in 1 ms steps, generalized-alpha rho_inf = 0.6:
  rancf's contact along the curve (8 Gauss points per element) against Exudyn's
  ``ObjectContactFrictionCircleCable2D`` (8 contact segments per element), per-step solve time,
  in this process through each code's Python API (``integrate`` / ``SolveDynamic``); the tips'
  final positions show both solved the same problem.  Exudyn's circle is the cable's centre
  line's (radius R + r), its ``contactStiffness`` per unit length like rancf's.

Writes ``contact_cost.json`` to ``--out`` (default ``benchmarks/results``).
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))

import exudyn_cases as ex  # noqa: E402

from rancf.model.mesh import mesh_line  # noqa: E402
from rancf.model.system import Material, Model, Section, Support  # noqa: E402
from rancf.solvers.dynamic import DynamicOptions, integrate  # noqa: E402
from rancf.system import Obstacle, System, contact_outputs  # noqa: E402

G = 9.81


def _steel(r: float) -> tuple[Section, Material]:
    return Section.circular(r), Material(7850.0, 2e11)


def ground_case(n: int, steps: int, lying: bool) -> dict:
    """The cable lying on the ground (straight, touching it) or hanging from a pin (no obstacle)."""
    r, length = 0.002, 10.0
    sec, mat = _steel(r)
    if lying:
        mesh = mesh_line([0.0, r], [length, r], n)
        cable = Model(mesh, "rancf", sec, mat, [], gravity=[0, -G])
        obs = [Obstacle("plane", point=(0, 0), normal=(0, 1), name="ground")]
    else:
        mesh = mesh_line([0.0, 0.0], [0.0, -length], n)
        cable = Model(mesh, "rancf", sec, mat, [Support(0, "pin")], gravity=[0, -G])
        obs = []
    s = System({"cable": cable}, obstacles=obs, gravity=[0, -G])
    h = 1e-3
    t_end = steps * h
    opts = DynamicOptions(t_end=t_end, step=h, rho_inf=0.5, max_newton=25, output_step=t_end)
    res = integrate(s, opts)
    assert res.status.value == "completed", res.message
    out = {
        "us_per_step": 1e6 * res.wall_time / res.n_steps,
        "newton_per_step": res.n_newton / res.n_steps,
        "rejected": res.n_rejected,
    }
    if lying:
        c = contact_outputs(s, s.y_from_q(res.q[-1]))["ground"]
        weight = mat.density * sec.area * length * G
        out["reaction_over_weight"] = float(c.normal[1] / weight)
        out["penetration_over_radius"] = c.penetration / r
    return out


CIRCLE = dict(length=2.0, r=0.002, center=(1.0, -0.3), radius=0.2, k=1e7, t_end=1.0, h=1e-3)


def circle_rancf(n: int, t_end: float) -> dict:
    c = CIRCLE
    sec, mat = _steel(c["r"])
    mesh = mesh_line([0.0, 0.0], [c["length"], 0.0], n)
    cable = Model(mesh, "rancf", sec, mat, [Support(0, "pin")], gravity=[0, -G])
    disc = Obstacle("cylinder", center=c["center"], radius=c["radius"], stiffness=c["k"],
                    name="disc")  # fmt: skip
    s = System({"cable": cable}, obstacles=[disc], gravity=[0, -G])
    opts = DynamicOptions(t_end=t_end, step=c["h"], rho_inf=0.6, max_newton=25, output_step=t_end)
    t0 = time.perf_counter()
    res = integrate(s, opts)
    total = time.perf_counter() - t0
    assert res.status.value == "completed", res.message
    tip = cable.node_positions(res.q[-1][: cable.n])[-1]
    return {
        "us_per_step": 1e6 * res.wall_time / res.n_steps,
        "setup_s": total - res.wall_time,
        "newton_per_step": res.n_newton / res.n_steps,
        "tip": [float(tip[0]), float(tip[1])],
    }


def circle_exudyn(n: int, t_end: float) -> dict:
    import exudyn as exu
    from exudyn.itemInterface import (
        MarkerBodyCable2DShape,
        MarkerBodyRigid,
        NodeGenericData,
        ObjectContactFrictionCircleCable2D,
        ObjectGround,
    )

    from rancf.exudyn_compat import cable2d, dynamic_settings

    c = CIRCLE
    sec, mat = _steel(c["r"])
    e_mod, rho = mat.youngs_modulus, mat.density
    t0 = time.perf_counter()
    sc = exu.SystemContainer()
    mbs = sc.AddSystem()
    template = cable2d(massPerLength=rho * sec.area, bendingStiffness=e_mod * sec.inertia,
                       axialStiffness=e_mod * sec.area)  # fmt: skip
    from exudyn import beams

    made = beams.GenerateBeamElementsAlongLine(
        mbs, [0, 0, 0], [c["length"], 0, 0], n, template, gravity=[0, -G, 0],
        groundConstraintsStart=[1, 1, 0, 0], nodeNumberStart=-1, nodeNumberEnd=-1,
    )  # fmt: skip
    ground = mbs.AddObject(ObjectGround(referencePosition=[0, 0, 0]))
    centre = mbs.AddMarker(
        MarkerBodyRigid(bodyNumber=ground, localPosition=[c["center"][0], c["center"][1], 0])
    )
    segments = 8
    for el in made["elements"]:
        shape = mbs.AddMarker(MarkerBodyCable2DShape(bodyNumber=el, numberOfSegments=segments))
        data = mbs.AddNode(NodeGenericData(
            initialCoordinates=[0.1] * segments + [-2] * segments + [0.0] * segments,
            numberOfDataCoordinates=3 * segments))  # fmt: skip
        mbs.AddObject(ObjectContactFrictionCircleCable2D(
            markerNumbers=[centre, shape], nodeNumber=data, numberOfContactSegments=segments,
            contactStiffness=c["k"], contactDamping=0.0, frictionCoefficient=0.0,
            circleRadius=c["radius"] + c["r"]))  # fmt: skip
    mbs.Assemble()
    ss = dynamic_settings(t_end, c["h"], 0.6)
    t1 = time.perf_counter()
    mbs.SolveDynamic(ss)
    t2 = time.perf_counter()
    tip = mbs.GetNodeOutput(made["nodes"][-1], exu.OutputVariableType.Position)
    steps = ss.timeIntegration.numberOfSteps
    return {
        "us_per_step": 1e6 * (t2 - t1) / steps,
        "setup_s": t1 - t0,
        "tip": [float(tip[0]), float(tip[1])],
    }


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--quick", action="store_true", help="small sizes (a smoke run)")
    p.add_argument("--no-exudyn", action="store_true")
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--out", default=str(Path(__file__).resolve().parent / "results"))
    a = p.parse_args()
    n_ground, steps = (100, 20) if a.quick else (1000, 200)
    n_circle, t_circle = (10, 0.1) if a.quick else (40, CIRCLE["t_end"])
    report: dict = {"ground": {}, "circle": {}}
    lying = [ground_case(n_ground, steps, True) for _ in range(a.repeats)]
    hanging = [ground_case(n_ground, steps, False) for _ in range(a.repeats)]
    ratios = [x["us_per_step"] / y["us_per_step"] for x, y in zip(lying, hanging, strict=True)]
    report["ground"] = {
        "elements": n_ground, "steps": steps, "lying": lying[-1], "hanging": hanging[-1],
        "ratio_per_step": statistics.median(ratios),
    }  # fmt: skip
    print(f"ground, {n_ground} elements: lying {lying[-1]['us_per_step']:.0f} us/step "
          f"({lying[-1]['newton_per_step']:.2f} Newton), hanging "
          f"{hanging[-1]['us_per_step']:.0f} us/step ({hanging[-1]['newton_per_step']:.2f}), "
          f"ratio {report['ground']['ratio_per_step']:.2f}")  # fmt: skip
    rows = []
    for _ in range(a.repeats):
        row = {"rancf": circle_rancf(n_circle, t_circle)}
        if ex.AVAILABLE and not a.no_exudyn:
            row["exudyn"] = circle_exudyn(n_circle, t_circle)
        rows.append(row)
    circle = {"elements": n_circle, "t_end": t_circle, "rancf": rows[-1]["rancf"]}
    line = f"circle, {n_circle} elements: rancf {rows[-1]['rancf']['us_per_step']:.0f} us/step"
    if "exudyn" in rows[-1]:
        circle["exudyn"] = rows[-1]["exudyn"]
        circle["exudyn_version"] = ex.VERSION
        circle["ratio_per_step"] = statistics.median(
            r["rancf"]["us_per_step"] / r["exudyn"]["us_per_step"] for r in rows
        )
        line += (f", Exudyn {rows[-1]['exudyn']['us_per_step']:.0f} us/step, ratio "
                 f"{circle['ratio_per_step']:.2f}; tips rancf {rows[-1]['rancf']['tip']}, "
                 f"Exudyn {rows[-1]['exudyn']['tip']}")  # fmt: skip
    report["circle"] = circle
    print(line)
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "contact_cost.json").write_text(json.dumps(report, indent=1, allow_nan=False) + "\n")


if __name__ == "__main__":
    np.seterr(all="raise")
    main()
