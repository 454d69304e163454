"""``rancf simulate`` asks OpenBLAS for one thread unless told otherwise
(:func:`rancf.cli.sim.one_blas_thread`): set before NumPy is loaded, a value of the user's kept,
nothing changed once NumPy is loaded."""

from __future__ import annotations

import os
import subprocess
import sys

import pytest

CODE = """
import os, sys
{pre}
from rancf.cli.sim import one_blas_thread
assert "numpy" not in sys.modules or {pre!r}
one_blas_thread()
print(os.environ.get("OPENBLAS_NUM_THREADS"))
"""


@pytest.mark.parametrize(
    ("pre", "env", "expected"),
    [("", None, "1"), ("", "3", "3"), ("import numpy", None, "None")],
)
def test_one_blas_thread(pre: str, env: str | None, expected: str) -> None:
    environ = {k: v for k, v in os.environ.items() if k != "OPENBLAS_NUM_THREADS"}
    if env is not None:
        environ["OPENBLAS_NUM_THREADS"] = env
    p = subprocess.run(
        [sys.executable, "-c", CODE.format(pre=pre)],
        env=environ,
        capture_output=True,
        text=True,
        check=True,
    )
    assert p.stdout.strip() == expected


@pytest.mark.parametrize("command", ["simulate", "sweep"])
def test_the_run_commands_ask_for_one_blas_thread(command, tmp_path, monkeypatch):
    """``simulate`` and ``sweep`` call it first (before the scenario is read: here a missing
    file, refused after)."""
    import rancf.cli.sim as sim
    from rancf.cli import main

    calls = []
    monkeypatch.setattr(sim, "one_blas_thread", lambda: calls.append(command))
    args = [command, str(tmp_path / "missing.toml"), "--out", str(tmp_path / "out")]
    assert main(args) == 2
    assert calls == [command]
