"""Winches: a cable paid out of (or reeled onto) a drum at one end of a flexible body.

The body outside the winch keeps its mesh and its exact reference geometry; its unstretched
length follows ``L(t)`` (``length``: any time function; ``speed``: the pay-out rate, ``L`` its
integral from the body's length at ``t = 0``).  The material is spread uniformly over the mesh
and moves through it; the compiled core (``src/cpp/winch.hpp``) stretches the body's reference
by ``L(t)`` and adds the convective inertia of :mod:`rancf.bodies.winch_inertia`, so mass,
momentum and energy of the material outside the drum are exact: the material leaving the drum
enters with the drum's speed (docs/derivations/variable-length.md §2).  The winch's end of the
body must be held by a support (a pin, or a clamp for a line leaving in a fixed direction) at
the place where the line leaves the drum.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any, Literal, Protocol

import numpy as np

from rancf.bodies.flexible import Model
from rancf.bodies.length import unstretched_length
from rancf.bodies.rigid import PointMass
from rancf.bodies.time_function import TimeFunction
from rancf.bodies.winch_inertia import convective_matrices
from rancf.errors import InputError

__all__ = [
    "Winch", "winch_length", "winch_functions", "attach_winches", "winch_node", "unloaded_at",
    "LENGTH_RTOL",
]  # fmt: skip


class WinchedSystem(Protocol):
    """What the winches use of a system (:class:`rancf.system.system.System`)."""

    bodies: Mapping[str, Any]
    names: list[str]
    horizon: float | None
    core: Any
    y0: np.ndarray
    joints: Sequence[Any]

    def resolve(self, spec: Any) -> Any: ...

    def body_slice(self, name: str) -> slice: ...


#: The body's unstretched length and ``L(0)`` agree to this (relative).
LENGTH_RTOL = 1e-9


@dataclass(frozen=True)
class Winch:
    """A winch (module docstring).

    Parameters
    ----------
    name : str
    at : str
        ``"BODY:start"`` or ``"BODY:end"``: the end of a cable body at the drum.
    length : TimeFunction or float, optional
        The unstretched length outside the winch [m] as a function of time.
    speed : TimeFunction or float, optional
        The pay-out rate [m/s] (reeling in: negative); one of ``length`` and ``speed``.
    """

    name: str
    at: str
    length: TimeFunction | float | None = None
    speed: TimeFunction | float | None = None

    def body_and_end(self) -> tuple[str, Literal["start", "end"]]:
        """The body's name and the end at the drum."""
        body, _, end = self.at.rpartition(":")
        if not body or end not in ("start", "end"):
            raise InputError(f"winches.{self.name}.at", self.at, '"BODY:start" or "BODY:end"')
        return body, end  # type: ignore[return-value]


def winch_length(w: Winch, length0: float, horizon: float | None) -> TimeFunction:
    """``L(t)`` of a winch whose body is ``length0`` long at ``t = 0``: its ``length``, or
    ``length0`` plus the integral of its ``speed`` (trapezoidal on 20 001 points of
    ``[0, horizon]``, then a cubic table of the core's)."""
    if (w.length is None) == (w.speed is None):
        raise InputError(f"winches.{w.name}", "length and speed" if w.length is not None
                         else "neither", "one of length, speed")  # fmt: skip
    if w.length is not None:
        f = w.length if isinstance(w.length, TimeFunction) else TimeFunction.constant(w.length)
        return f
    speed = w.speed if isinstance(w.speed, TimeFunction) else TimeFunction.constant(w.speed)
    if horizon is None or not horizon > 0:
        raise InputError("horizon", horizon, "the run's end time t_end [s] > 0 (a winch's "
                         "speed is integrated on [0, t_end])")  # fmt: skip
    t = np.linspace(0.0, float(horizon), 20001)
    rate = np.array([float(np.ravel(speed.value(x))[0]) for x in t])
    cum = length0 + np.r_[0.0, np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))]

    def length(x: float) -> float:
        return float(np.interp(x, t, cum))

    return TimeFunction.from_callable(length)


def winch_functions(system: WinchedSystem, winches: tuple[Winch, ...], tf: Callable) -> list[int]:
    """The index of each winch's ``L(t)`` among the core's time functions (``tf`` registers
    one); ``L(0)`` must be the body's unstretched length."""
    out = []
    for w in winches:
        body = _body(system, w)
        length0 = unstretched_length(body)
        f = winch_length(w, length0, system.horizon)
        start = float(np.ravel(f.value(0.0))[0])
        if abs(start - length0) > LENGTH_RTOL * max(length0, 1.0):
            raise InputError(f"winches.{w.name}.length", start, f"the body's unstretched "
                             f"length at t = 0, {length0!r} m (rancf.bodies.length."
                             "set_unstretched_length gives the body its start length)")  # fmt: skip
        out.append(tf(f))
    return out


def attach_winches(system: WinchedSystem, winches: tuple[Winch, ...], tfs: list[int]) -> None:
    """Give the core each winch: its body, the index of its ``L(t)`` and the convective
    matrices."""
    for w, tf in zip(winches, tfs, strict=True):
        body = _body(system, w)
        name, end = w.body_and_end()
        c1, c2, d2 = convective_matrices(body, end)
        index = system.names.index(name)  # flexible bodies come first
        system.core.attach_winch(index, tf, unstretched_length(body), c1, c2, d2)


def winch_node(system: WinchedSystem, w: Winch) -> tuple[str, int]:
    """The body and the node at the drum."""
    name, end = w.body_and_end()
    return name, 0 if end == "start" else _body(system, w).n_nodes - 1


def _body(system: WinchedSystem, w: Winch) -> Model:
    name, end = w.body_and_end()
    body = system.bodies.get(name)
    if not isinstance(body, Model):
        raise InputError(f"winches.{w.name}.at", w.at, "the end of a flexible (cable) body")
    node = 0 if end == "start" else body.n_nodes - 1
    if not any(body.check_node(s.node, "supports.at") == node for s in body.supports):
        raise InputError(f"winches.{w.name}.at", w.at, "an end held by a support (pin or "
                         "clamp) where the line leaves the drum")  # fmt: skip
    return body


def unloaded_at(system: WinchedSystem, t: float) -> np.ndarray:
    """The system's reference coordinates with every winch's body stretched about the winch to
    its length at ``t`` (positions ``a + f (r - a)``, gradients ``f r_x``, ``f = L(t) / L(0)``):
    where statics at ``t`` start."""
    y = system.y0.copy()
    for w in getattr(system, "winches", ()):
        name, node = winch_node(system, w)
        body = _body(system, w)
        f = winch_length(w, unstretched_length(body), system.horizon)
        factor = float(np.ravel(f.value(t))[0]) / unstretched_length(body)
        sl = system.body_slice(name)
        q = body.q_from_y(y[sl]).reshape(body.n_nodes, body.dpn)
        d = body.dim
        a = q[node, :d].copy()
        q[:, :d] = a + factor * (q[:, :d] - a)
        q[:, d : 2 * d] *= factor
        y[sl] = body.y_from_q(q.ravel())
        for j in system.joints:  # a point mass pinned to the body goes with its node
            ends = [system.resolve(p) for p in j.between]
            for p, other in (ends, ends[::-1]):
                mass = system.bodies.get(other.body) if other.body else None
                if p.body == name and isinstance(mass, PointMass) and j.kind == "pin":
                    y[system.body_slice(other.body)][:d] = q[int(p.at), :d]
    return y
