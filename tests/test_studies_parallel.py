"""`rancf report` on every core: the relay between study drivers and the report's cluster, and
the same tables as the sequential run."""

from __future__ import annotations

import json
import multiprocessing
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest

from rancf.studies.parallel import RelayExecutor, _serve
from rancf.sweep.cluster import dask_client


@pytest.fixture
def relay():
    """A driver-side RelayExecutor wired to a cluster-side server thread."""
    here, there = multiprocessing.Pipe()
    with dask_client(None, 1, processes=False) as client:
        server = threading.Thread(target=_serve, args=(there, client, 1, 2), daemon=True)
        server.start()
        yield RelayExecutor(here), server


def test_relay_runs_every_call_and_passes_answers_back(relay, tmp_path):
    executor, server = relay
    calls = [(n, (n, {}, "base.toml", "simulate", str(tmp_path / n))) for n in ("a", "b", "c")]
    seen = []

    def on_done(name, row):
        seen.append((name, row["status"]))
        return ["c"] if name == "a" else []

    executor.execute(calls, on_done)
    # a and b run in one task (2 runs a task); c, a task of its own, may have been cancelled
    assert ("a", "failed") in seen and ("b", "failed") in seen
    assert {n for n, _ in seen} <= {"a", "b", "c"}
    executor.execute(calls[:1], on_done)  # the same server takes a second grid
    assert seen[-1] == ("a", "failed")
    executor.close()
    server.join(timeout=10)
    assert not server.is_alive()


def test_relay_stops_a_grid_whose_callback_raises(relay, tmp_path):
    executor, server = relay
    calls = [(n, (n, {}, "base.toml", "simulate", str(tmp_path / n))) for n in ("a", "b")]

    def on_done(name, row):
        raise ValueError("driver-side failure")

    with pytest.raises(ValueError, match="driver-side failure"):
        executor.execute(calls, on_done)
    seen = []
    executor.execute(calls, lambda name, row: seen.append(name) or [])  # the server goes on
    assert sorted(seen) == ["a", "b"]
    executor.close()
    server.join(timeout=10)
    assert not server.is_alive()


def test_parallel_report_has_the_sequential_tables(tmp_path):
    # the benchmark's own pair: `report --quick` with 1 and with 2 workers, tables compared
    bench = Path(__file__).resolve().parents[1] / "benchmarks" / "report_ratio.py"
    done = subprocess.run(
        [sys.executable, str(bench), "--quick", "--pairs", "1", "--out", str(tmp_path)],
        capture_output=True,
        text=True,
        timeout=600,
    )
    assert done.returncode == 0, done.stdout + done.stderr[-2000:]
    data = json.loads((tmp_path / "report_ratio.json").read_text())
    (pair,) = data["pairs"]
    assert pair["tables"] >= 10 and pair["tables_identical"] and data["all_tables_identical"]
    assert pair["workers_2"]["printed_s"] > 0 and pair["workers_1"]["cpu_s"] > 0


def test_study_tables_drop_times_and_sweeps(tmp_path):
    from rancf.studies.report import study_tables

    (tmp_path / "a" / "sweep").mkdir(parents=True)
    (tmp_path / "a" / "t.csv").write_text("n,error,wall time [s]\n1,0.5,0.01\n")
    (tmp_path / "a" / "sweep" / "results.csv").write_text("run,status\nx,failed\n")
    assert study_tables(tmp_path) == {"a/t.csv": [["n", "error"], ["1", "0.5"]]}


@pytest.mark.parametrize("workers", [1, 2])
def test_an_interrupted_report_keeps_the_finished_studies(tmp_path, monkeypatch, workers):
    # the second study is interrupted (Ctrl-C): the first's files and a partial report stay
    import rancf.studies.parallel as parallel
    from rancf.cli import main
    from rancf.studies.common import StudyResult

    def runner(name):
        def run(out, quick, executor=None):
            if name == "spatial-pendulum":
                # interrupted once the planar study has finished (in a driver of its own with
                # 2 workers: wait for its result to have reached the report process)
                done = out.parent / "planar-pendulum" / "table.csv"
                for _ in range(500):
                    if done.exists():
                        break
                    time.sleep(0.01)
                time.sleep(0.5)
                raise KeyboardInterrupt
            out.mkdir(parents=True, exist_ok=True)
            (out / "table.csv").write_text("x\n1\n")
            return StudyResult(name, f"the {name} study").finish()

        return run

    monkeypatch.setattr(parallel, "study_runner", runner)
    monkeypatch.setattr(parallel, "runs_a_grid", lambda name: False)  # drivers only, no cluster
    out = tmp_path / "rep"
    assert main(["report", "--quick", "--out", str(out), "--workers", str(workers)]) == 130
    doc = json.loads((out / "report.json").read_text())
    assert doc["complete"] is False and "spatial-pendulum" in doc["unfinished"]
    assert "planar-pendulum" in doc["studies"] and (out / "planar-pendulum" / "table.csv").exists()
    assert "Incomplete report" in (out / "report.html").read_text()
