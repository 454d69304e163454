"""The compiled core's :class:`rancf.kernels._core.System` of a :class:`rancf.system.System`:
its parts as the named arrays of the constructor (``src/cpp/bindings_system.cpp``)."""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from rancf.bodies.rigid import PointMass, RigidBody
from rancf.bodies.time_function import TimeFunction, pack
from rancf.kernels import _core
from rancf.system.contact import Obstacle, build_contact

if TYPE_CHECKING:
    from rancf.system.system import System

__all__ = ["build_core", "attach_contact"]


def build_core(
    system: System, rows: Any, joints: list[dict], tfs: list[TimeFunction]
) -> _core.System:
    """The core system of ``system``: places and time functions of ``rows``, the joints'
    records ``joints`` (:func:`rancf.system.joint_data.joint_data`), ``tfs`` the time functions
    the core evaluates."""
    i64 = np.int64
    pl = rows.places
    rigid = system.rigid
    spring = system._spring_rows
    loads = system._load_rows
    pre = system._prescribed
    return _core.System(
        dim=system.dim,
        models=[b.core for b in system.flex],
        rigid_point_mass=np.array([isinstance(b, PointMass) for b in rigid], dtype=i64),
        rigid_dim=np.array([b.dim for b in rigid], dtype=i64),
        rigid_mass=np.array([b.mass for b in rigid], dtype=float),
        rigid_inertia=np.array(
            [b.inertia_vector() if isinstance(b, RigidBody) else np.zeros(3) for b in rigid]
        ).reshape(-1, 3),
        place_kind=np.array([p[0] for p in pl], dtype=i64),
        place_body=np.array([p[1] for p in pl], dtype=i64),
        place_node=np.array([p[2] for p in pl], dtype=i64),
        place_point=np.array([p[3] for p in pl], dtype=float).reshape(-1, 3),
        place_motion=np.array([p[4] for p in pl], dtype=i64),
        place_angle0=np.array([p[5] for p in pl], dtype=float),
        joint_kind=np.array([j["kind"] for j in joints], dtype=i64),
        joint_a=np.array([j["a"] for j in joints], dtype=i64),
        joint_b=np.array([j["b"] for j in joints], dtype=i64),
        joint_driven=np.array([j["driven"] for j in joints], dtype=i64),
        joint_angle=np.array([j["angle"] for j in joints], dtype=i64),
        joint_beta0=np.array([j["beta0"] for j in joints], dtype=float),
        joint_rel=np.array([j["rel"] for j in joints], dtype=float).reshape(-1, 9),
        joint_axis_a=np.array([j["axis_a"] for j in joints], dtype=float).reshape(-1, 3),
        joint_normals_b=np.array([j["normals_b"] for j in joints], dtype=float).reshape(-1, 6),
        joint_w_a=np.array([j["w_a"] for j in joints], dtype=float).reshape(-1, 3),
        joint_w_b=np.array([j["w_b"] for j in joints], dtype=float).reshape(-1, 3),
        spring_a=np.array([s[0] for s in spring], dtype=i64),
        spring_b=np.array([s[1] for s in spring], dtype=i64),
        spring_data=np.array([s[2:] for s in spring], dtype=float).reshape(-1, 3),
        load_place=np.array([ld[0] for ld in loads], dtype=i64),
        load_force=np.array([ld[1] for ld in loads], dtype=float).reshape(-1, 3),
        load_torque=np.array([ld[2] for ld in loads], dtype=float).reshape(-1, 3),
        load_factor=np.array([ld[3] for ld in loads], dtype=i64),
        **pack(tfs),
        pre_coord=np.array([p[0] for p in pre], dtype=i64),
        pre_tf=np.array([p[1] for p in pre], dtype=i64),
        pre_comp=np.array([p[2] for p in pre], dtype=i64),
        pre_base=np.array([p[3] for p in pre], dtype=float),
        lin_row=system._linear[0],
        lin_col=system._linear[1],
        lin_coef=system._linear[2],
        gravity=np.ascontiguousarray(system.gravity),
        damping=system.damping,
        y_ref=system.y0,
    )


def attach_contact(
    system: System,
    obstacles: Sequence[Obstacle],
    contacts: Sequence[tuple[str, str]] | None,
    n_c: int,
    body_contacts: Sequence[tuple[str, str]] = (),
    body_friction: float = 0.0,
) -> tuple[_core.Contact | None, list[str], list[tuple[str, str]]]:
    """The contact data of ``system`` (:func:`rancf.system.contact.build_contact`: the core's
    :class:`rancf.kernels._core.Contact`, obstacle names, pairs) attached to its core; ``(None,
    [], [])`` without obstacles."""
    if not obstacles and not contacts and not body_contacts:
        return None, [], []
    contact, names, pairs = build_contact(
        system, obstacles, contacts, n_c, body_contacts, body_friction
    )
    system.core.attach_contact(contact)
    return contact, names, pairs
