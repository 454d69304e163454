"""``rancf view``: one self-contained HTML page of a run (bodies, obstacles, contact forces, play,
pause and a time slider).  The page's data are checked against the run folder without a
browser; with Chromium on the machine (Debian: ``apt-get install chromium``) the pages of the
belt drive and the robot cable are loaded headless: no console error, every trace and frame in
the live page, and the screenshot shows the body in its colour."""

from __future__ import annotations

import re
import shutil
import subprocess
from importlib import resources
from pathlib import Path

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section
from rancf.cli import main
from rancf.mesh.factories import mesh_line
from rancf.post.results import write_run
from rancf.post.system_run import load_run
from rancf.post.view import BODY_COLORS, view_figure
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.system import Obstacle, System

CHROMIUM = next((p for p in map(shutil.which, ("chromium", "chromium-browser")) if p), None)


def _spatial_run(folder: Path) -> None:
    """A spatial cable above a floor, a ball and a bar (the three kinds of obstacle), 10 ms."""
    cable = Model(
        mesh_line([-0.5, 0.0, 0.3], [0.5, 0.0, 0.3], 4),
        "rancf",
        Section.circular(0.01),
        Material(1000.0, 1e7),
        gravity=(0.0, 0.0, -9.81),
    )
    obstacles = [
        Obstacle("plane", point=(0, 0, 0), normal=(0, 0, 2), name="floor"),
        Obstacle("sphere", center=(0, 0, 0.1), radius=0.19, name="ball"),
        Obstacle("cylinder", center=(0.3, 0, 0.2), radius=0.06, axis=(0, 1, 1), name="bar"),
    ]
    system = System({"cable": cable}, obstacles=obstacles)
    write_run(folder, system, [], integrate(system, DynamicOptions(t_end=0.01, step=1e-3)))


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The belt drive (0.1 s), the robot cable (0.05 s after its static start) and a spatial
    cable touching three obstacles (10 ms)."""
    out = tmp_path_factory.mktemp("view")
    _spatial_run(out / "spatial")
    done = {"spatial": out / "spatial"}
    for name, t_end in (("belt-drive", 0.1), ("robot-cable", 0.05)):
        text = (resources.files("rancf.examples") / f"{name}.toml").read_text(encoding="utf-8")
        f = out / f"{name}.toml"
        f.write_text(re.sub(r"(?m)^t_end = .*$", f"t_end = {t_end}", text), encoding="utf-8")
        assert main(["simulate", str(f), "--out", str(out / name), "--quiet"]) == 0
        done[name] = out / name
    return done


def test_page_holds_the_run(runs, capsys):
    run = load_run(runs["belt-drive"])
    fig = view_figure(run, frames=4, per_element=8)
    idx = np.unique(np.linspace(0, run.t.size - 1, 4).round().astype(int))
    assert [f.name for f in fig.frames] == [run.time_text(run.t[i]) for i in idx]
    react = np.genfromtxt(runs["belt-drive"] / "reactions.csv", delimiter=",", names=True)
    forces = {
        ob: np.column_stack([react[f"{ob}_normal_{a}"] + react[f"{ob}_friction_{a}"] for a in "xy"])
        for ob in ("pulley_a", "pulley_b")
    }
    top = max(np.linalg.norm(f[idx], axis=1).max() for f in forces.values())
    allp = np.concatenate([p for i in idx for _, p in run.shapes(int(i), per_element=8)])
    size = 0.5 * np.ptp(allp, axis=0).max()  # half the bodies' extent
    for frame, i in zip(fig.frames, idx, strict=True):
        tr = {t.name: t for t in frame.data}
        belt = np.column_stack([tr["belt"].x, tr["belt"].y])
        expected = run.shapes(int(i), per_element=8)[0][1][:, :2]
        assert np.abs(belt - expected).max() < 1e-7  # float32 on the page
        centre, _ = run.rigid_frame(run.bodies[2], int(i))  # the driven pulley carries pulley_b
        ring = np.column_stack([tr["pulley_b"].x, tr["pulley_b"].y]) - centre[:2]
        assert np.abs(np.linalg.norm(ring, axis=1) - 0.1).max() < 1e-12
        for ob, f in forces.items():
            arrow = tr[f"force on {ob}"]
            d = np.array([arrow.x[1] - arrow.x[0], arrow.y[1] - arrow.y[0]])
            # arrows of one scale: the largest force of the drawn times is half the scene's size
            assert np.linalg.norm(d) * top == pytest.approx(
                np.linalg.norm(f[i]) * 0.5 * size, rel=1e-6, abs=1e-12
            )
            assert d @ f[i] >= 0.0
    assert main(["view", str(runs["belt-drive"]), "--frames", "3"]) == 0
    page = runs["belt-drive"] / "view.html"
    assert capsys.readouterr().out == f"3 of {run.t.size} stored times -> {page}\n"
    html = page.read_text(encoding="utf-8")
    assert not re.search(r"<script[^>]+src=", html)  # the library is inlined: works offline
    assert "Plotly.addFrames" in html and html.count('"name":"t = ') >= 3
    assert page.stat().st_size < 6e6


def test_spatial_obstacles_are_drawn_where_they_are(runs):
    """The surfaces lie on the obstacles: the sphere's points at its radius from its centre,
    the tube's at its radius from its axis, the floor's square in the plane z = 0 about the
    point below the cable's centre; the arrows point along the forces the run stored."""
    run = load_run(runs["spatial"])
    fig = view_figure(run, frames=3)
    tr = {t.name: t for t in fig.frames[-1].data}
    pts = {
        k: np.stack([np.asarray(tr[k][a], float) for a in "xyz"], axis=-1).reshape(-1, 3)
        for k in ("ball", "bar", "floor")
    }
    assert np.abs(np.linalg.norm(pts["ball"] - [0, 0, 0.1], axis=1) - 0.19).max() < 1e-12
    axis = np.array([0, 1, 1]) / np.sqrt(2)
    rel = pts["bar"] - [0.3, 0, 0.2]
    radial = rel - np.outer(rel @ axis, axis)
    assert np.abs(np.linalg.norm(radial, axis=1) - 0.06).max() < 1e-12
    assert np.abs(pts["floor"][:, 2]).max() == 0.0
    cable = np.concatenate([run.shapes(i, per_element=8)[0][1] for i in (0, 5, 10)])
    centre = 0.5 * (cable.min(axis=0) + cable.max(axis=0))  # of the cable over the drawn times
    assert pts["floor"][:, :2].mean(axis=0) == pytest.approx(centre[:2], abs=1e-12)
    react = np.genfromtxt(runs["spatial"] / "reactions.csv", delimiter=",", names=True)
    for ob in ("ball", "bar", "floor"):
        f = np.array(
            [react[f"{ob}_normal_{a}"][-1] + react[f"{ob}_friction_{a}"][-1] for a in "xyz"]
        )
        a = tr[f"force on {ob}"]
        d = np.array([a.x[1] - a.x[0], a.y[1] - a.y[0], a.z[1] - a.z[0]])
        if np.linalg.norm(f) > 0:
            assert d / np.linalg.norm(d) == pytest.approx(f / np.linalg.norm(f), abs=1e-9)
        else:
            assert np.linalg.norm(d) == 0.0


def test_frames_and_samples_are_checked(runs, capsys):
    assert main(["view", str(runs["robot-cable"]), "--frames", "0"]) == 2
    assert "--frames = 0 is not allowed: an integer >= 1" in capsys.readouterr().err


#: A test harness put before the page's own scripts: console errors and uncaught exceptions are
#: logged with a marker (Chromium's log does not say a message's level), and once loaded the
#: page goes to its last frame (as the slider does) and reports how many traces and frames its
#: plot holds and the slider's position.
HARNESS = """<script>
const _err = console.error;
console.error = (...a) => { console.log("VIEW-ERROR " + a.join(" ")); _err(...a); };
window.addEventListener("error", (e) => console.log("VIEW-ERROR " + e.message));
window.addEventListener("unhandledrejection", (e) => console.log("VIEW-ERROR " + e.reason));
window.addEventListener("load", () => setTimeout(() => {
  const d = document.querySelector(".plotly-graph-div");
  const frames = d._transitionData._frames;
  Plotly.animate(d, [frames[frames.length - 1].name],
                 {mode: "immediate", frame: {duration: 0, redraw: true}}).then(() =>
    console.log(["VIEW-LOADED", d.data.length, frames.length,
                 d.layout.sliders[0].active].join(" ")));
}, 300));
</script>"""


def _browse(page: Path, shot: Path) -> subprocess.Popen:
    harnessed = page.with_name("harnessed.html")
    harnessed.write_text(
        page.read_text(encoding="utf-8").replace("<head>", "<head>" + HARNESS, 1), encoding="utf-8"
    )
    cmd = [
        CHROMIUM,
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--enable-unsafe-swiftshader",
        "--enable-logging=stderr",
        "--v=0",
        "--window-size=900,700",
        "--virtual-time-budget=3000",
        f"--screenshot={shot}",
        harnessed.as_uri(),
    ]
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@pytest.mark.skipif(
    CHROMIUM is None,
    reason="no chromium binary on PATH (Debian: apt-get "
    "install chromium): the page is not loaded in a browser",
)
def test_pages_load_in_headless_chromium(runs, tmp_path):
    from PIL import Image

    pages = {}
    for name, run in runs.items():
        assert main(["view", str(run), "--frames", "5"]) == 0
        pages[name] = (_browse(run / "view.html", tmp_path / f"{name}.png"), run)
    try:
        logs = {name: proc.communicate(timeout=600)[1] for name, (proc, _) in pages.items()}
    finally:  # a browser that hangs is not left behind
        for proc, _ in pages.values():
            proc.kill()
    for name, (_, run) in pages.items():
        log = logs[name]
        console = [ln for ln in log.splitlines() if "CONSOLE" in ln]
        assert not [ln for ln in console if "VIEW-ERROR" in ln or "Uncaught" in ln], console
        loaded = [ln for ln in console if "VIEW-LOADED" in ln]
        traces = len(view_figure(load_run(run), 5).data)
        assert len(loaded) == 1 and f'"VIEW-LOADED {traces} 5 4"' in loaded[0], console
        img = np.asarray(Image.open(tmp_path / f"{name}.png").convert("RGB")).astype(int)
        assert img.shape == (700, 900, 3)
        plot = img[60:520, :690]  # the scene: below the title, above the slider, left of legend
        body = np.array([int(BODY_COLORS[0][k : k + 2], 16) for k in (1, 3, 5)])
        rows, cols = np.nonzero(np.abs(plot - body).sum(axis=-1) < 60)
        assert rows.size > 400, f"{name}: {rows.size} pixels of the body's colour"
        # the body spans the drawing: both runs are 0.7 m wide, 1.8 / 2.6 of the scene's width
        assert np.ptp(cols) > 150, f"{name}: the body's pixels span {np.ptp(cols)} columns"
