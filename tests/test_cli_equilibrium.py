"""The equilibrium commands through the real CLI process: ``static`` reactions and outputs,
``buckling``, ``simulate`` from an equilibrium."""

from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

RANCF = [sys.executable, "-m", "rancf"]


def _run(args: list[str], cwd, code: int = 0) -> subprocess.CompletedProcess:
    p = subprocess.run([*RANCF, *args], cwd=cwd, capture_output=True, text=True)
    assert p.returncode == code, p.stderr
    return p


@pytest.fixture
def hose(tmp_path):
    _run(["example", "copy", "installed-hose", "."], tmp_path)
    return tmp_path


def test_static_json_reactions_and_outputs(hose):
    out = json.loads(_run(["static", "installed-hose.toml", "--json", "--out", "st"], hose).stdout)
    assert [r["at"] for r in out["reactions"]] == ["start", "end"]
    assert all(set(r) == {"at", "force", "moment"} for r in out["reactions"])
    assert out["load_factors"][-1] == 2.0 and out["method"] == "load"
    weight = sum(r["force"][1] for r in out["reactions"])
    assert weight == pytest.approx(1200.0 * np.pi * 1e-4 * 9.81, rel=1e-9)
    head = (hose / "st" / "reactions.csv").read_text().splitlines()[0]
    assert head == "t,start_fx,start_fy,start_mz,end_fx,end_fy,end_mz"
    along = np.genfromtxt(hose / "st" / "bodies" / "body" / "along.csv", delimiter=",", names=True)
    assert along.dtype.names == (
        "s",
        "x",
        "y",
        "strain",
        "axial_force",
        "curvature",
        "bending_moment",
    )
    assert along["s"][0] == 0.0 and along["s"][-1] == pytest.approx(1.0, rel=1e-12)
    assert along["bending_moment"][0] == pytest.approx(-out["reactions"][0]["moment"][0], rel=1e-2)
    with np.load(hose / "st" / "results.npz") as z:
        assert z["reactions"].shape == (len(out["load_factors"]), 6)
    with np.load(hose / "st" / "bodies" / "body" / "results.npz") as z:
        assert z["along"].shape == (len(out["load_factors"]), 65, 4)


def test_simulate_from_the_equilibrium_stays_at_rest(hose):
    _run(["simulate", "installed-hose.toml", "--out", "run", "--quiet"], hose)
    summary = json.loads((hose / "run" / "summary.json").read_text())
    assert summary["initial_state"] == "static" and summary["static"]["newton_iterations"] > 0
    with np.load(hose / "run" / "results.npz") as z:
        assert np.abs(z["q"] - z["q"][0]).max() <= 1e-9
        assert np.abs(z["a"]).max() <= 1e-6 * 9.81 * 10  # at rest: 1.5e-6 measured (Newton tol.)
    r = np.genfromtxt(hose / "run" / "reactions.csv", delimiter=",", names=True)
    assert np.ptp(r["start_fx"]) <= 1e-9


def test_installed_support_needs_the_static_start(hose):
    text = (hose / "installed-hose.toml").read_text().replace('"static"', '"reference"')
    (hose / "ref.toml").write_text(text)
    p = _run(["simulate", "ref.toml", "--out", "run"], hose, code=2)
    assert len(p.stderr.splitlines()) == 1
    assert "supports[1].position" in p.stderr and 'initial_state = "static"' in p.stderr
    assert not (hose / "run").exists()


def test_buckling_json_and_plot(tmp_path):
    _run(["example", "copy", "cantilever", "."], tmp_path)
    text = (tmp_path / "cantilever.toml").read_text()
    text = text.replace("elements = 8", "elements = 16")
    text = text.replace("radius = 0.03", "area = 2.827433e-1\ninertia = 6.361725e-7")
    (tmp_path / "col.toml").write_text(text.replace("[0.0, -0.001]", "[-1.0, 0.0]"))
    p = _run(["buckling", "col.toml", "--count", "2", "--json", "--plot", "b.png"], tmp_path)
    out = json.loads(p.stdout)
    ei = 2e7 * 6.361725e-7
    assert out["load_factors"][0] == pytest.approx(np.pi**2 * ei / 1.0, rel=1e-3)  # π²EI/4L²
    assert out["about"] == "reference" and (tmp_path / "b.png").stat().st_size > 0
    p = _run(["buckling", "cantilever.toml", "--about", "sideways"], tmp_path, code=2)
    assert len(p.stderr.splitlines()) == 1 and "--about" in p.stderr


def test_vtk_export_carries_the_section_quantities(hose):
    import meshio

    _run(["static", "installed-hose.toml", "--out", "st"], hose)
    _run(["export", "st", "--vtk", "vtk"], hose)
    files = sorted((hose / "vtk" / "body").glob("body_*.vtu"))
    mesh = meshio.read(files[-1])
    for name in ("section_axial_force", "section_bending_moment", "section_curvature"):
        assert name in mesh.point_data
    moment = mesh.point_data["section_bending_moment"]
    along = np.genfromtxt(hose / "st" / "bodies" / "body" / "along.csv", delimiter=",", names=True)
    assert moment[0] == pytest.approx(along["bending_moment"][0], rel=1e-12)
    assert moment[-1] == pytest.approx(along["bending_moment"][-1], rel=1e-12)


def test_static_and_modes_of_one_body_with_system_keys(tmp_path, capsys):
    """One body with what only the system solver runs (a reaction or axial-force sensor, a
    moving support, a time load) was refused by `static` and `modes` ("not yet solved by this
    command") while `simulate` ran it: both now go through its one-body system and give the
    answers of the plain file."""
    from rancf.cli import main
    from tests.test_cli_sim import CANTILEVER

    plain, extra = tmp_path / "plain.toml", tmp_path / "extra.toml"
    plain.write_text(CANTILEVER)
    extra.write_text(
        CANTILEVER + '\n[[sensors]]\nname = "root"\nkind = "reaction"\nat = "start"\n'
        '\n[[sensors]]\nname = "N"\nkind = "axial_force"\nat = 4\n'
    )
    docs = []
    for f in (plain, extra):
        assert main(["modes", str(f), "--count", "3", "--json"]) == 0
        docs.append(json.loads(capsys.readouterr().out))
    assert np.allclose(docs[1]["frequencies_hz"], docs[0]["frequencies_hz"], rtol=1e-9)
    assert main(["static", str(extra), "--json"]) == 0
    doc = json.loads(capsys.readouterr().out)
    assert doc["sensors"]["root_y"] == pytest.approx(0.001, rel=1e-9)  # holds the tip load
    assert main(["static", str(plain), "--json"]) == 0
    tip = json.loads(capsys.readouterr().out)["sensors"]["tip_y"]
    assert doc["sensors"]["tip_y"] == pytest.approx(tip, rel=1e-9)


#: A rope pinned at its end, its start hung by a pin joint to the ground (labels of 8 and 6).
PINNED_ROPE = """
[[bodies]]
name = "rope"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]
[bodies.mesh]
elements = 4
[bodies.section]
radius = 0.005
[bodies.material]
density = 1000.0
youngs_modulus = 1.0e9

[[supports]]
at = "rope:end"
kind = "pin"

[[joints]]
name = "anchor"
kind = "pin"
between = ["rope:start", "ground"]

[[sensors]]
name = "middle_of_the_rope"
kind = "position"
at = "rope:2"

[loads]
gravity = [0.0, -9.81]
"""


def test_static_table_columns_align_with_long_labels(tmp_path, capsys):
    from rancf.cli import main

    (tmp_path / "rope.toml").write_text(PINNED_ROPE)
    assert main(["static", str(tmp_path / "rope.toml")]) == 0
    lines = capsys.readouterr().out.splitlines()
    reactions = [x for x in lines if x.startswith("  reaction at ")]
    assert [x.split()[2] for x in reactions] == ["rope:end", "anchor"]
    assert len({x.index(" force [") for x in reactions}) == 1, reactions
    values = [x for x in lines if x.startswith("  middle_of_the_rope_")]
    assert len(values) == 2, lines
    # the numbers start in one column, after the longest name (a sign's column before them)
    assert len({x.index(x.split()[1]) + (x.split()[1][0] == "-") for x in values}) == 1, values
