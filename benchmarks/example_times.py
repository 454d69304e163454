"""The run time of every shipped example, as a user runs it: ``rancf example run NAME``.

    python benchmarks/example_times.py [--repeats N] [--out DIR] [--only NAME ...]

Each example runs as a whole process (``python -m rancf example run NAME --out TMP --workers
1``: import, set-up, every analysis the example lists, its figures and report), ``--repeats``
times in turn; the median and the spread of the wall time are kept with the CPU they ran on.
Writes ``example_times.json`` to ``--out`` (default ``benchmarks/results``) and prints the
table that ``docs/guide/examples-time.md`` quotes (a test checks that the page lists every
shipped example).
"""

from __future__ import annotations

import argparse
import json
import platform
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE / "mooring"))

from provenance import cpu_model  # noqa: E402


def example_names() -> list[str]:
    """Every shipped example: the paper studies and the scenario examples."""
    from rancf.studies.catalog import EXAMPLES, SCENARIO_ANALYSES

    return [*EXAMPLES, *SCENARIO_ANALYSES]


def time_example(name: str, repeats: int) -> dict[str, Any]:
    """Median, min and max wall time [s] of ``rancf example run NAME`` over ``repeats`` runs."""
    walls = []
    for _ in range(repeats):
        with tempfile.TemporaryDirectory() as tmp:
            cmd = [
                sys.executable,
                "-m",
                "rancf",
                "example",
                "run",
                name,
                "--out",
                tmp,
                "--workers",
                "1",
            ]
            t0 = time.perf_counter()
            subprocess.run(cmd, check=True, capture_output=True)
            walls.append(time.perf_counter() - t0)
    return {
        "example": name,
        "median_s": statistics.median(walls),
        "min_s": min(walls),
        "max_s": max(walls),
        "repeats": repeats,
    }


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=3)
    p.add_argument("--out", default=str(HERE / "results"))
    p.add_argument("--only", nargs="*", default=None)
    args = p.parse_args()
    rows = [time_example(n, args.repeats) for n in (args.only or example_names())]
    doc = {
        "cpu": cpu_model(),
        "cores": __import__("os").cpu_count(),
        "python": platform.python_version(),
        "date": time.strftime("%Y-%m-%d"),
        "rows": rows,
    }
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    (out / "example_times.json").write_text(json.dumps(doc, indent=2) + "\n")
    print(f"{doc['cpu']}, {doc['cores']} cores, Python {doc['python']}, {doc['date']}")
    print("| example | wall time (median) | min – max |")
    print("|---|---|---|")
    for r in rows:
        spread = f"{r['min_s']:.1f} – {r['max_s']:.1f} s"
        print(f"| `{r['example']}` | {r['median_s']:.1f} s | {spread} |")


if __name__ == "__main__":
    main()
