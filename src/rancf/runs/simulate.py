"""The dynamics driver: :func:`run_simulate` for runs held in memory (sweeps, the shipped
examples, the Python API's :func:`simulate`) and, through the same steps, ``rancf simulate``,
which streams its rows to disk as the run goes (:mod:`rancf.cli.sim`: checkpoints,
``--resume``, the progress bar).

The steps: the system and its outputs planned against a size limit (:func:`plan_simulate`,
:func:`~rancf.post.run_plan.plan_run`), the start state (:func:`~rancf.solvers.start.start_state`;
a resumed run goes on from its checkpoint), generalized-α on the constrained system
(:func:`~rancf.solvers.dynamic.integrate`) and the run's warnings
(:func:`~rancf.post.checks.finished_warnings`), in :func:`simulate_planned`.  A :class:`Stream`
is what a streamed run adds: where it starts, the sink of its stored states and its callbacks,
and how its folder ends.
"""

from __future__ import annotations

import warnings as _warnings
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.options import DynamicOptions
from rancf.post.checks import finished_warnings
from rancf.post.energy_check import energy_failure
from rancf.post.results import sensor_table, write_run
from rancf.post.run_plan import plan_run
from rancf.solvers.dynamic import DynamicResult, integrate
from rancf.solvers.form import find_form
from rancf.solvers.start import start_state
from rancf.system.outputs import SystemOutputs

__all__ = [
    "MAX_OUTPUT_GB",
    "Plan",
    "Stream",
    "SimulateRun",
    "plan_simulate",
    "simulate_planned",
    "run_simulate",
    "simulate",
]

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


@dataclass(frozen=True)
class Plan:
    """A planned dynamic run: the system, its outputs, the ``[solver]`` options and the warning
    lines of a mesh refined for the static start (:mod:`rancf.runs.static_mesh`)."""

    system: Any
    outputs: SystemOutputs
    options: DynamicOptions
    notes: tuple[str, ...] = ()


class Stream(Protocol):
    """What a run streamed to disk adds to :func:`simulate_planned` (``rancf simulate``)."""

    def start(self, plan: Plan) -> tuple[Any, dict[str, Any]]:
        """Where the run goes on from: an earlier run's state and its start keys, or
        ``(None, {})`` to start anew (from the start state)."""
        ...

    def ready(self, plan: Plan, start: dict[str, Any]) -> Any:
        """The sink of the stored states (:class:`~rancf.solvers.dynamic.OutputSink`), once the
        start is known, right before the time loop."""
        ...

    def callbacks(
        self,
    ) -> tuple[Callable[..., None] | None, Callable[[], bool] | None, Callable[[], None] | None]:
        """``on_output``, ``should_stop`` and ``on_start`` of
        :func:`~rancf.solvers.dynamic.integrate`."""
        ...

    def flush(self) -> None:
        """Derive the rows of every stored state (the largest strain among them)."""
        ...

    def finish(self, plan: Plan, result: DynamicResult, warnings: list[str]) -> dict[str, Any]:
        """End the run's folder with the result and its warnings; returns its summary."""
        ...


def plan_simulate(sc: Any, limit_gb: float = MAX_OUTPUT_GB, limit_key: str = "limit_gb") -> Plan:
    """The system of scenario ``sc`` and its outputs, planned against the disk ``limit_gb``
    (``limit_key`` names it in the refusal), and the ``[solver]`` options.  A run from its
    static equilibrium (``solver.initial_state = "static"``) is planned on the mesh that
    ``rancf static`` solves on where a line's touchdown needs a finer one
    (:func:`rancf.runs.static_mesh.refine_for_start`: the same rule and warning lines).

    Raises
    ------
    RunTooLargeError
        The files would pass ``limit_gb``.
    """
    find_form(sc)  # a [form]'s length first: the system is built with it
    system, outputs = plan_run(sc, limit_gb, limit_key)
    notes: tuple[str, ...] = ()
    if sc.solver["initial_state"] == "static":
        from rancf.runs.static_mesh import refine_for_start

        found = refine_for_start(sc, system, "the static start and the run")
        notes = tuple(str(n) for n in found.notes)
        if found.scenario is not None:
            find_form(found.scenario)  # found again on the refined mesh
            system, outputs = plan_run(found.scenario, limit_gb, limit_key)
    return Plan(system, outputs, sc.dynamic_options(), notes)


def simulate_planned(
    sc: Any,
    plan: Plan,
    folder: str | Path | None = None,
    info: dict[str, Any] | None = None,
    table: bool = False,
    stream: Stream | None = None,
) -> SimulateRun:
    """Run the dynamics of scenario ``sc`` as planned, from the reference or its static
    equilibrium (``solver.initial_state``; a ``stream`` may go on from an earlier run) to
    ``solver.t_end``.

    With a ``folder``, the run folder is written (:func:`~rancf.post.results.write_run`; ``info``:
    more keys of its ``summary.json``); with a ``stream``, the stream writes it as the run goes.
    ``table``: derive the sensors at every stored time. A run that fails keeps what it
    computed: ``result.status`` says so.
    """
    system, outputs, opts = plan.system, plan.outputs, plan.options
    state, start = (None, {}) if stream is None else stream.start(plan)
    y0 = None
    if state is None:
        y0, start = start_state(sc, system)
        start.update({"mesh_refinement": list(plan.notes)} if plan.notes else {})
    summary = None
    if stream is None:
        result = integrate(system, opts, initial=y0)
        energies = np.column_stack([result.kinetic, result.strain, result.gravity])
        outputs.energy.add(result.t, energies)
        energy_failure(system, outputs.energy, result, opts)  # an unstable run fails
        if folder is not None:  # the rows are derived here: the largest strain is tracked
            extra = {**(info or {}), **start}
            summary = write_run(
                folder, system, sc.sensors, result, extra, outputs=outputs, options=opts
            )
    else:
        sink = stream.ready(plan, start)
        on_output, should_stop, on_start = stream.callbacks()
        result = integrate(system, opts, on_output, should_stop, sink, on_start, y0, state)
        stream.flush()
        energy_failure(system, outputs.energy, result, opts)  # an unstable run fails
    names: list[str] = list(outputs.sensor_names)
    values = None
    if table:
        names, values = sensor_table(outputs, sc.sensors, result.q, result.v, t=result.t)
    notes = (
        list(plan.notes)
        + start.get("static", {}).get("warnings", [])
        + finished_warnings(
            system, outputs.largest_strain, result, opts, outputs.largest_by_body, outputs.energy
        )
    )
    if stream is not None:
        summary = stream.finish(plan, result, notes)
    return SimulateRun(system, outputs, result, start, notes, summary, names, values)


def run_simulate(
    sc: Any,
    folder: str | Path | None = None,
    info: dict[str, Any] | None = None,
    limit_gb: float = MAX_OUTPUT_GB,
    limit_key: str = "limit_gb",
    table: bool = False,
) -> SimulateRun:
    """Plan (:func:`plan_simulate`) and run (:func:`simulate_planned`) the dynamics of scenario
    ``sc``: the run folder written to ``folder`` when given (``info``: more keys of its
    ``summary.json``), the sensors at every stored time with ``table``.

    Raises
    ------
    RunTooLargeError
        The files would pass ``limit_gb``.
    """
    plan = plan_simulate(sc, limit_gb, limit_key)
    return simulate_planned(sc, plan, folder, info, table)


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
