"""The surging mooring chain in MoorDyn 2.7 (the peer of ``rancf simulate mooring-surge.toml``).

    python benchmarks/mooring/moordyn_surge.py --segments N [--dt DT] [--csv FILE]

The chain of ``moorpy_statics.py`` (330 m, 288 kg/m, EA = 1.2326e9 N, d = 0.216 m; anchor
(-300, 0, -100) on the seabed at z = -100), its fairlead at (0, 0, 0) surging
x = 5 sin(2 pi t / 20) m for 60 s.  Drag normal / axial 1.333 / 0.639, added mass 1.0 / 0.5,
internal damping BA = -1 (MoorDyn's convention: critical damping of one segment, so it vanishes
as the segments shrink), seabed contact as MoorDyn does it (kBot = 3e6 Pa/m, cBot = 3e5 Pa s/m,
no friction), seawater 1025 kg/m^3, g = 9.81.  MoorDyn starts from its own static solution
(its stationary solver, threshIC 1e-3 by default).  Its scheme is RK2 (MoorDyn's default) with
the step ``--dt`` (default 0.04 s / segments).

Prints one JSON line (segments, MoorDyn's step, set-up and solve wall time) and with ``--csv``
writes the time series: t, fairlead x, the fairlead tension (the size of the force the line puts
on the coupled fairlead point), the tension of the top segment (MoorDyn's ``GetLineFairTen``,
half a segment below the fairlead) and the force's components.
"""

from __future__ import annotations

import argparse
import csv
import importlib.metadata
import json
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))

import moordyn  # noqa: E402
from moordyn_case import Case, LineType, Point, run  # noqa: E402

AMPLITUDE, PERIOD, T_END = 5.0, 20.0, 60.0
CHAIN = dict(diameter=0.216, mass=288.0, ea=1.2326e9, cd=1.333, ca=1.0, cd_ax=0.639, ca_ax=0.5)


def case(segments: int, dt: float | None, thresh_ic: float = 1e-3) -> Case:
    options = {
        "g": 9.81,
        "rho": 1025.0,
        "WtrDpth": 100.0,
        "kBot": 3.0e6,
        "cBot": 3.0e5,
        "threshIC": thresh_ic,
        "TmaxIC": 300.0,
        "disableOutput": 1,
        "disableOutTime": 1,
    }
    if dt is not None:
        options["dtM"] = dt
    return Case(
        LineType("chain", ba=-1.0, **CHAIN),
        [Point("Fixed", (-300.0, 0.0, -100.0)), Point("Coupled", (0.0, 0.0, 0.0))],
        330.0,
        segments,
        options=options,
    )


def fairlead(t: float) -> tuple[list[float], list[float]]:
    """The fairlead's position and velocity at ``t``."""
    w = 2.0 * math.pi / PERIOD
    return [AMPLITUDE * math.sin(w * t), 0.0, 0.0], [AMPLITUDE * w * math.cos(w * t), 0.0, 0.0]


def record(system: object, line: object, forces: list[float]) -> dict[str, float]:
    fx, fy, fz = forces
    return {
        "tension_N": math.sqrt(fx * fx + fy * fy + fz * fz),
        "top_segment_tension_N": moordyn.GetLineFairTen(line),
        "force_x_N": fx,
        "force_y_N": fy,
        "force_z_N": fz,
    }


def default_step(segments: int) -> float:
    """MoorDyn's step for ``segments``: 0.04 s / N (2e-3 s at 20 segments; the explicit scheme's
    limit falls with the segment length; MoorDyn's own CFL estimate, 0.025 s at 20 segments, blows
    up for this line)."""
    return 0.04 / segments


def simulate(segments: int, dt: float | None = None, t_end: float = T_END, thresh_ic: float = 1e-3):
    """One MoorDyn run: :class:`moordyn_case.Run` with the fairlead x added."""
    dt = default_step(segments) if dt is None else dt
    r = run(case(segments, dt, thresh_ic), fairlead, record, t_end)
    r.columns = {"x_m": [fairlead(t)[0][0] for t in r.times], **r.columns}
    return r


def write_csv(path: Path, r) -> None:
    keys = list(r.columns)
    with path.open("w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["t_s", *keys])
        for i, t in enumerate(r.times):
            w.writerow([f"{t:.4f}", *(f"{r.columns[k][i]:.9g}" for k in keys)])


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--segments", type=int, required=True)
    p.add_argument("--dt", type=float, default=None, help="MoorDyn's step dtM [s]")
    p.add_argument("--thresh-ic", type=float, default=1e-3, help="MoorDyn's threshIC")
    p.add_argument("--t-end", type=float, default=T_END)
    p.add_argument("--csv", type=Path, default=None)
    a = p.parse_args()
    r = simulate(a.segments, a.dt, a.t_end, a.thresh_ic)
    if a.csv:
        write_csv(a.csv, r)
    ten = r.columns["tension_N"]
    print(
        json.dumps(
            {
                "version": importlib.metadata.version("moordyn"),
                "segments": a.segments,
                "dt_s": r.dt,
                "init_s": r.init_s,
                "solve_s": r.solve_s,
                "tension_0_N": ten[0],
                "tension_max_N": max(ten),
                "tension_min_N": min(ten),
            }
        )
    )


if __name__ == "__main__":
    main()
