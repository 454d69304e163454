"""Ensembles in one process: independent runs on threads, each with its own model.

The time loop of a run is compiled and releases the interpreter lock while it steps
(:meth:`rancf.kernels._core.SystemIntegrator.run`), so runs on several threads step on several
cores at once; the Python between the compiled calls (building the model, storing a block of
outputs) takes turns.  Every run has its own :class:`~rancf.system.System` (its own compiled
model and work arrays), so a run's numbers do not depend on the others or on the number of
threads: they are those of the same run alone.

:func:`run_ensemble` integrates given systems; :class:`ThreadExecutor` runs the variants of a
sweep (``rancf sweep --threads N``) the same way, without Dask.
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from rancf.errors import InputError
from rancf.solvers.dynamic import DynamicOptions, DynamicResult, integrate
from rancf.sweep.runner import run_variant
from rancf.system import System

__all__ = ["run_ensemble", "ThreadExecutor", "default_threads"]


def default_threads() -> int:
    """The cores this process may use (its CPU affinity; else the machine's count)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except (AttributeError, OSError):  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _check_threads(threads: int | None) -> int:
    if threads is None:
        return default_threads()
    if isinstance(threads, bool) or not isinstance(threads, int) or threads < 1:
        raise InputError("threads", threads, "an integer >= 1")
    return threads


def run_ensemble(
    systems: Sequence[System],
    options: DynamicOptions | Sequence[DynamicOptions],
    threads: int | None = None,
) -> list[DynamicResult]:
    """Integrate every system (:func:`rancf.solvers.dynamic.integrate`) on ``threads`` threads
    of this process (default: the cores it may use); the results in the order of ``systems``.

    Parameters
    ----------
    systems : sequence of System
        One per run, each a separate object (a run steps its own compiled model).
    options : DynamicOptions or sequence of them
        For all runs, or one per run.
    threads : int, optional

    Raises
    ------
    InputError
        The same System given twice, options of another length, or ``threads`` < 1.
    """
    n = _check_threads(threads)
    if len({id(s) for s in systems}) != len(systems):
        raise InputError("systems", "a System given twice", "one System object per run")
    opts = [options] * len(systems) if isinstance(options, DynamicOptions) else list(options)
    if len(opts) != len(systems):
        raise InputError("options", f"{len(opts)} options", f"one or {len(systems)} (one a run)")
    if n == 1:
        return [integrate(s, o) for s, o in zip(systems, opts, strict=True)]
    with ThreadPoolExecutor(max_workers=n, thread_name_prefix="rancf-run") as pool:
        return list(pool.map(integrate, systems, opts))


class ThreadExecutor:
    """Runs a sweep's variants on threads of this process (:func:`run_ensemble`'s way): the same
    :func:`~rancf.sweep.runner.run_variant` calls as :class:`~rancf.sweep.engine.LocalExecutor`,
    so the same numbers.

    Parameters
    ----------
    threads : int, optional
        Default: the cores this process may use.
    """

    def __init__(self, threads: int | None = None) -> None:
        self.threads = _check_threads(threads)
        self.description = f"{self.threads} thread(s) of this process"

    def execute(
        self,
        calls: list[tuple[str, tuple[Any, ...]]],
        on_done: Callable[[str, dict[str, Any]], Any],
    ) -> None:
        """Call :func:`run_variant` with each ``(name, args)``; ``on_done(name, row)`` as rows
        arrive, in call order; the names it returns (calls no longer needed) are skipped if
        they have not started."""
        skip: set[str] = set()

        def one(name: str, args: tuple[Any, ...]) -> dict[str, Any] | None:
            return None if name in skip else run_variant(*args)

        with ThreadPoolExecutor(max_workers=self.threads, thread_name_prefix="rancf-run") as pool:
            futures = [(name, pool.submit(one, name, args)) for name, args in calls]
            for name, fut in futures:
                row = fut.result()
                if row is not None:
                    skip.update(on_done(name, row))
