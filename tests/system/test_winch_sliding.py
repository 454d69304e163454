"""A winch's line through a sliding guide: the guide on the straight hanging line takes no
force, so a driven drum lifts the load exactly as without it (the winch's start state moves only
what is pinned to its body's nodes; the guide is not)."""

from __future__ import annotations

import tomllib

import numpy as np

from rancf.cli import main
from rancf.scenario import Scenario
from tests.scenario.test_winch_scenario import HOIST

#: The hoist of the winch scenario tests, its winch a driven drum lifting the load.
DRUM = {
    "name": "hoist",
    "at": "wire:start",
    "radius": 0.2,
    "inertia": 0.5,
    "torque": {"table": [[0.0, 25.668], [0.05, 33.368], [10.0, 33.368]]},
}
GUIDE = {"name": "guide", "kind": "sliding", "between": ["wire", "ground"], "position": [0.0, -1.0]}


def _scenario(guide: bool) -> Scenario:
    raw = tomllib.loads(HOIST)
    raw["winches"] = [DRUM]
    raw["joints"] += [GUIDE] if guide else []
    raw["solver"] = {"t_end": 0.4, "step": 0.01, "output_step": 0.1, "initial_state": "static"}
    raw["sensors"] = [{"name": "drum", "kind": "winch", "winch": "hoist"}]
    return Scenario.from_dict(raw, "hoist.toml")


def test_a_guide_on_the_straight_line_changes_nothing(tmp_path):
    runs = {}
    for name in ("plain", "guide"):
        _scenario(name == "guide").save(tmp_path / f"{name}.toml")
        out = tmp_path / name
        assert main(["simulate", str(tmp_path / f"{name}.toml"), "--out", str(out), "--quiet"]) == 0
        runs[name] = np.genfromtxt(out / "sensors.csv", delimiter=",", names=True)
    a, b = runs["plain"], runs["guide"]
    assert a["drum_length"][-1] < a["drum_length"][0] - 0.05  # the drum lifts the load
    scale = float(np.abs(a["drum_tension"]).max())
    for col in ("drum_length", "drum_speed"):
        assert np.abs(a[col] - b[col]).max() <= 1e-9 * max(1.0, float(np.abs(a[col]).max()))
    assert np.abs(a["drum_tension"] - b["drum_tension"]).max() <= 1e-9 * scale
    r = np.genfromtxt(tmp_path / "guide" / "reactions.csv", delimiter=",", names=True)
    assert np.abs(np.c_[r["guide_fx"], r["guide_fy"]]).max() <= 1e-9 * scale
