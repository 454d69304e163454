"""Runs under hostile conditions: interrupts however small the step, a full
disk, shared and earlier output folders, damaged or edited run folders, non-UTF-8 names, strict
JSON, sweeps resumed or stopped."""

from __future__ import annotations

import csv
import io
import json
import os
import random
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from tests.test_cli_errors import LINE, ROD, mutated, rod
from tests.test_cli_signals import _boot_times, _check_run_dir

RANCF = [sys.executable, "-m", "rancf"]
#: 40 elements for 0.5 s in steps of 1 ns: hours of stepping, whatever the moment of the stop
TINY_STEP = mutated(
    mesh__elements=40, solver__t_end=0.5, solver__step=1e-9, solver__output_step=1e-3
)
LONG = mutated(mesh__elements=40, solver__t_end=100.0, solver__output_step=1e-2)


def _strict(text: str) -> object:
    def refuse(name: str) -> None:
        raise ValueError(f"{name} is not strict JSON")

    return json.loads(text, parse_constant=refuse)


def _no_leftovers(folder: Path) -> None:
    assert not (folder / ".history").exists()
    assert not [p.name for p in folder.iterdir() if p.name.startswith(".")]


def test_a_stop_ends_within_a_second_however_small_the_step(tmp_path):
    """Ctrl-C or SIGTERM at any moment of a run of 1 ns steps: within 1 s, status 130, one line,
    and a truthful run folder."""
    (tmp_path / "s.toml").write_text(TINY_STEP)
    rng = random.Random(15)
    for i, sig in enumerate((signal.SIGINT, signal.SIGTERM, signal.SIGINT)):
        run = tmp_path / f"run{i}"
        p = subprocess.Popen(
            [*RANCF, "simulate", "s.toml", "--out", run.name, "--quiet"],
            cwd=tmp_path,
            stderr=subprocess.PIPE,
        )
        deadline = time.monotonic() + 60
        while not (run / "summary.json").exists() and time.monotonic() < deadline:
            time.sleep(0.01)  # the run has started (stops before that: test_cli_signals)
        time.sleep(rng.uniform(0.05, 1.0))
        sent = time.monotonic()
        p.send_signal(sig)
        try:
            _, err = p.communicate(timeout=5)
        except subprocess.TimeoutExpired:
            p.kill()
            pytest.fail(f"{sig!r} ignored for 5 s")
        took = time.monotonic() - sent
        assert took < 1.0, took
        assert p.returncode == 130 and len(err.decode().splitlines()) == 1, err
        summary = _check_run_dir(run)
        assert summary["status"] == "interrupted" and summary["steps"] > 0
        _no_leftovers(run)


def test_a_static_run_stopped_by_sigterm_says_so(tmp_path):
    """A load path stopped by SIGTERM: status 130, one line, and a summary that says so (the
    signal is sent again later or earlier if it missed the solve)."""
    clamped = {"geometry": LINE, "supports": [{"at": 0, "kind": "clamp"}]}
    loads = {"point": [{"at": -1, "force": [0.0, -1e-3]}]}
    text = mutated(**clamped, loads=loads, mesh__elements=20000, solver__load_steps=10**6)
    (tmp_path / "st.toml").write_text(text)
    delay = max(_boot_times()) + 2.0  # meshing and assembly, then some 2 s of load steps
    for attempt in range(8):
        out = tmp_path / f"eq{attempt}"
        p = subprocess.Popen(
            [*RANCF, "static", "st.toml", "--out", out.name],
            cwd=tmp_path,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.PIPE,
        )
        time.sleep(delay)
        p.send_signal(signal.SIGTERM)
        _, err = p.communicate(timeout=60)
        if p.returncode != 130:  # the solve ended first (20000 short elements may fail to rest)
            delay *= 0.6
            continue
        assert len(err.decode().splitlines()) == 1, err
        if not out.exists():  # stopped before the solve: nothing written
            delay *= 1.5
            continue
        summary = _check_run_dir(out)
        assert summary["status"] == "interrupted" and "interrupted" in summary["message"]
        assert 0 <= summary["load_factor_reached"] < 1
        return
    pytest.fail("the signal never landed in the solve")


def test_the_error_path_of_a_run_keeps_its_last_checkpoint(tmp_path, monkeypatch, capsys):
    """Any exception after a run started (here a full disk while the history is appended):
    one line naming the file, status 3, the folder holds the last complete checkpoint and its
    summary says failed."""
    from rancf.post.history import HistoryStore

    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(solver__t_end=0.5))
    flush = HistoryStore.flush

    def full_disk(self: HistoryStore) -> None:
        if self.saved_rows and self.n_rows + self._pending > 100:
            raise OSError(28, "No space left on device", str(self.raw / "q.f64"))
        flush(self)

    monkeypatch.setattr(HistoryStore, "flush", full_disk)
    monkeypatch.setattr(HistoryStore, "__init__", _small_buffer(HistoryStore.__init__))
    code = main(["simulate", "s.toml", "--out", "run", "--quiet", "--checkpoint-every", "1e-9"])
    err = capsys.readouterr().err.strip().splitlines()
    assert code == 3 and len(err) == 1, err
    assert "q.f64: No space left on device" in err[0] and "summary.json says failed" in err[0]
    summary = _check_run_dir(tmp_path / "run")
    assert summary["status"] == "failed" and "No space left" in summary["message"]
    assert (
        summary["outputs"]
        == np.loadtxt(tmp_path / "run/sensors.csv", delimiter=",", skiprows=1, ndmin=2).shape[0]
    )
    assert 0 < summary["t_reached"] < 0.5
    _no_leftovers(tmp_path / "run")


def _small_buffer(init):  # noqa: ANN001, ANN202 - wraps HistoryStore.__init__
    def wrapped(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
        kwargs["buffer_bytes"] = 1
        init(self, *args, **kwargs)

    return wrapped


@pytest.fixture
def tmpfs(tmp_path):
    """A 300 KB file system (skipped where mounting is not allowed)."""
    where = tmp_path / "small"
    where.mkdir()
    p = subprocess.run(
        ["mount", "-t", "tmpfs", "-o", "size=300k", "tmpfs", str(where)], capture_output=True
    )
    if p.returncode != 0:
        pytest.skip("mounting a tmpfs is not allowed here")
    yield where
    subprocess.run(["umount", str(where)], check=False)


def test_a_full_disk(tmp_path, tmpfs):
    (tmp_path / "s.toml").write_text(
        mutated(mesh__elements=20, solver__t_end=0.3, solver__output_step=1e-3)
    )
    cmd = [*RANCF, "simulate", "s.toml", "--quiet", "--checkpoint-every", "0.01", "--out"]
    # full while the run goes on: status 3, the file named, the last checkpoint kept
    p = subprocess.run([*cmd, str(tmpfs / "run")], cwd=tmp_path, capture_output=True, text=True)
    lines = p.stderr.splitlines()
    assert p.returncode == 3 and len(lines) == 1, p.stderr
    assert f"{tmpfs}/run/" in lines[0] and "No space left on device" in lines[0]
    summary = _check_run_dir(tmpfs / "run")
    assert summary["status"] == "failed" and summary["t_reached"] < 0.3
    _no_leftovers(tmpfs / "run")
    # an export into the full disk: the file named, nothing left (no .vtu without .pvd)
    assert (
        main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "r"), "--quiet"]) == 0
    )
    p = subprocess.run(
        [*RANCF, "export", "r", "--vtk", str(tmpfs / "vtk")],
        cwd=tmp_path,
        capture_output=True,
        text=True,
    )
    assert p.returncode == 2 and len(p.stderr.splitlines()) == 1, p.stderr
    assert f"{tmpfs}/vtk/body/body_" in p.stderr and not (tmpfs / "vtk").exists()
    # full before the first checkpoint: status 2 and nothing written
    (tmpfs / "run").rename(tmpfs / "kept")
    free = os.statvfs(tmpfs).f_bavail * os.statvfs(tmpfs).f_frsize
    (tmpfs / "filler").write_bytes(b"x" * max(0, free - 8192))
    p = subprocess.run([*cmd, str(tmpfs / "run2")], cwd=tmp_path, capture_output=True, text=True)
    assert p.returncode == 2 and len(p.stderr.splitlines()) == 1, p.stderr
    assert "No space left on device" in p.stderr and not (tmpfs / "run2").exists()


def test_a_run_failing_on_a_full_disk_still_says_so(tmpfs):
    """A disk that fills to the last byte while a run goes on: the raw history's reserve is
    freed, so the last ``summary.json`` says ``failed`` (not the ``running`` of before)."""
    import tomllib

    from rancf.post.history import HistoryStore
    from rancf.scenario import parse_scenario
    from rancf.scenario.system_build import support_labels
    from rancf.system.outputs import SystemOutputs

    sc = parse_scenario(tomllib.loads(mutated()), "s.toml")
    system = sc.build_system()
    out = tmpfs / "run"
    out.mkdir()
    store = HistoryStore(out, SystemOutputs(system, sc.sensors, support_labels(sc)), {})
    store.write_summary({"status": "running", "t_reached": 0.0})
    with open(tmpfs / "filler", "wb", buffering=0) as fh, pytest.raises(OSError):
        while True:  # every byte the disk has left
            fh.write(b"x" * 4096)
    assert not store.fail({"status": "failed", "message": "disk full", "t_reached": None})
    summary = json.loads((out / "summary.json").read_text())
    assert summary["status"] == "failed" and "disk full" in summary["message"]


def test_two_processes_on_one_output_folder(tmp_path):
    """The second process is refused with one line naming the first, which goes on unharmed."""
    (tmp_path / "s.toml").write_text(LONG)
    (tmp_path / "short.toml").write_text(mutated())
    cmd = [*RANCF, "simulate", "s.toml", "--out", "run", "--quiet"]
    first = subprocess.Popen(cmd, cwd=tmp_path, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 30
    while not (tmp_path / "run/.rancf.lock").exists() and time.monotonic() < deadline:
        time.sleep(0.02)
    second = subprocess.run(cmd, cwd=tmp_path, capture_output=True, text=True)
    assert second.returncode == 2 and len(second.stderr.splitlines()) == 1, second.stderr
    assert f"process {first.pid} is" in second.stderr and "--out" in second.stderr
    first.send_signal(signal.SIGINT)
    _, err = first.communicate(timeout=30)
    assert first.returncode == 130, err
    assert _check_run_dir(tmp_path / "run")["status"] == "interrupted"
    _no_leftovers(tmp_path / "run")
    # two started at once on a new folder: exactly one runs
    short = [*RANCF, "simulate", "short.toml"]
    both = [
        subprocess.Popen(
            [*short, "--out", "new", "--quiet"], cwd=tmp_path, stderr=subprocess.PIPE, text=True
        )
        for _ in range(2)
    ]
    ends = sorted((p.wait(timeout=120), p.stderr.read()) for p in both)
    assert [code for code, _ in ends] == [0, 2], ends
    assert len(ends[1][1].splitlines()) == 1 and "--out = 'new'" in ends[1][1]
    assert _check_run_dir(tmp_path / "new")["status"] == "completed"


def test_overwrite_replaces_an_earlier_run_wholly(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated())
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    assert main(["plot", "run"]) == 0
    (tmp_path / "run/notes.txt").write_text("stale")
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 2
    assert "--overwrite" in capsys.readouterr().err
    assert (tmp_path / "run/plots").is_dir()
    assert main(["simulate", "s.toml", "--out", "run", "--quiet", "--overwrite"]) == 0
    names = sorted(p.name for p in (tmp_path / "run").iterdir())
    assert names == [
        "bodies",
        "checkpoint.npz",
        "energy.csv",
        "reactions.csv",
        "results.npz",
        "scenario.toml",
        "sensors.csv",
        "summary.json",
    ]
    (tmp_path / "mine").mkdir()
    (tmp_path / "mine/thesis.tex").write_text("keep me")
    assert main(["simulate", "s.toml", "--out", "mine", "--quiet", "--overwrite"]) == 2
    assert "not a rancf run folder" in capsys.readouterr().err
    assert (tmp_path / "mine/thesis.tex").read_text() == "keep me"


def test_a_run_folder_outlives_edits_of_its_scenario(tmp_path, monkeypatch):
    """The run keeps a copy of its scenario: editing (or deleting) the original later changes
    nothing for export, plot and animate."""
    import meshio

    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(section__radius=0.02))
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    (tmp_path / "s.toml").write_text(mutated(mesh__elements=7, section__radius=0.5))
    assert main(["export", "run", "--vtk", "vtk"]) == 0
    radius = meshio.read(tmp_path / "vtk/body/body_00000.vtu").point_data["radius"]
    assert np.all(radius == 0.02)
    (tmp_path / "s.toml").unlink()
    assert main(["animate", "run", "--out", "run.gif", "--every", "10"]) == 0


def test_non_utf8_folder_names(tmp_path):
    """A run folder whose name is not UTF-8: plot and export work and print the name back as the
    same bytes."""
    (tmp_path / "s.toml").write_text(mutated())
    run, vtk = b"run\xff", b"vtk\xfe"
    env = {**os.environ, "LC_ALL": "C.UTF-8"}
    for args, printed in (
        ([b"simulate", b"s.toml", b"--out", run, b"--quiet"], b""),
        ([b"plot", run], run + b"/plots/energy.png"),
        ([b"export", run, b"--vtk", vtk, b"--every", b"10"], b"VTK frame(s) of run\xef\xbf\xbd"),
        ([b"export", run, b"--nurbs", b"shape\xfd.json"], b"shape\xfd.json"),
    ):
        p = subprocess.run([*RANCF, *args], cwd=tmp_path, capture_output=True, env=env)
        assert p.returncode == 0 and p.stderr == b"", p.stderr
        assert printed in p.stdout
    assert (tmp_path / os.fsdecode(vtk) / "body" / "body.pvd").is_file()


def test_modes_json_is_strict(tmp_path, capsys):
    """An eigenvalue that overflows (density 1e-300) is ``null``, not ``Infinity``."""
    loads = {"point": [{"at": "end", "moment": [0.0, 0.0, 1e-3]}]}
    (tmp_path / "r.toml").write_text(rod(material__density=1e-300, loads=loads))
    assert main(["modes", str(tmp_path / "r.toml"), "--json", "--about", "static"]) == 0
    out, err = capsys.readouterr()
    doc = _strict(out)
    assert err == "" and None in doc["frequencies_hz"] + doc["growth_rates_per_s"]


def test_sweep_rows_with_non_finite_values_fail(tmp_path, monkeypatch):
    from rancf.sweep import runner
    from rancf.sweep.engine import results_table
    from rancf.sweep.spec import Variant

    monkeypatch.setattr(
        runner, "_analyse", lambda sc, a, f: ("completed", "", 0.1, {"f1_hz": float("inf")})
    )
    raw = __import__("tomllib").loads(ROD)
    row = runner.run_variant("r", raw, str(tmp_path / "b.toml"), "modes", str(tmp_path / "r"))
    assert row["status"] == "failed" and "f1_hz" in row["message"]
    assert _strict((tmp_path / "r/row.json").read_text())["values"]["f1_hz"] is None
    table = results_table([Variant(0, "r", {}, raw)], {"r": row})
    (line,) = csv.DictReader(io.StringIO(table))
    assert line["status"] == "failed" and line["f1_hz"] == ""


def test_a_sweep_resumes_only_unchanged_variants(tmp_path):
    from rancf.sweep.engine import LocalExecutor, run_variants
    from rancf.sweep.spec import load_sweep

    base = {"geometry": LINE, "supports": [{"at": 0, "kind": "clamp"}]}
    loads = {"point": [{"at": -1, "force": [0.0, -1e-3]}]}
    (tmp_path / "c.toml").write_text(mutated(**base, loads=loads))
    (tmp_path / "w.toml").write_text(
        'base = "c.toml"\nanalysis = "static"\n[grid]\n"mesh.elements" = [2, 3]\n'
    )

    def sweep() -> dict:
        spec = load_sweep(tmp_path / "w.toml")
        out = tmp_path / "out"
        run_variants(LocalExecutor(), spec.variants(), spec.base, spec.analysis, out, False)
        return {p.parent.name: p.stat().st_mtime_ns for p in out.glob("runs/*/row.json")}

    first = sweep()
    assert sweep() == first  # nothing changed: nothing runs again
    (tmp_path / "c.toml").write_text(mutated(**base, loads=loads, material__density=3000.0))
    again = sweep()
    assert set(again) == set(first) and all(again[k] != first[k] for k in first)


def test_a_sweep_stopped_by_sigterm_is_quiet_and_truthful(tmp_path):
    (tmp_path / "s.toml").write_text(LONG.replace("t_end = 100.0", "t_end = 4.0"))
    grid = ", ".join(str(n) for n in range(10, 22))
    (tmp_path / "w.toml").write_text(f'base = "s.toml"\n[grid]\n"mesh.elements" = [{grid}]\n')
    p = subprocess.Popen(
        [*RANCF, "sweep", "w.toml", "--out", "sw", "--workers", "2", "--quiet"],
        cwd=tmp_path,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
        start_new_session=True,
    )
    deadline = time.monotonic() + 60
    while not list(tmp_path.glob("sw/runs/*/row.json")) and time.monotonic() < deadline:
        time.sleep(0.05)
    os.killpg(p.pid, signal.SIGTERM)  # the whole group: the workers get it too
    _, err = p.communicate(timeout=60)
    assert p.returncode == 130 and err.decode().strip() == "rancf: interrupted", err
    rows = (tmp_path / "sw/results.csv").read_text().splitlines()[1:]
    finished = {r.split(",")[0] for r in rows if ",pending," not in r}
    assert finished == {f.parent.name for f in tmp_path.glob("sw/runs/*/row.json")}
    assert finished and len(finished) < 12


def test_a_refused_process_never_removes_what_another_wrote(tmp_path):
    """A process that made the folder but lost the lock to another (a race of two starts)
    leaves the folder and the other's files alone."""
    from rancf.cli.io import OutputDir
    from rancf.errors import InputError

    with OutputDir(tmp_path / "new", kind="run") as first:
        (first.path / "summary.json").write_text("{}")
        second = OutputDir(tmp_path / "new", kind="run")
        second.created = tmp_path / "new"  # as if the second had made it a moment earlier
        with pytest.raises(InputError, match="no other rancf process"):
            second.__enter__()
        assert (tmp_path / "new/summary.json").is_file()
        first.keep()
    assert sorted(p.name for p in (tmp_path / "new").iterdir()) == ["summary.json"]


def _example(name: str) -> str:
    from importlib.resources import files

    return (files("rancf.examples") / f"{name}.toml").read_text(encoding="utf-8")


def _tether(law: str, extra: str = "") -> str:
    """tether-reel-out for 1 s with its winch's law replaced by ``law`` and ``extra`` added."""
    text = _example("tether-reel-out").replace("t_end = 20.0", "t_end = 1.0")
    i = text.index("length = { table")
    j = text.index("\n", i)
    return text[:i] + law + text[j:] + extra


_SECOND_WINCH = '\n[[winches]]\nname = "{name}"\nat = "tether:{end}"\nlength = 10.0\n'
_SENSORS = (
    '\n[[sensors]]\nname = "w"\nkind = "position"\nat = "weight"\n'
    '\n[[sensors]]\nname = "w_x"\nkind = "energy"\n'
)

_SHALLOW = """[geometry]
kind = "line"
start = [0.0, 0.0, -10.0]
end = [2.0, 0.0, 0.0]
[mesh]
elements = 3
[section]
radius = 0.01
[material]
density = 2000.0
youngs_modulus = 1e9
[[supports]]
at = "start"
[loads]
gravity = [0.0, 0.0, -9.81]
[fluid]
density = 1025.0
surface = 0.0
waves = { height = 2.0, period = 8.0, depth = 1e-9 }
[hydro]
diameter = 0.03
[solver]
t_end = 0.1
"""

#: Inputs that ran to a wrong answer with exit 0 (or a traceback), and what refuses them.
AMBIGUOUS = {
    "contact-twice": (
        'contacts = [["rope", "pulley"], ["rope", "pulley"]]\n' + _example("capstan"),
        "[contacts[1]] lists the pair ['rope', 'pulley'] again (contacts[0] has it",
    ),
    "body-contact-twice": (
        'body_contacts = [["leg1", "leg2"], ["leg2", "leg1"]]\n' + _example("argyris-frame"),
        "[body_contacts[1]] lists the pair ['leg1', 'leg2'] again",
    ),
    "same-column": (
        _example("capstan") + _SENSORS,
        "[sensors[4].name] 'w_x' gives the column 'w_x', as sensors[3] ('w', kind 'position') does",
    ),
    "same-winch-name": (
        _tether("length = 10.0", _SECOND_WINCH.format(name="reel", end="end")),
        "[winches[1].name] 'reel' is used twice (winches[0] has it)",
    ),
    "two-winches-one-end": (
        _tether("length = 10.0", _SECOND_WINCH.format(name="other", end="start")),
        "[winches[1].at] 'tether:start': body 'tether' already has a winch "
        "(winches[0]): one winch per body",
    ),
    "vector-length": (
        _tether("length = [10.0, 3.0]"),
        "[winches[0].length] must be a scalar time function (numbers, not "
        "vectors), got [10.0, 3.0]",
    ),
    "length-below-zero": (
        _tether("length = { table = [[0, 10.0], [0.5, 5.0], [1.0, -1.0]] }"),
        "[winches[0].length] the length outside the winch must stay > 0 m "
        "over the run (t = 0 to t_end = 1 s), but it is -0.004 m at "
        "t = 0.917 s",
    ),
    "speed-past-zero": (
        _tether("speed = -30.0"),
        "[winches[0].speed] the length outside the winch must stay > 0 m over "
        "the run (t = 0 to t_end = 1 s), but it is -0.005 m at t = 0.3335 s",
    ),
    "length-zero-at-the-start": (
        _tether("length = { ramp = 0.1, value = -1.0 }"),
        "[winches[0].length] the length outside the winch must stay > 0 "
        "m over the run (t = 0 to t_end = 1 s), but it is 0 m at t = 0 s",
    ),
    "winch-at-no-body": (
        _tether("length = 10.0").replace(
            'at = "tether:start"\nlength', 'at = "nobody:start"\nlength'
        ),
        "[winches[0].at] names no body: 'nobody' (bodies: tether, payload)",
    ),
    "sensor-of-no-winch": (
        _tether("length = 10.0").replace('winch = "reel"', 'winch = "nope"'),
        "[sensors[0].winch] names no winch: 'nope' (winches: reel)",
    ),
    "waves-depth": (
        _SHALLOW,
        "[fluid.waves.depth] must reach the bodies in the fluid: depth "
        "= 1e-09 m puts the floor at -1e-09 m, above body's node at -10 m (give "
        "depth >= 10 m)",
    ),
}


@pytest.mark.parametrize("case", list(AMBIGUOUS))
def test_ambiguous_inputs_are_refused_in_one_line(tmp_path, monkeypatch, capsys, case):
    """Ambiguous inputs: each refused on one line naming the file and the key, exit 2,
    nothing written."""
    text, needle = AMBIGUOUS[case]
    monkeypatch.chdir(tmp_path)
    Path("s.toml").write_text(text)
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and err.startswith("rancf: error: s.toml: ["), err
    assert needle in err, err
    assert not Path("run").exists()


def test_a_sweep_over_an_array_of_tables_is_refused_in_one_line(tmp_path, monkeypatch, capsys):
    """``"winches.speed"`` (``[[winches]]`` is an array of tables) is one line, not a TypeError
    traceback."""
    monkeypatch.chdir(tmp_path)
    Path("base.toml").write_text(_tether("speed = 0.5"))
    Path("sw.toml").write_text('base = "base.toml"\n[grid]\n"winches.speed" = [0.5, 1.0]\n')
    assert main(["sweep", "sw.toml", "--out", "out", "--threads", "1", "--quiet"]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith(
        "rancf: error: sw.toml: [grid.winches.speed] 'winches' is an array of "
        "tables ([[winches]]) in the base scenario, not a table"
    ), err
    assert not Path("out").exists()


_GUIDE = """[[bodies]]
name = "rope"
[bodies.geometry]
kind = "line"
start = [0.0, 0.0]
end = [0.0, -0.5]
[bodies.mesh]
elements = 10
element = "ancf"
[bodies.section]
radius = 0.002
[bodies.material]
density = 1000.0
youngs_modulus = 1.0e9

[[bodies]]
name = "weight"
kind = "mass"
mass = 1.0
position = [0.0, -0.5]

[[joints]]
name = "hook"
kind = "pin"
between = ["rope:end", "weight"]

[[joints]]
name = "eye"
kind = "sliding"
between = ["rope", "ground"]
position = [0.0, -0.05]

[loads]
gravity = [0.0, -9.81]

[solver]
t_end = 0.2
step = 2.0e-3
output_step = 0.01

[[sensors]]
name = "eye"
kind = "reaction"
joint = "eye"
"""

#: Runs that went past a coordinate's range: the file, the column that must
#: stay in range, and the failure's line (a pattern).
PAST_LIMITS = {
    "drum-reels-in-the-line": (
        _example("drum-hoist").replace(
            "[0.05, 33.368], [10.0, 33.368]", "[0.05, 80.0], [10.0, 80.0]"
        ),
        "drum_length",
        r"rancf: simulation failed: winch 'hoist': the length outside the drum is -0\.0\d+ m "
        r"at t = 0\.99 s, not > 0 \(the drum has reeled in the whole line\); the run stops at "
        r"the step before \(written to run\)",
    ),
    "rope-through-its-guide": (
        _GUIDE,
        "eye_s",
        r"rancf: simulation failed: sliding joint 'eye': the start of body 'rope' passes through "
        r"its place at t = 0\.102 s \(material coordinate -0\.0\d+ of 0\.\.10 elements\); the "
        r"run stops at the step before \(make the body longer\) \(written to run\)",
    ),
}


@pytest.mark.parametrize("case", list(PAST_LIMITS))
def test_a_run_stops_where_a_coordinate_leaves_its_range(tmp_path, monkeypatch, capsys, case):
    """Exit 3 at the step before the length or the guide's place leaves its range, with one
    line naming the winch or joint, the time and the value; nothing stored past it."""
    text, column, line = PAST_LIMITS[case]
    monkeypatch.chdir(tmp_path)
    Path("s.toml").write_text(text)
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 3
    err = capsys.readouterr().err.strip()
    assert re.fullmatch(line, err.splitlines()[-1]), err
    with open("run/sensors.csv") as fh:
        rows = list(csv.DictReader(fh))
    assert all(float(r[column]) >= 0.0 for r in rows), [r[column] for r in rows]
    summary = _strict(Path("run/summary.json").read_text())
    assert summary["status"] == "failed" and summary["message"] in err
    assert summary["t_reached"] == float(rows[-1]["t"])
