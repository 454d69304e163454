"""A corpus of hostile inputs for the newer features: winches and driven drums, CSV
tables, Campbell spins, fluid, the 3D view.  Each case says what a careful user expects; each
must end with exit status 2, exactly one line on standard error naming the key path (or the
option) and the value given, no traceback, and nothing written.  In-process, a few seconds."""

from __future__ import annotations

import json
import os
import tomllib
from importlib.resources import files
from pathlib import Path

import pytest

from rancf.cli import main
from tests.scenario.test_scenario import BASE
from tests.scenario.test_table_files import _with_table
from tests.test_cli_errors import check_one_line

DRUM = (files("rancf.examples") / "drum-hoist.toml").read_text(encoding="utf-8")
CRANE = (files("rancf.examples") / "crane-hoist.toml").read_text(encoding="utf-8")
#: A blade (rod clamped on the spin axis) for ``rancf modes`` with ``[modes] spin_rates``.
BLADE = """
[geometry]
kind = "line"
start = [0.0, 0.0, 0.0]
end = [1.0, 0.0, 0.0]
[mesh]
elements = 4
element = "rod"
[section]
radius = 0.01
[material]
density = 7800.0
youngs_modulus = 2.0e9
poisson_ratio = 0.3
[[supports]]
at = "start"
kind = "clamp"
[modes]
count = 2
"""
#: A riser: a vertical steel pipe pinned at the seabed (z = -50 m) and at the surface, in a 1 m/s
#: current.
RISER = """
[geometry]
kind = "line"
start = [0.0, 0.0, -50.0]
end = [0.0, 0.0, 0.0]
[mesh]
elements = 10
element = "ancf"
[section]
radius = 0.1
[material]
density = 7850.0
youngs_modulus = 2.0e11
[hydro]
diameter = 0.2
drag_normal = 1.2
added_mass_normal = 1.0
[fluid]
density = 1025.0
surface = 0.0
current = [1.0, 0.0, 0.0]
[[supports]]
at = "start"
kind = "pin"
[[supports]]
at = "end"
kind = "pin"
[loads]
gravity = [0.0, 0.0, -9.81]
[solver]
t_end = 0.02
step = 0.01
initial_state = "static"
"""
WAVES = "[fluid.waves]\nheight = 4.0\nperiod = 8.0\ndepth = 50.0\n"


def _winch(text: str, key: str, value: str | None) -> str:
    """``text`` with its (first) ``[[winches]]`` table's ``key`` set to ``value`` (None drops
    it)."""
    i = text.index("[[winches]]")
    j = text.index("\n\n", i)
    lines = [ln for ln in text[i:j].splitlines() if not ln.startswith(f"{key} ")]
    if value is not None:
        lines.append(f"{key} = {value}")
    return text[:i] + "\n".join(lines) + text[j:]


SPEED = _winch(CRANE, "length", None)  # the crane's winch without its length law: give speed

#: (id, scenario text, command after its file name, words the line must hold); the comment
#: says what a careful user expects.
CASES = [
    # a Campbell diagram up to 1e300 rad/s is a unit mistake: refused, not an OverflowError
    (
        "spin-1e300",
        BLADE + "spin_rates = [0.0, 1e300]\n",
        ["modes"],
        ["[modes.spin_rates[1]]", "1e+300", "at most 1e+06 rad/s"],
    ),
    ("spin-1e7", BLADE + "spin_rates = [1e7]\n", ["modes"], ["[modes.spin_rates[0]]", "1e+06"]),
    ("spin-negative", BLADE + "spin_rates = [-3.0]\n", ["modes"], ["[modes.spin_rates[0]]"]),
    ("spin-planar", BASE + "[modes]\nspin_rates = [1.0]\n", ["modes"], ["modes.spin_rates"]),
    # every winch key with a bad value names winches[0].key
    ("winch-length-nan", _winch(CRANE, "length", "nan"), [], ["[winches[0].length]", "nan"]),
    (
        "winch-length-tiny",
        _winch(CRANE, "length", "1e-300"),
        [],  # not a joint's fault
        ["[winches[0].length]", "1e-300", "within a factor 1000"],
    ),
    ("winch-length-huge", _winch(CRANE, "length", "1e300"), [], ["[winches[0].length]"]),
    ("winch-speed-inf", _winch(SPEED, "speed", "1e999"), [], ["[winches[0].speed]", "inf"]),
    ("winch-speed-vector", _winch(SPEED, "speed", "[1.0, 2.0]"), [], ["[winches[0].speed]"]),
    ("winch-speed-and-length", _winch(CRANE, "speed", "1.0"), [], ["[winches[0].length]"]),
    ("winch-torque-text", _winch(DRUM, "torque", '"x"'), [], ["[winches[0].torque]", "'x'"]),
    # a torque no hanging weight can hold: statics names the winch's table and the file
    (
        "winch-torque-static",
        _winch(DRUM, "torque", "1e12"),
        ["static"],
        ["s.toml: [winches[0].torque]", "1000000000000.0"],
    ),
    ("winch-torque-start", _winch(DRUM, "torque", "1e12"), [], ["s.toml: [winches[0].torque]"]),
    ("winch-radius-negative", _winch(DRUM, "radius", "-1"), [], ["[winches[0].radius]", "-1"]),
    # a radius whose J / r^2 overflows: not a ZeroDivisionError
    (
        "winch-radius-tiny",
        _winch(DRUM, "radius", "1e-300"),
        [],
        ["[winches[0].radius]", "1e-300", "J / r^2"],
    ),
    ("winch-radius-no-torque", _winch(CRANE, "radius", "0.2"), [], ["[winches[0].radius]"]),
    ("winch-inertia-zero", _winch(DRUM, "inertia", "0"), [], ["[winches[0].inertia]"]),
    ("winch-inertia-missing", _winch(DRUM, "inertia", None), [], ["[winches[0].inertia]"]),
    ("winch-at-nobody", _winch(DRUM, "at", '"nope:start"'), [], ["[winches[0].at]", "nope"]),
    ("winch-at-middle", _winch(DRUM, "at", '"wire:middle"'), [], ["[winches[0].at]"]),
    ("winch-at-number", _winch(DRUM, "at", "3"), [], ["[winches[0].at]"]),
    # a 3D point for a planar line: not a broadcast traceback
    (
        "winch-position-3d",
        _winch(CRANE, "position", "[0.0, 1.0, 2.0]"),
        [],
        ["[winches[0].position]", "2 numbers"],
    ),
    ("winch-position-far", _winch(DRUM, "position", "[1.0, 2.0]"), [], ["[winches[0].position]"]),
    ("winch-name", _winch(DRUM, "name", '"1x"'), [], ["[winches[0].name]", "'1x'"]),
    ("winch-unknown-key", _winch(DRUM, "reel", "1"), [], ["[winches[0].reel]"]),
    # fluid: waves need a water depth > 0 and a surface
    ("waves-depth-0", RISER + WAVES.replace("50.0", "0.0"), [], ["[fluid.waves.depth]"]),
    ("waves-no-surface", RISER.replace("surface = 0.0\n", "") + WAVES, [], ["fluid"]),
    ("current-size", RISER.replace("[1.0, 0.0, 0.0]", "[1.0]"), [], ["[fluid.current]"]),
    # a CSV table's first line with a typo among its numbers is not a header to drop
    ("csv-typo-first-line", _with_table('"t.csv"'), [], ["t.csv line 1: 'oops'"]),
    # a CSV table that is a loop of symbolic links: one line, not a RuntimeError
    (
        "csv-symlink-loop",
        _with_table('"loop.csv"'),
        [],
        ["[supports[0].motion.table]", "loop.csv", "cannot be read"],
    ),
]


def _files(root: Path) -> None:
    (root / "t.csv").write_text("0, 0, oops\n0, 0, 0\n1, 0, 0\n")
    os.symlink("loop.csv", root / "loop.csv")


@pytest.mark.parametrize(
    ("text", "command", "needles"), [c[1:] for c in CASES], ids=[c[0] for c in CASES]
)
def test_hostile_input(tmp_path, monkeypatch, capsys, text, command, needles):
    monkeypatch.chdir(tmp_path)
    _files(tmp_path)
    (tmp_path / "s.toml").write_text(text)
    argv = [*command, "s.toml"] if command else ["simulate", "s.toml", "--out", "run", "--quiet"]
    line = check_one_line(capsys, argv, 2, needles[0], tmp_path)
    assert all(n in line for n in needles), line
    assert "s.toml" in line or command == ["modes"] and "spin_rates" in line


@pytest.fixture(scope="module")
def run_dir(tmp_path_factory):
    """A short run of the test scenario, for ``rancf view``."""
    folder = tmp_path_factory.mktemp("view")
    (folder / "s.toml").write_text(BASE)
    assert main(["simulate", str(folder / "s.toml"), "--out", str(folder / "run"), "--quiet"]) == 0
    return folder / "run"


@pytest.mark.parametrize(
    "out",
    [
        "adir",  # a directory: the page needs a file name
        "afile/v.html",  # a folder that is a file
        "/proc/rancf-view.html",  # a place nobody can write (root too): not the temporary file
    ],
)
def test_view_out_names_the_users_path(tmp_path, monkeypatch, capsys, run_dir, out):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "adir").mkdir()
    (tmp_path / "afile").write_text("x")
    line = check_one_line(capsys, ["view", str(run_dir), "--out", out], 2, "--out", tmp_path)
    assert f"'{out}'" in line and ".html." not in line, line


@pytest.mark.skipif(os.geteuid() == 0, reason="root may write into a read-only directory")
def test_view_out_in_a_read_only_folder(tmp_path, monkeypatch, capsys, run_dir):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "ro").mkdir(mode=0o555)
    line = check_one_line(
        capsys, ["view", str(run_dir), "--out", "ro/v.html"], 2, "--out", tmp_path
    )
    assert "'ro/v.html'" in line and "not writable" in line


def test_a_numeric_first_line_is_data_not_a_header(tmp_path, monkeypatch, capsys):
    """A table file whose first line is numbers has no header: that line is the first row."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "t.csv").write_text("1, 0, 0\n0, 0, 0\n2, 0, 0\n")
    (tmp_path / "s.toml").write_text(_with_table('"t.csv"'))
    assert main(["simulate", "s.toml", "--out", "run", "--quiet"]) == 2  # rows 1, 0: not sorted
    assert "[supports[0].motion.table[1][0]] times must increase" in capsys.readouterr().err


def test_statics_with_waves_are_those_of_the_still_surface(tmp_path, monkeypatch, capsys):
    """A riser in a current, with and without waves: ``rancf static`` and a static start see
    the still surface and the current (docs/guide/fluid.md), so both converge to the same
    state."""
    monkeypatch.chdir(tmp_path)
    (tmp_path / "still.toml").write_text(RISER)
    (tmp_path / "waves.toml").write_text(RISER + WAVES)
    found = {}
    for name in ("still", "waves"):
        assert main(["static", f"{name}.toml", "--json"]) == 0
        found[name] = json.loads(capsys.readouterr().out)
        found[name].pop("wall_time_s")
        assert main(["simulate", f"{name}.toml", "--out", name, "--quiet"]) == 0
        summary = json.loads((tmp_path / name / "summary.json").read_text())
        found[name + "-start"] = summary["static"]["newton_iterations"]
    assert found["still"] == found["waves"]
    assert found["still-start"] == found["waves-start"]
    drift = found["still"]["positions"]["body"][5][0]
    assert drift > 0.01  # the current pushes the riser downstream


def test_the_corpus_covers_every_winch_key():
    keys = {"name", "at", "position", "length", "speed", "torque", "radius", "inertia"}
    named = {n.split(".")[1].rstrip("]") for c in CASES for n in c[3] if "winches[0]." in n}
    assert keys <= named, keys - named
    assert tomllib.loads(_winch(DRUM, "radius", "0.3"))["winches"][0]["radius"] == 0.3
