"""``kind = "sliding"`` joints in a scenario file: a stiff rope (a beam) pinned at both ends
runs through a guide on the ground; the guide's reaction and arc length in ``reactions.csv``
and through a ``reaction`` sensor; one-line refusals naming the key."""

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
from tests.numbers import csv_columns

BEAM = """
[[bodies]]
name = "beam"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [2.0, 0.0]
[bodies.mesh]
elements = 20
element = "ancf"
[bodies.section]
radius = 0.01
[bodies.material]
density = 1000.0
youngs_modulus = 1.0e11

[[supports]]
at = "beam:start"
kind = "pin"

[[supports]]
at = "beam:end"
kind = "pin"

[[joints]]
name = "guide"
kind = "sliding"
between = ["beam", "ground"]
position = [0.95, 0.0]

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.01
step = 0.005
initial_state = "static"

[[sensors]]
name = "ring"
kind = "reaction"
joint = "guide"
"""


def test_sliding_joint_from_a_scenario_file(tmp_path):
    """The guide at 0.95 m of the 2 m beam carries the middle support's reaction of the
    continuous beam (statics at the start, ``M_B`` by three moments; 2e-4), at arc length
    0.95 m, in ``reactions.csv`` (``guide_fx, guide_fy, guide_s``) and the sensor's columns
    (``ring_x, ring_y, ring_s``)."""
    (tmp_path / "s.toml").write_text(BEAM)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "run")]) == 0
    r = csv_columns(tmp_path / "run" / "reactions.csv")
    s = csv_columns(tmp_path / "run" / "sensors.csv")
    w, a, b = 1000.0 * np.pi * 0.01**2 * 9.81, 0.95, 1.05
    mb = -w * (a**3 + b**3) / (8 * (a + b))
    assert r["guide_fy"][0] == pytest.approx(w * (a + b) / 2 - mb / a - mb / b, rel=2e-4)
    np.testing.assert_allclose(r["guide_s"], 0.95, atol=1e-6)
    for key, col in (("x", "guide_fx"), ("y", "guide_fy"), ("s", "guide_s")):
        np.testing.assert_array_equal(s[f"ring_{key}"], r[col])


@pytest.mark.parametrize(
    ("old", "new", "key"),
    [
        ('between = ["beam", "ground"]', 'between = ["beam:3", "ground"]', "joints[0].between[0]"),
        ('between = ["beam", "ground"]', 'between = ["rope", "ground"]', "joints[0].between[0]"),
        ("position = [0.95, 0.0]\n", "", "joints[0].position"),
        ("position = [0.95, 0.0]", "position = [0.95, 0.0, 0.0]", "joints[0].position"),
        ("position = [0.95, 0.0]", "position = [0.95, 0.2]", "guide.between"),
        ('kind = "sliding"', 'kind = "pin"', "joints[0].position"),
    ],
)
def test_bad_sliding_joint_is_one_line_naming_the_key(old, new, key):
    text = BEAM.replace(old, new, 1)
    assert text != BEAM
    with pytest.raises((ScenarioError, InputError), match=re.escape(key)) as err:
        sc = Scenario.from_dict(tomllib.loads(text), "s.toml")
        SystemOutputs(sc.build_system(), sc.sensors)
    assert "\n" not in str(err.value)
