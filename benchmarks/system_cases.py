"""System benchmarks: systems through `rancf simulate`, side by side with Exudyn.

    python benchmarks/system_cases.py [--repeats N] [--out DIR]

* ``slider-crank`` and ``spin-up``: the shipped examples as they are (``rancf simulate`` as a
  whole process) against the Exudyn models of the same size, step and ρ∞
  (``exudyn_slider_crank.py``, ``exudyn_spinup.py``: ANCF cables, index-3 constraints, Exudyn's
  faster linear solver for the size, chosen by a short trial of each; Exudyn's sensors stored
  at the example's output interval, in memory).  Per step: each side's
  own solve time over its steps (rancf: ``summary.json``; Exudyn: ``SolveDynamic``); set-up:
  process start to the first step (rancf: ``setup_wall_time_s``; Exudyn: imports and
  ``Assemble``); pairs interleaved (A B A B ...), the ratio taken pair by pair, median quoted.
* ``chain``: 10 cables of 100 elements joined end to end by 9 pins against one cable of 1000
  elements (a hanging chain released from the horizontal), both through ``rancf simulate``: the
  cost of joints in the bordered band solve.

Writes ``system_bench.json`` to ``--out`` (default ``benchmarks/results``) and prints a table.
"""

from __future__ import annotations

import argparse
import json
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from importlib import resources
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent

CABLE = """
[[bodies]]
name = "c{i}"
[bodies.geometry]
kind = "line"
start = [{x0}, 0.0]
end = [{x1}, 0.0]
[bodies.mesh]
elements = {n}
element = "ancf"
[bodies.section]
radius = 0.01
[bodies.material]
density = 7800.0
youngs_modulus = 2.0e9
"""

TAIL = """
[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.2
step = 1.0e-3
output_step = 0.01
"""


def chain_scenario(pieces: int, per_piece: int) -> str:
    """``pieces`` cables of ``per_piece`` elements over 10 m, pinned to each other, the first
    pinned at the origin (one cable of ``pieces * per_piece`` elements for ``pieces = 1``)."""
    length = 10.0 / pieces
    text = "".join(
        CABLE.format(i=i, x0=i * length, x1=(i + 1) * length, n=per_piece) for i in range(pieces)
    )
    text += '\n[[supports]]\nat = "c0:start"\nkind = "pin"\n'
    for i in range(pieces - 1):
        between = f'["c{i}:end", "c{i + 1}:start"]'
        text += f'\n[[joints]]\nname = "j{i}"\nkind = "pin"\nbetween = {between}\n'
    return text + TAIL


def run_rancf(scenario: Path, out: Path) -> dict[str, Any]:
    """``rancf simulate`` as a whole process; per-step and set-up times from its summary."""
    shutil.rmtree(out, ignore_errors=True)
    t0 = time.perf_counter()
    cmd = [sys.executable, "-m", "rancf", "simulate", str(scenario), "--out", str(out), "--quiet"]
    subprocess.run(cmd, check=True, capture_output=True)
    wall = time.perf_counter() - t0
    s = json.loads((out / "summary.json").read_text())
    return {
        "wall_s": wall,
        "solve_s": s["solve_wall_time_s"],
        "steps": s["steps"],
        "setup_s": s["setup_wall_time_s"],
        "newton": s["newton_iterations"],
    }


def run_exudyn(script: str, args: list[str]) -> dict[str, Any]:
    t0 = time.perf_counter()
    p = subprocess.run(
        [sys.executable, str(HERE / script), *args], capture_output=True, text=True, check=True
    )
    out = json.loads(p.stdout.strip().splitlines()[-1])
    out["wall_s"] = time.perf_counter() - t0
    return out


def _med(xs: list[float]) -> float:
    return float(statistics.median(xs))


def _pairs(fa: Any, fb: Any, repeats: int) -> dict[str, Any]:
    fa(), fb()  # warm-up
    a, b = [], []
    for _ in range(repeats):
        a.append(fa())
        b.append(fb())
    per = [
        (x["solve_s"] / x["steps"]) / (y["solve_s"] / y["steps"]) for x, y in zip(a, b, strict=True)
    ]
    return {
        "a_us_per_step": 1e6 * _med([x["solve_s"] / x["steps"] for x in a]),
        "b_us_per_step": 1e6 * _med([y["solve_s"] / y["steps"] for y in b]),
        "a_setup_s": _med([x["setup_s"] for x in a]),
        "b_setup_s": _med([y["setup_s"] for y in b]),
        "a_process_s": _med([x["wall_s"] for x in a]),
        "b_process_s": _med([y["wall_s"] for y in b]),
        "steps": [a[0]["steps"], b[0]["steps"]],
        "ratio": _med(per),
        "ratios": per,
    }


EXUDYN = {  # example -> (script, its arguments: the example's size, step, output, t_end, rho_inf)
    "slider-crank": (
        "exudyn_slider_crank.py",
        [
            "--elements",
            "8",
            "--step",
            "2e-5",
            "--output-step",
            "1e-3",
            "--t-end",
            "0.2",
            "--rho-inf",
            "0.9",
        ],
    ),
    "spin-up-beam": (
        "exudyn_spinup.py",
        [
            "--elements",
            "8",
            "--step",
            "1e-3",
            "--output-step",
            "1e-2",
            "--t-end",
            "20",
            "--rho-inf",
            "0.0",
        ],
    ),
}


def _solver(script: str, args: list[str]) -> str:
    """Exudyn's faster linear solver for the case (a short run of each)."""
    short = [*args[:-4], "--t-end", "0.01" if "slider" in script else "0.5", *args[-2:]]
    times = {s: run_exudyn(script, [*short, "--solver", s])["solve_s"] for s in ("dense", "sparse")}
    return min(times, key=times.get)


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=5)
    p.add_argument("--out", default=str(HERE / "results"))
    p.add_argument("--chain-only", action="store_true", help="only the chain against one cable")
    a = p.parse_args()
    rows: dict[str, Any] = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        for name, (script, args) in EXUDYN.items() if not a.chain_only else ():
            scenario = Path(str(resources.files("rancf.examples") / f"{name}.toml"))
            solver = _solver(script, args)
            row = _pairs(
                lambda sc=scenario, n=name: run_rancf(sc, tmpd / n),
                lambda s=script, x=args, v=solver: run_exudyn(s, [*x, "--solver", v]),
                a.repeats,
            )
            rows[name] = {"exudyn_solver": solver, **row}
        chain, one = tmpd / "chain.toml", tmpd / "one.toml"
        chain.write_text(chain_scenario(10, 100))
        one.write_text(chain_scenario(1, 1000))
        rows["chain 10 x 100 vs 1 x 1000"] = _pairs(
            lambda: run_rancf(chain, tmpd / "chain"),
            lambda: run_rancf(one, tmpd / "one"),
            a.repeats,
        )
    out = Path(a.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "system_bench.json").write_text(json.dumps(rows, indent=2) + "\n")
    print(
        f"{'case':30s} {'rancf us/step':>14s} {'other us/step':>14s} {'ratio':>7s} "
        f"{'setup rancf/other s':>20s}"
    )
    for name, r in rows.items():
        print(
            f"{name:30s} {r['a_us_per_step']:14.1f} {r['b_us_per_step']:14.1f} "
            f"{r['ratio']:7.3f} {r['a_setup_s']:9.3f}/{r['b_setup_s']:.3f}"
        )


if __name__ == "__main__":
    main()
