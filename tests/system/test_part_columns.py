"""The reaction columns of a run are its parts' own: every part names its columns
(``Part.sensors``) in the order of ``System.parts``, the outputs write exactly those, and a
part's values at a static state (``Part.reactions``) are the outputs' values there, column for
column: supports (a clamp, a pin), joints (a pin, a fixed and a driven one), an obstacle and a
pair of bodies in contact."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.rigid import PointMass, RigidBody
from rancf.bodies.time_function import TimeFunction
from rancf.mesh.factories import mesh_line
from rancf.system import Joint, Obstacle, System
from rancf.system.outputs import SystemOutputs

R = 0.002


def _cable(y: float, n: int, x0: float, x1: float, supports: list) -> Model:
    return Model(
        mesh_line([x0, y], [x1, y], n),
        "rancf",
        Section.circular(R),
        Material(7850.0, 2e11),
        supports,
        gravity=[0, -9.81],
    )


def _system() -> System:
    a = _cable(0.0, 6, 0.0, 1.0, [Support(0, "clamp")])
    b = _cable(2 * R - 2e-6, 5, 0.2, 0.8, [Support(-1, "pin")])
    bodies = {
        "a": a,
        "b": b,
        "bob": PointMass(2, 0.5, (1.0, 0.0)),
        "arm": RigidBody(2, 1.0, 0.01, (0.2, 2 * R - 2e-6 + 0.5), points={"tip": (0.0, -0.5)}),
    }
    joints = [
        Joint("pin", ("a:end", "bob"), name="hang"),
        Joint("fixed", ("arm", "ground")),
        Joint("pin", ("arm:tip", "b:start"), angle=TimeFunction.constant(0.0), name="drive"),
    ]
    floor = Obstacle("plane", point=[0.0, -R + 1e-6], normal=[0.0, 1.0], name="floor")
    return System(
        bodies,
        joints=joints,
        obstacles=[floor],
        contacts=[("a", "floor")],
        body_contacts=[("a", "b")],
        gravity=[0.0, -9.81],
    )


def test_the_outputs_columns_are_the_parts_columns_in_order():
    s = _system()
    out = SystemOutputs(s)
    mine = [c for p in s.parts for c in p.sensors(s)]
    assert out.reaction_names == mine
    assert mine[:3] == ["a:start_fx", "a:start_fy", "a:start_mz"]  # a clamp: its moment
    assert mine[3:5] == ["b:end_fx", "b:end_fy"]  # a pin: none
    assert mine[5:7] == ["hang_fx", "hang_fy"]
    assert mine[7:10] == ["joint1_fx", "joint1_fy", "joint1_mz"]  # unnamed: its position
    assert mine[10:13] == ["drive_fx", "drive_fy", "drive_mz"]  # driven: a moment
    assert mine[13:20] == [
        f"floor_{x}"
        for x in ("normal_x", "normal_y", "friction_x", "friction_y", "mz", "length", "penetration")
    ]
    assert mine[20:] == ["a_b_contact_force", "a_b_penetration"]


def test_a_parts_values_at_a_static_state_are_the_outputs_values():
    s = _system()
    out = SystemOutputs(s, labels={"b": ["far"]})
    rng = np.random.default_rng(5)
    y = s.y0 + 1e-4 * rng.standard_normal(s.n) * ~s.fixed
    lam = rng.standard_normal(s.m)
    row = out.rows(np.array([0.7]), s.q_from_y(y)[None], lam=lam[None], static=True)["r"][0]
    mine = {}
    for p in s.labelled_parts(out.labels):
        mine.update(p.reactions(s, y, lam, 0.7))
    assert list(mine) == out.reaction_names and "far_fx" in mine
    assert np.abs(row).max() > 0
    np.testing.assert_allclose(list(mine.values()), row, rtol=1e-12, atol=1e-9)
    assert mine["floor_penetration"] > 0 and mine["a_b_contact_force"] > 0  # both touch
    assert mine["hang_fx"] == pytest.approx(row[out.reaction_names.index("hang_fx")])
