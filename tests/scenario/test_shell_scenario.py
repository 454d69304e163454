"""Shell bodies in scenario files: a surface [geometry] makes a flexible body a shell, with its
own mesh, section and material keys, edge and point places, and clear one-line refusals."""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import numpy as np
import pytest

from rancf.bodies.shell_loads import resultant
from rancf.bodies.shell_supports import constraint_rows
from rancf.errors import ScenarioError
from rancf.scenario import Scenario
from rancf.scenario.shell_build import (
    shell_body,
    shell_indices,
    shell_load,
    shell_sensor_values,
    shell_sensors,
)

ROOF = """
[geometry]
kind = "cylinder"
radius = 25.0
length = 50.0
angles_deg = [50.0, 130.0]

[mesh]
elements = [4, 4]

[section]
thickness = 0.25

[material]
youngs_modulus = 4.32e8
poisson_ratio = 0.0
density = 1.0

[[supports]]
at = "v0"
kind = "diaphragm"

[[supports]]
at = "v1"
kind = "diaphragm"

[[supports]]
at = "u0"
kind = "symmetry"
normal = [1.0, 0.0, 0.0]

[[supports]]
at = [0.5, 0.5]
kind = "roller"
axis = [0.0, 0.0, 1.0]

[[loads.distributed]]
force = [0.0, 0.0, -90.0]

[[loads.point]]
at = [0.5, 1.0]
force = [0.0, 0.0, -1.0]

[[loads.edge]]
at = "u1"
force = [0.0, 0.0, -2.0]
moment = [0.0, 3.0, 0.0]

[[sensors]]
name = "mid"
kind = "position"
at = [0.0, 0.5]
"""


def _raw() -> dict:
    return tomllib.loads(ROOF)


def _error(raw: dict) -> str:
    with pytest.raises(ScenarioError) as info:
        Scenario.from_dict(raw, "roof.toml")
    msg = str(info.value)
    assert "\n" not in msg, msg
    return msg


def test_a_surface_geometry_makes_a_shell_with_its_places():
    sc = Scenario.from_dict(_raw(), "roof.toml")
    assert sc.dim == 3
    assert sc.mesh is not None and sc.mesh.pair == (4, 4)
    assert sc.section is not None and sc.section.thickness == 0.25
    kinds = [(s.at, s.kind) for s in sc.supports]
    assert kinds[0] == ("v0", "diaphragm") and kinds[2][1] == "symmetry"
    assert sc.supports[2].normal == [1.0, 0.0, 0.0]
    p = sc.place("u1")
    assert (p.where, p.edge) == ("edge", "u1")
    q = sc.place([0.5, 1.0])
    assert (q.where, q.uv) == ("surface", (0.5, 1.0))
    assert sc.data["loads"]["edge"][0]["moment"] == [0.0, 3.0, 0.0]
    assert sc.sensors[0].places == ([0.0, 0.5],)
    assert Scenario.from_dict(sc.to_dict()) == Scenario.from_dict(_raw())


def test_a_shell_among_bodies_has_named_places():
    raw = _raw()
    body = {k: raw.pop(k) for k in ("geometry", "mesh", "section", "material")}
    raw["bodies"] = [{"name": "roof", **body}]
    for s in raw["supports"]:
        s["at"] = f"roof:{s['at']}" if isinstance(s["at"], str) else "roof:0.5,0.5"
    raw["loads"]["point"][0]["at"] = "roof:0.5,1"
    raw["loads"]["edge"][0]["at"] = "roof:u1"
    raw["sensors"][0]["at"] = "roof:0,0.5"
    sc = Scenario.from_dict(raw, "roof.toml")
    assert sc.place("roof:0.5,1").uv == (0.5, 1.0)
    assert sc.place("roof:v1").edge == "v1"


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        (
            lambda d: d["section"].update(radius=0.1),
            "[section.radius] a shell's section is its thickness only",
        ),
        (
            lambda d: d.update(section={"radius": 0.1}),
            "[section.radius] applies to line bodies (cables, beams, rods), not to a shell",
        ),
        (
            lambda d: d["material"].update(shear_modulus=1e8, poisson_ratio=None),
            "[material.shear_modulus] applies to line bodies",
        ),
        (lambda d: d["mesh"].update(continuity="C2"), "[mesh.continuity] applies to line bodies"),
        (
            lambda d: d["material"].update(axial_law={"table": [[0.0, 0.0], [0.1, 1e6]]}),
            "[material.axial_law] applies to line bodies",
        ),
        (lambda d: d["mesh"].update(elements=4), "[mesh.elements] must be [nu, nv] for a shell"),
        (lambda d: d["mesh"].update(elements=[4, 0]), "[mesh.elements[1]] must be >= 1"),
        (lambda d: d["material"].pop("poisson_ratio"), "[material.poisson_ratio] required"),
        (
            lambda d: d["geometry"].update(angles_deg=[0.0, 400.0]),
            "[geometry.angles_deg] must be [start, end] degrees",
        ),
        (
            lambda d: d["geometry"].update(start=[0.0, 0.0, 0.0]),
            "[geometry.start] does not apply to kind = 'cylinder'",
        ),
        (
            lambda d: d["supports"][3].update(at=[0.5, 1.2]),
            "[supports[3].at] a place of a shell is an edge",
        ),
        (lambda d: d["supports"][3].update(at="end"), "[supports[3].at] a place of a shell"),
        (
            lambda d: d["supports"][0].update(at=[0.5, 0.0]),
            "[supports[0].at] a diaphragm holds an edge",
        ),
        (lambda d: d["supports"][2].pop("normal"), "[supports[2].normal] required for kind"),
        (
            lambda d: d["supports"][0].update(position=[0.0, 0.0, 0.0]),
            "[supports[0].position] not for a shell's support",
        ),
        (
            lambda d: d["loads"]["point"][0].update(at="u1"),
            "[loads.point[0].at] a point load on a shell acts at a point",
        ),
        (
            lambda d: d["loads"]["point"][0].update(moment=[1.0, 0.0, 0.0]),
            "[loads.point[0].moment] applies to rod elements only",
        ),
        (
            lambda d: d["loads"]["edge"][0].update(at=[1.0, 0.5]),
            "[loads.edge[0].at] must be an edge of a shell",
        ),
        (
            lambda d: d["sensors"][0].update(kind="tension"),
            "[sensors[0].at] a tension sensor measures at a node",
        ),
        (lambda d: d["sensors"][0].update(at="u0"), "[sensors[0].at] must be a surface point"),
    ],
)
def test_bad_shell_input_is_one_line_naming_the_key(change, needle):
    raw = _raw()
    change(raw)
    msg = _error(raw)
    assert msg.startswith("roof.toml: ") and needle in msg, msg


LINE = {
    "geometry": {"kind": "line", "start": [0.0, 0.0, 0.0], "end": [1.0, 0.0, 0.0]},
    "mesh": {"elements": 4},
    "section": {"radius": 0.01},
    "material": {"density": 7800.0, "youngs_modulus": 2e11},
}


@pytest.mark.parametrize(
    ("change", "needle"),
    [
        (
            lambda d: d.update(section={"thickness": 0.01}),
            "[section.thickness] applies to shells",
        ),
        (lambda d: d["mesh"].update(elements=[4, 4]), "[mesh.elements] must be one number"),
        (
            lambda d: d.update(supports=[{"at": "end", "kind": "diaphragm"}]),
            "[supports[0].kind] 'diaphragm' holds a shell's edge",
        ),
        (
            lambda d: d.update(supports=[{"at": [0.5, 0.5]}]),
            "[supports[0].at] a surface point [u, v] is a place of a shell",
        ),
        (
            lambda d: d["loads"].update(edge=[{"at": "end", "force": [0.0, 0.0, 1.0]}]),
            "[loads.edge[0].at] must be an edge of a shell",
        ),
    ],
)
def test_shell_keys_on_a_line_are_refused(change, needle):
    raw = copy.deepcopy(LINE)
    raw["loads"] = {}
    change(raw)
    msg = _error(raw)
    assert needle in msg, msg


def test_the_system_refuses_a_shell_support_in_one_line_naming_its_key():
    sc = Scenario.from_dict(_raw(), "roof.toml")
    with pytest.raises(ScenarioError, match=r"^roof.toml: \[supports\[2\]\.normal\] the direction"):
        sc.build_system()


DATA = Path(__file__).parent / "data"


def test_the_roof_file_builds_its_shell_body():
    sc = Scenario.from_toml(DATA / "scordelis_lo.toml")
    (i,) = shell_indices(sc)
    body = shell_body(sc, i)
    assert body.thickness == 0.25 and body.poisson_ratio == 0.0 and len(body.supports) == 3
    c, d = constraint_rows(body)
    # a node: diaphragm 4, symmetry 6 rows; held twice where they meet: 2 (u0 v0) + 3 (u0 v1)
    assert c.shape == (5 * 4 + 2 * 5 * 6 - 5, body.n_dofs)
    assert np.linalg.matrix_rank(c.toarray()) == c.shape[0]
    force, _ = resultant(body, shell_load(sc, body))
    area = 25.0 * np.radians(40.0) * 25.0
    np.testing.assert_allclose(force, [0.0, 0.0, -90.0 * area], rtol=1e-12, atol=1e-8)
    ((name, uv),) = shell_sensors(sc, body)
    a = np.radians(130.0)
    np.testing.assert_allclose(body.position(uv), [25 * np.cos(a), 25.0, 25 * np.sin(a)])
    assert name == "free_mid"
    moved = body.q0.reshape(-1, 4, 3).copy()
    moved[:, 0, 2] -= 0.3
    cols = shell_sensor_values(sc, body, moved.ravel())
    assert list(cols) == ["free_mid_x", "free_mid_y", "free_mid_z"]
    assert abs(cols["free_mid_z"] - (25 * np.sin(a) - 0.3)) < 1e-12


def test_gravity_on_a_shell_is_its_weight_per_area():
    raw = _raw()
    raw["loads"] = {"gravity": [0.0, 0.0, -9.81]}
    sc = Scenario.from_dict(raw)
    body = shell_body(sc, 0)
    force, _ = resultant(body, shell_load(sc, body))
    weight = 1.0 * 0.25 * 25.0 * np.radians(80.0) * 50.0 * 9.81
    np.testing.assert_allclose(force, [0.0, 0.0, -weight], rtol=1e-12, atol=1e-8)


def test_buckling_refuses_a_shell_in_one_line_and_writes_nothing(tmp_path, monkeypatch, capsys):
    from rancf.cli import main

    monkeypatch.chdir(tmp_path)
    (tmp_path / "roof.toml").write_text((DATA / "scordelis_lo.toml").read_text())
    assert main(["buckling", "roof.toml"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "[geometry] 'cylinder' makes the body a shell" in err[0], err
    assert "`rancf buckling` does not run shells yet" in err[0], err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["roof.toml"]
