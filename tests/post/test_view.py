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

from rancf.cli import main
from rancf.post.system_run import load_run
from rancf.post.view import BODY_COLORS, view_figure

CHROMIUM = next((p for p in map(shutil.which, ("chromium", "chromium-browser")) if p), None)


@pytest.fixture(scope="module")
def runs(tmp_path_factory):
    """The belt drive (0.1 s) and the robot cable (0.05 s after its static start)."""
    out = tmp_path_factory.mktemp("view")
    done = {}
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
    forces = {ob: np.column_stack([react[f"{ob}_normal_{a}"] + react[f"{ob}_friction_{a}"]
                                   for a in "xy"]) for ob in ("pulley_a", "pulley_b")}  # fmt: skip
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
            assert np.linalg.norm(d) * top == pytest.approx(np.linalg.norm(f[i]) * 0.5 * size,
                                                            rel=1e-6, abs=1e-12)  # fmt: skip
            assert d @ f[i] >= 0.0
    assert main(["view", str(runs["belt-drive"]), "--frames", "3"]) == 0
    page = runs["belt-drive"] / "view.html"
    assert capsys.readouterr().out == f"3 of {run.t.size} stored times -> {page}\n"
    html = page.read_text(encoding="utf-8")
    assert not re.search(r"<script[^>]+src=", html)  # the library is inlined: works offline
    assert "Plotly.addFrames" in html and html.count('"name":"t = ') >= 3
    assert page.stat().st_size < 6e6


def test_frames_and_samples_are_checked(runs, capsys):
    assert main(["view", str(runs["robot-cable"]), "--frames", "0"]) == 2
    assert "--frames = 0 is not allowed: an integer >= 1" in capsys.readouterr().err


#: A test harness put before the page's own scripts: console errors and uncaught exceptions are
#: logged with a marker (Chromium's log does not say a message's level), and once loaded the
#: page reports how many traces and frames its plot holds.
HARNESS = """<script>
const _err = console.error;
console.error = (...a) => { console.log("VIEW-ERROR " + a.join(" ")); _err(...a); };
window.addEventListener("error", (e) => console.log("VIEW-ERROR " + e.message));
window.addEventListener("unhandledrejection", (e) => console.log("VIEW-ERROR " + e.reason));
window.addEventListener("load", () => setTimeout(() => {
  const d = document.querySelector(".plotly-graph-div");
  console.log("VIEW-LOADED " + d.data.length + " " + d._transitionData._frames.length);
}, 500));
</script>"""


def _browse(page: Path, shot: Path) -> subprocess.Popen:
    harnessed = page.with_name("harnessed.html")
    harnessed.write_text(page.read_text(encoding="utf-8").replace("<head>", "<head>" + HARNESS,
                                                                  1), encoding="utf-8")  # fmt: skip
    cmd = [CHROMIUM, "--headless", "--no-sandbox", "--disable-gpu", "--enable-unsafe-swiftshader",
           "--enable-logging=stderr", "--v=0", "--window-size=900,700",
           "--virtual-time-budget=3000", f"--screenshot={shot}", harnessed.as_uri()]  # fmt: skip
    return subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium binary on PATH (Debian: apt-get "
                    "install chromium): the page is not loaded in a browser")  # fmt: skip
def test_pages_load_in_headless_chromium(runs, tmp_path):
    from PIL import Image

    pages = {}
    for name, run in runs.items():
        assert main(["view", str(run), "--frames", "5"]) == 0
        pages[name] = (_browse(run / "view.html", tmp_path / f"{name}.png"), run)
    for name, (proc, run) in pages.items():
        _, log = proc.communicate(timeout=120)
        console = [ln for ln in log.splitlines() if "CONSOLE" in ln]
        assert not [ln for ln in console if "VIEW-ERROR" in ln or "Uncaught" in ln], console
        loaded = [ln for ln in console if "VIEW-LOADED" in ln]
        traces = len(view_figure(load_run(run), 5).data)
        assert len(loaded) == 1 and f'"VIEW-LOADED {traces} 5"' in loaded[0], console
        img = np.asarray(Image.open(tmp_path / f"{name}.png").convert("RGB")).astype(int)
        assert img.shape == (700, 900, 3)
        plot = img[60:520, :690]  # the scene: below the title, above the slider, left of legend
        body = np.array([int(BODY_COLORS[0][k : k + 2], 16) for k in (1, 3, 5)])
        rows, cols = np.nonzero(np.abs(plot - body).sum(axis=-1) < 60)
        assert rows.size > 400, f"{name}: {rows.size} pixels of the body's colour"
        # the body spans the drawing: both runs are 0.7 m wide, 1.8 / 2.6 of the scene's width
        assert np.ptp(cols) > 150, f"{name}: the body's pixels span {np.ptp(cols)} columns"
