"""Winches: a cable paid out of (or reeled onto) a drum at one end of a flexible body.

The body outside the winch keeps its mesh and its exact reference geometry; its unstretched
length follows ``L(t)`` (``length``: any time function; ``speed``: the pay-out rate, ``L`` its
integral from the body's length at ``t = 0``).  The material is spread uniformly over the mesh
and moves through it; the compiled core (``src/cpp/system/winch.hpp``) stretches the body's
reference by ``L(t)`` and adds the convective inertia of :mod:`rancf.bodies.winch_inertia`, so mass,
momentum and energy of the material outside the drum are exact: the material leaving the drum
enters with the drum's speed (docs/derivations/variable-length.md §2).  The winch's end of the
body must be held by a support (a pin, or a clamp for a line leaving in a fixed direction) at
the place where the line leaves the drum.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, Protocol

import numpy as np

from rancf.bodies.flexible import Model
from rancf.bodies.length import unstretched_length
from rancf.bodies.rigid import PointMass
from rancf.bodies.time_function import TimeFunction, build_up_factor
from rancf.errors import InputError
from rancf.system.drums import add_drum_coordinate
from rancf.system.parts.winch import Winch

__all__ = [
    "Winch",
    "winch_length",
    "winch_functions",
    "add_drums",
    "winch_node",
    "unloaded_at",
    "winch_factor",
    "LENGTH_RTOL",
    "length_law",
]


class WinchedSystem(Protocol):
    """What the winches use of a system (:class:`rancf.system.system.System`)."""

    #: the coordinate of each driven drum by name (set by :func:`add_drums`)
    drums: dict[str, int]

    # read-only: implementations may narrow a member's type
    @property
    def bodies(self) -> Mapping[str, Any]: ...

    @property
    def names(self) -> list[str]: ...

    @property
    def horizon(self) -> float | None: ...

    @property
    def core(self) -> Any: ...

    @property
    def y0(self) -> np.ndarray: ...

    @property
    def joints(self) -> Sequence[Any]: ...

    @property
    def winch_lengths(self) -> dict[str, TimeFunction]: ...

    @property
    def n(self) -> int: ...

    @property
    def v0(self) -> np.ndarray: ...

    def resolve(self, spec: Any) -> Any: ...

    def body_slice(self, name: str) -> slice: ...


#: A callable ``L(t)`` is sampled this much past the horizon (its rate is not cut at the end).
HORIZON_MARGIN = 1.05

#: The body's unstretched length and ``L(0)`` agree to this (relative).
LENGTH_RTOL = 1e-9


def winch_length(w: Winch, length0: float, horizon: float | None) -> TimeFunction:
    """``L(t)`` of a winch whose body is ``length0`` long at ``t = 0``: its ``length``, or
    ``length0`` plus the integral of its ``speed`` (trapezoidal on 20 001 points of
    ``[0, 1.05 horizon]``, then a cubic table of the core's)."""
    given = [k for k in ("length", "speed", "torque") if getattr(w, k) is not None]
    if len(given) != 1:
        raise InputError(
            f"winches.{w.name}", " and ".join(given) or "none", "one of length, speed, torque"
        )
    if w.torque is not None:  # the drum's start: its length at t = 0, a coordinate after
        return TimeFunction.constant(length0)
    if w.length is not None:
        f = w.length if isinstance(w.length, TimeFunction) else TimeFunction.constant(w.length)
        return length_law(f)
    assert w.speed is not None  # the one given
    speed = w.speed if isinstance(w.speed, TimeFunction) else TimeFunction.constant(w.speed)
    if horizon is None or not horizon > 0:
        raise InputError(
            "horizon",
            horizon,
            "the run's end time t_end [s] > 0 (a winch's speed is integrated on [0, t_end])",
        )
    t = np.linspace(0.0, HORIZON_MARGIN * float(horizon), 20001)
    rate = np.array([float(np.ravel(speed.value(x))[0]) for x in t])
    cum = length0 + np.r_[0.0, np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t))]

    def length(x: float) -> float:
        return float(np.interp(x, t, cum))

    return TimeFunction.from_callable(length)


def length_law(f: TimeFunction) -> TimeFunction:
    """A winch's ``length`` as it is paid out: ``f`` itself, or with a build-up ``B`` (T.6) its
    change from its start built up, ``L(t) = f(0) + r(t) (f(t) − f(0))`` (a length cannot start
    from 0; its rate starts from 0 and joins ``f′`` at ``B``), a callable then."""
    if f.build_up <= 0.0:
        return f
    plain, b = f.with_build_up(0.0), f.build_up
    start = float(np.ravel(plain.value(0.0))[0])

    def length(t: float) -> float:
        change = float(np.ravel(plain.value(t))[0]) - start
        return start + build_up_factor(t, b)[0] * change

    return TimeFunction.from_callable(length)


def winch_functions(system: WinchedSystem, winches: tuple[Winch, ...]) -> dict[str, TimeFunction]:
    """Each winch's ``L(t)`` as the core evaluates it (a callable sampled on the horizon; a
    driven drum: its start) by name (its record, :meth:`Winch.record`, registers it);
    ``L(0)`` must be the body's unstretched length."""
    functions = {}
    for w in winches:
        body = _body(system, w)
        length0 = unstretched_length(body)
        f = winch_length(w, length0, system.horizon)
        start = float(np.ravel(f.value(0.0))[0])
        if abs(start - length0) > LENGTH_RTOL * max(length0, 1.0):
            raise InputError(
                f"winches.{w.name}.length",
                start,
                f"the body's unstretched "
                f"length at t = 0, {length0!r} m (rancf.bodies.length."
                "set_unstretched_length gives the body its start length)",
            )
        if f.kind == "callable":
            if system.horizon is None:
                raise InputError(
                    "horizon",
                    None,
                    "the run's end time t_end [s] (a winch's "
                    "length function is sampled on [0, t_end])",
                )
            f = f.sampled(HORIZON_MARGIN * float(system.horizon))
        functions[w.name] = f
    return functions


def add_drums(system: WinchedSystem, winches: tuple[Winch, ...]) -> None:
    """After the core is built: each driven drum's coordinate added to the system
    (``system.drums``: the coordinate of each by name)."""
    system.drums = {}
    for w in winches:
        if w.driven:
            system.drums[w.name] = add_drum_coordinate(system, w, _body(system, w))


def winch_node(system: WinchedSystem, w: Winch) -> tuple[str, int]:
    """The body and the node at the drum."""
    return w.node(system)


def _body(system: WinchedSystem, w: Winch) -> Model:
    return w.body(system)


def unloaded_at(system: WinchedSystem, t: float) -> np.ndarray:
    """The system's reference coordinates with every winch's body stretched about the winch to
    its length at ``t`` (positions ``a + f (r - a)``, gradients ``f r_x``, ``f = L(t) / L(0)``):
    where statics at ``t`` start."""
    y = system.y0.copy()
    for w in getattr(system, "winches", ()):
        name, node = winch_node(system, w)
        body = _body(system, w)
        f = system.winch_lengths[w.name]
        factor = float(np.ravel(f.value(t))[0]) / float(np.ravel(f.value(0.0))[0])
        sl = system.body_slice(name)
        q = body.q_from_y(y[sl]).reshape(body.n_nodes, body.dpn)
        d = body.dim
        a = q[node, :d].copy()
        q[:, :d] = a + factor * (q[:, :d] - a)
        q[:, d : 2 * d] *= factor
        y[sl] = body.y_from_q(q.ravel())
        for j in system.joints:  # a point mass joined to the body goes with its node
            if not j.entry.joins_positions:
                continue
            ends = [system.resolve(p) for p in j.between]
            for p, other in (ends, ends[::-1]):
                mass = system.bodies.get(other.body) if other.body else None
                if p.body == name and isinstance(mass, PointMass):
                    y[system.body_slice(other.body)][:d] = q[int(p.at), :d]
    return y


def winch_factor(system: Any, name: str, t: float, y: np.ndarray | None = None) -> float:
    """The unstretched length at ``t`` (a driven drum: in the state ``y``) of the body ``name``
    over the one its arrays hold (1 for a body without a winch): what its section values are
    measured against."""
    for w in getattr(system, "winches", ()):
        body, _ = winch_node(system, w)
        if body == name:
            f = system.winch_lengths[w.name]
            drum = getattr(system, "drums", {}).get(w.name)
            if drum is not None and y is not None:
                return float(y[drum]) / float(np.ravel(f.value(0.0))[0])
            return float(np.ravel(f.value(t))[0]) / float(np.ravel(f.value(0.0))[0])
    return 1.0
