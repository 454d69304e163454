"""A system's parts as the named records the core takes (System.model): one record per place,
joints, springs, loads and time functions referring to them by position, and nothing else the
core needs."""

from __future__ import annotations

import tomllib

import numpy as np

from rancf.kernels.call_records import ResidualOptions, ResidualPoint
from rancf.scenario import parse_scenario
from rancf.scenario.system_build import build_system
from rancf.system.core_data import build_core
from tests.scenario.systems import SLIDER_CRANK


def _slider_crank():
    return build_system(parse_scenario(tomllib.loads(SLIDER_CRANK), "s.toml"))


def test_records_of_the_slider_crank():
    """Crank (rigid, pivot and tip), rod (cable nodes 0 and 8), slider (point mass), the ground
    twice (at the pivot and at the slider), the motor's spin-up; a place used twice (the slider:
    rod end and guide) is one record."""
    s = _slider_crank()
    r = s.model
    places = [(p.kind, p.body, p.node, p.point[:2]) for p in r.places]
    assert places == [
        ("rigid2d", 0, 0, (-0.075, 0.0)),
        ("ground", -1, 0, (0.0, 0.0)),
        ("rigid2d", 0, 0, (0.075, 0.0)),
        ("cable", 0, 0, (0.0, 0.0)),
        ("cable", 0, 8, (0.0, 0.0)),
        ("mass", 1, 0, (0.0, 0.0)),
        ("ground", -1, 0, (0.45, 0.0)),
    ]
    assert [(j.kind, j.driven) for j in r.joints] == [
        ("pin", True),
        ("pin", False),
        ("pin", False),
        ("slider", False),
    ]
    motor = r.joints[0]
    assert r.places[motor.b].kind == "ground" and r.places[motor.a].kind == "rigid2d"
    assert r.time_functions[motor.angle].kind == "spin_up"
    assert r.time_functions[motor.angle].value == (150.0,)
    rod_slider, guide = r.joints[2], r.joints[3]
    assert rod_slider.b == guide.a  # the slider's one place
    assert guide.normals_b[:2] == (0.0, 1.0)  # the axis' normal in the ground's frame


def test_the_records_are_all_the_core_takes():
    """A core built again from the system's one model record (System.model) gives the same
    residual, bit for bit, at a perturbed state."""
    s = _slider_crank()
    rod = s.bodies["rod"]
    assert s.model.models == (rod.core,) and [p.name for p in s.body_parts] == s.names
    assert [r.point_mass for r in s.model.rigid] == [False, True]  # the crank, the slider
    again = build_core(s.model)
    rng = np.random.default_rng(3)
    y = s.y0 + 1e-3 * rng.standard_normal(s.n) * ~s.fixed
    v, a, lam = rng.standard_normal(s.n), rng.standard_normal(s.n), rng.standard_normal(s.m)
    r1, r2 = np.empty(s.n + s.m), np.empty(s.n + s.m)
    s.core.residual(ResidualPoint(y, lam, r1, v, a), ResidualOptions(0.03))
    again.residual(ResidualPoint(y, lam, r2, v, a), ResidualOptions(0.03))
    assert np.array_equal(r1, r2) and np.abs(r1).max() > 0
