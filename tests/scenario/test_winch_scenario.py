"""``[[winches]]`` and ``winch`` sensors in a scenario file: a 10 kg load on a steel wire paid
out at a rate (``speed``) from 5 m; the sensor's columns, the load following the length, and
one-line refusals naming the key."""

from __future__ import annotations

import contextlib
import io
import re
import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.errors import InputError, ScenarioError
from rancf.scenario import Scenario
from rancf.system.outputs import SystemOutputs

HOIST = """
[[bodies]]
name = "wire"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -5.0]
[bodies.mesh]
elements = 10
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

[[supports]]
at = "wire:start"
kind = "pin"

[[winches]]
name = "hoist"
at = "wire:start"
speed = { ramp = 2.0, value = 1.0 }

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 4.0
step = 0.01
output_step = 0.5
initial_state = "static"

[[sensors]]
name = "drum"
kind = "winch"
winch = "hoist"

[[sensors]]
name = "hook"
kind = "position"
at = "load"
"""


def _sensors(tmp_path, text: str) -> dict[str, np.ndarray]:
    (tmp_path / "s.toml").write_text(text)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "run")]) == 0
    head, *rows = (tmp_path / "run" / "sensors.csv").read_text().splitlines()
    vals = np.array([[float(x) for x in r.split(",")] for r in rows])
    return {c: vals[:, i] for i, c in enumerate(head.split(","))}


def test_speed_winch_and_its_sensor(tmp_path):
    """The speed ramps to 1 m/s over 2 s: L = 5 + t²/4, then 6 + (t - 2); the load hangs at L
    plus its stretch (below 0.2 mm here); the tension is the force of the winch's support
    (``reactions.csv``), at the static start ``(m + ρ A L) g``."""
    s = _sensors(tmp_path, HOIST)
    t = s["t"]
    length = np.where(t < 2.0, 5.0 + t**2 / 4, 6.0 + (t - 2.0))
    np.testing.assert_allclose(s["drum_length"], length, rtol=0, atol=1e-6)
    np.testing.assert_allclose(s["drum_speed"], np.minimum(t / 2, 1.0), rtol=0, atol=1e-3)
    assert np.all(np.abs(-s["hook_y"] - s["drum_length"]) < 2e-4)
    rho_a = 7850.0 * np.pi * 0.005**2
    assert s["drum_tension"][0] == pytest.approx((10.0 + rho_a * 5.0) * 9.81, rel=1e-6)
    head, *rows = (tmp_path / "run" / "reactions.csv").read_text().splitlines()
    r = np.array([[float(x) for x in row.split(",")] for row in rows])
    cols = head.split(",")
    force = np.hypot(r[:, cols.index("wire:start_fx")], r[:, cols.index("wire:start_fy")])
    np.testing.assert_allclose(s["drum_tension"], force, rtol=1e-12)


@pytest.mark.parametrize(
    ("old", "new", "key"),
    [
        ("speed = { ramp = 2.0, value = 1.0 }", "torque = 5.0\ninertia = 0.1", "winches[0].radius"),
        ("speed = { ramp = 2.0, value = 1.0 }", "torque = 5.0\nradius = 0.2", "winches[0].inertia"),
        (
            "speed = { ramp = 2.0, value = 1.0 }",
            "speed = 1.0\nradius = 0.2\ninertia = 0.1",
            "winches[0].radius",
        ),
        (
            "speed = { ramp = 2.0, value = 1.0 }",
            "torque = 5.0\nradius = -0.2\ninertia = 0.1",
            "winches[0].radius",
        ),
        (
            "speed = { ramp = 2.0, value = 1.0 }",
            "torque = 5.0\nspeed = 1.0\nradius = 0.2\ninertia = 0.1",
            "winches[0]",
        ),
        ('at = "wire:start"\nspeed', 'at = "wire:3"\nspeed', "winches[0].at"),
        ("speed = { ramp = 2.0, value = 1.0 }", "speed = 1.0\nlength = 5.0", "winches[0]"),
        ('winch = "hoist"', 'winch = "drum"', "[sensors[0].winch] names no winch: 'drum'"),
        (
            "speed = { ramp = 2.0, value = 1.0 }",
            "speed = 1.0\nposition = [0.0, 1.0]",
            "winches[0].position",
        ),
    ],
)
def test_bad_winch_is_one_line_naming_the_key(tmp_path, old, new, key):
    text = HOIST.replace(old, new, 1)
    assert text != HOIST
    with pytest.raises((ScenarioError, InputError), match=re.escape(key)):
        sc = Scenario.from_dict(tomllib.loads(text), "s.toml")
        SystemOutputs(sc.build_system(), sc.sensors)
