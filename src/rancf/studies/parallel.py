"""Running several studies: one after another in this process, or all at once on every core.

:func:`run_studies_here` is the sequential baseline: every run in this process, in order.
:func:`run_studies_parallel` starts one driver process per study and one local Dask cluster
(``workers`` processes on 127.0.0.1); each driver sends its mesh grid to the cluster through
the sweep engine and draws its own figures, so the drivers' figures, meshes and GIFs overlap
with the other studies' runs; the grids run in the order of ``names`` (the first studies draw
the most figures, so theirs are done while the last grid runs).  The drivers start before the
cluster: what a study computes before its grid (6.3, which has no mesh grid, is all of it)
overlaps with the cluster's start-up, and a driver connects when it reaches its grid.  Both
give the same numbers: the runs are the same function calls on the same scenarios.
"""

from __future__ import annotations

import importlib
import multiprocessing
import sys
from concurrent.futures import ProcessPoolExecutor
from contextlib import ExitStack
from pathlib import Path
from typing import Any

from rancf.studies import runs_a_grid, study_runner
from rancf.studies.common import StudyResult
from rancf.sweep.engine import OnDone

__all__ = ["run_studies_here", "run_studies_parallel", "run_on_cluster"]

#: Seconds a driver waits for the cluster's address before it gives up.
CLUSTER_START_TIMEOUT = 120.0
#: Longest scheduler address the drivers can be told (bytes).
_ADDRESS_SIZE = 256
#: Runs per Dask task (:class:`~rancf.sweep.engine.DaskExecutor`) of grids that never cancel a
#: run: the exact-geometry grid's 260 runs take about 40 ms each, and a task costs the cluster
#: and the driver a few ms of CPU.  Convergence grids (6.1, 6.2) cancel sizes: one run a task.
RUNS_PER_TASK = {"exact-geometry": 5}


def run_studies_here(names: list[str], out: Path, quick: bool) -> dict[str, StudyResult]:
    """Run the studies ``names`` into ``out/<name>/`` one after another in this process."""
    return {name: study_runner(name)(out / name, quick) for name in names}


def run_on_cluster(
    name: str, out: Path, quick: bool, address: str, priority: int = 0
) -> StudyResult:
    """Run one study (in a driver process) with its mesh grid on the Dask scheduler at
    ``address``; grids of a higher ``priority`` go first."""
    from dask.distributed import Client

    from rancf.sweep.engine import DaskExecutor

    if not runs_a_grid(name):
        return study_runner(name)(out, quick)
    with Client(address, timeout=30) as client:
        executor = DaskExecutor(client, priority, RUNS_PER_TASK.get(name, 1))
        return study_runner(name)(out, quick, executor)


class ClusterWhenReady:
    """A sweep executor for a driver started before its cluster: at its first grid it waits
    for the scheduler's address (set by :func:`run_studies_parallel`), connects, and runs the
    grid as :class:`~rancf.sweep.engine.DaskExecutor` does; :meth:`close` disconnects."""

    def __init__(self, priority: int, runs_per_task: int = 1) -> None:
        self.priority = priority
        self.runs_per_task = runs_per_task
        self._stack = ExitStack()
        self._executor: Any = None

    def execute(self, calls: list[tuple[str, tuple[Any, ...]]], on_done: OnDone) -> None:
        """Run ``calls`` on the cluster (see :meth:`rancf.sweep.engine.DaskExecutor.execute`)."""
        if self._executor is None:
            from dask.distributed import Client

            from rancf.sweep.engine import DaskExecutor

            client = self._stack.enter_context(Client(_cluster_address(), timeout=30))
            self._executor = DaskExecutor(client, self.priority, self.runs_per_task)
        self._executor.execute(calls, on_done)

    def close(self) -> None:
        self._stack.close()


def run_studies_parallel(
    names: list[str], out: Path, quick: bool, workers: int
) -> dict[str, StudyResult]:
    """Run the studies ``names`` into ``out/<name>/`` at once: one driver process per study,
    their mesh grids on a local Dask cluster of ``workers`` processes."""
    from rancf.sweep.engine import dask_client

    ctx = _context()
    ready, address = ctx.Event(), ctx.Array("c", _ADDRESS_SIZE)
    with ProcessPoolExecutor(
        len(names), mp_context=ctx, initializer=_driver_init, initargs=(ready, address)
    ) as pool:
        # the drivers start now, before the cluster's threads exist (safe to fork)
        list(pool.map(_warm, range(len(names))))
        futures = {
            n: pool.submit(_drive, n, out / n, quick, len(names) - i) for i, n in enumerate(names)
        }
        try:
            with dask_client(None, workers, processes=False) as client:
                address.value = client.scheduler.address.encode()
                ready.set()
                return {n: f.result() for n, f in futures.items()}
        finally:
            ready.set()  # a driver still waiting now learns that there is no cluster


# the cluster's address in a driver process (inherited from run_studies_parallel)
_READY: Any = None
_ADDRESS: Any = None


def _driver_init(ready: Any, address: Any) -> None:
    global _READY, _ADDRESS
    _READY, _ADDRESS = ready, address


def _cluster_address() -> str:
    if not _READY.wait(CLUSTER_START_TIMEOUT) or not _ADDRESS.value:
        raise RuntimeError("the local Dask cluster did not start")
    return _ADDRESS.value.decode()


def _drive(name: str, out: Path, quick: bool, priority: int) -> StudyResult:
    """One study in a driver process; its grid goes to the cluster once the cluster is up."""
    if not runs_a_grid(name):
        return study_runner(name)(out, quick)
    executor = ClusterWhenReady(priority, RUNS_PER_TASK.get(name, 1))
    try:
        return study_runner(name)(out, quick, executor)
    finally:
        executor.close()


def _context() -> multiprocessing.context.BaseContext:
    """``fork`` on Linux after importing what the drivers need (each spawned driver would
    spend about 2 s of CPU importing it again), else ``spawn``."""
    if sys.platform != "linux":
        return multiprocessing.get_context("spawn")
    import dask.distributed  # noqa: F401

    from rancf.post.plots import pyplot

    pyplot()
    for name in (
        "planar_pendulum", "spatial_pendulum", "arc_vibration", "exact_geometry", "exudyn_cable"
    ):  # fmt: skip
        importlib.import_module(f"rancf.studies.{name}")
    return multiprocessing.get_context("fork")


def _warm(i: int) -> int:
    return i
