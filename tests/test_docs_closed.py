"""docs/guide/closed-curves.md tells the truth: its console transcripts are run and compared
(text exactly, numbers within tests.numbers.RTOL), with the machinery of test_readme, and its
study tables are those of benchmarks/results/continuity_study.json."""

from __future__ import annotations

import importlib.util
import json
import re
import subprocess
from pathlib import Path

import pytest

from tests.numbers import assert_lines_match
from tests.test_readme import _normalize, _transcript, shell_env  # noqa: F401 (a fixture)

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "guide" / "closed-curves.md"
TEXT = PAGE.read_text(encoding="utf-8")
CONSOLE = re.findall(r"```console\n(.*?)```", TEXT, flags=re.S)


def test_page_has_ring_and_c2_examples():
    assert len(CONSOLE) >= 4
    assert any("ring.toml" in b for b in CONSOLE)
    assert any('continuity = "C2"' in b for b in CONSOLE)


@pytest.mark.parametrize("block", CONSOLE, ids=[f"console{i}" for i in range(len(CONSOLE))])
def test_console_block(block, shell_env, tmp_path):  # noqa: F811
    for command, expected in _transcript(block):
        p = subprocess.run(
            ["sh", "-c", command], cwd=tmp_path, env=shell_env, capture_output=True, text=True
        )
        assert p.returncode == 0, (command, p.stderr)
        got = [_normalize(x) for x in p.stdout.splitlines()]
        assert_lines_match(got, [_normalize(x) for x in expected], what=command)


def test_study_tables_are_the_results_file():
    spec = importlib.util.spec_from_file_location(
        "continuity_study", ROOT / "benchmarks" / "continuity_study.py"
    )
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    doc = json.loads((ROOT / "benchmarks" / "results" / "continuity_study.json").read_text())
    for line in mod.tables(doc).splitlines():
        if line.startswith("|"):
            assert line in TEXT, line
