"""A background thread that works through a run's blocks of stored rows while the time loop
goes on (:class:`rancf.post.history.HistoryStore`).

Deriving a block's outputs (consistent accelerations, reactions, section values) and appending
them to the raw files costs about half a step a row for a long line stored every step.  The
compiled time loop and the block's core calls release the interpreter lock, so on a machine
with a free core the block is derived beside the steps instead of between them: the run's wall
time drops, its CPU time does not.  One block at a time, in order: :meth:`BlockWorker.submit`
first waits for the block before, so at most two blocks are held in memory.

Only for systems whose rows go through the core as blocks (no contact, rods' triads or
sliding joints: :func:`rancf.system.output_block.takes_block`), so that the worker reads
nothing the time loop changes.
"""

from __future__ import annotations

import threading
from collections.abc import Callable
from typing import Any

__all__ = ["BlockWorker", "works_beside"]


def works_beside(outputs: Any) -> bool:
    """Whether the rows of ``outputs`` (:class:`~rancf.system.outputs.SystemOutputs`) may be
    derived beside the time loop: they take the block path and nothing of theirs is changed
    by the steps (rods re-reference their triads, contact keeps its state)."""
    s = outputs.system
    sliding = any(j.entry.slides for j in s.joints)
    return not (s.has_contact or sliding or outputs.n_directors)


class BlockWorker:
    """Runs one job at a time on a thread of its own; an error is raised by the next
    :meth:`submit` or :meth:`wait`."""

    def __init__(self) -> None:
        self._thread: threading.Thread | None = None
        self._error: BaseException | None = None

    def submit(self, job: Callable[..., None], *args: Any) -> None:
        """Wait for the job before (raising its error), then start ``job(*args)``."""
        self.wait()

        def run() -> None:
            try:
                job(*args)
            except BaseException as exc:  # noqa: BLE001 - handed to the caller by wait()
                self._error = exc

        self._thread = threading.Thread(target=run, name="rancf-outputs", daemon=True)
        self._thread.start()

    def wait(self) -> None:
        """Wait for the running job; raise its error, if any (once)."""
        if self._thread is not None:
            self._thread.join()
            self._thread = None
        if self._error is not None:
            err, self._error = self._error, None
            raise err
