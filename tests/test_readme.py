"""The README tells the truth: its console transcripts and Python examples are run and compared
(text exactly, numbers within :data:`tests.numbers.RTOL`: round-off differs between machines)."""

from __future__ import annotations

import os
import re
import stat
import subprocess
import sys
import tomllib
from pathlib import Path

import pytest

from rancf.scenario import parse_scenario
from tests.numbers import assert_lines_match

README = Path(__file__).resolve().parents[1] / "README.md"
TEXT = README.read_text(encoding="utf-8")


def _blocks(lang: str) -> list[str]:
    return re.findall(rf"```{lang}\n(.*?)```", TEXT, flags=re.S)


def _transcript(block: str) -> list[tuple[str, list[str]]]:
    """``(command, expected output lines)`` for every ``$ `` line of a console block."""
    steps: list[tuple[str, list[str]]] = []
    for line in block.splitlines():
        if line.startswith("$ "):
            steps.append((line[2:], []))
        else:
            steps[-1][1].append(line)
    return steps


def _normalize(line: str) -> str:
    """Wall times vary: ``1.570 s (1.570 ms/step)`` compares as ``# s (# ms/step)``."""
    return re.sub(r"\d+\.\d+ (s|ms/step)\b", r"# \1", line.rstrip())


@pytest.fixture(scope="module")
def shell_env(tmp_path_factory):
    """A PATH whose ``rancf`` is this interpreter's ``python -m rancf``."""
    bin_dir = tmp_path_factory.mktemp("bin")
    exe = bin_dir / "rancf"
    exe.write_text(f'#!/bin/sh\nexec "{sys.executable}" -m rancf "$@"\n')
    exe.chmod(exe.stat().st_mode | stat.S_IEXEC)
    return {**os.environ, "PATH": f"{bin_dir}{os.pathsep}{os.environ['PATH']}"}


def _own_console_blocks() -> list[str]:
    """Console blocks, except those of the sections ``test_readme_post`` runs with its files."""
    from tests.test_readme_post import SECTIONS, _section

    skip = {
        b for title in SECTIONS for b in re.findall(r"```console\n(.*?)```", _section(title), re.S)
    }
    return [b for b in _blocks("console") if b not in skip]


CONSOLE = _own_console_blocks()


def test_readme_has_console_examples():
    assert len(CONSOLE) >= 4


@pytest.mark.parametrize("block", CONSOLE, ids=[f"console{i}" for i in range(len(CONSOLE))])
def test_console_block(block, shell_env, tmp_path):
    for command, expected in _transcript(block):
        p = subprocess.run(
            ["sh", "-c", command], cwd=tmp_path, env=shell_env, capture_output=True, text=True
        )
        assert p.returncode == 0, (command, p.stderr)
        got = [_normalize(x) for x in p.stdout.splitlines()]
        assert_lines_match(got, [_normalize(x) for x in expected], what=command)


def test_python_examples(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    blocks = _blocks("python")
    assert blocks
    for code in blocks:
        exec(compile(code, str(README), "exec"), {})  # noqa: S102
        out = capsys.readouterr().out.splitlines()
        expected = [
            ln.split("  # ", 1)[1]
            for ln in code.splitlines()
            if ln.startswith("print(") and "  # " in ln
        ]
        assert_lines_match(out, expected, what="python example")


def test_scenario_example_is_valid():
    toml = _blocks("toml")[0]  # the complete scenario example (the others are sweep files)
    assert "[geometry]" in toml
    sc = parse_scenario(tomllib.loads(toml), "README")
    assert sc.build_model().n_el == 5


def test_system_example_is_valid():
    """The README's system example: the keys of issue 18, read into the models; the one-body
    commands stop on it with one line until the system solver takes it."""
    from rancf.errors import ScenarioError

    toml = next(b for b in _blocks("toml") if "[[bodies]]" in b)
    sc = parse_scenario(tomllib.loads(toml), "s.toml")
    assert [b.name for b in sc.bodies] == ["rod", "crank", "slider"]
    assert [j.kind for j in sc.joints] == ["pin", "pin", "pin", "slider"]
    assert sc.data["joints"][0]["angle"].kind == "spin_up" and sc.springs[0].stiffness == 10.0
    assert [s.columns(2) for s in sc.sensors][2:] == [["N"], ["p_x", "p_y"]]
    with pytest.raises(ScenarioError, match=r"^s\.toml: \[bodies\] multibody systems: not yet"):
        sc.build_model()
