"""A spatial run is drawn in 3D: a helix keeps its z."""

from __future__ import annotations

import numpy as np
import pytest

import rancf.post.run_plots as run_plots
import rancf.post.system_run as system_run
from rancf.cli import main
from rancf.post.centerline import sample_centerline
from rancf.post.system_run import animate_system_run, load_run

#: One turn of a helix (radius 0.2 m, rise 0.1 m: wider than tall, so an x-y view loses its
#: z), as a cubic B-spline through 9 control points on it.
_S = np.linspace(0.0, 2.0 * np.pi, 9)
HELIX = np.column_stack([0.2 * np.cos(_S), 0.2 * np.sin(_S), 0.1 * _S / (2.0 * np.pi)])
KNOTS = [0, 0, 0, 0, 1, 2, 3, 4, 5, 6, 6, 6, 6]

SCENARIO = f"""
[geometry]
kind = "nurbs"
degree = 3
knots = {KNOTS}
control_points = {np.round(HELIX, 12).tolist()}

[mesh]
elements = 1

[section]
radius = 0.005

[material]
density = 1000.0
youngs_modulus = 1.0e8

[[supports]]
at = "start"
kind = "clamp"

[loads]
gravity = [0.0, 0.0, -9.81]

[solver]
t_end = 0.004
step = 1.0e-3
"""


@pytest.fixture(scope="module")
def helix_run(tmp_path_factory):
    d = tmp_path_factory.mktemp("helix")
    (d / "helix.toml").write_text(SCENARIO)
    assert main(["simulate", str(d / "helix.toml"), "--out", str(d / "run"), "--quiet"]) == 0
    return d / "run"


def _figures(monkeypatch) -> dict:
    saved: dict = {}
    real = run_plots.save_figure

    def keep(fig, path, *args, **kwargs):
        axes = fig.axes[0]
        saved[path.name] = (
            getattr(axes, "name", ""),
            [axes.get_xlabel(), axes.get_ylabel(), getattr(axes, "get_zlabel", str)()],
            [
                ln.get_data_3d() if hasattr(ln, "get_data_3d") else ln.get_data()
                for ln in axes.lines
            ],
        )
        return real(fig, path, *args, **kwargs)

    monkeypatch.setattr(run_plots, "save_figure", keep)
    monkeypatch.setattr(system_run, "save_figure", keep)
    return saved


def test_configurations_of_a_helix_are_drawn_in_3d(helix_run, tmp_path, monkeypatch, capsys):
    saved = _figures(monkeypatch)
    assert main(["plot", str(helix_run), "--out", str(tmp_path), "--configurations", "2"]) == 0
    name, labels, lines = saved["configurations.png"]
    assert name == "3d" and labels == ["x [m]", "y [m]", "z [m]"]
    run = load_run(helix_run).body()
    first = sample_centerline(run, 0).points
    x, y, z = (np.asarray(c) for c in lines[0])
    assert np.ptp(z) > 0.09  # the helix rises 0.1 m: its z is drawn, not dropped
    assert np.allclose(np.column_stack([x, y, z]), first, rtol=0, atol=1e-12)
    assert (tmp_path / "configurations.png").stat().st_size > 0


def test_planar_runs_stay_planar(tmp_path, monkeypatch, capsys):
    from tests.scenario.test_scenario import BASE

    (tmp_path / "p.toml").write_text(BASE)
    assert (
        main(["simulate", str(tmp_path / "p.toml"), "--out", str(tmp_path / "r"), "--quiet"]) == 0
    )
    saved = _figures(monkeypatch)
    assert main(["plot", str(tmp_path / "r")]) == 0
    name, labels, _ = saved["configurations.png"]
    assert name != "3d" and labels[:2] == ["x [m]", "y [m]"]


def test_animation_of_a_helix_is_3d(helix_run, tmp_path, monkeypatch):
    frames = []
    import matplotlib.animation as animation

    real = animation.PillowWriter.grab_frame

    def grab(self, **kw):
        ax = self.fig.axes[0]
        frames.append((ax.name, np.asarray(ax.lines[0].get_data_3d()[2]).copy()))
        return real(self, **kw)

    monkeypatch.setattr(animation.PillowWriter, "grab_frame", grab)
    assert animate_system_run(load_run(helix_run), tmp_path / "h.gif", fps=5) == 5
    assert all(name == "3d" for name, _ in frames) and np.ptp(frames[-1][1]) > 0.09
