"""Rows derived beside the time loop (:mod:`rancf.post.block_worker`): the same files as rows
derived between the steps, errors handed to the caller, and no worker where the steps change
what the rows read (rods' triads, contact)."""

from __future__ import annotations

import threading
from importlib import resources

import numpy as np
import pytest

from rancf.cli import main
from rancf.post.block_worker import BlockWorker, works_beside
from rancf.post.history import HistoryStore
from rancf.scenario import load_scenario
from rancf.system.outputs import SystemOutputs
from tests.test_cli_errors import mutated


def _arrays(folder) -> dict[str, np.ndarray]:
    out = {}
    for f in ("results.npz", "bodies/body/results.npz"):
        with np.load(folder / f) as z:
            out.update({f"{f}:{k}": z[k] for k in z.files})
    return out


def test_a_run_with_the_worker_writes_the_same_files(tmp_path, monkeypatch):
    """A line stored every step in blocks of 16 rows (many hand-overs while the loop runs):
    every array of both results files equals, bit for bit, the run that derives each block
    between the steps; the CSV files are the same text."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(solver__t_end=0.2, mesh__elements=16))
    init = HistoryStore.__init__
    seen = []

    def small(beside: bool):  # noqa: ANN202
        def wrapped(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
            n_q = args[1].n_q  # HistoryStore(out, outputs, info): 16 rows a buffer
            kwargs.update(buffer_bytes=16 * (16 * n_q + 32), beside=beside)
            init(self, *args, **kwargs)
            seen.append(self._worker is not None)

        return wrapped

    runs = {}
    for beside in (True, False):
        monkeypatch.setattr(HistoryStore, "__init__", small(beside))
        out = tmp_path / f"run-{beside}"
        assert main(["simulate", "s.toml", "--out", str(out), "--quiet"]) == 0
        runs[beside] = out
    assert seen == [True, False]
    a, b = _arrays(runs[True]), _arrays(runs[False])
    assert a.keys() == b.keys() and a["results.npz:t"].size > 100
    for key in a:
        np.testing.assert_array_equal(a[key], b[key], err_msg=key)
    for name in ("sensors.csv", "energy.csv", "reactions.csv", "bodies/body/envelope.csv"):
        assert (runs[True] / name).read_text() == (runs[False] / name).read_text(), name


def test_the_worker_runs_jobs_in_order_and_hands_back_errors():
    """Each job starts after the one before ended (on another thread); an error is raised by
    the next submit or wait, once."""
    worker, done, threads = BlockWorker(), [], set()

    def job(i: int) -> None:
        threads.add(threading.get_ident())
        done.append(i)

    for i in range(5):
        worker.submit(job, i)
    worker.wait()
    assert done == [0, 1, 2, 3, 4] and threading.get_ident() not in threads

    def fails() -> None:
        raise OSError(28, "No space left on device", "q.f64")

    worker.submit(fails)
    with pytest.raises(OSError, match="No space left"):
        worker.wait()
    worker.wait()  # raised once
    worker.submit(fails)
    with pytest.raises(OSError, match="No space left"):
        worker.submit(job, 5)  # the error before the next job
    assert done[-1] == 4


@pytest.mark.parametrize(
    ("name", "beside"),
    [("cantilever", True), ("slider-crank", True), ("argyris-frame", False), ("belt-drive", False)],
)
def test_no_worker_where_the_steps_change_what_rows_read(name, beside):
    """Rods (their triads follow the steps) and contact (its state) keep deriving between the
    steps."""
    with resources.as_file(resources.files("rancf.examples") / f"{name}.toml") as p:
        system = load_scenario(p).build_system()
    assert works_beside(SystemOutputs(system)) is beside


def test_the_loop_time_counts_every_stored_row(tmp_path, monkeypatch):
    """``solve_wall_time_s`` is taken after every stored row is derived and appended: when
    :func:`~rancf.solvers.dynamic.integrate` returns, the store holds them all (none left in
    its buffer for the last checkpoint: the store's ``flush``), with the worker and without it."""
    import rancf.runs.simulate as driver  # the dynamics driver rancf simulate runs

    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(solver__t_end=0.05, mesh__elements=8))
    integrate, seen = driver.integrate, []

    def watched(*args, **kwargs):  # noqa: ANN002, ANN003, ANN202
        result = integrate(*args, **kwargs)
        sink = args[4]  # integrate(model, options, on_output, should_stop, sink, ...)
        seen.append((sink.n_rows, sink._pending, result.n_outputs))
        return result

    monkeypatch.setattr(driver, "integrate", watched)
    init = HistoryStore.__init__
    for beside in (True, False):

        def big(self, *a, _beside=beside, **kw):  # noqa: ANN001, ANN002, ANN003, ANN202
            init(self, *a, **{**kw, "buffer_bytes": 1 << 26, "beside": _beside})

        monkeypatch.setattr(HistoryStore, "__init__", big)
        out = tmp_path / f"run-{beside}"
        assert main(["simulate", "s.toml", "--out", str(out), "--quiet"]) == 0
        monkeypatch.setattr(HistoryStore, "__init__", init)
    assert len(seen) == 2
    for rows, pending, stored in seen:
        assert pending == 0 and rows == stored == 51


def test_a_worker_hands_over_small_blocks(tmp_path, monkeypatch):
    """With the worker a block is at most :data:`~rancf.post.history.WORKER_BLOCK_BYTES` and
    :data:`~rancf.post.history.WORKER_BLOCK_ROWS` rows, so that the last block, which the loop
    waits for, is short and a small model's rows too are derived beside the loop: a run of
    201 rows of 8 elements is handed over as the first row (the first checkpoint, before the
    first step), three full blocks of 64 and the rest (two idle cores: the loop's and the
    worker's)."""
    from rancf.post import history

    assert history.WORKER_BLOCK_BYTES <= 1 << 20 and history.WORKER_BLOCK_ROWS <= 128
    import rancf.solvers.dynamic as dynamic

    monkeypatch.setattr(history, "WORKER_BLOCK_ROWS", 64)
    monkeypatch.setattr(dynamic, "CALL_TARGET_SECONDS", 1e-12)  # calls of 2 rows (1 %)
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(solver__t_end=0.2, mesh__elements=8))
    sizes = []
    submit = BlockWorker.submit

    def counted(self, job, rows, alpha, k):  # noqa: ANN001, ANN202
        sizes.append(k)
        submit(self, job, rows, alpha, k)

    monkeypatch.setattr(BlockWorker, "submit", counted)
    monkeypatch.setattr("rancf.cli.sim.idle_cores", lambda: 2)
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    assert sizes == [1, 64, 64, 64, 8]


@pytest.mark.parametrize("idle", [0, 1])
def test_without_a_core_of_its_own_no_worker(tmp_path, monkeypatch, idle):
    """With fewer than two idle cores (the loop's and the worker's) `rancf simulate` derives
    the rows between the steps: no worker thread, nothing handed over."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "s.toml").write_text(mutated(solver__t_end=0.05, mesh__elements=8))
    handed, stores = [], []
    monkeypatch.setattr(BlockWorker, "submit", lambda self, *a: handed.append(a))
    init = HistoryStore.__init__

    def seen(self, *args, **kwargs):  # noqa: ANN001, ANN002, ANN003, ANN202
        init(self, *args, **kwargs)
        stores.append(self._worker)

    monkeypatch.setattr(HistoryStore, "__init__", seen)
    monkeypatch.setattr("rancf.cli.sim.idle_cores", lambda: idle)
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    assert stores == [None] and handed == []
    with np.load(tmp_path / "run" / "results.npz") as z:
        assert z["t"].size == 51 and np.isfinite(z["a"]).all()


def test_energies_derived_from_the_rows_equal_the_loops(tmp_path, monkeypatch):
    """A run folder's energies, derived from the stored rows by the store (not in the time
    loop), equal those the loop computes for the same run kept in memory (1e-12 of the
    largest), row by row; a rod's stay in the loop (its triads are not in the rows)."""
    from rancf.scenario.system_build import build_system
    from rancf.solvers.dynamic import integrate

    monkeypatch.chdir(tmp_path)
    text = mutated(solver__t_end=0.1, mesh__elements=12)
    (tmp_path / "s.toml").write_text(text)
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 0
    sc = load_scenario(tmp_path / "s.toml")
    mem = integrate(build_system(sc), sc.dynamic_options())
    with np.load(tmp_path / "run" / "results.npz") as z:
        for key in ("kinetic", "strain", "gravity"):
            loop, rows = getattr(mem, key), z[key]
            assert rows.shape == loop.shape and rows.size > 50
            scale = np.abs(loop).max()
            assert scale > 0 and np.abs(rows - loop).max() <= 1e-12 * scale, key
    from rancf.post.run_plan import plan_run

    (tmp_path / "x").mkdir()
    store = HistoryStore(tmp_path / "x", plan_run(sc, 1.0)[1], {})
    assert store.derives_energies
    store.discard()
