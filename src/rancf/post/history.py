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

A checkpoint replaces the three history files and the summary together
(:class:`rancf.atomic.FileSet`), so they always hold the same rows.  When a run fails for a
reason outside the model (a full disk), :meth:`HistoryStore.fail` keeps the last complete
checkpoint and marks its summary ``failed`` with the time that checkpoint reached.
"""

from __future__ import annotations

import contextlib
import datetime
import os
import shutil
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet, atomic_write
from rancf.errors import RunTooLargeError
from rancf.model.outputs import DerivedOutputs
from rancf.model.system import Model
from rancf.post.results import strict_json, write_history_files
from rancf.scenario.sensors import Sensor

__all__ = ["HistoryStore", "estimate_output_bytes", "check_output_size", "HISTORY_FILES"]

#: The files a run directory's history is kept in (replaced together at each checkpoint).
HISTORY_FILES = ("sensors.csv", "energy.csv", "reactions.csv", "results.npz")

_FILES = ("t", "q", "v", "e")


def estimate_output_bytes(
    n_outputs: int, n_q: int, n_sensor_columns: int, n_directors: int = 0, n_derived: int = 0
) -> int:
    """Disk space a run needs at its end (raw history + results.npz + the CSV files).

    Raw and ``.npz`` copies of ``t, q, v, a``, energies, ``n_directors`` director components (a
    rod's 3 per node) and ``n_derived`` reactions and section values at 8 bytes a number each,
    about 20 bytes a number in the CSV files.
    """
    binary = 3 * n_q + 4 + n_sensor_columns + n_directors + n_derived
    per_row = 2 * 8 * binary + 20 * (n_sensor_columns + 6 + n_derived)
    return int(n_outputs) * per_row


def check_output_size(
    where: str,
    n_outputs: int,
    n_q: int,
    n_sensor_columns: int,
    n_directors: int,
    limit_gb: float,
    limit_name: str = "--max-output-gb",
    n_derived: int = 0,
) -> None:
    """Refuse, before it starts, a run whose files would take more than ``limit_gb`` GB
    (:func:`estimate_output_bytes`).

    Raises
    ------
    RunTooLargeError
        Naming ``where`` (the scenario), the size, the number of stored states and the limit.
    """
    need = estimate_output_bytes(n_outputs, n_q, n_sensor_columns, n_directors, n_derived)
    if need > limit_gb * 1e9:
        raise RunTooLargeError(
            f"{where}: this run would write about {need / 1e9:.3g} GB ({n_outputs} stored "
            f"states of {n_q} coordinates), more than {limit_name} = {limit_gb:g}; "
            "raise solver.output_step, shorten solver.t_end or raise the limit"
        )


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
        #: Rows and last time of the history files on disk (the last complete checkpoint).
        self.saved_rows = 0
        self.saved_t: float | None = None

    def append(
        self,
        t: float,
        q: NDArray,
        v: NDArray,
        energy: NDArray,
        directors: NDArray | None = None,
        lam: NDArray | None = None,
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
        lam: NDArray | None = None,
    ) -> None:
        """Store consecutive outputs: ``t (k,)``, ``q, v (k, n_q)``, ``energy (k, 3)``, rods'
        ``directors (k, n_nodes, 3)`` (``lam``: multipliers of a system's joints, unused for one
        body)."""
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
        files (an error of a full disk names the file)."""
        key = "t"
        try:
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
            for key in self._fh:
                self._fh[key].flush()
        except OSError as exc:  # a full disk: name the file
            where = str(self.raw / f"{key}.f64")
            raise OSError(exc.errno, exc.strerror or str(exc), where) from None
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

    def _summary_text(self, summary: dict[str, Any]) -> str:
        return strict_json({**summary, **self.info, "updated_at": _now()})

    def write_summary(self, summary: dict[str, Any]) -> None:
        """Rewrite ``summary.json`` (strict JSON) with the run's fixed keys added."""
        atomic_write(self.out / "summary.json", self._summary_text(summary))

    def checkpoint(self, summary: dict[str, Any]) -> None:
        """Flush; replace ``sensors.csv``, ``energy.csv``, ``results.npz`` and the summary
        together."""
        self.flush()
        arrays = self._arrays()
        t, q, v, e, m1, a, r, along = arrays
        with FileSet() as files:
            write_history_files(
                self.out, self.model, self.sensors, t, q, v, e, m1, self.derived, (a, r, along),
                files=files,
            )  # fmt: skip
            files.write(self.out / "summary.json", self._summary_text(summary))
        self.saved_rows = self.n_rows
        self.saved_t = float(t[-1]) if self.n_rows else None

    def finish(self, summary: dict[str, Any]) -> None:
        """Last checkpoint, then close and remove the raw files."""
        self.checkpoint(summary)
        self.close()
        shutil.rmtree(self.raw, ignore_errors=True)

    def fail(self, summary: dict[str, Any]) -> bool:
        """End a run that raised: a last checkpoint with ``summary`` if the disk takes it, else
        the last complete checkpoint kept with its summary marked ``failed`` (``t_reached`` and
        ``outputs`` of that checkpoint).  Never raises an :class:`OSError`; the raw files are
        removed.  Returns whether the final checkpoint was written."""
        try:
            self.checkpoint(summary)
            done = True
        except Exception:  # noqa: BLE001 - a full disk, or raw files cut short by one
            done = False
        self.close()
        shutil.rmtree(self.raw, ignore_errors=True)  # frees the disk for the summary below
        if not done:
            kept = {
                **summary,
                "t_reached": self.saved_t,
                "outputs": self.saved_rows,
                "message": f"{summary.get('message', '')}; the files hold the last complete "
                f"checkpoint (t = {self.saved_t or 0.0:g} s, {self.saved_rows} stored states)",
            }
            try:
                self.write_summary(kept)
            except OSError:
                pass  # the disk takes nothing: the summary of the last checkpoint stays
        return done

    def discard(self) -> None:
        """Remove everything the store wrote (a run that failed before its first checkpoint)."""
        self.close()
        shutil.rmtree(self.raw, ignore_errors=True)
        for name in (*HISTORY_FILES, "summary.json"):
            with contextlib.suppress(OSError):
                (self.out / name).unlink()

    def close(self) -> None:
        """Close the raw files (they stay on disk)."""
        for fh in self._fh.values():
            with contextlib.suppress(OSError):
                fh.close()
