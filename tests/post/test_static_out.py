"""`rancf static --out`: the load path as a run directory that export, plot and animate read."""

import json
import re

import numpy as np
import pytest

from rancf import load_scenario
from rancf.cad import read_curves
from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import load_run
from rancf.solvers.static import solve_static
from tests.post.test_rod_output import ROD


@pytest.fixture(scope="module")
def cantilever(tmp_path_factory):
    d = tmp_path_factory.mktemp("static")
    assert main(["example", "copy", "cantilever", str(d)]) == 0
    return d / "cantilever.toml"


def test_static_out_is_the_load_path(cantilever, tmp_path, capsys):
    out = tmp_path / "st"
    assert main(["static", str(cantilever), "--out", str(out)]) == 0
    assert f"-> {out}" in capsys.readouterr().out
    run = load_run(out).body()
    sc = load_scenario(cantilever)
    model = sc.build_model()
    res = solve_static(model, sc.solver["load_steps"])
    assert run.static and run.time_label.startswith("load factor")
    assert np.array_equal(run.t, res.load_factors) and run.t[-1] == 1.0
    assert np.array_equal(run.q[-1], res.q) and np.array_equal(run.q[0], model.q0)
    assert np.all(run.v == 0) and np.all(run.energies["kinetic"] == 0)
    assert run.energies["strain"][-1] > 0
    summary = json.loads((out / "summary.json").read_text())
    assert summary["analysis"] == "static" and summary["status"] == "completed"
    # the equilibrium shape to CAD: exactly the element curve
    assert main(["export", str(out), "--nurbs", str(tmp_path / "eq.json")]) == 0
    assert "λ = 1:" in capsys.readouterr().out
    (back,) = read_curves(tmp_path / "eq.json")
    assert back.name == "st lambda=1"
    c = sample_centerline(run, run.t.size - 1)
    breaks = np.concatenate([[0.0], np.cumsum(run.scales)])
    u = np.concatenate(
        [np.linspace(a, b, 17)[:-1] for a, b in zip(breaks[:-1], breaks[1:], strict=True)]
        + [breaks[-1:]]
    )
    assert np.abs(back.curve(u)[:, :2] - c.points).max() < 1e-12 * np.abs(c.points).max()
    assert main(["plot", str(out)]) == 0
    assert (out / "plots" / "configurations.png").is_file()


def test_static_out_of_a_rod_has_its_frames(tmp_path, capsys):
    (tmp_path / "rod.toml").write_text(ROD)
    out = tmp_path / "st"
    assert main(["static", str(tmp_path / "rod.toml"), "--out", str(out)]) == 0
    run = load_run(out).body()
    assert run.directors is not None and run.directors.shape == (run.t.size, run.n_nodes, 3)
    assert main(["export", str(out), "--vtk", str(tmp_path / "vtk")]) == 0
    assert (tmp_path / "vtk" / "body" / "body_nodes.pvd").is_file()


def test_a_failed_static_run_keeps_the_converged_steps(tmp_path, capsys):
    # the pendulum without its pin: a free body under gravity has no static equilibrium (with
    # the pin, whether Newton finds the hanging state from the reference is round-off's luck)
    assert main(["example", "copy", "planar-pendulum", str(tmp_path)]) == 0
    f = tmp_path / "planar-pendulum.toml"
    f.write_text(re.sub(r"\[\[supports\]\]\n(?:[^\[\n].*\n)*", "", f.read_text()))
    out = tmp_path / "st"
    assert main(["static", str(f), "--out", str(out)]) == 3
    assert "did not converge" in capsys.readouterr().err
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed" and summary["load_factor_reached"] < 1.0
    run = load_run(out).body()
    assert run.t[0] == 0.0 and run.t.size == summary["load_steps_converged"] + 1
