"""Reaction sensors carry the moment of the support or joint, as ``reactions.csv`` does: a
planar clamp ``NAME_mz``, a spatial clamp ``NAME_mx, _my, _mz``, a driven pin ``NAME_mz``; a
pin's sensor has its force only.  The force columns keep their names ``NAME_x, _y[, _z]``."""

from __future__ import annotations

import contextlib
import io

import numpy as np
import pytest

from rancf.cli import main
from tests.scenario.systems import SLIDER_CRANK
from tests.scenario.test_scenario import BASE
from tests.test_cli_errors import ROD


def _run(tmp_path, text: str) -> tuple[dict, dict]:
    """Sensors and reactions of a short run, as ``{column: values}``."""
    (tmp_path / "s.toml").write_text(text)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", str(tmp_path / "s.toml"), "--out", str(tmp_path / "run")]) == 0
    out = []
    for f in ("sensors.csv", "reactions.csv"):
        head, *rows = (tmp_path / "run" / f).read_text().splitlines()
        vals = np.array([[float(x) for x in r.split(",")] for r in rows])
        out.append({c: vals[:, i] for i, c in enumerate(head.split(","))})
    return out[0], out[1]


def _same(sensors: dict, reactions: dict, sensor: str, label: str, axes: list[str]) -> None:
    """The sensor's columns are the reaction's: ``NAME_x`` is ``LABEL_fx``, ``NAME_mz`` is
    ``LABEL_mz``; the moment is not zero (the test measures something)."""
    assert [c for c in sensors if c.startswith(f"{sensor}_")] == [f"{sensor}_{a}" for a in axes]
    for a in axes:
        r = reactions[f"{label}_{a if a.startswith('m') else 'f' + a}"]
        np.testing.assert_allclose(sensors[f"{sensor}_{a}"], r, rtol=1e-12, atol=0.0)
        if a.startswith("m") or a == axes[-1]:
            assert np.abs(r).max() > 0.0


def test_planar_clamp_and_pin(tmp_path):
    text = BASE.replace('kind = "pin"', 'kind = "clamp"')
    text += '\n[[supports]]\nat = "end"\nkind = "pin"\n'
    text += '\n[[sensors]]\nname = "root"\nkind = "reaction"\nat = "start"\n'
    text += '\n[[sensors]]\nname = "tip_force"\nkind = "reaction"\nat = "end"\n'
    s, r = _run(tmp_path, text)
    _same(s, r, "root", "start", ["x", "y", "mz"])
    _same(s, r, "tip_force", "end", ["x", "y"])  # a pin carries no moment


def test_spatial_rod_clamp(tmp_path):
    text = ROD + "\n[loads]\ngravity = [0.0, -9.81, -2.0]\n"
    text += '\n[[sensors]]\nname = "root"\nkind = "reaction"\nat = "start"\n'
    s, r = _run(tmp_path, text)
    _same(s, r, "root", "start", ["x", "y", "z", "mx", "my", "mz"])


@pytest.mark.parametrize("joint", ["motor", "guide"])
def test_driven_pin_of_a_system(tmp_path, joint):
    text = SLIDER_CRANK.replace("t_end = 0.2", "t_end = 0.003")
    text += f'\n[[sensors]]\nname = "{joint}_r"\nkind = "reaction"\njoint = "{joint}"\n'
    s, r = _run(tmp_path, text)
    # the driven pin transmits the motor's torque; the slider guide only a force
    _same(s, r, f"{joint}_r", joint, ["x", "y", "mz"] if joint == "motor" else ["x", "y"])
