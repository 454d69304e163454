"""One call from a scenario to its dynamics: :func:`simulate` (the Python side of
``rancf simulate``, for scenarios built in Python or read from files)."""

from __future__ import annotations

import warnings
from pathlib import Path
from typing import Any

from rancf.post.checks import error_warnings
from rancf.post.results import sensor_table, write_run
from rancf.post.run_plan import plan_run
from rancf.solvers.dynamic import DynamicResult, integrate
from rancf.solvers.start import start_state

__all__ = ["simulate", "MAX_OUTPUT_GB"]

#: The disk a run folder written by :func:`simulate` may take [GB] (``rancf simulate``'s default).
MAX_OUTPUT_GB = 2.0


def simulate(
    scenario: Any, out: str | Path | None = None, limit_gb: float = MAX_OUTPUT_GB
) -> tuple[DynamicResult, list[str], Any]:
    """Run the dynamics of ``scenario`` (a :class:`~rancf.scenario.Scenario`: one body or a
    system) as ``rancf simulate`` does: from the reference or its static equilibrium
    (``solver.initial_state``), generalized-α on the constrained system.

    With ``out``, the run folder is written as by ``rancf simulate`` (the files of
    :mod:`rancf.post.run_files` and ``summary.json``; no ``scenario.toml``: a scenario built in
    Python has no file).  Returns the result, the sensor column names and their values at every
    stored time ``(n_t, n_columns)``. A run that fails (no convergence) returns what it
    computed, with ``result.status`` ``failed`` and one warning line saying where and why.
    """
    system, outputs = plan_run(scenario, limit_gb, "limit_gb")
    y0, start = start_state(scenario, system)
    result = integrate(system, scenario.dynamic_options(), initial=y0)
    if out is not None:
        write_run(out, system, scenario.sensors, result, {**start}, outputs=outputs)
    names, values = sensor_table(outputs, scenario.sensors, result.q, result.v, t=result.t)
    if result.status.value != "completed":  # said, not raised: what was computed is returned
        warnings.warn(f"rancf: the run {result.status.value} at t = {result.t_reached:g} s: "
                      f"{result.message} (the states up to there are returned)",
                      stacklevel=2)  # fmt: skip
    else:  # as rancf simulate: the steps that did not meet solver.rtol
        for line in error_warnings(result, scenario.dynamic_options()):
            warnings.warn(f"rancf: warning: {line}", stacklevel=2)
    return result, names, values
