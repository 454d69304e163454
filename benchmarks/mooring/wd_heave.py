"""MoorDyn's regression chain WD0050 heaved as its ``QuasiStatic/ZZP1_A1`` input, beside rancf.

    python benchmarks/mooring/wd_heave.py [--segments 164] [--dt 1e-3] [--rancf-step 6.25e-3]

MoorDyn's ``tests/Mooring/WD0050_Chain.txt``: a 410 m chain (d = 0.252 m, 390 kg/m,
EA = 1.674e9 N, BA = -1, Cd 1.37, Ca 1.0, CdAx 0.64, CaAx 0) from an anchor at (400, 0, -50)
on the seabed to a fairlead at the surface, seabed kBot = 1e5 Pa/m, cBot = 1e4 Pa s/m and
friction 0.5, seawater 1025 kg/m^3; the fairlead heaved z = 2 sin(2 pi t / 10) m from the static
state, at once (ZZP1_A1).  MoorDyn (2.7, PyPI, a benchmark dependency only) with ``--segments``
and its step ``--dt``; rancf with ``benchmarks/mooring/wd0050.toml`` (the same line in the x-z
plane, 164 elements, BA = -1 mapped to ``[damping] axial = (L/N) sqrt(EA m)``, kBot d and cBot
as the seabed's ``stiffness`` and ``damping_normal``) with the same motion.

Prints one JSON line: each side's fairlead tension mean and peak to peak over t = 10-30 s, the
largest difference relative to MoorDyn's mean, and the wall times.
"""

from __future__ import annotations

import argparse
import json
import math
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from moordyn_case import Case, LineType, Point, run  # noqa: E402

AMPLITUDE, PERIOD, T_END = 2.0, 10.0, 30.0
CHAIN = dict(diameter=0.252, mass=390.0, ea=1.674e9, cd=1.37, ca=1.0, cd_ax=0.64, ca_ax=0.0)


def fairlead(t: float) -> tuple[list[float], list[float]]:
    """The fairlead's position and velocity at ``t`` (MoorDyn's frame: the anchor at +400 m)."""
    w = 2.0 * math.pi / PERIOD
    return [0.0, 0.0, AMPLITUDE * math.sin(w * t)], [0.0, 0.0, AMPLITUDE * w * math.cos(w * t)]


def moordyn_run(segments: int, dt: float) -> tuple[np.ndarray, np.ndarray, float]:
    options = {"g": 9.81, "rho": 1025.0, "WtrDpth": 50.0, "kBot": 1.0e5, "cBot": 1.0e4,
               "FrictionCoefficient": 0.5, "dtM": dt, "dtIC": 1.0, "TmaxIC": 200.0,
               "CdScaleIC": 4.0, "threshIC": 1e-3, "disableOutput": 1,
               "disableOutTime": 1}  # fmt: skip
    case = Case(LineType("chain", ba=-1.0, **CHAIN),
                [Point("Fixed", (400.0, 0.0, -50.0)), Point("Coupled", (0.0, 0.0, 0.0))],
                410.0, segments, options=options)  # fmt: skip

    def record(system: object, line: object, f: list[float]) -> dict[str, float]:
        return {"tension": math.sqrt(sum(x * x for x in f))}

    r = run(case, fairlead, record, T_END)
    return np.array(r.times), np.array(r.columns["tension"]), r.solve_s


def rancf_run(step: float) -> tuple[np.ndarray, np.ndarray, float]:
    text = (HERE / "wd0050.toml").read_text()
    text = text.replace("motion = { harmonic = 0.1, amplitude = [0.0, 2.0] }",
                        "motion = { harmonic = 0.1, amplitude = [0.0, 2.0], build_up = 0.0 }")
    text = re.sub(r"(?m)^step = .*$", f"step = {step!r}", text)
    text = re.sub(r"(?m)^output_step = .*$", "output_step = 0.01", text)
    with tempfile.TemporaryDirectory() as tmp:
        path, out = Path(tmp) / "wd.toml", Path(tmp) / "run"
        path.write_text(text)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "rancf", "simulate", str(path), "--out", str(out),
                        "--quiet"], check=True, capture_output=True)  # fmt: skip
        wall = time.perf_counter() - t0
        rows = np.genfromtxt(out / "sensors.csv", delimiter=",", names=True)
    return rows["t"], rows["tension"], wall


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--segments", type=int, default=164)
    p.add_argument("--dt", type=float, default=1e-3, help="MoorDyn's step dtM [s]")
    p.add_argument("--rancf-step", type=float, default=6.25e-3)
    a = p.parse_args()
    tm, fm, wall_m = moordyn_run(a.segments, a.dt)
    tr, fr, wall_r = rancf_run(a.rancf_step)
    window = (tm >= 10.0) & (tm <= 30.0)
    ours = np.interp(tm[window], tr, fr)
    theirs = fm[window]
    print(json.dumps({
        "moordyn_segments": a.segments, "moordyn_dt_s": a.dt, "rancf_step_s": a.rancf_step,
        "moordyn_mean_N": float(theirs.mean()), "rancf_mean_N": float(ours.mean()),
        "moordyn_p2p_N": float(np.ptp(theirs)), "rancf_p2p_N": float(np.ptp(ours)),
        "max_diff_rel_mean": float(np.abs(ours - theirs).max() / theirs.mean()),
        "moordyn_solve_s": wall_m, "rancf_process_s": wall_r,
    }))  # fmt: skip


if __name__ == "__main__":
    main()
