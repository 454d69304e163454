"""The time functions of prescribed motions (supports' ``motion``, driven joints' ``angle``),
their default build-up (:mod:`rancf.bodies.time_function`, T.6), and the warnings of impulsive
starts (``docs/guide/scenarios.md``, "Impulsive starts").

A harmonic support motion or joint angle that would start with a jump of its rate builds up
smoothly, and says so in one line (a note): a steady oscillation whose start is not the point.
Every other time function that drives something is written as its author meant it, so a jump
at ``t = 0`` is warned about instead (one line naming the item, the jump and the cure):

* prescribed kinematics (a support's ``motion``, a joint's ``angle``, a winch's ``length`` or
  ``speed``): a rate jump from rest, and a value jump (a displacement or angle other than the
  reference's) unless the run starts from the static equilibrium at ``t = 0``;
* loads (a point or distributed load's ``time``, a driven drum's ``torque``): a value jump from
  0, unless the run starts from the static equilibrium (which carries the loads at ``t = 0``).

A start from rest is impulsive when the value (``order`` 0) or the rate (``order`` 1) jumps at
``t = 0`` from 0 (everything is at rest, and at its reference, before the run): a prescribed
rate jump ``Δv`` is an impact.  :func:`start_jump` gives the jump and the largest magnitude of
the same over the run; a jump up to :data:`JUMP_RTOL` of that largest magnitude passes; a
function with ``build_up`` stated (0 too) is taken as meant.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.scenario.time_functions import (
    HarmonicFunction,
    RampFunction,
    TableFunction,
    time_function,
)

__all__ = [
    "motion_function",
    "BUILD_UP_PERIODS",
    "Law",
    "start_warning",
    "start_warnings",
    "start_jump",
    "JUMP_RTOL",
    "absolute_motion",
    "PATH_START_TOL",
]

#: A jump of a value or rate at ``t = 0`` up to this fraction of the largest magnitude the same
#: reaches over the run is not reported: the transient a jump excites is linear in it, and an
#: impulsive start excites some 20-30 times the smooth response (the reported winch and crank
#: cases), so 1e-3 of it keeps the spurious part within a few per cent; it passes the spline
#: artefacts of tables that start flat (a not-a-knot spline's end slope, 1e-4 of the peak rate).
JUMP_RTOL = 1e-3


def start_jump(f: TimeFunction, order: int, t_end: float) -> tuple[float, float]:
    """The jump at ``t = 0`` of ``f``'s value (``order`` 0) or rate (1) from rest, the largest
    magnitude over the components, and the largest magnitude of the same over ``[0, t_end]``
    and a table's rows (sampled on 1001 times and every row; the jump included): a table is
    measured against its own scale, whatever part of it a run covers.

    A table's rate at a row is its right derivative, so a rate jump at ``t = 0`` is the first
    interval's slope; a function with a build-up (T.6) starts from 0 in value and rate.
    """
    end = max(float(t_end), 0.0)
    if f.rows is not None:
        end = max(end, float(f.rows[-1, 0]))
    times = np.linspace(0.0, end, 1001)
    if f.rows is not None:
        knots = f.rows[:, 0]
        times = np.union1d(times, knots[knots >= 0.0])
    at = f.value if order == 0 else f.rate
    size = [float(np.max(np.abs(at(t)))) for t in times]
    return size[0], max(size)


#: The default build-up of a harmonic motion that would start with a jump of its rate, in
#: periods of the harmonic.
BUILD_UP_PERIODS = 2.0


def motion_function(v: Any, key: str) -> tuple[TimeFunction | None, str | None]:
    """The time function of a motion (a support's ``motion``, a joint's ``angle``) named
    ``key``, and the one-line note saying when it got its default build-up: a harmonic without
    ``build_up`` whose rate at ``t = 0`` is not zero (a jump from rest) builds up over
    :data:`BUILD_UP_PERIODS` periods."""
    if v is None:
        return None, None
    f = time_function(v)
    if not (isinstance(v, HarmonicFunction) and v.build_up is None):
        return f, None
    rate = np.atleast_1d(f.rate(0.0))
    if not np.any(np.abs(rate) > 1e-12 * max(1.0, float(np.max(np.abs(f.values))))):
        return f, None
    b = BUILD_UP_PERIODS / v.harmonic
    note = (
        f"{key}: the harmonic would start with a jump of its rate to "
        f"{float(np.max(np.abs(rate))):.3g}; it builds up over {b:g} s ({BUILD_UP_PERIODS:g} "
        f"periods; give build_up = 0 to start it at once)"
    )
    return f.with_build_up(b), note


#: How far [m] (times the larger of 1 and the largest coordinate of the reference point) a path
#: of absolute positions may start from the support's reference point: the rounding of a path
#: file written with six decimals in metres.
PATH_START_TOL = 1e-6


def absolute_motion(f: TimeFunction, reference: NDArray, key: str, static: bool) -> TimeFunction:
    """The displacement from ``reference`` (the support's reference point, ``dim``) of a motion
    ``f`` given as absolute positions (a table, :class:`~rancf.scenario.time_functions.PathTable`
    with ``absolute = true``; its build-up kept: ``r(t) (p(t) − reference)``, T.6).

    At ``t = 0`` the body lies in its reference shape, the support at ``reference``.  A path
    that starts farther than :data:`PATH_START_TOL` from there would make the support jump; it
    is refused in one line naming ``key``, unless ``f`` builds up (the support moves smoothly
    from its reference point onto the path) or the run starts from the static equilibrium
    (``static``: the statics installs the support at the path's start)."""
    ref = np.asarray(reference, dtype=float)[: f.size]
    assert f.rows is not None  # a PathTable is a table
    gap = float(np.linalg.norm(f.rows[0, 1:] - ref))
    tol = PATH_START_TOL * max(1.0, float(np.abs(ref).max(initial=0.0)))
    if gap > tol and not f.build_up and not static:
        b = float(f"{_time_scale(f, 0.0) / 10.0:.1g}")
        raise InputError(
            key,
            f"a path starting at {_point(f.rows[0, 1:])}",
            f"a path that starts at the support's reference point {_point(ref)} (it starts "
            f"{gap:.4g} m away): draw the body with the support there, give build_up = {b:g} "
            "to move it onto the path smoothly, or start from the static equilibrium "
            '(solver.initial_state = "static")',
        )
    out = TimeFunction.table(f.rows - np.r_[0.0, ref], f.interpolation)  # (T.2): linear in rows
    return out.with_build_up(f.build_up)


def _point(x: NDArray) -> str:
    return "(" + ", ".join(f"{v:.6g}" for v in x) + ")"


@dataclass(frozen=True)
class Law:
    """What a time function drives, for the warning of its impulsive start.

    Attributes
    ----------
    what : str
        The quantity, e.g. ``"angular rate"``.
    unit : str
        Its unit after a space (``" m/s"``; empty for a factor).
    order : int
        0: the function's value is checked (a load, a winch's speed), 1: its rate.
    static_cures : bool
        Whether a start from the static equilibrium removes the jump (value jumps).
    """

    what: str
    unit: str
    order: int
    static_cures: bool = False


def start_warning(
    v: Any, f: TimeFunction | None, item: str, law: Law, t_end: float, static: bool
) -> str | None:
    """The warning line of the impulsive start of ``f`` (written as ``v``; ``item`` names it),
    or None: no jump above :data:`JUMP_RTOL` of its largest over ``[0, t_end]``, a ``build_up``
    stated, or a value jump that a ``static`` start removes."""
    if f is None or getattr(v, "build_up", None) is not None or (static and law.static_cures):
        return None
    jump, largest = start_jump(f, law.order, t_end)
    if not jump > JUMP_RTOL * largest:
        return None
    b = float(f"{_time_scale(f, t_end) / 10.0:.1g}")
    alt = _alternative(v, law, b)
    return (
        f"{item}: the {law.what} jumps from 0 to {jump:.4g}{law.unit} at t = 0, an "
        f"impulsive start (an impact: forces and ringing far above a smooth start's); give "
        f"build_up = {b:g} to build it up over {b:g} s{alt}"
    )


def _time_scale(f: TimeFunction, t_end: float) -> float:
    """The function's own time scale: a table's span, a ramp's or spin-up's duration, 20
    periods of a harmonic (a build-up of 2), else the run's."""
    if f.rows is not None:
        span = float(f.rows[-1, 0] - max(f.rows[0, 0], 0.0))
        return span if span > 0.0 else t_end
    if f.kind == "harmonic":
        return 20.0 / f.frequency
    return f.duration if f.duration > 0.0 else t_end


def _alternative(v: Any, law: Law, b: float) -> str:
    start = "at rate 0" if law.order == 1 else "at 0"
    steady = isinstance(v, RampFunction) and not isinstance(v.value, list)
    if steady and law.unit == " rad/s":  # a steady rate without overshoot
        return f", or write angle = {{ spin_up = {b:g}, rate = {v.value / v.ramp:.4g} }}"
    if isinstance(v, TableFunction):
        return f", or start the table {start}"
    if law.static_cures:
        return ', or start from the static equilibrium (solver.initial_state = "static")'
    spin = " (spin_up for a steady rate)" if law.unit == " rad/s" else ""
    return f", or write a function that starts {start}{spin}"


#: Support motions and joint angles: the rate (here) and the value (:data:`_PLACED`).
_MOVED = {"motion": Law("velocity", " m/s", 1), "angle": Law("angular rate", " rad/s", 1)}
_PLACED = {"motion": Law("displacement", " m", 0, True), "angle": Law("angle", " rad", 0, True)}
_WINCH = {
    "length": Law("pay-out rate", " m/s", 1),
    "speed": Law("pay-out rate", " m/s", 0),
    "torque": Law("torque", " N m", 0, True),
}
_LOAD = Law("load factor", "", 0, True)


def start_warnings(sc: Any) -> list[str]:
    """The warning of every impulsive start of a scenario ``sc`` (its tables and
    :attr:`~rancf.scenario.scenario.Scenario.data`; module docstring)."""
    t_end, static = sc.solver.t_end, sc.solver.initial_state == "static"
    d, out = sc.data, []

    def check(v: Any, f: Any, item: str, *laws: Law) -> None:
        for law in laws:
            line = start_warning(v, f, item, law, t_end, static)
            out.extend([line] if line else [])

    for i, s in enumerate(sc.supports):
        f, item = d["supports"][i]["motion"], f"support at {s.at!r} (supports[{i}].motion)"
        placed = () if d["supports"][i]["absolute"] else (_PLACED["motion"],)  # absolute_motion
        check(s.motion, f, item, *placed, _MOVED["motion"])
        f, item = d["supports"][i]["rotation"], f"support at {s.at!r} (supports[{i}].rotation)"
        check(s.rotation, f, item, _PLACED["angle"], _MOVED["angle"])
    for i, j in enumerate(sc.joints):
        f, item = d["joints"][i]["angle"], f"joint {j.name!r} (joints[{i}].angle)"
        check(j.angle, f, item, _PLACED["angle"], _MOVED["angle"])
    for i, w in enumerate(sc.winches):
        for k, law in _WINCH.items():
            check(w[k], d["winches"][i][k], f"winch {w.name!r} (winches[{i}].{k})", law)
    for kind in ("point", "distributed"):
        for i, p in enumerate(sc.loads[kind]):
            at = f" at {p.at!r}" if kind == "point" else ""
            item = f"{kind} load{at} (loads.{kind}[{i}].time)"
            check(p.time, d["loads"][kind][i]["time"], item, _LOAD)
    return out
