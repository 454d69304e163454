"""Ensembles on threads of one process: the same numbers as the runs alone."""

from __future__ import annotations

import numpy as np
import pytest

from rancf.bodies.flexible import Material, Model, Section, Support
from rancf.cli import main
from rancf.errors import InputError
from rancf.mesh.factories import mesh_line
from rancf.solvers.dynamic import DynamicOptions, integrate
from rancf.sweep.threads import run_ensemble
from rancf.system import as_system
from tests.sweep.test_sweep import _rows, _write


def _pendulum(youngs: float):
    model = Model(
        mesh_line([0.0, 0.0], [1.2, 0.0], 8),
        "ancf",
        Section.circular(0.02),
        Material(6000.0, youngs),
        [Support(0, "pin")],
        gravity=[0.0, -9.81],
    )
    return as_system(model)


def test_an_ensemble_on_threads_gives_each_run_alone():
    """Eight pendulums of different stiffness on two threads: every state at every output equals
    that of the same run alone to 1e-12 of the size (each run has its own compiled model), and
    the stiffness matters (the runs differ)."""
    youngs = np.geomspace(1e7, 1e9, 8)
    opts = DynamicOptions(t_end=0.05, step=1e-3)
    alone = [integrate(_pendulum(e), opts) for e in youngs]
    together = run_ensemble([_pendulum(e) for e in youngs], opts, threads=2)
    for a, b in zip(alone, together, strict=True):
        assert b.status == a.status and b.n_steps == a.n_steps
        assert np.abs(b.q - a.q).max() <= 1e-12 * 1.2
        assert np.abs(b.v - a.v).max() <= 1e-12 * np.abs(a.v).max()
    assert np.abs(alone[0].q[-1] - alone[-1].q[-1]).max() > 1e-6


def test_an_ensemble_refuses_a_system_twice_and_bad_threads():
    s = _pendulum(1e8)
    opts = DynamicOptions(t_end=0.002, step=1e-3)
    with pytest.raises(InputError, match="systems"):
        run_ensemble([s, s], opts)
    with pytest.raises(InputError, match="threads"):
        run_ensemble([s], opts, threads=0)
    with pytest.raises(InputError, match="options"):
        run_ensemble([s], [opts, opts])


def test_sweep_on_threads_gives_the_rows_of_one_process(tmp_path):
    """``rancf sweep --threads 2`` writes the rows (failed runs included) of the same sweep
    run one after another in this process (``--threads 1``)."""
    f = _write(tmp_path)
    for k in (1, 2):
        argv = ["sweep", str(f), "--out", str(tmp_path / f"t{k}"), "--threads", str(k), "--quiet"]
        assert main(argv) == 0
    one, two = (_rows(tmp_path / f"t{k}" / "results.csv") for k in (1, 2))
    assert one == two and [r["status"] for r in two] == ["completed", "failed"] * 2
    assert main(["sweep", str(f), "--out", str(tmp_path / "x"), "--threads", "0"]) == 2
