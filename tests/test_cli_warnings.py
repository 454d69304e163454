"""Likely unit mistakes are warned about in one line, the run goes on and summary.json keeps the
warning: an axial strain past 10 %, a section radius past a tenth of the
body's length."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import rancf
from rancf.cli import main
from rancf.post.checks import STRAIN_LIMIT, largest_strain, run_warnings
from tests.scenario.test_scenario import BASE
from tests.test_cli_sim import CANTILEVER

#: A 1 m hose hanging from a pin, E = 50 Pa where 50 MPa was meant: it stretches by metres.
HOSE = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]

[mesh]
elements = 4

[section]
radius = 0.01

[material]
density = 1000.0
youngs_modulus = 50.0

[[supports]]
at = "start"
kind = "pin"

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.1
step = 1.0e-3
"""
#: The same hose with E = 200 GPa and a radius of 10 m (meant as 10 mm).
THICK = HOSE.replace("radius = 0.01", "radius = 10.0").replace("= 50.0", "= 2.0e11")


def _warnings(err: str) -> list[str]:
    lines = err.strip().splitlines()
    assert all(x.startswith("rancf: warning: ") for x in lines), err
    return [x.removeprefix("rancf: warning: ") for x in lines]


def test_soft_hose_warns_of_its_strain_and_runs_on(tmp_path):
    (tmp_path / "hose.toml").write_text(HOSE)
    p = subprocess.run(
        [sys.executable, "-m", "rancf", "simulate", "hose.toml", "--out", "run"],
        capture_output=True,
        text=True,
        cwd=tmp_path,
    )
    assert p.returncode == 0 and p.stdout.startswith("completed: t = 0.1 s")
    (line,) = _warnings(p.stderr)
    assert "largest axial strain is" in line and "youngs_modulus" in line
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["status"] == "completed" and summary["warnings"] == [line]
    assert float(line.split("strain is ")[1].split(" %")[0]) > 50.0  # stretched, not noise


def test_thick_section_warns_of_its_radius(tmp_path, capsys):
    (tmp_path / "thick.toml").write_text(THICK)
    assert main(["simulate", str(tmp_path / "thick.toml"), "--out", str(tmp_path / "r")]) == 0
    (line,) = _warnings(capsys.readouterr().err)
    assert "radius 10 m is more than a tenth of the body's length 1 m" in line
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["warnings"] == [line]


def test_a_sound_run_has_no_warning(tmp_path, capsys):
    (tmp_path / "p.toml").write_text(BASE)
    assert main(["simulate", str(tmp_path / "p.toml"), "--out", str(tmp_path / "r")]) == 0
    assert capsys.readouterr().err == ""
    assert json.loads((tmp_path / "r" / "summary.json").read_text())["warnings"] == []


def test_static_and_modes_warn_too(tmp_path, capsys):
    soft = CANTILEVER.replace("youngs_modulus = 2.0e7", "youngs_modulus = 2.0").replace(
        "force = [0.0, -0.001]", "force = [1.0, 0.0]"
    )
    (tmp_path / "soft.toml").write_text(soft)
    assert (
        main(["static", str(tmp_path / "soft.toml"), "--json", "--out", str(tmp_path / "s")]) == 0
    )
    cap = capsys.readouterr()
    (line,) = _warnings(cap.err)
    assert "axial strain" in line and "at load factor λ = 1" in line
    assert json.loads(cap.out)["warnings"] == [line]
    assert json.loads((tmp_path / "s" / "summary.json").read_text())["warnings"] == [line]
    thick = CANTILEVER.replace("radius = 0.03", "radius = 0.3")
    (tmp_path / "thick.toml").write_text(thick)
    assert main(["modes", str(tmp_path / "thick.toml"), "--count", "2", "--json"]) == 0
    cap = capsys.readouterr()
    (line,) = _warnings(cap.err)
    assert "radius 0.3 m" in line and json.loads(cap.out)["warnings"] == [line]
    assert main(["static", str(tmp_path / "thick.toml")]) == 0
    assert _warnings(capsys.readouterr().err) == [line]


@pytest.mark.parametrize("element", ["rancf", "ancf", "beam", "rod"])
def test_strain_check_measures_a_uniform_stretch(element):
    # a straight body stretched uniformly by 1.2: Green-Lagrange strain (1.44 - 1) / 2 = 0.22
    dim = 3 if element == "rod" else 2
    end = [2.0, 0.0, 0.0][:dim]
    model = rancf.Model(
        rancf.mesh_line([0.0] * dim, end, 3),
        element,
        rancf.Section.circular(0.01),
        rancf.Material(1000.0, 1e6, poisson_ratio=0.3 if element == "rod" else None),
    )
    q = model.q0.reshape(model.n_nodes, model.dpn).copy()
    if element == "beam":
        q[:, 0] *= 1.2
    else:
        q[:, : 2 * dim] *= np.tile([1.2] + [1.0] * (dim - 1), 2)  # x and dx/ds stretched
    largest, at = largest_strain(model, [0.0, 0.5], np.stack([model.q0, q.ravel()]))
    assert largest == pytest.approx(0.22, rel=1e-12) and at == 0.5
    assert largest > STRAIN_LIMIT
    assert run_warnings(model, [0.0], model.q0[None]) == []


def test_write_run_of_the_api_keeps_its_warnings(tmp_path):
    model = rancf.Model(
        rancf.mesh_line([0.0, 0.0], [1.0, 0.0], 2),
        "rancf",
        rancf.Section.circular(0.5),
        rancf.Material(1000.0, 1e9),
    )
    result = rancf.integrate(model, rancf.DynamicOptions(t_end=0.002, step=1e-3))
    summary = rancf.write_run(tmp_path / "r", model, [], result)
    assert len(summary["warnings"]) == 1 and "radius 0.5 m" in summary["warnings"][0]
