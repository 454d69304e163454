"""Sensor kinds: the system's own, and those each part class offers and builds in its module."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.rigid import PointMass
from rancf.errors import InputError
from rancf.scenario.sensors import SENSOR_KINDS, Sensor
from rancf.system import Joint, Spring, System
from rancf.system.outputs import SystemOutputs
from rancf.system.parts import catalog
from rancf.system.readers import NamedReader


def _hanging() -> System:
    bodies = {"top": PointMass(2, 1.0, (0.0, 0.0)), "bob": PointMass(2, 2.0, (0.0, -1.0))}
    return System(
        bodies,
        joints=[Joint("pin", ("top", "ground"))],
        springs=[Spring(("top", "bob"), 100.0)],
        gravity=(0.0, -9.81),
    )


def test_every_kind_of_the_schema_is_read_and_each_once():
    offered = catalog.sensor_kinds()
    own = SystemOutputs(_hanging()).sensors._system_kinds()
    assert not set(offered) & set(own)
    assert sorted({**offered, **own}) == sorted(SENSOR_KINDS)


def test_an_unknown_kind_is_one_line_naming_it():
    with pytest.raises(
        InputError, match=r"^sensors.s.kind = 'bogus' is not allowed: a sensor kind"
    ):
        SystemOutputs(_hanging(), [Sensor("s", "bogus")])


class _Plumb:
    """A part class that offers a sensor kind of its own: the height of a body above the
    lowest point of its reference (``NAME_h``)."""

    @staticmethod
    def _height(host, sen) -> NamedReader:
        o = host.system.offsets[sen.body]
        low = min(host.system.y0[host.system.offsets[n] + 1] for n in host.system.names)
        return NamedReader(lambda blk: blk[1][:, o + 1 : o + 2] - low, [f"{sen.name}_h"])

    sensor_kinds = {"height": _height}


def test_a_new_part_brings_its_sensor_kind(monkeypatch):
    monkeypatch.setattr(catalog, "PARTS", (*catalog.PARTS, _Plumb))
    s = _hanging()
    out = SystemOutputs(s, [Sensor("bob", "height", body="bob"), Sensor("e", "energy")])
    assert out.sensors.names == ["bob_h", "e"]
    q = np.array([[0.0, 0.0, 0.0, -1.0], [0.0, 0.0, 0.1, -1.25]])
    values = out.sensors.values(np.zeros(2), q, None, {}, np.ones((2, 3)))
    np.testing.assert_allclose(values, [[0.0, 3.0], [-0.25, 3.0]], rtol=0, atol=1e-15)
