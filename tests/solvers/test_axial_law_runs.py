"""Runs with a nonlinear axial law (``material.axial_law``): a weight hanging on a rope
stretches it by the integral of the inverse table, a linear table repeats the ``EA`` run, the
tension sensors and section forces follow the law, an axial mode takes the tangent stiffness
at the static strain, and a table from a CSV file is read, digested and warned about like the
scenario's other inputs."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.interpolate import PchipInterpolator
from scipy.optimize import brentq

from rancf.bodies.section_outputs import SectionSampler
from rancf.cli import main
from rancf.runs.modes import run_modes
from rancf.runs.static import run_static
from rancf.scenario.read_files import file_digests
from rancf.scenario.scenario import load_scenario

#: A polyester-like curve: tangent stiffness MBL (α + β T / MBL) (the Del Vecchio form), α =
#: 11.6, β = 40, MBL = 3.08 MN (a 0.1 m rope), so T(e) = MBL α / β (exp(β e) − 1).
MBL, ALPHA, BETA = 3.08e6, 11.6, 40.0
STRAINS = np.arange(0.0, 0.03501, 0.0025)
TENSIONS = MBL * ALPHA / BETA * np.expm1(BETA * STRAINS)
TABLE = "[" + ", ".join(f"[{e:.4f}, {t:.8g}]" for e, t in zip(STRAINS, TENSIONS, strict=True)) + "]"
RADIUS, DENSITY, LENGTH, WEIGHT = 0.05, 1380.0, 100.0, 15000.0 * 9.81

HANGING = f"""
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -{LENGTH}]
[mesh]
elements = 20
[section]
radius = {RADIUS}
[material]
density = {DENSITY}
youngs_modulus = 2.0e9
LAW
[[supports]]
at = "start"
kind = "pin"
[[loads.point]]
at = "end"
force = [0.0, -{WEIGHT}]
[loads]
gravity = [0.0, -9.81]
[[sensors]]
name = "top"
kind = "tension"
at = "start"
[[sensors]]
name = "middle"
kind = "tension"
at_point = [0.0, -50.0]
[[sensors]]
name = "tip"
kind = "position"
at = "end"
"""


def _static(tmp_path, law: str, name: str = "rope.toml"):
    f = tmp_path / name
    f.write_text(HANGING.replace("LAW", law))
    return run_static(load_scenario(f))


def test_a_hanging_weight_stretches_the_rope_by_the_integral_of_the_inverse_table(tmp_path):
    """100 m of rope (radius 0.05 m, density 1380) with 15 t at its end: the static stretch is
    the integral over the unstretched length of the strain of the tension there, the weight
    below, within 0.5 %: the inverse table (strain against tension) interpolated by SciPy's
    monotone cubic, and the curve the table samples.  (Its linear interpolation, 0.8 % below
    the curve at these strains, is no reference at 0.5 %.)"""
    run = _static(tmp_path, f"axial_law = {{ table = {TABLE} }}")
    stretch = -run.sensors["tip_y"] - LENGTH
    w = DENSITY * math.pi * RADIUS**2 * 9.81  # weight per unstretched length

    inverse = PchipInterpolator(TENSIONS, STRAINS)

    def strain(s: float) -> float:
        return float(inverse(WEIGHT + w * (LENGTH - s)))

    expected = quad(strain, 0.0, LENGTH)[0]
    assert stretch == pytest.approx(expected, rel=5e-3)
    exact = quad(
        lambda s: math.log1p(BETA * (WEIGHT + w * (LENGTH - s)) / (ALPHA * MBL)), 0, LENGTH
    )
    assert stretch == pytest.approx(exact[0] / BETA, rel=1e-3)  # the curve the table samples
    # linear EA at the slope at 0 stretches it by (W L + w L² / 2) / EA: 6 % more
    linear = (WEIGHT * LENGTH + 0.5 * w * LENGTH**2) / (MBL * ALPHA)
    assert linear / stretch - 1.0 > 0.05
    assert run.sensors["top"] == pytest.approx(WEIGHT + w * LENGTH, rel=1e-6)
    # the section forces are the table's tension of the strain at every point
    system = run.system
    body = system.bodies["body"]
    vals = SectionSampler(body, 4).values(run.result.y[system.body_slice("body")])
    e = np.sqrt(1.0 + 2.0 * vals[:, 0]) - 1.0
    law = body.material.axial_law
    assert np.abs(vals[:, 1] - law.tension(e)).max() <= 1e-3 * WEIGHT
    assert run.sensors["middle"] == pytest.approx(WEIGHT + 0.5 * w * LENGTH, rel=1e-3)


def test_a_linear_table_repeats_the_ea_run_to_round_off(tmp_path):
    ea = 2.0e9 * math.pi * RADIUS**2
    a = _static(tmp_path, f"axial_law = {{ table = [[0.0, 0.0], [0.05, {0.05 * ea!r}]] }}")
    b = _static(tmp_path, 'axial_strain = "engineering"', "ea.toml")
    assert np.abs(a.result.y - b.result.y).max() <= 1e-10 * LENGTH
    assert a.sensors["top"] == pytest.approx(b.sensors["top"], rel=1e-10)


def test_a_csv_table_with_a_header_is_read_digested_and_checked(tmp_path, capsys):
    """The table from a CSV file (header row, path relative to the scenario) gives the inline
    table's answer; the file is among the scenario's digested inputs; a table whose last row
    the run passes gets a warning."""
    rows = "\n".join(f"{e:.4f},{t:.8g}" for e, t in zip(STRAINS, TENSIONS, strict=True))
    (tmp_path / "polyester.csv").write_text("strain,tension_N\n" + rows + "\n")
    a = _static(tmp_path, 'axial_law = { table = "polyester.csv" }')
    b = _static(tmp_path, f"axial_law = {{ table = {TABLE} }}", "inline.toml")
    assert a.result.y == pytest.approx(b.result.y, rel=1e-12, abs=1e-12)
    raw = {"material": {"axial_law": {"table": "polyester.csv"}}}
    assert str((tmp_path / "polyester.csv").resolve()) in file_digests(raw, tmp_path / "rope.toml")
    f = tmp_path / "short.toml"
    f.write_text(HANGING.replace("LAW", "axial_law = { table = [[0.0, 0.0], [0.001, 40000.0]] }"))
    assert main(["static", str(f), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert any("beyond the axial_law table's last row (0.001)" in w for w in out["warnings"])


MODES = f"""
[[bodies]]
name = "rope"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [{LENGTH}, 0.0]
[bodies.mesh]
elements = 20
[bodies.section]
radius = {RADIUS}
[bodies.material]
density = {DENSITY}
youngs_modulus = 2.0e9
axial_law = {{ table = {TABLE} }}
[[bodies]]
name = "weight"
kind = "mass"
mass = 15000.0
position = [{LENGTH}, 0.0]
[[supports]]
at = "rope:start"
kind = "pin"
[[supports]]
at = "rope:end"
kind = "roller"
axis = [1.0, 0.0]
[[joints]]
name = "hook"
kind = "pin"
between = ["rope:end", "weight"]
[[loads.point]]
at = "weight"
force = [{WEIGHT}, 0.0]
[modes]
count = 4
about = "static"
"""


def test_an_axial_mode_takes_the_tangent_stiffness_at_the_static_strain(tmp_path):
    """A rope pulled straight by F through a 15 t mass (no gravity): its axial mode is the rod's
    with a tip mass, β tan β = ρA L / M, ω = (β / L) sqrt(EA_t / ρA), with the tangent
    EA_t = dT/de = MBL α + β F at the static strain, 17 % above the slope at 0."""
    f = tmp_path / "modes.toml"
    f.write_text(MODES)
    run = run_modes(load_scenario(f))
    rho_a = DENSITY * math.pi * RADIUS**2
    root = brentq(lambda b: b * math.tan(b) - rho_a * LENGTH / 15000.0, 1e-9, 1.5)

    def freq(ea: float) -> float:
        return root / LENGTH * math.sqrt(ea / rho_a) / (2.0 * math.pi)

    system, res = run.system, run.result
    body = system.bodies["rope"]
    axial = []  # the share of each mode's motion along the rope
    for shape in res.modes:
        nodes = shape[system.body_slice("rope")].reshape(body.n_nodes, body.dpn)
        axial.append(np.linalg.norm(nodes[:, 0]) / np.linalg.norm(nodes[:, :2]))
    i = int(np.argmax(axial))
    assert axial[i] > 0.99
    tangent = MBL * ALPHA + BETA * WEIGHT
    assert res.frequencies_hz[i] == pytest.approx(freq(tangent), rel=2e-3)
    assert abs(res.frequencies_hz[i] / freq(MBL * ALPHA) - 1.0) > 0.05  # not the slope at 0
