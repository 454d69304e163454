"""rancf sweep on a local Dask cluster and on a separately started scheduler + worker."""

import csv
import json
import socket
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.errors import ScenarioError
from rancf.sweep.spec import load_sweep
from tests.numbers import assert_rows_match
from tests.scenario.test_scenario import BASE

SWEEP = """
base = "pend.toml"
analysis = "simulate"
[grid]
"mesh.elements" = [2, 3]
"solver.max_newton" = [12, 1]
"""
TIMES = ("wall_time_s", "solve_time_s")


def _write(d: Path) -> Path:
    # 5 steps of 1 ms; max_newton = 1 with min_step = step cannot converge: two failed runs
    (d / "pend.toml").write_text(
        BASE.replace(
            "t_end = 0.02\nstep = 1.0e-3", "t_end = 0.005\nstep = 1.0e-3\nmin_step = 1.0e-3"
        )
    )
    (d / "sweep.toml").write_text(SWEEP)
    return d / "sweep.toml"


def _rows(path: Path) -> list[dict]:
    with open(path) as fh:
        return [{k: v for k, v in r.items() if k not in TIMES} for r in csv.DictReader(fh)]


@pytest.fixture(scope="module")
def local_sweep(tmp_path_factory):
    d = tmp_path_factory.mktemp("sweep")
    f = _write(d)
    assert main(["sweep", str(f), "--out", str(d / "out"), "--workers", "2", "--quiet"]) == 0
    return d


def test_local_cluster_rows_and_failures(local_sweep, capsys):
    rows = _rows(local_sweep / "out" / "results.csv")
    assert [r["run"] for r in rows] == [
        "0000_elements=2_max_newton=12",
        "0001_elements=2_max_newton=1",
        "0002_elements=3_max_newton=12",
        "0003_elements=3_max_newton=1",
    ]
    assert [r["status"] for r in rows] == ["completed", "failed"] * 2
    assert "Newton" in rows[1]["message"] and rows[1]["AB"] != ""  # state up to the failure
    assert float(rows[0]["t_reached"]) == pytest.approx(0.005)
    for r in rows:
        assert (local_sweep / "out" / "runs" / r["run"] / "row.json").is_file()
    # same numbers as `rancf simulate` of the same variant
    sc = local_sweep / "out" / "runs" / rows[2]["run"] / "scenario.toml"
    assert main(["simulate", str(sc), "--out", str(local_sweep / "single"), "--quiet"]) == 0
    last = (local_sweep / "single" / "sensors.csv").read_text().splitlines()[-1].split(",")
    assert float(last[1]) == pytest.approx(float(rows[2]["AB"]), rel=1e-11)


def test_resume_skips_finished_runs(local_sweep, capsys):
    out = local_sweep / "out"
    before = _rows(out / "results.csv")
    gone = out / "runs" / before[3]["run"] / "row.json"
    gone.unlink()  # as if the sweep had been interrupted before this run finished
    stamp = (out / "runs" / before[0]["run"] / "row.json").stat().st_mtime_ns
    argv = ["sweep", str(local_sweep / "sweep.toml"), "--out", str(out), "--workers", "1"]
    assert main([*argv, "--quiet"]) == 0
    assert "4 run(s): 3 already finished, 1 run on" in capsys.readouterr().out
    assert (out / "runs" / before[0]["run"] / "row.json").stat().st_mtime_ns == stamp
    assert gone.is_file()
    assert_rows_match(_rows(out / "results.csv"), before, rtol=1e-12)  # run 3 ran again here


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_separate_scheduler_gives_identical_values(local_sweep, tmp_path):
    dask = str(Path(sys.executable).parent / "dask")
    port = _free_port()
    addr = f"tcp://127.0.0.1:{port}"
    sched = subprocess.Popen(
        [dask, "scheduler", "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
    )
    worker = None
    try:
        worker = subprocess.Popen(
            [
                dask,
                "worker",
                addr,
                "--host",
                "127.0.0.1",
                "--nthreads",
                "1",
                "--nworkers",
                "1",
                "--no-dashboard",
            ],
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        from dask.distributed import Client

        deadline = time.monotonic() + 60
        while True:
            try:
                with Client(addr, timeout=5) as c:
                    c.wait_for_workers(1, timeout=60)
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.5)
        f = _write(tmp_path)
        out = tmp_path / "out"
        assert main(["sweep", str(f), "--out", str(out), "--scheduler", addr, "--quiet"]) == 0
    finally:
        for p in (worker, sched):
            if p is not None:
                p.terminate()
                p.wait(timeout=30)
    # the same numbers from another process (round-off aside: a stated tolerance)
    assert_rows_match(
        _rows(out / "results.csv"), _rows(local_sweep / "out" / "results.csv"), rtol=1e-12
    )


def test_several_runs_per_task_on_worker_threads(local_sweep, tmp_path):
    # the report's cluster: worker threads, consecutive runs as one task; same rows, and a task
    # none of whose runs is needed any more is cancelled unless it started already (both or none)
    from rancf.sweep.cluster import dask_client
    from rancf.sweep.engine import DaskExecutor, run_variants

    spec = load_sweep(_write(tmp_path))
    variants = spec.variants()
    seen = []

    def on_row(name, row):
        seen.append(name)
        return [v.name for v in variants[2:]]  # the second task (runs 2 and 3) is not needed

    with dask_client(None, 1, processes=False) as client:
        ex = DaskExecutor(client, runs_per_task=2)
        run_variants(ex, variants, spec.base, "simulate", tmp_path / "out", False, on_row)
    rows = _rows(tmp_path / "out" / "results.csv")
    assert seen[:2] == [v.name for v in variants[:2]]
    full = _rows(local_sweep / "out" / "results.csv")
    assert_rows_match(rows[:2], full[:2], rtol=1e-12)
    pending = [{**r, "status": "pending", "message": ""} for r in rows[2:]]
    if rows[2:] != pending:  # both runs of the second task ran after all
        assert_rows_match(rows[2:], full[2:], rtol=1e-12)
    with pytest.raises(ValueError, match="runs_per_task"):
        DaskExecutor(client, runs_per_task=0)


def test_bad_sweep_files_name_the_key(tmp_path):
    f = _write(tmp_path)
    f.write_text(SWEEP.replace('"mesh.elements"', '"mesh.elemnts"'))
    with pytest.raises(ScenarioError, match=r"grid \(run 0000_elemnts=2.*mesh.elemnts"):
        load_sweep(f)
    f.write_text(SWEEP.replace('"simulate"', '"dynamics"'))
    with pytest.raises(ScenarioError, match=r"\[analysis\] must be one of"):
        load_sweep(f)
    f.write_text(SWEEP.replace("[2, 3]", "[]"))
    with pytest.raises(ScenarioError, match=r"grid.mesh.elements\] must be a non-empty list"):
        load_sweep(f)


def test_static_and_modes_sweeps(tmp_path):
    (tmp_path / "cant.toml").write_text(
        __import__("tests.test_cli_sim", fromlist=["CANTILEVER"]).CANTILEVER
    )
    for analysis, col in (("static", "tip_y"), ("modes", "f1_hz")):
        f = tmp_path / f"{analysis}.toml"
        f.write_text(
            f'base = "cant.toml"\nanalysis = "{analysis}"\n[grid]\n"mesh.elements" = [2, 4]\n'
        )
        out = tmp_path / analysis
        assert main(["sweep", str(f), "--out", str(out), "--workers", "1", "--quiet"]) == 0
        rows = _rows(out / "results.csv")
        assert [r["status"] for r in rows] == ["completed"] * 2 and rows[1][col] != ""
    # a static run's folder is also a run directory of its load path (export, plot, animate)
    from rancf.post.system_run import load_run

    run = load_run(next((tmp_path / "static" / "runs").iterdir()))
    assert run.static and run.t[0] == 0.0 and run.t[-1] == 1.0


def test_static_sweep_of_a_system_file(tmp_path):
    """A file of several bodies and a joint sweeps like a one-body file: the Argyris frame's
    static equilibrium in 4 and in 8 load steps is the same state."""
    from rancf.studies.common import example_path

    (tmp_path / "frame.toml").write_text(example_path("argyris-frame").read_text())
    spec = tmp_path / "s.toml"
    spec.write_text(
        'base = "frame.toml"\nanalysis = "static"\n[grid]\n"solver.load_steps" = [4, 8]\n'
    )
    out = tmp_path / "out"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1", "--quiet"]) == 0
    rows = _rows(out / "results.csv")
    assert [r["status"] for r in rows] == ["completed"] * 2, rows
    runs = sorted((out / "runs").iterdir())
    docs = [json.loads((r / "static.json").read_text()) for r in runs]
    assert set(docs[0]["positions"]) == {"leg1", "leg2"}
    tip = [np.array([d["sensors"][f"tip_{c}"] for c in "xyz"]) for d in docs]
    assert tip[0][0] > 0.24 and np.linalg.norm(tip[0] - tip[1]) < 1e-8


POWER_LINE = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [325.0, 0.0]
[mesh]
elements = 16
[section]
area = 2.2783e-4
inertia = 4.1306e-9
[material]
density = 2844.23
youngs_modulus = 5.7e10
[[supports]]
at = "start"
[[supports]]
at = "end"
[loads]
gravity = [0.0, -9.81]
[modes]
about = "static"
count = 3
"""


def test_warned_runs_say_so_in_the_table(tmp_path, capsys):
    """A run that completes with a warning (here a section radius of 0.3 m on a 0.5 m body: a
    unit mistake) carries that warning into its row of ``results.csv`` and ``row.json``, and
    the summary line counts it; a run without warnings has an empty cell."""
    (tmp_path / "cant.toml").write_text(
        __import__("tests.test_cli_sim", fromlist=["CANTILEVER"]).CANTILEVER
    )
    for analysis in ("static", "modes"):
        f = tmp_path / f"{analysis}.toml"
        f.write_text(
            f'base = "cant.toml"\nanalysis = "{analysis}"\n[grid]\n"section.radius" = [0.03, 0.3]\n'
        )
        out = tmp_path / analysis
        assert main(["sweep", str(f), "--out", str(out), "--threads", "1"]) == 0
        assert "0 failed, 1 with warnings (its column) ->" in capsys.readouterr().out
        rows = _rows(out / "results.csv")
        assert [r["status"] for r in rows] == ["completed"] * 2
        assert rows[0]["warnings"] == ""
        assert "section's radius 0.3 m" in rows[1]["warnings"]
        row = json.loads((out / "runs" / rows[1]["run"] / "row.json").read_text())
        assert any("section.radius" in w for w in row["warnings"])
