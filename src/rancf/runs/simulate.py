"""The dynamics driver for runs held in memory: :func:`run_simulate` (sweeps, the shipped
examples) and the Python API's :func:`simulate` on it.

``rancf simulate`` streams its rows to disk as the run goes (checkpoints, ``--resume``, the
progress bar, :mod:`rancf.cli.sim`) but takes the same steps: the system and its outputs planned
against a size limit (:func:`~rancf.post.run_plan.plan_run`), the start state
(:func:`~rancf.solvers.start.start_state`), generalized-α on the constrained system
(:func:`~rancf.solvers.dynamic.integrate`) and the same warnings
(:func:`~rancf.post.checks.finished_warnings`).
"""

from __future__ import annotations

import warnings as _warnings
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from numpy.typing import NDArray

from rancf.post.checks import finished_warnings
from rancf.post.results import sensor_table, write_run
from rancf.post.run_plan import plan_run
from rancf.solvers.dynamic import DynamicResult, integrate
from rancf.solvers.start import start_state
from rancf.system.outputs import SystemOutputs

__all__ = ["MAX_OUTPUT_GB", "SimulateRun", "run_simulate", "simulate"]

#: The disk a run folder may take [GB] (``rancf simulate``'s default ``--max-output-gb``).
MAX_OUTPUT_GB = 2.0


@dataclass
class SimulateRun:
    """A dynamic run: the system, its outputs, the integrator's result, the start's summary keys
    (``initial_state`` ...), the run's warnings (one line each, as ``rancf simulate`` prints
    them), the summary when a folder was written, and the sensors at every stored time when
    asked for (``names``, ``values (n_t, n_columns)``)."""

    system: Any
    outputs: SystemOutputs
    result: DynamicResult
    start: dict[str, Any]
    warnings: list[str]
    summary: dict[str, Any] | None
    names: list[str]
    values: NDArray | None


def run_simulate(
    sc: Any,
    folder: str | Path | None = None,
    info: dict[str, Any] | None = None,
    limit_gb: float = MAX_OUTPUT_GB,
    limit_key: str = "limit_gb",
    table: bool = False,
) -> SimulateRun:
    """Run the dynamics of scenario ``sc`` from the reference or its static equilibrium
    (``solver.initial_state``) to ``solver.t_end``.

    With a ``folder``, the run folder is written (:func:`~rancf.post.results.write_run`; ``info``:
    more keys of its ``summary.json``). ``limit_gb``: the disk the folder may take (``limit_key``
    names it in the refusal); ``table``: derive the sensors at every stored time. A run that
    fails keeps what it computed: ``result.status`` says so.

    Raises
    ------
    RunTooLargeError
        The files would pass ``limit_gb``.
    """
    system, outputs = plan_run(sc, limit_gb, limit_key)
    y0, start = start_state(sc, system)
    opts = sc.dynamic_options()
    result = integrate(system, opts, initial=y0)
    summary = None
    if folder is not None:  # the rows are derived here: the largest strain is tracked
        extra = {**(info or {}), **start}
        summary = write_run(
            folder, system, sc.sensors, result, extra, outputs=outputs, options=opts
        )
    names: list[str] = list(outputs.sensor_names)
    values = None
    if table:
        names, values = sensor_table(outputs, sc.sensors, result.q, result.v, t=result.t)
    notes = finished_warnings(system, outputs.largest_strain, result, opts)
    return SimulateRun(system, outputs, result, start, notes, summary, names, values)


def simulate(
    scenario: Any, out: str | Path | None = None, limit_gb: float = MAX_OUTPUT_GB
) -> tuple[DynamicResult, list[str], NDArray]:
    """Run the dynamics of ``scenario`` (a :class:`~rancf.scenario.Scenario`: one body or a
    system) as ``rancf simulate`` does (:func:`run_simulate`).

    With ``out``, the run folder is written as by ``rancf simulate`` (the files of
    :mod:`rancf.post.run_files` and ``summary.json``; no ``scenario.toml``: a scenario built in
    Python has no file).  Returns the result, the sensor column names and their values at every
    stored time ``(n_t, n_columns)``. The run's warnings (impulsive starts, the steps, the
    largest strain, the error estimate) are issued as Python warnings, one line each, as
    ``rancf simulate`` prints them. A run that fails (no convergence) returns what it computed,
    with ``result.status`` ``failed`` and one warning line saying where and why.
    """
    run = run_simulate(scenario, out, None, limit_gb, "limit_gb", table=True)
    result = run.result
    for line in run.warnings:
        _warnings.warn(f"rancf: warning: {line}", stacklevel=2)
    if result.status.value != "completed":  # said, not raised: what was computed is returned
        _warnings.warn(
            f"rancf: the run {result.status.value} at t = {result.t_reached:g} s: "
            f"{result.message} (the states up to there are returned)",
            stacklevel=2,
        )
    assert run.values is not None  # table=True
    return result, run.names, run.values
