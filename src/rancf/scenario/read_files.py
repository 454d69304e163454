"""The files a scenario reads besides itself — CSV tables (``table = "file.csv"``) and CAD files
(``kind = "cad"``, ``file = ...``) — and digests of their contents, so that a result computed
from a file is not taken for the result of the file as it is now (a sweep's finished runs,
``rancf simulate --resume``)."""

from __future__ import annotations

import hashlib
from pathlib import Path
from typing import Any

from rancf.scenario.table_files import FILE_KEYS

__all__ = ["read_file_paths", "file_digests", "changed_file"]

#: The digest of a file that cannot be read.
UNREADABLE = "unreadable"


def read_file_paths(raw: Any, scenario_path: str | Path) -> list[Path]:
    """The files the parsed scenario ``raw`` (read from ``scenario_path``) names, absolute
    (relative names are relative to the scenario's folder), sorted, each once."""
    base = Path(scenario_path).parent
    found: set[Path] = set()

    def walk(node: Any) -> None:
        if isinstance(node, dict):
            for key, value in node.items():
                if key in FILE_KEYS and isinstance(value, str):
                    found.add((base / value).resolve())
                else:
                    walk(value)
            if node.get("kind") == "cad" and isinstance(node.get("file"), str):
                found.add((base / node["file"]).resolve())
        elif isinstance(node, list):
            for item in node:
                walk(item)

    walk(raw)
    return sorted(found)


def _digest(path: Path) -> str:
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    except OSError:
        return UNREADABLE
    return h.hexdigest()


def file_digests(raw: Any, scenario_path: str | Path) -> dict[str, str]:
    """SHA-256 of the contents of every file :func:`read_file_paths` names, by absolute path
    (:data:`UNREADABLE` for a file that cannot be read)."""
    return {str(p): _digest(p) for p in read_file_paths(raw, scenario_path)}


def changed_file(earlier: dict[str, str], now: dict[str, str]) -> str | None:
    """The first file whose digest differs between ``earlier`` and ``now`` (or that only one
    of them names), or None."""
    for path in sorted(set(earlier) | set(now)):
        if earlier.get(path) != now.get(path):
            return path
    return None
