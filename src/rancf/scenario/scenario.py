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

from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING, Any

from pydantic import Field, PrivateAttr, ValidationError, ValidationInfo, model_validator

from rancf.errors import ScenarioError
from rancf.scenario.base import ContactPoints, Name, NonNegative, Table
from rancf.scenario.bodies import Body, FlexibleBody
from rancf.scenario.checks import check_scenario
from rancf.scenario.damping import DampingTable
from rancf.scenario.data import body_tables, columns_once, scenario_data, sensor_record
from rancf.scenario.files import deferred_interrupts, read_toml, write_atomic
from rancf.scenario.fluid import FluidTable, HydroTable
from rancf.scenario.form import FormTable
from rancf.scenario.geometry import CadGeometry, Geometry, MeshTable
from rancf.scenario.joints import JointTable, SpringTable
from rancf.scenario.loads import (
    InitialMotionTable,
    InitialVelocityTable,
    LoadsTable,
    SupportTable,
)
from rancf.scenario.messages import scenario_error
from rancf.scenario.motions import start_warnings
from rancf.scenario.obstacles import ObstacleTable
from rancf.scenario.section import MaterialTable, SectionTable
from rancf.scenario.sensors import Sensor, SensorTable
from rancf.scenario.solver import ModesTable, SolverTable
from rancf.scenario.surface import is_surface
from rancf.scenario.winches import WinchTable

if TYPE_CHECKING:
    from rancf.bodies.flexible import Model
    from rancf.options import DynamicOptions
    from rancf.scenario.places import ResolvedPlace
    from rancf.system import System

__all__ = ["Scenario", "load_scenario", "parse_scenario"]

_PYTHON = "<scenario>"


class Scenario(Table):
    """A validated scenario (module docstring); the keys of the file are its fields.  Besides
    the tables: :attr:`path`, :attr:`dim`, :attr:`data` (every table as plain dictionaries,
    defaults filled in), :attr:`sensors` (the records of ``[[sensors]]``)."""

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
    form: FormTable | None = Field(
        None,
        description="one-body file: form-finding, the unstretched length found to meet a sag, "
        "horizontal tension or end tension in statics",
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
    _body_tables: tuple[tuple[str, Any], ...] = PrivateAttr(())
    _form_lengths: dict[str, float] = PrivateAttr(default_factory=dict)
    _form_search: bool = PrivateAttr(False)

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
        self._body_tables = body_tables(self)
        self._data = scenario_data(self)
        self._data["warnings"] = start_warnings(self)
        g, b = self.geometry, self._bodies
        self._sensors = tuple(sensor_record(s, b, g) for s in self.sensor_tables)
        columns_once(self._sensors, self._dim)
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
    def support_labels(self) -> list[Any]:
        """Each support's ``at`` as written (``"start"``, ``"end"``, a node index, a place)."""
        return [s.at for s in self.supports]

    def support_place(self, i: int) -> ResolvedPlace:
        """The resolved place of ``supports[i]``."""
        return self._support_places[i]

    @property
    def body_tables(self) -> tuple[tuple[str, Any], ...]:
        """Every body as ``(key prefix, [[bodies]] table)``, a one-body file's too: the one form
        code past parsing reads (:func:`rancf.scenario.data.body_tables`)."""
        return self._body_tables

    @property
    def bodies_by_name(self) -> dict[str, Any]:
        """The ``[[bodies]]`` by name (empty for a file without them)."""
        return dict(self._bodies or {})

    def place(self, value: int | str) -> ResolvedPlace:
        """``value`` (a place as written in this scenario) resolved against its bodies."""
        from pydantic_core import PydanticCustomError

        from rancf.scenario.places import resolve_place

        try:
            return resolve_place("", value, self._bodies, True, is_surface(self.geometry))
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

    def forms(self) -> list[tuple[str, str, FormTable]]:
        """Every ``[form]`` as ``(key prefix, body name, table)``."""
        return [
            (key, b.name, b.form)
            for key, b in self.body_tables
            if getattr(b, "form", None) is not None
        ]

    def set_form_length(self, name: str, length: float | None) -> None:
        """Give body ``name`` (with a ``[form]``) the unstretched length its form-finding found
        (:func:`rancf.solvers.form.find_form`): every model built from here on has it (None:
        not found)."""
        if length is None:
            self._form_lengths.pop(name, None)
        else:
            self._form_lengths[name] = float(length)

    def form_length(self, name: str) -> float | None:
        """The unstretched length found for body ``name``'s ``[form]``, or None (not found)."""
        return self._form_lengths.get(name)

    @contextmanager
    def form_search(self) -> Iterator[None]:
        """Within it, a body whose ``[form]`` has no length yet is built at its reference's
        (the form-finding's own system: :func:`rancf.solvers.form.find_form`)."""
        self._form_search = True
        try:
            yield
        finally:
            self._form_search = False

    def body_length(self, name: str) -> float | None:
        """The unstretched length body ``name`` is given (its ``[form]``'s found length, or a
        line's ``geometry.length``), or None (its reference's).

        Raises
        ------
        ScenarioError
            The body has a ``[form]`` whose length is not found yet (outside
            :meth:`form_search`).
        """
        if name in self._form_lengths:
            return self._form_lengths[name]
        for key, b in self.body_tables:
            if b.name != name:
                continue
            if getattr(b, "form", None) is not None and not self._form_search:
                raise ScenarioError(
                    self.path,
                    f"{key}form",
                    "asks for an unstretched length found by a static solve first: "
                    "rancf.find_form(scenario) finds it (the rancf commands do)",
                )
            return getattr(getattr(b, "geometry", None), "length", None)
        return None

    def length_keys(self) -> list[str]:
        """The keys that give a flexible body an unstretched length other than its reference's
        (``geometry.length`` of a line, a ``[form]``), so that its reference carries a force."""
        out = [f"{key}form" for key, _, _ in self.forms()]
        for key, b in self.body_tables:
            g = getattr(b, "geometry", None)
            length = getattr(g, "length", None)
            if length is not None and g is not None and not is_surface(g):  # a line's
                chord = sum((e - s) ** 2 for s, e in zip(g.start, g.end, strict=True)) ** 0.5
                if abs(length - chord) > 1e-9 * chord:
                    out.append(f"{key}geometry.length")
        return out

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
        write_atomic(Path(path), self.to_toml(Path(path).resolve().parent))

    def _time_functions(self) -> list[tuple[str, Any]]:
        out = [(f"supports[{i}].rotation", s.rotation) for i, s in enumerate(self.supports)]
        out += [(f"supports[{i}].motion", s.motion) for i, s in enumerate(self.supports)]
        out += [(f"loads.point[{i}].time", p.time) for i, p in enumerate(self.loads.point)]
        out += [(f"joints[{i}].angle", j.angle) for i, j in enumerate(self.joints)]
        out += [
            (f"loads.distributed[{i}].time", p.time) for i, p in enumerate(self.loads.distributed)
        ]
        out += [(f"loads.edge[{i}].time", p.time) for i, p in enumerate(self.loads.edge)]
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


def load_scenario(path: str | Path) -> Scenario:
    """Read and validate a TOML scenario file (:meth:`Scenario.from_toml`)."""
    return Scenario.from_toml(path)


def parse_scenario(raw: dict[str, Any], path: str = _PYTHON) -> Scenario:
    """Validate a scenario given as a dictionary (:meth:`Scenario.from_dict`)."""
    return Scenario.from_dict(raw, path)
