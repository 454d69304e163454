"""`rancf report` on every core against one after another, as whole processes, in pairs.

    python benchmarks/report_ratio.py [--pairs N] [--quick] [--out DIR]

Each pair runs ``rancf report --workers 1`` (every run in one process) and then
``rancf report --workers 2`` (the default on a 2-core machine: one driver process per study,
the grids on a local Dask cluster), each into a fresh folder, and records per run the wall time
the report prints, the whole process's wall time and its CPU time (user + system of the process
tree), and whether every study table of the two runs is identical (wall-time columns aside;
:func:`rancf.studies.report.study_tables`).  Ratios are parallel / sequential, pair by pair; the
medians are printed and written to ``DIR/report_ratio.json`` (default ``benchmarks/results``).
Run it on a quiet machine: another job on one of the two cores makes the ratio say more about
the machine than about the report.
"""

from __future__ import annotations

import argparse
import datetime
import json
import os
import platform
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

from rancf.studies.report import study_tables

RANCF = [sys.executable, "-m", "rancf"]


def _children_cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def run_report(out: Path, workers: int, quick: bool) -> dict[str, float]:
    """One ``rancf report`` as a whole process: printed wall time, process wall and CPU time."""
    argv = [*RANCF, "report", "--out", str(out), "--workers", str(workers)]
    cpu0, t0 = _children_cpu(), time.perf_counter()
    done = subprocess.run([*argv, *(["--quick"] if quick else [])], capture_output=True, text=True)
    wall, cpu = time.perf_counter() - t0, _children_cpu() - cpu0
    if done.returncode != 0:
        raise SystemExit(f"{' '.join(argv)} failed ({done.returncode}):\n{done.stderr[-2000:]}")
    printed = re.search(r"wall time ([\d.]+) s on", done.stderr)
    if printed is None:
        raise SystemExit(f"no 'wall time' line in the output of {' '.join(argv)}")
    return {"printed_s": float(printed.group(1)), "process_s": wall, "cpu_s": cpu}


def main(argv: list[str] | None = None) -> dict[str, Any]:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--pairs", type=int, default=3, help="number of pairs (default 3)")
    ap.add_argument("--quick", action="store_true", help="the reduced studies (report --quick)")
    ap.add_argument("--out", default=str(Path(__file__).parent / "results"), help="result folder")
    args = ap.parse_args(argv)
    pairs = []
    with tempfile.TemporaryDirectory() as tmp:
        for i in range(args.pairs):
            seq, par = Path(tmp, f"seq{i}"), Path(tmp, f"par{i}")
            a = run_report(seq, 1, args.quick)
            b = run_report(par, 2, args.quick)
            same = study_tables(seq) == study_tables(par)
            pair = {
                "workers_1": a,
                "workers_2": b,
                "ratio_printed": b["printed_s"] / a["printed_s"],
                "ratio_process": b["process_s"] / a["process_s"],
                "tables_identical": same,
                "tables": len(study_tables(seq)),
            }
            pairs.append(pair)
            print(
                f"pair {i + 1}: {a['printed_s']:.1f} s / {b['printed_s']:.1f} s = "
                f"{pair['ratio_printed']:.3f} (whole process {a['process_s']:.2f} / "
                f"{b['process_s']:.2f} s = {pair['ratio_process']:.3f}; CPU {a['cpu_s']:.1f} / "
                f"{b['cpu_s']:.1f} s); {pair['tables']} tables "
                + ("identical" if same else "DIFFER")
            )
    result = {
        "date": datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds"),
        "machine": {"cpus": os.cpu_count(), "python": platform.python_version()},
        "quick": args.quick,
        "pairs": pairs,
        "median_ratio_printed": statistics.median(p["ratio_printed"] for p in pairs),
        "median_ratio_process": statistics.median(p["ratio_process"] for p in pairs),
        "all_tables_identical": all(p["tables_identical"] for p in pairs),
    }
    print(
        f"median ratio {result['median_ratio_printed']:.3f} (whole process "
        f"{result['median_ratio_process']:.3f}); tables identical in every pair: "
        f"{result['all_tables_identical']}"
    )
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "report_ratio.json").write_text(json.dumps(result, indent=2) + "\n", encoding="utf-8")
    return result


if __name__ == "__main__":
    main()
