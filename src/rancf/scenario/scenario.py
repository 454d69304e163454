"""The scenario: a model (one flexible body, or ``[[bodies]]`` with joints and springs) and its
analysis, as a TOML file or built in Python — one typed description for both.

    >>> sc = Scenario(geometry={"kind": "line", "start": [0, 0], "end": [1, 0]},
    ...               mesh={"elements": 4}, section={"radius": 0.01},
    ...               material={"density": 7800, "youngs_modulus": 2e11})

Every table has a fixed set of keys: an unknown key, a missing required key, a value of the wrong
type or out of range, or a meaningless combination raises :class:`~rancf.errors.ScenarioError`
naming the file (``<scenario>`` for one built in Python) and the key
(``geometry.angles_deg[1]``), so a typo never passes silently.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any

from pydantic import Field, PrivateAttr, ValidationError, ValidationInfo, model_validator

from rancf.errors import ScenarioError
from rancf.scenario.base import ContactPoints, Name, NonNegative, Table, fail, show
from rancf.scenario.bodies import Body, FlexibleBody
from rancf.scenario.checks import check_scenario
from rancf.scenario.damping import DampingTable
from rancf.scenario.files import deferred_interrupts, read_toml, write_atomic
from rancf.scenario.fluid import FluidTable, HydroTable
from rancf.scenario.geometry import GEOMETRY_KEYS, CadGeometry, Geometry, MeshTable
from rancf.scenario.joints import JointTable, SpringTable
from rancf.scenario.loads import (
    InitialMotionTable,
    InitialVelocityTable,
    LoadsTable,
    SupportTable,
    time_function,
)
from rancf.scenario.messages import scenario_error
from rancf.scenario.motions import motion_function, start_warnings
from rancf.scenario.obstacles import ObstacleTable
from rancf.scenario.section import MaterialTable, SectionTable
from rancf.scenario.sensors import Sensor, SensorTable
from rancf.scenario.solver import ModesTable, SolverTable
from rancf.scenario.winches import WinchTable

if TYPE_CHECKING:
    from rancf.bodies.flexible import Model
    from rancf.options import DynamicOptions
    from rancf.scenario.places import ResolvedPlace
    from rancf.system import System

__all__ = ["Scenario", "load_scenario", "parse_scenario"]

_PYTHON = "<scenario>"


class Scenario(Table):
    """A validated scenario (module docstring); the keys of the file are its fields.

    Attributes besides the tables: :attr:`path` (the file, or ``<scenario>``), :attr:`dim`
    (2 or 3), :attr:`data` (every table as plain dictionaries, defaults filled in),
    :attr:`sensors` (the :class:`~rancf.scenario.sensors.Sensor` records of ``[[sensors]]``).
    """

    geometry: Geometry | None = None
    mesh: MeshTable | None = Field(None, description="one-body file: the elements")
    section: SectionTable | None = Field(None, description="one-body file: the cross-section")
    material: MaterialTable | None = Field(None, description="one-body file: the material")
    bodies: list[Body] = Field([], description="a system: flexible, rigid and point-mass bodies")
    joints: list[JointTable] = Field([], description="joints between two places")
    springs: list[SpringTable] = Field([], description="spring-dampers between two places")
    obstacles: list[ObstacleTable] = Field([], description="rigid obstacles the bodies touch")
    winches: list[WinchTable] = Field(
        [], description="cables paid out or reeled in at an end of a flexible body"
    )
    body_contacts: list[list[Name]] = Field(
        [],
        description="pairs [BODY, BODY] of flexible bodies in contact with each other (a body "
        "twice: self-contact; friction: body_friction)",
    )
    body_friction: NonNegative = Field(
        0.0, description="Coulomb coefficient of the contact between flexible bodies"
    )
    contact_points: ContactPoints = Field(
        8,
        description="Gauss points per element where contact is evaluated (at most a tube "
        "radius apart resolves crossings of tubes)",
    )
    contacts: list[list[Name]] | None = Field(
        None,
        description="the pairs [BODY, OBSTACLE] in contact (default: every flexible body "
        "with every obstacle)",
    )
    supports: list[SupportTable] = Field([], description="places held fixed or moved")
    loads: LoadsTable = Field(
        default_factory=LoadsTable, description="gravity, point and distributed loads"
    )
    fluid: FluidTable | None = Field(None, description="the fluid the bodies are in")
    hydro: HydroTable | None = Field(
        None, description="one-body file: the body's hydrodynamic coefficients"
    )
    damping: DampingTable = Field(
        default_factory=DampingTable,
        description="Rayleigh (mass- and stiffness-proportional) and Kelvin-Voigt strain-rate "
        "damping of the flexible bodies",
    )
    initial_velocity: list[InitialVelocityTable] = Field(
        [], description="velocities of single nodes (their energy depends on the mesh)"
    )
    initial_motion: InitialMotionTable | None = Field(
        None, description="a rigid-body velocity field of the whole model"
    )
    solver: SolverTable = Field(default_factory=SolverTable, description="analysis settings")
    modes: ModesTable = Field(default_factory=ModesTable, description="defaults of rancf modes")
    sensor_tables: list[SensorTable] = Field([], alias="sensors", description="monitored values")

    _path: str = PrivateAttr(_PYTHON)
    _dim: int = PrivateAttr(0)
    _bodies: dict[str, Any] | None = PrivateAttr(None)
    _support_places: list[Any] = PrivateAttr(default_factory=list)
    _data: dict[str, Any] = PrivateAttr(default_factory=dict)
    _sensors: tuple[Sensor, ...] = PrivateAttr(())

    @classmethod
    def error_path(cls) -> str:
        return _PYTHON

    @classmethod
    def unknown_key_message(cls, key: str) -> str:
        return f"unknown table (allowed: {', '.join(cls.file_keys())})"

    @model_validator(mode="after")
    def _whole(self, info: ValidationInfo) -> Scenario:
        self._path = str((info.context or {}).get("path", _PYTHON))
        self._dim, self._bodies, self._support_places = check_scenario(self)
        self._data = _data(self)
        self._data["warnings"] = start_warnings(self)
        self._sensors = tuple(_record(s, self._bodies) for s in self.sensor_tables)
        _columns_once(self._sensors, self._dim)
        return self

    # ------------------------------------------------------------------ the facade
    @property
    def path(self) -> str:
        """The scenario file (``<scenario>`` for one built in Python)."""
        return self._path

    @property
    def dim(self) -> int:
        """2 (planar) or 3 (spatial)."""
        return self._dim

    @property
    def notes(self) -> list[str]:
        """One line each on defaults the file did not state but the run uses (a harmonic
        motion's build-up)."""
        return list(self._data["notes"])

    @property
    def warnings(self) -> list[str]:
        """One line each on the impulsive starts of the run (a jump at ``t = 0`` of a
        prescribed rate or value, or of a load: :func:`rancf.scenario.motions.start_warnings`)."""
        return list(self._data["warnings"])

    @property
    def data(self) -> dict[str, Any]:
        """Every table as plain dictionaries with defaults filled in (places of a one-body
        file as node indices; ``supports[i]["label"]`` keeps ``at`` as written)."""
        return self._data

    @property
    def sensors(self) -> tuple[Sensor, ...]:
        """The sensors in file order."""
        return self._sensors

    @property
    def support_labels(self) -> list[int | str]:
        """Each support's ``at`` as written (``"start"``, ``"end"``, a node index, a place)."""
        return [s.at for s in self.supports]

    def support_place(self, i: int) -> ResolvedPlace:
        """The resolved place of ``supports[i]``."""
        return self._support_places[i]

    @property
    def bodies_by_name(self) -> dict[str, Any]:
        """The ``[[bodies]]`` by name (empty for a file without them)."""
        return dict(self._bodies or {})

    def place(self, value: int | str) -> ResolvedPlace:
        """``value`` (a place as written in this scenario) resolved against its bodies."""
        from pydantic_core import PydanticCustomError

        from rancf.scenario.places import resolve_place

        try:
            return resolve_place("", value, self._bodies, ground=True)
        except PydanticCustomError as exc:
            raise ScenarioError(self.path, "place", str(exc)) from None

    def installed_support(self) -> str | None:
        """The key of the first support installed away from its reference (``position`` or
        ``direction``), or None."""
        for i, s in enumerate(self.supports):
            for k in ("position", "direction"):
                if s[k] is not None:
                    return f"supports[{i}].{k}"
        return None

    def dynamic_options(self) -> DynamicOptions:
        """:class:`~rancf.options.DynamicOptions` of the ``[solver]`` table."""
        return self.solver.dynamic_options()

    def static_options(self) -> dict[str, Any]:
        """The ``[solver]`` table's keywords of :func:`rancf.solvers.static.solve_static`."""
        return self.solver.static_options()

    def build_model(self) -> Model:
        """Mesh the geometry and assemble the model (errors name the scenario key)."""
        from rancf.scenario.build import build_model

        return build_model(self)

    def build_system(self) -> System:
        """The :class:`~rancf.system.System` of the scenario: every body, joint, spring, support
        and load (a file without ``[[bodies]]`` is one body named ``"body"``)."""
        from rancf.scenario.system_build import build_system

        return build_system(self)

    # ------------------------------------------------------------------ files
    @classmethod
    def from_dict(cls, raw: Any, path: str = _PYTHON) -> Scenario:
        """Validate a scenario given as a dictionary (the parsed TOML); ``path`` names it in
        errors and is where relative CAD files are found."""
        try:
            with deferred_interrupts():  # Ctrl-C in a validator would be lost in pydantic-core
                return cls.model_validate(raw, context={"path": path})
        except ValidationError as exc:
            raise scenario_error(exc, path) from None

    @classmethod
    def from_toml(cls, path: str | Path) -> Scenario:
        """Read and validate a TOML scenario file."""
        return cls.from_dict(read_toml(Path(path)), str(path))

    def to_dict(self) -> dict[str, Any]:
        """The scenario as a file holds it: the keys given (defaults left out), TIME_FUNCTIONs
        in their table form."""
        for key, f in self._time_functions():
            if getattr(f, "kind", None) == "callable":
                raise ScenarioError(
                    self.path,
                    key,
                    "is a Python function: it cannot be saved "
                    "(give it as a table, ramp, harmonic or spin_up)",
                )
        return self.model_dump(by_alias=True, exclude_unset=True, exclude_none=True)

    def to_toml(self, relative_to: str | Path | None = None) -> str:
        """The scenario as TOML text (compact arrays: :func:`rancf.scenario.toml_text.dumps`).
        CAD files given relative to this scenario's file are rewritten relative to
        ``relative_to`` (a directory), absolute when there is none."""
        from rancf.scenario.toml_text import dumps

        d = self.to_dict()
        for g, where in self._cad_tables(d):
            own = Path(where.resolved_file)
            if relative_to is not None and not Path(g["file"]).is_absolute():
                try:
                    g["file"] = str(own.relative_to(Path(relative_to).resolve()))
                    continue
                except ValueError:
                    pass
            g["file"] = str(own)
        return dumps(d)

    def save(self, path: str | Path) -> None:
        """Write the scenario to ``path`` as TOML (atomically: a complete file or none)."""
        p = Path(path)
        write_atomic(p, self.to_toml(p.resolve().parent))

    def _time_functions(self) -> list[tuple[str, Any]]:
        out = [(f"supports[{i}].motion", s.motion) for i, s in enumerate(self.supports)]
        out += [(f"loads.point[{i}].time", p.time) for i, p in enumerate(self.loads.point)]
        out += [(f"joints[{i}].angle", j.angle) for i, j in enumerate(self.joints)]
        out += [
            (f"loads.distributed[{i}].time", p.time) for i, p in enumerate(self.loads.distributed)
        ]
        out += [
            (f"winches[{i}].{k}", w[k])
            for i, w in enumerate(self.winches)
            for k in ("length", "speed", "torque")
        ]
        return [(k, f) for k, f in out if f is not None]

    def _cad_tables(self, d: dict[str, Any]) -> list[tuple[dict[str, Any], CadGeometry]]:
        out: list[tuple[dict[str, Any], CadGeometry]] = []
        if isinstance(self.geometry, CadGeometry):
            out.append((d["geometry"], self.geometry))
        for b, raw in zip(self.bodies, d.get("bodies", []), strict=False):
            if isinstance(b, FlexibleBody) and isinstance(b.geometry, CadGeometry):
                out.append((raw["geometry"], b.geometry))
        return out


def _geometry_data(g: Any) -> dict[str, Any]:
    out: dict[str, Any] = dict.fromkeys(k for keys in GEOMETRY_KEYS.values() for k in keys)
    out.update(g.plain())
    if isinstance(g, CadGeometry):
        out["file"], out["curves"], out["labels"] = g.resolved_file, g.curves, g.labels
        out["curve"] = 0 if g.curve is None else g.curve
    return out


def _tf(v: Any) -> Any:
    return None if v is None else time_function(v)


def _node_or_text(v: int | str, one_body: bool) -> int | str:
    if one_body and v in ("start", "end"):
        return 0 if v == "start" else -1
    return v


def _data(sc: Scenario) -> dict[str, Any]:
    """The tables as plain dictionaries (:attr:`Scenario.data`)."""
    one = not sc.bodies
    d: dict[str, Any] = {}
    if one:
        d["geometry"] = _geometry_data(sc.geometry)
        for k in ("mesh", "section", "material"):
            d[k] = sc[k].plain()
    d["bodies"] = []
    for b in sc.bodies:
        bd = b.plain()
        if isinstance(b, FlexibleBody):
            bd["geometry"] = _geometry_data(b.geometry)
            im = b.initial_motion
            bd["initial_motion"] = None if im is None else im.as_dict()
        d["bodies"].append(bd)
    notes: list[str] = []

    def motion(v: Any, key: str) -> Any:
        f, note = motion_function(v, key)
        notes.extend([note] if note else [])
        return f

    d["joints"] = [
        {**j.plain(frozenset({"angle"})), "angle": motion(j.angle, f"joints[{i}].angle")}
        for i, j in enumerate(sc.joints)
    ]
    d["springs"] = [s.plain() for s in sc.springs]
    d["obstacles"] = [o.plain() for o in sc.obstacles]
    d["winches"] = [
        {
            **w.plain(frozenset({"length", "speed", "torque"})),
            **{k: _tf(w[k]) for k in ("length", "speed", "torque")},
        }
        for w in sc.winches
    ]
    d["supports"] = [
        {
            **s.plain(frozenset({"motion"})),
            "at": _node_or_text(s.at, one),
            "label": s.at,
            "motion": motion(s.motion, f"supports[{i}].motion"),
        }
        for i, s in enumerate(sc.supports)
    ]
    d["loads"] = {
        "gravity": sc.loads.gravity,
        "point": [
            {**p.plain(frozenset({"time"})), "at": _node_or_text(p.at, one), "time": _tf(p.time)}
            for p in sc.loads.point
        ],
        "distributed": [
            {**p.plain(frozenset({"time"})), "time": _tf(p.time)} for p in sc.loads.distributed
        ],
    }
    d["damping"] = sc.damping.plain()
    d["initial_velocity"] = [
        {"at": _node_or_text(iv.at, one), "value": iv.value} for iv in sc.initial_velocity
    ]
    d["initial_motion"] = None if sc.initial_motion is None else sc.initial_motion.as_dict()
    d["solver"] = sc.solver.plain()
    d["modes"] = sc.modes.plain()
    d["notes"] = notes
    return d


def _columns_once(sensors: tuple[Sensor, ...], dim: int) -> None:
    """Refuse two sensors that give a column of the same name (a position ``tip`` gives
    ``tip_x``, as a sensor named ``tip_x`` does): readers would take one for the other."""
    owner: dict[str, int] = {}
    for i, s in enumerate(sensors):
        for col in s.columns(dim):
            if col in owner:
                j = owner[col]
                raise fail(
                    f"sensors[{i}].name",
                    f"{show(s.name)} gives the column {col!r}, as "
                    f"sensors[{j}] ({show(sensors[j].name)}, kind {sensors[j].kind!r}) "
                    "does: each column of sensors.csv needs its own name",
                )
            owner[col] = i


def _record(s: SensorTable, bodies: dict[str, Any] | None) -> Sensor:
    if bodies is not None:
        return s.record()
    return s.record(tuple(int(_node_or_text(p, True)) for p in s.places()))


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a TOML scenario file (:meth:`Scenario.from_toml`)."""
    return Scenario.from_toml(path)


def parse_scenario(raw: dict[str, Any], path: str = _PYTHON) -> Scenario:
    """Validate a scenario given as a dictionary (:meth:`Scenario.from_dict`)."""
    return Scenario.from_dict(raw, path)
