"""Springs: a spring-damper between two places, a :class:`~rancf.system.part.Part`.

:class:`Spring` is the linear spring-damper: tension ``T = k (ℓ - ℓ0) + c dℓ/dt`` along the
line between its places; ``length`` ℓ0 defaults to their distance in the reference
configuration.  With ``ℓ0 = 0`` (a spring to ``ground``, which sits at the other place's
reference) it is ``F = k (x_a - x_b) + c (v_a - v_b)``: the same stiffness, with a direction also
where the places meet; ``ℓ0 > 0`` needs the places apart at the reference.

:class:`SpringLaw` is the base of a nonlinear elastic law ``T(e) + c dℓ/dt`` of the stretch
``e = ℓ - ℓ0``: a subclass gives :meth:`SpringLaw.tension` (vectorized) and the range of
stretch it is written for; the core evaluates the law as the not-a-knot cubic spline through
``samples`` points of that range (exact for a cubic polynomial), continued linearly with its end
slopes beyond it (``src/cpp/system/spring_law.hpp``; its energy is the spline's integral).  A
new law is one such class in a module of its own (CONTRIBUTING.md shows one).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from rancf.bodies.time_function import TimeFunction
from rancf.errors import InputError
from rancf.kernels.records import SpringRecord
from rancf.system.places import Place

if TYPE_CHECKING:
    from rancf.system.part import PartHost
    from rancf.system.record_rows import RecordRows

__all__ = ["Spring", "SpringLaw"]


@dataclass(frozen=True)
class Spring:
    """A linear spring-damper between two places (module docstring)."""

    between: tuple[Place | str, Place | str]
    stiffness: float
    damping: float = 0.0
    length: float | None = None
    name: str = ""
    #: No sensor kinds of its own (its tension: :meth:`stretch`, :meth:`tension`).
    sensor_kinds: ClassVar[Mapping[str, Any]] = {}

    def key(self) -> str:
        """Its scenario key: ``springs.NAME`` (or its places)."""
        return f"springs.{self.name or '/'.join(map(str, self.between))}"

    def tension(self, stretch: ArrayLike) -> NDArray[np.float64]:
        """The elastic tension ``k e`` at the stretches ``e`` [N]."""
        return self.stiffness * np.asarray(stretch, dtype=float)

    def rest_length(self, system: PartHost) -> tuple[float, float]:
        """``(ℓ0, reference distance)``: the rest length (given, or the places' distance in the
        reference configuration; 0 if one is the ground)."""
        pa, pb = (system.resolve(x) for x in self.between)
        xa = system.reference_position(pa) if pa.body is not None else None
        xb = system.reference_position(pb) if pb.body is not None else None
        ref = 0.0 if xa is None or xb is None else float(np.linalg.norm(xa - xb))
        return (ref if self.length is None else float(self.length)), ref

    def record(self, system: PartHost, rows: RecordRows) -> SpringRecord:
        """The core's record (its places registered in ``rows``)."""
        a, b = system.place_pair(self.between, rows)
        for key, v in (("springs.stiffness", self.stiffness), ("springs.damping", self.damping)):
            if not (np.isfinite(v) and v >= 0):
                raise InputError(key, v, "a finite number >= 0")
        length, ref = self.rest_length(system)
        if length != 0.0 and ref <= 1e-12 * system.size:  # no direction where the places meet
            raise InputError(
                f"{self.key()}.length",
                length,
                "0 where its places meet at the reference (ground sits at "
                "the other place's reference): the linear spring-damper "
                "k (x_a - x_b) + c (v_a - v_b)",
            )
        return SpringRecord(
            a, b, float(self.stiffness), float(self.damping), length, self.law(rows, length)
        )

    def law(self, rows: RecordRows, length: float) -> int:
        """The index of its law's table among the core's time functions; -1: ``k e``."""
        return -1

    def stretch(self, system: PartHost, y: NDArray) -> float:
        """Its stretch ``e = ℓ - ℓ0`` [m] at the coordinates ``y`` (its tension:
        :meth:`tension` of it)."""
        xa, _ = system.place_state(self.between[0], y)
        xb, _ = system.place_state(self.between[1], y)
        return float(np.linalg.norm(xa - xb)) - self.rest_length(system)[0]

    def sensors(self, system: Any) -> Sequence[str]:
        """None among the outputs' columns (its tension: :meth:`stretch`, :meth:`tension`)."""
        return ()

    def reactions(
        self, system: Any, y: NDArray, lam: NDArray, t: float = 0.0
    ) -> Mapping[str, float]:
        """None (:meth:`sensors`)."""
        return {}


@dataclass(frozen=True)
class SpringLaw(Spring):
    """A spring with a nonlinear elastic law ``T(e)`` (module docstring): subclasses give
    :meth:`tension` and ``stretch_range``; ``stiffness`` is unused (0)."""

    stiffness: float = 0.0
    #: The stretches ``(e_min, e_max)`` [m] the law is tabulated on (0 inside).
    stretch_range: ClassVar[tuple[float, float]] = (-1.0, 1.0)
    #: Points of the table over the range.
    samples: ClassVar[int] = 201

    def tension(self, stretch: ArrayLike) -> NDArray[np.float64]:
        """The elastic tension ``T(e)`` [N] at the stretches ``e`` [m] (vectorized)."""
        raise NotImplementedError

    def law(self, rows: RecordRows, length: float) -> int:
        lo, hi = self.stretch_range
        if not (np.isfinite(lo) and np.isfinite(hi) and lo <= 0.0 < hi):
            raise InputError(f"{self.key()}.stretch_range", (lo, hi), "e_min <= 0 < e_max [m]")
        if not length > 0.0:
            raise InputError(f"{self.key()}.length", length, "a rest length > 0 with a law")
        e = np.linspace(lo, hi, max(int(self.samples), 4))
        t = np.asarray(self.tension(e), dtype=float)
        if t.shape != e.shape or not np.all(np.isfinite(t)):
            raise InputError(f"{self.key()}.tension", "T(e)", "finite tensions, one per stretch")
        return rows.tf(TimeFunction.table(np.c_[e, t], "cubic"))
