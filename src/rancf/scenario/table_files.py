"""Tables read from CSV files: ``table = "path.csv"`` wherever a table of rows is accepted.

The path is relative to the scenario file (to the current folder for a scenario built in
Python).  The file holds one row a line, numbers separated by commas; blank lines and lines
starting with ``#`` are skipped, and a first line none of whose cells is a number is a header
(column names); a first line of numbers is data.  Anything else — a missing or unreadable file
(a loop of symbolic links), a cell that is not a finite number (in a line with numbers), rows of
different lengths — is refused in one line naming the file, the line and the cell.
A run folder's copy of the scenario names the file by its absolute path
(:func:`absolute_table_paths`), so that the copy reads the same table wherever it lies.
"""

from __future__ import annotations

import csv
import math
from pathlib import Path
from typing import Any

from pydantic import ValidationInfo

from rancf.scenario.base import fail

__all__ = [
    "read_table",
    "table_rows",
    "absolute_table_paths",
    "TABLE_KEY",
    "FILE_KEYS",
    "ROWS_SCHEMA",
]

#: The key whose text value names a CSV file.
TABLE_KEY = "table"
#: Every key whose text value names a CSV file (``[fluid] waves = { elevation = "eta.csv" }``).
FILE_KEYS = (TABLE_KEY, "elevation")


#: The JSON Schema of a table: rows of numbers, or a CSV file's name.
ROWS_SCHEMA = {
    "anyOf": [
        {"type": "array", "minItems": 2, "items": {"type": "array", "items": {"type": "number"}}},
        {"type": "string", "minLength": 1},
    ]
}


def table_rows(v: Any, info: ValidationInfo) -> Any:
    """A table's value as validated: rows as given, or the rows of the CSV file it names
    (a pydantic before-validator: the scenario's path is in the validation context)."""
    if isinstance(v, str):
        return read_table(v, str((info.context or {}).get("path", "<scenario>")))
    return v


def _base(scenario_path: str) -> Path:
    return Path(scenario_path).parent if not scenario_path.startswith("<") else Path.cwd()


def read_table(file: str, scenario_path: str) -> list[list[float]]:
    """The rows of CSV file ``file`` (relative to the folder of ``scenario_path``).

    Raises
    ------
    pydantic_core.PydanticCustomError
        One line naming the file (and line and cell) and the problem, for the key that names
        the file.
    """
    path = _absolute(_base(scenario_path) / file)
    try:
        with open(path, encoding="utf-8-sig", newline="") as fh:  # a byte-order mark: no cell
            lines = list(csv.reader(fh))
    except FileNotFoundError:
        raise fail("", f"the CSV file {path} does not exist") from None
    except (OSError, UnicodeDecodeError, csv.Error) as exc:
        why = exc.strerror if isinstance(exc, OSError) and exc.strerror else exc
        raise fail("", f"the CSV file {path} cannot be read ({why})") from None
    rows: list[list[float]] = []
    first = True
    for number, cells in enumerate(lines, start=1):
        cells = [c.strip() for c in cells]
        if not any(cells) or cells[0].startswith("#"):
            continue
        if first and not any(_is_number(c) for c in cells):  # column names
            first = False
            continue
        bad = next((c for c in cells if not _is_number(c)), None)
        if bad is not None:
            hint = " (a header line holds names only, a data line numbers only)" if first else ""
            raise fail("", f"{path} line {number}: {bad!r} is not a number{hint}")
        first = False
        row = [float(c) for c in cells]
        if not all(math.isfinite(x) for x in row):
            raise fail("", f"{path} line {number}: the numbers must be finite")
        if rows and len(row) != len(rows[0]):
            raise fail(
                "",
                f"{path} line {number}: {len(row)} numbers, but the first row has {len(rows[0])}",
            )
        rows.append(row)
    if len(rows) < 2:
        raise fail(
            "", f"{path} holds {len(rows)} rows of numbers: at least 2 rows [t, v...] are needed"
        )
    return rows


def _absolute(path: Path) -> Path:
    """``path`` absolute, its links resolved where they can be (a loop of symbolic links
    stays as named: opening it is refused)."""
    try:
        return path.resolve()
    except (OSError, RuntimeError):  # RuntimeError: a symlink loop (Python < 3.13)
        return path.absolute()


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def absolute_table_paths(raw: Any, scenario_path: str | Path) -> Any:
    """``raw`` (a parsed scenario, changed in place) with every ``table = "file"`` (and
    ``elevation = "file"``) made absolute against the folder of ``scenario_path``; returns
    ``raw``."""
    if isinstance(raw, dict):
        for key, value in raw.items():
            if key in FILE_KEYS and isinstance(value, str):
                raw[key] = str(_absolute(_base(str(scenario_path)) / value))
            else:
                absolute_table_paths(value, scenario_path)
    elif isinstance(raw, list):
        for item in raw:
            absolute_table_paths(item, scenario_path)
    return raw
