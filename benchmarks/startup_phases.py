"""Where a `rancf simulate` start-up goes: the imports and the first read of a scenario, timed
in order in fresh processes (the figures of the performance page's "Whole process" item).

    python benchmarks/startup_phases.py [--runs 5]

Each run is a new interpreter (``OPENBLAS_NUM_THREADS=1``, as ``rancf simulate`` sets it) that
times, one after the other: NumPy and the compiled core; pydantic; the scenario modules (the
model classes and the modules of ours they import); the first ``load_scenario`` of the
8-element pendulum of ``cli_cases.py`` (pydantic builds the validator of the whole tree) and a
second one.  Prints the median of every phase over the runs, in seconds, as one JSON line.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cli_cases import SCENARIO  # noqa: E402

CODE = """
import json, sys, time
t0 = time.perf_counter()
import numpy, rancf.kernels._core
t1 = time.perf_counter()
import pydantic
from pydantic import BaseModel
t2 = time.perf_counter()
import rancf.scenario.scenario
t3 = time.perf_counter()
from rancf.scenario import load_scenario
load_scenario(sys.argv[1])
t4 = time.perf_counter()
load_scenario(sys.argv[1])
t5 = time.perf_counter()
print(json.dumps({"numpy and the core": t1 - t0, "pydantic": t2 - t1,
                  "scenario modules": t3 - t2, "first read": t4 - t3, "second read": t5 - t4}))
"""


def main(argv: list[str] | None = None) -> dict[str, float]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--runs", type=int, default=5)
    a = p.parse_args(argv)
    env = {**os.environ, "OPENBLAS_NUM_THREADS": "1"}
    runs = []
    with tempfile.TemporaryDirectory() as tmp:
        sc = Path(tmp) / "p8.toml"
        sc.write_text(SCENARIO.format(n=8, t_end=1.0, out="output_step = 0.01\n", newton=""))
        for _ in range(a.runs):
            out = subprocess.run(
                [sys.executable, "-c", CODE, str(sc)],
                env=env,
                check=True,
                capture_output=True,
                text=True,
            ).stdout
            runs.append(json.loads(out.strip().splitlines()[-1]))
    med = {k: statistics.median(r[k] for r in runs) for k in runs[0]}
    print(json.dumps({k: round(v, 4) for k, v in med.items()}))
    return med


if __name__ == "__main__":
    main()
