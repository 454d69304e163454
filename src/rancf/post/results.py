"""Result files: written atomically, so an interrupted run never leaves a corrupt file.

A run directory holds

* ``sensors.csv`` — header ``t`` then one column per sensor scalar;
* ``energy.csv`` — ``t, kinetic, strain, gravity, total`` [J];
* ``results.npz`` — the full state history (``t``, ``q``, ``v``, energies, mesh data, JSON
  metadata), loadable with :func:`load_results` or plain ``numpy.load``;
* ``summary.json`` — status, message, time reached, counters and wall times (strict JSON:
  a non-finite number is written as ``null``).

Every file is written through :mod:`rancf.atomic`: under a temporary name, given the permissions
the umask allows (0644 under umask 0022) and renamed into place; the history files
(``sensors.csv``, ``energy.csv``, ``results.npz``) are renamed together once all three are
written, so they always hold the same rows.  Histories are written in chunks of rows, so a long
run's files are built without holding them in memory.
"""

from __future__ import annotations

import json
import math
import zipfile
from collections.abc import Callable, Iterator, Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet
from rancf.model.scenario_sensors import Sensor
from rancf.model.system import Model
from rancf.solvers.dynamic import DynamicResult

__all__ = [
    "strict_json",
    "write_history_files",
    "write_run",
    "run_summary",
    "load_results",
    "sensor_table",
]

#: Rows of a history handled at once when writing files.
CHUNK_BYTES = 1 << 24


def _finite(value: Any) -> Any:
    if isinstance(value, float | np.floating):
        return float(value) if math.isfinite(value) else None
    if isinstance(value, np.integer):
        return int(value)
    if isinstance(value, dict):
        return {k: _finite(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_finite(v) for v in value]
    return value


def strict_json(value: Any, default: Callable[[Any], Any] | None = None) -> str:
    """JSON text with every non-finite number replaced by ``null`` (never ``NaN`` or
    ``Infinity``, which strict JSON readers refuse); ``default`` converts other objects."""
    return json.dumps(_finite(value), indent=2, allow_nan=False, default=default) + "\n"


def sensor_table(
    model: Model, sensors: Sequence[Sensor], q: NDArray
) -> tuple[list[str], NDArray[np.float64]]:
    """Column names and values ``(n_t, n_columns)`` of the sensors for states ``q``.

    ``twist`` sensors (rods) read the node's twist coordinate ``φ`` (the 7th of the node).
    """
    qq = np.atleast_2d(q)
    pos = model.node_positions(qq)
    twists = None
    if model.element == "rod":
        twists = qq.reshape(qq.shape[:-1] + (model.n_nodes, model.dpn))[..., 6]
    names: list[str] = []
    cols = []
    for s in sensors:
        names += s.columns(model.dim)
        cols.append(s.evaluate(pos, twists))
    vals = np.concatenate(cols, axis=1) if cols else np.empty((pos.shape[0], 0))
    return names, vals


def _rows(n: int, width: int) -> Iterator[slice]:
    step = max(1, CHUNK_BYTES // (8 * max(width, 1)))
    for i in range(0, n, step):
        yield slice(i, min(n, i + step))


def _npy(zf: zipfile.ZipFile, name: str, shape: tuple[int, ...], chunks: Iterator[NDArray]) -> None:
    with zf.open(f"{name}.npy", "w", force_zip64=True) as f:
        header = {"descr": "<f8", "fortran_order": False, "shape": shape}
        np.lib.format.write_array_header_2_0(f, header)
        for c in chunks:
            f.write(np.ascontiguousarray(c, dtype="<f8").tobytes())


def write_history_files(
    out: Path,
    model: Model,
    sensors: Sequence[Sensor],
    t: NDArray,
    q: NDArray,
    v: NDArray,
    energy: NDArray,
    directors: NDArray | None = None,
    files: FileSet | None = None,
) -> list[str]:
    """``sensors.csv``, ``energy.csv`` and ``results.npz`` of a history, chunk by chunk.

    ``t (n,)``, ``q`` and ``v (n, n_q)``, ``energy (n, 3)`` and a rod's nodal ``directors``
    (``(n, 3 n_nodes)`` or ``(n, n_nodes, 3)``, stored as ``directors (n, n_nodes, 3)``) may be
    memory maps.  The three files replace the old ones together (see :mod:`rancf.atomic`): when
    the block ends, or with ``files`` given, when that set is committed.  Returns the sensor
    column names.
    """
    if files is None:
        with FileSet() as own:
            return write_history_files(out, model, sensors, t, q, v, energy, directors, own)
    n = t.shape[0]
    names, _ = sensor_table(model, sensors, q[:1])
    with files.file(out / "sensors.csv") as fh:
        fh.write((",".join(["t", *names]) + "\n").encode())
        for r in _rows(n, q.shape[1]):
            _, vals = sensor_table(model, sensors, q[r])
            np.savetxt(fh, np.column_stack([t[r], vals]), delimiter=",", fmt="%.12g")
    with files.file(out / "energy.csv") as fh:
        fh.write(b"t,kinetic,strain,gravity,total\n")
        for r in _rows(n, 5):
            e = energy[r]
            np.savetxt(fh, np.column_stack([t[r], e, e.sum(axis=1)]), delimiter=",", fmt="%.12g")
    meta = {
        "element": model.element,
        "dim": model.dim,
        "dofs_per_node": model.dpn,
        "n_nodes": model.n_nodes,
        "n_elements": model.n_el,
        "sensor_columns": names,
    }
    small = {
        "weights": model.mesh.weights,
        "scales": model.mesh.scales,
        "reference": model.q0,
        "metadata": np.array(json.dumps(meta)),
    }
    with files.file(out / "results.npz") as fh:
        with zipfile.ZipFile(fh, "w", zipfile.ZIP_STORED, allowZip64=True) as z:
            _npy(z, "t", (n,), (t[r] for r in _rows(n, 1)))
            for name, arr in (("q", q), ("v", v)):
                _npy(z, name, arr.shape, (arr[r] for r in _rows(n, arr.shape[1])))
            for j, name in enumerate(("kinetic", "strain", "gravity")):
                _npy(z, name, (n,), (energy[r, j] for r in _rows(n, 3)))
            if directors is not None:
                m1 = directors.reshape(n, -1)
                shape3 = (n, m1.shape[1] // 3, 3)
                _npy(z, "directors", shape3, (m1[r] for r in _rows(n, m1.shape[1])))
            shape = (n, len(names))
            rows = _rows(n, q.shape[1])
            _npy(z, "sensors", shape, (sensor_table(model, sensors, q[r])[1] for r in rows))
            for name, arr in small.items():
                with z.open(f"{name}.npy", "w") as f:
                    np.lib.format.write_array(f, np.asarray(arr), allow_pickle=False)
    return names


def run_summary(model: Model, result: DynamicResult) -> dict[str, Any]:
    """The counters of ``summary.json`` for a result (status, times, steps, sizes, energies)."""
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
        "n_elements": model.n_el,
        "element": model.element,
        "n_dofs": model.n,
        "outputs": result.n_outputs,
        "final_energy_j": {
            "kinetic": float(result.kinetic[-1]),
            "strain": float(result.strain[-1]),
            "gravity": float(result.gravity[-1]),
        },
    }


def write_run(
    out: str | Path,
    model: Model,
    sensors: Sequence[Sensor],
    result: DynamicResult,
    extra: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Write the four files of a run directory from an in-memory result; returns the summary."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    energy = np.column_stack([result.kinetic, result.strain, result.gravity])
    summary = {**run_summary(model, result), **(extra or {})}
    with FileSet() as files:  # the four files replace an earlier run's together
        write_history_files(
            out, model, sensors, result.t, result.q, result.v, energy, result.directors, files
        )
        files.write(out / "summary.json", strict_json(summary))
    return summary


class LoadPath:
    """The converged load steps of a static solve: pass :meth:`record` as ``on_step`` of
    :func:`rancf.solvers.static.solve_static`, then :func:`write_static_run`."""

    def __init__(self, model: Model) -> None:
        self.model = model
        self.steps: list[tuple[float, NDArray, NDArray | None]] = []

    def record(self, load_factor: float, y: NDArray) -> None:
        """Keep one converged step (rods: with the nodal directors the triads were carried to)."""
        self.steps.append((load_factor, np.array(y, dtype=float), self.model.nodal_directors(y)))


def write_static_run(
    out: str | Path, path: LoadPath, sensors: Sequence[Sensor], summary: dict[str, Any]
) -> dict[str, Any]:
    """Write a static load path as a run directory (``rancf static --out``, static sweeps).

    The files are those of a dynamic run with the load factor ``λ`` in place of the time
    (``t`` of ``results.npz`` and the CSV files; ``summary.json`` has ``"analysis": "static"``),
    zero velocities and kinetic energy, so ``export``, ``plot`` and ``animate`` read it.
    Returns the summary written.
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    model = path.model
    t = np.array([lam for lam, _, _ in path.steps], dtype=float)
    ys = np.array([y for _, y, _ in path.steps], dtype=float)
    q = model.q_from_y(ys)
    energy = np.array(
        [[0.0, model.strain_energy(y), model.gravity_energy(y)] for y in ys], dtype=float
    )
    m1 = np.array([m for _, _, m in path.steps]) if model.element == "rod" else None
    doc = {
        "analysis": "static",
        "load_factor_reached": float(t[-1]),
        "load_steps_converged": int(t.size - 1),
        "n_elements": model.n_el,
        "element": model.element,
        "n_dofs": model.n,
        "outputs": int(t.size),
        **summary,
    }
    with FileSet() as files:
        write_history_files(out, model, sensors, t, q, np.zeros_like(q), energy, m1, files)
        files.write(out / "summary.json", strict_json(doc))
    return doc


def load_results(path: str | Path) -> dict[str, Any]:
    """Read a ``results.npz`` into a dictionary (``metadata`` decoded from JSON)."""
    with np.load(path, allow_pickle=False) as z:
        data = {k: z[k] for k in z.files}
    data["metadata"] = json.loads(str(data["metadata"]))
    return data
