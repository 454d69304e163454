"""The command line as a real process: interrupts, kills, broken pipes, file modes."""

from __future__ import annotations

import argparse
import json
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.post.results import load_results
from tests.test_cli_errors import mutated

RANCF = [sys.executable, "-m", "rancf"]

# meshing and assembly take a noticeable moment, then ~2 s of time stepping
# (rtol: the pendulum's release is not resolved in its first step, and a completed run must
# print nothing here)
SLOW = mutated(mesh__elements=3000, solver__t_end=0.15, solver__output_step=1e-3, solver__rtol=1e-3)
LONG = mutated(mesh__elements=40, solver__t_end=100.0, solver__output_step=1e-2)


def _start(args: list[str], cwd: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [*RANCF, *args], cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.PIPE
    )


def _check_run_dir(run: Path) -> dict:
    """Every file of a run directory is complete and consistent; returns the summary."""
    summary = json.loads((run / "summary.json").read_text())  # strict JSON
    sensors = np.loadtxt(run / "sensors.csv", delimiter=",", skiprows=1, ndmin=2)
    energy = np.loadtxt(run / "energy.csv", delimiter=",", skiprows=1, ndmin=2)
    res = load_results(run / "results.npz")
    assert sensors.shape[0] == energy.shape[0] == res["t"].size == res["q"].shape[0]
    assert np.all(np.diff(sensors[:, 0]) > 0)
    return summary


def _boot_times() -> list[float]:
    """Times the interpreter takes to start and load ``rancf.__main__`` (no rancf code runs
    before that: an interrupt then is Python's own start-up, outside the project's reach)."""
    times = []
    for _ in range(3):
        t0 = time.monotonic()
        subprocess.run([sys.executable, "-c", "import rancf.__main__"], check=True)
        times.append(time.monotonic() - t0)
    return times


def _interrupt(tmp_path: Path, name: str, delay: float, early: bool = False) -> str:
    """Ctrl-C ``delay`` s after the start of ``simulate``; checks the outcome and returns what
    it met: ``"before the run"`` or the run's status; with ``early``, ``"start-up"`` when the
    interrupt came during Python's own start-up, before ``rancf.__main__`` ran (its traceback
    has no frame of it)."""
    run = tmp_path / name
    p = _start(["simulate", "s.toml", "--out", run.name, "--quiet"], tmp_path)
    time.sleep(delay)
    p.send_signal(signal.SIGINT)
    _, err = p.communicate(timeout=120)
    text = err.decode()
    if early and "Traceback" in text and "rancf/__main__.py" not in text:
        assert not run.exists()
        return "start-up"
    assert "Traceback" not in text, text
    assert p.returncode in (0, 130), (delay, p.returncode, text)
    assert len(text.strip().splitlines()) == (p.returncode == 130), text
    if not run.exists():
        assert p.returncode == 130
        return "before the run"
    summary = _check_run_dir(run)
    assert not (run / ".history").exists()
    expected = "completed" if p.returncode == 0 else "interrupted"
    assert summary["status"] in (expected, "completed"), (summary, text)
    return summary["status"]


def test_sigint_at_random_moments(tmp_path):
    """Ctrl-C during imports, meshing, assembly, stepping and writing: one line, status 130,
    either no output at all or a complete, truthful run directory."""
    (tmp_path / "s.toml").write_text(SLOW)
    rng = random.Random(20261122)
    times = _boot_times()
    boot = max(times)
    delays = [boot + d for d in (0.02, 0.2, 0.5, 1.0)]
    delays += [boot + rng.uniform(0.0, 3.0) for _ in range(4)]
    seen = {_interrupt(tmp_path, f"run{i}", delay) for i, delay in enumerate(delays)}
    # on a loaded machine the start-up time varies: more tries from the quickest start-up on
    for i in range(10):
        if "before the run" in seen:
            break
        seen.add(_interrupt(tmp_path, f"early{i}", min(times) + 0.02 * i, early=True))
    # and, on a loaded machine, later ones until one meets the run stepping
    for i in range(6):
        if "interrupted" in seen or "completed" in seen:
            break
        seen.add(_interrupt(tmp_path, f"late{i}", boot + 3.0 * (i + 2)))
    assert "before the run" in seen and "interrupted" in seen


def test_sigkill_during_a_run_leaves_readable_files(tmp_path):
    (tmp_path / "s.toml").write_text(LONG)
    run = tmp_path / "run"
    p = _start(
        ["simulate", "s.toml", "--out", "run", "--quiet", "--checkpoint-every", "0.2"], tmp_path
    )
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        try:
            doc = json.loads((run / "summary.json").read_text())
        except (OSError, ValueError):
            doc = {}
        if doc.get("t_reached", 0) > 0.05:
            break
        time.sleep(0.05)
    p.send_signal(signal.SIGKILL)
    p.communicate(timeout=30)
    summary = _check_run_dir(run)
    assert summary["status"] == "running" and summary["pid"] == p.pid
    assert summary["t_reached"] > 0.05
    with pytest.raises(ProcessLookupError):
        os.kill(p.pid, 0)


def test_broken_pipe_is_quiet(tmp_path):
    args = ["conic", "--chord", "0.5", "--angles", "30", "40", "--point", "0.315", "0.077"]
    p = _start([*args, "--json", "--elements", "200"], tmp_path)
    head = p.stdout.read(10)
    p.stdout.close()
    err = p.stderr.read().decode()
    p.wait(timeout=60)
    assert len(head) == 10
    assert "Traceback" not in err and err == ""
    assert p.returncode == 141


def test_errors_in_a_real_process_are_one_line(tmp_path):
    (tmp_path / "latin.toml").write_bytes("# café\n".encode("latin-1"))
    (tmp_path / "afile").write_text("x")
    for args, needle in (
        (["static", "latin.toml"], "UTF-8"),
        (["simulate", "latin.toml", "--out", "afile/run"], "--out"),
    ):
        p = subprocess.run([*RANCF, *args], cwd=tmp_path, capture_output=True, text=True)
        assert p.returncode == 2 and p.stdout == ""
        assert len(p.stderr.splitlines()) == 1 and needle in p.stderr, p.stderr


@pytest.mark.parametrize(
    ("umask", "file_mode", "dir_mode"), [(0o022, 0o644, 0o755), (0o027, 0o640, 0o750)]
)
def test_files_honour_the_umask(tmp_path, monkeypatch, umask, file_mode, dir_mode):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated())
    old = os.umask(umask)
    try:
        assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    finally:
        os.umask(old)
    run = tmp_path / "run"
    assert run.stat().st_mode & 0o777 == dir_mode
    files = sorted(run.iterdir())
    names = ["bodies", "checkpoint.npz", "energy.csv", "reactions.csv", "results.npz"]
    names += ["scenario.toml"]
    names += ["sensors.csv", "summary.json"]
    assert [f.name for f in files] == names
    body = run / "bodies" / "body"
    assert all(d.stat().st_mode & 0o777 == dir_mode for d in (files[0], body))
    assert (body / "results.npz").stat().st_mode & 0o777 == file_mode
    assert all(f.stat().st_mode & 0o777 == file_mode for f in files[1:])


def test_an_interrupted_command_in_python_leaves_ctrl_c_to_the_caller(tmp_path, monkeypatch):
    """``main()`` called from Python (a notebook, a test) that ends by an interrupt gives the
    caller its Ctrl-C handler back: it set Ctrl-C to "ignore" for the rest of the process (and
    every process started from it, which then ignored Ctrl-C until their run began)."""
    before = signal.getsignal(signal.SIGINT)

    def interrupted(args):
        raise KeyboardInterrupt

    args = argparse.Namespace(func=interrupted)
    monkeypatch.setattr("rancf.cli.build_parser", lambda command=None: _Fixed(args))
    assert main(["conic"]) == 130
    assert signal.getsignal(signal.SIGINT) is before


class _Fixed:
    """A parser that returns fixed arguments."""

    def __init__(self, args):
        self.args = args

    def parse_args(self, argv):
        return self.args
