"""Dask clusters for sweeps and studies: a local cluster of worker processes (or threads), or an
existing scheduler; the settings that keep them quiet and cheap."""

from __future__ import annotations

import contextlib
import logging
import os
import re
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

from rancf.errors import InputError

__all__ = ["dask_client", "check_scheduler", "QUIET_DASK", "SCHEDULER_SCHEMES"]


#: Dask settings for the clusters and clients rancf starts itself: no statistical profiler
#: (it samples every worker thread every 10 ms), slower event-loop health ticks and resource
#: monitors, and no work stealing (runs last tens of ms to seconds, and each worker has one
#: thread).  Together they cut an idle cluster's CPU use about eightfold; only the dashboard's
#: profile and health views lose detail.
QUIET_DASK = {
    "distributed.worker.profile.enabled": False,
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "5s",
    "distributed.scheduler.work-stealing": False,
}


@contextmanager
def dask_client(
    scheduler: str | None, workers: int | None, processes: bool = True
) -> Iterator[Any]:
    """A Dask client: of the scheduler at ``scheduler``, or of a new local cluster of
    ``workers`` (default: the number of cores) one-thread worker processes listening on
    127.0.0.1 only, or, with ``processes=False``, worker threads of this process that talk to
    the scheduler in memory (no sockets)."""
    import dask
    from dask.distributed import Client, LocalCluster  # first: it adds its config defaults

    if scheduler is not None:
        check_scheduler(scheduler)
        try:
            client = Client(scheduler, timeout=30)
        except (OSError, TimeoutError, ValueError, TypeError) as exc:
            raise InputError(
                "--scheduler", scheduler, f"a reachable Dask scheduler ({exc})"
            ) from None
        with _log_level_kept(), client, _quiet_on_the_way_out():
            yield client
        return
    n = workers if workers is not None else (os.cpu_count() or 1)
    if isinstance(n, bool) or not isinstance(n, int) or n < 1:
        raise InputError("--workers", workers, "an integer >= 1")
    with dask.config.set(QUIET_DASK):
        with _quiet_children() if processes else contextlib.nullcontext():
            cluster = LocalCluster(
                n_workers=n,
                threads_per_worker=1,
                processes=processes,
                **({"protocol": "tcp://", "host": "127.0.0.1"} if processes else {}),
                dashboard_address=None,
                # its own logs stay silent: a run's failure is its row, and when Ctrl-C or
                # SIGTERM stop the workers with this process the scheduler's complaints about
                # them (lost keys, closed connections) would only hide the one line that counts
                silence_logs=logging.CRITICAL,
            )
        with _log_level_kept(), cluster, Client(cluster) as client, _quiet_on_the_way_out():
            yield client


@contextmanager
def _quiet_children() -> Iterator[None]:
    """Processes started inside the block (a local cluster's workers, multiprocessing's resource
    tracker) get /dev/null as their standard error: stopped by Ctrl-C or SIGTERM they would
    print connection tracebacks and warnings.  Their failures still reach the sweep: a run's
    exception is its row's message and its ``error.txt``, a lost worker a ``worker error`` row."""
    try:
        sys.stderr.flush()
        saved = os.dup(2)
    except (OSError, ValueError, AttributeError):  # pragma: no cover - no standard error
        yield
        return
    devnull = os.open(os.devnull, os.O_WRONLY)
    try:
        os.dup2(devnull, 2)
        yield
    finally:
        os.dup2(saved, 2)
        os.close(saved)
        os.close(devnull)


#: Address schemes of a Dask scheduler ``--scheduler`` accepts.
SCHEDULER_SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")


def check_scheduler(address: str) -> str:
    """Refuse a scheduler address that is not ``SCHEME://HOST:PORT`` (before any connection)."""
    m = re.fullmatch(r"([a-z]+)://(\[[0-9a-fA-F:.]+\]|[A-Za-z0-9_.-]+):(\d{1,5})", address)
    if m is None or m[1] not in SCHEDULER_SCHEMES or not 1 <= int(m[3]) <= 65535:
        schemes = "|".join(SCHEDULER_SCHEMES)
        raise InputError("--scheduler", address, f"an address {schemes}://HOST:PORT")
    return address


@contextmanager
def _quiet_on_the_way_out() -> Iterator[None]:
    """After an interrupt (or any error) in the block, Dask's own logs are silenced while the
    cluster is torn down: cancelled tasks and closed connections are expected then, and the
    command's one line says what happened."""
    try:
        yield
    except BaseException:
        logging.getLogger("distributed").setLevel(logging.CRITICAL + 1)
        raise


@contextmanager
def _log_level_kept() -> Iterator[None]:
    """Dask's log level as it was before the block, restored after it (and its teardown)."""
    log = logging.getLogger("distributed")
    level = log.level
    try:
        yield
    finally:
        log.setLevel(level)
