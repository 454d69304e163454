"""TIME_FUNCTION values of a scenario: a number, a vector or a function table.

A TIME_FUNCTION (:class:`~rancf.bodies.time_function.TimeFunction`, equations T.1–T.6) is written
as a number (or a vector where the key is a vector: a support's ``motion``), or as a table with
one of the keys ``table``, ``ramp``, ``harmonic`` or ``spin_up`` (and an optional ``build_up``);
in Python also a ``TimeFunction`` or any callable ``f(t)``.  :func:`time_function` turns a
validated value into its ``TimeFunction``.  A support's ``motion`` (:data:`MotionValue`) may also
be a table of absolute positions (:class:`PathTable`, ``absolute = true``).
"""

from __future__ import annotations

from typing import Annotated, Any, Literal

from pydantic import BeforeValidator, Field, PlainSerializer, PlainValidator, Tag, model_validator
from pydantic.json_schema import SkipJsonSchema

from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.scenario.base import (
    Flag,
    JsonSchema,
    KindOf,
    NonNegative,
    Number,
    NumberOrVector123,
    Positive,
    Table,
    Vector123,
    fail,
    show,
)
from rancf.scenario.table_files import ROWS_SCHEMA, table_rows

__all__ = [
    "TableFunction",
    "PathTable",
    "MotionValue",
    "RampFunction",
    "HarmonicFunction",
    "SpinUpFunction",
    "TimeFunctionValue",
    "time_function",
    "time_size",
    "is_absolute",
    "check_scalar",
]

Amount = NumberOrVector123


class _Function(Table):
    """What every function table has: an optional build-up (T.6)."""

    build_up: NonNegative | None = Field(
        None,
        description="B [s]: the function times a smooth step from 0 to 1 over [0, B] (value, "
        "rate and acceleration start from 0; a winch's length: its change from the start); 0: "
        "none. Default: none, but a harmonic support motion or joint angle that would start "
        "with a jump of its rate builds up over two periods (said in one line); other jumps at "
        "t = 0 are warned about unless build_up is given",
    )

    def function(self) -> TimeFunction:
        """The time function."""
        f = self._function()
        return f if not self.build_up else f.with_build_up(self.build_up)

    def _function(self) -> TimeFunction:
        raise NotImplementedError


class TableFunction(_Function):
    """``{ table = [[t, v...], ...], interpolation = ... }`` (T.2); or ``table = "file.csv"``,
    the rows read from a CSV file relative to the scenario file."""

    table: Annotated[
        list[list[Number]],
        BeforeValidator(table_rows),
        JsonSchema(ROWS_SCHEMA),
    ] = Field(
        min_length=2,
        description="rows [t, v...]: times [s] strictly increasing, one value per component; "
        "held at the first row before it and at the last row after it; or a CSV file of such "
        'rows ("path.csv", relative to the scenario file; a header line of names allowed)',
    )
    interpolation: Literal["linear", "cubic"] = Field(
        "linear",
        description='"linear" | "cubic" (the not-a-knot cubic spline: C2, exact for cubics)',
    )

    @model_validator(mode="after")
    def _rows(self) -> TableFunction:
        width = len(self.table[0])
        for i, row in enumerate(self.table):
            if len(row) < 2 or len(row) != width:
                raise fail(
                    f"table[{i}]",
                    f"must be a row [t, v...] of {max(width, 2)} numbers "
                    f"like the first row, got {show(row)}",
                )
            if i and not row[0] > self.table[i - 1][0]:
                raise fail(
                    f"table[{i}][0]",
                    f"times must increase strictly, got {show(row[0])} "
                    f"after {show(self.table[i - 1][0])}",
                )
        return self

    def _function(self) -> TimeFunction:
        return TimeFunction.table(self.table, self.interpolation)


class PathTable(TableFunction):
    """A support's ``motion`` as a table: displacements from the reference position, or with
    ``absolute = true`` the positions themselves (a robot's path file;
    ``docs/derivations/clamp-paths.md`` §1)."""

    absolute: Flag = Field(
        False,
        description="true: the rows are absolute positions [m] of the support (a path), not "
        "displacements from its reference position; the path must start at the reference "
        "point unless build_up is given or the run starts from the static equilibrium",
    )


class RampFunction(_Function):
    """``{ ramp = DURATION, value = ... }``: ``value · min(t / DURATION, 1)`` (T.3)."""

    ramp: Positive = Field(description="duration T of the ramp [s]")
    value: Amount = Field(1.0, description="the value reached at t = T (a number or a vector)")

    def _function(self) -> TimeFunction:
        return TimeFunction.ramp(self.ramp, self.value)


class HarmonicFunction(_Function):
    """``{ harmonic = FREQUENCY_HZ, amplitude = ..., phase_deg = ... }``:
    ``amplitude · sin(2π f t + phase)`` (T.4)."""

    harmonic: Positive = Field(description="frequency f [Hz]")
    amplitude: Amount = Field(1.0, description="amplitude (a number or a vector)")
    phase_deg: Number = Field(0.0, description="phase [deg]")

    def _function(self) -> TimeFunction:
        return TimeFunction.harmonic(self.harmonic, self.amplitude, self.phase_deg)


class SpinUpFunction(_Function):
    """``{ spin_up = DURATION, rate = OMEGA }``: an angle whose rate rises smoothly from 0 to
    OMEGA in DURATION T, ``(Ω/T)[t²/2 + (T/2π)²(cos(2πt/T) − 1)]`` for ``t ≤ T`` and
    ``Ω (t − T/2)`` after (T.5; Kane, Ryan & Banerjee 1987)."""

    spin_up: Positive = Field(description="duration T of the spin-up [s]")
    rate: Number = Field(description="the final angular rate Omega [rad/s]")

    def _function(self) -> TimeFunction:
        return TimeFunction.spin_up(self.spin_up, self.rate)


def _python_function(v: Any) -> TimeFunction:
    if isinstance(v, TimeFunction):
        return v
    if callable(v):
        try:
            return TimeFunction.from_callable(v)
        except InputError as exc:
            raise fail("", f"must return a number or a vector at t = 0 ({exc.allowed})") from None
    raise fail("", f"must be a time function, got {show(v)}")


def _serialize_python(f: TimeFunction) -> Any:
    return f if f.kind == "callable" else f.to_toml()  # a callable has no file form


_KINDS = ("table", "ramp", "harmonic", "spin_up")


_TAGS: dict[type, str] = {
    TableFunction: "[table]",
    PathTable: "[table]",
    RampFunction: "[ramp]",
    HarmonicFunction: "[harmonic]",
    SpinUpFunction: "[spin_up]",
}


def _time_kind(v: Any) -> str | None:
    if isinstance(v, bool):
        return None
    if isinstance(v, int | float):
        return "[number]"
    if isinstance(v, list | tuple):
        return "[vector]"
    if isinstance(v, dict):
        found = [k for k in _KINDS if k in v]
        return f"[{found[0]}]" if len(found) == 1 else None
    if type(v) in _TAGS:
        return _TAGS[type(v)]
    if isinstance(v, TimeFunction) or callable(v):
        return "[python]"
    return None


#: The TIME_FUNCTION forms before a table (a number, a vector) and after it (the function
#: tables and, in Python, a :class:`~rancf.bodies.time_function.TimeFunction` or a callable),
#: in the order the schema lists them.
_PLAIN = Annotated[Number, Tag("[number]")] | Annotated[Vector123, Tag("[vector]")]
_FUNCTIONS = (
    Annotated[RampFunction, Tag("[ramp]")]
    | Annotated[HarmonicFunction, Tag("[harmonic]")]
    | Annotated[SpinUpFunction, Tag("[spin_up]")]
    | SkipJsonSchema[
        Annotated[
            TimeFunction,
            PlainValidator(_python_function),
            PlainSerializer(_serialize_python),
            Tag("[python]"),
        ]
    ]
)
#: The value's kind picks its form (:func:`_time_kind`).
_KIND = KindOf(
    _time_kind,
    custom_error_type="time_function",
    custom_error_message="must be a time function",
)
#: A TIME_FUNCTION value: a number, a vector, one of the function tables, or (Python) a
#: :class:`~rancf.bodies.time_function.TimeFunction` or a callable.
TimeFunctionValue = Annotated[_PLAIN | Annotated[TableFunction, Tag("[table]")] | _FUNCTIONS, _KIND]
#: A support's ``motion``: a TIME_FUNCTION whose table may hold absolute positions
#: (:class:`PathTable`).
MotionValue = Annotated[_PLAIN | Annotated[PathTable, Tag("[table]")] | _FUNCTIONS, _KIND]


def time_function(v: Any) -> TimeFunction:
    """The :class:`~rancf.bodies.time_function.TimeFunction` of a validated TIME_FUNCTION."""
    if isinstance(v, TimeFunction):
        return v
    if isinstance(v, int | float | list):
        return TimeFunction.constant(v)
    return v.function()


def is_absolute(v: Any) -> bool:
    """Whether a validated motion ``v`` is a table of absolute positions (:class:`PathTable`)."""
    return isinstance(v, PathTable) and v.absolute


def time_size(v: Any) -> int | None:
    """Number of components of a validated TIME_FUNCTION (None: a scalar)."""
    if isinstance(v, TimeFunction):
        return v.size if v.vector else None
    if isinstance(v, list):
        return len(v)
    if isinstance(v, TableFunction):
        return len(v.table[0]) - 1 if len(v.table[0]) > 2 else None
    for attr in ("value", "amplitude"):
        if isinstance(getattr(v, attr, None), list):
            return len(getattr(v, attr))
    return None


def check_scalar(key: str, v: Any) -> None:
    """Raise unless the TIME_FUNCTION ``v`` (of ``key``) is scalar valued."""
    if v is not None and time_size(v) is not None:
        got = show(v) if isinstance(v, list) else f"{time_size(v)} components"
        raise fail(key, f"must be a scalar time function (numbers, not vectors), got {got}")
