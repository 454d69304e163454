"""`mesh.continuity = "C2"` on the command line: runs, exports and `export --nurbs`
give the same curves (a C² run of a cubic B-spline of n spans exports as n + 3 control points,
a C¹ run of the same mesh needs more), `rancf modes` counts fewer free coordinates, and bad
values get one clear line."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from rancf.cad import read_curves

SPLINE = """
[geometry]
kind = "nurbs"
degree = 3
knots = [0, 0, 0, 0, 0.2, 0.35, 0.6, 0.8, 1, 1, 1, 1]
control_points = [[0, 0], [0.1, 0.08], [0.25, 0.1], [0.4, 0.02], [0.55, -0.05], [0.7, 0.0],
                  [0.85, 0.1], [1.0, 0.05]]
weights = [1, 1, 1, 1, 1, 1, 1, 1]

[mesh]
elements = {per_span}
element = "{element}"
continuity = "{continuity}"

[section]
radius = 0.01

[material]
density = 1000.0
youngs_modulus = 1.0e7

[[supports]]
at = "start"
kind = "clamp"

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.05
step = 1.0e-3

[modes]
count = 2

[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""


def _rancf(tmp_path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "rancf", *args], capture_output=True, text=True, cwd=tmp_path
    )


def _write(tmp_path, name: str, **kw) -> str:
    kw = {"per_span": 1, "element": "rancf", "continuity": "C2"} | kw
    (tmp_path / name).write_text(SPLINE.format(**kw))
    return name


@pytest.mark.parametrize(("continuity", "n_ctrl"), [("C2", 8), ("C1", 12)])
def test_export_nurbs_of_a_run_is_its_curve(tmp_path, continuity, n_ctrl):
    """5 spans: C² deforms as a cubic B-spline of 8 control points and exports as one; C¹ keeps
    double knots (its nodes carry slopes of their own).  The exported curve passes through the
    run's nodes at its knots."""
    f = _write(tmp_path, "s.toml", continuity=continuity)
    p = _rancf(tmp_path, "simulate", f, "--out", "run")
    assert p.returncode == 0, p.stderr
    p = _rancf(tmp_path, "export", "run", "--nurbs", "shape.json")
    assert p.returncode == 0, p.stderr
    assert f"cubic NURBS, {n_ctrl} control points" in p.stdout
    (cad,) = read_curves(tmp_path / "shape.json")
    d = np.load(tmp_path / "run" / "results.npz")
    nodes = d["q"][-1].reshape(-1, 4)[:, :2]
    assert np.abs(nodes[-1] - [1.0, 0.05]).max() > 1e-3  # it moved
    knots = np.unique(cad.curve.knots)
    assert np.abs(cad.curve(knots)[:, :2] - nodes).max() < 1e-12
    rows = np.loadtxt(tmp_path / "run" / "sensors.csv", delimiter=",", skiprows=1)
    assert np.abs(rows[-1, 1:3] - nodes[-1]).max() < 1e-9  # the sensor reads the same tip


def test_c1_and_c2_runs_approach_each_other(tmp_path):
    """The tip after 0.05 s of falling: C² and C¹ meet as the spans are split."""
    tips = {}
    for c in ("C1", "C2"):
        for k in (1, 4):
            f = _write(tmp_path, f"{c}{k}.toml", continuity=c, per_span=k)
            p = _rancf(tmp_path, "simulate", f, "--out", f"{c}{k}")
            assert p.returncode == 0, p.stderr
            q = np.load(tmp_path / f"{c}{k}" / "results.npz")["q"][-1]
            tips[c, k] = q.reshape(-1, 4)[-1, :2]
    coarse = np.linalg.norm(tips["C1", 1] - tips["C2", 1])
    fine = np.linalg.norm(tips["C1", 4] - tips["C2", 4])
    assert fine < coarse / 50  # 2.8e-3 m with 5 elements, 1.1e-5 m with 20


def test_modes_count_fewer_free_coordinates(tmp_path):
    out = {}
    for c in ("C1", "C2"):
        p = _rancf(
            tmp_path, "modes", _write(tmp_path, f"{c}.toml", continuity=c, per_span=4), "--json"
        )
        assert p.returncode == 0, p.stderr
        out[c] = json.loads(p.stdout)
    # 20 elements: C¹ 2 (21) nodes x 2 coordinates - 3 held; C² 2 (20 + 3) - 3
    assert out["C1"]["n_dofs_free"] == 81 and out["C2"]["n_dofs_free"] == 43
    f1, f2 = (np.array(out[c]["frequencies_hz"]) for c in ("C1", "C2"))
    assert np.all(f2 >= f1) and np.all(f2 < 1.001 * f1)


@pytest.mark.parametrize(
    ("value", "element", "says"),
    [
        ('"C3"', "rancf", "mesh.continuity"),
        ('"C2"', "beam", "C2 needs cable or rod elements"),
    ],
)
def test_bad_continuity_is_one_line(tmp_path, value, element, says):
    text = SPLINE.format(per_span=1, element=element, continuity="X").replace('"X"', value)
    (tmp_path / "bad.toml").write_text(text)
    p = _rancf(tmp_path, "simulate", "bad.toml", "--out", "run")
    assert p.returncode == 2
    assert len(p.stderr.strip().splitlines()) == 1, p.stderr
    assert says in p.stderr and "continuity" in p.stderr


def test_c2_where_the_reference_curvature_jumps_says_so(tmp_path):
    """A Hermite (ANCF) reference of a conic has a curvature jump at every node: C2 cannot hold
    there, the nodes stay C1, and one warning line says so."""
    text = (
        '[geometry]\nkind = "conic"\nstart = [0.0, 0.0]\nend = [0.5, 0.0]\n'
        "angles_deg = [30.0, 40.0]\npoint = [0.315, 0.077]\n"
        '[mesh]\nelements = 3\nelement = "ancf"\ncontinuity = "C2"\n'
        "[section]\nradius = 0.02\n[material]\ndensity = 6000.0\nyoungs_modulus = 2.0e6\n"
        '[[supports]]\nat = "start"\nkind = "pin"\n[loads]\ngravity = [0.0, -9.81]\n'
        "[solver]\nt_end = 0.01\nstep = 1.0e-3\n"
    )
    (tmp_path / "h.toml").write_text(text)
    p = _rancf(tmp_path, "simulate", "h.toml", "--out", "run")
    assert p.returncode == 0, p.stderr
    (line,) = p.stderr.strip().splitlines()
    assert line.startswith("rancf: warning: body: mesh.continuity: C2 holds at 0 of 2 inner nodes")
    assert "node(s) 1, 2, which stay C1" in line
    doc = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert any("C2 holds at 0 of 2" in w for w in doc["warnings"])
