"""Running several studies: one after another in this process, or all at once on every core.

:func:`run_studies_here` is the sequential baseline: every run in this process, in order.
:func:`run_studies_parallel` starts one local Dask cluster (``workers`` processes on
127.0.0.1) and one driver process per study; each driver sends its mesh grid to the cluster
through the sweep engine and draws its own figures, so the drivers' figures, meshes and GIFs
overlap with the other studies' runs; the grids run in the order of ``names`` (the first
studies draw the most figures, so theirs are done while the last grid runs).  A study without
a mesh grid (6.3) runs whole in its driver.  Both give the same numbers: the runs are the same
function calls on the same scenarios.
"""

from __future__ import annotations

import importlib
import multiprocessing
import sys
from concurrent.futures import ProcessPoolExecutor
from pathlib import Path

from rancf.studies import runs_a_grid, study_runner
from rancf.studies.common import StudyResult

__all__ = ["run_studies_here", "run_studies_parallel", "run_on_cluster"]


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
        return study_runner(name)(out, quick, DaskExecutor(client, priority))


def run_studies_parallel(
    names: list[str], out: Path, quick: bool, workers: int
) -> dict[str, StudyResult]:
    """Run the studies ``names`` into ``out/<name>/`` at once: one driver process per study,
    their mesh grids on a local Dask cluster of ``workers`` processes."""
    from rancf.sweep.engine import dask_client

    with ProcessPoolExecutor(len(names), mp_context=_context()) as pool:
        # the drivers start now, before the cluster's threads exist (safe to fork)
        list(pool.map(_warm, range(len(names))))
        with dask_client(None, workers) as client:
            address = client.scheduler.address
            futures = {
                n: pool.submit(run_on_cluster, n, out / n, quick, address, len(names) - i)
                for i, n in enumerate(names)
            }
            return {n: f.result() for n, f in futures.items()}


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
