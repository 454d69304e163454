"""Closed curves: a closed NURBS circle, a CAD circle and a chain of two half circles
are rings (not silently cut open: the seam holds, a start-end distance stays
zero); an open curve whose ends merely touch at a kink is an open curve, and one warning line says
why."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from rancf.cad import write_curve
from rancf.cad.geomdl_json import curve_dict
from rancf.geometry.nurbs import NurbsCurve

S = float(np.sqrt(0.5))
#: The full unit circle as a rational quadratic NURBS (9 control points, 4 spans).
CIRCLE = (
    2,
    [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
    [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]],
    [1, S, 1, S, 1, S, 1, S, 1],
)
#: A teardrop: leaves (0, 0) along (2, 1) and comes back along (-2, 1): ends touch at a kink.
TEARDROP = (2, [0, 0, 0, 0.5, 1, 1, 1], [[0, 0], [2, 1], [2, -1], [0, 0]], [1, 1, 1, 1])

REST = """
[mesh]
elements = 2

[section]
radius = 0.01

[material]
density = 1000.0
youngs_modulus = 1.0e7

[[supports]]
at = "start"
kind = "pin"

[[sensors]]
name = "gap"
kind = "distance"
between = ["start", "end"]

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.002
step = 1.0e-3
"""


def _nurbs_toml(degree, knots, points, weights) -> str:
    return (
        f'[geometry]\nkind = "nurbs"\ndegree = {degree}\nknots = {knots}\n'
        f"control_points = {points}\nweights = {weights}\n" + REST
    )


def _cad_toml(file: str, curve: str) -> str:
    return f'[geometry]\nkind = "cad"\nfile = "{file}"\ncurve = {curve}\n' + REST


def _simulate(tmp_path, text: str):
    f = tmp_path / "s.toml"
    f.write_text(text)
    return subprocess.run(
        [
            sys.executable,
            "-m",
            "rancf",
            "simulate",
            str(f),
            "--out",
            str(tmp_path / "run"),
            "--overwrite",
        ],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )


def _ring_run(p, tmp_path) -> None:
    """The run succeeded and its body is a ring: the stored repeat of the first node stays on it
    (positions and gradient directions) while the ring swings and deforms, and the start-end
    distance sensor reads zero."""
    assert p.returncode == 0, p.stderr
    assert "warning" not in p.stderr
    d = np.load(tmp_path / "run" / "results.npz")
    q = d["q"].reshape(len(d["t"]), -1, 4)
    assert np.abs(q[:, -1, :2] - q[:, 0, :2]).max() < 1e-12
    g0, g1 = q[:, 0, 2:], q[:, -1, 2:]
    assert np.abs(g0[:, 0] * g1[:, 1] - g0[:, 1] * g1[:, 0]).max() < 1e-12 * np.abs(g0).max() ** 2
    assert np.abs(q[-1, :, :2] - q[0, :, :2]).max() > 1e-6  # it moved
    assert np.abs(d["sensors"]).max() == 0.0


def test_closed_nurbs_circle_is_a_ring(tmp_path):
    _ring_run(_simulate(tmp_path, _nurbs_toml(*CIRCLE)), tmp_path)


def test_cad_chain_whose_ends_meet_is_a_ring(tmp_path):
    # the circle as one curve, and as two half circles chained [0, 1] (one geomdl JSON file)
    d, k, p, w = CIRCLE
    half = [0, 0, 0, 0.5, 0.5, 1, 1, 1]
    curves = [
        curve_dict(NurbsCurve(d, half, p[:5], w[:5]), "upper"),
        curve_dict(NurbsCurve(d, half, p[4:], w[4:]), "lower"),
    ]
    doc = {"shape": {"type": "curve", "count": 2, "data": curves}}
    (tmp_path / "halves.json").write_text(json.dumps(doc))
    write_curve(tmp_path / "ring.dxf", NurbsCurve(d, k, p, w))
    _ring_run(_simulate(tmp_path, _cad_toml("halves.json", "[0, 1]")), tmp_path)
    _ring_run(_simulate(tmp_path, _cad_toml("ring.dxf", "0")), tmp_path)


@pytest.mark.parametrize("where", ["nurbs", "cad"])
def test_ends_that_touch_at_a_kink_are_an_open_curve(tmp_path, where):
    if where == "nurbs":
        text = _nurbs_toml(*TEARDROP)
    else:
        write_curve(tmp_path / "drop.dxf", NurbsCurve(*TEARDROP[:2], TEARDROP[2], TEARDROP[3]))
        text = _cad_toml("drop.dxf", "0")
    p = _simulate(tmp_path, text)
    assert p.returncode == 0, p.stderr
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1, p.stderr
    assert lines[0].startswith("rancf: warning: body: geometry: the curve's ends meet at (0, 0)")
    assert "126.9 deg" in lines[0] and "open curve" in lines[0] and "same tangent" in lines[0]
    d = np.load(tmp_path / "run" / "results.npz")
    q = d["q"].reshape(len(d["t"]), -1, 4)
    assert np.abs(q[-1, -1, :2] - q[-1, 0, :2]).max() > 1e-6  # the free end fell away


def test_rancf_modes_of_a_closed_nurbs_circle_are_a_rings(tmp_path):
    """`rancf modes` of the closed NURBS circle is a ring's, not an open arc's: 3 rigid-body modes
    removed and the free ring's frequencies (thin ring, n = 2, 3: ω² = (EI/ρA R⁴) n²(n²-1)²/
    (n²+1) with EI/ρA = E r²/4ρ = 0.25 m⁴/s²), not those of an open arc."""
    text = _nurbs_toml(*CIRCLE).replace("elements = 2", "elements = 12")
    text = text.replace('[[supports]]\nat = "start"\nkind = "pin"\n', "")  # a free ring
    (tmp_path / "c.toml").write_text(text + "\n[modes]\ncount = 4\n")
    p = subprocess.run(
        [sys.executable, "-m", "rancf", "modes", "c.toml", "--json"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert p.returncode == 0, p.stderr
    doc = json.loads(p.stdout)
    assert doc["rigid_body_modes_removed"] == 3
    n = np.array([2, 2, 3, 3])
    want = np.sqrt(0.25 * n**2 * (n**2 - 1) ** 2 / (n**2 + 1)) / (2 * np.pi)
    assert np.abs(np.array(doc["frequencies_hz"]) / want - 1).max() < 3e-3
