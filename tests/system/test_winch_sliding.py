"""A winch's line through a sliding guide: the guide on the straight hanging line takes no
force, so the drum lifts the load exactly as without it (the winch's start state moves only
what is pinned to its body's nodes; the guide is not)."""

from __future__ import annotations

import numpy as np

from rancf.cli import main

DRUM = """
[[bodies]]
name = "wire"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -5.0]
[bodies.mesh]
elements = 6
element = "ancf"
[bodies.section]
radius = 0.005
[bodies.material]
density = 7850.0
youngs_modulus = 2.0e11

[[bodies]]
name = "load"
kind = "mass"
mass = 10.0
position = [0.0, -5.0]

[[joints]]
name = "hook"
kind = "pin"
between = ["wire:end", "load"]
GUIDE
[[supports]]
at = "wire:start"
kind = "pin"

[[winches]]
name = "hoist"
at = "wire:start"
radius = 0.2
inertia = 0.5
torque = { table = [[0.0, 25.668], [0.05, 33.368], [10.0, 33.368]] }

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.4
step = 0.01
output_step = 0.1
initial_state = "static"

[[sensors]]
name = "drum"
kind = "winch"
winch = "hoist"
"""

GUIDE = """
[[joints]]
name = "guide"
kind = "sliding"
between = ["wire", "ground"]
position = [0.0, -1.0]
"""


def test_a_guide_on_the_straight_line_changes_nothing(tmp_path):
    runs = {}
    for name, guide in (("plain", ""), ("guide", GUIDE)):
        (tmp_path / f"{name}.toml").write_text(DRUM.replace("GUIDE", guide))
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
