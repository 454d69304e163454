"""The static driver: one static analysis of a scenario, as ``rancf static``, static sweeps and
the shipped examples run it: the equilibrium of the scenario's system along its load path, the
load path written as a run folder (when one is given) and the sensors and reactions at the full
loads."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rancf.post.results import LoadPath, sensor_table, write_static_run
from rancf.system.outputs import SystemOutputs

__all__ = ["StaticRun", "run_static"]


@dataclass
class StaticRun:
    """A static analysis: the system, the solver's result, the outputs at the full loads and,
    when a folder was written, its ``summary.json`` contents."""

    system: Any
    result: Any
    outputs: SystemOutputs
    sensors: dict[str, float]
    summary: dict[str, Any] | None


def run_static(
    sc: Any,
    folder: str | Path | None = None,
    info: dict[str, Any] | None = None,
    on_written: Callable[[dict[str, Any]], None] | None = None,
) -> StaticRun:
    """Solve the static equilibrium of scenario ``sc`` (:func:`rancf.solvers.static.solve_static`
    with the ``[solver]`` table's ``load_steps`` and ``static_method``).

    With a ``folder``, the converged load steps are written there
    (:func:`~rancf.post.results.write_static_run`) also when a later increment fails or the run
    is interrupted: the summary's ``status`` then says so and the error propagates. ``info``:
    more keys of ``summary.json``; ``on_written``: called with the summary once the folder
    holds the run.
    """
    from rancf.scenario.system_build import scenario_keys, support_labels
    from rancf.solvers.sag_start import SAG_START
    from rancf.solvers.static import FRICTION, solve_static

    system = sc.build_system()
    labels = support_labels(sc)
    path = LoadPath(system, labels)
    outputs = SystemOutputs(system, sc.sensors, labels)  # the run folder's and the full loads'
    doc = None
    keys = dict(info or {})
    try:
        with scenario_keys(sc):
            res = solve_static(system, on_step=path.record, **sc.static_options())
        if res.method.startswith(SAG_START) or res.method.endswith(FRICTION):  # the path's
            path.steps[:] = path.steps[-1:]  # states were abandoned or are frictionless
        keys.update(
            status="completed",
            message="reached the end of the load path",
            method=res.method,
            relaxation_steps=res.relaxation_steps,
        )
    except BaseException as exc:
        kind = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
        lam = path.steps[-1][0] if path.steps else 0.0
        text = " ".join(str(exc).split()) or f"{kind} at load factor {lam:g}"
        keys.update(status=kind, message=text)
        raise
    finally:
        if folder is not None and path.steps:  # what converged is kept
            doc = write_static_run(folder, path, sc.sensors, keys, outputs)
            if on_written is not None:
                on_written(doc)
    assert res.lam is not None  # a system's solution has its multipliers (empty: no joints)
    names, vals = sensor_table(
        outputs, sc.sensors, res.q, static=True, t=res.load_factors[-1:], lam=res.lam[None]
    )
    sensors = dict(zip(names, map(float, vals[0]), strict=True))
    return StaticRun(system, res, outputs, sensors, doc)
