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
from dataclasses import dataclass
from typing import Any, Literal, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.rigid import RigidBody
from rancf.elements.cable import cable_shape_functions
from rancf.errors import InputError
from rancf.geometry.quadrature import gauss_legendre
from rancf.kernels import _core
from rancf.system.seabed import seabed_stiffness

__all__ = [
    "Obstacle",
    "OBSTACLE_KINDS",
    "obstacle_records",
]


class ContactSystem(Protocol):
    """What contact reads of a system (:class:`rancf.system.system.System`): it is built by the
    system, so it sees the system through this protocol rather than importing it."""

    dim: int
    bodies: dict[str, Any]
    rigid: list[Any]
    obstacles: tuple[Any, ...]
    obstacle_names: list[str]
    contact: Any

    def y_from_q(self, q: Any) -> NDArray[np.float64]: ...


OBSTACLE_KINDS = ("plane", "cylinder", "sphere")
_KIND = {k: i for i, k in enumerate(OBSTACLE_KINDS)}
#: Default penalty stiffness per Young's modulus (module docstring).
STIFFNESS_FACTOR = 0.1
#: Default onset width per tube radius (module docstring).
ONSET_FACTOR = 1e-3
#: Default regularization velocity ε of the friction [m/s].
SLIP_VELOCITY = 1e-3


@dataclass(frozen=True)
class Obstacle:
    """An obstacle (module docstring).

    Parameters
    ----------
    kind : {"plane", "cylinder", "sphere"}
    point, normal : (dim,)
        Plane: a point of it and its outward normal (need not be unit).
    center, radius :
        Cylinder (a circle in 2D) and sphere.
    axis : (3,)
        Cylinder in 3D.
    body : str, optional
        The rigid body that carries it (geometry then in its frame).
    friction : float
        Coulomb coefficient μ.
    stiffness : float, optional
        Penalty ``k`` [N/m²]; default: on a seabed (a fixed plane in a fluid facing up against
        the body's gravity) the body's wet weight over 1 % of its diameter
        (:func:`rancf.system.seabed.seabed_stiffness`), else a tenth of its Young's modulus.
    onset : float, optional
        Width ``d`` [m] of the pressure's smooth onset; default 1e-3 of each body's radius.
    damping : float
        Hunt–Crossley factor ``χ`` [s/m]: the pressure is ``k <-g> (1 + χ <-ġ>)`` while the
        point approaches the obstacle (``ġ < 0``), so impacts lose energy and nothing pulls.
    damping_normal : float
        Linear normal damping ``c`` per unit contact area [Pa s/m] while in contact, as
        MoorDyn's seabed ``cBot``: the force per length ``p - c D ġ`` (``D`` the tube's
        diameter, the contact width), never pulling.
    slip_velocity : float
        Regularization ``ε`` of the friction [m/s] (module docstring).
    name : str
    """

    kind: Literal["plane", "cylinder", "sphere"]
    point: Sequence[float] | None = None
    normal: Sequence[float] | None = None
    center: Sequence[float] | None = None
    radius: float | None = None
    axis: Sequence[float] | None = None
    body: str | None = None
    friction: float = 0.0
    stiffness: float | None = None
    onset: float | None = None
    damping: float = 0.0
    damping_normal: float = 0.0
    slip_velocity: float = SLIP_VELOCITY
    name: str = ""


def _vec(key: str, v: Sequence[float] | None, dim: int, unit: bool = False) -> NDArray:
    a = np.asarray([] if v is None else v, dtype=float)
    if a.shape != (dim,) or not np.all(np.isfinite(a)) or (unit and not np.linalg.norm(a) > 0):
        what = "a nonzero vector" if unit else "a point"
        raise InputError(key, None if v is None else list(v), f"{what} of {dim} finite numbers")
    a = np.r_[a, np.zeros(3 - dim)]
    return a / np.linalg.norm(a) if unit else a


def _number(key: str, v: float | None, lo: float, strict: bool) -> float:
    ok = v is not None and np.isfinite(v) and (v > lo if strict else v >= lo)
    if not ok:
        raise InputError(key, v, f"a finite number {'>' if strict else '>='} {lo:g}")
    return float(v)  # type: ignore[arg-type]


def _geometry(ob: Obstacle, dim: int) -> tuple[NDArray, NDArray, float]:
    """(point, direction, radius) of an obstacle, 3 components each."""
    key = f"obstacles.{ob.name or ob.kind}"
    if ob.kind not in OBSTACLE_KINDS:
        raise InputError("obstacles.kind", ob.kind, f"one of {', '.join(OBSTACLE_KINDS)}")
    if ob.kind == "plane":
        return _vec(f"{key}.point", ob.point, dim), _vec(f"{key}.normal", ob.normal, dim, True), 0.0
    if ob.kind == "sphere" and dim == 2:
        raise InputError(f"{key}.kind", "sphere", 'a 3D system (in 2D a circle is "cylinder")')
    center = _vec(f"{key}.center", ob.center, dim)
    radius = _number(f"{key}.radius", ob.radius, 0.0, True)
    if ob.kind == "sphere":
        return center, np.array([0.0, 0.0, 1.0]), radius
    if dim == 2:
        if ob.axis is not None:
            raise InputError(f"{key}.axis", list(ob.axis), "none in 2D (a circle in the plane)")
        return center, np.array([0.0, 0.0, 1.0]), radius
    return center, _vec(f"{key}.axis", ob.axis, 3, True), radius


def _body_points(model: Model, n_c: int) -> tuple[NDArray, NDArray, NDArray, NDArray]:
    """Shape functions (n_el, n_c, 4), their derivatives, Gauss weights and weights × |r0'|."""
    mesh = model.mesh
    xi, gw = gauss_legendre(n_c)
    n0, n1, _ = cable_shape_functions(mesh.weights, mesh.scales, xi)
    a0 = np.einsum("eqk,ekd->eqd", n1, mesh.element_nodal())
    w = gw[None, :] * np.linalg.norm(a0, axis=-1)
    return np.ascontiguousarray(n0), np.ascontiguousarray(n1), np.ascontiguousarray(gw), w


def build_contact(
    system: ContactSystem,
    obstacles: Sequence[Obstacle],
    contacts: Sequence[tuple[str, str]] | None,
    n_c: int,
    body_contacts: Sequence[tuple[str, str]] = (),
    body_friction: float = 0.0,
) -> tuple[_core.Contact, list[str], list[tuple[str, str]]]:
    """The core's contact data of a system: (Contact, obstacle names, pairs).  ``body_contacts``:
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
    dim = system.dim
    kinds, bodies, points, dirs, radii = [], [], [], [], []
    for ob, name in zip(obstacles, names, strict=True):
        p, d, rad = _geometry(ob, dim)
        body = -1
        if ob.body is not None:
            b = system.bodies.get(ob.body)
            if not isinstance(b, RigidBody):
                raise InputError(f"obstacles.{name}.body", ob.body, "the name of a rigid body")
            body = system.rigid.index(b)
        for key, v in (
            ("friction", ob.friction),
            ("damping", ob.damping),
            ("damping_normal", ob.damping_normal),
        ):
            _number(f"obstacles.{name}.{key}", v, 0.0, False)
        _number(f"obstacles.{name}.slip_velocity", ob.slip_velocity, 0.0, True)
        for key, given in (("stiffness", ob.stiffness), ("onset", ob.onset)):
            if given is not None:
                _number(f"obstacles.{name}.{key}", given, 0.0, True)
        kinds.append(_KIND[ob.kind])
        bodies.append(body)
        points.append(p)
        dirs.append(d)
        radii.append(rad)
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
        bpairs.append((pair[0], pair[1]))
    used = {f for f, _ in pairs} | {x for p in bpairs for x in p}
    curves = {x for p in bpairs for x in p}
    keys = ("nc", "radius", "n", "n1", "gw", "w", "weights", "scales", "arc0")
    lists: dict[str, list] = {k: [] for k in keys}
    for name in flex_names:
        model = system.bodies[name]
        n0 = n1 = gw = w = np.zeros(0)
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
        lists["nc"].append(n_c if name in used else 0)
        lists["radius"].append(model.section.radius)
        for key, arr in (("n", n0), ("n1", n1), ("gw", gw), ("w", w)):
            lists[key].append(np.ascontiguousarray(arr.ravel()))
        mesh = model.mesh
        on = name in curves
        lists["weights"].append(
            np.ascontiguousarray(mesh.weights, float).ravel() if on else np.zeros(0)
        )
        lists["scales"].append(np.ascontiguousarray(mesh.scales, float) if on else np.zeros(0))
        lists["arc0"].append(np.r_[0.0, np.cumsum(w.sum(axis=1))] if on else np.zeros(0))
    data = []
    for f, o in pairs:
        ob = obstacles[names.index(o)]
        k = ob.stiffness
        if k is None:
            k = seabed_stiffness(system, f, ob, dirs[names.index(o)])
        if k is None:
            k = STIFFNESS_FACTOR * system.bodies[f].material.youngs_modulus
        rt = system.bodies[f].section.radius
        onset = ONSET_FACTOR * rt if ob.onset is None else ob.onset
        cn = ob.damping_normal * 2.0 * rt  # per area to per length: the contact width D
        data.append([k, onset, ob.damping, ob.friction, ob.slip_velocity, cn])
    i64 = np.int64
    core = _core.Contact(
        body_nc=lists["nc"],
        body_radius=lists["radius"],
        body_n=lists["n"],
        body_n1=lists["n1"],
        body_gw=lists["gw"],
        body_w=lists["w"],
        ob_kind=np.array(kinds, dtype=i64),
        ob_body=np.array(bodies, dtype=i64),
        ob_point=np.array(points, dtype=float).reshape(-1, 3),
        ob_dir=np.array(dirs, dtype=float).reshape(-1, 3),
        ob_radius=np.array(radii, dtype=float),
        pair_flex=np.array([flex_names.index(f) for f, _ in pairs], dtype=i64),
        pair_obstacle=np.array([names.index(o) for _, o in pairs], dtype=i64),
        pair_data=np.array(data, dtype=float).reshape(-1, 6),
        body_weights=lists["weights"],
        body_scales=lists["scales"],
        body_arc0=lists["arc0"],
        bpair_a=np.array([flex_names.index(a) for a, _ in bpairs], dtype=i64),
        bpair_b=np.array([flex_names.index(b) for _, b in bpairs], dtype=i64),
        bpair_data=np.array(
            [_body_pair_data(system, a, b, body_friction) for a, b in bpairs], dtype=float
        ).reshape(-1, 4),
    )
    return core, names, pairs


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


def _body_pair_data(system: ContactSystem, a: str, b: str, friction: float) -> list[float]:
    """Stiffness, onset, friction and slip velocity of two flexible bodies in contact
    (:func:`build_contact`)."""
    ma, mb = system.bodies[a], system.bodies[b]
    k = 0.5 * STIFFNESS_FACTOR * min(ma.material.youngs_modulus, mb.material.youngs_modulus)
    onset = ONSET_FACTOR * min(ma.section.radius, mb.section.radius)
    return [k, onset, friction, SLIP_VELOCITY]
