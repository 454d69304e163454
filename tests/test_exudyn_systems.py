"""Exudyn's peers of the shipped systems run and reproduce their numbers on coarse settings.

``benchmarks/exudyn_spinup.py`` and ``benchmarks/exudyn_slider_crank.py`` as a user runs them (one
JSON line each); skipped without Exudyn (``pip install .[bench]``).  Coarse: 8 elements and
h = 0.01 s for 5 s of the spin-up, 4 elements and h = 1e-4 s for 0.05 s of the slider-crank;
the converged values are in the scripts' docstrings.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]


def run(script: str, *args: str) -> dict:
    pytest.importorskip("exudyn")
    p = subprocess.run(
        [sys.executable, "-W", "error::DeprecationWarning", str(ROOT / "benchmarks" / script)]
        + list(args),
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 0, p.stderr[-3000:]
    lines = p.stdout.strip().splitlines()
    assert len(lines) == 1, p.stdout
    return json.loads(lines[0])


def test_spin_up_first_five_seconds():
    args = ("--elements", "8", "--step", "0.01", "--t-end", "5")
    out = run("exudyn_spinup.py", *args)
    assert out["converged"] and out["steps"] == 500 and out["t_end"] == pytest.approx(5.0)
    assert out["setup_s"] > 0 and out["solve_s"] > 0 and out["user_functions"] == "symbolic"
    # converged reference: v(5 s) = -0.46844 m; 8 elements and h = 0.01 s are 5e-5 m off
    assert out["v_5"] == pytest.approx(-0.46844, rel=2e-4)
    assert out["v_10"] is None
    # the hub driven by Python callbacks instead of Exudyn's symbolic functions: the same run
    python = run("exudyn_spinup.py", *args, "--user-functions", "python")
    assert python["v_5"] == pytest.approx(out["v_5"], rel=1e-12)


def test_slider_crank_first_revolutions():
    out = run("exudyn_slider_crank.py", "--elements", "4", "--step", "1e-4", "--t-end", "0.05")
    assert out["converged"] and out["steps"] == 500 and out["times"] == [0.05]
    # converged reference: slider x = 0.164394 m, midpoint deflection -4.779e-4 m at 0.05 s
    assert out["slider_x"][0] == pytest.approx(0.164394, abs=1e-6)
    assert out["deflection"][0] == pytest.approx(-4.779e-4, rel=2e-3)


def test_slider_crank_needs_a_midpoint_node():
    pytest.importorskip("exudyn")
    p = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "exudyn_slider_crank.py"), "--elements", "3"],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert p.returncode == 2 and "--elements 3: an even number" in p.stderr
