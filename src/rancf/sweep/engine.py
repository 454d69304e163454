"""Running a sweep on Dask: a local cluster (processes, one thread each, bound to 127.0.0.1) or
an existing scheduler; resume, progress bar, ``results.csv``.

``DIR/results.csv`` has one row per run in grid order: ``run``, the grid values, ``status``
(``completed``/``failed``/``interrupted``, or ``pending`` before it ran), ``message``,
``warnings`` (the run's warnings as ``rancf simulate``, ``static`` or ``modes`` prints them,
joined by `` | ``: a completed run's numbers may still be suspect), ``wall_time_s`` (the
whole run in its worker), ``solve_time_s`` (the solver alone) and the result columns
(``simulate``: ``t_reached``, ``steps`` and the final sensor values; ``static``: the
equilibrium sensor values; ``modes``: ``f1_hz`` …).  It is rewritten atomically as runs
finish (at most every :data:`CSV_INTERVAL_S` seconds) and when the sweep ends or is interrupted;
each run's own ``row.json`` is written first, so the table can always be rebuilt from them.  A
run whose folder already holds ``row.json`` is not run again.
"""

from __future__ import annotations

import csv
import io
import json
import logging
import math
import shutil
import sys
import time
import uuid
from collections.abc import Callable, Iterable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

from rancf.atomic import atomic_write
from rancf.errors import InputError
from rancf.sweep.cluster import dask_client
from rancf.sweep.runner import ROW_FILE, run_variant, run_variants_in_order, scenario_hash
from rancf.sweep.spec import SweepSpec, Variant
from rancf.sweep.toml_out import with_absolute_paths

__all__ = [
    "run_sweep",
    "run_variants",
    "LocalExecutor",
    "DaskExecutor",
    "SweepExecutor",
    "SweepReport",
    "results_table",
]

logger = logging.getLogger(__name__)

#: Shortest interval between two rewrites of ``results.csv`` while runs finish (seconds): with
#: hundreds of short runs, rewriting the whole table after each one costs more than the runs.
CSV_INTERVAL_S = 1.0


@dataclass(frozen=True)
class SweepReport:
    """What a sweep did: runs in total, skipped (finished before), run now, failed, and the runs
    (of all) with warnings."""

    total: int
    skipped: int
    ran: int
    failed: int
    csv_path: Path
    warned: int = 0


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
    head = ["run", *keys, "status", "message", "warnings", "wall_time_s", "solve_time_s"]
    w.writerow([*head, *value_cols])
    for v in variants:
        r = rows.get(v.name, {"status": "pending", "message": "", "values": {}})
        vals = r.get("values", {})
        w.writerow(
            [
                v.name,
                *(v.values[k] for k in keys),
                r["status"],
                r.get("message", ""),
                " | ".join(r.get("warnings", ())),
                _num(r.get("wall_time_s")),
                _num(r.get("solve_time_s")),
                *(_num(vals.get(c)) for c in value_cols),
            ]
        )
    return buf.getvalue()


def _num(x: Any) -> str:
    """A number of the table: empty for none, or for a non-finite one (the row failed)."""
    return "" if x is None or not math.isfinite(float(x)) else repr(float(x))


#: ``on_done(name, row) -> names of later calls that are no longer needed``.
OnDone = Callable[[str, dict[str, Any]], Iterable[str]]


class SweepExecutor(Protocol):
    """What runs a sweep's calls: :class:`LocalExecutor`, :class:`DaskExecutor` or another
    object with the same :meth:`execute`."""

    def execute(self, calls: list[tuple[str, tuple[Any, ...]]], on_done: OnDone) -> None: ...


class LocalExecutor:
    """Runs the variants one after another in this process, in order (no Dask).

    The sequential baseline of a parallel sweep: the same :func:`run_variant` calls, so the
    same numbers.
    """

    description = "this process"

    def execute(self, calls: list[tuple[str, tuple[Any, ...]]], on_done: OnDone) -> None:
        """Call :func:`run_variant` with each ``(name, args)``; ``on_done(name, row)`` returns
        the names of calls still to come that are no longer needed (they are skipped)."""
        skip: set[str] = set()
        for name, args in calls:
            if name in skip:
                continue
            skip.update(on_done(name, run_variant(*args)))


class DaskExecutor:
    """Runs the variants on a Dask cluster, earlier calls first (Dask priorities).

    Parameters
    ----------
    client : dask.distributed.Client
        Of a local cluster (:func:`dask_client`) or an existing scheduler.
    priority : int
        When several executors share a cluster, the runs of one with a higher priority start
        before those of one with a lower priority.
    runs_per_task : int
        Consecutive calls sent as one Dask task (:func:`~rancf.sweep.runner.run_variants_in_order`):
        fewer, longer tasks cost the scheduler, the workers and this client less (a few ms of
        CPU per task), but a task is cancelled only when none of its runs is needed any more.
        1 (default) for grids that cancel runs; more for many short runs.
    """

    def __init__(self, client: Any, priority: int = 0, runs_per_task: int = 1) -> None:
        k = runs_per_task
        if isinstance(k, bool) or not isinstance(k, int) or k < 1:
            raise InputError("runs_per_task", runs_per_task, "an integer >= 1")
        self.client = client
        self.priority = priority
        self.runs_per_task = runs_per_task
        self.description = f"a Dask cluster of {len(client.scheduler_info()['workers'])} worker(s)"

    def execute(self, calls: list[tuple[str, tuple[Any, ...]]], on_done: OnDone) -> None:
        """Submit every call; ``on_done(name, row)`` (called as rows arrive, in any order across
        tasks, in call order within one) returns names of calls no longer needed: a task not
        started yet whose calls are all unneeded is cancelled."""
        from dask.distributed import as_completed

        token = uuid.uuid4().hex[:12]
        k = self.runs_per_task
        tasks = [calls[i : i + k] for i in range(0, len(calls), k)]
        futures = {}
        for i, task in enumerate(tasks):
            names = [name for name, _ in task]
            if len(task) == 1:
                fut = self.client.submit(
                    run_variant,
                    *task[0][1],
                    key=f"rancf-sweep-{names[0]}-{token}",
                    pure=False,
                    priority=self.priority * 1_000_000 + len(tasks) - i,
                )
            else:
                fut = self.client.submit(
                    run_variants_in_order,
                    [args for _, args in task],
                    key=f"rancf-sweep-{names[0]}+{len(task) - 1}-{token}",
                    pure=False,
                    priority=self.priority * 1_000_000 + len(tasks) - i,
                )
            futures[fut] = names
        by_name = {n: f for f, names in futures.items() for n in names}
        unneeded: set[str] = set()
        for fut in as_completed(list(futures)):
            if fut.cancelled():
                continue
            names = futures[fut]
            try:
                result = fut.result()
                rows = [result] if len(names) == 1 else result
            except Exception as exc:  # noqa: BLE001 - a lost worker: recorded, retried on resume
                rows = [{"status": "failed", "message": f"worker error: {exc}"}] * len(names)
            for name, row in zip(names, rows, strict=True):
                unneeded.update(on_done(name, row))
            for other in {by_name[n] for n in unneeded if n in by_name}:
                if not other.done() and all(n in unneeded for n in futures[other]):
                    other.cancel()


def run_variants(
    executor: SweepExecutor,
    variants: list[Variant],
    base: str | Path,
    analysis: str,
    out: str | Path,
    progress: bool = True,
    on_row: OnDone | None = None,
) -> dict[str, dict[str, Any]]:
    """Run every variant not finished yet into ``out/runs/<name>/``; keep ``out/results.csv``.

    Parameters
    ----------
    executor : SweepExecutor (LocalExecutor, DaskExecutor)
    variants : list of Variant
        In priority order (earlier ones start first).
    base : path
        The base scenario (relative CAD files are resolved against it).
    analysis : {"simulate", "static", "modes"}
    out : path
        The sweep directory.
    progress : bool
        Show a progress bar.
    on_row : callable, optional
        ``on_row(name, row)`` for each finished run (finished before included); returns the
        names of variants that are no longer needed (not started ones are skipped).

    Returns
    -------
    dict
        Run name -> result row (``run``, ``status``, ``message``, ``wall_time_s``,
        ``solve_time_s``, ``values``) of every finished run.
    """
    from tqdm import tqdm

    out = Path(out)
    if out.exists() and not out.is_dir():
        raise InputError("--out", str(out), "a directory (it exists and is a file)")
    runs = out / "runs"
    runs.mkdir(parents=True, exist_ok=True)
    rows = finished_rows(variants, base, analysis, out)
    for v in variants:  # a run of another scenario (the base or the grid changed): run again
        if v.name not in rows and (runs / v.name).is_dir():
            shutil.rmtree(runs / v.name)
    skip: set[str] = set()
    for name, row in list(rows.items()):
        if on_row is not None:
            skip.update(on_row(name, row))
    todo = [v for v in variants if v.name not in rows and v.name not in skip]
    csv_path = out / "results.csv"
    atomic_write(csv_path, results_table(variants, rows))
    if not todo:
        return rows
    shown = progress and sys.stderr.isatty()  # no carriage returns in logs
    bar = tqdm(
        total=len(variants), initial=len(rows), unit="run", file=sys.stderr, disable=not shown
    )

    written = time.monotonic()

    def done(name: str, row: dict[str, Any]) -> Iterable[str]:
        nonlocal written
        rows[name] = row
        if time.monotonic() - written >= CSV_INTERVAL_S:
            atomic_write(csv_path, results_table(variants, rows))
            written = time.monotonic()
        bar.update(1)
        return on_row(name, row) if on_row is not None else ()

    calls = [
        (v.name, (v.name, v.raw, str(base), analysis, str((runs / v.name).resolve()))) for v in todo
    ]
    try:
        executor.execute(calls, done)
    finally:
        bar.close()
        # runs that finished in a worker but whose row had not reached us (an interrupt)
        rows.update(finished_rows(variants, base, analysis, out))
        atomic_write(csv_path, results_table(variants, rows))
    return rows


def finished_rows(
    variants: list[Variant], base: str | Path, analysis: str, out: str | Path
) -> dict[str, dict[str, Any]]:
    """The rows of the runs in ``out/runs`` that finished for the scenario they have now: a
    readable ``row.json`` whose ``scenario_sha256`` is that of the variant's scenario (with
    its CAD file made absolute), ``analysis`` and the contents of the files it reads."""
    rows: dict[str, dict[str, Any]] = {}
    for v in variants:
        f = Path(out) / "runs" / v.name / ROW_FILE
        if not f.is_file():
            continue
        try:
            row = json.loads(f.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            continue  # a damaged row: run again
        want = scenario_hash(with_absolute_paths(v.raw, base), analysis, base)
        if isinstance(row, dict) and row.get("scenario_sha256") == want:
            rows[v.name] = row
    return rows


def run_sweep(
    spec: SweepSpec,
    out: str | Path,
    scheduler: str | None = None,
    workers: int | None = None,
    progress: bool = True,
    threads: int | None = None,
) -> SweepReport:
    """Run every variant not finished yet; write ``out/runs/<name>/`` and ``out/results.csv``.

    ``threads``: run them on that many threads of this process
    (:class:`~rancf.sweep.threads.ThreadExecutor`) instead of on Dask."""
    out = Path(out)
    variants = spec.variants()
    finished = (
        set(finished_rows(variants, spec.base, spec.analysis, out)) if out.is_dir() else set()
    )
    if len(finished) == len(variants):
        rows = run_variants(LocalExecutor(), variants, spec.base, spec.analysis, out, progress)
    elif threads is not None:
        from rancf.sweep.threads import ThreadExecutor

        rows = run_variants(
            ThreadExecutor(threads), variants, spec.base, spec.analysis, out, progress
        )
    else:
        try:
            with dask_client(scheduler, workers) as client:
                rows = run_variants(
                    DaskExecutor(client), variants, spec.base, spec.analysis, out, progress
                )
        finally:  # the workers are stopped now: the table holds every run that finished
            if (out / "results.csv").is_file():
                done = finished_rows(variants, spec.base, spec.analysis, out)
                atomic_write(out / "results.csv", results_table(variants, done))
    skipped = sum(1 for name in finished if name in rows)
    failed = sum(1 for r in rows.values() if r.get("status") != "completed")
    warned = sum(1 for r in rows.values() if r.get("warnings"))
    return SweepReport(
        len(variants), skipped, len(variants) - skipped, failed, out / "results.csv", warned
    )
