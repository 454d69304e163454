"""Contact outputs through the command line: a one-body file with a ground plane
(``[[obstacles]]``), the ground's columns in reactions.csv (normal, friction, contact length,
penetration), the ``contact_force`` sensor, the contact files of ``rancf export --vtk``, and
bad obstacle input as one line naming the key."""

from __future__ import annotations

from pathlib import Path

import meshio
import numpy as np
import pytest

from rancf.cli import main

R, L, RHO, G = 0.002, 1.0, 7850.0, 9.81

GROUND = f"""
[geometry]
kind = "line"
start = [0.0, {R + 0.01}]
end = [{L}, {R + 0.03}]
[mesh]
elements = 16
[section]
radius = {R}
[material]
density = {RHO}
youngs_modulus = 2.0e11
[loads]
gravity = [0.0, -{G}]
[damping]
mass_proportional = 20.0
[[obstacles]]
name = "ground"
kind = "plane"
point = [0.0, 0.0]
normal = [0.0, 1.0]
friction = 0.3
[solver]
t_end = 0.6
step = 1.0e-3
output_step = 0.01
rho_inf = 0.5
max_newton = 25
[[sensors]]
name = "floor"
kind = "contact_force"
obstacle = "ground"
"""


def _table(path: Path) -> dict[str, np.ndarray]:
    d = np.genfromtxt(path, delimiter=",", names=True)
    return {k: d[k] for k in d.dtype.names}


def test_ground_columns_sensor_and_vtk(tmp_path, capsys):
    """A tilted cable dropped 1 cm onto the ground with friction comes to rest: the ground's
    normal force is its weight (1e-3), the friction force vanishes at rest, the contact length
    is the cable's length, the penetration stays below 1 % of the radius; the sensor is the
    normal and friction columns summed; the VTK export has the ground's forces over time."""
    f = tmp_path / "ground.toml"
    f.write_text(GROUND)
    assert main(["simulate", str(f), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    r = _table(tmp_path / "run" / "reactions.csv")
    s = _table(tmp_path / "run" / "sensors.csv")
    weight = RHO * np.pi * R**2 * np.hypot(L, 0.02) * G
    assert r["ground_normal_y"][-1] == pytest.approx(weight, rel=1e-3)
    assert abs(r["ground_normal_x"][-1]) < 1e-3 * weight
    assert np.hypot(r["ground_friction_x"][-1], r["ground_friction_y"][-1]) < 1e-3 * weight
    assert np.max(np.abs(r["ground_friction_x"])) > 1e-3 * weight  # it acted while sliding
    assert r["ground_length"][0] == 0.0 and r["ground_length"][-1] == pytest.approx(
        np.hypot(L, 0.02), rel=1e-3
    )
    assert np.max(r["ground_penetration"]) < 0.01 * R
    total = r["ground_normal_y"] + r["ground_friction_y"]
    assert s["floor_y"] == pytest.approx(total, rel=1e-10, abs=1e-15)
    capsys.readouterr()
    assert (
        main(["export", str(tmp_path / "run"), "--vtk", str(tmp_path / "vtk"), "--every", "20"])
        == 0
    )
    assert "contact forces: open" in capsys.readouterr().out
    assert (tmp_path / "vtk" / "contact.pvd").is_file()
    last = sorted((tmp_path / "vtk").glob("contact_*.vtu"))[-1]
    m = meshio.read(last)
    assert m.points.tolist() == [[0.0, 0.0, 0.0]]
    assert m.point_data["normal_force"][0][1] == pytest.approx(r["ground_normal_y"][-1], rel=1e-9)
    assert m.point_data["contact_length"][0] == pytest.approx(r["ground_length"][-1], rel=1e-9)


@pytest.mark.parametrize(
    ("change", "message"),
    [
        ('kind = "sphere"\ncenter = [0.0, 0.0]\nradius = 1.0', "obstacles[0].kind"),
        ("radius = 0.5", "obstacles[0].radius"),
        ('body = "nobody"', "obstacles[0].body"),
        ("damping = -1", "obstacles[0].damping"),
        ("normal = [0.0, 0.0]", "obstacles[0].normal"),
    ],
)
def test_bad_obstacles_are_one_line(tmp_path, capsys, change, message):
    text = GROUND
    if change.startswith("kind"):
        text = text.replace('kind = "plane"\npoint = [0.0, 0.0]\nnormal = [0.0, 1.0]', change)
    elif change.startswith("normal"):
        text = text.replace("normal = [0.0, 1.0]", change)
    else:
        text = text.replace('kind = "plane"', 'kind = "plane"\n' + change)
    f = tmp_path / "bad.toml"
    f.write_text(text)
    assert main(["simulate", str(f), "--out", str(tmp_path / "run"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and message in err[0], err


TWO = """
contacts = [["low", "ground"]]
body_contacts = [["low", "high"]]
[[bodies]]
name = "low"
[bodies.geometry]
kind = "line"
start = [0.0, 0.002]
end = [1.0, 0.002]
[bodies.mesh]
elements = 8
[bodies.section]
radius = 0.002
[bodies.material]
density = 7850.0
youngs_modulus = 2.0e11
[[bodies]]
name = "high"
[bodies.geometry]
kind = "line"
start = [0.2, 0.008]
end = [0.8, 0.008]
[bodies.mesh]
elements = 4
[bodies.section]
radius = 0.002
[bodies.material]
density = 7850.0
youngs_modulus = 2.0e11
[loads]
gravity = [0.0, -9.81]
[damping]
mass_proportional = 20.0
[[obstacles]]
name = "ground"
kind = "plane"
point = [0.0, 0.0]
normal = [0.0, 1.0]
[solver]
t_end = 0.3
step = 1.0e-3
output_step = 0.01
rho_inf = 0.5
max_newton = 25
"""


def test_body_contacts_from_a_file(tmp_path, capsys):
    """``body_contacts`` in a file: the upper cable falls 2 mm onto the lower one on the ground;
    reactions.csv has the pair's force (at rest: the upper cable's weight, 1e-3) and its
    penetration (below 1 % of r); a pair naming no flexible body is one line."""
    f = tmp_path / "two.toml"
    f.write_text(TWO)
    assert main(["simulate", str(f), "--out", str(tmp_path / "run"), "--quiet"]) == 0
    # elements of 12.5 and 15 cm, 8 contact points each: crossings could pass through
    # and the impact at 24 ms is not resolved by its 1 ms steps
    *warn, impact = capsys.readouterr().err.strip().splitlines()
    assert warn == [
        "rancf: warning: high: contact points up to 9.38 tube radii apart: tubes crossing at a "
        "large angle can pass through each other between them; give contact_points = 64 (an "
        "element's length over the radius) and shorter elements",
        "rancf: warning: low: contact points up to 7.81 tube radii apart: tubes crossing at a "
        "large angle can pass through each other between them; give contact_points = 63 (an "
        "element's length over the radius)",
    ]
    assert impact.startswith("rancf: warning: the local error estimate is ")
    assert "t = 0.024 s" in impact
    r = _table(tmp_path / "run" / "reactions.csv")
    w_high = RHO * np.pi * R**2 * 0.6 * G
    assert r["low_high_contact_force"][0] == 0.0
    assert r["low_high_contact_force"][-1] == pytest.approx(w_high, rel=1e-3)
    assert np.max(r["low_high_penetration"]) < 0.01 * R
    assert r["ground_normal_y"][-1] == pytest.approx(w_high / 0.6 * 1.6, rel=1e-3)
    f.write_text(TWO.replace('body_contacts = [["low", "high"]]', 'body_contacts = [["low", "x"]]'))
    capsys.readouterr()
    assert main(["simulate", str(f), "--out", str(tmp_path / "bad"), "--quiet"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "body_contacts[0]" in err[0], err
