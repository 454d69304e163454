"""A validated scenario turned into a :class:`rancf.system.System` (the system solver's input).

Every scenario is a system: a file without ``[[bodies]]`` is one flexible body named ``body``
(its supports, loads and sensors written as today); with ``[[bodies]]``:

* a flexible body becomes a :class:`~rancf.bodies.flexible.Model` (keys ``bodies[i].…``) carrying
  the supports, point loads and initial velocities at its nodes, ``[loads] gravity`` and the
  ``[damping]`` (its strain-rate keys, or a body's own ``[bodies.damping]``, on each flexible
  body);
* a rigid body a :class:`~rancf.bodies.rigid.RigidBody` (``orientation_deg`` in degrees in 2D;
  the rotation matrix's rows in 3D), a point mass a :class:`~rancf.bodies.rigid.PointMass`;
* a support at a rigid body's place or a point mass is a joint to the ground: a ``pin`` a pin,
  a ``clamp`` a fixed joint, a ``roller`` a slider along its ``axis``; its ``motion`` moves the
  ground point;
* a point load at a rigid place is a system load (``moment``: a torque; ``time``: its factor);
  ``frequency_hz`` belongs to flexible bodies (on a rigid body give ``time = { harmonic }``);
* joints and springs as written; sensor places on rigid bodies are observed by the system;
* ``[[obstacles]]`` become :class:`~rancf.system.Obstacle` (``contacts`` the pairs).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from contextlib import contextmanager
from typing import Any

import numpy as np

from rancf.bodies.rigid import PointMass, RigidBody
from rancf.bodies.support_kinds import support_kind
from rancf.errors import InputError, ScenarioError
from rancf.scenario.build import body_model
from rancf.scenario.fluid import fluid_value, hydro_value
from rancf.scenario.places import ONE_BODY
from rancf.scenario.surface import is_surface
from rancf.scenario.view import ScenarioView
from rancf.scenario.winches import system_winches, winch_key
from rancf.system import Joint, Load, Place, Spring, System
from rancf.system.parts.joint_kinds import joint_kind

__all__ = ["build_system", "scenario_keys", "support_labels", "ONE_BODY"]


#: The places of a shell (:mod:`rancf.scenario.places`): its supports and loads are its model's.
SHELL_PLACES = ("edge", "surface")


def _rigid(b: Any, dim: int) -> RigidBody | PointMass:
    if b.kind == "mass":
        return PointMass(dim, b.mass, tuple(b.position), _tuple(b.velocity))
    if dim == 2:
        orient: Any = math.radians(b.orientation_deg or 0.0)
    else:
        orient = tuple(tuple(r) for r in b.orientation) if b.orientation is not None else 0.0
    return RigidBody(
        dim,
        b.mass,
        b.inertia if dim == 2 else tuple(b.inertia),
        tuple(b.position),
        orient,
        _tuple(b.velocity),
        b.angular_velocity
        if not isinstance(b.angular_velocity, list)
        else tuple(b.angular_velocity),
        {k: tuple(v) for k, v in b.points.items()},
    )


def _tuple(v: Any) -> tuple[float, ...] | None:
    return None if v is None else tuple(v)


def support_labels(sc: ScenarioView) -> dict[str, list[int | str]]:
    """The supports' ``at`` as written, per flexible body (reaction column names)."""
    out: dict[str, list[int | str]] = {}
    for i, s in enumerate(sc.supports):
        p = sc.support_place(i)
        held = s.rotation is None  # a turning clamp is a joint (_support_joints)
        if p.where == "node" and p.body is not None and held:  # (a node place names its body)
            out.setdefault(p.body, []).append(s.at)
    return out


@contextmanager
def scenario_keys(sc: ScenarioView) -> Iterator[None]:
    """Within it, an :class:`~rancf.errors.InputError` (building or solving the system of
    ``sc``) becomes a :class:`~rancf.errors.ScenarioError` naming the file and the scenario key
    (a winch by its table, ``winches[i]``)."""
    try:
        yield
    except InputError as exc:
        raise ScenarioError(
            sc.path, winch_key(sc.winches, exc.parameter), f"{exc.allowed} (got {exc.value!r})"
        ) from None


def build_system(sc: ScenarioView) -> System:
    """The system of a scenario (module docstring), carrying its warnings of impulsive starts
    (:attr:`System.start_warnings`); errors name the scenario key."""
    with scenario_keys(sc):
        system = _build(sc)
    system.start_warnings = tuple(getattr(sc, "warnings", ()))
    return system


def _observed(sc: ScenarioView) -> list[Place]:
    out = []
    for sen in sc.sensors:
        for text in sen.places:
            p = sc.place(text)
            if p.where == "point":
                out.append(p.system_place())
    return out


def _build(sc: ScenarioView) -> System:
    if any(b.kind == "flexible" and is_surface(b.geometry) for _, b in sc.body_tables):
        from rancf.scenario.shell_build import refuse_shells  # loaded with a shell only

        refuse_shells(sc)
    gravity, damping = sc.loads.gravity, sc.damping.mass_proportional
    beta = sc.damping.stiffness_proportional
    bodies: dict[str, Any] = {}
    for i, (_, b) in enumerate(sc.body_tables):
        bodies[b.name] = body_model(sc, i) if b.kind == "flexible" else _rigid(b, sc.dim)
    _held_once_by_joints(sc, bodies)
    return System(
        bodies,
        gravity=gravity,
        damping=damping,
        stiffness_damping=beta,
        horizon=sc.solver.t_end,
        **_parts(sc, bodies),
    )


def _held_once_by_joints(sc: ScenarioView, bodies: dict[str, Any]) -> None:
    """Refuse a joint between the ground and a supported place, or a second joint between the
    same two places, naming both keys: its rows repeat the support's or the other joint's (a
    redundant constraint: the Newton matrix is singular, the solves failed with no key named),
    as two supports at one place are refused."""

    def where(text: Any) -> tuple[Any, ...]:
        p = sc.place(text)
        if p.where != "node":
            return (p.where, p.body, p.point, p.edge, p.uv)
        n, node = bodies[str(p.body)].n_nodes, int(p.node or 0)  # a node place has its node
        return ("node", p.body, node % n if -n <= node < n else node)

    def refuse(key: str, done: str, again: str) -> None:
        raise ScenarioError(
            sc.path,
            key,
            f"{done} already: {again} (a redundant constraint: the solves would fail); remove "
            "one of them",
        )

    held = {where(t["at"]): f"supports[{i}]" for i, t in enumerate(sc.data["supports"])}
    pairs: dict[frozenset[tuple[Any, ...]], str] = {}
    for i, j in enumerate(sc.joints):
        if j.kind == "sliding":
            continue
        ends = [where(text) for text in j.between]
        for k, text in enumerate(j.between):
            if ends[1 - k][0] == "ground" and ends[k] in held:
                where_k = f"joints[{i}].between[{k}]"
                done = f"{text!r} is held by {held[ends[k]]}"
                refuse(where_k, done, "a joint to the ground there holds it again")
        pair = frozenset(ends)
        if pair in pairs:
            a, b = j.between
            done = f"{a!r} and {b!r} are joined by {pairs[pair]}"
            refuse(f"joints[{i}].between", done, "a second joint between them holds them again")
        pairs[pair] = f"joints[{i}]"


def _parts(sc: ScenarioView, bodies: dict[str, Any]) -> dict[str, Any]:
    """Joints (with supports of rigid places), springs, loads on rigid places, observed places."""

    def place(text: Any) -> Place:
        return sc.place(text).system_place()

    joints = _support_joints(sc, bodies)
    for j, jd in zip(sc.joints, sc.data["joints"], strict=True):
        if joint_kind(j.kind).slides:  # a flexible body (by name) through a place
            body = Place(str(j.between[0]))
            pos = None if j.position is None else tuple(j.position)
            joints.append(Joint("sliding", (body, place(j.between[1])), name=j.name, position=pos))
            continue
        axis = None if j.axis is None else tuple(j.axis)
        joints.append(
            Joint(j.kind, (place(j.between[0]), place(j.between[1])), axis, jd["angle"], j.name)
        )
    springs = [
        Spring(
            (place(s.between[0]), place(s.between[1])),
            s.stiffness,
            s.damping,
            s.length,
            s.name or f"spring{k}",
        )
        for k, s in enumerate(sc.springs)
    ]
    loads = []
    for k, (ld, t) in enumerate(zip(sc.loads.point, sc.data["loads"]["point"], strict=True)):
        p = sc.place(ld.at)
        if p.where in ("node", *SHELL_PLACES):  # the body's own load vector
            continue
        if ld.frequency_hz is not None:
            raise ScenarioError(
                sc.path,
                f"loads.point[{k}].frequency_hz",
                "applies to flexible bodies; on a rigid body give time = { harmonic = F }",
            )
        moment = ld.moment
        torque = None if moment is None else tuple(np.atleast_1d(moment).tolist())
        loads.append(Load(place(ld.at), _tuple(ld.force), torque, t["time"]))
    obstacles = []
    if sc.obstacles:
        from rancf.system.contact import Obstacle

        obstacles = [Obstacle(**_record_fields(o.plain())) for o in sc.obstacles]
    contacts = None if sc.contacts is None else [(a, b) for a, b in sc.contacts]
    return {
        "joints": joints,
        "springs": springs,
        "loads": loads,
        "observe": _observed(sc),
        "obstacles": obstacles,
        "contacts": contacts,
        "body_contacts": [(a, b) for a, b in sc.body_contacts],
        "contact_points": sc.contact_points,
        "body_friction": sc.body_friction,
        "winches": system_winches(sc, bodies),
        **_fluid(sc, bodies),
    }


def _support_joints(sc: ScenarioView, bodies: dict[str, Any]) -> list[Joint]:
    """The supports that are joints to the ground: at a rigid body's place or a point mass (a
    ``pin`` a pin, a ``clamp`` a fixed joint, a ``roller`` a slider; named ``supportI``), and a
    clamp with a ``rotation`` at a flexible body's node (a fixed joint to a frame turned by the
    rotation, ``docs/derivations/clamp-paths.md`` §2; named by its place as written, so its
    reaction columns are a support's).  A ``motion`` moves the ground point; one of absolute
    positions is made the displacement from the place's reference point."""
    from rancf.scenario.motions import absolute_motion
    from rancf.system.stack import BodyStack

    stack, joints = BodyStack(bodies), []
    static = sc.solver.initial_state == "static"
    for i, s in enumerate(sc.supports):
        p, d = sc.support_place(i), sc.data["supports"][i]
        if p.where in ("ground", *SHELL_PLACES) or (p.where == "node" and s.rotation is None):
            continue  # held by the body's model (a shell's: rancf.bodies.shell_model)
        at = p.system_place()
        motion = d["motion"]
        if d["absolute"]:
            ref = stack.reference_position(stack.resolve(at))
            motion = absolute_motion(motion, ref, f"supports[{i}].motion", static)
        rot = d["rotation"]
        if rot is not None and (rot.size, rot.vector) != ((1, False) if sc.dim == 2 else (3, True)):
            what = "the angle about z (a number)" if sc.dim == 2 else "a rotation vector of 3"
            raise InputError(f"supports[{i}].rotation", f"{rot.size} components", f"{what} [rad]")
        label = f"node{s.at}" if isinstance(s.at, int) else str(s.at)  # as a support's columns
        name = f"support{i}" if p.where != "node" else label
        axis = None if s.axis is None else tuple(s.axis)
        kind = support_kind(s.kind).joint
        joints.append(
            Joint(kind, (at, Place(None)), axis, None, name, motion, rotation=d["rotation"])
        )
    return joints


def _fluid(sc: ScenarioView, bodies: dict[str, Any]) -> dict[str, Any]:
    """The fluid, the flexible bodies' coefficients and the distributed loads."""
    from pydantic_core import PydanticCustomError

    try:
        fluid = fluid_value(sc.fluid, sc.dim)
    except PydanticCustomError as exc:
        ctx = exc.context or {}
        raise ScenarioError(
            sc.path, f"fluid.{ctx.get('key', '')}", str(ctx.get("problem"))
        ) from None
    hydro = {
        b.name: hydro_value(b.hydro)
        for _, b in sc.body_tables
        if getattr(b, "hydro", None) is not None
    }
    dist = []
    if sc.data["loads"]["distributed"]:
        from rancf.system.fluid import DistributedLoad

        shells = {
            b.name for _, b in sc.body_tables if b.kind == "flexible" and is_surface(b.geometry)
        }
        lines = {b.name for _, b in sc.body_tables if b.kind == "flexible"} - shells
        dist = [  # a shell's are in its own load vector (rancf.scenario.shell_build)
            DistributedLoad(tuple(d["force"]), d["body"], d["time"])
            for d in sc.data["loads"]["distributed"]
            if d["body"] not in shells and (d["body"] is not None or lines)
        ]
    _check_depth(sc, fluid, {k: bodies.get(k) for k in hydro})
    return {"fluid": fluid, "hydro": hydro, "distributed": dist}


def _check_depth(sc: ScenarioView, fluid: Any, wet: dict[str, Any]) -> None:
    """Refuse waves whose water ``depth`` puts the sea floor above a node of a body in the
    fluid (``wet``: the bodies with hydrodynamic coefficients): Airy kinematics hold between
    the floor and the surface only (below it they grow without bound)."""
    waves = None if fluid is None else fluid.waves
    if waves is None or fluid.surface is None:
        return
    floor = fluid.surface - waves.depth
    for name, body in wet.items():
        if body is None:
            continue
        z = body.node_positions(body.q0)[:, -1]
        low = float(z.min())
        if low < floor - 1e-9 * max(1.0, abs(floor)):
            raise ScenarioError(
                sc.path,
                "fluid.waves.depth",
                f"must reach the bodies in the "
                f"fluid: depth = {waves.depth:g} m puts the floor at "
                f"{floor:g} m, above {name}'s node at {low:g} m (give depth "
                f">= {fluid.surface - low:g} m)",
            )


def _record_fields(table: dict[str, Any]) -> dict[str, Any]:
    """A table's values as fields of a frozen record (lists as tuples)."""
    return {k: tuple(v) if isinstance(v, list) else v for k, v in table.items()}
