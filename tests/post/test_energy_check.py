"""A run in which nothing does work on the system may not gain energy: a large rise fails the run
(exit status 3, one line naming the energy, the time, the step and rho_inf), a smaller one is a
warning; a run with loads doing work is not checked."""

from __future__ import annotations

import json

import numpy as np

from rancf.cli import main
from rancf.post.energy_check import ENERGY_BLOW_UP, ENERGY_GROWTH, energy_rise
from rancf.runs.simulate import run_simulate
from rancf.scenario import parse_scenario
from rancf.system.energy_track import EnergyTrack

#: A 1 kg bob on a stiff spring (k = 1e5 N/m, period 20 ms) to a pinned point mass, let go
#: from 41 % stretch: a nonlinear spring pendulum. Steps of 10 ms (half the spring's period)
#: at rho_inf 0.9 gain energy until it is many times the start's.
SPRING_PENDULUM = """
[[bodies]]
name = "bob"
kind = "mass"
mass = 1.0
position = [1.0, -1.0]

[[bodies]]
name = "top"
kind = "mass"
mass = 1.0
position = [0.0, 0.0]

[[joints]]
name = "pivot"
kind = "pin"
between = ["top", "ground"]

[[springs]]
between = ["bob", "top"]
stiffness = 1.0e5
length = 1.0

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 2.0
step = 0.01
rho_inf = 0.9
"""

#: MoorDyn's pendulum (its test case ``pendulum.txt``): a 100 t bob on a nearly weightless
#: 100.5 m line of EA = 1e9 N, let go 10 m off the vertical; 10 elements, steps of 0.05 s.
STIFF_LINE_PENDULUM = """
[[bodies]]
name = "line"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0, 0.0]
end = [10.0, 0.0, -100.0]
[bodies.mesh]
elements = 10
[bodies.section]
radius = 0.05
[bodies.material]
density = 1.0
youngs_modulus = 1.2732395e11

[[bodies]]
name = "bob"
kind = "mass"
mass = 1.0e5
position = [10.0, 0.0, -100.0]

[[supports]]
at = "line:start"
kind = "pin"

[[joints]]
name = "hook"
kind = "pin"
between = ["line:end", "bob"]

[loads]
gravity = [0.0, 0.0, -9.81]

[solver]
t_end = 60.0
step = 0.05
rho_inf = 0.9
"""


def _toml_dict(text: str) -> dict:
    import tomllib

    return tomllib.loads(text)


def test_an_unstable_spring_pendulum_fails_naming_its_energy(tmp_path, capsys):
    (tmp_path / "p.toml").write_text(SPRING_PENDULUM)
    assert main(["simulate", str(tmp_path / "p.toml"), "--out", str(tmp_path / "r")]) == 3
    err = capsys.readouterr().err
    (line,) = [x for x in err.splitlines() if "energy" in x]
    assert line.startswith("rancf: simulation failed: unstable: the total energy")
    assert "rose from 8579 J at t = 0 s" in line
    assert "solver.step (now 0.01 s)" in line and "solver.rho_inf (now 0.9)" in line
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["status"] == "failed" and summary["message"].startswith("unstable:")
    energy = np.genfromtxt(tmp_path / "r" / "energy.csv", delimiter=",", names=True)
    total = energy["kinetic"] + energy["strain"] + energy["gravity"]
    assert total.max() > 10 * total[0]  # the energy the check saw in the written rows


def test_the_same_pendulum_with_small_steps_passes():
    data = _toml_dict(SPRING_PENDULUM)
    data["solver"]["step"] = 1e-3
    run = run_simulate(parse_scenario(data))
    assert run.result.status.value == "completed"
    assert energy_rise(run.outputs.energy) < ENERGY_GROWTH
    assert not [w for w in run.warnings if "energy" in w]


def test_moordyns_stiff_line_pendulum_at_coarse_steps_is_warned_about():
    run = run_simulate(parse_scenario(_toml_dict(STIFF_LINE_PENDULUM)))
    assert run.result.status.value == "completed"
    rise = energy_rise(run.outputs.energy)
    assert ENERGY_GROWTH < rise < ENERGY_BLOW_UP
    (line,) = [w for w in run.warnings if "energy" in w]
    assert "while nothing does work on the system" in line and "(now 0.05 s)" in line


def test_a_load_doing_work_is_not_checked():
    data = _toml_dict(SPRING_PENDULUM)
    data["loads"]["point"] = [{"at": "bob", "force": [0.0, 0.0]}]
    run = run_simulate(parse_scenario(data))
    assert run.result.status.value == "completed"
    assert energy_rise(run.outputs.energy) > ENERGY_BLOW_UP  # the same motion, unchecked
    assert not [w for w in run.warnings if "energy" in w]


def test_the_track_scale_bounds_the_energies_of_a_free_motion():
    track = EnergyTrack()
    # a pendulum let go from rest: gravity to kinetic and back, no rise
    t = np.linspace(0.0, 1.0, 5)
    drop = np.array([0.0, -1.0, -2.0, -1.0, 0.0])
    track.add(t, np.column_stack([-drop, np.zeros(5), drop]))
    track.add(t[:2], np.column_stack([-drop, np.zeros(5), drop])[:2])  # a row seen twice
    assert track.t0 == 0.0 and track.e0 == 0.0 and track.scale == 2.0
    assert energy_rise(track) == 0.0
    track.add([2.0], [[2.2, 0.0, -2.0]])  # 0.2 J more than the 2 J of the motion: 10 %
    assert np.isclose(energy_rise(track), 0.1)
    track.add([3.0], [[np.nan, 0.0, 0.0]])  # a diverged row
    assert energy_rise(track) == np.inf


def test_a_resumed_run_is_checked_from_its_start(tmp_path, capsys):
    """The spring pendulum run to 0.2 s, then resumed to its end: the check of the whole run,
    its rise counted from t = 0 (the rows before the resumption included)."""
    (tmp_path / "p.toml").write_text(SPRING_PENDULUM)
    base = ["simulate", str(tmp_path / "p.toml"), "--quiet"]
    assert main([*base, "--out", str(tmp_path / "whole")]) == 3
    whole = [x for x in capsys.readouterr().err.splitlines() if "total energy" in x]
    assert main([*base, "--out", str(tmp_path / "r"), "--t-end", "0.2"]) == 0
    capsys.readouterr()
    assert main([*base, "--out", str(tmp_path / "r"), "--resume"]) == 3
    resumed = [x for x in capsys.readouterr().err.splitlines() if "total energy" in x]
    assert len(whole) == 1 and "rose from 8579 J at t = 0 s" in whole[0]
    assert [x.split(" (written to")[0] for x in resumed] == [
        x.split(" (written to")[0] for x in whole
    ]


def test_a_model_at_rest_is_not_failed_by_the_round_off_of_its_energy():
    """A clamped curved rod at rest, no loads: its energy is the reference's round-off
    (1e-27 J) and rises by a few times that, far below the model's energy unit."""
    from tests.test_cli_errors import ROD

    run = run_simulate(parse_scenario(_toml_dict(ROD)))
    track = run.outputs.energy
    assert 0.0 < track.e_max - track.e0 < 1e-24  # round-off, relative to its own 1e-27 J
    assert run.result.status.value == "completed"
    assert not [w for w in run.warnings if "energy" in w]
