"""The Markdown pages whose examples the tests run: the README and every page of ``docs/``.

:data:`PAGES` is the list; :func:`blocks` finds a page's fenced code blocks of one language,
:func:`section` the text under one heading of a page (to its next heading of the same or a
higher level), :func:`transcript` the commands and expected output of a ``console`` block.
"""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
DOCS = ROOT / "docs"
#: Folders of ``docs/`` that hold built or generated files, not pages.
_NOT_PAGES = ("_build", "gallery")

#: The README first, then every Markdown page of docs/ (the user guide, reference, ...).
PAGES: list[Path] = [README] + sorted(
    p for p in DOCS.rglob("*.md") if not set(p.relative_to(DOCS).parts) & set(_NOT_PAGES)
)


def name(page: Path) -> str:
    """``README.md``, ``docs/guide/outputs.md``: a page as the test ids show it."""
    return page.relative_to(ROOT).as_posix()


def text(page: Path) -> str:
    return page.read_text(encoding="utf-8")


def blocks(source: str, lang: str) -> list[str]:
    """The fenced ```` ```lang ```` blocks of a page's (or a section's) text, in order."""
    return re.findall(rf"^```{lang}\n(.*?)^```", source, flags=re.S | re.M)


def section(page: Path, title: str) -> str:
    """The text under the heading of ``page`` that starts with ``title`` (``#`` marks not
    included), up to the next heading of the same or a higher level (lines inside code blocks,
    such as TOML comments, are no headings)."""
    lines = text(page).splitlines(keepends=True)
    fence, start, level = False, None, 0
    for i, line in enumerate(lines):
        if line.startswith("```"):
            fence = not fence
        m = None if fence else re.match(r"(#+) ", line)
        if m and start is None and line[m.end() :].startswith(title):
            start, level = i, len(m.group(1))
        elif m and start is not None and len(m.group(1)) <= level:
            return "".join(lines[start:i])
    if start is None:
        raise LookupError(f"{name(page)}: no heading {title!r}")
    return "".join(lines[start:])


def transcript(block: str) -> list[tuple[str, list[str]]]:
    """``(command, expected output lines)`` for every ``$ `` line of a console block."""
    steps: list[tuple[str, list[str]]] = []
    for line in block.splitlines():
        if line.startswith("$ "):
            steps.append((line[2:], []))
        elif steps:
            steps[-1][1].append(line)
    return steps
