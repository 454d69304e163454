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
from rancf.system import System, as_system
from rancf.system.limits import first_outside, state_limits
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


def _left_range(
    check: Callable,
    k0: int,
    stored: int,
    out_time: Callable,
    oy: NDArray,
    ol: NDArray | None,
    t: float,
    y: NDArray,
    lam: NDArray,
) -> bool:
    """Whether a call of the compiled loop left a bounded coordinate's range: at one of its
    ``stored`` outputs (from the ``k0``-th) or at its end state ``(t, y, λ)`` (a step past the
    last output)."""
    ts = np.array([out_time(k0 + i) for i in range(stored)])
    if first_outside(check, ts, oy[:stored], None if ol is None else ol[:stored]) >= 0:
        return True
    return check(t, y, lam) is not None


def _failure_message(t: float, min_step: float) -> str:
    return (
        f"Newton iteration did not converge at t = {t:.6g} s even with the minimum "
        f"step {min_step:.3g} s; results up to t = {t:.6g} s are kept"
    )


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
    integ = GeneralizedAlpha(system, o.rho_inf, o.newton_tol, o.max_newton, o.newton, o.rtol)
    out_dt = o.output_step if o.output_step is not None else o.step
    n_out = o.n_outputs - 1
    n_grid = int(np.floor(o.t_end / out_dt + 1e-9))

    def out_time(i: int) -> float:  # the i-th output after the initial state (0-based)
        return out_dt * (i + 1) if i < n_grid else o.t_end

    min_step = o.min_step if o.min_step is not None else o.step / 1024.0
    max_step = o.max_step if o.max_step is not None else max(out_dt, o.step)
    memory = MemorySink() if sink is None else None
    target_sink: OutputSink = memory if memory is not None else sink  # type: ignore[assignment]
    last: list = []

    rod = any(b.element == "rod" for b in system.flex)
    directors = system.nodal_directors  # rods: of the state the triads were last carried to
    mult = system.m > 0  # store the joints' multipliers
    # a sink that derives the energies from the stored rows (beside the loop): none here
    loop_energies = not getattr(target_sink, "derives_energies", False)

    last_y: list = []  # the last row's y, v (its energies where the sink derives them)

    def store(tt: float, yy: NDArray, vv: NDArray, alpha: NDArray | None) -> None:
        e = np.array(system.energies(yy, vv, tt)) if loop_energies else None
        last_y[:] = [yy.copy(), vv.copy()]
        m1 = directors(yy)
        ll = lam.copy() if mult else None
        row = (tt, system.q_from_y(yy), system.q_from_y(vv), e, m1, ll, alpha)
        target_sink.append(tt, row[1], row[2], e, directors=m1, lam=ll, alpha=alpha)
        last[:] = [row]
        result.n_outputs += 1

    def store_block(
        k0: int, oy: NDArray, ov: NDArray, oe: NDArray | None, ol: NDArray, oa: NDArray | None
    ) -> None:
        """Outputs ``k0, k0 + 1, ...`` from the core's loop, passed on as one block (rods: one
        output a block, whose state is the one the triads were carried to)."""
        ts = np.array([out_time(k0 + i) for i in range(len(oy))])
        qs, vs = system.q_from_y(oy), system.q_from_y(ov)
        m1 = directors(oy[-1])
        ll = ol if mult else None
        target_sink.append_block(
            ts, qs, vs, oe, directors=None if m1 is None else m1[None], lam=ll, alpha=oa
        )
        last_y[:] = [oy[-1].copy(), ov[-1].copy()]
        last[:] = [
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
        result.n_outputs += len(oy)

    empty = np.empty(0)
    result = DynamicResult(empty, empty, empty, empty, empty, empty, DynamicStatus.COMPLETED, "")
    contact = system.has_contact
    h, k_out, within, base = o.step, 0, 0, {"n_newton": 0, "wall_time": 0.0}
    if start is None:
        y = system.y0.copy() if initial is None else np.array(initial, dtype=float)
        v = system.v0.copy()
        t = 0.0
        integ.prescribe(0.0, y, v)  # moving supports at t = 0
        lam = start_multipliers(system, None if initial is None else y)
        a = integ.initial_acceleration(y, v, t, lam)
        w = a.copy()  # the algorithmic accelerations start at the consistent ones
        store(0.0, y, v, np.concatenate([y, v]) if contact else None)
    else:
        t, y, v, a, w, lam, h, k_out, within = take_up(system, integ, start, result, base)
    if on_start is not None:
        on_start()
    started = time.perf_counter()

    def snapshot(status: DynamicStatus, message: str) -> DynamicResult:
        if not last:  # a resumed run with nothing stored yet
            ts, qs, vs, es = empty, np.empty((0, system.n)), np.empty((0, system.n)), empty
            es = np.empty((0, 3))
            result.directors = result.lam = result.alpha = None
        elif memory is not None:
            ts, qs, vs, es = memory.arrays()
            result.directors = memory.stream("directors")
            result.lam = memory.stream("lam")
            result.alpha = memory.stream("alpha")
        else:
            tt, qq, vv, ee, m1, ll, aa = last[0]
            if ee is None:  # derived by the sink: the last row's here, as the sink does
                ee = np.empty((1, 3))
                system.core.energies_rows(np.array([tt]), *last_y, ee)
                last[0] = (tt, qq, vv, ee[0], m1, ll, aa)
            ts, qs, vs, es = np.array([tt]), qq[None], vv[None], np.reshape(ee, (1, 3))
            result.directors = None if m1 is None else m1[None]
            result.lam = None if ll is None else ll[None]
            result.alpha = None if aa is None else aa[None]
        result.t, result.q, result.v = ts, qs, vs
        result.kinetic, result.strain, result.gravity = es[:, 0], es[:, 1], es[:, 2]
        result.status, result.message = status, message
        result.n_newton = int(base["n_newton"]) + integ.n_newton
        result.n_factorizations = integ.n_factorizations
        result.wall_time = base["wall_time"] + time.perf_counter() - started
        result.state = DynamicState(
            t,
            y.copy(),
            v.copy(),
            a.copy(),
            w.copy(),
            lam.copy(),
            h,
            min(k_out, n_grid),
            within,
            triads_of(system),
            integ.memory(),
            {k: getattr(result, k) for k in COUNTERS},
            o.t_end,
        )
        return result

    status, message = DynamicStatus.COMPLETED, f"reached t_end = {o.t_end:g} s"
    # compiled fixed-step loop: outputs on a grid that is a whole number of steps
    ratio = out_dt / o.step
    per_out = int(round(ratio))
    fast = not o.adaptive and per_out >= 1 and abs(ratio - per_out) < 1e-9
    # outputs per compiled call: first ~1 % of the run, then sized to CALL_TARGET_SECONDS; at
    # most ~16 MB of stored states per array
    cap = max(1, (1 << 21) // system.n)
    chunk_out = least = int(np.clip(n_grid // 100, 1, cap))
    if rod:  # the triads at a call's end are those of its one stored state
        chunk_out = least = cap = 1

    check = state_limits(system)  # bounded coordinates: each step checked
    fast = fast and not (check is not None and rod)  # (a rod's triads cannot step back)
    slow_until = -1.0  # the compiled loop left a coordinate's range: steps here until then

    def notify(tt: float) -> None:
        if on_output is not None:
            msg = f"running, t = {tt:g} s"
            on_output(tt, lambda: snapshot(DynamicStatus.INTERRUPTED, msg))

    while k_out < n_out:
        target = out_time(k_out)
        last_out = out_time(k_out - 1) if k_out else 0.0
        on_grid = within > 0 or abs(t - last_out) <= 1e-12 * max(1.0, t)
        if fast and h == o.step and k_out < n_grid and on_grid and t >= slow_until:
            n_chunk = min(chunk_out, n_grid - k_out)
            before = None if check is None else (y.copy(), v.copy(), a.copy(), w.copy(), lam.copy())
            called = time.perf_counter()
            done, st, iters, stored, oy, ov, oe, ol, oa, err, t_err = integ.run_steps(
                y,
                v,
                a,
                w,
                t,
                o.step,
                n_chunk * per_out - within,
                per_out,
                within,
                CALL_SECONDS,  # the step times do not depend on where a call ends
                lam,
                out_dt,
                k_out,
                energies=loop_energies,
            )
            left = check is not None and _left_range(
                check, k_out, stored, out_time, oy, ol, t, y, lam
            )
            if left and before is not None:
                y, v, a, w, lam = before  # again step by step, to the step that leaves it
                slow_until = out_time(min(k_out + n_chunk, n_grid) - 1)
                continue
            result.took(o.step, done)
            result.note_error(integ.relative_error(err, o.rtol), t_err, o.step)
            took = time.perf_counter() - called
            if stored == n_chunk and took > 0.0:  # a whole call: the next sized to the target
                grown = stored * CALL_TARGET_SECONDS / took
                chunk_out = int(np.clip(grown, max(least, chunk_out // 4), min(cap, 4 * chunk_out)))
            if stored:
                store_block(
                    k_out,
                    oy[:stored],
                    ov[:stored],
                    None if oe is None else oe[:stored],
                    ol[:stored],
                    None if oa is None else oa[:stored],
                )
            k_out += stored
            within = within + done - stored * per_out
            last_out = out_time(k_out - 1) if k_out else 0.0
            t = float(last_out) + within * o.step if within else float(last_out)
            if stored:
                notify(float(last_out))
            if should_stop is not None and should_stop():
                status, message = DynamicStatus.INTERRUPTED, f"interrupted at t = {t:.6g} s"
                break
            if st == 1:
                continue
            ahead = None if check is None else check(t + o.step, y, lam)  # the step's end
            if ahead is not None:  # left a length law's range: no retry, the state stays here
                status, message = DynamicStatus.FAILED, ahead
                break
            within = 0  # the steps to the next output are taken below
            h = o.step * 0.25  # the failing step is retried below, smaller
            result.n_rejected += 1
            if h < min_step:
                status, message = DynamicStatus.FAILED, _failure_message(t, min_step)
                break
            continue
        h_try = min(h, target - t)
        if target - (t + h_try) < 1e-12 * max(1.0, target):
            h_try = target - t
        ahead = None if check is None else check(t + h_try, y, lam)  # a law at the step's end
        if ahead is not None:
            status, message = DynamicStatus.FAILED, ahead
            break
        lam_try = lam.copy()
        ok, y1, v1, a1, w1, e1 = integ.step(y, v, a, w, t, h_try, lam_try)
        err = integ.relative_error(e1, o.rtol)
        if not ok or (o.adaptive and err > 1.0):
            result.n_rejected += 1
            h = h_try * (0.25 if not ok else max(0.2, 0.9 * err ** (-1.0 / 3.0)))
            if h < min_step:
                status, message = DynamicStatus.FAILED, _failure_message(t, min_step)
                break
            continue
        outside = None if check is None else check(t + h_try, y1, lam_try)
        if outside is not None:  # the state stays at the step before
            status, message = DynamicStatus.FAILED, outside
            break
        alpha = integ.alpha_point(y, v, y1, v1) if contact else None  # before re-referencing
        y, v, a, w, t, lam = y1, v1, a1, w1, t + h_try, lam_try
        system.rereference(y, v, a, w)  # rods: triads follow the step, twist rates the spin
        result.took(h_try)
        result.note_error(err, t, h_try)
        if o.adaptive:
            h = min(max_step, h_try * min(2.0, 0.9 * max(err, 1e-10) ** (-1.0 / 3.0)))
        else:
            h = o.step
        if abs(t - target) <= 1e-12 * max(1.0, target):
            t = float(target)
            store(t, y, v, alpha)
            k_out += 1
            notify(t)
        if should_stop is not None and should_stop():
            status, message = DynamicStatus.INTERRUPTED, f"interrupted at t = {t:.6g} s"
            break
    settle = getattr(target_sink, "flush", None)  # rows a sink derives beside the loop or
    if settle is not None:  # holds in a buffer: all of them derived and appended, counted in
        settle()  # the loop's time
    return snapshot(status, message)
