"""Scenario files (TOML): a model and its analysis, validated strictly.

Every table has a fixed set of keys; an unknown key, a missing required key, a value of the wrong
type or out of range raises :class:`~rancf.errors.ScenarioError` naming the file and the key, so a
typo never passes silently.  See the README for a complete example.
"""

from __future__ import annotations

import tomllib
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError, ScenarioError

if TYPE_CHECKING:
    from rancf.model.analysis import DynamicOptions
    from rancf.model.system import Model

__all__ = ["Scenario", "load_scenario", "parse_scenario", "Sensor", "MAX_ELEMENTS", "K_RANGE"]

_REQ = object()  # marker: required key

#: Largest ``mesh.elements`` (and total number of elements of a NURBS mesh).
MAX_ELEMENTS = 1_000_000
#: The mapping factors a scenario may fix (``mesh.k``); outside, the cubic form degenerates.
K_RANGE = (1e-4, 1.0 - 1e-4)
#: Element kinds of ``mesh.element``.
ELEMENTS = ("rancf", "ancf", "beam", "rod")
#: Sensor kinds (``twist``: rods only).
SENSOR_KINDS = ("distance", "position", "twist")
#: Keys of ``[geometry]`` for each kind.
GEOMETRY_KEYS = {
    "conic": ("start", "end", "angles_deg", "point"),
    "line": ("start", "end"),
    "nurbs": ("degree", "knots", "control_points", "weights"),
    "cad": ("file", "curve"),
}


@dataclass(frozen=True)
class Sensor:
    """A monitored quantity of one or two nodes.

    ``distance`` between two nodes, ``position`` of one node, or (rods) ``twist`` of one node:
    its twist coordinate ``φ`` [rad], the rotation of the cross-section about the tangent
    relative to the reference director carried along with the tangent by smallest rotations
    (docs/rod-derivation.md; cumulative: it is not wrapped to ``(-π, π]``).
    """

    name: str
    kind: str
    nodes: tuple[int, ...]

    def columns(self, dim: int) -> list[str]:
        """CSV column names of the sensor's scalars."""
        if self.kind in ("distance", "twist"):
            return [self.name]
        return [f"{self.name}_{c}" for c in "xyz"[:dim]]

    def evaluate(self, positions: NDArray, twists: NDArray | None = None) -> NDArray[np.float64]:
        """Values ``(n_t, n_columns)`` from node positions ``(n_t, n_nodes, dim)`` and, for
        ``twist``, the nodal twists ``(n_t, n_nodes)``."""
        if self.kind == "distance":
            d = positions[:, self.nodes[1]] - positions[:, self.nodes[0]]
            return np.linalg.norm(d, axis=1)[:, None]
        if self.kind == "twist":
            if twists is None:
                raise InputError(f"sensors.{self.name}", "twist", "a rod model (nodal twists)")
            return twists[:, self.nodes[0], None]
        return positions[:, self.nodes[0]]


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

    def dynamic_options(self) -> DynamicOptions:
        """:class:`~rancf.solvers.dynamic.DynamicOptions` of the ``[solver]`` table."""
        return _guard(self.path, "solver", lambda: _dynamic_options(self.solver))


def _dynamic_options(sv: dict[str, Any]) -> DynamicOptions:
    from rancf.model.analysis import DynamicOptions

    keys = ("t_end", "step", "rho_inf", "adaptive", "rtol", "min_step", "output_step")
    keys += ("newton_tol", "max_newton", "newton")
    return DynamicOptions(**{k: sv[k] for k in keys})


# ---------------------------------------------------------------------------- schema helpers
def _err(path: str, key: str, problem: str) -> ScenarioError:
    return ScenarioError(path, key, problem)


def _number(path: str, key: str, v: Any, positive: bool = False, nonneg: bool = False) -> float:
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise _err(path, key, f"must be a number, got {v!r}")
    f = float(v)
    if not np.isfinite(f):
        raise _err(path, key, f"must be finite, got {v!r}")
    if positive and not f > 0:
        raise _err(path, key, f"must be > 0, got {v!r}")
    if nonneg and f < 0:
        raise _err(path, key, f"must be >= 0, got {v!r}")
    return f


def _integer(path: str, key: str, v: Any, minimum: int | None = None) -> int:
    if isinstance(v, bool) or not isinstance(v, int):
        raise _err(path, key, f"must be an integer, got {v!r}")
    if minimum is not None and v < minimum:
        raise _err(path, key, f"must be >= {minimum}, got {v!r}")
    return int(v)


def _vector(path: str, key: str, v: Any, sizes: tuple[int, ...]) -> list[float]:
    if not isinstance(v, list) or len(v) not in sizes:
        want = " or ".join(str(s) for s in sizes)
        raise _err(path, key, f"must be a list of {want} numbers, got {v!r}")
    return [_number(path, f"{key}[{i}]", x) for i, x in enumerate(v)]


def _choice(path: str, key: str, v: Any, options: tuple[str, ...]) -> str:
    if v not in options:
        raise _err(path, key, f"must be one of {', '.join(repr(o) for o in options)}, got {v!r}")
    return v


def _table(path: str, key: str, v: Any, schema: dict[str, Any]) -> dict[str, Any]:
    if not isinstance(v, dict):
        raise _err(path, key, f"must be a table, got {v!r}")
    for k in v:
        if k not in schema:
            raise _err(path, f"{key}.{k}", f"unknown key (allowed: {', '.join(schema)})")
    out = {}
    for k, default in schema.items():
        if k in v:
            out[k] = v[k]
        elif default is _REQ:
            raise _err(path, f"{key}.{k}", "required key is missing")
        else:
            out[k] = default
    return out


def _place(path: str, key: str, v: Any) -> int:
    if v == "start":
        return 0
    if v == "end":
        return -1
    if isinstance(v, int) and not isinstance(v, bool):
        return v
    raise _err(path, key, f'must be "start", "end" or a node index, got {v!r}')


def _guard(path: str, key: str, fn: Callable[[], Any]) -> Any:
    try:
        return fn()
    except ScenarioError:
        raise
    except InputError as exc:
        raise _err(path, exc.parameter, f"{exc.allowed} (got {_show(exc.value)})") from None


def _show(value: Any) -> str:
    if isinstance(value, float):
        return f"{value:.6g}"
    if isinstance(value, np.ndarray):
        return np.array2string(value, precision=6, separator=", ").replace("\n", "")
    return str(value) if isinstance(value, str) else repr(value)


_TOP = (
    "geometry",
    "mesh",
    "section",
    "material",
    "supports",
    "loads",
    "damping",
    "initial_velocity",
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
    except tomllib.TOMLDecodeError as exc:
        raise _err(str(p), "file", f"is not valid TOML: {exc}") from None
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
    g = _table(
        path,
        "geometry",
        raw["geometry"],
        {
            "kind": _REQ,
            "start": None,
            "end": None,
            "angles_deg": None,
            "point": None,
            "degree": None,
            "knots": None,
            "control_points": None,
            "weights": None,
            "file": None,
            "curve": None,
        },
    )
    kind = _choice(path, "geometry.kind", g["kind"], tuple(GEOMETRY_KEYS))
    for k in g:
        if k != "kind" and g[k] is not None and k not in GEOMETRY_KEYS[kind]:
            raise _err(
                path,
                f"geometry.{k}",
                f"does not apply to kind = {kind!r} (its keys: {', '.join(GEOMETRY_KEYS[kind])})",
            )
    if kind == "cad":
        from rancf.model.cad_geometry import parse_cad_geometry

        dim = parse_cad_geometry(path, g)
    if kind in ("conic", "line"):
        for k in ("start", "end"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", f"required key is missing for kind = {kind!r}")
        g["start"] = _vector(path, "geometry.start", g["start"], (2, 3))
        dim = len(g["start"])
        g["end"] = _vector(path, "geometry.end", g["end"], (dim,))
    if kind == "conic":
        for k in ("angles_deg", "point"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", "required key is missing for kind = 'conic'")
        g["angles_deg"] = _vector(path, "geometry.angles_deg", g["angles_deg"], (2,))
        g["point"] = _vector(path, "geometry.point", g["point"], (dim,))
    if kind == "nurbs":
        for k in ("degree", "knots", "control_points"):
            if g[k] is None:
                raise _err(path, f"geometry.{k}", "required key is missing for kind = 'nurbs'")
        g["degree"] = _integer(path, "geometry.degree", g["degree"], 2)
        if g["degree"] > 3:
            raise _err(path, "geometry.degree", f"must be 2 or 3, got {g['degree']!r}")
        if not isinstance(g["control_points"], list) or not g["control_points"]:
            raise _err(path, "geometry.control_points", "must be a list of points")
        if len(g["control_points"]) < g["degree"] + 1:
            raise _err(
                path,
                "geometry.control_points",
                f"a NURBS of degree {g['degree']} needs at least {g['degree'] + 1} control "
                f"points, got {len(g['control_points'])}",
            )
        first = _vector(path, "geometry.control_points[0]", g["control_points"][0], (2, 3))
        dim = len(first)
        g["control_points"] = [
            _vector(path, f"geometry.control_points[{i}]", p, (dim,))
            for i, p in enumerate(g["control_points"])
        ]
        if not isinstance(g["knots"], list):
            raise _err(path, "geometry.knots", "must be a list of numbers")
        g["knots"] = [_number(path, f"geometry.knots[{i}]", x) for i, x in enumerate(g["knots"])]
        if g["weights"] is not None:
            if not isinstance(g["weights"], list):
                raise _err(path, "geometry.weights", "must be a list of numbers")
            g["weights"] = [
                _number(path, f"geometry.weights[{i}]", x) for i, x in enumerate(g["weights"])
            ]
    d["geometry"] = g

    m = _table(
        path,
        "mesh",
        raw["mesh"],
        {
            "elements": _REQ,
            "element": "rancf",
            "k": "opt",
            "spacing": "arc",
            "quadrature_points": None,
        },
    )
    m["elements"] = _integer(path, "mesh.elements", m["elements"], 1)
    if m["elements"] > MAX_ELEMENTS:
        raise _err(path, "mesh.elements", f"must be at most {MAX_ELEMENTS}, got {m['elements']!r}")
    m["element"] = _choice(path, "mesh.element", m["element"], ELEMENTS)
    if m["k"] != "opt":
        k = _number(path, "mesh.k", m["k"])
        lo, hi = K_RANGE
        if not lo <= k <= hi:
            raise _err(path, "mesh.k", f'must be "opt" or a number in [{lo:g}, {hi:g}], got {k!r}')
        m["k"] = k
    m["spacing"] = _choice(path, "mesh.spacing", m["spacing"], ("arc", "parameter"))
    if m["quadrature_points"] is not None:
        q = _integer(path, "mesh.quadrature_points", m["quadrature_points"], 2)
        if q > 64:
            raise _err(path, "mesh.quadrature_points", f"must be at most 64, got {q!r}")
        m["quadrature_points"] = q
    if m["element"] == "beam" and dim != 2:
        raise _err(path, "mesh.element", "the beam element is planar: use 2-coordinate geometry")
    if m["element"] == "rod" and dim != 3:
        raise _err(path, "mesh.element", "the rod element is spatial: use 3-coordinate geometry")
    d["mesh"] = m

    from rancf.model.scenario_parts import (
        parse_material,
        parse_point_loads,
        parse_section,
        parse_supports,
    )

    el = m["element"]
    d["section"] = parse_section(path, raw["section"], el)
    d["material"] = parse_material(path, raw["material"], el)

    d["supports"] = parse_supports(path, raw.get("supports", []), el)

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

    sv = _table(
        path,
        "solver",
        raw.get("solver", {}),
        {
            "t_end": 1.0,
            "step": 1e-3,
            "rho_inf": 0.9,
            "load_steps": 10,
            "adaptive": False,
            "rtol": 1e-5,
            "output_step": None,
            "min_step": None,
            "newton_tol": 1e-10,
            "max_newton": 12,
            "newton": "full",
        },
    )
    sv["t_end"] = _number(path, "solver.t_end", sv["t_end"], positive=True)
    sv["step"] = _number(path, "solver.step", sv["step"], positive=True)
    sv["rho_inf"] = _number(path, "solver.rho_inf", sv["rho_inf"])
    if not 0 <= sv["rho_inf"] <= 1:
        raise _err(path, "solver.rho_inf", f"must be in [0, 1], got {sv['rho_inf']!r}")
    sv["load_steps"] = _integer(path, "solver.load_steps", sv["load_steps"], 1)
    if not isinstance(sv["adaptive"], bool):
        raise _err(path, "solver.adaptive", f"must be true or false, got {sv['adaptive']!r}")
    sv["rtol"] = _number(path, "solver.rtol", sv["rtol"], positive=True)
    for k in ("output_step", "min_step"):
        if sv[k] is not None:
            sv[k] = _number(path, f"solver.{k}", sv[k], positive=True)
    sv["newton_tol"] = _number(path, "solver.newton_tol", sv["newton_tol"], positive=True)
    sv["max_newton"] = _integer(path, "solver.max_newton", sv["max_newton"], 1)
    sv["newton"] = _choice(path, "solver.newton", sv["newton"], ("full", "modified"))
    d["solver"] = sv
    _guard(path, "solver", lambda: _dynamic_options(sv))

    md = _table(path, "modes", raw.get("modes", {}), {"count": 6, "about": "reference"})
    md["count"] = _integer(path, "modes.count", md["count"], 1)
    md["about"] = _choice(path, "modes.about", md["about"], ("reference", "static"))
    d["modes"] = md

    sens = raw.get("sensors", [])
    if not isinstance(sens, list):
        raise _err(path, "sensors", "must be an array of tables [[sensors]]")
    sensors = []
    names: set[str] = set()
    for i, sn in enumerate(sens):
        t = _table(
            path, f"sensors[{i}]", sn, {"name": _REQ, "kind": _REQ, "between": None, "at": None}
        )
        if not isinstance(t["name"], str) or not t["name"].isidentifier():
            raise _err(path, f"sensors[{i}].name", f"must be a simple name, got {t['name']!r}")
        if t["name"] in names or t["name"] == "t":
            raise _err(path, f"sensors[{i}].name", f"{t['name']!r} is used twice or reserved")
        names.add(t["name"])
        kd = _choice(path, f"sensors[{i}].kind", t["kind"], SENSOR_KINDS)
        if kd == "twist" and m["element"] != "rod":
            raise _err(
                path, f"sensors[{i}].kind", f"'twist' needs rod elements (mesh.element = \"rod\"), "
                f"not {m['element']!r}",
            )  # fmt: skip
        if kd == "distance":
            b = t["between"]
            if t["at"] is not None or not isinstance(b, list) or len(b) != 2:
                raise _err(
                    path, f"sensors[{i}].between", "a distance sensor needs between = [A, B]"
                )
            nodes = tuple(_place(path, f"sensors[{i}].between[{j}]", x) for j, x in enumerate(b))
        else:
            if t["between"] is not None or t["at"] is None:
                raise _err(path, f"sensors[{i}].at", f"a {kd} sensor needs at = PLACE")
            nodes = (_place(path, f"sensors[{i}].at", t["at"]),)
        sensors.append(Sensor(t["name"], kd, nodes))
    return Scenario(path, d, dim, tuple(sensors))
