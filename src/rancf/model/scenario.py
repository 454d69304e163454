"""Scenario files (TOML): a model and its analysis, validated strictly.

Every table has a fixed set of keys; an unknown key, a missing required key, a value of the wrong
type or out of range raises :class:`~rancf.errors.ScenarioError` naming the file and the key, so a
typo never passes silently.  See the README for a complete example.
"""

from __future__ import annotations

import tomllib
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from rancf.errors import shorten
from rancf.model.scenario_checks import _REQ, _err, _guard, _number, _place, _table, _vector
from rancf.model.scenario_parts import (
    parse_initial_motion,
    parse_material,
    parse_point_loads,
    parse_section,
    parse_supports,
)
from rancf.model.scenario_sensors import Sensor, parse_sensors
from rancf.model.scenario_tables import (
    dynamic_options,
    parse_geometry,
    parse_mesh,
    parse_modes,
    parse_solver,
)

if TYPE_CHECKING:
    from rancf.model.analysis import DynamicOptions
    from rancf.model.system import Model

__all__ = ["Scenario", "load_scenario", "parse_scenario", "Sensor"]


@dataclass(frozen=True)
class Scenario:
    """A parsed, validated scenario."""

    path: str
    data: dict[str, Any]
    dim: int
    sensors: tuple[Sensor, ...] = field(default_factory=tuple)

    @property
    def solver(self) -> dict[str, Any]:
        """The ``[solver]`` table with defaults filled in."""
        return self.data["solver"]

    def build_model(self) -> Model:
        """Mesh the geometry and assemble the model (errors name the scenario key)."""
        from rancf.model.scenario_model import build_model

        return build_model(self)

    @property
    def support_labels(self) -> list[int | str]:
        """Each support's ``at`` as written (``"start"``, ``"end"`` or a node index)."""
        return [t["label"] for t in self.data["supports"]]

    def installed_support(self) -> str | None:
        """The key of the first support installed away from its reference (``position`` or
        ``direction``), or None."""
        for i, t in enumerate(self.data["supports"]):
            for k in ("position", "direction"):
                if t[k] is not None:
                    return f"supports[{i}].{k}"
        return None

    def dynamic_options(self) -> DynamicOptions:
        """:class:`~rancf.solvers.dynamic.DynamicOptions` of the ``[solver]`` table."""
        return _guard(self.path, "solver", lambda: dynamic_options(self.solver))


_TOP = (
    "geometry",
    "mesh",
    "section",
    "material",
    "supports",
    "loads",
    "damping",
    "initial_velocity",
    "initial_motion",
    "solver",
    "sensors",
    "modes",
)


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a TOML scenario file."""
    p = Path(path)
    try:
        data = p.read_bytes()
    except OSError as exc:
        raise _err(str(p), "file", f"cannot be read: {exc.strerror}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[: exc.start].count(b"\n") + 1
        raise _err(
            str(p), "file", f"is not UTF-8 text (byte {exc.start}, line {line}); save it as UTF-8"
        ) from None
    try:
        raw = tomllib.loads(text)
    except RecursionError:
        raise _err(
            str(p), "file", "is nested too deeply (arrays or tables within each other)"
        ) from None
    except ValueError as exc:  # TOMLDecodeError, or an integer of more than 4300 digits
        raise _err(str(p), "file", f"is not valid TOML: {shorten(str(exc))}") from None
    return parse_scenario(raw, str(p))


def parse_scenario(raw: dict[str, Any], path: str = "<scenario>") -> Scenario:
    """Validate a scenario given as a dictionary (the parsed TOML)."""
    for k in raw:
        if k not in _TOP:
            raise _err(path, k, f"unknown table (allowed: {', '.join(_TOP)})")
    for k in ("geometry", "mesh", "section", "material"):
        if k not in raw:
            raise _err(path, k, "required table is missing")
    d: dict[str, Any] = {}
    g, dim = parse_geometry(path, raw["geometry"])
    d["geometry"] = g

    m = parse_mesh(path, raw["mesh"], dim)
    d["mesh"] = m

    el = m["element"]
    d["section"] = parse_section(path, raw["section"], el)
    d["material"] = parse_material(path, raw["material"], el)

    d["supports"] = parse_supports(path, raw.get("supports", []), el, dim)

    ld = _table(path, "loads", raw.get("loads", {}), {"gravity": None, "point": []})
    if ld["gravity"] is not None:
        ld["gravity"] = _vector(path, "loads.gravity", ld["gravity"], (dim,))
    ld["point"] = parse_point_loads(path, ld["point"], dim, el)
    d["loads"] = ld

    dm = _table(path, "damping", raw.get("damping", {}), {"mass_proportional": 0.0})
    dm["mass_proportional"] = _number(
        path, "damping.mass_proportional", dm["mass_proportional"], nonneg=True
    )
    d["damping"] = dm

    ivs = raw.get("initial_velocity", [])
    if not isinstance(ivs, list):
        raise _err(path, "initial_velocity", "must be an array of tables [[initial_velocity]]")
    d["initial_velocity"] = []
    for i, iv in enumerate(ivs):
        t = _table(path, f"initial_velocity[{i}]", iv, {"at": _REQ, "value": _REQ})
        t["at"] = _place(path, f"initial_velocity[{i}].at", t["at"])
        t["value"] = _vector(path, f"initial_velocity[{i}].value", t["value"], (dim,))
        d["initial_velocity"].append(t)

    d["initial_motion"] = parse_initial_motion(path, raw.get("initial_motion"), dim)
    if d["initial_motion"] is not None and d["initial_velocity"]:
        raise _err(
            path, "initial_motion", "give [initial_motion] or [[initial_velocity]], not both"
        )

    d["solver"] = parse_solver(path, raw.get("solver", {}))

    d["modes"] = parse_modes(path, raw.get("modes", {}))

    sensors = parse_sensors(path, raw.get("sensors", []), m["element"], dim)
    return Scenario(path, d, dim, sensors)
