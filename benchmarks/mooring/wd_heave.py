"""MoorDyn's chains WD0050 and WD0200 heaved as its ``QuasiStatic/ZZP1_A1`` input, beside rancf.

    python benchmarks/mooring/wd_heave.py [--case wd0050 wd0200] [--dt 1e-3] [--rancf-step H]
        [--json results/wd_heave.json] [--reference tests/references]

MoorDyn's ``tests/Mooring/WD0050_Chain.txt`` and ``WD0200_Chain.txt``: a chain (d = 0.252 m,
390 kg/m, EA = 1.674e9 N, BA = -1, Cd 1.37, Ca 1.0, CdAx 0.64, CaAx 0) of 410 m from an anchor at
(400, 0, -50), and of 760 m from (700, 0, -200), on the seabed to a fairlead at the surface,
seabed kBot = 1e5 Pa/m, cBot = 1e4 Pa s/m and FrictionCoefficient 0.5 (FricDamp at its default
200 N s/m), seawater 1025 kg/m^3; the fairlead heaved z = 2 sin(2 pi t / 10) m from the static
state, at once (ZZP1_A1).  MoorDyn (2.7, PyPI, a benchmark dependency only) in segments of 2.5 m
(164 and 304; its own files take 41 and 76) at its step ``--dt``; rancf with ``wd0050.toml`` and
``wd0200.toml`` of this folder (the same lines in the x-z plane, MoorDyn's inputs mapped as their
comments say) with the same motion, at the files' fixed steps or at ``--rancf-step``.

Prints one JSON line per case: each side's fairlead tension (the size of the force between line
and fairlead, what MoorDyn's coupled point reports) mean and peak to peak over t = 10-30 s, the
largest difference relative to MoorDyn's mean, and the wall times (MoorDyn's initial state and
solve, rancf's solve and process); ``--json`` also writes them, keyed by case, with their
provenance.
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
#: Each case: the anchor's distance and depth [m], the chain's length [m] and MoorDyn's segments.
CASES = {"wd0050": (400.0, 50.0, 410.0, 164), "wd0200": (700.0, 200.0, 760.0, 304)}
CHAIN = dict(diameter=0.252, mass=390.0, ea=1.674e9, cd=1.37, ca=1.0, cd_ax=0.64, ca_ax=0.0)


def fairlead(t: float) -> tuple[list[float], list[float]]:
    """The fairlead's position and velocity at ``t`` (MoorDyn's frame: the anchor at +400 m)."""
    w = 2.0 * math.pi / PERIOD
    return [0.0, 0.0, AMPLITUDE * math.sin(w * t)], [0.0, 0.0, AMPLITUDE * w * math.cos(w * t)]


def moordyn_run(case: str, dt: float) -> tuple[np.ndarray, np.ndarray, float, float]:
    """MoorDyn's fairlead tension of ``case`` at its step ``dt``: times, tensions, the solve's
    and the initial state's (its ``Init``) wall times."""
    span, depth, length, segments = CASES[case]
    options = {
        "g": 9.81,
        "rho": 1025.0,
        "WtrDpth": depth,
        "kBot": 1.0e5,
        "cBot": 1.0e4,
        "FrictionCoefficient": 0.5,
        "dtM": dt,
        "dtIC": 1.0,
        "TmaxIC": 200.0,
        "CdScaleIC": 4.0,
        "threshIC": 1e-3,
        "disableOutput": 1,
        "disableOutTime": 1,
    }
    case = Case(
        LineType("chain", ba=-1.0, **CHAIN),
        [Point("Fixed", (span, 0.0, -depth)), Point("Coupled", (0.0, 0.0, 0.0))],
        length,
        segments,
        options=options,
    )

    def record(system: object, line: object, f: list[float]) -> dict[str, float]:
        return {"tension": math.sqrt(sum(x * x for x in f))}

    r = run(case, fairlead, record, T_END)
    return np.array(r.times), np.array(r.columns["tension"]), r.solve_s, r.init_s


def rancf_run(case: str, step: float | None) -> tuple[np.ndarray, np.ndarray, float, float]:
    """rancf's fairlead tension of ``case`` (the size of the fairlead reaction): times, tensions,
    solve and process times; at the file's step, or ``step``."""
    text = (HERE / f"{case}.toml").read_text()
    text = text.replace(
        "motion = { harmonic = 0.1, amplitude = [0.0, 2.0] }",
        "motion = { harmonic = 0.1, amplitude = [0.0, 2.0], build_up = 0.0 }",
    )
    if step is not None:  # the files take fixed steps
        text = re.sub(r"(?m)^step = .*$", f"step = {step!r}", text)
    with tempfile.TemporaryDirectory() as tmp:
        path, out = Path(tmp) / "wd.toml", Path(tmp) / "run"
        path.write_text(text)
        t0 = time.perf_counter()
        subprocess.run(
            [sys.executable, "-m", "rancf", "simulate", str(path), "--out", str(out), "--quiet"],
            check=True,
            capture_output=True,
        )
        wall = time.perf_counter() - t0
        rows = np.genfromtxt(out / "reactions.csv", delimiter=",", names=True)
        solve = json.loads((out / "summary.json").read_text())["solve_wall_time_s"]
    names = [n for n in rows.dtype.names if re.fullmatch(r"end_f[xyz]", n)]
    force = np.sqrt(sum(rows[n] ** 2 for n in names))
    return rows["t"], force, solve, wall


def write_reference(path: Path, t: np.ndarray, force: np.ndarray) -> None:
    """MoorDyn's fairlead tension to t = 12 s every 0.05 s as CSV (the regression test's peer
    numbers: tests/solvers/test_moordyn_heave.py)."""
    keep = (t <= 12.0 + 1e-9) & (np.abs(t / 0.05 - np.round(t / 0.05)) < 1e-6)
    rows = np.column_stack([t[keep], force[keep]])
    np.savetxt(path, rows, fmt=("%.2f", "%.1f"), delimiter=",", header="t,tension", comments="")


def compare(case: str, dt: float, step: float | None, reference: Path | None) -> dict[str, object]:
    """Both codes' fairlead tensions of ``case`` over t = 10-30 s, side by side; MoorDyn's
    series to 12 s written to ``reference/CASE_moordyn.csv`` if given."""
    tm, fm, solve_m, init_m = moordyn_run(case, dt)
    if reference is not None:
        write_reference(reference / f"{case}_moordyn.csv", tm, fm)
    tr, fr, solve_r, wall_r = rancf_run(case, step)
    text = (HERE / f"{case}.toml").read_text()
    window = (tm >= 10.0) & (tm <= 30.0)
    ours, theirs = np.interp(tm[window], tr, fr), fm[window]
    return {
        "case": case,
        "moordyn_segments": CASES[case][3],
        "moordyn_dt_s": dt,
        "rancf_step_s": step or float(re.search(r"(?m)^step = (.*)$", text).group(1)),
        "moordyn_mean_N": float(theirs.mean()),
        "rancf_mean_N": float(ours.mean()),
        "moordyn_p2p_N": float(np.ptp(theirs)),
        "rancf_p2p_N": float(np.ptp(ours)),
        "max_diff_rel_mean": float(np.abs(ours - theirs).max() / theirs.mean()),
        "moordyn_solve_s": solve_m,
        "moordyn_init_s": init_m,
        "rancf_solve_s": solve_r,
        "rancf_process_s": wall_r,
    }


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--case", nargs="+", choices=sorted(CASES), default=sorted(CASES))
    p.add_argument("--dt", type=float, default=1e-3, help="MoorDyn's step dtM [s]")
    p.add_argument("--rancf-step", type=float, default=None, help="rancf's step [s]")
    p.add_argument("--json", type=Path, default=None, help="also write the results here")
    p.add_argument(
        "--reference",
        type=Path,
        default=None,
        help="a folder: write MoorDyn's series to 12 s there (tests/references)",
    )
    a = p.parse_args()
    results = {}
    for case in a.case:
        results[case] = compare(case, a.dt, a.rancf_step, a.reference)
        print(json.dumps(results[case]))
    if a.json is not None:
        from provenance import machine, provenance

        results["provenance"] = {**provenance("rancf", "moordyn"), "machine": machine()}
        a.json.write_text(json.dumps(results, indent=1) + "\n")


if __name__ == "__main__":
    main()
