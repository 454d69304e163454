"""Implicit generalized-α time integration (Chung & Hulbert 1993) in the form of Arnold & Brüls
(2007), with Newton on the exact tangent (``docs/derivations/time-integration.md``).

For ``M ÿ + c M ẏ + f_int(y) = f_ext(t)`` and spectral radius at infinity ``ρ∞ ∈ [0, 1]``:

    α_m = (2ρ∞ - 1)/(ρ∞ + 1),  α_f = ρ∞/(ρ∞ + 1),  γ = ½ - α_m + α_f,  β = ¼ (1 - α_m + α_f)²

The balance holds at ``t_{n+1}``, ``M a_{n+1} + c M v_{n+1} + f_int(y_{n+1}) = f_ext(t_{n+1})``;
the α-blend acts on the accelerations alone, through the algorithmic accelerations ``w``,
``(1 - α_m) w_{n+1} + α_m w_n = (1 - α_f) a_{n+1} + α_f a_n``, and the Newmark updates
``y_{n+1} = y_n + h v_n + h² ((½ - β) w_n + β w_{n+1})``,
``v_{n+1} = v_n + h ((1 - γ) w_n + γ w_{n+1})``.  Forces are evaluated at real states only: a
blend of the absolute nodal coordinates of a turning body lies inside its circle and would
stretch it (the chord error).  Newton solves for ``y_{n+1}`` with Jacobian
``[(1-α_m)/((1-α_f) β h²) + c γ/(β h)] M + K_T(y_{n+1})``.  The scheme is second order with
spectral radius ``ρ∞`` at infinity; ``ρ∞ = 1`` is the trapezoidal rule (no numerical
dissipation).

Step control: fixed steps, or adaptive steps from the local error estimate
``e = h² |β - γ/2 + 1/12| max_i s_i |w_{n+1,i} - w_{n,i}|`` (after Zienkiewicz & Xie 1991), which
fixed-step runs record too (the largest, its time and step: :class:`DynamicResult`).  A step
whose Newton iteration fails is retried with a quarter of the step; below ``min_step`` the run
stops with status ``FAILED`` and keeps everything computed up to then.  So does a step that
takes a bounded coordinate out of its range (:mod:`rancf.system.limits`: a driven drum's
length, a sliding guide's place on the rope): the run stops at the step before, storing
nothing from it on.

The steps are the :class:`rancf.solvers.stepper.Stepper`'s (the state, one step or a block of
fixed steps in the compiled core: accepted or rejected, with the error estimate and the step
to take next); the loop here chooses where steps end (the output times), stores the outputs,
counts and reports (:class:`_Loop`, :class:`_Outputs`).
"""

from __future__ import annotations

import time
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.options import DynamicOptions
from rancf.solvers.generalized_alpha import GeneralizedAlpha
from rancf.solvers.output import MemorySink, OutputSink
from rancf.solvers.result import DynamicResult, DynamicStatus
from rancf.solvers.state import COUNTERS, DynamicState, take_up, triads_of
from rancf.solvers.stepper import Stepper
from rancf.system import System, as_system
from rancf.system.limits import state_limits
from rancf.system.sliding import start_multipliers

__all__ = ["DynamicOptions", "DynamicStatus", "DynamicResult", "GeneralizedAlpha", "integrate"]


#: Wall time [s] after which the compiled fixed-step loop hands back to Python, which polls the
#: stop flag (Ctrl-C, SIGTERM): a run stops within about this time whatever its step.  Only with
#: a stop flag or an output callback: where a call ends shifts the step times by round-off, so a
#: run without them ends its calls at fixed steps and gives the same answer at any load.
CALL_SECONDS = 0.1

#: Wall time [s] a call of the compiled loop is sized for, from the calls before (at least 1 % of
#: the run's outputs, as the first): each call costs about 25 µs in Python, and 100 calls of 10
#: steps of an 8-element pendulum took 15 % of its run; longer calls hand an output worker its
#: rows later (the last block, which the loop waits for, grows).  Where calls end does not
#: change the steps (their times are counted from the outputs), so the sizes may follow the
#: machine.
CALL_TARGET_SECONDS = 0.002


class _Outputs:
    """Where a run's outputs go (a sink, or memory) and the result they make: the rows stored,
    the last one kept for snapshots of a streamed run."""

    def __init__(self, system: System, sink: OutputSink | None, out_time: Callable) -> None:
        self.system = system
        self.memory = MemorySink() if sink is None else None
        self.sink: OutputSink = self.memory if self.memory is not None else sink  # type: ignore[assignment]
        self.out_time = out_time
        self.directors = system.nodal_directors  # rods: of the state the triads were carried to
        self.mult = system.m > 0  # store the joints' multipliers
        # a sink that derives the energies from the stored rows (beside the loop): none here
        self.energies = not getattr(self.sink, "derives_energies", False)
        self.last: list = []  # the last row
        self.last_y: list = []  # the last row's y, v (its energies where the sink derives them)
        empty = np.empty(0)
        self.result = DynamicResult(
            empty, empty, empty, empty, empty, empty, DynamicStatus.COMPLETED, ""
        )

    def store(
        self, tt: float, yy: NDArray, vv: NDArray, lam: NDArray, alpha: NDArray | None
    ) -> None:
        """One output row at time ``tt``."""
        system = self.system
        e = np.array(system.energies(yy, vv, tt)) if self.energies else None
        self.last_y[:] = [yy.copy(), vv.copy()]
        m1 = self.directors(yy)
        ll = lam.copy() if self.mult else None
        row = (tt, system.q_from_y(yy), system.q_from_y(vv), e, m1, ll, alpha)
        self.sink.append(tt, row[1], row[2], e, directors=m1, lam=ll, alpha=alpha)
        self.last[:] = [row]
        self.result.n_outputs += 1

    def store_block(self, k0: int, rows: tuple, stored: int) -> None:
        """Outputs ``k0, k0 + 1, ...`` from the core's loop (the first ``stored`` of ``rows``,
        :class:`rancf.solvers.stepper.Block`), passed on as one block (rods: one output a
        block, whose state is the one the triads were carried to)."""
        oy, ov, ol = (x[:stored] for x in (rows[0], rows[1], rows[3]))
        oe, oa = (None if x is None else x[:stored] for x in (rows[2], rows[4]))
        ts = np.array([self.out_time(k0 + i) for i in range(len(oy))])
        qs, vs = self.system.q_from_y(oy), self.system.q_from_y(ov)
        m1 = self.directors(oy[-1])
        ll = ol if self.mult else None
        self.sink.append_block(
            ts, qs, vs, oe, directors=None if m1 is None else m1[None], lam=ll, alpha=oa
        )
        self.last_y[:] = [oy[-1].copy(), ov[-1].copy()]
        self.last[:] = [
            (
                float(ts[-1]),
                qs[-1],
                vs[-1],
                None if oe is None else np.array(oe[-1]),
                m1,
                None if ll is None else ll[-1],
                None if oa is None else oa[-1],
            )
        ]
        self.result.n_outputs += len(oy)

    def _history(self) -> tuple[NDArray, NDArray, NDArray, NDArray]:
        """``(t, q, v, energies)`` of the result, and its other streams set."""
        result, system = self.result, self.system
        if not self.last:  # a resumed run with nothing stored yet
            result.directors = result.lam = result.alpha = None
            return np.empty(0), np.empty((0, system.n)), np.empty((0, system.n)), np.empty((0, 3))
        if self.memory is not None:
            ts, qs, vs, es = self.memory.arrays()
            result.directors = self.memory.stream("directors")
            result.lam = self.memory.stream("lam")
            result.alpha = self.memory.stream("alpha")
            return ts, qs, vs, es
        tt, qq, vv, ee, m1, ll, aa = self.last[0]
        if ee is None:  # derived by the sink: the last row's here, as the sink does
            ee = np.empty((1, 3))
            system.core.energies_rows(np.array([tt]), *self.last_y, ee)
            self.last[0] = (tt, qq, vv, ee[0], m1, ll, aa)
        result.directors = None if m1 is None else m1[None]
        result.lam = None if ll is None else ll[None]
        result.alpha = None if aa is None else aa[None]
        return np.array([tt]), qq[None], vv[None], np.reshape(ee, (1, 3))

    def snapshot(self, loop: _Loop, status: DynamicStatus, message: str) -> DynamicResult:
        """The result so far, with the state the run stands at."""
        result, st = self.result, loop.stepper
        ts, qs, vs, es = self._history()
        result.t, result.q, result.v = ts, qs, vs
        result.kinetic, result.strain, result.gravity = es[:, 0], es[:, 1], es[:, 2]
        result.status, result.message = status, message
        result.n_newton = int(loop.base["n_newton"]) + loop.integ.n_newton
        result.n_factorizations = loop.integ.n_factorizations
        result.wall_time = loop.base["wall_time"] + time.perf_counter() - loop.started
        result.state = DynamicState(
            st.t,
            st.y.copy(),
            st.v.copy(),
            st.a.copy(),
            st.w.copy(),
            st.lam.copy(),
            st.h,
            min(loop.k_out, loop.n_grid),
            loop.within,
            triads_of(self.system),
            loop.integ.memory(),
            {k: getattr(result, k) for k in COUNTERS},
            loop.options.t_end,
        )
        return result


class _Loop:
    """The time loop of :func:`integrate`: it chooses the steps' ends (the output grid), has
    the :class:`Stepper` take them (blocks of fixed steps in the compiled core where it can),
    stores the outputs, counts, reports and polls the stop flag."""

    def __init__(
        self,
        options: DynamicOptions,
        stepper: Stepper,
        outputs: _Outputs,
        grid: tuple[float, int, int],
        position: tuple[int, int],
        base: dict,
        on_output: Callable[[float, Callable[[], DynamicResult]], None] | None,
        should_stop: Callable[[], bool] | None,
    ) -> None:
        o = self.options = options
        self.stepper, self.integ, self.outputs = stepper, stepper.integ, outputs
        self.result = outputs.result
        self.out_dt, self.n_grid, self.n_out = grid
        self.k_out, self.within = position
        self.base, self.on_output, self.should_stop = base, on_output, should_stop
        self.out_time = outputs.out_time  # the i-th output time after the initial state
        self.started = time.perf_counter()
        system = self.integ.system
        # compiled fixed-step loop: outputs on a grid that is a whole number of steps
        ratio = self.out_dt / o.step
        self.per_out = int(round(ratio))
        fast = not o.adaptive and self.per_out >= 1 and abs(ratio - self.per_out) < 1e-9
        # outputs per compiled call: first ~1 % of the run, then sized to CALL_TARGET_SECONDS;
        # at most ~16 MB of stored states per array
        self.cap = max(1, (1 << 21) // system.n)
        self.chunk_out = self.least = int(np.clip(self.n_grid // 100, 1, self.cap))
        if any(b.family.has_triads for b in system.flex):  # the triads at a call's end are
            self.chunk_out = self.least = self.cap = 1  # those of its one stored state
            fast = fast and stepper.check is None  # (a rod's triads cannot step back)
        self.fast = fast
        self.slow_until = -1.0  # the compiled loop left a coordinate's range: steps until then

    def _notify(self, tt: float) -> None:
        if self.on_output is not None:
            msg = f"running, t = {tt:g} s"
            self.on_output(tt, lambda: self.outputs.snapshot(self, DynamicStatus.INTERRUPTED, msg))

    def _stopped(self) -> tuple[DynamicStatus, str] | None:
        if self.should_stop is not None and self.should_stop():
            return DynamicStatus.INTERRUPTED, f"interrupted at t = {self.stepper.t:.6g} s"
        return None

    def run(self) -> tuple[DynamicStatus, str]:
        """Step to the end (or a failure, or the stop flag): the run's status and message."""
        o, st = self.options, self.stepper
        while self.k_out < self.n_out:
            last_out = self.out_time(self.k_out - 1) if self.k_out else 0.0
            on_grid = self.within > 0 or abs(st.t - last_out) <= 1e-12 * max(1.0, st.t)
            if (
                self.fast
                and st.h == o.step
                and self.k_out < self.n_grid
                and on_grid
                and st.t >= self.slow_until
            ):
                end = self._block()
            else:
                end = self._single(self.out_time(self.k_out))
            if end is not None:
                return end
        return DynamicStatus.COMPLETED, f"reached t_end = {o.t_end:g} s"

    def _block(self) -> tuple[DynamicStatus, str] | None:
        """A block of fixed steps in the compiled core, sized to the wall clock."""
        o, st, result = self.options, self.stepper, self.result
        n_chunk = min(self.chunk_out, self.n_grid - self.k_out)
        called = time.perf_counter()
        b = st.block(
            n_chunk * self.per_out - self.within,
            self.per_out,
            self.within,
            self.k_out,
            self.out_time,
            self.outputs.energies,
            CALL_SECONDS,
        )
        if b.left:  # again step by step, to the step that leaves it
            self.slow_until = self.out_time(min(self.k_out + n_chunk, self.n_grid) - 1)
            return None
        result.took(o.step, b.done)
        result.note_error(b.error, b.t_error, o.step)
        took = time.perf_counter() - called
        if b.stored == n_chunk and took > 0.0:  # a whole call: the next sized to the target
            grown = b.stored * CALL_TARGET_SECONDS / took
            lo, hi = max(self.least, self.chunk_out // 4), min(self.cap, 4 * self.chunk_out)
            self.chunk_out = int(np.clip(grown, lo, hi))
        if b.stored:
            self.outputs.store_block(self.k_out, b.rows, b.stored)
        self.k_out += b.stored
        self.within = self.within + b.done - b.stored * self.per_out
        last_out = self.out_time(self.k_out - 1) if self.k_out else 0.0
        st.t = float(last_out) + self.within * o.step if self.within else float(last_out)
        end = None  # a failed step: rejected before the outputs are announced, so that a
        if not b.converged:  # snapshot (a checkpoint) there holds the rejection and its cost
            step = st.after_failed_block()
            if not step.rejected:  # left a length law's range: the state stays here
                end = DynamicStatus.FAILED, str(step.failure)
            else:  # the steps to the next output are taken one by one, smaller
                self.within = 0
                result.n_rejected += 1
                end = None if step.failure is None else (DynamicStatus.FAILED, step.failure)
        if b.stored:
            self._notify(float(last_out))
        return end if end is not None else self._stopped()

    def _single(self, target: float) -> tuple[DynamicStatus, str] | None:
        """One step through Python (adaptive, or toward an output off the fixed grid)."""
        st, result = self.stepper, self.result
        h_try = min(st.h, target - st.t)
        if target - (st.t + h_try) < 1e-12 * max(1.0, target):
            h_try = target - st.t
        step = st.step(h_try)
        if step.rejected:
            result.n_rejected += 1
            return None if step.failure is None else (DynamicStatus.FAILED, step.failure)
        if not step.accepted:
            return DynamicStatus.FAILED, str(step.failure)
        result.took(h_try)
        result.note_error(step.error, st.t, h_try)
        if abs(st.t - target) <= 1e-12 * max(1.0, target):
            st.t = float(target)
            self.outputs.store(st.t, st.y, st.v, st.lam, step.alpha)
            self.k_out += 1
            self._notify(st.t)
        return self._stopped()


def integrate(
    model: Model | System,
    options: DynamicOptions,
    on_output: Callable[[float, Callable[[], DynamicResult]], None] | None = None,
    should_stop: Callable[[], bool] | None = None,
    sink: OutputSink | None = None,
    on_start: Callable[[], None] | None = None,
    initial: NDArray | None = None,
    start: DynamicState | None = None,
) -> DynamicResult:
    """Integrate the model from its reference configuration (or ``initial``) and initial
    velocities.

    Parameters
    ----------
    model : Model or System
        A model is a one-body system.
    options : DynamicOptions
    on_output : callable, optional
        Called as ``on_output(t, snapshot)`` after every stored output; ``snapshot()`` builds the
        result so far (call it only now and then: without a sink it copies the history).
    should_stop : callable, optional
        Polled after every step (and every :data:`CALL_SECONDS` of the compiled loop); returning
        True ends the run with status ``INTERRUPTED``.
    sink : OutputSink, optional
        Receives every stored state (e.g. streamed to disk); the result then holds only the
        last one, so memory does not grow with ``t_end``.  Default: kept in memory.
    on_start : callable, optional
        Called once, right before the time loop (after the initial acceleration).
    initial : ndarray, optional
        Model coordinates to start from instead of the reference, e.g. a static equilibrium
        (:func:`rancf.solvers.static.solve_static`'s ``y``; rods: with the nodal triads the
        static solve left, which are then kept).  The velocities are the model's initial
        velocities either way.
    start : DynamicState, optional
        Go on from where an earlier run of the same system stood (its result's ``state``, or a
        run folder's checkpoint): the same steps as if it had never stopped, to
        ``options.t_end`` (which may lie beyond the earlier run's).  The result holds the
        outputs after ``start`` and counts the whole run (steps, iterations, wall time).

    Returns
    -------
    DynamicResult
        Never raises on non-convergence: the status says ``FAILED`` and the message names the
        time reached.  ``wall_time`` is the time loop's, with the ``sink``'s ``flush`` (every
        stored row derived) at its end.  ``state`` is where the run stands (also in every
        ``snapshot()``).
    """
    o = options.fitted()  # fixed steps that divide the output interval
    system = as_system(model)
    if start is not None and initial is not None:
        raise ValueError("integrate: give initial (coordinates) or start (a state), not both")
    if initial is None and start is None:
        system.reset_triads()
    integ = GeneralizedAlpha(
        system, o.rho_inf, o.newton_tol, o.max_newton, o.newton, o.rtol, o.strain_error
    )
    out_dt = o.output_step if o.output_step is not None else o.step
    n_grid = int(np.floor(o.t_end / out_dt + 1e-9))
    grid = (out_dt, n_grid, o.n_outputs - 1)
    outputs = _Outputs(system, sink, lambda i: out_dt * (i + 1) if i < n_grid else o.t_end)
    base = {"n_newton": 0, "wall_time": 0.0}
    if start is None:
        y = system.y0.copy() if initial is None else np.array(initial, dtype=float)
        v = system.v0.copy()
        integ.prescribe(0.0, y, v)  # moving supports at t = 0
        lam = start_multipliers(system, None if initial is None else y)
        a = integ.initial_acceleration(y, v, 0.0, lam)
        w = a.copy()  # the algorithmic accelerations start at the consistent ones
        outputs.store(0.0, y, v, lam, np.concatenate([y, v]) if system.has_contact else None)
        state, h, position = (0.0, y, v, a, w, lam), o.step, (0, 0)
    else:
        t, y, v, a, w, lam, h, k_out, within = take_up(system, integ, start, outputs.result, base)
        state, position = (t, y, v, a, w, lam), (k_out, within)
    min_step = o.min_step if o.min_step is not None else o.step / 1024.0
    max_step = o.max_step if o.max_step is not None else max(out_dt, o.step)
    stepper = Stepper(integ, o, state, h, min_step, max_step, state_limits(system))
    if on_start is not None:
        on_start()
    loop = _Loop(o, stepper, outputs, grid, position, base, on_output, should_stop)
    status, message = loop.run()
    settle = getattr(outputs.sink, "flush", None)  # rows a sink derives beside the loop or
    if settle is not None:  # holds in a buffer: all of them derived and appended, counted in
        settle()  # the loop's time
    return outputs.snapshot(loop, status, message)
