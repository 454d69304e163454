"""Rod runs in the output chain: the nodal directors stored at every output, read back, exported
to ParaView with the material frames, plotted, animated and exported as the centreline's NURBS."""

import tomllib

import meshio
import numpy as np
import pytest

from rancf import DynamicOptions, integrate, parse_scenario
from rancf.cli import main
from rancf.kernels import _core
from rancf.post.centerline import nodal_frames, sample_centerline
from rancf.post.system_run import load_run

ROD = """
[geometry]
kind = "conic"
start = [0.0, 0.0, 0.0]
end = [0.5, 0.0, 0.0]
angles_deg = [30.0, 30.0]
point = [0.25, 0.067, 0.0]

[mesh]
elements = 6
element = "rod"

[section]
radius = 0.03

[material]
density = 6000.0
youngs_modulus = 2.0e7
poisson_ratio = 0.3

[[supports]]
at = "start"
kind = "clamp"

[[loads.point]]
at = "end"
force = [0.0, 0.0, -1.0]
moment = [0.3, 0.0, 0.2]

[[sensors]]
name = "phi"
kind = "twist"
at = "end"

[solver]
t_end = 0.1
step = 0.002
"""


def _run(output_every: int = 1, adaptive: bool = False, t_end: float = 0.5):
    # 250 steps: long enough for the compiled loop to store several outputs a call for cables
    sc = parse_scenario(tomllib.loads(ROD), "rod.toml")
    model = sc.build_model()
    opts = DynamicOptions(
        t_end=t_end, step=0.002, output_step=0.002 * output_every, adaptive=adaptive
    )
    return model, integrate(model, opts)


def test_directors_are_the_triads_carried_step_by_step():
    # every step stored: replay the re-referencing (smallest rotation of the last reference
    # triad onto each new tangent) with the core's nodal triad and compare
    model, res = _run()
    assert res.directors is not None and res.directors.shape == (res.t.size, model.n_nodes, 3)
    model.reset_triads()
    tref, uref = model.kernel.tref.reshape(-1, 3).copy(), model.kernel.m1ref.reshape(-1, 3).copy()
    worst = 0.0
    for k in range(res.t.size):
        q = res.q[k].reshape(model.n_nodes, 7)
        for n in range(model.n_nodes):
            rx = np.ascontiguousarray(q[n, 3:6])
            _, m1 = _core.rod_nodal_triad(tref[n], uref[n], rx, float(q[n, 6]))
            worst = max(worst, np.abs(np.array(m1) - res.directors[k, n]).max())
            t3, u = _core.rod_nodal_triad(tref[n], uref[n], rx, 0.0)
            tref[n], uref[n] = t3, u
    assert worst < 1e-13
    # the frames do turn: the tip's director moves away from its reference direction
    assert np.abs(res.directors[-1, -1] - res.directors[0, -1]).max() > 1e-3


def test_thinned_and_adaptive_outputs_store_the_same_frames():
    _, every = _run(1)
    _, fifth = _run(5)
    assert np.abs(fifth.directors - every.directors[::5]).max() < 1e-13
    model, adaptive = _run(1, adaptive=True, t_end=0.1)
    m1, q = adaptive.directors, adaptive.q.reshape(adaptive.t.size, model.n_nodes, 7)
    t = q[:, :, 3:6] / np.linalg.norm(q[:, :, 3:6], axis=2, keepdims=True)
    assert np.abs(np.linalg.norm(m1, axis=2) - 1).max() < 1e-13
    assert np.abs(np.sum(m1 * t, axis=2)).max() < 1e-13


@pytest.fixture(scope="module")
def rod_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("rod")
    (d / "rod.toml").write_text(ROD)
    assert main(["simulate", str(d / "rod.toml"), "--out", str(d / "run"), "--quiet"]) == 0
    return d


def test_run_directory_holds_the_directors(rod_run):
    run = load_run(rod_run / "run").body()
    _, res = _run(t_end=0.1)
    assert run.directors is not None
    assert np.array_equal(run.directors, res.directors)


def test_vtk_export_has_the_material_frames(rod_run, capsys):
    out = rod_run / "vtk"
    assert main(["export", str(rod_run / "run"), "--vtk", str(out), "--every", "10"]) == 0
    assert "body_nodes.pvd" in capsys.readouterr().out
    whole = load_run(rod_run / "run")
    run = whole.body()
    sensors = whole.sensors[:, whole.sensor_names.index("phi")]
    out = out / "body"  # the run's one flexible body
    files = sorted(out.glob("body_nodes_*.vtu"))
    assert len(files) == 6 and (out / "body_nodes.pvd").is_file()
    for k, f in enumerate(files):
        m = meshio.read(f)
        t, m1, m2 = (m.point_data[x] for x in ("tangent", "m1", "m2"))
        frame = np.stack([t, m1, m2], axis=1)  # (n_nodes, 3, 3), rows orthonormal, right-handed
        assert np.abs(frame @ frame.transpose(0, 2, 1) - np.eye(3)).max() < 1e-12
        assert np.abs(np.linalg.det(frame) - 1).max() < 1e-12
        i = min(10 * k, run.t.size - 1)
        assert m.point_data["twist"][-1] == pytest.approx(sensors[i], abs=1e-12)
        assert np.abs(m.points - nodal_frames(run, i).points).max() < 1e-15
    # the centreline file of a rod is the exact curve as for cables
    line = meshio.read(out / "body_00005.vtu")
    assert np.abs(line.points - sample_centerline(run, run.t.size - 1).points).max() < 1e-15


def test_plot_animate_and_nurbs_export_of_a_rod_run(rod_run, capsys):
    run_dir = rod_run / "run"
    assert main(["plot", str(run_dir), "--out", str(rod_run / "plots")]) == 0
    assert (rod_run / "plots" / "configurations.png").stat().st_size > 5000
    assert main(["animate", str(run_dir), "--out", str(rod_run / "a.gif")]) == 0
    assert (rod_run / "a.gif").stat().st_size > 5000
    assert main(["export", str(run_dir), "--nurbs", str(rod_run / "c.json")]) == 0
    from rancf.cad import read_curves

    (back,) = read_curves(rod_run / "c.json")
    run = load_run(run_dir).body()
    c = sample_centerline(run, run.t.size - 1)
    breaks = np.concatenate([[0.0], np.cumsum(run.scales)])
    u = np.concatenate(
        [np.linspace(a, b, 17)[:-1] for a, b in zip(breaks[:-1], breaks[1:], strict=True)]
        + [breaks[-1:]]
    )
    assert np.abs(back.curve(u) - c.points).max() < 1e-12 * np.abs(c.points).max()


def test_a_rod_run_without_directors_exports_its_centreline_and_says_why_no_frames(
    rod_run, tmp_path, capsys
):
    # a run directory written before the directors were stored
    import shutil

    old = tmp_path / "old"
    shutil.copytree(rod_run / "run", old)
    body = old / "bodies" / "body" / "results.npz"
    data = dict(np.load(body))
    del data["directors"]
    np.savez(body, **data)
    assert main(["export", str(old), "--vtk", str(tmp_path / "vtk")]) == 0
    err = capsys.readouterr().err
    assert "no rod directors" in err and "no material frames" in err
    assert (tmp_path / "vtk" / "body" / "body.pvd").is_file()
    assert not list((tmp_path / "vtk" / "body").glob("body_nodes*"))
