"""Obstacles and contact of flexible bodies with them (``src/cpp/contact/contact.hpp``).

A flexible body (cable or rod elements) is a tube of its section's radius ``rt = sqrt(A / π)``
about its centre line.  Contact is a penalty line contact integrated along the curve: at
``contact_points`` Gauss points per element (default 8) the gap ``g`` to each obstacle gives the
force per reference length ``p n + f_t`` with the pressure ``p = p_k(g) <1 - χ ġ>`` (Hunt &
Crossley damping ``χ``, never pulling) and the regularized Coulomb friction
``f_t = -μ p v_t / sqrt(|v_t|² + ε²)`` (``v_t`` the slip velocity of the centre line relative to
the obstacle's material point there, ``ε`` = ``slip_velocity``).  The penalty ``p_k`` has the
stiffness ``k`` and a smooth onset over the depth ``d``: ``k g² / (2 d)`` for ``-d < g < 0``,
``k (-g - d / 2)`` deeper.  In a time step the pressure is the mean of ``p_k`` over an interval
of gaps centred on the generalized-α point's gap and ending at the step's end: on the linear
piece the generalized-α force itself, and with ``rho_inf = 1`` (the midpoint rule) the discrete
gradient of the penalty's potential, whose energy balance is then exact for a plane.  Statics
are frictionless (``[solver] static_friction``: the seabeds' friction as MoorPy's,
:mod:`rancf.solvers.static_friction`).

Penalty stiffness.  ``k`` [N/m²] (force per reference length per penetration) of a seabed
(a fixed plane in a ``[fluid]`` the body's own wet weight presses on) defaults to the weight
over 1 % of the diameter (:mod:`rancf.system.seabed`); of every other obstacle to ``E / 10``
of the body's Young's modulus: the order of the transverse stiffness of the section
itself pressed on a rigid surface.  Hertz's line contact of a solid circular section gives
``P / δ = π E / (2 (1 - ν²) (ln(4 rt / a) - 1/2))`` with the contact half-width ``a``, i.e.
``E / 4`` to ``E / 8`` for ``ln(4 rt / a)`` between 5 and 10 (every practical load); stranded
cables, ropes and hoses are softer across than a solid bar, so ``E / 10``.  Under a line load
``p`` the penetration is ``p / k + d / 2`` above ``p = k d / 2`` and ``sqrt(2 d p / k)`` below.

Onset.  ``d`` defaults to ``1e-3 rt``.  Without it a resting point of a stiff section would sink
by less than the Newton tolerance (a steel cable of radius 2 mm on the ground: 5e-11 m) and its
stiffness would switch on and off between the iterations; with it the point rests at
``sqrt(2 d q / k)`` (the same cable: 1.4e-8 m, 7e-6 of its radius) with the stiffness
``sqrt(2 k q / d)``, growing with the load as a Hertzian contact's does.

Friction regularization.  ``ε`` = ``slip_velocity`` defaults to 1 mm/s: at a slip velocity of
``7 ε`` the friction is 99 % of ``μ p``, at ``20 ε`` 99.9 % (a capstan's ratio ``e^{μφ}`` is then
0.1 % low); a part that sticks creeps at ``ε f / sqrt(1 - f²)`` where ``f`` is the used fraction
of ``μ p``.  Smaller ``ε`` sticks better but makes the Newton iterations of slip reversals fail
(1e-4 m/s does in the capstan example).

Time steps.  The penalty's oscillation is far above what any step resolves: use numerical
damping (``rho_inf`` about 0.5) and allow Newton 25 iterations (``max_newton``) for impacts.

Geometry: ``"plane"`` (``point``, outward ``normal``), ``"cylinder"`` (``center``, ``radius``;
3D ``axis``; a circle in 2D), ``"sphere"`` (3D: ``center``, ``radius``).  With ``body`` (a rigid
body of the system) the obstacle moves with it and ``point``/``center`` and ``normal``/``axis``
are in the body's frame, relative to its centre of mass (as its named points); otherwise world.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import NamedTuple

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels.contact_records import ContactBodyRecord, ContactRecord
from rancf.system.contact_view import ContactSystem
from rancf.system.parts.contact_pair import BodyPair, ContactPair
from rancf.system.parts.obstacle import (
    OBSTACLE_KINDS,
    Obstacle,
    _geometry,
    _number,
)

__all__ = [
    "Obstacle",
    "OBSTACLE_KINDS",
    "obstacle_records",
]


def _body_points(model: Model, n_c: int) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Shape functions (n_el, n_c, 4), their derivatives, Gauss weights and weights × |r0'|."""
    mesh = model.mesh
    xi, gw = gauss_legendre(n_c)
    n0, n1, _ = cable_shape_functions(mesh.weights, mesh.scales, xi)
    a0 = np.einsum("eqk,ekd->eqd", n1, mesh.element_nodal())
    w = gw[None, :] * np.linalg.norm(a0, axis=-1)
    return np.ascontiguousarray(n0), np.ascontiguousarray(n1), np.ascontiguousarray(gw), w


class ContactParts(NamedTuple):
    """A system's contact: the core's record, the obstacles' names, the pairs of a flexible
    body and an obstacle and the pairs of flexible bodies (Parts, :mod:`rancf.system.parts.
    contact_pair`)."""

    record: ContactRecord
    obstacle_names: list[str]
    pairs: list[ContactPair]
    body_pairs: list[BodyPair]


def build_contact(
    system: ContactSystem,
    obstacles: Sequence[Obstacle],
    contacts: Sequence[tuple[str, str]] | None,
    n_c: int,
    body_contacts: Sequence[tuple[str, str]] = (),
    body_friction: float = 0.0,
) -> ContactParts:
    """The core's contact record of a system, its obstacle names and its pairs in contact
    (:class:`ContactParts`).  ``body_contacts``:
    pairs of flexible bodies in contact with each other (a body twice: self-contact;
    ``src/cpp/contact/body_contact.hpp``) with the Coulomb coefficient ``body_friction``
    (regularized by
    :data:`SLIP_VELOCITY`), the stiffness ``E / 20`` of the softer (two sections in series, each
    ``E / 10``) and the onset ``1e-3`` of the thinner radius."""
    names = [ob.name or f"obstacle{i}" for i, ob in enumerate(obstacles)]
    if len(set(names)) != len(names):
        raise InputError("obstacles.name", names, "distinct names")
    if not (isinstance(n_c, int) and 1 <= n_c <= 64):
        raise InputError("contact_points", n_c, "an integer in 1 .. 64")
    obs = [ob.record(system, None, name) for ob, name in zip(obstacles, names, strict=True)]
    flex_names = [k for k, b in system.bodies.items() if isinstance(b, Model)]
    if contacts is None:
        pairs = [(f, o) for f in flex_names for o in names]
    else:
        pairs = []
        for pair in contacts:
            if len(pair) != 2 or pair[0] not in flex_names or pair[1] not in names:
                raise InputError(
                    "contacts", list(pair), "[FLEXIBLE_BODY, OBSTACLE] pairs of existing names"
                )
            pairs.append((pair[0], pair[1]))
    _number("body_friction", body_friction, 0.0, False)
    bpairs = []
    for pair in body_contacts:
        if len(pair) != 2 or not all(x in flex_names for x in pair):
            raise InputError("body_contacts", list(pair), "[FLEXIBLE_BODY, FLEXIBLE_BODY] pairs")
        bpairs.append(BodyPair(pair[0], pair[1], body_friction))
    parts = [ContactPair(f, obstacles[names.index(o)], o, names.index(o)) for f, o in pairs]
    record = ContactRecord(
        bodies=_contact_bodies(system, flex_names, {f for f, _ in pairs}, bpairs, n_c),
        obstacles=tuple(obs),
        pairs=tuple(p.record(system) for p in parts),  # Parts (system.part)
        body_pairs=tuple(p.record(system) for p in bpairs),
    )
    return ContactParts(record, names, parts, bpairs)


def _contact_bodies(
    system: ContactSystem, flex_names: list[str], on_obstacles: set[str], bpairs: list, n_c: int
) -> tuple[ContactBodyRecord, ...]:
    """Per flexible body, the core's contact record: its Gauss points (``n_c`` per element where
    it is in a pair, else none), radius, shape functions, weights; and, on a body in contact
    with bodies, its mesh's weights, scales and reference arc lengths."""
    curves = {x for p in bpairs for x in (p.a, p.b)}
    used = on_obstacles | curves
    out = []
    none = np.zeros(0)
    for name in flex_names:
        model = system.bodies[name]
        n0 = n1 = gw = w = none
        if name in used:
            if not model.family.gradient:
                raise InputError(
                    "contacts", name, "flexible bodies of cable or rod elements (not beam)"
                )
            if model.reduction is not None:
                raise InputError(
                    "contacts",
                    name,
                    "flexible bodies of C1 meshes (contact of a C2-reduced "
                    "mesh is not implemented)",
                )
            n0, n1, gw, w = _body_points(model, n_c)
        on = name in curves
        mesh = model.mesh
        out.append(
            ContactBodyRecord(
                n_c=n_c if name in used else 0,
                radius=float(model.section.radius),
                n=np.ascontiguousarray(n0.ravel()),
                n1=np.ascontiguousarray(n1.ravel()),
                gw=np.ascontiguousarray(gw.ravel()),
                w=np.ascontiguousarray(w.ravel()),
                weights=np.ascontiguousarray(mesh.weights, float).ravel() if on else none,
                scales=np.ascontiguousarray(mesh.scales, float).ravel() if on else none,
                arc0=np.r_[0.0, np.cumsum(w.sum(axis=1))] if on else none,
            )
        )
    return tuple(out)


def obstacle_records(system: ContactSystem) -> list[dict]:
    """Every obstacle of ``system`` as plain data (run metadata): ``name``, ``kind``, ``point``
    (plane point or centre) and ``direction`` (unit normal or axis; 3 components each, in the
    carrying body's frame if any), ``radius`` and ``body`` (the carrying body's name or None)."""
    out = []
    for ob, name in zip(system.obstacles, system.obstacle_names, strict=True):
        p, d, rad = _geometry(ob, system.dim)
        out.append(
            {
                "name": name,
                "kind": ob.kind,
                "point": p.tolist(),
                "direction": d.tolist(),
                "radius": rad,
                "body": ob.body,
            }
        )
    return out
