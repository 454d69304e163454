"""Result files: written atomically, so an interrupted run never leaves a corrupt file.

A run directory holds

* ``sensors.csv`` — header ``t`` then one column per sensor scalar;
* ``energy.csv`` — ``t, kinetic, strain, gravity, total`` [J];
* ``results.npz`` — the full state history (``t``, ``q``, ``v``, energies, mesh data, JSON
  metadata), loadable with :func:`load_results` or plain ``numpy.load``;
* ``summary.json`` — status, message, time reached, counters and wall times (strict JSON:
  a non-finite number is written as ``null``).

Every file is written through :mod:`rancf.atomic`: under a temporary name, given the permissions
the umask allows (0644 under umask 0022) and renamed into place; the files of a run
(``sensors.csv``, ``energy.csv``, ``reactions.csv``, ``results.npz`` and ``summary.json``) are
renamed together once all are written, so they always hold the same rows.  Histories are written
in chunks of rows, so a long run's files are built without holding them in memory.
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
from rancf.model.motion import angular_momentum
from rancf.model.outputs import DerivedOutputs
from rancf.model.system import Model
from rancf.post.checks import run_warnings
from rancf.scenario.sensors import Sensor
from rancf.solvers.dynamic import DynamicResult

__all__ = [
    "strict_json",
    "json_safe",
    "write_history_files",
    "reader_metadata",
    "write_run",
    "run_summary",
    "load_results",
    "sensor_table",
]

#: Rows of a history handled at once when writing files.
CHUNK_BYTES = 1 << 24


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
    model: Model,
    sensors: Sequence[Sensor],
    q: NDArray,
    v: NDArray | None = None,
    energy: NDArray | None = None,
) -> tuple[list[str], NDArray[np.float64]]:
    """Column names and values ``(n_t, n_columns)`` of the sensors for states ``q``, ``v``.

    ``twist`` sensors (rods) read the node's twist coordinate ``φ`` (the 7th of the node);
    ``angular_momentum`` needs the velocities ``v`` (default zero: a static state);
    ``energy`` sums the rows of ``energy`` ``(n_t, 3)`` (kinetic, strain, gravity; computed
    from ``q``, ``v`` when not given).
    """
    qq = np.atleast_2d(q)
    vv = np.zeros_like(qq) if v is None else np.atleast_2d(v)
    pos = model.node_positions(qq)
    twists = None
    if model.element == "rod":
        twists = qq.reshape(qq.shape[:-1] + (model.n_nodes, model.dpn))[..., 6]
    names: list[str] = []
    cols = []
    for s in sensors:
        names += s.columns(model.dim)
        if s.kind == "angular_momentum":
            cols.append(angular_momentum(model, qq, vv, s.about))
        elif s.kind == "energy":
            if energy is None:
                energy = _energies(model, qq, vv)
            cols.append(np.atleast_2d(energy).sum(axis=1)[:, None])
        else:
            cols.append(s.evaluate(pos, twists))
    vals = np.concatenate(cols, axis=1) if cols else np.empty((pos.shape[0], 0))
    return names, vals


def _energies(model: Model, q: NDArray, v: NDArray) -> NDArray[np.float64]:
    """``(kinetic, strain, gravity)`` of states ``q``, ``v`` (full coordinates), ``(n_t, 3)``."""
    ys, vs = model.y_from_q(q), model.y_from_q(v)
    return np.array(
        [[model.kinetic_energy(b, a), model.strain_energy(a), model.gravity_energy(a)]
         for a, b in zip(ys, vs, strict=True)]
    )  # fmt: skip


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


def reader_metadata(model: Model) -> dict[str, Any]:
    """What readers of a run directory need besides the states (no scenario file required):
    ``section_radius`` (``sqrt(A / π)``, the radius of a circular section) and, for beams, the
    reference nodal ``tangent_angles`` [rad]."""
    meta: dict[str, Any] = {"section_radius": model.section.radius}
    if model.element == "beam":
        t = model.mesh.nodes[:, 1]
        meta["tangent_angles"] = np.arctan2(t[:, 1], t[:, 0]).tolist()
    return meta


def write_history_files(
    out: Path,
    model: Model,
    sensors: Sequence[Sensor],
    t: NDArray,
    q: NDArray,
    v: NDArray,
    energy: NDArray,
    directors: NDArray | None = None,
    derived: DerivedOutputs | None = None,
    precomputed: tuple[NDArray, NDArray, NDArray] | None = None,
    static: bool = False,
    files: FileSet | None = None,
) -> list[str]:
    """``sensors.csv``, ``energy.csv``, ``reactions.csv`` and ``results.npz`` of a history,
    chunk by chunk.

    ``t (n,)``, ``q`` and ``v (n, n_q)``, ``energy (n, 3)`` and a rod's nodal ``directors``
    (``(n, 3 n_nodes)`` or ``(n, n_nodes, 3)``, stored as ``directors (n, n_nodes, 3)``) may be
    memory maps.  The accelerations, reactions and section values (:class:`DerivedOutputs`)
    come from ``precomputed = (a (n, n_q), reactions (n, n_r), along (n, n_points * n_names))``
    or are computed from the rows (``static``: rows of a load path, ``t`` the path parameter).
    The files replace the old ones together (:mod:`rancf.atomic`): when the call ends, or, with
    ``files`` given, when that set is committed.  Returns the sensor column names.
    """
    if files is None:
        with FileSet() as own:
            return write_history_files(
                out, model, sensors, t, q, v, energy, directors, derived, precomputed, static, own
            )
    n = t.shape[0]
    derived = derived if derived is not None else DerivedOutputs(model)
    m1 = None if directors is None else directors.reshape(n, -1)

    def derived_rows(r: slice) -> tuple[NDArray, NDArray, NDArray]:
        if precomputed is not None:
            return precomputed[0][r], precomputed[1][r], precomputed[2][r]
        mm = None if m1 is None else m1[r]
        acc, reac, along = derived.rows(t[r], q[r], v[r], mm, static=static)
        return acc, reac, along.reshape(along.shape[0], -1)

    names, _ = sensor_table(model, sensors, q[:1])
    with files.file(out / "sensors.csv") as fh:
        fh.write((",".join(["t", *names]) + "\n").encode())
        for r in _rows(n, q.shape[1]):
            _, vals = sensor_table(model, sensors, q[r], v[r], energy[r])
            np.savetxt(fh, np.column_stack([t[r], vals]), delimiter=",", fmt="%.12g")
    with files.file(out / "energy.csv") as fh:
        fh.write(b"t,kinetic,strain,gravity,total\n")
        for r in _rows(n, 5):
            e = energy[r]
            np.savetxt(fh, np.column_stack([t[r], e, e.sum(axis=1)]), delimiter=",", fmt="%.12g")
    width = len(derived.section_names) * derived.n_points
    chunks = [(r, *derived_rows(r)) for r in _rows(n, 2 * q.shape[1] + width)]
    if derived.reaction_names:
        with files.file(out / "reactions.csv") as fh:
            fh.write((",".join(["t", *derived.reaction_names]) + "\n").encode())
            for r, _, reac, _ in chunks:
                np.savetxt(fh, np.column_stack([t[r], reac]), delimiter=",", fmt="%.12g")
    meta = {
        "element": model.element,
        "dim": model.dim,
        "dofs_per_node": model.dpn,
        "n_nodes": model.n_nodes,
        "n_elements": model.n_el,
        "sensor_columns": names,
        "reaction_columns": derived.reaction_names,
        "section_names": list(derived.section_names),
        **reader_metadata(model),
    }
    small = {
        "weights": model.mesh.weights,
        "scales": model.mesh.scales,
        "reference": model.q0,
        "along_s": derived.sampler.s,
        "metadata": np.array(json.dumps(meta)),
    }
    n_r = len(derived.reaction_names)
    along_shape = (n, derived.n_points, len(derived.section_names))
    with files.file(out / "results.npz") as fh:
        with zipfile.ZipFile(fh, "w", zipfile.ZIP_STORED, allowZip64=True) as z:
            _npy(z, "t", (n,), (t[r] for r in _rows(n, 1)))
            for name, arr in (("q", q), ("v", v)):
                _npy(z, name, arr.shape, (arr[r] for r in _rows(n, arr.shape[1])))
            _npy(z, "a", q.shape, (c[1] for c in chunks))
            for j, name in enumerate(("kinetic", "strain", "gravity")):
                _npy(z, name, (n,), (energy[r, j] for r in _rows(n, 3)))
            if m1 is not None:
                shape3 = (n, m1.shape[1] // 3, 3)
                _npy(z, "directors", shape3, (m1[r] for r in _rows(n, m1.shape[1])))
            shape = (n, len(names))
            rows = _rows(n, q.shape[1])
            vals = (sensor_table(model, sensors, q[r], v[r], energy[r])[1] for r in rows)
            _npy(z, "sensors", shape, vals)
            _npy(z, "reactions", (n, n_r), (c[2] for c in chunks))
            _npy(z, "along", along_shape, (c[3] for c in chunks))
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
    labels: Sequence[int | str] | None = None,
) -> dict[str, Any]:
    """Write the files of a run directory from an in-memory result; returns the summary.

    ``labels``: the supports' ``at`` as written in the scenario (reaction column names).
    """
    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    energy = np.column_stack([result.kinetic, result.strain, result.gravity])
    summary = {
        **run_summary(model, result),
        "warnings": run_warnings(model, result.t, result.q),
        **(extra or {}),
    }
    with FileSet() as files:  # the files replace an earlier run's together
        write_history_files(
            out, model, sensors, result.t, result.q, result.v, energy, result.directors,
            DerivedOutputs(model, labels), files=files,
        )  # fmt: skip
        files.write(out / "summary.json", strict_json(summary))
    return summary


class LoadPath:
    """The converged load steps of a static solve: pass :meth:`record` as ``on_step`` of
    :func:`rancf.solvers.static.solve_static`, then :func:`write_static_run`.

    ``labels``: the supports' ``at`` as written in the scenario (reaction column names).
    """

    def __init__(self, model: Model, labels: Sequence[int | str] | None = None) -> None:
        self.model = model
        self.derived = DerivedOutputs(model, labels)
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
    with FileSet() as files:  # the files replace an earlier load path's together
        write_history_files(
            out, model, sensors, t, q, np.zeros_like(q), energy, m1, path.derived, static=True,
            files=files,
        )  # fmt: skip
        last = None if m1 is None else m1[-1]
        write_along_csv(out / "along.csv", path, q[-1], last, files)
        # after the rows: their outputs tracked the largest strain of the warnings
        doc = {
            "analysis": "static",
            "load_factor_reached": float(t[-1]),
            "load_steps_converged": int(t.size - 1),
            "n_elements": model.n_el,
            "element": model.element,
            "n_dofs": model.n,
            "outputs": int(t.size),
            "warnings": run_warnings(model, static=True, largest=path.derived.largest_strain),
            **summary,
        }
        files.write(out / "summary.json", strict_json(doc))
    return doc


def write_along_csv(
    path: Path, load_path: LoadPath, q: NDArray, m1: NDArray | None, files: FileSet | None = None
) -> None:
    """``along.csv`` of the last state of a load path: one row per section sample point with the
    reference arc length ``s``, the position and the section quantities (into the set ``files``,
    or atomically on its own)."""
    if files is None:
        with FileSet() as own:
            return write_along_csv(path, load_path, q, m1, own)
    d = load_path.derived
    lam = load_path.steps[-1][0]
    _, _, along = d.rows(np.array([lam]), q[None], directors=None if m1 is None else m1[None],
                         static=True)  # fmt: skip
    pos = d.sampler.positions(load_path.model.y_from_q(q))
    axes = ["x", "y", "z"][: load_path.model.dim]
    head = ",".join(["s", *axes, *d.section_names]) + "\n"
    with files.file(path) as fh:
        fh.write(head.encode())
        np.savetxt(fh, np.column_stack([d.sampler.s, pos, along[0]]), delimiter=",", fmt="%.12g")


def load_results(path: str | Path) -> dict[str, Any]:
    """Read a ``results.npz`` into a dictionary (``metadata`` decoded from JSON)."""
    with np.load(path, allow_pickle=False) as z:
        data = {k: z[k] for k in z.files}
    data["metadata"] = json.loads(str(data["metadata"]))
    return data
