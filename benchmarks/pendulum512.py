"""The straight pendulum at 512 elements: `rancf simulate` against Exudyn, pairs interleaved.

    python benchmarks/pendulum512.py [--repeats 3] [--elements 512]

Two spans: 0.1 s, which Exudyn finishes with its default Newton settings (from t = 0.103 s on
its Newton stalls at a relative error of 1.0e-8 to 1.9e-8 against the 1e-8 asked, cuts the step
down to 1e-8 s and stops with ``SolveDynamic terminated``), and 0.5 s with Exudyn's
``newton.relativeTolerance = 1e-6``, with which it finishes (its tip over the first 0.1 s
differs from that at the default by 2e-11 m).  Each span with rancf's output every step (the
default) and every 10 ms; Exudyn stores the tip sensor at the same interval in memory, no
solution file (``cli_cases.py``).  Per-step times from each side's own report; the ratio is
taken pair by pair (median quoted).  Prints one JSON line a case, then the machine.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import statistics
import sys
import tempfile
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from cli_cases import SCENARIO, _run_rancf  # noqa: E402

CASES = (  # (span [s], Exudyn's relative Newton tolerance or None: its default)
    (0.1, None),
    (0.5, 1e-6),
)


def _run_exudyn(n: int, t_end: float, out: float | None, rel_tol: float | None) -> dict:
    import subprocess
    import time

    cmd = [sys.executable, str(HERE / "exudyn_pendulum.py"), "--elements", str(n)]
    cmd += ["--solver", "sparse", "--t-end", str(t_end)]
    cmd += [] if out is None else ["--output-step", str(out)]
    cmd += [] if rel_tol is None else ["--newton-rel-tol", str(rel_tol)]
    t0 = time.perf_counter()
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        last = (p.stderr.strip().splitlines() or ["?"])[-1]
        return {"failed": last, "wall_s": time.perf_counter() - t0}
    return json.loads(p.stdout.strip().splitlines()[-1])


def _cpu() -> str:
    """The CPU's name, family and model, and whether it has AVX2 and AVX-512 (Linux)."""
    try:
        info = {}
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            k, _, v = line.partition(":")
            info.setdefault(k.strip(), v.strip())
        flags = info.get("flags", "").split()
        simd = ", ".join(f for f in ("avx2", "avx512f") if f in flags) or "no AVX2"
        return (
            f"{info.get('model name', '?')} (family {info.get('cpu family', '?')} model "
            f"{info.get('model', '?')}; {simd})"
        )
    except OSError:
        return platform.processor() or "?"


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--elements", type=int, default=512)
    a = p.parse_args()
    n = a.elements
    with tempfile.TemporaryDirectory() as tmp:
        tmpd = Path(tmp)
        for t_end, rel_tol in CASES:
            for every in (None, 0.01):
                sc = tmpd / f"p{n}-{t_end}-{every}.toml"
                out = "" if every is None else f"output_step = {every}\n"
                sc.write_text(SCENARIO.format(n=n, t_end=t_end, out=out, newton=""))
                run_dir = tmpd / "run"
                _run_rancf(sc, run_dir)  # warm-up (file-system caches), not counted
                pairs, loads = [], []
                for _ in range(a.repeats):
                    r = _run_rancf(sc, run_dir)
                    e = _run_exudyn(n, t_end, every, rel_tol)
                    loads.append(os.getloadavg()[0])
                    pairs.append((r, e))
                    if "failed" in e:
                        break
                rows = [(r["solve_s"] / r["steps"], e) for r, e in pairs]
                row: dict[str, Any] = {
                    "elements": n,
                    "span_s": t_end,
                    "output": "every step" if every is None else f"every {every:g} s",
                    "exudyn_newton_relative_tolerance": rel_tol or "default (1e-8)",
                    "rancf_us_per_step": [round(1e6 * x, 1) for x, _ in rows],
                    "rancf_newton_per_step": pairs[0][0]["newton"] / pairs[0][0]["steps"],
                    "load_average": [round(x, 1) for x in loads],
                }
                if any("failed" in e for _, e in rows):
                    row["exudyn_failed"] = next(e["failed"] for _, e in rows if "failed" in e)
                else:
                    ex = [e["solve_s"] / e["steps"] for _, e in rows]
                    ratios = [x / y for (x, _), y in zip(rows, ex, strict=True)]
                    row.update(
                        exudyn_us_per_step=[round(1e6 * y, 1) for y in ex],
                        ratios=[round(x, 3) for x in ratios],
                        ratio_median=round(statistics.median(ratios), 3),
                        tip_difference_m=max(
                            abs(u - v)
                            for u, v in zip(pairs[-1][0]["tip"], rows[-1][1]["tip"], strict=True)
                        ),
                    )
                print(json.dumps(row), flush=True)
    print(json.dumps({"cpu": _cpu(), "cores": os.cpu_count(), "python": platform.python_version()}))


if __name__ == "__main__":
    main()
