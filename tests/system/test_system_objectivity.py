"""Objectivity of joints: a rigid motion of a whole system (every body
turned by the same rotation Q and moved by c) keeps every joint between bodies satisfied and
gives no elastic force.  That the reactions turn with the system (F -> Q F) is shown on a
loaded frame of rods solved in two orientations (tests/system/test_system_balance.py)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from rancf.bodies.flexible import Material, Model, Section
from rancf.bodies.rigid import PointMass, RigidBody, quaternion_from_matrix
from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.mesh.factories import mesh_line
from rancf.system import Joint, System

SEC, MAT = Section.circular(0.01), Material(1000.0, 1e7)


def planar() -> System:
    cable = Model(mesh_line([0, 0], [1, 0], 3), "rancf", SEC, MAT, [])
    beam = Model(mesh_line([1, 0], [1.5, 0.5], 2), "beam", SEC, MAT, [])
    rot = np.array([[np.cos(0.3), -np.sin(0.3)], [np.sin(0.3), np.cos(0.3)]])
    pos = np.array([1.5, 0.5]) - rot @ [-0.2, 0.0]  # link:a at the beam's end
    link = RigidBody(2, 1.5, 0.02, tuple(pos), 0.3, points={"a": (-0.2, 0.0), "b": (0.2, 0.1)})
    axis = np.array([1.0, 0.3])
    mass = PointMass(2, 0.5, tuple(pos + rot @ [0.2, 0.1] + 0.3 * axis / np.linalg.norm(axis)))
    joints = [
        Joint("fixed", ("cable:end", "beam:start")),
        Joint("pin", ("beam:end", "link:a")),
        Joint("slider", ("mass", "link:b"), axis=(1.0, 0.3)),
    ]
    return System({"cable": cable, "beam": beam, "link": link, "mass": mass}, joints)


def spatial() -> System:
    cable = Model(mesh_line([0, 0, 0], [1, 0.2, 0.1], 3), "rancf", SEC, MAT, [])
    r0 = Rotation.from_rotvec([0.2, -0.4, 0.3]).as_matrix()
    a, b = np.array([-0.3, -0.2, -0.1]), np.array([0.1, 0.2, 0.0])
    pos = np.array([1.0, 0.2, 0.1]) - r0 @ a  # body:a at the cable's end
    link_pos = np.array([1.6, 0.9, 0.4])
    c = pos + r0 @ b - link_pos  # link:c at body:b
    body = RigidBody(
        3, 2.0, (0.1, 0.2, 0.3), tuple(pos), r0.tolist(), points={"a": tuple(a), "b": tuple(b)}
    )
    link = RigidBody(
        3,
        1.0,
        (0.05, 0.1, 0.1),
        tuple(link_pos),
        0.0,
        points={"c": tuple(c), "d": tuple(-link_pos)},
    )
    mass = PointMass(3, 0.5, tuple(link_pos + 0.3 * np.array([0.0, 1.0, 1.0]) / np.sqrt(2)))
    joints = [
        Joint("pin", ("cable:end", "body:a")),
        Joint("fixed", ("cable:start", "link:d")),  # a cable's tangent held by a frame
        Joint("revolute", ("body:b", "link:c"), axis=(0.0, 0.0, 1.0)),
        Joint("slider", ("mass", "link"), axis=(0.0, 1.0, 1.0)),
    ]
    return System({"cable": cable, "body": body, "link": link, "mass": mass}, joints)


def _moved(s: System, rot: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The reference configuration moved rigidly: x -> rot x + c (model coordinates)."""
    d = s.dim
    y = s.y0.copy()
    for name in s.names:
        b, sl = s.bodies[name], s.body_slice(name)
        u = y[sl]
        if isinstance(b, Model):
            nodes = u.reshape(b.n_nodes, b.dpn)
            nodes[:, :d] = nodes[:, :d] @ rot.T + c
            if b.element == "beam":
                nodes[:, 2] += np.arctan2(rot[1, 0], rot[0, 0])
            else:
                nodes[:, d : 2 * d] = nodes[:, d : 2 * d] @ rot.T
        elif isinstance(b, PointMass):
            u[:d] = rot @ u[:d] + c
        else:
            u[:d] = rot @ u[:d] + c
            if d == 2:
                u[2] += np.arctan2(rot[1, 0], rot[0, 0])
            else:
                old = Rotation.from_quat(u[3:7][[1, 2, 3, 0]]).as_matrix()
                u[3:7] = quaternion_from_matrix(rot @ old)
    return y


@pytest.mark.parametrize("build", [planar, spatial])
def test_rigid_motion_keeps_every_joint(build):
    s = build()
    d = s.dim
    if d == 2:
        a = 0.7
        rot = np.array([[np.cos(a), -np.sin(a)], [np.sin(a), np.cos(a)]])
        c = np.array([0.3, -1.2])
    else:
        rot = Rotation.from_rotvec([0.5, -0.8, 1.1]).as_matrix()
        c = np.array([0.3, -1.2, 2.0])
    y = _moved(s, rot, c)
    g = np.empty(s.m)
    s.core.constraints(y, 0.0, g)
    assert np.abs(g).max() <= 1e-13
    # no elastic force: the balance at rest without loads is zero on the bodies' rows
    r = np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, np.zeros(s.m), r), ResidualOptions(0.0, dynamic=False))
    assert np.abs(r[: s.n]).max() <= 1e-6  # EA = 7.85e2 N: round-off of the strains
