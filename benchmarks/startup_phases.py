"""Where a `rancf simulate` start-up goes: the imports and the first read of a scenario, timed
in order in fresh processes (the figures of the performance page's "Whole process" item).

    python benchmarks/startup_phases.py [--runs 5]

Each run is a new interpreter (``OPENBLAS_NUM_THREADS=1``, as ``rancf simulate`` sets it) that
times, one after the other: NumPy and the compiled core; pydantic; the scenario modules (the
model classes and the modules of ours they import); the import of pydantic's plugin loader
(``importlib.metadata``, which the first read would import); the first ``load_scenario`` of the
8-element pendulum of ``cli_cases.py`` (pydantic looks up its plugins and builds the validator
of the whole tree) and a second one; the modules of a run (checks, the run folder, the time
loop, the start); building the system and its initial state.  Across all of them, the CPU time
of making dataclasses (``dataclasses``' class processing, which compiles each class's methods;
rancf's own and the other packages'), measured by wrapping it.  Prints the median of every
phase over the runs, in seconds, wall and CPU (user + system of the process: the steadier
figure on a shared machine), as one JSON line.
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
import dataclasses, json, sys, time
marks = [("start", time.perf_counter(), time.process_time())]
def mark(name):
    marks.append((name, time.perf_counter(), time.process_time()))
made = {"rancf": 0.0, "other": 0.0}
_process_class = dataclasses._process_class
def timed_class(cls, *args, **kwargs):
    t0 = time.process_time()
    try:
        return _process_class(cls, *args, **kwargs)
    finally:
        key = "rancf" if cls.__module__.startswith("rancf") else "other"
        made[key] += time.process_time() - t0
dataclasses._process_class = timed_class
import numpy, rancf.kernels._core
mark("numpy and the core")
import pydantic
from pydantic import BaseModel
mark("pydantic")
import rancf.scenario.scenario
mark("scenario modules")
import pydantic.plugin._loader
mark("pydantic's plugin loader (importlib.metadata)")
from rancf.scenario import load_scenario
sc = load_scenario(sys.argv[1])
mark("first read")
load_scenario(sys.argv[1])
mark("second read")
from rancf.post.checks import before_run_warnings
from rancf.post.history import HistoryStore
from rancf.post.run_plan import plan_run
from rancf.solvers.dynamic import integrate
from rancf.solvers.start import start_state
mark("run modules")
system, outputs = plan_run(sc, 10.0)
start_state(sc, system)
mark("build and start")
out = {}
for (_, w0, c0), (name, w1, c1) in zip(marks, marks[1:]):
    out[name], out[name + " (CPU)"] = w1 - w0, c1 - c0
out["of all: making rancf's dataclasses (CPU)"] = made["rancf"]
out["of all: making other dataclasses (CPU)"] = made["other"]
print(json.dumps(out))
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
