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

from rancf.bodies.families import family
from rancf.errors import RunTooLargeError, ScenarioError, shorten

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
    raw = read_toml(p, where, "file")
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
    base_raw = read_toml(base, where, "base")
    for key in grid:
        _check_table(where, key, base_raw)
    spec = SweepSpec(p, base, analysis, dict(grid), base_raw)
    for v in spec.variants():
        try:
            sc = parse_scenario(copy.deepcopy(v.raw), str(base))
            if analysis == "simulate":
                _check_size(sc)
        except (ScenarioError, RunTooLargeError) as exc:
            raise ScenarioError(where, f"grid (run {v.name})", str(exc)) from None
    return spec


def _check_table(where: str, key: str, base_raw: dict[str, Any]) -> None:
    """Refuse a grid key ``table.key`` whose table is not a table of the base scenario (an
    array of tables such as ``[[winches]]``, or a value)."""
    table = key.split(".", 1)[0]
    have = base_raw.get(table)
    if have is None or isinstance(have, dict):
        return
    what = f"an array of tables ([[{table}]])" if isinstance(have, list) else "a value"
    raise ScenarioError(
        where,
        f"grid.{key}",
        f"{table!r} is {what} in the base scenario, not "
        f"a table: a grid key names a key of a table ([{table}] key = ...); "
        "sweep a copy of the base file per value instead",
    )


def _check_size(sc: Any) -> None:
    """Refuse a variant whose files would exceed a sweep run's disk limit, counting its nodes
    from the meshes' ``elements`` (a lower bound: NURBS and CAD meshes have at least as many;
    a system: its flexible bodies'), so no model is built."""
    from rancf.post.run_plan import check_output_size
    from rancf.sweep.runner import LIMIT, MAX_RUN_GB

    meshes = [b["mesh"] for b in sc.data["bodies"] if b.get("mesh")]
    n_q = n_rods = 0
    for mesh in meshes:
        n_nodes = mesh["elements"] + 1
        fam = family(mesh["element"])
        n_q += n_nodes * fam.dofs_per_node(sc.dim)
        n_rods += 3 * n_nodes if fam.has_triads else 0
    n_cols = sum(len(s.columns(sc.dim)) for s in sc.sensors)
    n_out = sc.dynamic_options().n_outputs
    check_output_size(sc.path, n_out, n_q, n_cols, n_rods, MAX_RUN_GB, LIMIT)


def read_toml(path: Path, where: str, key: str) -> dict[str, Any]:
    """A TOML file as a dictionary; errors (unreadable, not UTF-8, not TOML, nested too deeply)
    name ``where`` and ``key``."""
    what = "" if key == "file" else f"{path} "
    try:
        return tomllib.loads(path.read_text(encoding="utf-8"))
    except OSError as exc:
        raise ScenarioError(where, key, f"{what}cannot be read: {exc.strerror}") from None
    except UnicodeDecodeError:
        raise ScenarioError(where, key, f"{what}is not UTF-8 text") from None
    except RecursionError:
        raise ScenarioError(where, key, f"{what}is nested too deeply") from None
    except ValueError as exc:  # TOMLDecodeError, or an integer of more than 4300 digits
        raise ScenarioError(where, key, f"{what}is not valid TOML: {shorten(str(exc))}") from None
