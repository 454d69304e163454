"""The fluid of a system and what acts on its flexible bodies through it, a
:class:`~rancf.system.part.Part` (:mod:`rancf.system.fluid`; ``src/cpp/fluid/fluid.hpp``;
docs/derivations/fluid.md).

What it reads: the fluid (:class:`~rancf.system.fluid.Fluid`), the bodies' coefficients
(:class:`~rancf.system.fluid.Hydro`, by flexible body) and the distributed loads
(:class:`~rancf.system.parts.distributed.DistributedLoad`, Parts of their own whose records it
gathers per body).  Its record for the core: the fluid field (:class:`FluidRecord`) and one
:class:`LineRecord` per flexible body the fluid or a distributed load acts on (its quadrature,
coefficients and loads); none without a fluid, coefficients or distributed loads.  Its outputs
are its sensor kinds: ``fluid_force`` on a flexible body (``body``) or on all of them
(buoyancy, drag and the waves' Froude–Krylov force; the added mass left out) and
``wave_elevation`` with ``at_point`` (the free surface's height above that point's horizontal
position, :func:`rancf.system.fluid.surface_elevation`): no columns of its own.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, ClassVar

import numpy as np

from rancf.errors import InputError
from rancf.kernels.records import DistributedRecord, FluidRecord, LineRecord, floats, vec3
from rancf.system.fluid import Fluid, Hydro, surface_elevation
from rancf.system.part import NoOutputs
from rancf.system.parts.distributed import DistributedLoad
from rancf.system.readers import Block, Reader, SensorBuilder, SensorHost

if TYPE_CHECKING:
    from rancf.system.record_rows import RecordRows

__all__ = ["FluidPart", "fluid_records"]


def fluid_force_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``fluid_force`` sensor: buoyancy, drag and the waves' Froude-Krylov force on one
    flexible body or on all of them (docs/derivations/fluid.md section 3; the added mass needs
    accelerations: left out)."""
    s, d = host.system, host.system.dim
    flex = [n for n, _ in host.out.flex]
    body = getattr(sen, "body", None)
    if body is not None and body not in flex:
        raise InputError(f"sensors.{sen.name}.body", body, f"a flexible body: {', '.join(flex)}")
    pick = [flex.index(body)] if body is not None else list(range(len(flex)))

    def read(blk: Block) -> np.ndarray:
        out = np.zeros((len(blk[0]), d))
        for k, (tt, q, v) in enumerate(zip(blk[0], blk[1], blk[2], strict=True)):
            y, w = s.y_from_q(q), s.y_from_q(v)
            f = np.asarray(s.core.fluid_forces(y, w, np.zeros_like(y), float(tt)))
            out[k] = f.reshape(-1, 3)[pick, :d].sum(axis=0)
        return out

    return read


def wave_elevation_reader(host: SensorHost, sen: Any) -> Reader:
    """A ``wave_elevation`` sensor: the free surface's height above the horizontal position of
    ``sen.point`` (:func:`rancf.system.fluid.surface_elevation`)."""
    pt, system = sen.point, host.system
    return lambda blk: surface_elevation(system, pt, blk[0])


@dataclass(frozen=True, eq=False)
class FluidPart(NoOutputs):
    """The fluid ``fluid`` (None: none, only distributed loads), the coefficients ``hydro`` of
    the flexible bodies in it and the ``distributed`` loads (module docstring)."""

    fluid: Fluid | None = None
    hydro: Mapping[str, Hydro] = field(default_factory=dict)
    distributed: Sequence[DistributedLoad] = ()
    name = "fluid"
    #: Its sensor kinds (module docstring).
    sensor_kinds: ClassVar[Mapping[str, SensorBuilder]] = {
        "fluid_force": fluid_force_reader,
        "wave_elevation": wave_elevation_reader,
    }

    @property
    def empty(self) -> bool:
        """Neither a fluid, nor coefficients, nor distributed loads: no record."""
        return self.fluid is None and not self.hydro and not self.distributed

    def record(self, system: Any, rows: RecordRows) -> tuple[FluidRecord, list[LineRecord]] | None:
        """The core's records of the fluid and of every flexible body it or a distributed load
        acts on, the loads' time functions registered in ``rows`` (None: :attr:`empty`)."""
        if self.empty:
            return None
        loads = [(d.body, d.record(system, rows, i)) for i, d in enumerate(self.distributed)]
        names = system.names[: len(system.flex)]
        return fluid_records(
            names, system.flex, system.dim, system.gravity, self.fluid, self.hydro, loads
        )


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
    if c is None:  # the key that brought the body here: its [hydro], else a distributed load
        key = "hydro" if hydro is not None or not loads else "loads.distributed"
        raise InputError(key, "beam elements", "a body of cable or rod elements")
    h = hydro or Hydro()
    d = h.line_diameter(model.section.area)
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
