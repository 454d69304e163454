"""Scenario keys of rod elements: what they build, and the twist sensor."""

import json
import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import parse_scenario
from rancf.solvers.static import solve_static
from tests.test_cli_errors import PRINCIPAL, ROD, dump


def _rod(**tables):
    d = tomllib.loads(ROD)
    for k, v in tables.items():
        d[k] = v
    return parse_scenario(d, "rod.toml")


def test_circular_section_and_poisson_ratio():
    m = _rod().build_model()
    assert m.element == "rod" and m.dpn == 7 and m.n == 7 * 4
    stiff = m.core  # the model's stiffnesses as the core sees them
    r, e, nu = 0.03, 2.0e7, 0.3
    inertia = np.pi * r**4 / 4
    assert m.section.torsion == pytest.approx(2 * inertia)
    assert m.material.shear == pytest.approx(e / (2 * (1 + nu)))
    assert stiff.n == m.n
    # clamp: position, tangent direction and twist of node 0 fixed
    assert m.fixed[:7].tolist() == [True, True, True, False, True, True, True]


def test_principal_section_orientation_and_torsion_constant():
    sec = {**PRINCIPAL, "torsion_constant": 5e-8}
    mat = {"density": 6000.0, "youngs_modulus": 2e7, "shear_modulus": 8e6}
    m = _rod(section=sec, material=mat).build_model()
    s = m.section
    assert (s.area, s.inertia, s.inertia_2, s.torsion) == (1e-3, 1e-7, 2e-7, 5e-8)
    assert m.material.shear == 8e6
    assert m.kernel.m1ref[0] == pytest.approx([0.0, 0.0, 1.0])  # orientation at node 0
    # m1 = e_z is the normal of the arc's plane: bending in the plane is about m1 and uses
    # inertia_y, so the in-plane stiffness equals that of a round section with inertia_y
    ref = _rod(section={"area": 1e-3, "inertia": 1e-7}, material=mat).build_model()
    k1, k2 = (mm.dense(mm.internal_force_and_tangent(mm.y0)[1]) for mm in (m, ref))
    inplane = np.zeros((m.n_nodes, 7), dtype=bool)
    inplane[:, [0, 1, 3, 4]] = True
    sel = inplane.ravel()
    assert np.allclose(k1[np.ix_(sel, sel)], k2[np.ix_(sel, sel)], rtol=1e-12, atol=1e-9)


def test_radius_with_torsion_constant_and_fix_twist():
    sec = {"radius": 0.03, "torsion_constant": 1e-7}
    sup = [{"at": "start", "kind": "pin", "fix_twist": True}, {"at": "end"}]
    m = _rod(section=sec, supports=sup).build_model()
    assert m.section.torsion == 1e-7
    assert m.fixed[:7].tolist() == [True] * 3 + [False] * 3 + [True]
    assert m.fixed[-7:].tolist() == [True] * 3 + [False] * 4


def test_moment_and_twist_sensor_through_static(tmp_path, capsys):
    """A torque about the chord of a straight rod: the twist sensor reads T L / (G J)."""
    d = tomllib.loads(ROD)
    d["geometry"] = {"kind": "line", "start": [0.0, 0.0, 0.0], "end": [0.5, 0.0, 0.0]}
    torque = 1e-3
    d["loads"] = {"point": [{"at": "end", "moment": [torque, 0.0, 0.0]}]}
    d["sensors"] = [
        {"name": "phi", "kind": "twist", "at": "end"},
        {"name": "tip", "kind": "position", "at": "end"},
    ]
    sc = parse_scenario(d, "t.toml")
    assert [s.columns(3) for s in sc.sensors] == [["phi"], ["tip_x", "tip_y", "tip_z"]]
    m = sc.build_model()
    gj = m.material.shear * m.section.torsion
    (tmp_path / "t.toml").write_text(dump(d))
    assert main(["static", str(tmp_path / "t.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["sensors"]["phi"] == pytest.approx(torque * 0.5 / gj, rel=1e-6)
    y = solve_static(m, load_steps=1).q
    assert y.reshape(m.n_nodes, 7)[-1, 6] == pytest.approx(out["sensors"]["phi"], rel=1e-9)


def test_simulate_writes_the_twist_column(tmp_path, capsys):
    d = tomllib.loads(ROD)
    d["loads"] = {"point": [{"at": "end", "moment": [1e-3, 0.0, 0.0], "frequency_hz": 5.0}]}
    d["sensors"] = [{"name": "phi", "kind": "twist", "at": -1}]
    (tmp_path / "s.toml").write_text(dump(d))
    assert (
        main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r"), "--quiet"]) == 0
    )
    rows = (tmp_path / "r" / "sensors.csv").read_text().splitlines()
    assert rows[0] == "t,phi"
    assert len(rows) == 22 and float(rows[-1].split(",")[1]) != 0.0


def test_modes_command_reports_torsional_modes(tmp_path, capsys):
    """``rancf modes`` on a clamped straight rod lists the torsion bar's first frequency
    ``sqrt(G / ρ) / (4 L)`` among the bending ones (no zero modes)."""
    d = tomllib.loads(ROD)
    d["geometry"] = {"kind": "line", "start": [0.0, 0.0, 0.0], "end": [0.0, 0.0, 0.5]}
    d["mesh"]["elements"] = 16
    (tmp_path / "t.toml").write_text(dump(d))
    assert main(["modes", str(tmp_path / "t.toml"), "--count", "12", "--json"]) == 0
    f = np.array(json.loads(capsys.readouterr().out)["frequencies_hz"])
    g = 2.0e7 / (2 * 1.3)
    torsion = np.sqrt(g / 6000.0) / (4 * 0.5)
    assert f.min() > 1.0
    assert np.min(np.abs(f / torsion - 1)) < 5e-3


def test_modes_note_points_curved_spatial_cables_to_the_rod(tmp_path, capsys):
    d = tomllib.loads(ROD)
    d["mesh"]["element"] = "rancf"
    del d["material"]["poisson_ratio"]
    (tmp_path / "c.toml").write_text(dump(d))
    assert main(["modes", str(tmp_path / "c.toml")]) == 0
    out = capsys.readouterr().out
    assert "0.000000 Hz" in out and 'mesh.element = "rod"' in out
