"""Statics that find the equilibrium a user means: where Newton's method along the load path
cannot start or stalls, relaxation (pseudo-transient continuation,
``docs/derivations/relaxation.md``) follows the physics to rest and Newton polishes it."""

from __future__ import annotations

import json

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import load_scenario
from rancf.solvers.static import solve_static
from rancf.solvers.system_equilibrium import SystemEquilibrium

G = 9.81

PENDULUM = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]

[mesh]
elements = 8
element = "rancf"

[section]
radius = 0.005

[material]
density = 7850.0
youngs_modulus = 2.0e11

[[supports]]
at = "start"
kind = "pin"

[loads]
gravity = [0.0, -9.81]

[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""

# an L-shaped route, legs of 2 m and 1 m with a 5 cm corner (a degree-2 NURBS whose first and
# last segments are straight), a rope: EA = 1e5 N, almost no bending stiffness (EI = 2e-3 N m²)
ROPE = """
[geometry]
kind = "nurbs"
degree = 2
knots = [0, 0, 0, 0.49, 0.51, 1, 1, 1]
control_points = [[0.0, 0.0], [1.95, 0.0], [2.0, 0.0], [2.0, -0.05], [2.0, -1.0]]

[mesh]
elements = 24
element = "rancf"

[section]
area = 5.0e-5
inertia = 1.0e-12

[material]
density = 1140.0
youngs_modulus = 2.0e9

[[supports]]
at = "start"
kind = "pin"

[[supports]]
at = "end"
kind = "pin"

[loads]
gravity = [0.0, -9.81]

[[sensors]]
name = "mid"
kind = "position"
at = 12
"""


def _static_json(tmp_path, name, text, capsys):
    f = tmp_path / f"{name}.toml"
    f.write_text(text)
    assert main(["static", str(f), "--json"]) == 0
    return f, json.loads(capsys.readouterr().out)


def test_a_pinned_pendulum_drawn_horizontal_comes_to_rest_hanging(tmp_path, capsys):
    """The reference has no stiffness against the swing: load stepping cannot start, relaxation
    brings the cable to hang straight below its pin (tip x = 0 to 1e-9 of the length, the tip
    one stretched length below), and the pin carries the weight to 1e-9."""
    f, doc = _static_json(tmp_path, "pendulum", PENDULUM, capsys)
    assert doc["method"] == "relaxation+newton" and doc["relaxation_steps"] > 0
    assert doc["load_factors"][-1] == 1.0
    weight = load_scenario(f).build_model().total_mass * G
    assert weight == pytest.approx(7850.0 * np.pi * 0.005**2 * G, rel=1e-12)
    tip = doc["positions"]["body"][-1]
    assert abs(tip[0]) <= 1e-9 and -1.0001 < tip[1] < -1.0  # stretched by its own weight
    assert doc["sensors"]["tip_x"] == tip[0]
    (pin,) = doc["reactions"]
    assert pin["at"] == "start"
    assert np.abs(np.array(pin["force"]) - [0.0, weight]).max() <= 1e-9 * weight
    assert main(["static", str(f), "--out", str(tmp_path / "run")]) == 0
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("static equilibrium (relaxation+newton): ")
    assert "relaxation steps" in first
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["method"] == "relaxation+newton" and summary["status"] == "completed"
    assert summary["relaxation_steps"] == doc["relaxation_steps"]


def test_an_l_shaped_rope_pinned_at_both_ends_sags(tmp_path, capsys):
    """The slack rope drawn as an L (solved from its catenary start shape, no longer by
    relaxation from the L) sags below the chord between its pins; the
    horizontal reactions are equal and opposite (the rope's horizontal tension), the vertical
    ones carry the weight (1e-9), and the residual of the equilibrium is zero to the solver's
    tolerance: at most the force ``EA · 1e-10`` of an axial strain at the tolerance (1e-10 of
    the size; measured 2.9e-6 N = 2.9e-11 EA, the floor further Newton iterations keep)."""
    f, doc = _static_json(tmp_path, "rope", ROPE, capsys)
    assert doc["method"] == "sag start+newton"
    weight = load_scenario(f).build_model().total_mass * G
    a, b = (np.array(r["force"]) for r in doc["reactions"])
    assert a[0] < 0.0 < b[0]  # the pins pull the rope's ends apart: tension
    assert abs(a[0] + b[0]) <= 1e-9 * weight
    assert a[1] + b[1] == pytest.approx(weight, rel=1e-9)
    pos = np.array(doc["positions"]["body"])
    chord = pos[0] + (pos[:, 0:1] / 2.0) * (pos[-1] - pos[0])  # the line between the pins
    assert np.all(pos[1:-1, 1] < chord[1:-1, 1])  # every inner node hangs below it
    assert pos[:, 1].min() < -1.2  # 3 m of rope over a 2.24 m chord sags well below the L
    system = load_scenario(f).build_system()
    res = solve_static(system)
    assert res.method == "sag start+newton"
    r = SystemEquilibrium(system).residual(np.r_[res.y, res.lam], 1.0)
    assert np.abs(r).max() <= 1e-10 * 2.0e9 * 5.0e-5
    assert np.abs(system.flex[0].node_positions(res.q) - pos).max() <= 1e-9


def test_a_pendulum_without_its_pin_has_no_equilibrium_and_says_so_in_one_line(tmp_path, capsys):
    f = tmp_path / "free.toml"
    f.write_text(PENDULUM.replace('[[supports]]\nat = "start"\nkind = "pin"\n', ""))
    assert main(["static", str(f)]) == 3
    err = capsys.readouterr().err.strip()
    assert "\n" not in err
    assert "no equilibrium" in err and "add a support" in err and "load factor 0" in err


def test_a_mechanism_is_recognised_at_its_reference(tmp_path):
    """The stiffness the loads meet at the reference (the Rayleigh quotient of the linear
    response) is below round-off for the horizontal pendulum, and above it for a tension-free
    straight cable (its bending stiffness) and for a clamped cantilever: the pendulum's path
    goes to relaxation directly (the static answer, hanging, whatever the factorization's
    round-off), the others follow the load path."""
    from rancf.system import as_system
    from tests.solvers.test_equilibrium import ssnl114_model

    f, g = tmp_path / "pendulum.toml", tmp_path / "cantilever.toml"
    f.write_text(PENDULUM)
    g.write_text(PENDULUM.replace('kind = "pin"', 'kind = "clamp"'))
    pendulum = SystemEquilibrium(load_scenario(f).build_system())
    assert pendulum.mechanism(pendulum.start())
    for system in (as_system(ssnl114_model(8)), load_scenario(g).build_system()):
        problem = SystemEquilibrium(system)
        assert not problem.mechanism(problem.start())
    assert solve_static(load_scenario(g).build_system()).method == "load"


def _cantilever(size: float) -> dict:
    """A clamped cantilever of length ``size``, radius ``size / 50`` and a tip load with
    ``P L² / EI = 2`` (the tip drops by half its length): the same problem at every size."""
    length, radius, e_mod = size, size / 50, 2.0e9
    load = 2.0 * e_mod * np.pi * radius**4 / 4 / length**2
    return {
        "geometry": {"kind": "line", "start": [0.0, 0.0], "end": [length, 0.0]},
        "mesh": {"elements": 8},
        "section": {"radius": radius},
        "material": {"density": 6000.0, "youngs_modulus": e_mod},
        "supports": [{"at": "start", "kind": "clamp"}],
        "loads": {"point": [{"at": "end", "force": [0.0, -load]}]},
    }


@pytest.mark.parametrize("size", [1e-5, 1e4])
def test_the_mechanism_test_and_the_path_do_not_depend_on_the_units(size):
    """A 10 µm cantilever (and a 10 km one) is no mechanism, as the 1 m one: in metres its
    gradients outweighed its positions in the Rayleigh quotient and the 10 µm one was taken
    for a mechanism (relaxation instead of the load path); the horizontal pendulum is one at
    any size. Both cantilevers follow the same load path to the same shape."""
    from rancf.scenario import parse_scenario

    small = parse_scenario(_cantilever(size)).build_system()
    problem = SystemEquilibrium(small)
    assert not problem.mechanism(problem.start())
    pend = _cantilever(size)
    pend["supports"][0]["kind"], pend["loads"] = "pin", {"gravity": [0.0, -G]}
    pendulum = SystemEquilibrium(parse_scenario(pend).build_system())
    assert pendulum.mechanism(pendulum.start())
    res, ref = solve_static(small), solve_static(parse_scenario(_cantilever(1.0)).build_system())
    assert res.method == ref.method == "load"
    assert len(res.load_factors) == len(ref.load_factors)
    q, q_ref = res.q.reshape(-1, 4), ref.q.reshape(-1, 4)  # positions, then gradients
    assert np.allclose(q[:, :2] / size, q_ref[:, :2], rtol=0, atol=1e-12)
    assert np.allclose(q[:, 2:], q_ref[:, 2:], rtol=0, atol=1e-12)
