"""A small TOML writer for scenario dictionaries (tables, arrays of tables, scalars, lists)."""

from __future__ import annotations

import json
import math
from typing import Any

__all__ = ["dumps"]


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


def _table(path: str, d: dict[str, Any], out: list[str]) -> None:
    scalars = [(k, v) for k, v in d.items() if not isinstance(v, dict) and not _is_table_array(v)]
    if path and (scalars or not d):
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
            for item in v:
                out.append(f"[[{sub}]]")
                inner: list[str] = []
                _table("", {kk: vv for kk, vv in item.items()}, inner)
                out.extend(inner)


def dumps(data: dict[str, Any]) -> str:
    """TOML text of ``data`` (as parsed by :mod:`tomllib`, round-trip equal)."""
    out: list[str] = []
    _table("", data, out)
    return "\n".join(out).rstrip() + "\n"
