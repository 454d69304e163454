"""What storing every step costs at 512 elements: `rancf simulate` of the straight pendulum
(`cli_cases.py`'s scenario, n = 512, 0.5 s, h = 1 ms) with output every step against output
every 10 ms, as whole processes, pairs interleaved.

Each pair runs both output intervals one after the other (for every install given, in turn),
so machine drift cancels in the ratios.  Per run: the loop's time per step from `summary.json`
(`solve_wall_time_s / steps`: the steps and the output rows derived and appended while they
run, in the loop or, where the run folder has an output worker, beside it), the whole
process's wall time and its CPU time (user + system of the child, all its threads).  The
ratios every step / every 10 ms are taken pair by pair; medians are printed.

    python benchmarks/outputs512.py --pairs 3
    python benchmarks/outputs512.py --pairs 3 --install main=/path/to/unpacked/wheel

``--install LABEL=PATH`` runs ``python -S`` with ``PYTHONPATH=PATH:<this environment's
site-packages>`` (an unpacked wheel of another version, without this environment's editable
install); without it, this interpreter as installed.
"""

from __future__ import annotations

import argparse
import json
import os
import resource
import shutil
import statistics
import subprocess
import sys
import sysconfig
import tempfile
import time
from pathlib import Path
from typing import Any

sys.path.insert(0, str(Path(__file__).resolve().parent))
from cli_cases import SCENARIO  # noqa: E402


def _run(cmd: list[str], env: dict[str, str], scenario: Path, out: Path) -> dict[str, float]:
    shutil.rmtree(out, ignore_errors=True)
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    t0 = time.perf_counter()
    args = [*cmd, "-m", "rancf", "simulate", str(scenario), "--out", str(out), "--quiet"]
    subprocess.run(args, check=True, capture_output=True, env=env)
    wall = time.perf_counter() - t0
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    s = json.loads((out / "summary.json").read_text())
    return {
        "step_us": 1e6 * s["solve_wall_time_s"] / s["steps"],
        "wall_s": wall,
        "cpu_s": cpu,
        "steps": s["steps"],
    }


def main(argv: list[str] | None = None) -> dict[str, Any]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--pairs", type=int, default=3)
    p.add_argument("--elements", type=int, default=512)
    p.add_argument("--t-end", type=float, default=0.5)
    p.add_argument("--install", action="append", default=[], metavar="LABEL=PATH")
    a = p.parse_args(argv)
    site = sysconfig.get_paths()["purelib"]
    installs: list[tuple[str, list[str], dict[str, str]]] = []
    for spec in a.install:
        label, path = spec.split("=", 1)
        env = {**os.environ, "PYTHONPATH": f"{path}{os.pathsep}{site}"}
        installs.append((label, [sys.executable, "-S"], env))
    if not installs:
        installs.append(("this", [sys.executable], dict(os.environ)))
    runs: dict[tuple[str, str], list[dict[str, float]]] = {}
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        cases = {"every step": "", "every 10 ms": "output_step = 0.01\n"}
        files = {}
        for case, out in cases.items():
            files[case] = tmpd / f"{len(files)}.toml"
            text = SCENARIO.format(n=a.elements, t_end=a.t_end, out=out, newton="")
            files[case].write_text(text)
        for _, cmd, env in installs:  # warm-up: byte code, file-system caches
            _run(cmd, env, files["every 10 ms"], tmpd / "warm")
        for i in range(a.pairs):
            for label, cmd, env in installs:
                for case in cases:
                    r = _run(cmd, env, files[case], tmpd / "run")
                    r["load"] = os.getloadavg()[0]
                    runs.setdefault((label, case), []).append(r)
                    print(
                        f"pair {i + 1} {label:8s} {case:12s} {r['step_us']:8.1f} µs/step  "
                        f"wall {r['wall_s']:6.2f} s  CPU {r['cpu_s']:6.2f} s  "
                        f"load {r['load']:.1f}",
                        flush=True,
                    )
    report: dict[str, Any] = {}
    for label, _, _ in installs:
        every, ten = runs[(label, "every step")], runs[(label, "every 10 ms")]
        ratios = {
            key: [e[key] / t[key] for e, t in zip(every, ten, strict=True)]
            for key in ("step_us", "wall_s", "cpu_s")
        }
        extra = [
            (e["cpu_s"] - t["cpu_s"]) / e["steps"] * 1e6 for e, t in zip(every, ten, strict=True)
        ]
        report[label] = {
            **{
                f"median {k} every step": statistics.median(r[k] for r in every)
                for k in ("step_us", "wall_s", "cpu_s")
            },
            **{
                f"median {k} every 10 ms": statistics.median(r[k] for r in ten)
                for k in ("step_us", "wall_s", "cpu_s")
            },
            **{f"ratio {k}": statistics.median(v) for k, v in ratios.items()},
            **{f"ratio {k} range": (min(v), max(v)) for k, v in ratios.items()},
            "extra CPU a step stored [µs]": statistics.median(extra),
        }
        print(label, json.dumps(report[label], indent=1))
    return report


if __name__ == "__main__":
    main()
