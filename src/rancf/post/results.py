"""Result files: written atomically, so an interrupted run never leaves a corrupt file.

A run directory holds

* ``sensors.csv`` — header ``t`` then one column per sensor scalar;
* ``energy.csv`` — ``t, kinetic, strain, gravity, total`` [J];
* ``results.npz`` — the full state history (``t``, ``q``, ``v``, energies, mesh data, JSON
  metadata), loadable with :func:`load_results` or plain ``numpy.load``;
* ``summary.json`` — status, message, time reached, counters and wall time.

Each file is written to a temporary file in the same directory and moved into place with
:func:`os.replace`, which is atomic on POSIX and Windows.
"""

from __future__ import annotations

import io
import json
import os
import tempfile
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.model.scenario import Sensor
from rancf.model.system import Model
from rancf.solvers.dynamic import DynamicResult

__all__ = ["atomic_write", "write_run", "load_results", "sensor_table"]


def atomic_write(path: str | Path, data: bytes | str) -> None:
    """Write ``data`` to ``path`` through a temporary file and an atomic rename."""
    path = Path(path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(raw)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.unlink(tmp)
        raise


def sensor_table(
    model: Model, sensors: Sequence[Sensor], q: NDArray
) -> tuple[list[str], NDArray[np.float64]]:
    """Column names and values ``(n_t, n_columns)`` of the sensors for states ``q``."""
    pos = model.node_positions(np.atleast_2d(q))
    names: list[str] = []
    cols = []
    for s in sensors:
        names += s.columns(model.dim)
        cols.append(s.evaluate(pos))
    vals = np.concatenate(cols, axis=1) if cols else np.empty((pos.shape[0], 0))
    return names, vals


def _csv(header: list[str], data: NDArray) -> str:
    buf = io.StringIO()
    np.savetxt(buf, data, delimiter=",", header=",".join(header), comments="", fmt="%.12g")
    return buf.getvalue()


def write_run(
    out: str | Path,
    model: Model,
    sensors: Sequence[Sensor],
    result: DynamicResult,
    extra: dict[str, Any] | None = None,
) -> dict[str, Any]:
    """Write the four files of a run directory; returns the summary dictionary."""
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    names, vals = sensor_table(model, sensors, result.q)
    atomic_write(out / "sensors.csv", _csv(["t", *names], np.column_stack([result.t, vals])))
    energy = np.column_stack(
        [result.t, result.kinetic, result.strain, result.gravity, result.total_energy]
    )
    atomic_write(out / "energy.csv", _csv(["t", "kinetic", "strain", "gravity", "total"], energy))
    meta = {
        "element": model.element,
        "dim": model.dim,
        "dofs_per_node": model.dpn,
        "n_nodes": model.n_nodes,
        "n_elements": model.n_el,
        "sensor_columns": names,
    }
    buf = io.BytesIO()
    np.savez_compressed(
        buf,
        t=result.t,
        q=result.q,
        v=result.v,
        kinetic=result.kinetic,
        strain=result.strain,
        gravity=result.gravity,
        sensors=vals,
        weights=model.mesh.weights,
        scales=model.mesh.scales,
        reference=model.q0,
        metadata=np.array(json.dumps(meta)),
    )
    atomic_write(out / "results.npz", buf.getvalue())
    steps = np.asarray(result.steps)
    summary = {
        "status": result.status.value,
        "message": result.message,
        "t_reached": result.t_reached,
        "steps": result.n_steps,
        "rejected_steps": result.n_rejected,
        "newton_iterations": result.n_newton,
        "factorizations": result.n_factorizations,
        "solve_wall_time_s": result.wall_time,
        "time_per_step_s": result.wall_time / result.n_steps if result.n_steps else None,
        "min_step_s": float(steps.min()) if steps.size else None,
        "max_step_s": float(steps.max()) if steps.size else None,
        "n_elements": model.n_el,
        "element": model.element,
        "n_dofs": model.n,
        "outputs": int(result.t.size),
        "final_energy_j": {
            "kinetic": float(result.kinetic[-1]),
            "strain": float(result.strain[-1]),
            "gravity": float(result.gravity[-1]),
        },
        **(extra or {}),
    }
    atomic_write(out / "summary.json", json.dumps(summary, indent=2) + "\n")
    return summary


def load_results(path: str | Path) -> dict[str, Any]:
    """Read a ``results.npz`` into a dictionary (``metadata`` decoded from JSON)."""
    with np.load(path, allow_pickle=False) as z:
        data = {k: z[k] for k in z.files}
    data["metadata"] = json.loads(str(data["metadata"]))
    return data
