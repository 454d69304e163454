"""A running simulation's outputs streamed to disk, and its run directory kept readable.

:class:`HistoryStore` is an output sink for :func:`rancf.solvers.dynamic.integrate`: stored
states are buffered (a few MB) and appended to raw ``float64`` files in ``<out>/.history/``, so
memory stays bounded whatever ``t_end``.  :meth:`HistoryStore.checkpoint` rebuilds the result
files of :mod:`rancf.post.results` from those files (atomically, chunk by chunk) and rewrites
``summary.json``; :meth:`HistoryStore.finish` does it a last time and removes the raw files.

``summary.json`` says ``"running"`` from before the first step (with the process id, start time
and time of the last update) until the run ends, then ``completed``, ``failed`` or
``interrupted``.  A run killed outright (SIGKILL, power loss) keeps ``"running"`` with a process
id that no longer exists and the files of its last checkpoint.
"""

from __future__ import annotations

import datetime
import os
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.model.outputs import DerivedOutputs
from rancf.model.system import Model
from rancf.post.results import atomic_write, strict_json, write_history_files
from rancf.scenario.sensors import Sensor

__all__ = ["HistoryStore", "estimate_output_bytes"]

_FILES = ("t", "q", "v", "e")


def estimate_output_bytes(
    n_outputs: int, n_q: int, n_sensor_columns: int, n_directors: int = 0
) -> int:
    """Disk space a run needs at its end (raw history + results.npz + the two CSV files).

    Raw and ``.npz`` copies of ``t, q, v``, energies and ``n_directors`` director components (a
    rod's 3 per node) at 8 bytes a number each, about 20 bytes a number in the CSV files.
    """
    per_row = 2 * 8 * (2 * n_q + 4 + n_sensor_columns + n_directors) + 20 * (n_sensor_columns + 6)
    return int(n_outputs) * per_row


def _now() -> str:
    return datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")


class HistoryStore:
    """Output sink writing a run directory while the run goes on.

    Parameters
    ----------
    out : Path
        The run directory (must exist).
    model : Model
    sensors : sequence of Sensor
    info : dict
        Extra keys of ``summary.json`` (scenario path, wall times, ...).
    buffer_bytes : int
        Outputs kept in memory before they are appended to the raw files.
    """

    def __init__(
        self,
        out: Path,
        model: Model,
        sensors: Sequence[Sensor],
        info: dict[str, Any],
        buffer_bytes: int = 1 << 23,
        derived: DerivedOutputs | None = None,
    ) -> None:
        self.out = Path(out)
        self.model = model
        self.sensors = sensors
        self.info = {"pid": os.getpid(), "started_at": _now(), **info}
        self.derived = derived if derived is not None else DerivedOutputs(model)
        self.raw = self.out / ".history"
        self.raw.mkdir(exist_ok=True)
        # rods: the nodal directors too ("m", 3 numbers a node)
        self._keys = _FILES + (("m",) if model.element == "rod" else ())
        # derived at every flush from the buffered rows: accelerations "a", reactions "r",
        # section values "s"
        files = self._keys + ("a", "r", "s")
        self._fh = {k: open(self.raw / f"{k}.f64", "wb") for k in files}  # noqa: SIM115
        self._buf: dict[str, list[NDArray]] = {k: [] for k in self._keys}
        self._rows_per_flush = max(1, buffer_bytes // (16 * model.n + 32))
        self.n_rows = 0
        self._pending = 0

    def append(
        self,
        t: float,
        q: NDArray,
        v: NDArray,
        energy: NDArray,
        directors: NDArray | None = None,
    ) -> None:
        """Store one output (sink protocol of :func:`~rancf.solvers.dynamic.integrate`)."""
        self._add((np.array([t]), q, v, energy, directors), 1)

    def append_block(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray,
        energy: NDArray,
        directors: NDArray | None = None,
    ) -> None:
        """Store consecutive outputs: ``t (k,)``, ``q, v (k, n_q)``, ``energy (k, 3)``, rods'
        ``directors (k, n_nodes, 3)``."""
        self._add((t, q, v, energy, directors), len(t))

    def _add(self, values: tuple[NDArray | None, ...], rows: int) -> None:
        for key, val in zip(self._keys, values, strict=False):
            if val is None:
                raise ValueError(f"output stream {key!r} missing")
            self._buf[key].append(np.asarray(val, dtype="<f8").ravel())
        self._pending += rows
        if self._pending >= self._rows_per_flush:
            self.flush()

    def flush(self) -> None:
        """Append the buffered outputs, and their reactions and section values, to the raw
        files."""
        if self._pending:
            rows = {k: np.concatenate(self._buf[k]) for k in self._keys}
            k = self._pending
            acc, reac, along = self.derived.rows(
                rows["t"], rows["q"].reshape(k, -1), rows["v"].reshape(k, -1),
                rows["m"].reshape(k, -1) if "m" in rows else None,
            )  # fmt: skip
            rows["a"], rows["r"], rows["s"] = acc.ravel(), reac.ravel(), along.ravel()
            for key, val in rows.items():
                self._fh[key].write(np.ascontiguousarray(val, dtype="<f8").tobytes())
                self._buf.get(key, []).clear()
        for fh in self._fh.values():
            fh.flush()
        self.n_rows += self._pending
        self._pending = 0

    def _arrays(self) -> tuple[NDArray, ...]:
        n, nq = self.n_rows, self.model.q0.size

        def mm(key: str, width: int) -> NDArray:
            arr = np.memmap(self.raw / f"{key}.f64", dtype="<f8", mode="r", shape=(n * width,))
            return arr.reshape(n, width) if width > 1 else arr

        m1 = mm("m", 3 * self.model.n_nodes) if "m" in self._keys else None
        d = self.derived
        n_r, n_s = len(d.reaction_names), d.n_points * len(d.section_names)
        r = mm("r", n_r).reshape(n, n_r) if n_r else np.empty((n, 0))
        return mm("t", 1), mm("q", nq), mm("v", nq), mm("e", 3), m1, mm("a", nq), r, mm("s", n_s)

    def states(self) -> tuple[NDArray, NDArray]:
        """Times ``(n,)`` and coordinates ``q (n, n_q)`` of the outputs stored so far (memory
        maps of the raw files)."""
        self.flush()
        t, q, *_ = self._arrays()
        return t, q

    def write_summary(self, summary: dict[str, Any]) -> None:
        """Rewrite ``summary.json`` (strict JSON) with the run's fixed keys added."""
        doc = {**summary, **self.info, "updated_at": _now()}
        atomic_write(self.out / "summary.json", strict_json(doc))

    def checkpoint(self, summary: dict[str, Any]) -> None:
        """Flush, rebuild ``sensors.csv``, ``energy.csv``, ``results.npz``; then the summary."""
        self.flush()
        t, q, v, e, m1, a, r, along = self._arrays()
        write_history_files(
            self.out, self.model, self.sensors, t, q, v, e, m1, self.derived, (a, r, along)
        )
        self.write_summary(summary)

    def finish(self, summary: dict[str, Any]) -> None:
        """Last checkpoint, then close and remove the raw files."""
        self.checkpoint(summary)
        self.close()
        shutil.rmtree(self.raw, ignore_errors=True)

    def close(self) -> None:
        """Close the raw files (they stay on disk)."""
        for fh in self._fh.values():
            fh.close()
