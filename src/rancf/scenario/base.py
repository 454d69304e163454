"""The building blocks of the scenario models: a strict table, typed values, error markers.

Every table of a scenario file is a :class:`Table` (a pydantic model): unknown keys are refused
naming the keys it has; numbers are finite ``int``/``float`` values (never a bool or a string,
never ``NaN`` or ``inf``); integers are integers; vectors have a fixed number of components.
Validators report problems with :func:`fail`, which carries the key (relative to the table) into
the error, so :mod:`rancf.scenario.messages` can name the full key path in the one-line
:class:`~rancf.errors.ScenarioError`.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Annotated, Any, TypeAlias

import numpy as np
from pydantic import BaseModel, BeforeValidator, ConfigDict, Discriminator, Field, model_validator
from pydantic_core import PydanticCustomError

from rancf.errors import shorten
from rancf.geometry.conic import LENGTH_RANGE
from rancf.scenario.messages import scenario_error, show

__all__ = [
    "Table",
    "fail",
    "KindOf",
    "JsonSchema",
    "under",
    "show",
    "shorten",
    "Number",
    "number",
    "integer",
    "to_number",
    "Positive",
    "NonNegative",
    "Integer",
    "Flag",
    "Name",
    "vector",
    "number_or_vector",
    "Vector2",
    "Vector3",
    "Vector23",
    "Vector123",
    "NumberOrVector3",
    "NumberOrVector123",
    "MAX_COORDINATE",
    "MAX_ELEMENTS",
    "Point",
    "SemiAxes",
    "Degree",
    "ElementCount",
    "QuadraturePoints",
    "ContactPoints",
    "PoissonRatio",
]


def fail(key: str, problem: str) -> PydanticCustomError:
    """The validation error for ``key`` (relative to the table validated; ``""``: the table)."""
    return PydanticCustomError("scenario", "{problem}", {"key": key, "problem": problem})


class KindOf(Discriminator):
    """A discriminator (which model of a union validates a value) that can sit in a union
    (``X | None``) with its error context."""

    __hash__ = object.__hash__


class JsonSchema:
    """Annotation metadata giving a type's JSON Schema (``schema``), as pydantic's
    ``WithJsonSchema`` does, but usable in unions."""

    def __init__(self, schema: dict[str, Any]) -> None:
        self.schema = schema

    def __get_pydantic_json_schema__(self, core_schema: Any, handler: Any) -> dict[str, Any]:
        return dict(self.schema)


def under(key: str, exc: PydanticCustomError) -> PydanticCustomError:
    """The error ``exc`` of :func:`fail` with its key moved below ``key``."""
    ctx = exc.context or {}
    sub = str(ctx.get("key", ""))
    if not key or not sub:
        full = key or sub
    else:
        full = f"{key}{sub}" if sub.startswith("[") else f"{key}.{sub}"
    return fail(full, str(ctx.get("problem", exc.message())))


class Table(BaseModel):
    """A table of a scenario file: fixed keys, values validated, immutable once validated.

    Tables read like mappings too (``table["key"]``), as the dictionaries of earlier versions
    did.
    """

    model_config = ConfigDict(
        extra="forbid",
        frozen=True,
        allow_inf_nan=False,
        populate_by_name=True,
        arbitrary_types_allowed=True,
        # validators are built at first use: importing the models builds none, and a file's
        # Scenario builds its whole tree once (not one validator per table as well)
        defer_build=True,
    )

    def __init__(self, /, **data: Any) -> None:
        """Validate ``data`` (keys as in a file; nested tables as models or dictionaries);
        problems raise :class:`~rancf.errors.ScenarioError` naming ``<ClassName>`` and the key."""
        from pydantic import ValidationError

        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise scenario_error(exc, self.error_path()) from None

    # validation from a dictionary (model_validate) validates directly, without __init__
    __init__.__pydantic_base_init__ = True  # type: ignore[attr-defined]  # pydantic reads it

    def plain(self, exclude: frozenset[str] = frozenset()) -> dict[str, Any]:
        """The table's values as ``model_dump()`` gives them (nested tables as dictionaries,
        other values as they are), but ``exclude``; without building pydantic's serializer
        of the table, which would cost a run's first read about as much again as its
        validator (the tables are built lazily, ``defer_build``)."""
        return {
            k: _plain(v)
            for k, v in self.__dict__.items()
            if k in type(self).model_fields and k not in exclude
        }

    @classmethod
    def error_path(cls) -> str:
        """What errors of a table built in Python name instead of a file."""
        return f"<{cls.__name__}>"

    @model_validator(mode="before")
    @classmethod
    def _known_keys(cls, data: Any) -> Any:
        if isinstance(data, BaseModel):
            return data
        if not isinstance(data, dict):
            raise fail("", f"must be a table, got {show(data)}")
        allowed = cls.file_keys()
        for k in data:
            if k not in allowed and k not in cls.model_fields:
                raise fail(str(k), cls.unknown_key_message(str(k)))
        return data

    @classmethod
    def file_keys(cls) -> list[str]:
        """The keys of this table as written in a file."""
        return [f.alias or name for name, f in cls.model_fields.items()]

    @classmethod
    def unknown_key_message(cls, key: str) -> str:
        """The problem of an unknown ``key``."""
        return f"unknown key (allowed: {', '.join(cls.file_keys())})"

    def __eq__(self, other: object) -> bool:
        """Equal tables hold equal values (where a scenario came from is not compared)."""
        if not isinstance(other, BaseModel):
            return NotImplemented
        return type(self) is type(other) and self.__dict__ == other.__dict__

    __hash__ = None  # type: ignore[assignment]  # unhashable (pydantic hashes frozen models)

    def __getitem__(self, key: str) -> Any:
        for name, f in type(self).model_fields.items():
            if key in (name, f.alias):
                return getattr(self, name)
        raise KeyError(key)

    def get(self, key: str, default: Any = None) -> Any:
        """``table[key]``, or ``default`` for a key the table does not have."""
        try:
            return self[key]
        except KeyError:
            return default


# ---------------------------------------------------------------------- numbers
def _number(v: Any) -> float:
    if isinstance(v, np.generic) and not isinstance(v, np.bool_):
        v = v.item()
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise fail("", f"must be a number, got {show(v)}")
    try:
        f = float(v)
    except OverflowError:
        f = math.inf
    if not math.isfinite(f):
        raise fail("", f"must be finite, got {show(v)}")
    return f


def _integer(v: Any) -> int:
    if isinstance(v, np.integer):
        v = int(v)
    if isinstance(v, bool) or not isinstance(v, int):
        raise fail("", f"must be an integer, got {show(v)}")
    return v


def _flag(v: Any) -> bool:
    if isinstance(v, np.bool_):
        v = bool(v)
    if not isinstance(v, bool):
        raise fail("", f"must be true or false, got {show(v)}")
    return v


def _name(v: Any) -> str:
    if not isinstance(v, str) or not v.isidentifier():
        raise fail("", f"must be a simple name (letters, digits, _), got {show(v)}")
    return v


def to_number(v: Any) -> float:
    """``v`` as a finite float (an int or a float, not a bool), else a validation error."""
    return _number(v)


def number(
    *,
    gt: float | None = None,
    ge: float | None = None,
    lt: float | None = None,
    le: float | None = None,
) -> Any:
    """The type of a finite number within the limits given (``gt``, ``ge``, ``lt``, ``le``)."""
    return Annotated[float, Field(gt=gt, ge=ge, lt=lt, le=le), BeforeValidator(_number)]


def integer(*, ge: int | None = None, le: int | None = None) -> Any:
    """The type of an integer within the limits given (``ge``, ``le``)."""
    return Annotated[int, Field(ge=ge, le=le), BeforeValidator(_integer)]


#: A finite number (an int or a float, not a bool).
Number = Annotated[float, BeforeValidator(_number)]
#: A finite number > 0.
Positive = Annotated[float, Field(gt=0), BeforeValidator(_number)]
#: A finite number >= 0.
NonNegative = Annotated[float, Field(ge=0), BeforeValidator(_number)]
#: An integer (not a bool, not a float).
Integer = Annotated[int, BeforeValidator(_integer)]
#: ``true`` or ``false``.
Flag = Annotated[bool, BeforeValidator(_flag)]
#: A simple name: letters, digits and ``_``, not starting with a digit.
Name = Annotated[str, Field(pattern=r"^[A-Za-z_][A-Za-z0-9_]*$"), BeforeValidator(_name)]


def _sizes(sizes: tuple[int, ...]) -> Any:
    want = " or ".join(str(s) for s in sizes)

    def check(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            v = v.tolist()
        if isinstance(v, tuple):
            v = list(v)
        if not isinstance(v, list) or len(v) not in sizes:
            raise fail("", f"must be a list of {want} numbers, got {show(v)}")
        return v

    return check


def _bounded(bound: float) -> Any:
    def check(v: Any) -> float:
        f = _number(v)
        if abs(f) > bound:
            raise fail("", f"must be at most {bound:g} in size, got {show(v)}")
        return f

    return check


def vector(*sizes: int, bound: float | None = None) -> Any:
    """The type of a list of ``sizes`` finite numbers (each at most ``bound`` in size)."""
    item: Any = Number
    if bound is not None:
        item = Annotated[float, Field(ge=-bound, le=bound), BeforeValidator(_bounded(bound))]
    return Annotated[
        list[item],
        Field(min_length=min(sizes), max_length=max(sizes)),
        BeforeValidator(_sizes(sizes)),
    ]


def number_or_vector(*sizes: int) -> Any:
    """The type of a finite number or a list of ``sizes`` finite numbers."""
    check = _sizes(sizes)
    want = " or ".join(str(s) for s in sizes)

    def convert(v: Any) -> Any:
        if isinstance(v, list | tuple | np.ndarray):
            v = check(v)
            out = []
            for i, x in enumerate(v):
                try:
                    out.append(_number(x))
                except PydanticCustomError as exc:
                    raise fail(f"[{i}]", str(exc)) from None
            return out
        try:
            return _number(v)
        except PydanticCustomError:
            raise fail("", f"must be a number or a list of {want} numbers, got {show(v)}") from None

    items = {"type": "array", "items": {"type": "number"}}
    schema = {
        "oneOf": [{"type": "number"}, {**items, "minItems": min(sizes), "maxItems": max(sizes)}]
    }
    return Annotated[float | list[float], BeforeValidator(convert), JsonSchema(schema)]


#: Largest size of a geometry coordinate [m] (``start``, ``end``, ``point``, ``control_points``):
#: the longest chord a conic may have (:data:`rancf.geometry.conic.LENGTH_RANGE`).
MAX_COORDINATE = LENGTH_RANGE[1]
#: Largest ``mesh.elements`` (and total number of elements of a NURBS mesh).
MAX_ELEMENTS = 1_000_000

if TYPE_CHECKING:
    # what the validated values are; a type checker cannot evaluate the factories above
    Vector2: TypeAlias = list[float]
    Vector3: TypeAlias = list[float]
    Vector23: TypeAlias = list[float]
    Vector123: TypeAlias = list[float]
    NumberOrVector3: TypeAlias = float | list[float]
    NumberOrVector123: TypeAlias = float | list[float]
    Point: TypeAlias = list[float]
    SemiAxes: TypeAlias = list[float]
    Degree: TypeAlias = int
    ElementCount: TypeAlias = int
    QuadraturePoints: TypeAlias = int
    ContactPoints: TypeAlias = int
    PoissonRatio: TypeAlias = float
else:
    #: Two finite numbers.
    Vector2 = vector(2)
    #: Three finite numbers.
    Vector3 = vector(3)
    #: Two (planar) or three (spatial) finite numbers.
    Vector23 = vector(2, 3)
    #: One, two or three finite numbers.
    Vector123 = vector(1, 2, 3)
    #: A finite number or three finite numbers.
    NumberOrVector3 = number_or_vector(3)
    #: A finite number or one, two or three finite numbers.
    NumberOrVector123 = number_or_vector(1, 2, 3)
    #: A geometry point, 2 (planar) or 3 (spatial) coordinates.
    Point = vector(2, 3, bound=MAX_COORDINATE)
    #: The two semi-axes of an ellipse.
    SemiAxes = vector(2, bound=MAX_COORDINATE)
    #: The polynomial degree of a NURBS curve.
    Degree = integer(ge=2, le=3)
    #: The number of elements of a mesh.
    ElementCount = integer(ge=1, le=MAX_ELEMENTS)
    #: Gauss points per element (of the element forces; of contact).
    QuadraturePoints = integer(ge=2, le=64)
    ContactPoints = integer(ge=1, le=64)
    #: A Poisson ratio, in (-1, 0.5).
    PoissonRatio = number(gt=-1.0, lt=0.5)


def _plain(v: Any) -> Any:
    """A value of :meth:`Table.plain`: tables as dictionaries, in lists, tuples and dicts too."""
    if isinstance(v, BaseModel):
        return {k: _plain(x) for k, x in v.__dict__.items() if k in type(v).model_fields}
    if isinstance(v, (list, tuple)):
        return type(v)(_plain(x) for x in v)
    if isinstance(v, dict):
        return {k: _plain(x) for k, x in v.items()}
    return v
