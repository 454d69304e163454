"""The state of a static load path shared by its methods (load increments, arc length,
relaxation): the converged states, the counters and the ``on_step`` callback."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from numpy.typing import NDArray

from rancf.errors import ConvergenceError

if TYPE_CHECKING:
    from rancf.solvers.system_equilibrium import SystemEquilibrium

__all__ = ["PathState", "MIN_INCREMENT"]

#: Smallest load increment, relative to the first one, before a path method gives up (the
#: path stalls: relaxation takes over).
MIN_INCREMENT = 1e-4


class PathState:
    """The converged states of a static load path so far, with the counters and the
    ``on_step`` callback (:func:`rancf.solvers.static.solve_static`)."""

    def __init__(
        self, problem: SystemEquilibrium, on_step: Callable[[float, NDArray], None] | None
    ) -> None:
        self.problem = problem
        self.y = problem.start()
        self.prev: NDArray | None = None  # the state before the last accepted one
        self.lam = 0.0
        self.prev_lam = 0.0
        self.factors = [0.0]
        self.n_newton = 0
        self.n_residuals = 0
        self.n_relax = 0
        self.n_relax_factorizations = 0
        self.on_step = on_step
        if on_step is not None:
            on_step(0.0, self.y)

    def count(self, iterations: int, residuals: int) -> None:
        """Add Newton iterations and extra residual evaluations."""
        self.n_newton += iterations
        self.n_residuals += residuals

    def accept(self, y: NDArray, lam: float) -> None:
        """A converged state ``y`` at the path parameter ``lam``."""
        self.problem.accept(y)
        self.prev, self.prev_lam = self.y, self.lam
        self.y, self.lam = y, lam
        self.factors.append(lam)
        if self.on_step is not None:
            self.on_step(lam, y)

    def fail(self, what: str) -> ConvergenceError:
        """The error of a path method that cannot go on (relaxation then takes over)."""
        return ConvergenceError(
            f"static {what} did not converge beyond load factor {self.lam:.4g}", reached=self.lam
        )
