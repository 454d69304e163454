"""The first stored row of a run whose supports accelerate from the start: the reaction carries
the whole starting acceleration (the motion before t = 0 is no part of the run)."""

from __future__ import annotations

import contextlib
import io

import numpy as np

from rancf.cli import main

#: x(t) = -0.75 t², sampled: a cubic table holds the quadratic exactly (acceleration -1.5 m/s²)
PATH = [[t, -0.75 * t * t, 0.0] for t in (0.0, 0.5, 1.0, 1.5, 2.0)]


def test_a_mass_carried_by_an_accelerating_pin_reacts_with_m_a_from_the_first_row(tmp_path):
    """A 1 kg point mass on a pin whose path starts at -1.5 m/s² (no gravity): the pin's force
    is -1.5 N at t = 0 as at every later row (a central difference in time across t = 0, where
    the path is flat, gave half of it)."""
    (tmp_path / "s.toml").write_text(
        f"""
[[bodies]]
name = "m"
kind = "mass"
mass = 1.0
position = [0.0, 0.0]
[[supports]]
at = "m"
kind = "pin"
motion = {{ table = {PATH}, interpolation = "cubic" }}
[solver]
t_end = 0.05
step = 0.01
"""
    )
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "run")]) == 0
    rows = np.loadtxt(tmp_path / "run/reactions.csv", delimiter=",", skiprows=1)
    assert rows[0, 0] == 0.0
    np.testing.assert_allclose(rows[:, 1], -1.5, rtol=1e-8)
    np.testing.assert_allclose(rows[:, 2], 0.0, atol=1e-8)
