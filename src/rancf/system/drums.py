"""Driven drums: winches whose length follows from the drum's own balance.

A winch with a ``torque`` (positive reeling in), a drum ``radius`` ``r`` and ``inertia`` ``J``
(the drum's, with the rope on it at ``t = 0``) makes the unstretched length ``L`` outside the
winch a coordinate of the system, after every body: the drum's angle is ``θ = (L − L0) / r``
(paying out: ``θ`` grows).  Its balance is Lagrange's equation of ``L`` for the line's material
outside the drum (its kinetic energy with the material's flow through the mesh, its strain
energy at the stretched reference, its weight), the drum's inertia ``J(L) = J − ρA r² (L − L0)``
(the rope wound off it leaves with it) and the torque; statics: ``L`` where the line's pull on
the drum balances the torque (docs/derivations/variable-length.md §3).  The compiled core
assembles it (``src/cpp/system/winch.cpp``, ``drum_terms``).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.time_function import TimeFunction
from rancf.bodies.winch_inertia import arc_fractions_at_gauss_points
from rancf.errors import InputError
from rancf.kernels.records import DrumRecord, vec3

__all__ = [
    "drum_torque",
    "drum_record",
    "add_drum_coordinate",
    "drum_state",
    "drum_mass",
    "hold_drums",
    "refuse_static_drums",
]


def drum_torque(w: Any, tf: Callable) -> int:
    """The index of a driven drum's torque among the core's time functions (``tf`` registers
    one); its radius and inertia checked."""
    for key in ("radius", "inertia"):
        v = getattr(w, key)
        if v is None or not (np.isfinite(v) and v > 0):
            raise InputError(
                f"winches.{w.name}.{key}",
                v,
                "a driven drum's "
                + (
                    "radius [m], > 0"
                    if key == "radius"
                    else "moment of inertia [kg m^2], > 0 "
                    "(the drum's, with the rope on it at t = 0)"
                ),
            )
    if not np.isfinite(drum_mass(w)) or drum_mass(w) == 0.0:
        raise InputError(
            f"winches.{w.name}.radius",
            w.radius,
            "a driven drum's radius [m] with "
            f"a finite, non-zero mass along the line J / r^2 (J = {w.inertia:g} kg "
            "m^2)",
        )
    f = w.torque if isinstance(w.torque, TimeFunction) else TimeFunction.constant(w.torque)
    if np.ravel(f.value(0.0)).size != 1:
        raise InputError(
            f"winches.{w.name}.torque",
            np.ravel(f.value(0.0)).tolist(),
            "a scalar time function [N m]",
        )
    return tf(f)


def drum_mass(w: Any) -> float:
    """``J / r²`` [kg]: the drum's inertia at ``t = 0`` seen along the line."""
    with np.errstate(over="ignore", divide="ignore"):
        return float(np.float64(w.inertia) / np.float64(w.radius) ** 2)


def drum_record(w: Any, body: Model, node: int, torque: int, length_set: float) -> DrumRecord:
    """The core's record of the driven drum of the winch ``w`` at ``node`` of ``body``
    (``torque``: its time function's index; ``length_set`` the length ``L_s`` the body's arrays
    hold); its length ``L`` becomes a coordinate of the system, after every body and drum before
    it (:func:`add_drum_coordinate`).  Its line's fluid loads ``f`` enter its balance as
    ``−Σ c_q f·r'`` with ``c_q = gw_q d_q L_ref / L_s`` (``d = 1 − σ`` at the start, ``−σ`` at
    the end; docs/derivations/variable-length.md §3.5)."""
    if any(
        s.motion is not None
        for s in body.supports
        if body.check_node(s.node, "supports.at") == node
    ):
        raise InputError(
            f"winches.{w.name}.at",
            w.at,
            "a fixed support (a driven drum's line leaves it at a fixed place; no support motion)",
        )
    gravity = np.zeros(3)
    if body.gravity is not None:
        gravity[: body.dim] = body.gravity
    kernel = body.family.cable_kernel(body.kernel)
    if kernel is None:
        raise InputError(f"winches.{w.name}.at", w.at, "a place on a cable body")
    rho_a = float(kernel.props.rho_a)
    sigma, l_ref = arc_fractions_at_gauss_points(kernel)
    d = 1.0 - sigma if node == 0 else -sigma
    convective = kernel.gw[None, :] * d * (l_ref / length_set)
    return DrumRecord(
        torque=torque,
        mass=drum_mass(w),
        radius=float(w.radius),
        rho_a=rho_a,
        weight=vec3(rho_a * gravity),
        exit=int(body.node_base(node)),
        convective=np.ascontiguousarray(convective.ravel(), dtype=float),
    )


def add_drum_coordinate(system: Any, w: Any, body: Model) -> int:
    """Add the coordinate ``L`` of the driven drum of winch ``w`` (on ``body``) to the system:
    ``n``, ``y0`` (its length at the start: the body's unstretched length), ``v0`` (0), as the
    core appended it; returns its index."""
    index = system.n
    if int(system.core.n) <= index:
        raise InputError(f"winches.{w.name}", index, f"the coordinate {system.n}")
    kernel = body.family.cable_kernel(body.kernel)
    assert kernel is not None  # a cable body: drum_record
    system.n += 1
    system.y0 = np.r_[system.y0, float(np.sum(kernel.wj))]
    system.v0 = np.r_[system.v0, 0.0]
    return index


def drum_state(
    index: int, y: Sequence[float], v: Sequence[float] | None = None
) -> tuple[float, float]:
    """``(L, L̇)`` of the drum whose coordinate is ``index`` in ``y`` (and ``v``)."""
    return float(y[index]), (0.0 if v is None else float(v[index]))


def hold_drums(system: Any, hold: bool) -> None:
    """Hold every driven drum's length (``hold``) or free it: a held length is a held
    coordinate (``system.fixed``, and the core's for the solvers built after)."""
    system.held_coordinates = tuple(system.drums.values()) if hold else ()
    system.core.hold_drums(bool(hold))


def refuse_static_drums(
    system: Any,
    y: NDArray | Sequence[float] | None,
    t: float | None,
    failed: Exception | None = None,
) -> None:
    """Statics with a driven drum: a failed solve (``y`` None) or a length ``L <= 0`` is one line
    naming the first drum's torque (no length at which the line holds it at rest)."""
    drums = getattr(system, "drums", {})
    if not drums or (y is not None and all(y[i] > 0 for i in drums.values())):
        return
    name = next(iter(drums))
    w = next(w for w in system.winches if w.name == name)
    f = w.torque if isinstance(w.torque, TimeFunction) else TimeFunction.constant(w.torque)
    torque = float(np.ravel(f.value(0.0 if t is None else t))[0])
    raise InputError(
        f"winches.{name}.torque",
        torque,
        "a torque the line holds at rest at some "
        "length L > 0 (statics: r T = torque; none found, the hanging weight "
        "cannot balance it): start the run from the reference, or change the "
        "torque",
    ) from failed
