"""Impulsive starts are never silent (docs/guide/scenarios.md, "Impulsive starts"): a time
function that drives something and jumps at ``t = 0`` (a prescribed rate from rest, a prescribed
displacement or angle off its reference, a load switched on) gets a one-line warning naming the
item, the jump and the cure, on standard error and in ``summary.json``; a harmonic motion still
builds up by itself; ``build_up`` (tables and CSV tables too) cures and silences it."""

from __future__ import annotations

import json
import tomllib
from importlib.resources import files
from pathlib import Path

import numpy as np
import pytest

from rancf.bodies.time_function import TimeFunction
from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.scenario import parse_scenario
from rancf.scenario.motions import JUMP_RTOL, start_jump
from tests.scenario.test_winch_scenario import HOIST

GUIDE = Path(__file__).parents[2] / "docs" / "guide" / "scenarios.md"
#: The reported winch: paid out at 1 m/s from t = 0.
PAY_OUT = HOIST.replace(
    "speed = { ramp = 2.0, value = 1.0 }", "length = { table = [[0, 5], [10, 15]] }"
)
#: A pin-supported line whose support moves (MOTION) and carries a point load (TIME).
LINE = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]
[mesh]
elements = 2
[section]
radius = 0.01
[material]
density = 1000.0
youngs_modulus = 1.0e9
[[supports]]
at = "start"
kind = "pin"
{motion}
[[loads.point]]
at = "end"
force = [0.0, -1.0]
{time}
[[loads.distributed]]
force = [0.0, -1.0]
{dtime}
[solver]
t_end = 2.0
step = 1.0e-3
initial_state = "{start}"
"""


def _line(motion: str = "", time: str = "", dtime: str = "", start: str = "reference") -> list:
    text = LINE.format(motion=motion, time=time, dtime=dtime, start=start)
    return parse_scenario(tomllib.loads(text)).warnings


def _simulate(tmp_path: Path, text: str, capsys, *extra: str) -> tuple[list[str], dict]:
    (tmp_path / "s.toml").write_text(text)
    capsys.readouterr()
    out = tmp_path / "run"
    assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(out), "--quiet", *extra]) == 0
    err = capsys.readouterr().err.splitlines()
    warned = [x.removeprefix("rancf: warning: ") for x in err if x.startswith("rancf: warning: ")]
    return warned, json.loads((out / "summary.json").read_text())


def test_a_winch_paying_out_at_once_warns(tmp_path, capsys):
    warned, summary = _simulate(tmp_path, PAY_OUT, capsys, "--t-end", "0.5")
    (line, error) = warned  # the jump, then the steps that do not resolve it
    assert error.startswith("the local error estimate is ")
    assert line.startswith(
        "winch 'hoist' (winches[0].length): the pay-out rate jumps from 0 to 1 m/s at t = 0"
    )
    assert "give build_up = 1 to build it up over 1 s, or start the table at rate 0" in line
    assert summary["warnings"] == [line, error]
    # the fixed-step run's estimate, once at the end: where, the step, and a step that meets it
    err, h, at = summary["error_estimate"], summary["error_step_s"], summary["error_time_s"]
    assert err > 1.0 and h > 0.0 and 0.0 < at <= 0.5
    assert f"is {err:.3g} times solver.rtol" in error and f"at t = {at:.6g} s" in error
    assert f"with a step of {h:.3g} s" in error
    assert f"a step of about {h * 0.9 * err ** (-1 / 3):.3g} s meets it there" in error
    assert f"rancf: warning: {line}\n" in GUIDE.read_text()  # the guide shows it as it is


def test_a_built_up_winch_length_starts_at_rate_0_and_keeps_its_start(tmp_path, capsys):
    text = PAY_OUT.replace("[10, 15]] }", "[10, 15]], build_up = 1.0 }")
    text = text.replace("output_step = 0.5", "output_step = 0.25")
    warned, summary = _simulate(tmp_path, text, capsys, "--t-end", "1.5")
    assert warned == [] and summary["warnings"] == []
    head, *rows = (tmp_path / "run" / "sensors.csv").read_text().splitlines()
    s = dict(
        zip(
            head.split(","),
            np.array([[float(x) for x in r.split(",")] for r in rows]).T,
            strict=True,
        )
    )
    t = s["t"]
    x = np.minimum(t, 1.0)
    r = 10 * x**3 - 15 * x**4 + 6 * x**5
    np.testing.assert_allclose(s["drum_length"], 5.0 + r * t, atol=1e-6)  # L(0) + r (f - L(0))
    assert s["drum_speed"][0] == pytest.approx(0.0, abs=1e-6)
    assert s["drum_speed"][-1] == pytest.approx(1.0, abs=1e-6)


def test_a_crank_turned_at_once_warns(tmp_path, capsys):
    text = (files("rancf.examples") / "slider-crank.toml").read_text(encoding="utf-8")
    text = text.replace(
        "angle = { spin_up = 0.05, rate = 150.0 }", "angle = { ramp = 1, value = 150 }"
    )
    warned, summary = _simulate(tmp_path, text, capsys, "--t-end", "0.001")
    (line, error) = warned
    assert error.startswith("the local error estimate is ")
    assert line.startswith(
        "joint 'motor' (joints[0].angle): the angular rate jumps from 0 to 150 rad/s at t = 0"
    )
    assert line.endswith(
        "give build_up = 0.1 to build it up over 0.1 s, or write angle = "
        "{ spin_up = 0.1, rate = 150 }"
    )
    assert summary["warnings"] == [line, error]


def test_start_jump_of_every_kind():
    cases = [  # function, order, jump, largest over [0, 2]
        (TimeFunction.table([[0.0, 5.0], [10.0, 15.0]]), 1, 1.0, 1.0),
        (TimeFunction.table([[0.0, 1.0], [1.0, 3.0]]), 0, 1.0, 3.0),
        (TimeFunction.ramp(1.0, 150.0), 1, 150.0, 150.0),
        (TimeFunction.constant(2.0), 0, 2.0, 2.0),
        (TimeFunction.constant(2.0), 1, 0.0, 0.0),
        (TimeFunction.spin_up(0.5, 3.0), 1, 0.0, 3.0),
        (TimeFunction.harmonic(1.0, [0.0, 0.5], 90.0), 0, 0.5, 0.5),
        (TimeFunction.ramp(1.0, 150.0).with_build_up(0.5), 1, 0.0, 266.663),  # r' f + r f'
    ]
    for f, order, jump, largest in cases:
        got = start_jump(f, order, 2.0)
        np.testing.assert_allclose(got, (jump, largest), rtol=1e-3, err_msg=repr(f))


def test_a_table_that_starts_flat_passes():
    """The reel-out example's cubic table starts flat; its spline's end slope (3e-4 m/s against
    1.9 m/s) is below the threshold, a slope of 1 % of the peak is not."""
    rows = tomllib.loads((files("rancf.examples") / "tether-reel-out.toml").read_text())
    f = TimeFunction.table(rows["winches"][0]["length"]["table"], "cubic")
    jump, largest = start_jump(f, 1, 20.0)
    assert 0 < jump < JUMP_RTOL * largest
    steep = TimeFunction.table([[0.0, 0.0], [1.0, 0.01], [2.0, 2.01]])
    jump, largest = start_jump(steep, 1, 2.0)
    assert jump > JUMP_RTOL * largest


def test_support_motions_warn_of_rate_and_value_jumps():
    (line,) = _line("motion = { table = [[0, 0, 0], [1, 0, 0.1]] }")
    assert line.startswith(
        "support at 'start' (supports[0].motion): the velocity jumps from 0 to 0.1 m/s at t = 0"
    )
    (line,) = _line("motion = { table = [[0, 0, 0.02], [1, 0, 0.02]] }")
    assert "the displacement jumps from 0 to 0.02 m at t = 0" in line
    assert 'solver.initial_state = "static"' not in line and "start the table at 0" in line
    # a static start carries the displacement at t = 0, not a rate
    assert _line("motion = { table = [[0, 0, 0.02], [1, 0, 0.02]] }", start="static") == []
    assert len(_line("motion = { table = [[0, 0, 0.02], [1, 0, 0.1]] }", start="static")) == 1


def test_a_harmonic_motion_still_builds_up_by_itself():
    sc = parse_scenario(
        tomllib.loads(
            LINE.format(
                motion="motion = { harmonic = 1.0, amplitude = [0.0, 0.05] }",
                time="",
                dtime="",
                start="reference",
            )
        )
    )
    assert sc.warnings == [] and "builds up over 2 s" in sc.notes[0]


def test_loads_switched_on_warn_unless_the_start_is_static():
    (line,) = _line(time="time = 1.0")
    assert line == (
        "point load at 'end' (loads.point[0].time): the load factor jumps from 0 to 1 "
        "at t = 0, an impulsive start (an impact: forces and ringing far above a "
        "smooth start's); give build_up = 0.2 to build it up over 0.2 s, or start "
        'from the static equilibrium (solver.initial_state = "static")'
    )
    (line,) = _line(dtime="time = { harmonic = 2.0, phase_deg = 90.0 }")
    assert line.startswith(
        "distributed load (loads.distributed[0].time): the load factor jumps from 0 to 1 at t = 0"
    )
    assert "give build_up = 1 " in line  # two periods
    assert _line(time="time = 1.0", start="static") == []
    assert _line(time="time = { ramp = 0.5 }") == []  # starts at 0
    assert _line() == []  # a load without time: a constant load, not checked


def test_winch_speed_and_torque():
    (line,) = parse_scenario(
        tomllib.loads(HOIST.replace("{ ramp = 2.0, value = 1.0 }", "1.5"))
    ).warnings
    assert line.startswith(
        "winch 'hoist' (winches[0].speed): the pay-out rate jumps from 0 to 1.5 m/s at t = 0"
    )
    torque = HOIST.replace(
        "speed = { ramp = 2.0, value = 1.0 }", "torque = 30.0\nradius = 0.1\ninertia = 0.5"
    )
    assert parse_scenario(tomllib.loads(torque)).warnings == []  # static start: in balance
    (line,) = parse_scenario(
        tomllib.loads(torque.replace('initial_state = "static"\n', ""))
    ).warnings
    assert "winch 'hoist' (winches[0].torque): the torque jumps from 0 to 30 N m" in line


def test_a_stated_build_up_cures_and_silences(tmp_path):
    assert _line("motion = { table = [[0, 0, 0], [1, 0, 0.1]], build_up = 0.5 }") == []
    assert _line("motion = { table = [[0, 0, 0], [1, 0, 0.1]], build_up = 0 }") == []
    assert _line(time="time = { table = [[0, 1], [1, 1]], build_up = 0.3 }") == []
    (tmp_path / "up.csv").write_text("t, dx, dy\n0, 0, 0\n1, 0, 0.1\n")
    for build_up, count in (("", 1), (", build_up = 0.5", 0)):
        text = LINE.format(
            motion=f'motion = {{ table = "up.csv"{build_up} }}',
            time="",
            dtime="",
            start="reference",
        )
        (tmp_path / "s.toml").write_text(text)
        from rancf.scenario import load_scenario

        sc = load_scenario(tmp_path / "s.toml")
        assert len(sc.warnings) == count
        f = sc.data["supports"][0]["motion"]
        assert start_jump(f, 1, 2.0)[0] == (0.1 if count else 0.0)


def test_a_bad_build_up_names_its_key():
    with pytest.raises(ScenarioError) as exc:
        _line("motion = { table = [[0, 0, 0], [1, 0, 0.1]], build_up = -1 }")
    text = str(exc.value)
    assert "supports[0].motion" in text and "build_up" in text and "-1" in text
