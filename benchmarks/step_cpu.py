"""CPU time a step of the straight pendulum (`cli_cases.py`'s scenario), stored every step (the
default) and every 10 ms, in `rancf simulate` and in the Exudyn script, from whole processes.

    taskset -c 0 python benchmarks/step_cpu.py --elements 8 32 128 512 [--pairs 3]
        [--install before=PATH --install after=PATH]

A time a step from a run's own clock (``solve_wall_time_s``) is wall time: on a core shared
with other processes it counts their time too.  Here every case runs at two lengths, ``T`` and
``T / 2`` (``--t-end``; by default longer for small models), and the CPU time of a step is the
difference of the two processes' CPU times (user + system, all threads: rows derived on a
worker thread count) over the difference of their steps: start-up, set-up and the files'
fixed part cancel, what grows with the steps stays (the steps, the rows derived and
written).  One pair runs every case at both lengths in turn; the ratios (every step over every
10 ms; rancf over Exudyn) are taken pair by pair and their median printed.
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
import tempfile
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
from cli_cases import SCENARIO  # noqa: E402

STEP = 1e-3
#: Default run length [s] by elements: enough steps that the noise of a process's CPU time
#: (about 10 ms on a shared core) is a few per cent of the difference.
T_END = {8: 16.0, 32: 6.0, 128: 2.0, 512: 0.6}


def _cpu(cmd: list[str], env: dict[str, str] | None = None) -> float:
    """The CPU time (user + system) of the process ``cmd``."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(cmd, check=True, capture_output=True, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)


def _rancf(tmp: Path, n: int, t_end: float, every: float | None) -> list[str]:
    scenario = tmp / f"p{n}-{t_end:g}-{every}.toml"
    out = "" if every is None else f"output_step = {every}\n"
    scenario.write_text(SCENARIO.format(n=n, t_end=t_end, out=out, newton=""))
    folder = tmp / "run"
    shutil.rmtree(folder, ignore_errors=True)
    return [
        sys.executable,
        "-m",
        "rancf",
        "simulate",
        str(scenario),
        "--out",
        str(folder),
        "--quiet",
    ]


def _exudyn(n: int, t_end: float, every: float | None) -> list[str]:
    cmd = [sys.executable, str(HERE / "exudyn_pendulum.py"), "--elements", str(n)]
    cmd += ["--solver", "dense" if n < 128 else "sparse", "--t-end", str(t_end)]
    return cmd + ([] if every is None else ["--output-step", str(every)])


def measure(
    n: int, t_end: float, pairs: int, exudyn: bool, tmp: Path, installs: dict[str, str]
) -> dict[str, Any]:
    """µs of CPU a step of every case (medians) and the ratios, pair by pair, for ``n``
    elements; ``installs``: label -> ``PYTHONPATH`` of the rancf sources to run (label
    ``rancf``: this environment's)."""
    codes = list(installs) + (["exudyn"] if exudyn else [])
    order = [(code, every) for code in codes for every in (None, 0.01)]
    steps = {t: round(t / STEP) for t in (t_end, t_end / 2)}
    per_step: dict[tuple[str, float | None], list[float]] = {c: [] for c in order}
    for _ in range(pairs):
        for code, every in order:
            cpu = {}
            for t in steps:
                if code == "exudyn":
                    cpu[t] = _cpu(_exudyn(n, t, every))
                else:
                    env = dict(os.environ)
                    if installs[code]:
                        env["PYTHONPATH"] = installs[code]
                    cpu[t] = _cpu(_rancf(tmp, n, t, every), env)
            grown = cpu[t_end] - cpu[t_end / 2]
            per_step[(code, every)].append(1e6 * grown / (steps[t_end] - steps[t_end / 2]))
    row: dict[str, Any] = {"elements": n, "t_end": t_end, "pairs": pairs}
    for (code, every), vals in per_step.items():
        row[f"{code} {'every step' if every is None else 'every 10 ms'} [µs CPU]"] = (
            statistics.median(vals)
        )

    def ratio(a: tuple[str, float | None], b: tuple[str, float | None]) -> float:
        return statistics.median(x / y for x, y in zip(per_step[a], per_step[b], strict=True))

    for code in installs:
        row[f"{code} every step / every 10 ms"] = ratio((code, None), (code, 0.01))
        if exudyn:
            row[f"{code} / Exudyn, every step"] = ratio((code, None), ("exudyn", None))
            row[f"{code} / Exudyn, every 10 ms"] = ratio((code, 0.01), ("exudyn", 0.01))
    return row


def main(argv: list[str] | None = None) -> list[dict[str, Any]]:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--elements", type=int, nargs="+", default=[8, 32, 128, 512])
    p.add_argument("--pairs", type=int, default=3)
    p.add_argument("--t-end", type=float, default=None, help="T [s] (default: by size)")
    p.add_argument(
        "--no-exudyn",
        action="store_true",
        help="rancf's two outputs only (Exudyn's pendulum of 512 elements slows down to many "
        "minutes, or gives up, after about 0.1 s on the machine of the performance page)",
    )
    p.add_argument(
        "--install",
        action="append",
        default=[],
        metavar="LABEL=PATH",
        help="rancf from the sources at PATH (its PYTHONPATH), repeatable; default: this one",
    )
    a = p.parse_args(argv)
    installs = dict(x.split("=", 1) for x in a.install) or {"rancf": ""}
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for n in a.elements:
            t_end = a.t_end if a.t_end is not None else T_END.get(n, 0.4)
            rows.append(measure(n, t_end, a.pairs, not a.no_exudyn, Path(tmp), installs))
            print(json.dumps(rows[-1], ensure_ascii=False), flush=True)
    return rows


if __name__ == "__main__":
    main()
