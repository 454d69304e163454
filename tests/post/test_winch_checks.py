"""A winch's body with friction or axial fluid loads is warned about once (those use the mesh's
velocity, not the material's); a frictionless sheave and normal-only fluid loads are not."""

from __future__ import annotations

import tomllib

import pytest

from rancf.post.winch_checks import winch_warnings
from rancf.scenario import Scenario
from rancf.scenario.system_build import build_system
from rancf.studies.common import example_path


def _crane(**changes) -> Scenario:
    raw = tomllib.loads(example_path("crane-hoist").read_text())
    raw["obstacles"][0].update(changes.get("sheave", {}))
    raw.update(changes.get("top", {}))
    rope = next(b for b in raw["bodies"] if b["name"] == "rope")
    rope.update(changes.get("rope", {}))
    return Scenario.from_dict(raw, "crane-hoist.toml")


def test_the_shipped_crane_has_no_such_warning():
    assert winch_warnings(build_system(_crane())) == []


def test_friction_on_the_sheave_is_warned_about():
    (line,) = winch_warnings(build_system(_crane(sheave={"friction": 0.2})))
    assert line.startswith("winch 'hoist': friction on 'sheave' along rope use the mesh's")


@pytest.mark.parametrize(("axial", "warned"), [(0.0, False), (0.5, True)])
def test_axial_fluid_loads_are_warned_about(axial, warned):
    hydro = {"diameter": 0.02, "drag_normal": 1.2, "drag_axial": axial}
    sc = _crane(top={"fluid": {"density": 1.2}}, rope={"hydro": hydro})
    lines = winch_warnings(build_system(sc))
    assert bool(lines) == warned
    if warned:
        assert "axial drag along rope" in lines[0]
