"""Small things a new user tripped over: what `modes --plot` wrote, a missing
run folder, runs written by the Python API read back without their scenario."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import rancf
from rancf.cli import main
from tests.test_cli_sim import CANTILEVER


def test_modes_plot_says_which_file_it_wrote(tmp_path, capsys):
    f = tmp_path / "c.toml"
    f.write_text(CANTILEVER)
    png = tmp_path / "modes.png"
    assert main(["modes", str(f), "--count", "2", "--plot", str(png)]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[-1] == f"mode shapes written to {png}" and png.stat().st_size > 0
    # an existing figure is replaced (it was refused as "a file, not a directory")
    # with --json the object stays alone on standard output; the note goes to standard error
    assert main(["modes", str(f), "--count", "2", "--json", "--plot", str(png)]) == 0
    cap = capsys.readouterr()
    assert json.loads(cap.out)["frequencies_hz"] and f"written to {png}" in cap.err


@pytest.mark.parametrize(
    "command", [["plot"], ["export", "--vtk", "v"], ["animate", "--out", "a.gif"], ["view"]]
)
def test_a_missing_run_folder_is_called_missing(tmp_path, capsys, command, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "afile").write_text("x")
    for where, why in (("nothere", "the folder does not exist"), ("afile", "it is a file")):
        argv = [command[0], where, *command[1:]]
        assert main(argv) == 2
        err = capsys.readouterr().err
        assert err.count("\n") == 1 and f"RUN_DIR = '{where}'" in err and why in err


def _api_run(folder, element: str) -> None:
    """A run written by the Python API alone: no scenario file anywhere."""
    arc = rancf.conic_arc(0.5, (30.0, 40.0), (0.315, 0.077))
    model = rancf.Model(
        rancf.mesh_conic(arc, 3),
        element,
        rancf.Section.circular(0.02),
        rancf.Material(density=6000.0, youngs_modulus=2.0e6),
        supports=[rancf.Support(0, "pin")],
        gravity=[0.0, -9.81],
    )
    result = rancf.integrate(model, rancf.DynamicOptions(t_end=0.005, step=1e-3))
    rancf.write_run(folder, model, [rancf.Sensor("tip", "position", (-1,))], result)
    return model


@pytest.mark.parametrize("element", ["rancf", "beam"])
def test_api_run_plots_without_its_scenario(tmp_path, element):
    model = _api_run(tmp_path / "run", element)
    p = subprocess.run(
        [sys.executable, "-m", "rancf", "plot", str(tmp_path / "run")],
        capture_output=True,
        text=True,
    )
    assert p.returncode == 0 and p.stderr == ""  # was: "no scenario found; no radius field"
    assert len(p.stdout.splitlines()) == 4  # sensors, energy, envelope, configurations
    run = rancf.post.system_run.load_run(tmp_path / "run").body()
    assert run.radius == pytest.approx(0.02, rel=1e-15)
    if element == "beam":  # the reference tangents, not the chord directions
        t = model.mesh.nodes[:, 1]
        assert np.allclose(run.tangent_angles, np.arctan2(t[:, 1], t[:, 0]), rtol=0, atol=1e-15)
