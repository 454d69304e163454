"""A small TOML writer for scenario dictionaries (tables, arrays of tables, scalars, lists), and
the copy of a scenario a run folder keeps."""

from __future__ import annotations

import copy
import json
import math
from pathlib import Path
from typing import Any

__all__ = ["dumps", "with_absolute_paths", "scenario_copy"]


def _value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if not math.isfinite(v):
            raise ValueError(f"TOML cannot hold {v!r}")
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v, ensure_ascii=False)
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise ValueError(f"TOML writer: unsupported value {v!r}")


def _is_table_array(v: Any) -> bool:
    return isinstance(v, list) and bool(v) and all(isinstance(x, dict) for x in v)


def _table(path: str, d: dict[str, Any], out: list[str], header: bool = True) -> None:
    scalars = [(k, v) for k, v in d.items() if not isinstance(v, dict) and not _is_table_array(v)]
    if header and path and (scalars or not d):
        out.append(f"[{path}]")
    for k, v in scalars:
        out.append(f"{json.dumps(k) if not k.isidentifier() else k} = {_value(v)}")
    if scalars:
        out.append("")
    for k, v in d.items():
        sub = f"{path}.{k}" if path else k
        if isinstance(v, dict):
            _table(sub, v, out)
        elif _is_table_array(v):
            for item in v:  # its sub-tables under their full names ([bodies.geometry])
                out.append(f"[[{sub}]]")
                _table(sub, item, out, header=False)


def dumps(data: dict[str, Any]) -> str:
    """TOML text of ``data`` (as parsed by :mod:`tomllib`, round-trip equal)."""
    out: list[str] = []
    _table("", data, out)
    return "\n".join(out).rstrip() + "\n"


def with_absolute_paths(raw: dict[str, Any], base: str | Path) -> dict[str, Any]:
    """A copy of the scenario dictionary ``raw`` read from ``base`` whose CAD ``file`` (of the
    geometry and of every body's) and CSV ``table`` files (paths relative to ``base``) are
    absolute, so that the copy can live in another folder."""
    from rancf.scenario.table_files import absolute_table_paths

    raw = absolute_table_paths(copy.deepcopy(raw), base)  # table = "file.csv"
    _absolute_cad(raw, Path(base).parent)
    return raw


def _absolute_cad(node: Any, folder: Path) -> None:
    """Every ``kind = "cad"`` table's ``file`` in ``node`` (in place) made absolute against
    ``folder``: ``[geometry]`` and each ``[bodies.geometry]``."""
    if isinstance(node, dict):
        if node.get("kind") == "cad" and isinstance(node.get("file"), str):
            node["file"] = str((folder / node["file"]).resolve())
        for value in node.values():
            _absolute_cad(value, folder)
    elif isinstance(node, list):
        for item in node:
            _absolute_cad(item, folder)


def scenario_copy(text: str, raw: dict[str, Any], base: str | Path) -> str:
    """The text of a run folder's ``scenario.toml``: the scenario file's own ``text`` (comments
    kept), or, when it names a CAD file by a relative path, ``raw`` written with that path made
    absolute."""
    fixed = with_absolute_paths(raw, base)
    return text if fixed == raw else dumps(fixed)
