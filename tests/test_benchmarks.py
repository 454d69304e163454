"""The benchmark runner works (quick mode; Exudyn cases only where Exudyn is installed)."""

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_benchmark_runner_quick(tmp_path):
    p = subprocess.run(
        [
            sys.executable,
            str(ROOT / "benchmarks" / "run.py"),
            "--quick",
            "--repeats",
            "1",
            "--out",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    )
    assert "simulate pendulum 8 el" in p.stdout
    data = json.loads((tmp_path / "bench.json").read_text())
    rows = {r["case"]: r for r in data["rows"]}
    full_row = rows["simulate pendulum 8 el (full Newton, output every 0.01 s)"]
    assert full_row["rancf_us_per_step"] > 0
    assert full_row["rancf_process_s"] > full_row["rancf_us_per_step"] * 1e-6 * full_row["steps"]
    assert (tmp_path / "bench.csv").read_text().startswith("case,")
    # speed never changes the answer: full and chord (the default) Newton give the same tip
    full = full_row["rancf_tip"]
    chord = rows["simulate pendulum 8 el (default Newton, output every 0.01 s)"]["rancf_tip"]
    assert abs(full[0] - chord[0]) < 1e-8 and abs(full[1] - chord[1]) < 1e-8
    every = rows["simulate pendulum 8 el (default Newton, output every step)"]
    assert every["rancf_tip"] == chord  # outputs do not change the run
    # contact: the cable on the ground against the same cable hanging free
    ground = rows["contact: ground 100 el: lying vs hanging (B: hanging)"]
    assert ground["rancf_us_per_step"] > 0 and ground["hanging_us_per_step"] > 0


def test_rod_dynamics_benchmark_quick(tmp_path):
    """benchmarks/rod_dynamics.py runs (quick, without Exudyn; its energy case): a rigid
    rotation's energy is exact for every mesh."""
    subprocess.run(
        [
            sys.executable,
            str(ROOT / "benchmarks" / "rod_dynamics.py"),
            "--quick",
            "--no-exudyn",
            "--cases",
            "energy",
            "--out",
            str(tmp_path),
        ],
        capture_output=True,
        text=True,
        check=True,
        timeout=600,
    )
    data = json.loads((tmp_path / "rod_dynamics_energy.json").read_text())
    assert set(data["energy"]) == {"rancf", "rod torsion", "rod full"}
    assert max(max(v) for v in data["energy"].values()) < 1e-10


def test_startup_phases_benchmark_runs():
    """benchmarks/startup_phases.py runs: every phase timed (wall and CPU), the second read of
    the scenario far below the first (the validator is built once), and the CPU time of making
    dataclasses, rancf's own and the other packages', of all the phases."""
    p = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "startup_phases.py"), "--runs", "1"],
        capture_output=True,
        text=True,
        check=True,
        timeout=300,
    )
    med = json.loads(p.stdout.strip().splitlines()[-1])
    phases = [
        "numpy and the core",
        "pydantic",
        "scenario modules",
        "pydantic's plugin loader (importlib.metadata)",
        "first read",
        "second read",
        "run modules",
        "build and start",
    ]
    made = [f"of all: making {who} dataclasses (CPU)" for who in ("rancf's", "other")]
    assert set(med) == {*phases, *(f"{k} (CPU)" for k in phases), *made}
    assert all(med[k] > 0 and med[f"{k} (CPU)"] >= 0 for k in phases)
    assert med["second read"] < med["first read"]
    total = sum(med[f"{k} (CPU)"] for k in phases)
    assert all(0 < med[k] < total for k in made)


def test_belt_benchmark_scenarios_run(tmp_path):
    """benchmarks/scenarios/belt-exudyn.toml (Exudyn's belt test in rancf) and rope-coil.toml
    are valid scenarios, and the matched belt's first 5 ms run to their end."""
    from rancf.scenario import load_scenario

    for name in ("belt-exudyn.toml", "rope-coil.toml"):
        load_scenario(ROOT / "benchmarks" / "scenarios" / name)
    text = (ROOT / "benchmarks" / "scenarios" / "belt-exudyn.toml").read_text()
    short = tmp_path / "belt.toml"
    short.write_text(
        text.replace("t_end = 0.1", "t_end = 0.005").replace(
            "output_step = 0.01", "output_step = 0.005"
        )
    )
    subprocess.run(
        [
            sys.executable,
            "-m",
            "rancf",
            "simulate",
            str(short),
            "--out",
            str(tmp_path / "run"),
            "--quiet",
        ],
        check=True,
        capture_output=True,
        timeout=300,
    )
    summary = json.loads((tmp_path / "run" / "summary.json").read_text())
    assert summary["status"] == "completed" and summary["t_reached"] == 0.005
