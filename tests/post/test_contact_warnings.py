"""Warnings for contact set up wrongly (rancf.post.contact_checks): a body that starts deeper
inside an obstacle than its section radius, a frictional wrap with too few elements."""

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.mesh.factories import mesh_line
from rancf.post.checks import section_warnings
from rancf.post.contact_checks import contact_warnings, wrap_error
from rancf.system import Obstacle, System
from tests.system.test_contact_capstan import capstan

RT = 0.01
SECTION = Section(np.pi * RT**2, np.pi * RT**4 / 4)


def _cable_on(plane_y: float, kind: str = "plane") -> System:
    cable = Model(
        mesh_line([0, 0], [1, 0], 4), "rancf", SECTION, Material(1000.0, 1e8), gravity=(0.0, -9.81)
    )
    if kind == "plane":
        ob = Obstacle("plane", point=(0.0, plane_y), normal=(0.0, 1.0), name="ground")
    else:
        ob = Obstacle("cylinder", center=(0.5, plane_y - 0.2), radius=0.2, name="ground")
    return System({"cable": cable}, obstacles=[ob])


@pytest.mark.parametrize("kind", ["plane", "cylinder"])
def test_a_body_deep_inside_an_obstacle_is_named(kind):
    (w,) = contact_warnings(_cable_on(3 * RT, kind))  # the centre line 2 radii below the surface
    assert "\n" not in w and w.startswith("cable starts ")
    depth = float(w.split()[2])
    assert depth == pytest.approx(0.04, rel=1e-12 if kind == "plane" else 1e-2)
    rest = "inside obstacle 'ground', more than its section radius 0.01 m: the contact pushes"
    assert w.split(" m ", 1)[1].startswith(rest)
    force = float(w.split("pushes it out with ")[1].split(" N")[0])
    # the penalty E/10 times the depth beyond the onset, over the length inside (all of it)
    if kind == "plane":
        assert force == pytest.approx(1e7 * (0.04 - 0.5e-5) * 1.0, rel=1e-3)
    assert section_warnings(_cable_on(3 * RT, kind)) == [w]  # the run's warnings list it
    assert contact_warnings(_cable_on(-RT, kind)) == []  # resting on it: no warning
    assert contact_warnings(_cable_on(-0.5 * RT, kind)) == []  # half a radius deep: none


def test_too_few_elements_on_a_frictional_wrap():
    """The capstan: half a turn of rope over a pulley with friction 0.3."""
    (w,) = contact_warnings(capstan(0.3, 4, 3, 0.0))
    assert w == (
        "rope: 4 element(s) on its 180° frictional wrap of 'pulley' (up to 45° each): "
        "the motion it transmits errs by about 7.4 % (measured on an Atwood machine); "
        "give at least 12 elements on the wrap (at most 15° each)"
    )
    assert wrap_error(np.radians(22.5)) == pytest.approx(1.06, abs=0.01)  # measured: 1.0 %
    assert contact_warnings(capstan(0.3, 12, 3, 0.0)) == []  # 15° each
    assert contact_warnings(capstan(0.0, 4, 3, 0.0)) == []  # frictionless: nothing to transmit


def test_two_bodies_crossing_inside_each_other():
    """Two cables of radius 1 cm crossing at right angles, their centre lines meeting (the depth
    the contact points see: between one and two radii) or 15 mm apart (5 mm: less than a
    radius)."""

    def crossing(dz: float) -> System:
        mat = Material(1000.0, 1e8)
        a = Model(mesh_line([-0.5, 0, 0], [0.5, 0, 0], 5), "rancf", SECTION, mat)
        b = Model(mesh_line([0, -0.5, dz], [0, 0.5, dz], 5), "rancf", SECTION, mat)
        return System({"a": a, "b": b}, body_contacts=[("a", "b")], contact_points=16)

    (w,) = contact_warnings(crossing(0.0))
    assert w.startswith("a and b start ") and "\n" not in w
    assert 0.01 < float(w.split()[4]) <= 0.02
    rest = "inside each other, more than the section radius 0.01 m: the contact pushes them apart"
    assert w.split(" m ", 1)[1].startswith(rest)
    assert contact_warnings(crossing(0.015)) == []
