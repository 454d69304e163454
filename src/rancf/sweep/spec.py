"""``SWEEP.toml``: a base scenario, an analysis and a grid of scenario keys.

.. code-block:: toml

    base = "pendulum.toml"          # a scenario file, path relative to this file
    analysis = "simulate"           # "simulate" | "static" | "modes"
    [grid]
    "mesh.elements" = [2, 4, 8]
    "mesh.k" = ["opt", 0.3]

Grid keys are ``table.key`` names of the scenario; each value is a non-empty list.  The runs are
the Cartesian product in the order the keys are written (the last key varies fastest).  Every
variant is validated before anything runs, so a typo stops the sweep with one line naming it.
"""

from __future__ import annotations

import copy
import itertools
import tomllib
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from rancf.errors import ScenarioError

__all__ = ["SweepSpec", "Variant", "load_sweep", "ANALYSES"]

ANALYSES = ("simulate", "static", "modes")


@dataclass(frozen=True)
class Variant:
    """One run of a sweep: its name, grid values and the full scenario dictionary."""

    index: int
    name: str
    values: dict[str, Any]
    raw: dict[str, Any]


@dataclass(frozen=True)
class SweepSpec:
    """A parsed sweep file."""

    path: Path
    base: Path
    analysis: str
    grid: dict[str, list[Any]]
    base_raw: dict[str, Any]

    def variants(self) -> list[Variant]:
        """The Cartesian product of the grid, as scenario dictionaries."""
        keys = list(self.grid)
        out = []
        for i, combo in enumerate(itertools.product(*(self.grid[k] for k in keys))):
            raw = copy.deepcopy(self.base_raw)
            for key, value in zip(keys, combo, strict=True):
                table, name = key.split(".", 1)
                raw.setdefault(table, {})[name] = value
            values = dict(zip(keys, combo, strict=True))
            label = "_".join(f"{k.split('.')[-1]}={_slug(v)}" for k, v in values.items())
            out.append(Variant(i, f"{i:04d}_{label}"[:120], values, raw))
        return out


def _slug(v: Any) -> str:
    s = repr(v) if not isinstance(v, str) else v
    return "".join(c if c.isalnum() or c in ".-+" else "-" for c in s)


def load_sweep(path: str | Path) -> SweepSpec:
    """Read and validate ``SWEEP.toml`` (and every variant of its base scenario)."""
    from rancf.scenario import parse_scenario

    p = Path(path)
    where = str(p)
    try:
        raw = tomllib.loads(p.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ScenarioError(where, "file", f"cannot be read: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(where, "file", f"is not valid TOML: {exc}") from None
    for k in raw:
        if k not in ("base", "analysis", "grid"):
            raise ScenarioError(where, k, "unknown key (allowed: base, analysis, grid)")
    if not isinstance(raw.get("base"), str):
        raise ScenarioError(where, "base", "required: the base scenario file (a string)")
    analysis = raw.get("analysis", "simulate")
    if analysis not in ANALYSES:
        raise ScenarioError(
            where, "analysis", f"must be one of {', '.join(map(repr, ANALYSES))}, got {analysis!r}"
        )
    grid = raw.get("grid")
    if not isinstance(grid, dict) or not grid:
        raise ScenarioError(where, "grid", 'required: a table of "table.key" = [values]')
    for key, values in grid.items():
        if key.count(".") != 1 or not all(key.split(".")):
            raise ScenarioError(where, f"grid.{key}", 'keys must look like "table.key"')
        if isinstance(values, dict) or not isinstance(values, list) or not values:
            raise ScenarioError(where, f"grid.{key}", f"must be a non-empty list, got {values!r}")
    base = (p.parent / raw["base"]).resolve()
    try:
        base_raw = tomllib.loads(base.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ScenarioError(where, "base", f"{base} cannot be read: {exc.strerror}") from None
    except tomllib.TOMLDecodeError as exc:
        raise ScenarioError(where, "base", f"{base} is not valid TOML: {exc}") from None
    spec = SweepSpec(p, base, analysis, dict(grid), base_raw)
    for v in spec.variants():
        try:
            parse_scenario(copy.deepcopy(v.raw), str(base))
        except ScenarioError as exc:
            raise ScenarioError(where, f"grid (run {v.name})", str(exc)) from None
    return spec
