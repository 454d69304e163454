"""Analysis settings of a time integration (:class:`DynamicOptions`): plain, validated data.

They sit with the model (a scenario file describes both) and are consumed by
:func:`rancf.solvers.dynamic.integrate`, which re-exports them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from rancf.errors import InputError

__all__ = [
    "DynamicOptions",
    "MAX_STEPS",
    "MAX_NEWTON",
    "MAX_LOAD_STEPS",
    "MAX_SPIN_RATE",
    "SPIN_RATES",
]

#: Most time steps (``t_end / step`` of a fixed-step run) and stored states (``t_end /
#: output_step``) a run may have: a billion steps take hours even for the smallest model, so a
#: count beyond it is a unit mistake (``step = 1e-12``), refused before the run starts.
MAX_STEPS = 10**9
#: Largest ``max_newton`` (Newton iterations of a step).
MAX_NEWTON = 1000
#: Largest ``solver.load_steps`` of a static solve.
MAX_LOAD_STEPS = 10**6
#: Fastest steady rotation of ``modes.spin_rates`` [rad/s] (about 9.5 million rpm, beyond any
#: rotor of cables or rods): a faster one is a unit mistake whose centrifugal loads overflow.
MAX_SPIN_RATE = 1e6
#: What ``modes.spin_rates`` allows, for the messages that refuse a rate.
SPIN_RATES = (
    f"at most {MAX_SPIN_RATE:g} rad/s (about 9.5 million rpm; a faster spin is a unit mistake)"
)


@dataclass(frozen=True)
class DynamicOptions:
    """Options of :func:`integrate`; meaningless combinations are refused on construction.

    Attributes
    ----------
    t_end : float
        End time [s], finite and > 0.
    step : float
        Time step [s] (adaptive: the first), in (0, t_end]; a step that would pass an output
        time is shortened to end on it.  Fixed steps whose ``output_step`` is above ``step`` and
        not a whole number of steps are all ``output_step / ceil(output_step / step)``
        (:meth:`fitted`).
    rho_inf : float
        Spectral radius at infinity in [0, 1].
    adaptive : bool
        Adapt the step to ``rtol`` (local error relative to the model size).
    rtol : float
    strain_error : bool
        The local error estimate measures the flexible bodies' axial strain too (the tension
        of stiff lines), relative to each body's largest strain (at least 0.1 %), against
        ``rtol`` (TI.13 of ``docs/derivations/time-integration.md``).
    min_step, max_step : float, optional
        Step bounds (defaults ``step / 1024`` and ``max(output_step, step)``);
        ``min_step <= step`` and ``min_step <= max_step``.
    output_step : float, optional
        Interval of stored states (default: every ``step``), in (0, t_end]; the steps end on
        every output time and on ``t_end``, which is stored too.
    newton_tol : float
        Newton stops when ``max s_i |Δy_i| <= newton_tol * size`` (size = model extent; ``s_i``
        1 for positions, the element length for cables' gradients and beams' angles, at most 1:
        :mod:`rancf.solvers.increment_scale`).  A step whose iteration fails from the predictor
        ``y + h v + h² a/2`` is tried once more from ``y`` before the step is cut.
    max_newton : int
    newton : {"chord", "full", "modified"}
        ``"chord"`` (default): the exact tangent is assembled and factored at the first iteration
        of every step and reused for the step's further iterations (which then need the forces
        only) while the increments shrink fast, else the step starts again from ``y`` and,
        should the increments shrink slowly there too, goes on with full Newton
        (systems with contact: full Newton); the answer is that of ``"full"`` to far below the
        Newton tolerance.
        ``"full"``: the exact tangent is assembled and factored at every iteration.
        ``"modified"``: the factored Jacobian is reused across iterations and steps and refreshed
        from the exact tangent when the increments stop shrinking fast (the converged answer is
        the same to the Newton tolerance).

    Raises
    ------
    InputError
        Naming the ``solver.*`` key, e.g. ``step > t_end`` or ``min_step > step``.
    """

    t_end: float
    step: float
    rho_inf: float = 0.9
    adaptive: bool = False
    rtol: float = 1e-5
    strain_error: bool = False
    min_step: float | None = None
    max_step: float | None = None
    output_step: float | None = None
    newton_tol: float = 1e-10
    max_newton: int = 12
    newton: str = "chord"

    def __post_init__(self) -> None:
        def positive(name: str, value: object, upper: float = np.inf, what: str = "") -> None:
            if (
                isinstance(value, bool)
                or not isinstance(value, int | float)
                or not (np.isfinite(value) and 0 < value <= upper)
            ):
                raise InputError(f"solver.{name}", value, f"a finite number > 0{what}")

        positive("t_end", self.t_end)
        positive("step", self.step, self.t_end, f" and <= t_end = {self.t_end:g}")
        if not (0.0 <= self.rho_inf <= 1.0):
            raise InputError("solver.rho_inf", self.rho_inf, "a spectral radius in [0, 1]")
        positive("rtol", self.rtol)
        if self.output_step is not None:
            positive("output_step", self.output_step, self.t_end, f" and <= t_end = {self.t_end:g}")
        if self.min_step is not None:
            positive("min_step", self.min_step, self.step, f" and <= step = {self.step:g}")
        if self.max_step is not None:
            low = self.min_step if self.min_step is not None else 0.0
            positive("max_step", self.max_step)
            if self.max_step < low:
                raise InputError("solver.max_step", self.max_step, f">= min_step = {low:g}")
        positive("newton_tol", self.newton_tol)
        if isinstance(self.max_newton, bool) or not isinstance(self.max_newton, int):
            raise InputError("solver.max_newton", self.max_newton, "an integer >= 1")
        if not 1 <= self.max_newton <= MAX_NEWTON:
            raise InputError(
                "solver.max_newton", self.max_newton, f"an integer in [1, {MAX_NEWTON}]"
            )
        if self.newton not in ("full", "chord", "modified"):
            raise InputError("solver.newton", self.newton, 'one of "full", "chord", "modified"')
        steps = self.t_end / self.step
        if not self.adaptive and steps > MAX_STEPS:
            raise InputError(
                "solver.t_end / solver.step",
                steps,
                f"at most {MAX_STEPS:.0e} time steps (t_end = {self.t_end:g} s, step = "
                f"{self.step:g} s); raise solver.step or shorten solver.t_end",
            )
        out_dt = self.output_step if self.output_step is not None else self.step
        outputs = self.t_end / out_dt
        if outputs > MAX_STEPS:
            raise InputError(
                "solver.t_end / solver.output_step",
                outputs,
                f"at most {MAX_STEPS:.0e} stored states (t_end = {self.t_end:g} s, output "
                f"step = {out_dt:g} s); raise solver.output_step or shorten solver.t_end",
            )

    @property
    def n_outputs(self) -> int:
        """Number of stored states, the initial one included."""
        out_dt = self.output_step if self.output_step is not None else self.step
        n_grid = int(np.floor(self.t_end / out_dt + 1e-9))
        return 1 + n_grid + (1 if out_dt * n_grid < self.t_end * (1 - 1e-12) else 0)

    @property
    def steps_per_output(self) -> int | None:
        """Fixed steps whose ``output_step`` is above ``step`` and not a whole number of steps
        (within 1e-9): the steps an output interval is split into, ``ceil(output_step /
        step)``; else None."""
        out = self.output_step
        if self.adaptive or out is None:
            return None
        k = out / self.step
        if k <= 1.0 + 1e-9 or abs(k - round(k)) <= 1e-9 * k:
            return None
        return math.ceil(k)

    def fitted(self) -> DynamicOptions:
        """The options of the steps taken: where :attr:`steps_per_output` is not None, every
        step is ``output_step / steps_per_output`` (the largest step below ``step`` that
        divides the interval: as many steps as cutting each interval's last step short, all
        of one size); else these options."""
        n, out = self.steps_per_output, self.output_step
        if n is None or out is None:  # (n is None without an output step)
            return self
        h = out / n
        low = None if self.min_step is None else min(self.min_step, h)
        return replace(self, step=h, min_step=low)
