"""docs/guide/contact.md tells the truth: its console transcripts are run and compared with
tests/test_readme.py's machinery (text exactly, numbers within :data:`tests.numbers.RTOL`), and
its TOML blocks are valid scenarios.  (Until the docs site's test runs every docs/**/*.md.)"""

from __future__ import annotations

import re
import subprocess
import tomllib
from pathlib import Path

import pytest

from rancf.scenario import parse_scenario
from tests.numbers import assert_lines_match
from tests.test_readme import _normalize, _transcript, shell_env  # noqa: F401 - a fixture

PAGE = Path(__file__).resolve().parents[1] / "docs" / "guide" / "contact.md"
TEXT = PAGE.read_text(encoding="utf-8")
CONSOLE = re.findall(r"```console\n(.*?)```", TEXT, flags=re.S)
TOML = re.findall(r"```toml\n(.*?)```", TEXT, flags=re.S)


def test_page_has_examples():
    assert len(CONSOLE) >= 2 and TOML


@pytest.mark.parametrize("block", CONSOLE, ids=[f"console{i}" for i in range(len(CONSOLE))])
def test_console_block(block, shell_env, tmp_path):  # noqa: F811
    for command, expected in _transcript(block):
        p = subprocess.run(
            ["sh", "-c", command], cwd=tmp_path, env=shell_env, capture_output=True, text=True
        )
        assert p.returncode == 0, (command, p.stderr)
        got = [_normalize(x) for x in p.stdout.splitlines()]
        assert_lines_match(got, [_normalize(x) for x in expected], what=command)


@pytest.mark.parametrize("block", TOML, ids=[f"toml{i}" for i in range(len(TOML))])
def test_toml_block_is_a_scenario(block):
    sc = parse_scenario(tomllib.loads(block))
    assert sc.obstacles and sc.is_system
