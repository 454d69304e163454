"""Where :func:`rancf.solvers.dynamic.integrate` puts the stored states: output sinks.

A sink receives one row per output time: ``t``, nodal coordinates ``q (n_q,)``, velocities
``v (n_q,)``, the energies ``(kinetic, strain, gravity)`` and, for rods, the nodal directors
``m1 (n_nodes, 3)`` (the first material axis of each node's triad, which the stored coordinates
alone do not fix: the triads are carried along the whole path of the run).
:class:`MemorySink` keeps them in memory (the default, for library use); the command line
streams them to disk with
:class:`rancf.post.history.HistoryStore`, so memory stays bounded whatever ``t_end``.
"""

from __future__ import annotations

from typing import Protocol

import numpy as np
from numpy.typing import NDArray

__all__ = ["OutputSink", "MemorySink"]


class OutputSink(Protocol):
    """Receives the stored states of a run, in time order."""

    def append(
        self,
        t: float,
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray[np.float64],
        directors: NDArray[np.float64] | None = None,
    ) -> None:
        """Store one output: time, ``q (n_q,)``, ``v (n_q,)``, energies ``(3,)``, rods' nodal
        directors ``(n_nodes, 3)``."""

    def append_block(
        self,
        t: NDArray[np.float64],
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray,
        directors: NDArray[np.float64] | None = None,
    ) -> None:
        """Store consecutive outputs: ``t (k,)``, ``q, v (k, n_q)``, ``energy (k, 3)``,
        ``directors (k, n_nodes, 3)``."""


class MemorySink:
    """Keeps every output in memory; :meth:`arrays` stacks them."""

    def __init__(self) -> None:
        self.t: list[float] = []
        self.q: list[NDArray[np.float64]] = []
        self.v: list[NDArray[np.float64]] = []
        self.e: list[NDArray[np.float64]] = []
        self.m: list[NDArray[np.float64]] = []

    def append(
        self,
        t: float,
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray[np.float64],
        directors: NDArray[np.float64] | None = None,
    ) -> None:
        """Store one output (copies of the arrays)."""
        self.t.append(float(t))
        self.q.append(np.array(q, dtype=float))
        self.v.append(np.array(v, dtype=float))
        self.e.append(np.array(energy, dtype=float))
        if directors is not None:
            self.m.append(np.array(directors, dtype=float))

    def append_block(
        self,
        t: NDArray[np.float64],
        q: NDArray[np.float64],
        v: NDArray[np.float64],
        energy: NDArray,
        directors: NDArray[np.float64] | None = None,
    ) -> None:
        """Store consecutive outputs (the rows are kept as views of copies of the blocks)."""
        self.t.extend(np.asarray(t, dtype=float).tolist())
        self.q.extend(np.array(q, dtype=float))
        self.v.extend(np.array(v, dtype=float))
        self.e.extend(np.array(energy, dtype=float))
        if directors is not None:
            self.m.extend(np.array(directors, dtype=float))

    def directors(self) -> NDArray[np.float64] | None:
        """Rods' nodal directors ``(n, n_nodes, 3)`` (None when none were stored)."""
        return np.array(self.m) if self.m else None

    def arrays(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """``t (n,)``, ``q (n, n_q)``, ``v (n, n_q)``, energies ``(n, 3)``."""
        return np.array(self.t), np.array(self.q), np.array(self.v), np.array(self.e).reshape(-1, 3)
