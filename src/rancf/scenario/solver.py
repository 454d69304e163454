"""``[solver]`` and ``[modes]``: the analyses' settings.

The ``[solver]`` table is also checked as :class:`~rancf.options.DynamicOptions` (whose
own rules, e.g. ``step <= t_end`` and ``min_step <= step``, name the key); its defaults are the
Python API's (a test compares them).
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Annotated, Any, Literal

from pydantic import BeforeValidator, Field, model_validator

from rancf.errors import InputError
from rancf.options import MAX_LOAD_STEPS, MAX_NEWTON, MAX_SPIN_RATE, SPIN_RATES
from rancf.scenario.base import (
    Flag,
    Positive,
    Table,
    Vector3,
    fail,
    integer,
    number,
    show,
    to_number,
)

if TYPE_CHECKING:
    from typing import TypeAlias

    from rancf.options import DynamicOptions

    UnitInterval: TypeAlias = float
    LoadSteps: TypeAlias = int
    NewtonIterations: TypeAlias = int
    Count: TypeAlias = int
else:
    #: A number in [0, 1] (``rho_inf``).
    UnitInterval = number(ge=0.0, le=1.0)
    #: Load steps of a static solve.
    LoadSteps = integer(ge=1, le=MAX_LOAD_STEPS)
    #: Newton iterations per step.
    NewtonIterations = integer(ge=1, le=MAX_NEWTON)
    #: A count of at least one (modes).
    Count = integer(ge=1)

__all__ = ["SolverTable", "ModesTable"]

_DYNAMIC_KEYS = (
    "t_end",
    "step",
    "rho_inf",
    "adaptive",
    "rtol",
    "strain_error",
    "min_step",
    "output_step",
    "newton_tol",
    "max_newton",
    "newton",
)


def _shown(value: object) -> str:
    return f"{value:.6g}" if isinstance(value, float) else show(value)


class SolverTable(Table):
    """``[solver]``: time integration (generalized-alpha), Newton and statics settings."""

    t_end: Positive = Field(1.0, description="end time [s]")
    step: Positive = Field(
        1e-3,
        description="time step [s] (adaptive: the first), <= t_end; a step that would pass an "
        "output time is shortened to end on it",
    )
    rho_inf: UnitInterval = Field(
        0.9, description="generalized-alpha spectral radius at infinity, in [0, 1]"
    )
    load_steps: LoadSteps = Field(
        10, description="statics: the first load increment is 1/load_steps"
    )
    adaptive: Flag = Field(False, description="adapt the step to rtol (local error estimate)")
    rtol: Positive = Field(
        1e-5,
        description="local error / model size: adaptive steps keep below it, fixed "
        "steps warn at the end of a run above it",
    )
    strain_error: Flag = Field(
        False,
        description="the local error estimate measures the flexible bodies' axial strain "
        "too, relative to their largest strain (tension of stiff lines)",
    )
    output_step: Positive | None = Field(
        None,
        description="interval of stored states [s] (default: step), <= t_end; the steps end on "
        "every output time and on t_end, which is stored too",
    )
    min_step: Positive | None = Field(
        None, description="below this a failing step stops the run [s] (default: step / 1024)"
    )
    newton_tol: Positive = Field(
        1e-10,
        description="Newton: max |increment| / model size (gradients times their elements' length)",
    )
    max_newton: NewtonIterations = Field(12, description="Newton iterations per step")
    newton: Literal["chord", "full", "modified"] = Field(
        "chord",
        description='"chord" (exact tangent at each step\'s first iteration, reused within the '
        'step) | "full" (exact tangent every iteration) | "modified" (reused across steps)',
    )
    static_method: Literal["load", "arc_length", "linear"] = Field(
        "load",
        description='statics: "load" (adaptive load increments) | "arc_length" (limit points) '
        '| "linear" (small displacements: one solve with the reference\'s stiffness)',
    )
    static_friction: Flag = Field(
        False,
        description="statics: the seabed planes' friction fully mobilized toward the anchor, "
        "as MoorPy's catenary (default: frictionless statics)",
    )
    initial_state: Literal["reference", "static"] = Field(
        "reference",
        description='simulate: start from the "reference" or the "static" equilibrium',
    )

    @model_validator(mode="after")
    def _as_options(self) -> SolverTable:
        try:
            self.dynamic_options()
        except InputError as exc:
            key = exc.parameter.removeprefix("solver.")
            raise fail(key, f"{exc.allowed} (got {_shown(exc.value)})") from None
        return self

    def dynamic_options(self) -> DynamicOptions:
        """The :class:`~rancf.options.DynamicOptions` of this table."""
        from rancf.options import DynamicOptions

        return DynamicOptions(**{k: getattr(self, k) for k in _DYNAMIC_KEYS})

    def static_options(self) -> dict[str, Any]:
        """The keywords of :func:`rancf.solvers.static.solve_static` in this table
        (``load_steps``, ``method``, ``static_friction``)."""
        return {
            "load_steps": self.load_steps,
            "method": self.static_method,
            "static_friction": self.static_friction,
        }


def _spin_rate(v: Any) -> float:
    f = to_number(v)
    if not 0.0 <= f <= MAX_SPIN_RATE:
        raise fail("", f"must be >= 0 and {SPIN_RATES}, got {show(v)}")
    return f


#: A steady rotation rate of ``[modes]`` [rad/s].
SpinRate = Annotated[float, Field(ge=0, le=MAX_SPIN_RATE), BeforeValidator(_spin_rate)]


class ModesTable(Table):
    """``[modes]``: defaults of ``rancf modes``."""

    count: Count = Field(6, description="number of modes")
    about: Literal["reference", "static"] = Field(
        "reference",
        description='linearize about the "reference" or the "static" equilibrium',
    )
    spin_axis: Vector3 = Field(
        [0.0, 0.0, 1.0], description="axis of the steady rotation of spin_rates (3D)"
    )
    spin_center: Vector3 = Field([0.0, 0.0, 0.0], description="a point on the spin axis [m]")
    spin_rates: list[SpinRate] = Field(
        [], description="steady rotation rates for a Campbell diagram [rad/s]"
    )

    @model_validator(mode="after")
    def _axis(self) -> ModesTable:
        if self.spin_rates and not any(self.spin_axis):
            raise fail("spin_axis", f"a non-zero vector (got {show(self.spin_axis)})")
        return self
