"""Where :func:`rancf.solvers.dynamic.integrate` puts the stored states: output sinks.

A sink receives one row per output time: ``t``, nodal coordinates ``q (n_q,)``, velocities
``v (n_q,)``, the energies ``(kinetic, strain, gravity)`` and named streams: for rods, the nodal
directors ``directors (n_nodes, 3)`` (the first material axis of each node's triad, which the
stored coordinates alone do not fix: the triads are carried along the whole path of the run).
:class:`MemorySink` keeps them in memory (the default, for library use); the command line
streams them to disk with :class:`rancf.post.history.HistoryStore`, so memory stays bounded
whatever ``t_end``.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["OutputSink", "MemorySink", "STREAMS"]

#: Named streams of a row besides ``t, q, v`` and the energies: rods' ``directors``, the
#: multipliers ``lam`` and, in systems with contact, ``alpha``: the generalized-α point
#: ``(y_{n+1-α_f}, v_{n+1-α_f})`` of the step that ended at the row (model coordinates, ``2 n``
#: numbers), where that step's contact forces act.
STREAMS = ("directors", "lam", "alpha")


class OutputSink(Protocol):
    """Receives the stored states of a run, in time order."""

    def append(
        self,
        t: float,
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray[np.float64] | None,
        **streams: NDArray[np.float64] | None,
    ) -> None:
        """Store one output: time, ``q (n_q,)``, ``v (n_q,)``, energies ``(3,)`` (None where the
        sink derives them itself, ``derives_energies``) and the :data:`STREAMS` (rods'
        ``directors (n_nodes, 3)``; None: absent)."""

    def append_block(
        self,
        t: NDArray[np.float64],
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray | None,
        **streams: NDArray[np.float64] | None,
    ) -> None:
        """Store consecutive outputs: ``t (k,)``, ``q, v (k, n_q)``, ``energy (k, 3)`` (None
        where the sink derives them) and each stream with a leading axis ``k``."""


class MemorySink:
    """Keeps every output in memory; :meth:`arrays` and :meth:`stream` stack them."""

    def __init__(self) -> None:
        self.t: list[float] = []
        self.q: list[NDArray[np.float64]] = []
        self.v: list[NDArray[np.float64]] = []
        self.e: list[NDArray[np.float64]] = []
        self.streams: dict[str, list[NDArray[np.float64]]] = {k: [] for k in STREAMS}

    def append(
        self,
        t: float,
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray[np.float64],
        **streams: NDArray[np.float64] | None,
    ) -> None:
        """Store one output (copies of the arrays)."""
        self.append_block(
            np.array([t]),
            np.asarray(q)[None],
            np.asarray(v)[None],
            np.asarray(energy)[None],
            **{k: None if s is None else np.asarray(s)[None] for k, s in streams.items()},
        )

    def append_block(
        self,
        t: NDArray[np.float64],
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray,
        **streams: NDArray[np.float64] | None,
    ) -> None:
        """Store consecutive outputs (the rows are kept as views of copies of the blocks)."""
        self.t.extend(np.asarray(t, dtype=float).tolist())
        self.q.extend(np.array(q, dtype=float))
        self.v.extend(np.array(v, dtype=float))
        self.e.extend(np.array(energy, dtype=float))
        for k, s in streams.items():
            if s is not None:
                self.streams[k].extend(np.array(s, dtype=float))

    def stream(self, name: str) -> NDArray[np.float64] | None:
        """A stream stacked over the outputs (None when none was stored)."""
        rows = self.streams.get(name, [])
        return np.array(rows) if rows else None

    def arrays(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """``t (n,)``, ``q (n, n_q)``, ``v (n, n_q)``, energies ``(n, 3)``."""
        return np.array(self.t), np.array(self.q), np.array(self.v), np.array(self.e).reshape(-1, 3)
