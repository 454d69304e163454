"""Runs the console examples of the README sections on export, CAD, sweeps and the fourth study,
and compares their output with the README's (text exactly, numbers within
:data:`tests.numbers.RTOL`)."""

import os
import re
import shlex
from pathlib import Path

import numpy as np
import pytest

from rancf.cli import main
from tests.model.test_scenario import BASE
from tests.numbers import assert_lines_match

README = Path(__file__).resolve().parents[1] / "README.md"
SECTIONS = (
    "### Looking at a run",
    "### CAD in and out",
    "### Parameter sweeps on Dask",
    "### Rods with torsion",
    "### Rod dynamics",
    "### Where exact geometry pays",
)


def _section(title: str) -> str:
    text = README.read_text(encoding="utf-8")
    start = text.index(title)
    ends = [text.find(mark, start + 4) for mark in ("\n### ", "\n## ")]
    return text[start : min([e for e in ends if e > 0] or [len(text)])]


def _blocks(section: str, lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", section, flags=re.S)


def _commands(block: str) -> list[tuple[str, list[str]]]:
    out: list[tuple[str, list[str]]] = []
    for line in block.splitlines():
        if line.startswith("$ "):
            out.append((line[2:], []))
        elif out:
            out[-1][1].append(line)
    return out


def test_readme_console_examples(tmp_path, capsys, monkeypatch):
    monkeypatch.chdir(tmp_path)
    (tmp_path / "short.toml").write_text(BASE)
    sweep = _section(SECTIONS[2])
    (tmp_path / "sweep.toml").write_text(_blocks(sweep, "toml")[0])
    (tmp_path / "rod.toml").write_text(_blocks(_section(SECTIONS[3]), "toml")[0])
    dynamics = _section("### Rod dynamics")
    (tmp_path / "top.toml").write_text(_blocks(dynamics, "toml")[0])
    n = 0
    for title in SECTIONS:
        for block in _blocks(_section(title), "console"):
            for cmd, expected in _commands(block):
                argv = shlex.split(cmd)
                assert argv[0] == "rancf", cmd
                capsys.readouterr()
                assert main(argv[1:]) == 0, cmd
                got = capsys.readouterr().out.rstrip("\n").splitlines()
                assert_lines_match(got, expected, what=cmd)
                n += 1
    assert n >= 8
    assert len(list((tmp_path / "run" / "vtk").glob("*.vtu"))) == 5
    assert os.path.getsize(tmp_path / "run.gif") > 0
    # the heavy top's sensors as the README shows them (numbers across machines: 1e-6)
    shown = _blocks(dynamics, "text")[0].splitlines()
    run = (tmp_path / "top" / "sensors.csv").read_text().splitlines()
    assert run[0] == shown[0] and len(run) == len(shown)
    got, want = (np.array([r.split(",") for r in rows[1:]], dtype=float) for rows in (run, shown))
    assert np.allclose(got, want, rtol=1e-6, atol=1e-6)


@pytest.mark.parametrize("title", SECTIONS)
def test_sections_exist(title):
    assert _blocks(_section(title), "console")
