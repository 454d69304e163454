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
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from rancf.errors import InputError
from rancf.kernels.records import DistributedRecord, FluidRecord, LineRecord, floats, vec3
from rancf.kernels.rod import RodKernel

if TYPE_CHECKING:
    from rancf.system.irregular_waves import WaveComponents

__all__ = [
    "Fluid",
    "Waves",
    "JonswapWaves",
    "RecordedWaves",
    "Hydro",
    "DistributedLoad",
    "wave_number",
    "fluid_records",
]


@dataclass(frozen=True)
class Waves:
    """Linear (Airy) waves: ``height`` H [m], ``period`` T [s], ``direction_deg`` of travel in
    the horizontal plane from the x axis, water ``depth`` h [m] below the still surface."""

    height: float
    period: float
    direction_deg: float = 0.0
    depth: float = 1000.0

    def wave_components(self, g: float) -> WaveComponents:
        """The wave as one component of amplitude ``H/2`` and phase 0."""
        from rancf.system.irregular_waves import WaveComponents

        def one(x: float) -> np.ndarray:
            return np.array([x], dtype=float)

        om = 2.0 * math.pi / self.period
        k = wave_number(self.period, self.depth, g)
        amp = one(0.5 * float(self.height))
        return WaveComponents(amp, one(om), one(k), one(0.0), self.direction_deg, self.depth)


@dataclass(frozen=True)
class JonswapWaves:
    """An irregular sea of ``components`` Airy components of a JONSWAP spectrum (significant
    height ``hs`` [m], peak period ``tp`` [s], peak enhancement ``gamma``), phases drawn from
    ``seed`` (:func:`rancf.system.irregular_waves.jonswap_components`)."""

    hs: float
    tp: float
    gamma: float = 3.3
    depth: float = 1000.0
    components: int = 200
    seed: int = 0
    direction_deg: float = 0.0

    def wave_components(self, g: float) -> WaveComponents:
        """The sea's components under gravity ``g``."""
        from rancf.system.irregular_waves import jonswap_components

        return jonswap_components(
            self.hs,
            self.tp,
            self.gamma,
            self.depth,
            self.components,
            self.seed,
            self.direction_deg,
            g,
        )


@dataclass(frozen=True)
class RecordedWaves:
    """A measured elevation record ``eta`` [m] at the times ``t`` [s] (equal steps) at the
    origin, as the components of its discrete Fourier series
    (:func:`rancf.system.irregular_waves.record_components`)."""

    t: tuple[float, ...]
    eta: tuple[float, ...]
    depth: float = 1000.0
    direction_deg: float = 0.0

    def wave_components(self, g: float) -> WaveComponents:
        """The record's components under gravity ``g``."""
        from rancf.system.irregular_waves import record_components

        return record_components(self.t, self.eta, self.depth, self.direction_deg, g)


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


@dataclass(frozen=True)
class DistributedLoad:
    """A force per reference length ``force`` [N/m] (world axes) on the flexible body ``body``
    (None: every flexible body), times the time function ``time`` (None: constant)."""

    force: tuple[float, ...]
    body: str | None = None
    time: Any = None


def wave_number(period: float, depth: float, g: float) -> float:
    """The root ``k`` of the dispersion relation ``ω² = g k tanh(k h)`` (Newton from the deep-water
    value; fluid.md section 2)."""
    om2 = (2.0 * math.pi / period) ** 2
    k = max(om2 / g, math.sqrt(om2 / (g * depth)))
    for _ in range(100):
        th = math.tanh(k * depth)
        f = g * k * th - om2
        df = g * th + g * k * depth * (1.0 - th * th)
        step = f / df
        k -= step
        if abs(step) <= 1e-15 * k:
            break
    return k


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
    k = model.kernel
    c = k.cable if isinstance(k, RodKernel) else k
    if not hasattr(c, "n0"):
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
    distributed: Sequence[DistributedLoad],
    tf: Callable[[Any], int],
) -> tuple[FluidRecord, list[LineRecord]] | None:
    """The core's records of the fluid and of every flexible body it or a distributed load acts
    on (None: neither); ``tf`` registers a time function and gives its index."""
    for name in hydro:
        if name not in flex_names:
            raise InputError("hydro", name, f"a flexible body (one of {list(flex_names)})")
    if hydro and fluid is None:
        raise InputError(
            "hydro", sorted(hydro), "coefficients of bodies in a fluid: give the [fluid] table too"
        )
    loads: dict[str, list[DistributedRecord]] = {n: [] for n in flex_names}
    for i, ld in enumerate(distributed):
        if len(ld.force) != dim:
            raise InputError(f"loads.distributed[{i}].force", list(ld.force), f"{dim} components")
        if ld.body is not None and ld.body not in loads:
            raise InputError(
                f"loads.distributed[{i}].body",
                ld.body,
                f"a flexible body (one of {list(flex_names)})",
            )
        rec = DistributedRecord(vec3(list(ld.force) + [0.0] * (3 - dim)), tf(ld.time))
        for n in [ld.body] if ld.body is not None else flex_names:
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
