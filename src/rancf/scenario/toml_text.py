"""Scenario TOML text that reads like a hand-written file: short arrays on one line, a table's
rows one a line, long lists of numbers wrapped (:mod:`tomli_w` writes one number a line)."""

from __future__ import annotations

import re
import tomllib
from typing import Any

__all__ = ["dumps"]

#: Width the compact arrays keep within.
WIDTH = 99

#: A multi-line array whose items hold no brackets (the innermost ones), one item a line.
_INNERMOST = re.compile(r"\[\n((?:[ \t]*[^\[\]\n]*,\n)+)([ \t]*)\]")


def _compact(text: str) -> str:
    def inline(match: re.Match[str]) -> str:
        items = [line.strip().removesuffix(",") for line in match.group(1).splitlines()]
        start = text.rfind("\n", 0, match.start()) + 1
        prefix = len(text[start : match.start()].expandtabs())
        one = "[" + ", ".join(items) + "]"
        if prefix + len(one) + 1 <= WIDTH:
            return one
        indent = match.group(2) + "    "
        lines, line = [], ""
        for item in items:  # several numbers a line
            if line and len(indent) + len(line) + len(item) + 2 > WIDTH:
                lines.append(line.rstrip())
                line = ""
            line += f"{item}, "
        lines.append(line.rstrip())
        return "[\n" + "".join(f"{indent}{x}\n" for x in lines) + f"{match.group(2)}]"

    return _INNERMOST.sub(inline, text)


def dumps(data: dict[str, Any]) -> str:
    """TOML text of ``data`` (:func:`tomli_w.dumps`) with compact arrays; the text reads back
    as ``data`` (else :mod:`tomli_w`'s own text is returned)."""
    import tomli_w

    text = tomli_w.dumps(data)
    compact = _compact(text)
    try:
        same = tomllib.loads(compact) == tomllib.loads(text)
    except tomllib.TOMLDecodeError:  # pragma: no cover - a string the pattern misread
        same = False
    return compact if same else text
