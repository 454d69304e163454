"""The shipped winch examples through ``rancf simulate``: ``tether-reel-out`` (the payload's
distance from the winch is the tether's length plus its stretch at every output) and
``crane-hoist`` (its first 4 s: the load rises by the rope taken in, and the tension at the
drum starts at the static one)."""

from __future__ import annotations

import contextlib
import io
import tomllib

import numpy as np
import pytest

from rancf.cli import main
from rancf.scenario import Scenario
from rancf.studies.common import example_path


def _run(tmp_path, name: str, t_end: float | None = None) -> dict[str, np.ndarray]:
    raw = tomllib.loads(example_path(name).read_text())
    if t_end is not None:
        raw["solver"]["t_end"] = t_end
    Scenario.from_dict(raw, str(example_path(name))).save(tmp_path / "s.toml")
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "run")]) == 0
    d = np.genfromtxt(tmp_path / "run" / "sensors.csv", delimiter=",", names=True)
    return {k: d[k] for k in d.dtype.names}


def test_tether_reel_out(tmp_path):
    """Paid out from 10 m to 30 m: the payload stays at the tether's length plus a stretch
    below 1 cm (Dyneema at about 27 N: 1e-3 of the length at most)."""
    s = _run(tmp_path, "tether-reel-out")
    distance = np.hypot(s["payload_x"], s["payload_y"])
    assert s["reel_length"][0] == pytest.approx(10.0) and s["reel_length"][-1] == pytest.approx(
        30.0
    )
    assert np.all(np.abs(distance - s["reel_length"]) < 1e-2)
    assert np.all(s["reel_tension"] > 15.0)  # taut all the way


def test_crane_hoist_lifts_the_load_by_the_rope_taken_in(tmp_path):
    s = _run(tmp_path, "crane-hoist", t_end=4.0)
    taken = s["hoist_length"][0] - s["hoist_length"]
    lift = s["hook_y"] - s["hook_y"][0]
    assert taken[-1] > 0.5
    assert np.all(np.abs(lift - taken) < 0.01)
    rope = 7850.0 * 1.130973355292326e-4  # kg/m; the winch's side hangs 14 m below the sheave
    static = (100.0 + rope * 12.0) * 9.81 - rope * 14.0 * 9.81
    assert s["hoist_tension"][0] == pytest.approx(static, rel=0.02)
