"""Running a sweep on Dask: a local cluster (processes, one thread each, bound to 127.0.0.1) or
an existing scheduler; resume, progress bar, ``results.csv``.

``DIR/results.csv`` has one row per run in grid order: ``run``, the grid values, ``status``
(``completed``/``failed``/``interrupted``, or ``pending`` before it ran), ``message``,
``wall_time_s`` (the whole run in its worker), ``solve_time_s`` (the solver alone) and the
result columns (``simulate``: ``t_reached``, ``steps`` and the final sensor values; ``static``:
the equilibrium sensor values; ``modes``: ``f1_hz`` …).  It is rewritten atomically after each
finished run.  A run whose folder already holds ``row.json`` is not run again.
"""

from __future__ import annotations

import csv
import io
import json
import logging
import os
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rancf.errors import InputError
from rancf.post.results import atomic_write
from rancf.sweep.runner import ROW_FILE, run_variant
from rancf.sweep.spec import SweepSpec, Variant

__all__ = ["run_sweep", "SweepReport", "dask_client", "results_table"]

logger = logging.getLogger(__name__)


@dataclass(frozen=True)
class SweepReport:
    """What a sweep did: runs in total, skipped (finished before), run now, failed."""

    total: int
    skipped: int
    ran: int
    failed: int
    csv_path: Path


@contextmanager
def dask_client(scheduler: str | None, workers: int | None) -> Iterator[Any]:
    """A Dask client: of the scheduler at ``scheduler``, or of a new local cluster of
    ``workers`` processes (default: the number of cores) listening on 127.0.0.1 only."""
    from dask.distributed import Client, LocalCluster

    if scheduler is not None:
        try:
            client = Client(scheduler, timeout=30)
        except (OSError, TimeoutError) as exc:
            raise InputError(
                "--scheduler", scheduler, f"a reachable Dask scheduler ({exc})"
            ) from None
        with client:
            yield client
        return
    n = workers if workers is not None else (os.cpu_count() or 1)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise InputError("--workers", workers, "an integer >= 1")
    with (
        LocalCluster(
            n_workers=n,
            threads_per_worker=1,
            processes=True,
            host="127.0.0.1",
            dashboard_address=None,
            silence_logs=logging.ERROR,
        ) as cluster,
        Client(cluster) as client,
    ):
        yield client


def results_table(variants: list[Variant], rows: dict[str, dict[str, Any]]) -> str:
    """CSV text of the results (see the module docstring)."""
    keys = list(variants[0].values) if variants else []
    value_cols: list[str] = []
    for v in variants:
        for c in rows.get(v.name, {}).get("values", {}):
            if c not in value_cols:
                value_cols.append(c)
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(["run", *keys, "status", "message", "wall_time_s", "solve_time_s", *value_cols])
    for v in variants:
        r = rows.get(v.name, {"status": "pending", "message": "", "values": {}})
        vals = r.get("values", {})
        w.writerow(
            [
                v.name,
                *(v.values[k] for k in keys),
                r["status"],
                r.get("message", ""),
                _num(r.get("wall_time_s")),
                _num(r.get("solve_time_s")),
                *(_num(vals.get(c)) for c in value_cols),
            ]
        )
    return buf.getvalue()


def _num(x: Any) -> str:
    return "" if x is None else repr(float(x))


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool = True,
) -> SweepReport:
    """Run every variant not finished yet; write ``out/runs/<name>/`` and ``out/results.csv``."""
    from tqdm import tqdm

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a directory (it exists and is a file)")
    runs = out / "runs"
    runs.mkdir(parents=True, exist_ok=True)
    variants = spec.variants()
    rows: dict[str, dict[str, Any]] = {}
    for v in variants:
        f = runs / v.name / ROW_FILE
        if f.is_file():
            try:
                rows[v.name] = json.loads(f.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                pass  # a damaged row: run again
    skipped = len(rows)
    todo = [v for v in variants if v.name not in rows]
    csv_path = out / "results.csv"
    atomic_write(csv_path, results_table(variants, rows))
    if todo:
        bar = tqdm(
            total=len(variants), initial=skipped, unit="run", file=sys.stderr, disable=not progress
        )
        with dask_client(scheduler, workers) as client:
            from dask.distributed import as_completed

            futures = {
                client.submit(
                    run_variant,
                    v.name,
                    v.raw,
                    str(spec.base),
                    spec.analysis,
                    str((runs / v.name).resolve()),
                    key=f"rancf-sweep-{v.name}-{os.getpid()}",
                    pure=False,
                ): v
                for v in todo
            }
            for fut in as_completed(futures):
                v = futures[fut]
                try:
                    rows[v.name] = fut.result()
                except Exception as exc:  # noqa: BLE001 - a lost worker: recorded, retried on resume
                    rows[v.name] = {"status": "failed", "message": f"worker error: {exc}"}
                atomic_write(csv_path, results_table(variants, rows))
                bar.update(1)
        bar.close()
    failed = sum(1 for r in rows.values() if r.get("status") != "completed")
    return SweepReport(len(variants), skipped, len(todo), failed, csv_path)
