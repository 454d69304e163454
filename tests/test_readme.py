"""The README and the documentation tell the truth: the console transcripts and Python examples
of every page of :data:`tests.pages.PAGES` are run and compared (text exactly, numbers within
:data:`tests.numbers.RTOL`: round-off differs between machines)."""

from __future__ import annotations

import os
import re
import stat
import subprocess
import sys
import tomllib

import pytest

from rancf.scenario import parse_scenario
from tests.numbers import assert_lines_match
from tests.pages import DOCS, PAGES, README, blocks, name, section, text, transcript


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


def _own_console_blocks() -> list[tuple[str, str]]:
    """``(page, block)`` for every console block, except those of the sections
    ``test_readme_post`` runs in order with its files."""
    from tests.test_readme_post import SECTIONS

    skip = {(where[0], b) for where in SECTIONS for b in blocks(section(*where), "console")}
    return [(p, b) for p in PAGES for b in blocks(text(p), "console") if (p, b) not in skip]


CONSOLE = _own_console_blocks()
_IDS: list[str] = []
for _page, _ in CONSOLE:
    _IDS.append(f"{name(_page)}-{sum(1 for i in _IDS if i.startswith(name(_page) + '-'))}")


def test_pages_have_console_examples():
    assert len(CONSOLE) >= 4
    assert any(p == README for p, _ in CONSOLE)


@pytest.mark.parametrize(("page", "block"), CONSOLE, ids=_IDS)
def test_console_block(page, block, shell_env, tmp_path):
    for command, expected in transcript(block):
        p = subprocess.run(
            ["sh", "-c", command], cwd=tmp_path, env=shell_env, capture_output=True, text=True
        )
        assert p.returncode == 0, (name(page), command, p.stderr)
        got = [_normalize(x) for x in p.stdout.splitlines()]
        assert_lines_match(got, [_normalize(x) for x in expected], what=command)


PYTHON = [p for p in PAGES if blocks(text(p), "python")]


@pytest.mark.parametrize("page", PYTHON, ids=[name(p) for p in PYTHON])
def test_python_examples(page, tmp_path, monkeypatch, capsys):
    """A page's Python blocks run in order in one folder; ``print(...)  # expected`` lines
    are compared with what they print."""
    monkeypatch.chdir(tmp_path)
    for code in blocks(text(page), "python"):
        exec(compile(code, str(page), "exec"), {})  # noqa: S102
        out = capsys.readouterr().out.splitlines()
        expected = [
            ln.split("  # ", 1)[1]
            for ln in code.splitlines()
            if ln.startswith("print(") and "  # " in ln
        ]
        assert_lines_match(out, expected, what=f"python example of {name(page)}")


def test_python_examples_exist():
    assert README in PYTHON and len(PYTHON) >= 3


SCENARIOS = DOCS / "guide" / "scenarios.md"


def test_scenario_example_is_valid():
    toml = blocks(text(SCENARIOS), "toml")[0]  # the complete scenario example
    assert "[geometry]" in toml
    sc = parse_scenario(tomllib.loads(toml), "scenarios.md")
    assert sc.build_model().n_el == 5


def test_system_example_is_valid():
    """The system example of the guide: its keys read into the models; it is a system of parts,
    so asking it for one flexible body's model stops with one line pointing to its system."""
    from rancf.errors import ScenarioError

    toml = next(b for b in blocks(text(DOCS / "guide" / "systems.md"), "toml") if "[[bodies]]" in b)
    sc = parse_scenario(tomllib.loads(toml), "s.toml")
    assert [b.name for b in sc.bodies] == ["rod", "crank", "slider"]
    assert [j.kind for j in sc.joints] == ["pin", "pin", "pin", "slider"]
    assert sc.data["joints"][0]["angle"].kind == "spin_up" and sc.springs[0].stiffness == 10.0
    assert [s.columns(2) for s in sc.sensors][2:] == [["N"], ["p_x", "p_y"]]
    with pytest.raises(ScenarioError, match=r"^s\.toml: \[bodies\] makes this scenario a system"):
        sc.build_model()
