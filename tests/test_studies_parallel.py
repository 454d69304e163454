"""`rancf report` on every core: the relay between study drivers and the report's cluster, and
the same tables as the sequential run."""

from __future__ import annotations

import csv
import multiprocessing
import subprocess
import sys
import threading
from pathlib import Path

import pytest

from rancf.studies.parallel import RelayExecutor, _serve
from rancf.sweep.engine import dask_client


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


def _tables(folder: Path) -> dict[str, list[list[str]]]:
    """Every study table of a report folder, without its wall-time columns."""
    out = {}
    for f in sorted(folder.rglob("*.csv")):
        rel = f.relative_to(folder)
        if any(part.startswith("sweep") for part in rel.parts):
            continue  # run folders and the sweeps' own results.csv (statuses of cancelled runs)
        rows = list(csv.reader(f.open(encoding="utf-8")))
        keep = [i for i, h in enumerate(rows[0]) if "time" not in h.lower()]
        out[str(rel)] = [[r[i] for i in keep if i < len(r)] for r in rows]
    return out


def test_parallel_report_has_the_sequential_tables(tmp_path):
    argv = [sys.executable, "-m", "rancf", "report", "--quick"]
    seq, par = tmp_path / "seq", tmp_path / "par"
    for out, workers in ((seq, "1"), (par, "2")):
        done = subprocess.run(
            [*argv, "--out", str(out), "--workers", workers], capture_output=True, text=True
        )
        assert done.returncode == 0, done.stderr[-2000:]
    assert "on a local Dask cluster of 2 worker(s)" in done.stderr
    a, b = _tables(seq), _tables(par)
    assert len(a) >= 10 and a.keys() == b.keys()
    for name in a:
        assert a[name] == b[name], name
