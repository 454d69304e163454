"""Progress bars only on a terminal (a log file gets no carriage returns), and scenario files
saved with compact arrays (short arrays and table rows one a line, long ones wrapped)."""

from __future__ import annotations

import io
import tomllib
from importlib.resources import files

import numpy as np

import rancf
from rancf.cli import main, stream
from rancf.scenario.toml_text import WIDTH, _compact, dumps


class _Terminal(io.StringIO):
    def isatty(self) -> bool:
        return True


def test_progress_only_on_a_terminal(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    monkeypatch.setattr(stream, "PROGRESS_AFTER_S", 0.0)  # a bar from the first output on
    assert main(["example", "copy", "planar-pendulum", "."]) == 0
    args = ["simulate", "planar-pendulum.toml", "--t-end", "0.05"]
    capsys.readouterr()
    assert main([*args, "--out", "log"]) == 0  # standard error is no terminal here
    err = capsys.readouterr().err
    assert "\r" not in err and "completed" not in err
    terminal = _Terminal()
    monkeypatch.setattr("sys.stderr", terminal)
    assert main([*args, "--out", "tty"]) == 0
    assert "\r" in terminal.getvalue()  # the bar, where it belongs


def test_saved_scenarios_have_compact_arrays(tmp_path):
    sc = rancf.load_scenario(files("rancf.examples") / "capstan.toml")
    sc.save(tmp_path / "s.toml")
    text = (tmp_path / "s.toml").read_text()
    lines = text.splitlines()
    assert "knots = [0.0, 0.0, 0.0, 1.0, 1.0, 2.0, 2.0, 3.0, 3.0, 4.0, 4.0, 4.0]" in lines
    assert "    [0.1, 0.0, -0.0002]," in lines  # a table row a line
    assert not any(line.strip().rstrip(",").replace(".", "").isdigit() for line in lines)
    again = rancf.parse_scenario(tomllib.loads(text), str(tmp_path / "s.toml"))
    assert again.to_dict() == sc.to_dict()


def test_long_arrays_wrap_and_strings_stay():
    data = {"a": {"values": [float(x) for x in np.linspace(0, 1, 101)], "names": ["x, [y]", "z"]}}
    text = dumps(data)
    assert tomllib.loads(text) == data
    assert all(len(line) <= WIDTH for line in text.splitlines())
    assert 5 < len(text.splitlines()) < 30  # several numbers a line, not one
    assert _compact("a = [\n    1,\n    2,\n]\n") == "a = [1, 2]\n"
