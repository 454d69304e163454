"""``solver.static_method = "linear"``: the small-displacement answer of the linear benchmarks
(one solve with the reference's stiffness), through ``rancf static``."""

from __future__ import annotations

import json
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.errors import InputError, ScenarioError
from rancf.runs.static import run_static
from rancf.scenario import Scenario, load_scenario
from rancf.scenario.toml_text import dumps

ROOF = Path(__file__).parents[1] / "scenario" / "data" / "scordelis_lo.toml"
#: The middle of the roof's free edge moves down 0.3006 (linear; MacNeal & Harder 1985).
ROOF_REFERENCE = 0.3006


def _linear_file(src: Path, dest: Path, **solver: object) -> Path:
    """``src`` with ``[solver] static_method = "linear"`` (and ``solver``) written to ``dest``."""
    import tomllib

    raw = tomllib.loads(src.read_text())
    raw["solver"] = {"static_method": "linear", **solver}
    dest.write_text(dumps(raw))
    return dest


def test_the_roofs_linear_deflection_is_the_benchmarks(tmp_path, monkeypatch, capsys):
    """4 x 4 elements: the middle of the free edge moves down the linear 0.3006 within 1.5 %
    (the default, nonlinear statics gives 0.2529); the run says it is linear and warns that the
    deflection exceeds the thickness."""
    monkeypatch.chdir(tmp_path)
    _linear_file(ROOF, tmp_path / "roof.toml")
    assert main(["static", "roof.toml", "--out", "run"]) == 0
    out, err = capsys.readouterr()
    assert out.startswith("static equilibrium (linear):"), out
    assert "linear displacement is large" in err and "0.25 m" in err, err
    sensors = np.loadtxt(tmp_path / "run" / "sensors.csv", delimiter=",", skiprows=1)
    w = sensors[0, 3] - sensors[-1, 3]
    assert abs(w - ROOF_REFERENCE) < 0.015 * ROOF_REFERENCE, w
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["method"] == "linear" and summary["status"] == "completed"
    assert any("a nonlinear solve" in line for line in summary["warnings"]), summary["warnings"]
    assert len(sensors) == 2  # the reference and the linear state


def test_a_cantilevers_linear_tip_deflection_is_p_l3_over_3ei(tmp_path):
    """A tip load on a clamped cable beam: ``P L³ / 3EI`` (the cubic elements hold it exactly),
    the reactions those of the linear solve (no axial force: the nonlinear balance at the
    deflected state would have one of second order)."""
    src = resources.files("rancf.examples") / "cantilever.toml"
    sc = load_scenario(str(_linear_file(Path(str(src)), tmp_path / "c.toml")))
    run = run_static(sc)
    ei = run.system.flex[0].props.ei
    p, length = 1e-3, 0.5
    assert run.result.method == "linear" and run.result.n_newton == 1
    assert run.sensors["tip_y"] == pytest.approx(-p * length**3 / (3 * ei), rel=1e-6)
    assert not run.notes  # 3 µm under a 6 cm section: no large-displacement warning
    from rancf.post.static_run import reactions_json

    (r,) = reactions_json(run.outputs, run.result.y, run.result.lam)
    assert r["force"][0] == pytest.approx(0.0, abs=1e-12) and r["force"][1] == pytest.approx(p)
    assert r["moment"][0] == pytest.approx(p * length)


def _pendulum(supports: list[str]) -> dict:
    return {
        "solver": {"static_method": "linear"},
        "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [1.0, 0.0]},
        "mesh": {"elements": 4},
        "section": {"radius": 0.01},
        "material": {"density": 1000.0, "youngs_modulus": 1e9},
        "supports": [{"at": a, "kind": "pin"} for a in supports],
        "loads": {"gravity": [0.0, -9.81]},
    }


def test_a_mechanism_has_no_linear_answer_said_in_one_line():
    """A bar pinned at one end, drawn horizontal under gravity: its swing meets no stiffness."""
    with pytest.raises(ScenarioError, match="solver.static_method") as exc:
        run_static(Scenario.from_dict(_pendulum(["start"])))
    assert "mechanism" in str(exc.value) and "\n" not in str(exc.value)


def test_the_linear_reactions_carry_the_weight():
    """Pinned at both ends: each pin carries half the weight, no axial force (the nonlinear
    solve has its ends pull in: a string's tension)."""
    run = run_static(Scenario.from_dict(_pendulum(["start", "end"])))
    from rancf.post.static_run import reactions_json

    weight = 1000.0 * np.pi * 1e-4 * 9.81
    for r in reactions_json(run.outputs, run.result.y, run.result.lam):
        assert r["force"] == pytest.approx([0.0, weight / 2], rel=1e-8, abs=1e-9)


def test_a_linear_state_is_no_start_for_a_run():
    raw = _pendulum(["start", "end"])
    raw["solver"]["initial_state"] = "static"
    from rancf.solvers.start import start_state

    sc = Scenario.from_dict(raw)
    with pytest.raises(InputError, match="initial_state"):
        start_state(sc, sc.build_system())


def test_a_linear_answer_with_large_rotations_is_refused_in_one_line(tmp_path):
    """The shipped mooring line unloaded straight: its linear answer about the straight
    reference turns the chain by far more than a radian (and stretches it by 1e13 %): refused
    naming the method, where it printed tensions of 1e25 N with warnings."""
    with resources.as_file(resources.files("rancf.examples") / "mooring-line.toml") as src:
        sc = load_scenario(src)
    raw = sc.to_dict()
    raw["solver"]["static_method"] = "linear"
    with pytest.raises(ScenarioError, match=r"solver\.static_method.*turns by about") as exc:
        run_static(Scenario.from_dict(raw, str(tmp_path / "m.toml")))
    assert "\n" not in str(exc.value)
