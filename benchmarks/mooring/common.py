"""What the side-by-side mooring comparisons share: running the peer's scripts and rancf's CLI
as processes, reading rancf's outputs, and the table they print."""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

HERE = Path(__file__).resolve().parent
RESULTS = HERE / "results"


def peer(python: str, script: str, *args: str) -> tuple[Any, float]:
    """Run ``script`` of this folder with the peer's ``python``: its last stdout line as JSON
    and the process's wall time."""
    t0 = time.perf_counter()
    p = subprocess.run([python, str(HERE / script), *args], capture_output=True, text=True)
    wall = time.perf_counter() - t0
    if p.returncode:
        raise RuntimeError(f"{script} failed ({p.returncode}):\n{p.stderr[-2000:]}")
    return json.loads(p.stdout.strip().splitlines()[-1]), wall


def rancf(*args: str) -> tuple[subprocess.CompletedProcess, float]:
    """``rancf ARGS`` as a process (``python -m rancf`` of this interpreter) and its wall time."""
    t0 = time.perf_counter()
    p = subprocess.run([sys.executable, "-m", "rancf", *args], capture_output=True, text=True)
    return p, time.perf_counter() - t0


def failed(p: subprocess.CompletedProcess) -> str:
    """The last lines rancf wrote when it failed (a missing key of this branch, say)."""
    text = (p.stderr or p.stdout or "").strip().splitlines()
    last = text[-1] if text else f"exit status {p.returncode}"
    return last if len(last) <= 90 else last[:87] + "..."


def read_series(path: Path) -> dict[str, list[float]]:
    """A CSV with a header row as columns of floats."""
    with path.open() as f:
        rows = list(csv.reader(f))
    head, body = rows[0], rows[1:]
    return {k: [float(r[i]) for r in body] for i, k in enumerate(head)}


def fresh(folder: Path) -> Path:
    if folder.exists():
        shutil.rmtree(folder)
    return folder


def table(rows: list[list[str]]) -> str:
    """Rows of strings as a Markdown table (the first row the header)."""
    widths = [max(len(r[i]) for r in rows) for i in range(len(rows[0]))]
    lines = [
        "| " + " | ".join(c.ljust(w) for c, w in zip(r, widths, strict=True)) + " |" for r in rows
    ]
    lines.insert(1, "|" + "|".join("-" * (w + 2) for w in widths) + "|")
    return "\n".join(lines)
