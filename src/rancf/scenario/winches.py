"""``[[winches]]``: a cable paid out of or reeled onto a drum at an end of a flexible body.

Keys: ``name``; ``at`` (``"BODY:start"`` or ``"BODY:end"``; in a one-body file ``"start"`` or
``"end"``), an end held by a support (a ``pin``, or a ``clamp`` for a line leaving in a fixed
direction); ``position`` (where the line leaves the drum [m]; the body's end starts there, the
default); and one of ``length`` (the unstretched length outside the winch [m], a
TIME_FUNCTION), ``speed`` (the pay-out rate [m/s], a TIME_FUNCTION) or ``torque`` with the
drum's ``radius`` and ``inertia`` (a driven drum, :mod:`rancf.system.drums`: the torque
positive reeling in, the inertia the drum's with the rope on it at ``t = 0``).  The body is
drawn as the line is at ``t = 0``; with ``length``, a start length other than the drawing's
stretches the drawing about the winch (:mod:`rancf.system.winches`).  A ``length`` with
``build_up`` builds up its change from its start (:func:`~rancf.system.winches.length_law`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from pydantic import Field, model_validator

from rancf.bodies.flexible import Model
from rancf.bodies.length import set_unstretched_length, unstretched_length
from rancf.errors import ScenarioError
from rancf.scenario.base import Name, Positive, Table, Vector23, fail
from rancf.scenario.time_functions import TimeFunctionValue, check_scalar

if TYPE_CHECKING:  # loaded by a file with winches only
    from rancf.system.winches import Winch

__all__ = ["WinchTable", "system_winches", "winch_key"]


class WinchTable(Table):
    """One ``[[winches]]`` table (module docstring)."""

    name: Name = Field(description="the winch's name (sensors), unique")
    at: str = Field(description='the end of a cable body at the drum: "BODY:start" | "BODY:end"')
    position: Vector23 | None = Field(
        None, description="where the line leaves the drum [m] (default: the body's end)"
    )
    length: TimeFunctionValue | None = Field(
        None, description="the unstretched length outside the winch [m] (a TIME_FUNCTION)"
    )
    speed: TimeFunctionValue | None = Field(
        None, description="the pay-out rate [m/s] (reeling in: negative; a TIME_FUNCTION)"
    )
    torque: TimeFunctionValue | None = Field(
        None,
        description="a driven drum: the torque on it [N m], positive reeling in (a "
        "TIME_FUNCTION; with radius and inertia)",
    )
    radius: Positive | None = Field(None, description="a driven drum: its radius [m]")
    inertia: Positive | None = Field(
        None,
        description="a driven drum: its moment of inertia with the rope on it at the "
        "start [kg m^2]",
    )

    @model_validator(mode="after")
    def _one_law(self) -> WinchTable:
        given = [k for k in ("length", "speed", "torque") if self[k] is not None]
        if len(given) != 1:
            raise fail(
                "length", f"give one of length, speed or torque (got {', '.join(given) or 'none'})"
            )
        check_scalar(given[0], self[given[0]])
        for k in ("radius", "inertia"):
            if self[k] is None and self.torque is not None:
                raise fail(
                    k,
                    "a driven drum (torque) needs its "
                    + ("radius [m]" if k == "radius" else "moment of inertia [kg m^2]"),
                )
            if self[k] is not None and self.torque is None:
                raise fail(
                    k, "belongs to a driven drum: give torque with radius and inertia (or drop it)"
                )
        return self


def winch_key(winches: Any, parameter: str) -> str:
    """``parameter`` with a winch named by the system (``winches.NAME...``) named by its table,
    ``winches[i]...``; any other parameter as it is."""
    for i, w in enumerate(winches or ()):
        for sep in (".", ""):
            prefix = f"winches.{w.name}{sep}"
            if parameter.startswith(prefix) and (sep or parameter == prefix):
                return f"winches[{i}]{sep}{parameter[len(prefix) :]}"
    return parameter


def system_winches(sc: Any, bodies: dict[str, Any]) -> list[Winch]:
    """The :class:`~rancf.system.winches.Winch` of every ``[[winches]]`` table; a body whose
    length at ``t = 0`` is not its drawing's is stretched about the winch first
    (:func:`~rancf.bodies.length.set_unstretched_length`).  Errors name the key."""
    if not sc.winches:
        return []
    from rancf.system.winches import LENGTH_RTOL, Winch, length_law

    out = []
    for i, (w, wd) in enumerate(zip(sc.winches, sc.data["winches"], strict=True)):
        key = f"winches[{i}]"
        try:
            p = sc.place(w.at)
        except ScenarioError as exc:
            raise ScenarioError(sc.path, f"{key}.at", exc.problem) from None
        body = bodies.get(p.body) if p.where == "node" and p.body is not None else None
        if not isinstance(body, Model) or p.node not in (0, -1, body.n_nodes - 1):
            raise ScenarioError(
                sc.path, f"{key}.at", f'"BODY:start" or "BODY:end" of a cable body (got {w.at!r})'
            )
        node = 0 if p.node == 0 else body.n_nodes - 1
        end = "start" if node == 0 else "end"
        at = f"{p.body}:{end}"
        if w.position is not None:
            x = body.node_positions(body.q0)[node]
            if len(w.position) != x.size:
                raise ScenarioError(
                    sc.path,
                    f"{key}.position",
                    f"{x.size} numbers (the body is {x.size}D; got {w.position})",
                )
            if np.linalg.norm(np.asarray(w.position) - x) > 1e-9 * max(1.0, np.abs(x).max()):
                raise ScenarioError(
                    sc.path,
                    f"{key}.position",
                    f"where the body's {end} is "
                    f"drawn, {x.tolist()} (draw the line from the winch; got "
                    f"{w.position})",
                )
        length = wd["length"]
        winch = Winch(
            w.name,
            at,
            length=length,
            speed=wd["speed"],
            torque=wd["torque"],
            radius=w.radius,
            inertia=w.inertia,
        )
        _check_lengths(sc, key, winch, unstretched_length(body))  # before the body is stretched
        if length is not None:
            start = float(np.ravel(length_law(length).value(0.0))[0])
            _check_stretch(sc, key, start, unstretched_length(body))
            if abs(start - unstretched_length(body)) > LENGTH_RTOL * max(start, 1.0):
                set_unstretched_length(body, start, anchor=node)
        out.append(winch)
    return out


#: Largest factor between a winch's start length and its line's drawn length.
MAX_STRETCH = 1e3


def _check_stretch(sc: Any, key: str, start: float, drawn: float) -> None:
    """Refuse a start length so far from the drawn line's that stretching the drawing about
    the winch to it would make a line of another scale (a unit mistake, or overflow)."""
    if not drawn / MAX_STRETCH <= start <= drawn * MAX_STRETCH:
        raise ScenarioError(
            sc.path,
            f"{key}.length",
            f"a start length within a factor "
            f"{MAX_STRETCH:g} of the drawn line's {drawn:.6g} m (the drawing is "
            f"stretched about the winch to it; draw the line at about its start "
            f"length), got {start:.6g} m at t = 0",
        )


#: Uniform samples of ``[0, t_end]`` a winch's length is checked at (with a table's times).
LENGTH_SAMPLES = 2001


def _check_lengths(sc: Any, key: str, w: Winch, length0: float) -> None:
    """Refuse a ``length`` or ``speed`` law whose length outside the winch is not > 0 somewhere
    in ``[0, t_end]`` (a line reeled in past the drum: negative lengths, then NaN tensions).
    A driven drum's length is a coordinate: the run stops where it leaves its range."""
    if w.driven:
        return
    from rancf.system.winches import winch_length

    t_end = float(sc.dynamic_options().t_end)
    law = w.length if w.length is not None else w.speed
    f = winch_length(w, length0, t_end)
    times = np.linspace(0.0, t_end, LENGTH_SAMPLES)
    rows = getattr(law, "rows", None)
    if rows is not None:
        knots = np.asarray(rows)[:, 0]
        times = np.union1d(times, knots[(knots >= 0.0) & (knots <= t_end)])
    values = np.array([float(np.ravel(f.value(t))[0]) for t in times])
    bad = np.flatnonzero(~(values > 0.0))
    if bad.size:
        which = "length" if w.length is not None else "speed"
        t, v = float(times[bad[0]]), float(values[bad[0]]) + 0.0  # no "-0"
        raise ScenarioError(
            sc.path,
            f"{key}.{which}",
            f"the length outside the winch must stay "
            f"> 0 m over the run (t = 0 to t_end = {t_end:g} s), but it is "
            f"{v:.6g} m at t = {t:.6g} s",
        )
