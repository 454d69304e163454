"""What a dynamic run returns: the states at the output times, energies, status and counters
(:func:`rancf.solvers.dynamic.integrate`)."""

from __future__ import annotations

import enum
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    from rancf.solvers.state import DynamicState

__all__ = ["DynamicStatus", "DynamicResult"]


class DynamicStatus(enum.Enum):
    """How a run ended."""

    COMPLETED = "completed"
    FAILED = "failed"
    INTERRUPTED = "interrupted"


@dataclass
class DynamicResult:
    """States at the output times, energies, status and counters.

    With a ``sink`` given to :func:`integrate`, the arrays hold only the last stored state (the
    history went to the sink); ``n_outputs`` counts all of them.
    """

    t: NDArray[np.float64]
    q: NDArray[np.float64]
    v: NDArray[np.float64]
    kinetic: NDArray[np.float64]
    strain: NDArray[np.float64]
    gravity: NDArray[np.float64]
    status: DynamicStatus
    message: str
    n_steps: int = 0
    n_newton: int = 0
    n_factorizations: int = 0
    n_rejected: int = 0
    wall_time: float = 0.0
    min_step_taken: float | None = None
    max_step_taken: float | None = None
    n_outputs: int = 0
    #: Rods: nodal directors ``m1`` at the output times, ``(n_t, n_nodes, 3)``; else None.
    directors: NDArray[np.float64] | None = None
    #: Systems with joints: the multipliers ``λ`` at the output times ``(n_t, m)``; else None.
    lam: NDArray[np.float64] | None = None
    #: Systems with contact: the generalized-α point ``(y_{n+1-α_f}, v_{n+1-α_f})`` of the step
    #: that ended at each output time ``(n_t, 2 n)`` (model coordinates; the initial state
    #: itself at ``t = 0``), where that step's contact forces act; else None.
    alpha: NDArray[np.float64] | None = None
    #: The largest local error estimate of the steps taken, relative to the tolerance
    #: ``rtol * size`` (:meth:`~rancf.solvers.generalized_alpha.GeneralizedAlpha.relative_error`;
    #: above 1: a step was coarser than the tolerance), with the time at the end of that step
    #: and its size.
    error_estimate: float = 0.0
    error_time: float | None = None
    error_step: float | None = None
    #: Where the run stands at its end: :func:`integrate` goes on from it (``start=``).
    state: DynamicState | None = None

    def select(self, index: NDArray | slice) -> DynamicResult:
        """The result restricted to some of its outputs (every per-output array sliced)."""
        from dataclasses import replace

        per_output = ("t", "q", "v", "kinetic", "strain", "gravity", "directors", "lam")
        cut = {k: getattr(self, k)[index] for k in per_output if getattr(self, k) is not None}
        return replace(self, **cut)

    @property
    def total_energy(self) -> NDArray[np.float64]:
        """Kinetic + strain + gravitational potential."""
        return self.kinetic + self.strain + self.gravity

    @property
    def t_reached(self) -> float:
        """Last stored time."""
        return float(self.t[-1]) if self.t.size else 0.0

    def note_error(self, error: float, t: float, h: float) -> None:
        """Keep a step's relative local error estimate if it is the largest so far."""
        if error > self.error_estimate:
            self.error_estimate, self.error_time, self.error_step = float(error), t, h

    def took(self, h: float, count: int = 1) -> None:
        """Count ``count`` accepted steps of size ``h``."""
        if count <= 0:
            return
        self.n_steps += count
        self.min_step_taken = h if self.min_step_taken is None else min(self.min_step_taken, h)
        self.max_step_taken = h if self.max_step_taken is None else max(self.max_step_taken, h)
