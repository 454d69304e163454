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

from typing import Any

import numpy as np
from pydantic import Field, model_validator

from rancf.bodies.flexible import Model
from rancf.bodies.length import set_unstretched_length, unstretched_length
from rancf.errors import ScenarioError
from rancf.scenario.base import Name, Positive, Table, fail, vector
from rancf.scenario.loads import TimeFunctionValue
from rancf.system.winches import LENGTH_RTOL, Winch, length_law

__all__ = ["WinchTable", "system_winches"]


class WinchTable(Table):
    """One ``[[winches]]`` table (module docstring)."""

    name: Name = Field(description="the winch's name (sensors), unique")
    at: str = Field(description='the end of a cable body at the drum: "BODY:start" | "BODY:end"')
    position: vector(2, 3) | None = Field(
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
            raise fail("length", "give one of length, speed or torque (got "
                       f"{', '.join(given) or 'none'})")  # fmt: skip
        for k in ("radius", "inertia"):
            if self[k] is None and self.torque is not None:
                raise fail(
                    k,
                    "a driven drum (torque) needs its "
                    + ("radius [m]" if k == "radius" else "moment of inertia [kg m^2]"),
                )
            if self[k] is not None and self.torque is None:
                raise fail(k, "belongs to a driven drum: give torque with radius and inertia "
                           "(or drop it)")  # fmt: skip
        return self


def system_winches(sc: Any, bodies: dict[str, Any], one_body: str) -> list[Winch]:
    """The :class:`~rancf.system.winches.Winch` of every ``[[winches]]`` table; a body whose
    length at ``t = 0`` is not its drawing's is stretched about the winch first
    (:func:`~rancf.bodies.length.set_unstretched_length`).  Errors name the key."""
    out = []
    for i, (w, wd) in enumerate(zip(sc.winches, sc.data["winches"], strict=True)):
        key = f"winches[{i}]"
        p = sc.place(w.at)
        body = bodies.get(p.body or one_body) if p.where == "node" else None
        if not isinstance(body, Model) or p.node not in (0, -1, body.n_nodes - 1):
            raise ScenarioError(sc.path, f"{key}.at", f'"BODY:start" or "BODY:end" of a cable '
                                f"body (got {w.at!r})")  # fmt: skip
        node = 0 if p.node == 0 else body.n_nodes - 1
        end = "start" if node == 0 else "end"
        at = f"{p.body or one_body}:{end}"
        if w.position is not None:
            x = body.node_positions(body.q0)[node]
            if np.linalg.norm(np.asarray(w.position) - x) > 1e-9 * max(1.0, np.abs(x).max()):
                raise ScenarioError(sc.path, f"{key}.position", f"where the body's {end} is "
                                    f"drawn, {x.tolist()} (draw the line from the winch; got "
                                    f"{w.position})")  # fmt: skip
        length = wd["length"]
        if length is not None:
            start = float(np.ravel(length_law(length).value(0.0))[0])
            if abs(start - unstretched_length(body)) > LENGTH_RTOL * max(start, 1.0):
                set_unstretched_length(body, start, anchor=node)
        out.append(Winch(w.name, at, length=length, speed=wd["speed"], torque=wd["torque"],
                         radius=w.radius, inertia=w.inertia))  # fmt: skip
    return out
