import json

import numpy as np
import pytest

from rancf.cli import main
from rancf.post.results import load_results
from tests.scenario.test_scenario import BASE

CANTILEVER = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.5, 0.0]

[mesh]
elements = 8

[section]
radius = 0.03

[material]
density = 6000.0
youngs_modulus = 2.0e7

[[supports]]
at = "start"
kind = "clamp"

[[loads.point]]
at = "end"
force = [0.0, -0.001]

[solver]
load_steps = 4

[[sensors]]
name = "tip"
kind = "position"
at = -1
"""


@pytest.fixture
def pendulum_file(tmp_path):
    f = tmp_path / "pend.toml"
    f.write_text(BASE)
    return f


def test_simulate_writes_all_files(tmp_path, pendulum_file, capsys):
    out = tmp_path / "run"
    assert main(["simulate", str(pendulum_file), "--out", str(out), "--quiet"]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "completed"
    assert summary["t_reached"] == pytest.approx(0.02)
    assert summary["steps"] == 20
    assert summary["newton_iterations"] >= 20
    assert summary["solve_wall_time_s"] > 0
    header = (out / "sensors.csv").read_text().splitlines()[0]
    assert header == "t,AB,tip_x,tip_y"
    data = np.loadtxt(out / "sensors.csv", delimiter=",", skiprows=1)
    assert data.shape == (21, 4)
    assert data[0, 1] == pytest.approx(0.5)
    res = load_results(out / "results.npz")
    assert res["q"].shape == (21, 16)
    assert np.allclose(res["sensors"], data[:, 1:])
    energy = np.loadtxt(out / "energy.csv", delimiter=",", skiprows=1)
    assert np.allclose(energy[:, 1] + energy[:, 2] + energy[:, 3], energy[:, 4])
    assert [(b["name"], b["kind"], b["element"]) for b in res["metadata"]["bodies"]] == [
        ("body", "flexible", "rancf")
    ]


def test_simulate_failure_keeps_results(tmp_path, capsys):
    f = tmp_path / "fail.toml"
    f.write_text(
        BASE.replace(
            "t_end = 0.02\nstep = 1.0e-3",
            "t_end = 1.0\nstep = 1.0e-2\nmax_newton = 3\nmin_step = 1.25e-3",
        )
    )
    out = tmp_path / "run"
    assert main(["simulate", str(f), "--out", str(out), "--quiet"]) == 3
    err = capsys.readouterr().err
    assert "did not converge at t =" in err and len(err.strip().splitlines()) == 1
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed"
    assert 0 < summary["t_reached"] < 1.0
    data = np.loadtxt(out / "sensors.csv", delimiter=",", skiprows=1)
    assert data[-1, 0] == pytest.approx(summary["t_reached"])


def test_static_json(tmp_path, capsys):
    f = tmp_path / "c.toml"
    f.write_text(CANTILEVER)
    assert main(["static", str(f), "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert list(d["positions"]) == ["body"] and len(d["positions"]["body"]) == 9
    r, e, force, length = 0.03, 2e7, 1e-3, 0.5
    expected = force * length**3 / (3 * e * np.pi * r**4 / 4)
    assert -d["sensors"]["tip_y"] == pytest.approx(expected, rel=5e-3)
    assert d["positions"]["body"][-1][1] == d["sensors"]["tip_y"]


def test_modes_json_and_plot(tmp_path, capsys):
    f = tmp_path / "c.toml"
    f.write_text(CANTILEVER)
    png = tmp_path / "modes.png"
    assert main(["modes", str(f), "--count", "3", "--json", "--plot", str(png)]) == 0
    d = json.loads(capsys.readouterr().out)
    fr = d["frequencies_hz"]
    assert len(fr) == 3 and fr == sorted(fr)
    assert fr[0] == pytest.approx(1.9385, rel=1e-3)
    assert png.stat().st_size > 5000


def test_modes_pendulum_removes_rigid_mode(pendulum_file, capsys):
    assert main(["modes", str(pendulum_file), "--json", "--count", "2"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["rigid_body_modes_removed"] == 1
    assert d["frequencies_hz"][0] > 0.1


def test_summary_separates_setup_and_time_loop(tmp_path, pendulum_file, capsys):
    out = tmp_path / "run"
    assert main(["simulate", str(pendulum_file), "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["setup_wall_time_s"] > 0 and summary["solve_wall_time_s"] > 0
    # to the clock tick of /proc (0.01 s on Linux), with no digits beyond it
    assert len(repr(summary["setup_wall_time_s"]).split(".")[1]) <= 3
    assert summary["pid"] > 0 and summary["started_at"] and summary["updated_at"]
    assert summary["threads"] == 1  # a small model's element loops: one thread
    assert summary["time_per_step_s"] == pytest.approx(summary["solve_wall_time_s"] / 20)
    line = capsys.readouterr().out
    assert f"{1e3 * summary['time_per_step_s']:.3f} ms/step" in line
    assert not (out / ".history").exists()
