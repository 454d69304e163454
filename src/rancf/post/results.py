"""Result files: written atomically, so an interrupted run never leaves a corrupt file.

A run directory holds

* ``sensors.csv``, ``energy.csv``, ``reactions.csv`` and ``results.npz`` — the history
  (:mod:`rancf.post.run_files`; every flexible body also ``bodies/NAME/results.npz``, and a
  static run ``bodies/NAME/along.csv``);
* ``summary.json`` — status, message, time reached, counters and wall times (strict JSON:
  a non-finite number is written as ``null``).

Every file is written through :mod:`rancf.atomic`: under a temporary name, given the permissions
the umask allows (0644 under umask 0022) and renamed into place; the files of a run are renamed
together once all are written, so they always hold the same rows.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.bodies.flexible import Model
from rancf.errors import InputError
from rancf.options import DynamicOptions
from rancf.post.checks import finished_warnings, run_warnings
from rancf.post.csv_rows import write_rows
from rancf.post.run_files import reader_metadata, write_history_files
from rancf.solvers.dynamic import DynamicResult
from rancf.system import System, as_system
from rancf.system.outputs import SystemOutputs

__all__ = [
    "strict_json",
    "json_safe",
    "write_history_files",
    "reader_metadata",
    "write_run",
    "run_summary",
    "run_sizes",
    "load_results",
    "sensor_table",
    "system_outputs",
    "LoadPath",
    "write_static_run",
]

Labels = Sequence[int | str] | Mapping[str, Sequence[int | str]] | None


def system_outputs(
    model: Model | System, sensors: Sequence[Any] = (), labels: Labels = None
) -> SystemOutputs:
    """The :class:`SystemOutputs` of a model (a one-body system) or system; ``labels``: the
    supports' ``at`` as written (a list for one body, else per body name)."""
    system = as_system(model)
    if isinstance(model, Model) and labels is None:  # the one-body front: labels as written
        labels = [sup.node for sup in model.supports]
    if labels is not None and not isinstance(labels, Mapping):
        labels = {system.names[0]: list(labels)}
    return SystemOutputs(system, sensors, labels)


def json_safe(value: Any) -> Any:
    """``value`` with every non-finite float replaced by None (NumPy scalars as Python ones), in
    nested dictionaries and lists: what strict JSON can hold."""
    if isinstance(value, float | np.floating):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, dict):
        return {k: json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [json_safe(v) for v in value]
    return value


def strict_json(value: Any, default: Callable[[Any], Any] | None = None) -> str:
    """JSON text with every non-finite number replaced by ``null`` (never ``NaN`` or
    ``Infinity``, which strict JSON readers refuse); ``default`` converts other objects."""
    return json.dumps(json_safe(value), indent=2, allow_nan=False, default=default) + "\n"


def sensor_table(
    model: Model | System | SystemOutputs,
    sensors: Sequence[Any],
    q: NDArray,
    v: NDArray | None = None,
    energy: NDArray | None = None,
    static: bool = False,
    t: NDArray | None = None,
    lam: NDArray | None = None,
) -> tuple[list[str], NDArray[np.float64]]:
    """Column names and values ``(n_t, n_columns)`` of the sensors for states ``q``, ``v`` (full
    coordinates; ``v`` default zero) at times ``t`` (default zero; ``static``: load factors, the
    reactions those of a static state with multipliers ``lam``)."""
    out = model if isinstance(model, SystemOutputs) else system_outputs(model, sensors)
    qq = np.atleast_2d(np.asarray(q, dtype=float))
    tt = np.zeros(qq.shape[0]) if t is None else np.atleast_1d(np.asarray(t, dtype=float))
    vv = None if v is None else np.atleast_2d(v)
    rows = out.rows(
        tt,
        qq,
        vv,
        None,
        None if energy is None else np.atleast_2d(energy),
        None if lam is None else np.atleast_2d(lam),
        static,
    )
    return out.sensor_names, rows["c"]


def run_sizes(model: Model | System) -> dict[str, Any]:
    """The size keys of ``summary.json``, the same for every run: ``n_elements`` (all flexible
    bodies), ``element`` (the flexible bodies' element when they share one, else ``"mixed"``),
    ``n_dofs``, ``bodies`` and ``constraints`` (multipliers)."""
    s = as_system(model)
    kinds = {b.element for b in s.flex}
    return {
        "n_elements": sum(b.n_el for b in s.flex),
        "element": kinds.pop() if len(kinds) == 1 else "mixed",
        "n_dofs": s.n,
        "bodies": len(s.names),
        "constraints": s.m,
    }


def run_summary(model: Model | System, result: DynamicResult) -> dict[str, Any]:
    """The counters of ``summary.json`` for a result (status, times, steps, sizes, energies;
    a system also its bodies and constraint equations)."""
    return {
        "status": result.status.value,
        "message": result.message,
        "t_reached": result.t_reached,
        "steps": result.n_steps,
        "rejected_steps": result.n_rejected,
        "newton_iterations": result.n_newton,
        "factorizations": result.n_factorizations,
        "solve_wall_time_s": result.wall_time,
        "time_per_step_s": result.wall_time / result.n_steps if result.n_steps else None,
        "min_step_s": result.min_step_taken,
        "max_step_s": result.max_step_taken,
        "accepted_steps": result.n_steps,
        # the largest local error estimate relative to rtol * size (docs/guide/time-integration.md)
        "error_estimate": result.error_estimate,
        "error_time_s": result.error_time,
        "error_step_s": result.error_step,
        **run_sizes(model),
        "outputs": result.n_outputs,
        "final_energy_j": {
            "kinetic": float(result.kinetic[-1]),
            "strain": float(result.strain[-1]),
            "gravity": float(result.gravity[-1]),
        },
    }


def write_run(
    out: str | Path,
    model: Model | System,
    sensors: Sequence[Any],
    result: DynamicResult,
    extra: dict[str, Any] | None = None,
    labels: Labels = None,
    outputs: SystemOutputs | None = None,
    options: DynamicOptions | None = None,
) -> dict[str, Any]:
    """Write the files of a run directory from an in-memory result; returns the summary.

    ``labels``: the supports' ``at`` as written in the scenario (reaction column names);
    ``outputs``: the run's, when already made (then ``sensors`` and ``labels`` are its own);
    ``options``: the run's, to warn as ``rancf simulate`` does (its steps, its error estimate:
    :func:`~rancf.post.checks.finished_warnings`).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    energy = np.column_stack([result.kinetic, result.strain, result.gravity])
    outputs = outputs if outputs is not None else system_outputs(model, sensors, labels)
    with FileSet() as files:  # the files replace an earlier run's together
        write_history_files(
            out,
            outputs,
            result.t,
            result.q,
            result.v,
            energy,
            result.directors,
            files=files,
            alpha=result.alpha,
        )
        summary = {
            **run_summary(model, result),
            "warnings": run_warnings(
                model, largest=outputs.largest_strain, by_body=outputs.largest_by_body
            )
            if options is None
            else finished_warnings(
                model,
                outputs.largest_strain,
                result,
                options,
                outputs.largest_by_body,
                outputs.energy,
            ),
            **(extra or {}),
        }
        files.write(out / "summary.json", strict_json(summary))
    return summary


class LoadPath:
    """The converged load steps of a static solve: pass :meth:`record` as ``on_step`` of
    :func:`rancf.solvers.static.solve_static`, then :func:`write_static_run`.

    ``labels``: the supports' ``at`` as written in the scenario (reaction column names).
    """

    def __init__(self, model: Model | System, labels: Labels = None) -> None:
        self.model = model
        self.system = as_system(model)
        self.labels = labels
        self.steps: list[tuple[float, NDArray, NDArray | None, NDArray | None]] = []

    def record(self, load_factor: float, y: NDArray, lam: NDArray | None = None) -> None:
        """Keep one converged step (rods: with the nodal directors the triads were carried to;
        systems: with the multipliers ``lam``, or ``y`` holding them after the coordinates)."""
        y = np.array(y, dtype=float)
        n = self.system.n
        if lam is None and y.size == n + self.system.m and self.system.m:
            y, lam = y[:n], y[n:]
        self.steps.append(
            (
                load_factor,
                y,
                self.system.nodal_directors(y),
                None if lam is None else np.array(lam, dtype=float),
            )
        )


def write_static_run(
    out: str | Path,
    path: LoadPath,
    sensors: Sequence[Any],
    summary: dict[str, Any],
    outputs: SystemOutputs | None = None,
) -> dict[str, Any]:
    """Write a static load path as a run directory (``rancf static --out``, static sweeps).

    The files are those of a dynamic run with the load factor ``λ`` in place of the time
    (``t`` of ``results.npz`` and the CSV files; ``summary.json`` has ``"analysis": "static"``),
    zero velocities and kinetic energy, so ``export``, ``plot`` and ``animate`` read it.
    ``outputs``: the caller's outputs of ``sensors`` on the load path's system, if it has them.
    Returns the summary written.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    s = path.system
    if outputs is None:
        outputs = system_outputs(s, sensors, path.labels)
    t = np.array([st[0] for st in path.steps], dtype=float)
    ys = np.array([st[1] for st in path.steps], dtype=float)
    q = s.q_from_y(ys)
    energy = np.array([s.energies(y, np.zeros_like(y)) for y in ys], dtype=float)
    m1 = np.array([st[2] for st in path.steps]) if outputs.n_directors else None
    lam = np.array([st[3] for st in path.steps]) if s.m else None
    with FileSet() as files:  # the files replace an earlier load path's together
        write_history_files(
            out, outputs, t, q, np.zeros_like(q), energy, m1, static=True, files=files, lam=lam
        )
        last = None if m1 is None else m1[-1]
        write_along_csv(out, outputs, t[-1], q[-1], last, files)
        # after the rows: their outputs tracked the largest strain of the warnings
        doc = {
            "analysis": "static",
            "load_factor_reached": float(t[-1]),
            "load_steps_converged": int(t.size - 1),
            **run_sizes(s),
            "outputs": int(t.size),
            **summary,
            "warnings": list(summary.get("warnings", ()))  # the solve's, then the states'
            + run_warnings(
                s, static=True, largest=outputs.largest_strain, by_body=outputs.largest_by_body
            ),
        }
        files.write(out / "summary.json", strict_json(doc))
    return doc


def write_along_csv(
    out: Path,
    outputs: SystemOutputs,
    lam: float,
    q: NDArray,
    m1: NDArray | None,
    files: FileSet | None = None,
) -> None:
    """``bodies/NAME/along.csv`` of every flexible body in a static state (run folder ``out``,
    system coordinates ``q``): one row per section sample point with the reference arc length
    ``s``, the position and the section quantities (into the set ``files``, or atomically on
    their own)."""
    if files is None:
        with FileSet() as own:
            return write_along_csv(out, outputs, lam, q, m1, own)
    s = outputs.system
    rows = outputs.rows(
        np.array([lam]), q[None], None, None if m1 is None else m1[None], static=True
    )
    for name, model in outputs.flex:
        along = outputs.body_along(rows["s"], name)[0]
        sampler = outputs.samplers[name]
        pos = sampler.positions(model.y_from_q(q[s.body_slice(name)]))
        axes = ["x", "y", "z"][: model.dim]
        head = ",".join(["s", *axes, *outputs.section_names[name]]) + "\n"
        folder = Path(out) / "bodies" / name
        folder.mkdir(parents=True, exist_ok=True)
        with files.file(folder / "along.csv") as fh:
            fh.write(head.encode())
            write_rows(fh, np.column_stack([sampler.s, pos, along]))


def load_results(path: str | Path) -> dict[str, Any]:
    """Read a run's ``results.npz`` into a dictionary (``metadata`` decoded from JSON).

    ``path``: the ``results.npz`` file or the run folder that holds it (``rancf simulate --out``,
    ``rancf static --out``, a sweep's run).

    Raises
    ------
    InputError
        A folder without ``results.npz`` (not a run folder, or a run that has not written it).
    """
    path = Path(path)
    if path.is_dir():
        if not (path / "results.npz").is_file():
            raise InputError(
                "path",
                str(path),
                "a results.npz file or a run folder holding one "
                "(rancf simulate --out, rancf static --out)",
            )
        path = path / "results.npz"
    with np.load(path, allow_pickle=False) as z:
        data = {k: z[k] for k in z.files}
    data["metadata"] = json.loads(str(data["metadata"]))
    return data
