"""docs/guide/closed-curves.md holds a ring and a C² example (their console transcripts are run
by tests/test_readme.py, as every page's) and its study tables are those of
benchmarks/results/continuity_study.json."""

from __future__ import annotations

import importlib.util
import json
import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGE = ROOT / "docs" / "guide" / "closed-curves.md"
TEXT = PAGE.read_text(encoding="utf-8")
CONSOLE = re.findall(r"```console\n(.*?)```", TEXT, flags=re.S)


def test_page_has_ring_and_c2_examples():
    assert len(CONSOLE) >= 4
    assert any("ring.toml" in b for b in CONSOLE)
    assert any('continuity = "C2"' in b for b in CONSOLE)


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
