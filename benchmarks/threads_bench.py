"""One run on one thread against the same run on two (`rancf simulate --threads 1` / `2`), as
whole processes, pairs interleaved, and whether their results are the same bit for bit.

    python benchmarks/threads_bench.py [--pairs 3] [--case pendulum512|mooring160]

* ``pendulum512``: `cli_cases.py`'s straight pendulum at 512 elements, 0.2 s, output every
  10 ms;
* ``mooring160``: the shipped `mooring-line` example (a 3D line from its static state, with
  buoyancy, Morison loads, a current and the seabed) at 160 elements, its first 2 s.

Per run: the loop's time per step from `summary.json` (`solve_wall_time_s / steps`), the
whole process's wall and CPU time (user + system of the child, all its threads), and, measured
around the run's time integration inside the child (``--child``), its wall time (``loop_s``),
the CPU time of the calling thread alone (``main_cpu_s``) and of the process (``loop_cpu_s``);
the ratio one thread / two threads pair by pair, medians printed as one JSON line, with
``identical``: every array of the two runs' `results.npz` equal.

On a shared machine a thread waits for a core, which wall times count and CPU times do not:
``speedup_main_cpu_s`` (the one-thread loop's CPU time over the two-thread loop's calling
thread's) is what the second core saves where both are free. The calling thread does every
sequential part and waits for the worker where it must, spinning (which counts as its CPU time),
so this ratio does not overstate the speed-up; ``loop_cpu_s`` shows the work the threads add.
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

import numpy as np

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from cli_cases import SCENARIO  # noqa: E402


def _scenario(case: str, tmp: Path) -> Path:
    sc = tmp / f"{case}.toml"
    if case == "pendulum512":
        sc.write_text(SCENARIO.format(n=512, t_end=0.2, out="output_step = 0.01\n", newton=""))
    else:
        from rancf.studies.common import example_path

        text = example_path("mooring-line").read_text()
        text = re.sub(r"(?m)^elements = \d+", "elements = 160", text)
        text = re.sub(r"(?m)^t_end = [\d.]+", "t_end = 2.0", text)
        sc.write_text(text)
    return sc


def _child(sc: str, out: str, threads: str) -> None:
    """`rancf simulate` in this process, its time integration timed (module docstring)."""
    import rancf.runs.simulate as sim
    from rancf.cli import main

    inner = sim.integrate
    times: dict[str, float] = {}

    def timed(*args: Any, **kwargs: Any) -> Any:
        t0, c0, p0 = time.perf_counter(), time.thread_time(), time.process_time()
        result = inner(*args, **kwargs)
        times["loop_s"] = time.perf_counter() - t0
        times["main_cpu_s"] = time.thread_time() - c0
        times["loop_cpu_s"] = time.process_time() - p0
        return result

    sim.integrate = timed  # type: ignore[assignment]
    status = main(["simulate", sc, "--out", out, "--quiet", "--threads", threads])
    print(json.dumps(times))
    sys.stdout.flush()
    os._exit(status)


def _run(sc: Path, out: Path, threads: int) -> dict[str, Any]:
    shutil.rmtree(out, ignore_errors=True)
    cmd = [sys.executable, __file__, "--child", str(sc), str(out), str(threads)]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    p = subprocess.run(cmd, check=True, capture_output=True, text=True)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    s = json.loads((out / "summary.json").read_text())
    inner = json.loads(p.stdout.strip().splitlines()[-1])
    step = s["solve_wall_time_s"] / s["steps"]
    return {"step_s": step, "wall_s": wall, "cpu_s": cpu, **inner}


def _identical(a: Path, b: Path) -> bool:
    with np.load(a / "results.npz") as x, np.load(b / "results.npz") as y:
        return x.files == y.files and all(np.array_equal(x[k], y[k]) for k in x.files)


def main(argv: list[str] | None = None) -> dict[str, Any]:
    if argv is None and sys.argv[1:2] == ["--child"]:
        _child(*sys.argv[2:5])
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--pairs", type=int, default=3)
    p.add_argument("--case", choices=["pendulum512", "mooring160"], default="pendulum512")
    a = p.parse_args(argv)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    one, two = [], []
    with tempfile.TemporaryDirectory() as tmp:
        sc = _scenario(a.case, Path(tmp))
        _run(sc, Path(tmp) / "warm", 1)
        for _ in range(a.pairs):
            one.append(_run(sc, Path(tmp) / "one", 1))
            two.append(_run(sc, Path(tmp) / "two", 2))
        same = _identical(Path(tmp) / "one", Path(tmp) / "two")
    out: dict[str, Any] = {"case": a.case, "pairs": a.pairs, "identical": same}
    for key in ("step_s", "wall_s", "cpu_s", "loop_s", "main_cpu_s", "loop_cpu_s"):
        out[f"one_{key}"] = statistics.median(r[key] for r in one)
        out[f"two_{key}"] = statistics.median(r[key] for r in two)
        out[f"speedup_{key}"] = statistics.median(
            x[key] / y[key] for x, y in zip(one, two, strict=True)
        )
    out["load_average"] = os.getloadavg()[0]
    print(json.dumps({k: round(v, 6) if isinstance(v, float) else v for k, v in out.items()}))
    return out


if __name__ == "__main__":
    main()
