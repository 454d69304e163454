"""Running several studies: one after another in this process, or all at once on every core.

:func:`run_studies_here` is the sequential baseline: every run in this process, in order.

:func:`run_studies_parallel` forks one driver process per study and then starts one local Dask
cluster in this process (``workers`` worker threads, in-process transport: the compiled core
releases the GIL while it integrates, so no worker processes, imports or sockets are needed).
Each driver runs its study as ``--workers 1`` would, but its mesh grids go through the sweep
engine to a :class:`RelayExecutor`, which hands the calls over a pipe to a thread of this
process; that thread runs them on the cluster with :class:`~rancf.sweep.engine.DaskExecutor` and
sends each finished row back, and the driver's answer (runs no longer needed) back again.  So the
drivers draw their figures and animations while the other studies' runs go on, the cluster
has a single client, and the drivers never import Dask.  The grids run in the order of
``names`` (Dask priorities: the first studies draw the most figures after their grid, so theirs
are done while the last grid runs).  Both functions give the same numbers: the runs are the
same function calls on the same scenarios, and the drivers see the rows in the order they
finish, as a grid on the cluster of ``rancf sweep`` would.
"""

from __future__ import annotations

import importlib
import multiprocessing
import signal
import sys
import threading
from concurrent.futures import ProcessPoolExecutor
from multiprocessing.connection import Connection
from pathlib import Path
from typing import Any

from rancf.studies import runs_a_grid, study_runner
from rancf.studies.common import StudyResult
from rancf.sweep.engine import OnDone

__all__ = ["run_studies_here", "run_studies_parallel", "RelayExecutor"]

#: Runs per Dask task (:class:`~rancf.sweep.engine.DaskExecutor`) of grids that never cancel a
#: run: the exact-geometry grid's 260 runs take about 20 ms each, and a task costs the cluster
#: a few ms of CPU.  Convergence grids (6.1, 6.2) cancel sizes: one run a task.
RUNS_PER_TASK = {"exact-geometry": 5}


def run_studies_here(
    folders: dict[str, Path], quick: bool, results: dict[str, StudyResult] | None = None
) -> dict[str, StudyResult]:
    """Run each study ``name`` into ``folders[name]`` one after another in this process.

    ``results`` (default: a new dict) receives each study's result as it finishes, so a caller
    still has the finished ones when a later study fails or is interrupted; it is returned.
    """
    results = {} if results is None else results
    for name, out in folders.items():
        results[name] = study_runner(name)(out, quick)
    return results


class RelayExecutor:
    """A sweep executor that runs a driver's calls on the cluster of the process that forked it.

    The driver sends ``("execute", calls)`` over ``conn`` and answers every ``("row", name,
    row)`` with ``("answer", names)`` (what ``on_done(name, row)`` returned) until ``("done",)``;
    ``("error", message)`` raises.  If ``on_done`` raises, the driver sends ``("stop",)`` and the
    grid is abandoned; :meth:`close` sends ``("end",)``.  The other end is :func:`_serve`.
    """

    description = "the report's Dask cluster"

    def __init__(self, conn: Connection) -> None:
        self.conn = conn

    def execute(self, calls: list[tuple[str, tuple[Any, ...]]], on_done: OnDone) -> None:
        """Run ``calls`` (see :meth:`rancf.sweep.engine.DaskExecutor.execute`)."""
        self.conn.send(("execute", calls))
        while True:
            msg = self.conn.recv()
            if msg[0] == "done":
                return
            if msg[0] == "error":
                raise RuntimeError(f"the report's Dask cluster: {msg[1]}")
            try:
                unneeded = list(on_done(msg[1], msg[2]))
            except BaseException:
                self.conn.send(("stop",))
                raise
            self.conn.send(("answer", unneeded))

    def close(self) -> None:
        """Tell the cluster side that this driver sends no more grids."""
        self.conn.send(("end",))


def run_studies_parallel(
    folders: dict[str, Path],
    quick: bool,
    workers: int,
    results: dict[str, StudyResult] | None = None,
) -> dict[str, StudyResult]:
    """Run each study ``name`` into ``folders[name]``, all at once: one driver process per
    study, their mesh grids on a local Dask cluster of ``workers`` threads in this process.

    ``results`` receives each study's result as it finishes (see :func:`run_studies_here`); a
    study that raises does not stop the others, and the first such error is raised at the end.
    """
    from concurrent.futures import as_completed

    from threadpoolctl import threadpool_limits

    results = {} if results is None else results
    names = list(folders)
    ctx = _context()
    pipes = {n: ctx.Pipe() for n in names if runs_a_grid(n)}
    ends = {n: child for n, (_, child) in pipes.items()}
    # one BLAS thread per process: more would only spin on cores the runs already use
    with (
        threadpool_limits(1),
        ProcessPoolExecutor(
            len(names), mp_context=ctx, initializer=_driver_init, initargs=(ends,)
        ) as pool,
    ):
        # the drivers start now, before this process has any thread (safe to fork)
        list(pool.map(_warm, range(len(names))))
        for child in ends.values():
            child.close()  # the drivers hold their own copies
        futures = {n: pool.submit(_drive, n, folders[n], quick) for n in names}
        from rancf.sweep.cluster import dask_client

        with dask_client(None, workers, processes=False) as client:
            servers = [
                threading.Thread(
                    target=_serve,
                    args=(
                        parent,
                        client,
                        len(names) - names.index(n),
                        RUNS_PER_TASK.get(n, 1),
                        len(names),
                    ),
                    name=f"rancf-relay-{n}",
                    daemon=True,
                )
                for n, (parent, _) in pipes.items()
            ]
            for t in servers:
                t.start()
            errors = []
            name_of = {f: n for n, f in futures.items()}
            try:
                for f in as_completed(futures.values()):
                    try:
                        results[name_of[f]] = f.result()
                    except Exception as exc:  # noqa: BLE001 - raised once the others are done
                        errors.append(exc)
            finally:  # interrupted: keep every study that did finish
                for n, f in futures.items():
                    if n not in results and f.done() and not f.cancelled():
                        if f.exception() is None:
                            results[n] = f.result()
            for t in servers:
                t.join()  # each driver has sent "end"
            if errors:
                raise errors[0]
            return {n: results[n] for n in names}


def _serve(
    conn: Connection, client: Any, priority: int, runs_per_task: int, stride: int = 0
) -> None:
    """The cluster side of one driver's :class:`RelayExecutor` (a thread of the report).

    The driver's first grid runs with ``priority``, each later one ``stride`` lower (a study's
    second grid, which waits for what the study drew after its first, goes after every
    study's first grid).
    """
    from rancf.sweep.engine import DaskExecutor

    executor = DaskExecutor(client, priority, runs_per_task)

    def relay(name: str, row: dict[str, Any]) -> list[str]:
        conn.send(("row", name, row))
        answer = conn.recv()
        if answer[0] != "answer":
            raise _DriverStopped(answer[0])
        return list(answer[1])

    try:
        while True:
            msg = conn.recv()
            if msg[0] == "end":
                return
            try:
                executor.execute(msg[1], relay)
            except _DriverStopped as stop:
                if stop.args[0] == "end":
                    return
                continue
            except Exception as exc:  # noqa: BLE001 - the driver raises it with the message
                conn.send(("error", f"{type(exc).__name__}: {exc}"))
                continue
            finally:
                executor.priority -= stride
            conn.send(("done",))
    except (EOFError, OSError):
        return


class _DriverStopped(Exception):
    """The driver stopped its grid (``"stop"``: its ``on_done`` raised) or ended (``"end"``)."""


# the driver ends of the pipes (inherited from run_studies_parallel by fork)
_ENDS: dict[str, Connection] = {}


def _driver_init(ends: dict[str, Connection]) -> None:
    global _ENDS
    _ENDS = ends
    _idle_signals()


def _idle_signals() -> None:
    """A driver without a study ignores Ctrl-C and ends silently on SIGTERM: the report process
    handles both (an interrupt there would only print a worker's traceback)."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _on_sigterm(signum: int, frame: Any) -> None:
    raise KeyboardInterrupt


def _drive(name: str, out: Path, quick: bool) -> StudyResult:
    """One study in a driver process; its grids go to the report's cluster.  While it runs, Ctrl-C
    and SIGTERM stop it (its future then holds the KeyboardInterrupt)."""
    signal.signal(signal.SIGINT, signal.default_int_handler)
    signal.signal(signal.SIGTERM, _on_sigterm)
    executor = RelayExecutor(_ENDS[name]) if name in _ENDS else None
    try:
        if executor is None:
            return study_runner(name)(out, quick)
        return study_runner(name)(out, quick, executor)
    finally:
        if executor is not None:
            executor.close()
        _idle_signals()


def _context() -> multiprocessing.context.BaseContext:
    """``fork`` on Linux after importing what the drivers need, else ``spawn``.

    Everything a driver would import after the fork is imported here, once: each driver would
    otherwise import it again (scipy.optimize, used by three drivers, costs 0.4 s of CPU each),
    and a first drawing with text loads the fonts the drivers share.
    """
    if sys.platform != "linux":
        return multiprocessing.get_context("spawn")
    import io

    for name in _PRE_FORK:
        importlib.import_module(name)
    from rancf.post.plots import pyplot

    plt = pyplot()
    fig, ax = plt.subplots(figsize=(2, 2), constrained_layout=True)
    ax.semilogy([1, 2], [1, 10], label="warm")
    ax.set(title="warm", xlabel="x", ylabel="y")
    ax.legend(fontsize=7)
    fig.savefig(io.BytesIO(), format="png", dpi=60)
    plt.close(fig)
    return multiprocessing.get_context("fork")


#: Modules the drivers use, imported before they are forked.
_PRE_FORK = (
    "scipy.optimize",
    "tqdm",
    "matplotlib.animation",
    "PIL.GifImagePlugin",
    "PIL.PngImagePlugin",
    "rancf.extras",
    "rancf.examples",
    "rancf.post.run_data",
    "rancf.post.run_plots",
    "rancf.sweep.engine",
    "rancf.studies.planar_pendulum",
    "rancf.studies.spatial_pendulum",
    "rancf.studies.arc_vibration",
    "rancf.studies.exact_geometry",
    "rancf.studies.exudyn_cable",
)


def _warm(i: int) -> int:
    return i
