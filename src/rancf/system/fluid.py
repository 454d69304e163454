"""Lines in water and wind: the fluid, the bodies' hydrodynamic coefficients and distributed
loads, as the compiled core takes them (``src/cpp/fluid/fluid.hpp``; docs/derivations/fluid.md).

A :class:`Fluid` (density, free surface, current or current profile, linear waves) acts on every
flexible body that has :class:`Hydro` coefficients: buoyancy of the displaced volume below the
surface, Morison drag on the velocity relative to the fluid split about the exact tangent,
Froude–Krylov and added-mass forces (the added mass sits in the Jacobian's mass part, not lagged).
A :class:`DistributedLoad` is a force per reference length on flexible bodies, optionally times a
time function.  All of them are integrated over each element at the Gauss points of its elastic
forces (fluid.md section 3).  Their records for the core are made by the fluid's Part
(:mod:`rancf.system.parts.fluid`).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.system.irregular_waves import JonswapWaves, RecordedWaves, Waves, wave_number
from rancf.system.parts.distributed import DistributedLoad

__all__ = [
    "Fluid",
    "Waves",
    "JonswapWaves",
    "RecordedWaves",
    "Hydro",
    "DistributedLoad",
    "wave_number",
    "surface_elevation",
]


@dataclass(frozen=True)
class Fluid:
    """The fluid: ``density`` [kg/m³]; ``surface`` the still free surface's height on the last
    axis (None: every point submerged); a uniform ``current`` [m/s] or ``current_profile`` rows
    ``[height, u...]`` (linear in height, constant beyond the rows); optional ``waves``."""

    density: float
    surface: float | None = None
    current: tuple[float, ...] | None = None
    current_profile: tuple[tuple[float, ...], ...] | None = None
    waves: Waves | JonswapWaves | RecordedWaves | None = None


@dataclass(frozen=True)
class Hydro:
    """A flexible body's hydrodynamic coefficients: ``diameter`` [m] (volume equivalent; None:
    the section's, ``sqrt(4 A / pi)``), drag (normal on ``d``, axial on ``pi d``, MoorDyn's
    convention) and added-mass coefficients."""

    diameter: float | None = None
    drag_normal: float = 1.2
    drag_axial: float = 0.0
    added_mass_normal: float = 1.0
    added_mass_axial: float = 0.0

    def line_diameter(self, area: float) -> float:
        """The hydrodynamic diameter of a line of section area ``area`` [m²]: ``diameter``, else
        the volume-equivalent ``sqrt(4 A / pi)`` (``docs/derivations/fluid.md``)."""
        if self.diameter is not None:
            return float(self.diameter)
        return math.sqrt(4.0 * area / math.pi)


def surface_elevation(system: Any, point: Sequence[float], t: Any) -> NDArray[np.float64]:
    """The free surface's height (the still surface plus the waves' elevation, eq. (1) of
    :mod:`rancf.system.irregular_waves`) above the horizontal position of ``point`` at the
    times ``t``, from the fluid kernel (``surface_elevation`` of ``src/cpp/fluid/fluid.hpp``).

    Raises
    ------
    InputError
        The system is in no fluid with a free surface.
    """
    fl = getattr(system, "fluid", None)
    if fl is None or fl.surface is None:
        raise InputError("sensors.wave_elevation", "at_point", "a [fluid] with a surface")
    p = np.zeros(3)
    p[: len(point)] = point
    tt = np.atleast_1d(np.asarray(t, dtype=float))
    return np.asarray(system.core.surface_elevation(p, np.ascontiguousarray(tt)), dtype=float)
