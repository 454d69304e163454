"""The stepper of a dynamic run: it holds the state ``(t, y, v, a, w, λ)`` and takes a step, or
a block of fixed steps in the compiled core, from it.  Its contract (as SciPy's
``OdeSolver.step``): a step either is accepted (the state moves to ``t + h``) or rejected (the
state stays), and says its local error estimate, the step to try next and, where the run
cannot go on, why.  The loop of :func:`rancf.solvers.dynamic.integrate` chooses the steps'
ends (the output times), stores the outputs and counts; fixed and adaptive steps go through
the same stepper (``docs/derivations/time-integration.md`` sec. 3).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.options import DynamicOptions
from rancf.solvers.generalized_alpha import GeneralizedAlpha
from rancf.system.limits import first_outside

__all__ = ["Block", "Step", "Stepper", "failure_message"]


def failure_message(t: float, min_step: float, error: float = 0.0) -> str:
    """The message of a run that cannot step on from ``t`` even at ``min_step``: Newton's
    iteration failed, or (``error`` > 0) the local error estimate stayed above the tolerance."""
    what = (
        f"the local error estimate stayed {error:.3g} times the tolerance"
        if error > 0.0
        else "Newton iteration did not converge"
    )
    return (
        f"{what} at t = {t:.6g} s even with the minimum "
        f"step {min_step:.3g} s; results up to t = {t:.6g} s are kept"
    )


@dataclass
class Step:
    """What :meth:`Stepper.step` did.

    Attributes
    ----------
    accepted : bool
        The state moved to ``t + h``.
    h : float
        The step tried [s].
    error : float
        Its local error estimate relative to the tolerance (0 where Newton failed).
    h_next : float
        The step to try next [s].
    rejected : bool
        Not accepted, to be retried with ``h_next`` (counted as a rejected step).
    failure : str or None
        The run cannot go on (the state stays where it was): why.
    alpha : ndarray or None
        Systems with contact: the step's generalized-α point ``(y_f, v_f)``.
    """

    accepted: bool
    h: float
    error: float
    h_next: float
    rejected: bool = False
    failure: str | None = None
    alpha: NDArray | None = None


@dataclass
class Block:
    """What :meth:`Stepper.block` did: ``done`` fixed steps, ``stored`` outputs (rows of
    ``oy, ov, oe, ol, oa``: :meth:`GeneralizedAlpha.run_steps`), all converged or not, the
    largest relative error estimate and the time at its step's end; ``left``: a bounded
    coordinate left its range, and the state is back at the block's start."""

    done: int
    converged: bool
    stored: int
    rows: tuple
    error: float
    t_error: float
    left: bool = False


class Stepper:
    """Generalized-α steps from a state (module docstring).

    Parameters
    ----------
    integ : GeneralizedAlpha
    options : DynamicOptions
        Fitted options (``rtol``, ``adaptive``, ``step``).
    state : tuple
        ``(t, y, v, a, w, lam)`` to start from (the arrays are taken, not copied).
    h : float
        The step to try first.
    min_step, max_step : float
        Adaptive steps' bounds; below ``min_step`` a rejected step ends the run.
    check : callable or None
        Bounded coordinates (:func:`rancf.system.limits.state_limits`): ``check(t, y, λ)`` says
        why a state is out of range, or None.
    """

    def __init__(
        self,
        integ: GeneralizedAlpha,
        options: DynamicOptions,
        state: tuple,
        h: float,
        min_step: float,
        max_step: float,
        check: Callable[..., Any] | None,
    ) -> None:
        self.integ = integ
        self.options = options
        self.t, self.y, self.v, self.a, self.w, self.lam = state
        self.h = h
        self.min_step, self.max_step = min_step, max_step
        self.check = check
        self.contact = integ.system.has_contact

    def copy_state(self) -> tuple:
        """``(y, v, a, w, λ)``, copied."""
        return (self.y.copy(), self.v.copy(), self.a.copy(), self.w.copy(), self.lam.copy())

    def _rejected(self, h_try: float, error: float, factor: float, by_error: bool) -> Step:
        self.h = h_try * factor
        failure = None
        if self.h < self.min_step:
            failure = failure_message(self.t, self.min_step, error if by_error else 0.0)
        return Step(False, h_try, error, self.h, rejected=True, failure=failure)

    def step(self, h_try: float) -> Step:
        """One step of length ``h_try`` from the state: accepted (adaptive: where the estimate
        is within the tolerance) or rejected, with the step to try next (a quarter where Newton
        failed; adaptive: ``h · clamp(0.9 e^(-1/3), 0.2, 2)``, at most ``max_step``)."""
        o, t = self.options, self.t
        ahead = None if self.check is None else self.check(t + h_try, self.y, self.lam)
        if ahead is not None:  # a length law's range at the step's end
            return Step(False, h_try, 0.0, h_try, failure=ahead)
        lam_try = self.lam.copy()
        ok, y1, v1, a1, w1, e1 = self.integ.step(self.y, self.v, self.a, self.w, t, h_try, lam_try)
        err = self.integ.relative_error(e1, o.rtol)
        if not ok:
            return self._rejected(h_try, err, 0.25, False)
        if o.adaptive and err > 1.0:
            return self._rejected(h_try, err, max(0.2, 0.9 * err ** (-1.0 / 3.0)), True)
        outside = None if self.check is None else self.check(t + h_try, y1, lam_try)
        if outside is not None:  # the state stays at the step before
            return Step(False, h_try, err, self.h, failure=outside)
        alpha = self.integ.alpha_point(self.y, self.v, y1, v1) if self.contact else None
        self.y, self.v, self.a, self.w, self.lam = y1, v1, a1, w1, lam_try
        self.t = t + h_try
        # rods: triads follow the step, twist rates the spin
        self.integ.system.rereference(self.y, self.v, self.a, self.w)
        if o.adaptive:
            self.h = min(self.max_step, h_try * min(2.0, 0.9 * max(err, 1e-10) ** (-1.0 / 3.0)))
        else:
            self.h = o.step
        return Step(True, h_try, err, self.h, alpha=alpha)

    def block(
        self,
        n_steps: int,
        per_out: int,
        within: int,
        k_out: int,
        out_time: Callable[[int], float],
        energies: bool,
        call_seconds: float,
    ) -> Block:
        """Up to ``n_steps`` fixed steps of ``options.step`` in the compiled core, an output
        every ``per_out`` (the interval's first ``within`` taken before; output ``k_out`` next,
        at ``out_time(k_out)``); the state moves in place.  A block that leaves a bounded
        coordinate's range is undone (``left``).  The time ``t`` is the loop's to set (from
        the output grid)."""
        o = self.options
        before = None if self.check is None else self.copy_state()
        done, st, _, stored, oy, ov, oe, ol, oa, err, t_err = self.integ.run_steps(
            self.y,
            self.v,
            self.a,
            self.w,
            self.t,
            o.step,
            n_steps,
            per_out,
            within,
            call_seconds,  # the step times do not depend on where a call ends
            self.lam,
            o.output_step if o.output_step is not None else o.step,
            k_out,
            energies=energies,
        )
        rows = (oy, ov, oe, ol, oa)
        error = self.integ.relative_error(err, o.rtol)
        if before is not None and self._left_range(k_out, stored, out_time, oy, ol):
            self.y, self.v, self.a, self.w, self.lam = before  # to be stepped one by one
            return Block(done, st == 1, stored, rows, error, t_err, left=True)
        return Block(done, st == 1, stored, rows, error, t_err)

    def _left_range(
        self, k0: int, stored: int, out_time: Callable[[int], float], oy: NDArray, ol: NDArray
    ) -> bool:
        """Whether a block left a bounded coordinate's range: at one of its ``stored`` outputs
        (from the ``k0``-th) or at its end state (a step past the last output)."""
        assert self.check is not None
        ts = np.array([out_time(k0 + i) for i in range(stored)])
        if first_outside(self.check, ts, oy[:stored], None if ol is None else ol[:stored]) >= 0:
            return True
        return self.check(self.t, self.y, self.lam) is not None

    def after_failed_block(self) -> Step:
        """A block's step that failed (the state is at that step's start, time ``t``): the
        step is to be retried with a quarter of ``options.step``, unless the state's range
        ends there."""
        o = self.options
        ahead = None if self.check is None else self.check(self.t + o.step, self.y, self.lam)
        if ahead is not None:  # left a length law's range: no retry, the state stays here
            return Step(False, o.step, 0.0, o.step, failure=ahead)
        return self._rejected(o.step, 0.0, 0.25, False)
