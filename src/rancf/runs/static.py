"""The static driver: one static analysis of a scenario, as ``rancf static``, static sweeps and
the shipped examples run it: the equilibrium of the scenario's system along its load path, the
load path written as a run folder (when one is given) and the sensors and reactions at the full
loads."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field, replace
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
    #: One line per body whose mesh the static solve refined, or would have but could not
    #: (:mod:`rancf.runs.static_mesh`).
    notes: list[str]
    #: ``{"unstretched_length": ...}`` of the bodies with a ``[form]`` (found on the mesh
    #: solved: :func:`rancf.solvers.form.form_summary`), or empty.
    form: dict[str, Any] = field(default_factory=dict)
    #: One line per body with a ``[form]``: the length found
    #: (:func:`~rancf.solvers.form.form_lines`).
    form_lines: list[str] = field(default_factory=list)


def run_static(
    sc: Any,
    folder: str | Path | None = None,
    info: dict[str, Any] | None = None,
    on_written: Callable[[dict[str, Any]], None] | None = None,
) -> StaticRun:
    """Solve the static equilibrium of scenario ``sc`` (:func:`rancf.solvers.static.solve_static`
    with the ``[solver]`` table's ``load_steps`` and ``static_method``), on a mesh refined where
    a line's touchdown on a seabed needs it (:mod:`rancf.runs.static_mesh`: before the solve from
    its sagged start shape, after it from the solved state, then solved once more).

    With a ``folder``, the converged load steps are written there
    (:func:`~rancf.post.results.write_static_run`) also when a later increment fails or the run
    is interrupted: the summary's ``status`` then says so and the error propagates. ``info``:
    more keys of ``summary.json`` (where a mesh was refined or could not be,
    ``"mesh_refinement"``: the lines of :attr:`StaticRun.notes`); ``on_written``: called with
    the summary once the folder holds the run.
    """
    from rancf.runs.static_mesh import refine_for_start
    from rancf.solvers.form import find_form, form_lines, form_summary

    find_form(sc)  # a [form]'s length (found again on a refined mesh)
    system = sc.build_system()
    first = refine_for_start(sc, system)
    if first.scenario is not None:
        find_form(first.scenario)  # found again on the refined mesh
        sc, system = first.scenario, first.scenario.build_system()
    out = _Solve(sc, folder, {**(info or {}), **form_summary(sc)}, on_written)
    run = out.run(system, list(first.notes), recheck=True)
    if isinstance(run, StaticRun):
        run.form, run.form_lines = form_summary(sc), form_lines(sc)
        return run
    more = run.refinement
    find_form(more.scenario)
    keys = {**(info or {}), **form_summary(more.scenario)}
    solved = replace(out, sc=more.scenario, info=keys).run(
        more.scenario.build_system(), list(first.notes) + list(more.notes), recheck=False
    )
    assert isinstance(solved, StaticRun)
    # the solve time counts both solves
    solved.result = replace(solved.result, wall_time=solved.result.wall_time + run.wall_time)
    solved.form, solved.form_lines = form_summary(more.scenario), form_lines(more.scenario)
    return solved


@dataclass(frozen=True)
class _Again:
    """A solve whose solved touchdowns need a finer mesh: the refinement and the solve's
    time (nothing was written)."""

    refinement: Any  # rancf.runs.static_mesh.Refinement
    wall_time: float


@dataclass(frozen=True)
class _Solve:
    """One static solve of :func:`run_static`: the scenario and where its run goes."""

    sc: Any
    folder: str | Path | None
    info: dict[str, Any] | None
    on_written: Callable[[dict[str, Any]], None] | None

    def run(self, system: Any, notes: list[Any], recheck: bool) -> StaticRun | _Again:
        """:func:`run_static` on ``system`` of the scenario (``notes``: the mesh's so far,
        :class:`~rancf.runs.static_mesh.MeshNote`); with ``recheck``, :class:`_Again` instead
        where the solved touchdowns need a finer mesh."""
        from rancf.runs.static_mesh import refine_for_touchdowns
        from rancf.scenario.system_build import scenario_keys, support_labels
        from rancf.solvers.sag_start import SAG_START
        from rancf.solvers.static import solve_static
        from rancf.solvers.static_friction import FRICTION

        sc = self.sc
        labels = support_labels(sc)
        path = LoadPath(system, labels)
        outputs = SystemOutputs(system, sc.sensors, labels)  # the run folder's and full loads'
        doc = None
        keys = dict(self.info or {})
        again: _Again | None = None
        try:
            with scenario_keys(sc):
                res = solve_static(system, on_step=path.record, **sc.static_options())
            if recheck:
                found = refine_for_touchdowns(sc, system, res.touchdowns or {})
                named = {n.body for n in notes}  # a body's note once
                if found.scenario is not None:
                    again = _Again(found, res.wall_time)
                else:
                    notes = notes + [m for m in found.notes if m.body not in named]
            lines = [str(n) for n in notes]
            keys.update({"mesh_refinement": lines} if lines else {})
            if res.method.startswith(SAG_START) or res.method.endswith(FRICTION):  # the path's
                path.steps[:] = path.steps[-1:]  # states were abandoned or are frictionless
            keys.update(
                status="completed",
                message="reached the end of the load path",
                method=res.method,
                relaxation_steps=res.relaxation_steps,
                **({"warnings": list(res.warnings)} if res.warnings else {}),
            )
        except BaseException as exc:
            kind = "interrupted" if isinstance(exc, KeyboardInterrupt) else "failed"
            lam = path.steps[-1][0] if path.steps else 0.0
            text = " ".join(str(exc).split()) or f"{kind} at load factor {lam:g}"
            keys.update(status=kind, message=text)
            raise
        finally:
            if self.folder is not None and path.steps and again is None:  # what converged
                doc = write_static_run(self.folder, path, sc.sensors, keys, outputs)
                if self.on_written is not None:
                    self.on_written(doc)
        if again is not None:
            return again
        assert res.lam is not None  # a system's solution has its multipliers (empty: no joints)
        names, vals = sensor_table(
            outputs, sc.sensors, res.q, static=True, t=res.load_factors[-1:], lam=res.lam[None]
        )
        sensors = dict(zip(names, map(float, vals[0]), strict=True))
        said = res.warnings if doc is None else ()  # else in the summary's warnings
        return StaticRun(system, res, outputs, sensors, doc, [*map(str, notes), *said])
