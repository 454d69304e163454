"""ParaView export, plots and animations of a run (read back with meshio, Pillow, ffmpeg)."""

import json

import meshio
import numpy as np
import pytest

from rancf.cli import main
from rancf.geometry.conic import conic_arc_through
from rancf.post.centerline import sample_centerline
from rancf.post.run_data import frame_indices
from rancf.post.system_run import load_run
from tests.scenario.test_scenario import BASE


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    d = tmp_path_factory.mktemp("run")
    f = d / "pend.toml"
    f.write_text(BASE)  # 3 Kopt elements, 20 steps of 1 ms
    assert main(["simulate", str(f), "--out", str(d / "run"), "--quiet"]) == 0
    return d / "run"


def test_dense_centreline_is_the_exact_conic_in_the_reference(run_dir):
    run = load_run(run_dir).body()
    c = sample_centerline(run, 0, per_element=20)
    conic = conic_arc_through([0, 0], [0.5, 0], [30, 40], [0.315, 0.077])
    res = conic.implicit_residual(c.points)
    assert np.abs(res).max() < 1e-12
    assert c.points.shape == (61, 2)
    assert np.abs(c.axial_strain).max() == 0.0
    assert np.abs(c.displacement).max() == 0.0
    # curvature from r', r'' of the element interpolation = the conic's exact curvature
    u = np.linspace(0, 1, 2001)
    pts = conic(u)
    kappa = conic.curvature(u)
    near = np.argmin(np.linalg.norm(pts[None] - c.points[:, None], axis=2), axis=1)
    assert np.allclose(np.abs(c.curvature), np.abs(kappa[near]), rtol=5e-3)
    assert np.all(c.curvature < 0)  # clockwise from start to end


def test_export_vtk_reads_back_with_meshio(run_dir, tmp_path, capsys):
    out = tmp_path / "vtk"
    assert main(["export", str(run_dir), "--vtk", str(out), "--every", "6"]) == 0
    assert "5 VTK frame(s)" in capsys.readouterr().out  # t index 0, 6, 12, 18 and the last (20)
    run = load_run(run_dir).body()
    idx = frame_indices(run.t.size, 6)
    assert idx.tolist() == [0, 6, 12, 18, 20]
    out = out / "body"  # the run's one flexible body
    files = sorted(out.glob("*.vtu"))
    assert len(files) == 5
    pvd = (out / "body.pvd").read_text()
    assert pvd.count("<DataSet") == 5 and 'timestep="0.02"' in pvd
    m = meshio.read(files[-1])
    c = sample_centerline(run, 20)
    assert m.points.shape == (49, 3)
    assert np.array_equal(m.points[:, :2], c.points) and np.all(m.points[:, 2] == 0)
    assert m.cells_dict["line"].shape == (48, 2)
    for key in ("displacement", "velocity"):
        assert m.point_data[key].shape == (49, 3)
    assert np.array_equal(m.point_data["axial_strain"], c.axial_strain)
    assert np.array_equal(m.point_data["curvature"], c.curvature)
    assert np.all(m.point_data["radius"] == 0.02)
    # nodal velocities of the stored state at the element ends
    v_nodes = run.v[20].reshape(4, 2, 2)[:, 0]
    assert np.allclose(m.point_data["velocity"][::16, :2], v_nodes, atol=1e-14)


def test_plot_and_animation_frames(run_dir, tmp_path, capsys):
    from PIL import Image

    assert main(["plot", str(run_dir), "--out", str(tmp_path / "p")]) == 0
    names = sorted(p.name for p in (tmp_path / "p").glob("*.png"))
    assert names == ["configurations.png", "energy.png", "envelope_body.png", "sensors.png"]
    gif = tmp_path / "m.gif"
    assert main(["animate", str(run_dir), "--out", str(gif), "--fps", "5", "--every", "4"]) == 0
    assert Image.open(gif).n_frames == 6  # 0, 4, ..., 20
    mp4 = tmp_path / "m.mp4"
    assert main(["animate", str(run_dir), "--out", str(mp4), "--fps", "10", "--every", "2"]) == 0
    import imageio_ffmpeg

    assert imageio_ffmpeg.count_frames_and_secs(str(mp4))[0] == 11


@pytest.mark.parametrize(
    ("argv", "needle"),
    [
        (["export", "{run}"], "at least one of --vtk"),
        (["export", "{run}", "--vtk", "{tmp}/v", "--every", "0"], "--every = 0"),
        (["export", "{run}", "--nurbs", "{tmp}/x.txt"], "ending in .json"),
        (["export", "{run}", "--nurbs", "{tmp}/x.json", "--time", "9"], "--time = 9"),
        (["animate", "{run}", "--out", "{tmp}/a.avi"], ".gif or .mp4"),
        (["plot", "{tmp}/nothing"], "RUN_DIR"),
    ],
)
def test_bad_input_one_line(run_dir, tmp_path, capsys, argv, needle):
    argv = [a.format(run=run_dir, tmp=tmp_path) for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert needle in err and err.count("\n") == 1


def test_nurbs_export_is_the_deformed_chain(run_dir, tmp_path):
    from rancf.cad import read_curves
    from rancf.cli.post import run_to_nurbs

    run = load_run(run_dir).body()
    curve = run_to_nurbs(run, 10)
    c = sample_centerline(run, 10, per_element=8)
    # the chain's parameter is the cumulative gradient scale: element e covers a span
    b = np.concatenate([[0], np.cumsum(run.scales)])
    u = np.concatenate(
        [b[e] + np.linspace(0, 1, 9)[:-1] * run.scales[e] for e in range(3)] + [b[-1:]]
    )
    assert np.abs(curve(u) - c.points).max() < 1e-12 * np.abs(c.points).max()
    for suffix in ("json", "dxf", "step", "igs"):
        path = tmp_path / f"shape.{suffix}"
        assert main(["export", str(run_dir), "--nurbs", str(path), "--time", "0.01"]) == 0
        (back,) = read_curves(path)
        x = back.curve(u)[:, :2]
        assert np.abs(x - c.points).max() <= 1e-12 * np.abs(c.points).max(), suffix
    meta = json.loads((tmp_path / "shape.json").read_text())
    assert meta["shape"]["data"][0]["degree"] == 3
