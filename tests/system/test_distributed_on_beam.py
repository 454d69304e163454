"""A distributed load on a body of beam elements is refused naming the key that asked for it."""

from __future__ import annotations

import contextlib
import io

from rancf.cli import main

BEAM = """
[geometry]
kind = "line"
start = [0.0, 0.0]
end = [1.0, 0.0]
[mesh]
elements = 4
element = "beam"
[section]
radius = 0.01
[material]
density = 7800.0
youngs_modulus = 2.0e11
[[supports]]
at = "start"
kind = "clamp"
[[loads.distributed]]
force = [0.0, -10.0]
"""


def test_a_distributed_load_on_beam_elements_names_loads_distributed(tmp_path):
    (tmp_path / "s.toml").write_text(BEAM)
    err = io.StringIO()
    with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
        code = main(["static", str(tmp_path / "s.toml"), "--out", str(tmp_path / "o")])
    lines = err.getvalue().strip().splitlines()
    assert code == 2 and len(lines) == 1, lines
    assert "[loads.distributed]" in lines[0] and "beam elements" in lines[0]
    assert "hydro" not in lines[0]
