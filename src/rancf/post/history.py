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
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from rancf.atomic import FileSet, atomic_write
from rancf.post.block_worker import BlockWorker, works_beside
from rancf.post.results import strict_json
from rancf.post.resume import CHECKPOINT
from rancf.post.run_files import DERIVED, write_history_files

if TYPE_CHECKING:
    from rancf.system.outputs import SystemOutputs

__all__ = ["HistoryStore", "HISTORY_FILES", "WORKER_BLOCK_BYTES", "WORKER_BLOCK_ROWS"]

#: The files a run directory's history is kept in (replaced together at each checkpoint).
HISTORY_FILES = ("sensors.csv", "energy.csv", "reactions.csv", "results.npz")

_FILES = ("t", "q", "v", "e")

#: Bytes kept free for the last ``summary.json`` of a run that fails on a full disk: a file of
#: this size in the raw folder, which :meth:`HistoryStore.fail` removes before writing it.
RESERVE_BYTES = 1 << 15

#: Stored rows derived at a time, on the output worker or between the steps (bytes of ``q`` and
#: ``v``).
WORKER_BLOCK_BYTES = 1 << 20
#: ... and at most this many rows, so that a small model's rows too are derived beside the loop
#: (8 elements: 1000 rows in one block were derived after it, 9 ms against the loop's 17 ms).
WORKER_BLOCK_ROWS = 128


def _reserve(path: Path) -> None:
    """Write :data:`RESERVE_BYTES` at ``path`` if the disk takes them (else nothing is kept: the
    run's first write reports the full disk)."""
    try:
        with open(path, "wb") as fh:  # file systems charge written bytes at write time
            fh.write(b"\0" * RESERVE_BYTES)
    except OSError:
        with contextlib.suppress(OSError):
            path.unlink()


def _raw_bytes(values: NDArray) -> memoryview:
    """The numbers as little-endian float64 bytes, without a copy where they already are."""
    return np.ascontiguousarray(values, dtype="<f8").reshape(-1).data.cast("B")


def _now() -> str:
    return datetime.datetime.now(datetime.UTC).isoformat(timespec="seconds")


class HistoryStore:
    """Output sink writing a run directory while the run goes on.

    Parameters
    ----------
    out : Path
        The run directory (must exist).
    outputs : SystemOutputs
        The system, its sensors and what is derived from the stored rows.
    info : dict
        Extra keys of ``summary.json`` (scenario path, wall times, ...).
    buffer_bytes : int
        Outputs kept in memory before they are appended to the raw files (default: 8 MB; where
        the store derives the rows, with the worker or without, :data:`WORKER_BLOCK_BYTES` and
        at most :data:`WORKER_BLOCK_ROWS` rows).
    beside : bool, optional
        Derive and append each full buffer on a thread of its own while the run goes on
        (:mod:`rancf.post.block_worker`); default: where the system allows it.
    """

    def __init__(
        self,
        out: Path,
        outputs: SystemOutputs,
        info: dict[str, Any],
        buffer_bytes: int | None = None,
        beside: bool | None = None,
    ) -> None:
        self.out = Path(out)
        self.outputs = outputs
        self.info = {"pid": os.getpid(), "started_at": _now(), **info}
        self.raw = self.out / ".history"
        self.raw.mkdir(exist_ok=True)
        _reserve(self.raw / "reserve")
        # rods: the nodal directors too ("m", 3 numbers a node)
        self._keys = _FILES + (("m",) if outputs.n_directors else ())
        # derived at every flush from the buffered rows (rancf.post.run_files.DERIVED)
        files = self._keys + DERIVED
        self._fh = {k: open(self.raw / f"{k}.f64", "wb") for k in files}  # noqa: SIM115
        self._buf: dict[str, list[NDArray]] = {k: [] for k in self._keys}
        self._alpha: list[NDArray] = []  # the buffered rows' steps' alpha points (contact)
        #: The rows' energies come from the stored rows (:meth:`_energies`, beside the loop with
        #: the worker), not from the time loop, where the rows hold all they depend on (no
        #: rods' triads, contact or sliding joints): ``integrate`` then passes None.
        self.derives_energies = works_beside(outputs)
        beside = self.derives_energies if beside is None else beside
        self._worker = BlockWorker() if beside else None
        # rows derived by the store: small blocks, whose arrays stay in the caches (a block of
        # 2000 rows took 1.3 times the time a row of 128 or 512 did) and, beside the loop, whose
        # last, which the loop waits for, is short
        small = beside or self.derives_energies
        if buffer_bytes is None:
            buffer_bytes = WORKER_BLOCK_BYTES if small else 1 << 23
        self._rows_per_flush = max(1, buffer_bytes // (16 * outputs.n_q + 32))
        if small:  # small models too: several blocks a run
            self._rows_per_flush = min(self._rows_per_flush, WORKER_BLOCK_ROWS)
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
        energy: NDArray | None,
        directors: NDArray | None = None,
        lam: NDArray | None = None,
        alpha: NDArray | None = None,
    ) -> None:
        """Store one output (sink protocol of :func:`~rancf.solvers.dynamic.integrate`)."""
        self._add((np.array([t]), q, v, energy, directors), 1, alpha)

    def append_block(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray,
        energy: NDArray | None,
        directors: NDArray | None = None,
        lam: NDArray | None = None,
        alpha: NDArray | None = None,
    ) -> None:
        """Store consecutive outputs: ``t (k,)``, ``q, v (k, n_q)``, ``energy (k, 3)``, rods'
        ``directors (k, n_rod_nodes, 3)`` (``lam``, the integrator's multipliers, is not kept:
        the files hold the consistent ones; ``alpha``, the steps' generalized-α points of a
        system with contact, only until the rows' outputs are derived)."""
        self._add((t, q, v, energy, directors), len(t), alpha)

    def _add(
        self, values: tuple[NDArray | None, ...], rows: int, alpha: NDArray | None = None
    ) -> None:
        for key, val in zip(self._keys, values, strict=False):
            if val is None and key == "e":  # derived from the rows (derives_energies)
                continue
            if val is None:
                raise ValueError(f"output stream {key!r} missing")
            self._buf[key].append(np.asarray(val, dtype="<f8").ravel())
        if alpha is not None:
            self._alpha.append(np.asarray(alpha, dtype=float).reshape(rows, -1))
        self._pending += rows
        if self._pending >= self._rows_per_flush:
            self._hand_over()

    def seed(self, rows: dict[str, NDArray]) -> None:
        """Start from the rows of an earlier part of the run (a resumed run:
        :func:`rancf.post.resume.stored_rows`), already derived."""
        self.flush()
        n = len(rows["t"])
        self.outputs.energy.add(rows["t"], rows["e"])  # the energy check sees the whole run
        for key, fh in self._fh.items():
            fh.write(_raw_bytes(rows[key]))
            fh.flush()
        self.n_rows += n
        self.saved_rows = self.n_rows
        self.saved_t = float(rows["t"][-1]) if n else None

    def flush(self) -> None:
        """Append the buffered outputs, and what is derived from them, to the raw files (an
        error of a full disk names the file); :func:`rancf.solvers.dynamic.integrate` calls it
        before the run's wall time is taken, so that every stored row's derivation counts in
        it (the worker's blocks and the last buffer's)."""
        self._hand_over()
        self.wait()

    def _hand_over(self) -> None:
        """The buffered outputs to :meth:`_append`: on the worker thread if the store has one
        (returning at once), else here."""
        if self._pending:
            rows = {k: np.concatenate(self._buf[k]) for k in self._keys if self._buf[k]}
            alpha = np.concatenate(self._alpha) if self._alpha else None
            k, self._pending = self._pending, 0
            for buf in self._buf.values():
                buf.clear()
            self._alpha.clear()
            if self._worker is None:
                self._append(rows, alpha, k)
            else:
                self._worker.submit(self._append, rows, alpha, k)

    def wait(self) -> None:
        """Wait until the blocks handed to the worker are derived and appended (raising its
        error)."""
        if self._worker is not None:
            self._worker.wait()

    def _append(self, rows: dict[str, NDArray], alpha: NDArray | None, k: int) -> None:
        key = "t"
        try:
            if k and "e" not in rows:  # the energies of the rows, (k, 3)
                rows["e"] = self._energies(rows, k)
            if k:
                derived = self.outputs.rows(
                    rows["t"],
                    rows["q"].reshape(k, -1),
                    rows["v"].reshape(k, -1),
                    rows["m"].reshape(k, -1) if "m" in rows else None,
                    rows["e"].reshape(k, 3),
                    per_body=True,
                    alpha=alpha,
                )
                rows.update({d: derived[d].ravel() for d in DERIVED})
                self.outputs.energy.add(rows["t"], rows["e"])
                for key, val in rows.items():
                    self._fh[key].write(_raw_bytes(val))
            for key in self._fh:
                self._fh[key].flush()
        except OSError as exc:  # a full disk: name the file
            where = str(self.raw / f"{key}.f64")
            raise OSError(exc.errno, exc.strerror or str(exc), where) from None
        self.n_rows += k

    def _energies(self, rows: dict[str, NDArray], k: int) -> NDArray:
        """Kinetic, strain and gravitational energy of ``k`` buffered rows (the time loop's
        ``system_energies`` at each row's time), as the loop would have stored them."""
        s, e = self.outputs.system, np.empty((k, 3))
        ys = s.y_from_q(rows["q"].reshape(k, -1))
        vs = s.y_from_q(rows["v"].reshape(k, -1))
        s.core.energies_rows(rows["t"], np.ascontiguousarray(ys), np.ascontiguousarray(vs), e)
        return e.ravel()

    def _arrays(self) -> tuple[dict[str, NDArray], NDArray | None]:
        n, o = self.n_rows, self.outputs
        s = o.system
        widths = {
            "t": 1,
            "q": o.n_q,
            "v": o.n_q,
            "e": 3,
            "m": o.n_directors,
            "a": o.n_q,
            "lam": s.m,
            "r": len(o.reaction_names),
            "s": o.n_along,
            "c": len(o.sensor_names),
            "eb": 3 * len(s.flex),
        }

        def mm(key: str) -> NDArray:
            w = widths[key]
            if n * w == 0:
                return np.empty((n, w)) if key != "t" else np.empty(0)
            arr = np.memmap(self.raw / f"{key}.f64", dtype="<f8", mode="r", shape=(n * w,))
            return arr if key == "t" else arr.reshape(n, w)

        arrays = {k: mm(k) for k in (*_FILES, *DERIVED)}
        return arrays, (mm("m") if "m" in self._keys else None)

    def states(self) -> tuple[NDArray, NDArray]:
        """Times ``(n,)`` and coordinates ``q (n, n_q)`` of the outputs stored so far (memory
        maps of the raw files)."""
        self.flush()
        arrays, _ = self._arrays()
        return arrays["t"], arrays["q"]

    def _summary_text(self, summary: dict[str, Any]) -> str:
        return strict_json({**summary, **self.info, "updated_at": _now()})

    def write_summary(self, summary: dict[str, Any]) -> None:
        """Rewrite ``summary.json`` (strict JSON) with the run's fixed keys added."""
        atomic_write(self.out / "summary.json", self._summary_text(summary))

    def checkpoint(self, summary: dict[str, Any], state: Any = None) -> None:
        """Flush; replace ``sensors.csv``, ``energy.csv``, ``results.npz``, the summary and
        (given the run's :class:`~rancf.solvers.state.DynamicState` after the last row)
        ``checkpoint.npz`` together."""
        self.flush()
        arr, m1 = self._arrays()
        t = arr["t"]
        with FileSet() as files:
            write_history_files(
                self.out,
                self.outputs,
                t,
                arr["q"],
                arr["v"],
                arr["e"],
                m1,
                {k: arr[k] for k in DERIVED},
                files=files,
            )
            if state is not None:  # renamed after the rows it follows, before the summary
                files.write(self.out / CHECKPOINT, state.to_bytes())
            files.write(self.out / "summary.json", self._summary_text(summary))
        self.saved_rows = self.n_rows
        self.saved_t = float(t[-1]) if self.n_rows else None

    def finish(self, summary: dict[str, Any], state: Any = None) -> None:
        """Last checkpoint (with the run's last ``state``), then close and remove the raw
        files."""
        self.checkpoint(summary, state)
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
        shutil.rmtree(self.raw, ignore_errors=True)  # frees the reserve for the summary below
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
        for name in (*HISTORY_FILES, "summary.json", CHECKPOINT):
            with contextlib.suppress(OSError):
                (self.out / name).unlink()
        shutil.rmtree(self.out / "bodies", ignore_errors=True)

    def close(self) -> None:
        """Close the raw files (they stay on disk), once the worker's block is done."""
        if self._worker is not None:
            with contextlib.suppress(Exception):  # the run ends anyway; its error was raised
                self._worker.wait()
        for fh in self._fh.values():
            with contextlib.suppress(OSError):
                fh.close()
