"""Lines in water and wind: the fluid, the bodies' hydrodynamic coefficients and distributed
loads, as the compiled core takes them (``src/cpp/fluid/fluid.hpp``; docs/derivations/fluid.md).

A :class:`Fluid` (density, free surface, current or current profile, linear waves) acts on every
flexible body that has :class:`Hydro` coefficients: buoyancy of the displaced volume below the
surface, Morison drag on the velocity relative to the fluid split about the exact tangent,
Froude–Krylov and added-mass forces (the added mass sits in the Jacobian's mass part, not lagged).
A :class:`DistributedLoad` is a force per reference length on flexible bodies, optionally times a
time function.  All of them are integrated over each element at the Gauss points of its elastic
forces (fluid.md section 3).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from rancf.errors import InputError
from rancf.kernels.records import DistributedRecord, FluidRecord, LineRecord, floats, vec3
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
    "fluid_records",
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


def _fluid_record(fl: Fluid, gravity: np.ndarray, dim: int) -> FluidRecord:
    g = float(np.linalg.norm(gravity))
    prof_z: tuple[float, ...] = ()
    prof_u: tuple[float, ...] = ()
    if fl.current_profile is not None:
        rows = sorted(fl.current_profile, key=lambda r: r[0])
        prof_z = floats([r[0] for r in rows])
        prof_u = floats([list(r[1:]) + [0.0] * (3 - dim) for r in rows])
    wave: dict[str, Any] = {}
    if fl.waves is not None:
        w = fl.waves
        if fl.surface is None:
            raise InputError("fluid.waves", "waves", "a fluid with a surface (fluid.surface)")
        if not g > 0:
            raise InputError("fluid.waves", "waves", "gravity (loads.gravity) for waves")
        c = w.wave_components(g)
        b = math.radians(c.direction_deg)
        wave = {
            "waves": True,
            "wave_amplitude": floats(c.amplitude),
            "wave_omega": floats(c.omega),
            "wave_k": floats(c.k),
            "wave_phase": floats(c.phase),
            "wave_depth": float(c.depth),
            "wave_dir": (math.cos(b), math.sin(b), 0.0)
            if dim == 3
            else (math.copysign(1.0, math.cos(b)), 0.0, 0.0),
        }
    cur = [0.0, 0.0, 0.0] if fl.current is None else list(fl.current) + [0.0] * (3 - dim)
    return FluidRecord(
        density=float(fl.density),
        gravity=vec3(gravity[:3]),
        has_surface=fl.surface is not None,
        surface=float(fl.surface or 0.0),
        current=vec3(cur),
        profile_z=prof_z,
        profile_u=prof_u,
        **wave,
    )


def _line(
    index: int, model: Any, hydro: Hydro | None, loads: list[DistributedRecord]
) -> LineRecord:
    c = model.family.centre_line(model.kernel)
    if c is None:
        raise InputError("hydro", "beam elements", "a body of cable or rod elements")
    h = hydro or Hydro()
    d = h.diameter if h.diameter is not None else math.sqrt(4.0 * model.section.area / math.pi)
    return LineRecord(
        body=index,
        hydro=hydro is not None,
        diameter=float(d),
        drag_normal=h.drag_normal,
        drag_axial=h.drag_axial,
        added_mass_normal=h.added_mass_normal,
        added_mass_axial=h.added_mass_axial,
        n_qp=int(c.gw.size),
        n0=floats(c.n0),
        n1=floats(c.n1),
        gw=floats(c.gw),
        j0=floats(c.j0),
        loads=tuple(loads),
    )


def fluid_records(
    flex_names: Sequence[str],
    flex: Sequence[Any],
    dim: int,
    gravity: np.ndarray,
    fluid: Fluid | None,
    hydro: Mapping[str, Hydro],
    distributed: Sequence[tuple[str | None, DistributedRecord]],
) -> tuple[FluidRecord, list[LineRecord]] | None:
    """The core's records of the fluid and of every flexible body it or a distributed load acts
    on (None: neither); ``distributed``: each distributed load's body (None: every flexible
    body) and record (:meth:`DistributedLoad.record`)."""
    for name in hydro:
        if name not in flex_names:
            raise InputError("hydro", name, f"a flexible body (one of {list(flex_names)})")
    if hydro and fluid is None:
        raise InputError(
            "hydro", sorted(hydro), "coefficients of bodies in a fluid: give the [fluid] table too"
        )
    loads: dict[str, list[DistributedRecord]] = {n: [] for n in flex_names}
    for body, rec in distributed:
        for n in [body] if body is not None else flex_names:
            loads[n].append(rec)
    lines = [
        _line(i, m, hydro.get(n), loads[n])
        for i, (n, m) in enumerate(zip(flex_names, flex, strict=True))
        if n in hydro or loads[n]
    ]
    if not lines and fluid is None:
        return None
    fl = fluid if fluid is not None else Fluid(density=0.0)
    return _fluid_record(fl, np.asarray(gravity, float), dim), lines


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
