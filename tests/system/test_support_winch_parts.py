"""Supports and winches are Parts (rancf.system.part): the system's prescribed and winch records
are the ones their parts make, a moving support's records follow its node's coordinates, and a
winch's output column reads its length law."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.mesh.factories import mesh_line
from rancf.system import System
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
    assert mine == s.records.prescribed
    base = s.offsets["w"] + s.bodies["w"].node_base(4)
    assert [(r.coord, r.comp) for r in mine] == [(base, 0), (base + 1, 1)]
    assert [r.base for r in mine] == [4.0, 0.0]
    assert parts[1].sensors() == () and parts[1].reactions(s, s.y0, np.zeros(0)) == {}


def test_a_moving_roller_is_refused_naming_the_key():
    with pytest.raises(InputError, match="supports.motion"):
        _shaken("roller", (1.0, 0.0))


def test_a_winchs_record_and_length_column():
    s = hoist(payout, 10.0, n_el=4)
    (w,) = s.winches
    rec = w.record(s, RecordRows(10.0))
    assert rec.body == s.model.winches[0].body == 0 and rec.length_set == pytest.approx(5.0)
    assert np.array_equal(rec.c1, s.model.winches[0].c1) and rec.drum is None
    assert w.sensors() == ("hoist_length",)
    got = w.reactions(s, s.y0, np.zeros(s.m), 5.0)["hoist_length"]
    assert got == pytest.approx(payout(5.0), rel=1e-6)
