"""The static catenaries through ``rancf static --json`` as whole processes.

    python benchmarks/catenary_cases.py [--repeats N]

SSNL114 (Irvine's elastic catenary, 325 m, from the straight stress-free line, 40 elements) and a
slack steel cable hanging from a curved reference (80 m span, 82 m arc, 32 elements), scenario
files in ``benchmarks/scenarios``.  Per case: the solve time and Newton iterations that the
command reports (``wall_time_s``, ``newton_iterations``: the static solve alone), the whole
process's wall time (median over the repeats), and the mid-span sag.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
CASES = {"SSNL114 catenary, 40 el": "ssnl114.toml", "slack catenary, 32 el": "slack-catenary.toml"}


def measure(repeats: int = 5) -> list[dict[str, Any]]:
    rows = []
    for name, file in CASES.items():
        cmd = [sys.executable, "-m", "rancf", "static", str(HERE / "scenarios" / file), "--json"]
        subprocess.run(cmd, check=True, capture_output=True)  # warm-up
        walls, solves, out = [], [], {}
        for _ in range(repeats):
            t0 = time.perf_counter()
            p = subprocess.run(cmd, check=True, capture_output=True, text=True)
            walls.append(time.perf_counter() - t0)
            out = json.loads(p.stdout)
            solves.append(out["wall_time_s"])
        rows.append(
            {
                "case": f"static {name}",
                "rancf_s": statistics.median(solves),
                "process_s": statistics.median(walls),
                "newton_iterations": out["newton_iterations"],
                "load_steps": len(out["load_factors"]) - 1,
                "mid_sag_m": -out["sensors"]["mid_y"],
            }
        )
    return rows


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=5)
    for row in measure(p.parse_args().repeats):
        print(json.dumps(row))


if __name__ == "__main__":
    main()
