"""``rancf sweep`` gives the numbers of the single-analysis command, for every analysis a sweep
offers: both run the scenario through the same driver (:mod:`rancf.runs`), so a variant of the
grid equal to the base file reproduces ``rancf simulate``, ``rancf static`` and ``rancf modes``
to 1e-6 (the modes of a sagging power line about its static state included)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from rancf.sweep.spec import ANALYSES
from tests.scenario.test_scenario import BASE
from tests.sweep.test_sweep import POWER_LINE
from tests.test_cli_sim import CANTILEVER

RTOL = 1e-6


def _sweep(tmp_path: Path, base: str, analysis: str, key: str, value: object) -> tuple[dict, Path]:
    """One-variant sweep of ``base`` whose grid sets ``key`` to the value the file has."""
    spec = tmp_path / f"{analysis}.toml"
    spec.write_text(f'base = "{base}"\nanalysis = "{analysis}"\n[grid]\n"{key}" = [{value}]\n')
    out = tmp_path / f"sweep-{analysis}"
    assert main(["sweep", str(spec), "--out", str(out), "--workers", "1", "--quiet"]) == 0
    with open(out / "results.csv") as fh:
        (row,) = list(csv.DictReader(fh))
    assert row["status"] == "completed", row
    return row, next((out / "runs").iterdir())


def _simulate(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    (tmp_path / "pend.toml").write_text(BASE)
    assert main(["simulate", str(tmp_path / "pend.toml"), "--out", str(tmp_path / "r")]) == 0
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    with open(tmp_path / "r" / "sensors.csv") as fh:
        last = list(csv.DictReader(fh))[-1]
    row, _ = _sweep(tmp_path, "pend.toml", "simulate", "mesh.elements", 3)
    assert float(row["t_reached"]) == summary["t_reached"] > 0
    assert int(float(row["steps"])) == summary["steps"]
    for name in ("AB", "tip_x", "tip_y"):
        np.testing.assert_allclose(float(row[name]), float(last[name]), rtol=RTOL, atol=1e-12)


def _static(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    (tmp_path / "cant.toml").write_text(CANTILEVER)
    capsys.readouterr()
    assert main(["static", str(tmp_path / "cant.toml"), "--json"]) == 0
    want = json.loads(capsys.readouterr().out)
    row, folder = _sweep(tmp_path, "cant.toml", "static", "solver.load_steps", 4)
    got = json.loads((folder / "static.json").read_text())
    assert want["sensors"] and set(got["sensors"]) == set(want["sensors"])
    for name, v in want["sensors"].items():
        np.testing.assert_allclose(float(row[name]), v, rtol=RTOL, atol=1e-12)
        np.testing.assert_allclose(got["sensors"][name], v, rtol=RTOL, atol=1e-12)
    for body, xs in want["positions"].items():
        np.testing.assert_allclose(got["positions"][body], xs, rtol=RTOL, atol=1e-12)


def _modes(tmp_path: Path, capsys: pytest.CaptureFixture) -> None:
    (tmp_path / "line.toml").write_text(POWER_LINE)
    capsys.readouterr()
    assert main(["modes", str(tmp_path / "line.toml"), "--json"]) == 0
    want = json.loads(capsys.readouterr().out)
    assert want["about"] == "static" and want["frequencies_hz"][0] > 0.1  # not the slack line's
    row, folder = _sweep(tmp_path, "line.toml", "modes", "mesh.elements", 16)
    got = [float(row[f"f{i}_hz"]) for i in (1, 2, 3)]
    np.testing.assert_allclose(got, want["frequencies_hz"], rtol=RTOL)
    assert json.loads((folder / "modes.json").read_text())["about"] == "static"


CHECKS = {"simulate": _simulate, "static": _static, "modes": _modes}


def test_every_analysis_of_a_sweep_is_checked():
    assert set(CHECKS) == set(ANALYSES)


@pytest.mark.parametrize("analysis", sorted(CHECKS))
def test_sweep_equals_the_single_command(analysis, tmp_path, capsys):
    CHECKS[analysis](tmp_path, capsys)
