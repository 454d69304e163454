"""Supports, winches, obstacles and contact pairs are Parts (rancf.system.part): the system's
prescribed and winch records are the ones their parts make, a moving support's records follow
its node's coordinates, a winch's length follows its law (no column of its own), an obstacle's
record is its checked geometry and a pair's its contact law with the defaults; a distributed
load's record is its force and time function."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels import _core
from rancf.kernels.contact_records import (
    BodyPairRecord,
    ContactPairRecord,
    ContactRecord,
    ObstacleRecord,
)
from rancf.mesh.factories import mesh_line
from rancf.system import Obstacle, System
from rancf.system.parts.contact_pair import BodyPair, ContactPair
from rancf.system.parts.distributed import DistributedLoad
from rancf.system.parts.support import supports_of
from rancf.system.record_rows import RecordRows
from tests.system.test_winch import hoist, payout

STEEL, WIRE = Material(7850.0, 2.0e11), Section.circular(0.005)


def _shaken(kind: str = "pin", axis: tuple[float, ...] | None = None) -> System:
    """A wire held at both ends; its end moves by a sine in both axes."""
    shake = TimeFunction.from_callable(lambda t: [0.1 * np.sin(t), 0.2 * np.sin(t)])
    wire = Model(
        mesh_line([0, 0], [4.0, 0], 4),
        "ancf",
        WIRE,
        STEEL,
        [Support(0, "pin"), Support(-1, kind, axis=axis, motion=shake)],
    )
    return System({"w": wire}, horizon=1.0)


def test_a_moving_supports_records_are_its_nodes_coordinates():
    s = _shaken()
    parts = supports_of(s)
    assert [p.name for p in parts] == ["w:0", "w:-1"]
    assert parts[0].record(s, RecordRows(1.0)) == ()  # a support that stays
    mine = parts[1].record(s, RecordRows(1.0))
    assert mine == s.model.prescribed
    base = s.offsets["w"] + s.bodies["w"].node_base(4)
    assert [(r.coord, r.comp) for r in mine] == [(base, 0), (base + 1, 1)]
    assert [r.base for r in mine] == [4.0, 0.0]
    assert parts[1].sensors(s) == ["w:end_fx", "w:end_fy"]  # a pin: no moment


def test_a_moving_roller_is_refused_naming_the_key():
    with pytest.raises(InputError, match="supports.motion"):
        _shaken("roller", (1.0, 0.0))


def test_a_winchs_record_and_length():
    s = hoist(payout, 10.0, n_el=4)
    (w,) = s.winches
    rec = w.record(s, RecordRows(10.0))
    assert rec.body == s.model.winches[0].body == 0 and rec.length_set == pytest.approx(5.0)
    assert np.array_equal(rec.c1, s.model.winches[0].c1) and rec.drum is None
    assert w.sensors(s) == ()  # its length is the winch sensor's
    got = float(np.ravel(s.winch_lengths["hoist"].value(5.0))[0])
    assert got == pytest.approx(payout(5.0), rel=1e-6)


def test_an_obstacles_record_and_its_pairs_laws():
    s = _shaken()
    plane = Obstacle("plane", point=[0.0, -1.0], normal=[0.0, 2.0], friction=0.3, name="floor")
    rec = plane.record(s)
    assert (rec.kind, rec.body, rec.radius) == ("plane", -1, 0.0)
    assert rec.point == (0.0, -1.0, 0.0) and rec.direction == (0.0, 1.0, 0.0)
    law = ContactPair("w", plane, "floor", 2).record(s)
    rt, e = WIRE.radius, STEEL.youngs_modulus
    assert law == ContactPairRecord(0, 2, 0.1 * e, 1e-3 * rt, 0.0, 0.3, 1e-3, 0.0)
    pair = BodyPair("w", "w", 0.2).record(s)
    assert pair == BodyPairRecord(0, 0, 0.05 * e, 1e-3 * rt, 0.2, 1e-3)
    assert ContactPair("w", plane, "floor").name == "w/floor"


def test_a_contact_record_field_of_a_wrong_value_is_named_in_one_line():
    cone = ObstacleRecord("cone", -1, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0)
    with pytest.raises(
        ValueError,
        match=r"^contact\.obstacles\[0\]\.kind: expected one of "
        r"plane, cylinder, sphere, got 'cone'$",
    ):
        _core.Contact(ContactRecord(obstacles=(cone,)))
    plane = ObstacleRecord("plane", -1, (0.0, 0.0, 0.0), (0.0, 0.0, 1.0), 0.0)
    pair = ContactPairRecord(0, 0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0)
    with pytest.raises(ValueError, match=r"^contact\.pairs\[0\]\.body: expected a flexible"):
        _core.Contact(ContactRecord(obstacles=(plane,), pairs=(pair,)))


def test_an_obstacles_bad_field_is_named_with_its_system_name():
    s = _shaken()
    with pytest.raises(InputError, match=r"obstacles\.obstacle0\.friction"):
        Obstacle("plane", point=[0.0, 0.0], normal=[0.0, 1.0], friction=-1.0).record(
            s, None, "obstacle0"
        )
    with pytest.raises(InputError, match=r"obstacles\.plane\.normal"):
        Obstacle("plane", point=[0.0, 0.0], normal=[0.0, 0.0]).record(s)


def test_a_distributed_loads_record():
    s = _shaken()
    rows = RecordRows(1.0)
    rec = DistributedLoad((0.0, -9.0), "w", TimeFunction.constant(2.0)).record(s, rows, 3)
    assert rec.force == (0.0, -9.0, 0.0) and rec.factor == len(rows.tfs) - 1 == 0
    assert DistributedLoad((1.0, 0.0)).record(s, rows).factor == -1
    with pytest.raises(InputError, match=r"loads\.distributed\[3\]\.force"):
        DistributedLoad((1.0, 0.0, 0.0)).record(s, rows, 3)
    with pytest.raises(InputError, match=r"loads\.distributed\[0\]\.body = 'x'.*\['w'\]"):
        DistributedLoad((1.0, 0.0), "x").record(s, rows)
