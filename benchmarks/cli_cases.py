"""`rancf simulate` against the equivalent Exudyn script, as whole processes, pairs interleaved.

Each pair runs A (`rancf simulate SCENARIO --out DIR --quiet`) then B (`exudyn_pendulum.py`),
outputs matched: rancf stores its state and the tip sensor every output interval (by default
every step), Exudyn the tip sensor at the same interval (in memory, no solution file);
per-step times come from each side's own report (rancf: `summary.json`, `solve_wall_time_s /
steps`; Exudyn: its script's solve time), whole-process wall times are measured from outside,
and the ratio A/B is taken pair by pair (median quoted), so machine drift cancels.

Run it with a wheel install (``pip install .`` into its own environment), as users have it: an
editable install with ``editable.rebuild`` runs CMake twice at every start to check the build,
and without compiled byte code (``PYTHONDONTWRITEBYTECODE``) every module is compiled at every
start; both are set-up time a user's install does not have.
"""

from __future__ import annotations

import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent

SCENARIO = """\
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.2, 0.0]

[mesh]
elements = {n}
element = "ancf"

[section]
radius = 0.02

[material]
density = 6000.0
youngs_modulus = 2.0e8

[[supports]]
at = "start"
kind = "pin"

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = {t_end}
step = 1.0e-3
rho_inf = 0.9
{out}{newton}

[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""


def _run_rancf(scenario: Path, out: Path) -> dict[str, Any]:
    shutil.rmtree(out, ignore_errors=True)  # a new folder each time (untimed), as --out wants
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "rancf", "simulate", str(scenario), "--out", str(out), "--quiet"]
    subprocess.run(cmd, check=True, capture_output=True)
    wall = time.perf_counter() - t0
    s = json.loads((out / "summary.json").read_text())
    lines = (out / "sensors.csv").read_text().splitlines()
    tip = dict(zip(lines[0].split(","), map(float, lines[-1].split(",")), strict=True))
    return {
        "wall_s": wall,
        "solve_s": s["solve_wall_time_s"],
        "setup_s": s.get("setup_wall_time_s"),
        "steps": s["steps"],
        "newton": s["newton_iterations"],
        "tip": [tip.get("tip_x"), tip.get("tip_y")],
    }


def _run_exudyn(n: int, solver: str, t_end: float, out: float | None = None) -> dict[str, Any]:
    """One run of the Exudyn script (its sensor every ``out`` s, default every step);
    ``failed`` (with its last message line) if it gave up."""
    t0 = time.perf_counter()
    cmd = [sys.executable, str(HERE / "exudyn_pendulum.py"), "--elements", str(n)]
    cmd += ["--solver", solver, "--t-end", str(t_end)]
    cmd += [] if out is None else ["--output-step", str(out)]
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["?"])[-1]
        return {"failed": last, "wall_s": wall}
    out = json.loads(p.stdout.strip().splitlines()[-1])
    out["wall_s"] = wall
    return out


def simulate_cases(
    ns: list[int],
    newtons: list[str | None],
    repeats: int,
    t_end: float,
    exudyn: bool,
    outputs: tuple[float | None, ...] = (None,),
) -> list[dict[str, Any]]:
    """Per-step and whole-process times of the straight pendulum through `rancf simulate`.

    ``newtons``: ``solver.newton`` (None: the default); ``outputs``: output intervals [s] (None:
    the default, every step), Exudyn's tip sensor at the same interval.  A size where Exudyn
    gives up is measured once (its failure is recorded, not a ratio).
    """
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        for n in ns:
            solver = "dense"
            if exudyn:  # Exudyn's faster linear solver for this size, from a short run of each
                trial = min(t_end, 0.02)
                trials = {s: _run_exudyn(n, s, trial) for s in ("dense", "sparse")}
                times = {s: r.get("solve_s", float("inf")) for s, r in trials.items()}
                solver = min(times, key=times.get)
            for newton in newtons:
                for every in outputs:
                    sc = tmpd / f"p{n}-{newton}-{every}.toml"
                    sc.write_text(
                        SCENARIO.format(
                            n=n,
                            t_end=t_end,
                            out="" if every is None else f"output_step = {every}\n",
                            newton="" if newton is None else f'newton = "{newton}"\n',
                        )
                    )
                    out = tmpd / f"run{n}-{newton}"
                    a_runs, b_runs = [], []
                    _run_rancf(sc, out)  # warm-up (file-system caches), not counted
                    for _ in range(repeats):
                        a_runs.append(_run_rancf(sc, out))
                        if exudyn:
                            b_runs.append(_run_exudyn(n, solver, t_end, every))
                            if "failed" in b_runs[-1]:
                                break
                    rows.append(_row(n, newton, solver, a_runs, b_runs, every))
    return rows


def _med(runs: list[dict[str, Any]], key: str) -> float | None:
    vals = [r[key] for r in runs if r.get(key) is not None]
    return statistics.median(vals) if vals else None


def _row(
    n: int, newton: str | None, solver: str, a: list[dict], b: list[dict], every: float | None
) -> dict[str, Any]:
    steps = a[0]["steps"]
    outs = "output every step" if every is None else f"output every {every:g} s"
    row: dict[str, Any] = {
        "case": f"simulate pendulum {n} el ({newton or 'default'} Newton, {outs})",
        "elements": n,
        "output_step": every,
        "steps": steps,
        "newton_iterations": a[0]["newton"],
        "rancf_us_per_step": 1e6 * _med([{"x": r["solve_s"] / r["steps"]} for r in a], "x"),
        "rancf_ns_per_element_iteration": 1e9
        * _med([{"x": r["solve_s"] / r["newton"] / n} for r in a], "x"),
        "rancf_setup_s": _med(a, "setup_s"),
        "rancf_process_s": _med(a, "wall_s"),
        "rancf_tip": a[-1]["tip"],
    }
    if b and "failed" in b[-1]:
        row.update(
            exudyn_solver=solver, exudyn_failed=b[-1]["failed"], exudyn_wall_s=b[-1]["wall_s"]
        )
    elif b:
        pairs = list(zip(a, b, strict=True))
        ratios = [(x["solve_s"] / x["steps"]) / (y["solve_s"] / y["steps"]) for x, y in pairs]
        wall_ratios = [x["wall_s"] / y["wall_s"] for x, y in pairs]
        row.update(
            exudyn_solver=solver,
            exudyn_us_per_step=1e6 * _med([{"x": r["solve_s"] / r["steps"]} for r in b], "x"),
            exudyn_setup_s=_med(b, "setup_s"),
            exudyn_process_s=_med(b, "wall_s"),
            ratio=statistics.median(ratios),
            process_ratio=statistics.median(wall_ratios),
            exudyn_tip=b[-1]["tip"],
        )
    return row
