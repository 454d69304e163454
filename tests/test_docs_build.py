"""The documentation builds with warnings as errors, and its generated references are complete.

One Sphinx build (``python -m sphinx -W --keep-going -b html``) of a copy of ``docs/`` per test
session (sphinx-gallery writes into its source folder, so the repository stays untouched); it
fails on any warning: a broken cross-reference, a docstring that does not parse, a gallery
script that raises. The checks after it read the built HTML: every scenario key ``rancf schema``
knows has its row, every command its section, every public name its entry, every shipped
example its executed gallery page with a figure.
"""

from __future__ import annotations

import html
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from rancf import _API, scenario_schema
from rancf.cli import COMMAND_MODULES
from rancf.cli.files import shipped_scenarios
from tests.pages import DOCS


@pytest.fixture(scope="module")
def built(tmp_path_factory) -> Path:
    src = tmp_path_factory.mktemp("docs") / "docs"
    shutil.copytree(DOCS, src, ignore=shutil.ignore_patterns("_build", "gallery"))
    out = src.parent / "html"
    start = time.perf_counter()
    p = subprocess.run(
        [
            sys.executable,
            "-m",
            "sphinx",
            "-W",
            "--keep-going",
            "-q",
            "-b",
            "html",
            str(src),
            str(out),
        ],
        capture_output=True,
        text=True,
    )
    print(f"docs built in {time.perf_counter() - start:.1f} s")
    assert p.returncode == 0, p.stderr[-5000:]
    assert "WARNING" not in p.stderr and "ERROR" not in p.stderr, p.stderr[-5000:]
    return out


def _html(built: Path, page: str) -> str:
    return (built / page).read_text(encoding="utf-8")


def _schema_keys() -> list[tuple[str, str, dict]]:
    """``(model, key, schema node)`` of every key of every table the schema knows."""
    schema = scenario_schema()
    keys = [("scenario", k, p) for k, p in schema["properties"].items()]
    for model, node in schema["$defs"].items():
        keys += [(model, k, p) for k, p in node.get("properties", {}).items()]
    return keys


KEYS = _schema_keys()


def test_every_scenario_key_is_documented(built):
    page = _html(built, "reference/scenario.html")
    assert len(KEYS) > 100
    missing = []
    for model, key, node in KEYS:
        row = re.search(
            rf'<tr[^>]*>\s*<td[^>]*><p id="key-{model.lower()}-{key.lower()}".*?</tr>',
            page,
            flags=re.S,
        )
        text = html.unescape(re.sub(r"<[^>]+>", "", row.group(0))) if row else ""
        if not row or node["description"] not in text or "default" in node and not text:
            missing.append(f"{model}.{key}")
    assert missing == []


def test_scenario_rows_show_defaults_and_units(built):
    page = _html(built, "reference/scenario.html")
    row = re.search(r'<p id="key-solvertable-t_end".*?</tr>', page, flags=re.S).group(0)
    cells = [
        html.unescape(re.sub(r"<[^>]+>", "", c)).strip()
        for c in re.findall(r"<td.*?</td>", row, re.S)
    ]
    assert cells == ["number", "1", "> 0", "s", "end time [s]"]


def test_every_command_is_documented(built):
    page = _html(built, "reference/cli.html")
    commands = [c for cmds in COMMAND_MODULES.values() for c in cmds]
    assert len(commands) >= 13
    for command in commands:
        assert re.search(rf'<section id="rancf-{command}"', page), command


def test_every_public_name_is_documented(built):
    page = _html(built, "reference/api.html")
    assert [n for n in _API if f'id="rancf.{n}"' not in page] == []


def test_every_shipped_example_runs_in_the_gallery(built):
    """One gallery page per shipped scenario, executed (its figure and its output shown)."""
    for name in shipped_scenarios():
        page = built / "gallery" / f"plot_{name.replace('-', '_')}.html"
        assert page.exists(), name
        text = _html(built, f"gallery/{page.name}")
        assert re.search(r'<img [^>]*src="\.\./_images/sphx_glr_plot_', text), name


#: Shipped examples whose fixed steps do not resolve everything they excite (a release or a
#: load at t = 0, an impact, undamped vibrations), which ``rancf simulate`` says in its local
#: error warning (docs/guide/time-integration.md); each is to be looked at and resolved, and
#: this list only shrinks.
#: (crane-hoist steps adaptively: fixed steps do not resolve its rope's contact onsets.)
UNRESOLVED: set[str] = set()


def test_gallery_scripts_run_cleanly(built):
    """No script of the gallery prints a warning (a deprecation, a unit warning of rancf), but
    the local error warning of the examples of :data:`UNRESOLVED`."""
    pages = sorted((built / "gallery").glob("plot_*.html"))
    assert len(pages) > len(shipped_scenarios())
    error = re.compile(r"[^<\n]*rancf: warning: the local error estimate is [^<\n]*")
    quiet = []  # listed, but not warned: off the list
    for page in pages:
        text = page.read_text(encoding="utf-8")
        if page.stem.removeprefix("plot_") in UNRESOLVED:
            quiet += [] if error.search(text) else [page.stem]
            text = error.sub("", text)
        assert not re.search(r"Warning\b|rancf: warning", text), page.name
    assert quiet == []
