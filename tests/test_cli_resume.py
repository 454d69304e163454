"""``rancf simulate --resume``: a run killed with SIGKILL halfway goes on from its last
checkpoint and its folder then reads as one run, the same to 1e-12 as a run never stopped (a
pendulum, a mechanism with joints, a rope with friction over a capstan); ``--t-end`` extends a
finished run; the leftovers of a killed run (raw history, temporary files, the lock file with its
dead process's id) block neither a resume nor a new run."""

from __future__ import annotations

import errno
import json
import os
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.cli.io import LOCK_NAME, OutputDir
from rancf.errors import InputError
from rancf.solvers.state import DynamicState

RANCF = [sys.executable, "-m", "rancf"]
RTOL = 1e-12

#: Examples and end times whose stepping takes about a second: long enough to be killed near
#: halfway (a checkpoint takes about 0.1 s), short enough for the suite.
KILLED = {"planar-pendulum": 12.0, "slider-crank": 0.26, "capstan": 0.8}

#: The fraction of the end time after which a run is killed.
KILL_AFTER = 0.4


def _arrays(run: Path) -> dict[str, np.ndarray]:
    with np.load(run / "results.npz") as z:
        out = {k: z[k] for k in ("t", "q", "v", "a", "lam", "sensors", "reactions")}
    out["sensors.csv"] = np.loadtxt(run / "sensors.csv", delimiter=",", skiprows=1, ndmin=2)
    return out


def _same_run(got: Path, want: Path) -> None:
    a, b = _arrays(got), _arrays(want)
    np.testing.assert_array_equal(a["t"], b["t"])
    for key in ("q", "v", "a", "lam", "sensors", "reactions", "sensors.csv"):
        scale = max(float(np.max(np.abs(b[key]), initial=0.0)), 1e-300)
        assert a[key].shape == b[key].shape, key
        assert float(np.max(np.abs(a[key] - b[key]), initial=0.0)) <= RTOL * scale, key
    sa = json.loads((got / "summary.json").read_text())
    sb = json.loads((want / "summary.json").read_text())
    assert sa["status"] == sb["status"] == "completed"
    assert sa["steps"] == sb["steps"] and sa["newton_iterations"] == sb["newton_iterations"]


def _start(name: str, t_end: float, cwd: Path) -> subprocess.Popen:
    return subprocess.Popen(
        [
            *RANCF,
            "simulate",
            f"{name}.toml",
            "--out",
            f"killed-{name}",
            "--quiet",
            "--t-end",
            repr(t_end),
            "--checkpoint-every",
            "0.01",
            "--overwrite",
        ],
        cwd=cwd,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )


def _kill_midway(ends: dict[str, float], cwd: Path) -> dict[str, float]:
    """Start the runs and SIGKILL each once its folder's checkpoint passed :data:`KILL_AFTER`
    of its end time; a run that ended before a checkpoint came there (checkpoints follow
    each other at least four times the time one takes) is run again, twice as long.  Returns
    the end times of the runs killed."""
    procs = {name: _start(name, t_end, cwd) for name, t_end in ends.items()}
    deadline = time.monotonic() + 300
    while procs and time.monotonic() < deadline:
        for name, p in list(procs.items()):
            try:
                doc = json.loads((cwd / f"killed-{name}" / "summary.json").read_text())
            except (OSError, ValueError):
                doc = {}
            reached = doc.get("t_reached") or 0.0
            midway = KILL_AFTER * ends[name] <= reached < ends[name]  # not at its very end
            if midway and doc.get("status") == "running":
                p.send_signal(signal.SIGKILL)
                p.communicate(timeout=30)
                del procs[name]
            elif p.poll() is not None:  # ended first: again, longer
                ends[name] *= 2.0
                procs[name] = _start(name, ends[name], cwd)
        time.sleep(0.002)
    assert not procs, "runs not killed midway"
    return ends


def test_killed_runs_resume_to_the_same_state(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    for name in KILLED:
        assert main(["example", "copy", name, "."]) == 0
    ends = _kill_midway(dict(KILLED), tmp_path)
    for name, t_end in ends.items():
        run = tmp_path / f"killed-{name}"
        args = ["simulate", f"{name}.toml", "--out", f"whole-{name}", "--quiet"]
        assert main([*args, "--t-end", repr(t_end)]) == 0  # the run never stopped
        summary = json.loads((run / "summary.json").read_text())
        assert summary["status"] == "running"
        assert KILL_AFTER * t_end <= summary["t_reached"] < t_end  # killed midway
        at = DynamicState.load(run / "checkpoint.npz").t  # renamed before the summary
        assert at >= summary["t_reached"]
        assert (run / LOCK_NAME).read_text().split() == [str(summary["pid"])]
        assert (run / ".history").is_dir()
        if name == "planar-pendulum":  # the leftovers block no new run either
            shutil.copytree(run, tmp_path / "again")
            again = ["simulate", f"{name}.toml", "--out", "again", "--quiet", "--t-end", "0.05"]
            assert main([*again, "--overwrite"]) == 0
            assert sorted(p.name for p in (tmp_path / "again").iterdir()) == sorted(
                p.name for p in (tmp_path / f"whole-{name}").iterdir()
            )
        capsys.readouterr()
        args = ["simulate", f"{name}.toml", "--out", run.name, "--resume", "--t-end", repr(t_end)]
        assert main(args) == 0
        err = capsys.readouterr().err
        assert f"process {summary['pid']} no longer runs" in err
        assert f"resuming from t = {at:g} s" in err
        _same_run(run, tmp_path / f"whole-{name}")
        left = sorted(p.name for p in run.iterdir())
        assert left == sorted(p.name for p in (tmp_path / f"whole-{name}").iterdir())
        assert json.loads((run / "summary.json").read_text())["resumed_at"] == [at]


def test_t_end_extends_a_finished_run(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["example", "copy", "capstan", "."]) == 0
    base = ["simulate", "capstan.toml", "--quiet"]
    assert main([*base, "--out", "whole", "--t-end", "0.06"]) == 0
    assert main([*base, "--out", "run", "--t-end", "0.03"]) == 0
    assert main([*base, "--out", "run", "--resume", "--t-end", "0.06"]) == 0
    _same_run(tmp_path / "run", tmp_path / "whole")
    capsys.readouterr()
    assert main(["simulate", "capstan.toml", "--out", "run", "--resume", "--t-end", "0.06"]) == 0
    assert "nothing to do" in capsys.readouterr().err


def test_resume_refuses_another_scenario(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["example", "copy", "planar-pendulum", "."]) == 0
    assert (
        main(["simulate", "planar-pendulum.toml", "--out", "run", "--quiet", "--t-end", "0.05"])
        == 0
    )
    text = (tmp_path / "planar-pendulum.toml").read_text().replace("rho_inf = 0.9", "rho_inf = 0.8")
    (tmp_path / "other.toml").write_text(text)
    capsys.readouterr()
    assert main(["simulate", "other.toml", "--out", "run", "--resume", "--t-end", "0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "solver.rho_inf differs" in err, err
    # a new or empty folder: --resume starts a new run
    assert (
        main(
            [
                "simulate",
                "planar-pendulum.toml",
                "--out",
                "new",
                "--resume",
                "--quiet",
                "--t-end",
                "0.05",
            ]
        )
        == 0
    )
    assert json.loads((tmp_path / "new" / "summary.json").read_text())["status"] == "completed"


def test_a_stale_lock_is_told_by_its_pid_where_flock_fails(tmp_path, monkeypatch):
    import fcntl

    def no_flock(fd, op):
        raise OSError(errno.ENOLCK, "No locks available")

    monkeypatch.setattr(fcntl, "flock", no_flock)
    dead = subprocess.Popen([sys.executable, "-c", "pass"])
    dead.wait()
    (tmp_path / LOCK_NAME).write_text(f"{dead.pid}\n")
    with OutputDir(tmp_path, kind="any") as od:  # stale: taken
        assert (tmp_path / LOCK_NAME).read_text().split() == [str(os.getpid())]
        assert od.path == tmp_path
    (tmp_path / LOCK_NAME).write_text(f"{os.getppid()}\n")  # a process that runs
    with pytest.raises(InputError, match=f"process {os.getppid()} is"), OutputDir(tmp_path):
        pass


def test_resume_needs_a_checkpoint(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["example", "copy", "cantilever", "."]) == 0
    assert main(["static", "cantilever.toml", "--out", "eq"]) == 0
    capsys.readouterr()
    assert main(["simulate", "cantilever.toml", "--out", "eq", "--resume"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "a checkpoint to go on from" in err, err
    assert (tmp_path / "eq" / "summary.json").is_file()  # the static solution stays


def _hashes(folder: Path) -> dict[str, str]:
    import hashlib

    return {
        str(p.relative_to(folder)): hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(folder.rglob("*"))
        if p.is_file()
    }


def _damage(run: Path, how: str) -> None:
    if how in ("truncated", "results"):
        path = run / ("checkpoint.npz" if how == "truncated" else "results.npz")
        data = path.read_bytes()
        path.write_bytes(data[: len(data) // 2])
        return
    state = DynamicState.load(run / "checkpoint.npz")
    if how == "shape":
        state.y = np.zeros(10)
    elif how == "memory":
        state.memory = np.zeros(7)
    elif how == "k_out":
        state.k_out = -5
    else:
        state.v[3] = np.nan
    state.save(run / "checkpoint.npz")


@pytest.mark.parametrize(
    ("how", "says"),
    [
        ("shape", "coordinates 10; needed: a state of this system (coordinates 24)"),
        ("nan", "a NaN or infinite number in v"),
        (
            "memory",
            "memory of 7 numbers; needed: an integrator memory of this system and its "
            "Newton method",
        ),
        ("k_out", "k_out = -5; needed: a state of finite numbers"),
        ("truncated", "a state written by a rancf run (reading it: File is not a zip file)"),
        ("results", "run/results.npz' is not allowed: a run folder's results file"),
    ],
)
def test_a_refused_resume_leaves_the_run_as_it_was(tmp_path, monkeypatch, capsys, how, says):
    """A damaged checkpoint (another system's, a NaN, cut short) or results file is refused on
    one line naming the file, exit 2, before anything in the folder changes."""
    monkeypatch.chdir(tmp_path)
    assert main(["example", "copy", "planar-pendulum", "."]) == 0
    args = ["simulate", "planar-pendulum.toml", "--out", "run", "--quiet"]
    assert main([*args, "--t-end", "0.05"]) == 0
    _damage(tmp_path / "run", how)
    (tmp_path / "run" / ".history").mkdir()  # a killed run's leftover stays too
    before = _hashes(tmp_path / "run")
    capsys.readouterr()
    assert main([*args, "--resume", "--t-end", "0.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and says in err, err
    assert "run/" in err and err.startswith("rancf: error: "), err
    assert _hashes(tmp_path / "run") == before
    assert (tmp_path / "run" / ".history").is_dir()
