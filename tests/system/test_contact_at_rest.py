"""Contact outputs at rest are steady: once the kinetic energy has settled (below 1e-6 of the
potential energy), a contact force's standard deviation is below 1 % of its mean (measured
1e-11 and 1e-10): the rows report the force the step's balance uses, not a sample of the
penalty's vibration."""

from __future__ import annotations

import re
from importlib import resources
from pathlib import Path

import numpy as np

from rancf.cli import main

TESTS = Path(__file__).parent


def _steady(run: Path, column: str, table: str = "reactions.csv") -> None:
    rows = np.genfromtxt(run / table, delimiter=",", names=True)
    energy = np.genfromtxt(run / "energy.csv", delimiter=",", names=True)
    potential = np.abs(energy["gravity"] + energy["strain"])
    settled = energy["kinetic"] < 1e-6 * potential
    assert settled[-1], "the run must come to rest"
    start = np.flatnonzero(~settled)[-1] + 1 if (~settled).any() else 0
    force = rows[column][start:]
    assert force.size >= 20, force.size
    assert force.std() < 0.01 * abs(force.mean()), (force.mean(), force.std())


def test_two_draped_cables_report_steady_forces(tmp_path):
    """The upper cable of tests/system/test_contact_outputs.py dropped on the lower one on the
    ground, run on to 1 s."""
    text = (TESTS / "test_contact_outputs.py").read_text()
    two = re.search(r'TWO = """(.*?)"""', text, re.S).group(1).replace("t_end = 0.3", "t_end = 1.0")
    (tmp_path / "two.toml").write_text(two)
    assert (
        main(["simulate", str(tmp_path / "two.toml"), "--out", str(tmp_path / "r"), "--quiet"]) == 0
    )
    _steady(tmp_path / "r", "ground_normal_y")
    _steady(tmp_path / "r", "low_high_contact_force")


def test_a_mooring_line_on_the_seabed_reports_a_steady_force(tmp_path):
    """The shipped mooring line from its static state, its fairlead held (no surge)."""
    text = (resources.files("rancf.examples") / "mooring-line.toml").read_text()
    still = re.sub(r"(?m)^motion = .*\n", "", text).replace("t_end = 20.0", "t_end = 5.0")
    (tmp_path / "m.toml").write_text(still)
    assert (
        main(["simulate", str(tmp_path / "m.toml"), "--out", str(tmp_path / "r"), "--quiet"]) == 0
    )
    _steady(tmp_path / "r", "seabed_normal_z")
    _steady(tmp_path / "r", "seabed_z", "sensors.csv")  # its contact_force sensor
