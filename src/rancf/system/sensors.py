"""Sensors of a system, evaluated from stored rows and their derived values.

Kinds (column names ``NAME`` for one number, ``NAME_x``, ``NAME_y`` (, ``NAME_z``) for vectors).
The whole system's, here:

* ``position`` (``at``) and ``distance`` (``between``) of places (``position`` with
  ``at_point``: at the material point nearest to a fixed point in space,
  :mod:`rancf.system.at_point`);
* ``angular_momentum`` about ``about`` (default the origin; 2D: the ``z`` component) and
  ``energy`` (kinetic + strain + gravitational [J]) of the whole system;
* ``center_of_mass`` [m] and ``momentum`` (linear, [kg m/s]) of the body ``body`` or, without
  it, of the whole system.

The parts' kinds, each offered and built by its part's module (``sensor_kinds``, found through
:mod:`rancf.system.parts.catalog`): ``twist``, ``axial_force`` and ``tension`` of a flexible body
(:mod:`rancf.system.parts.flexible`); ``angle`` of a rigid body
(:mod:`rancf.system.parts.rigid`); ``reaction`` of a joint or support
(:mod:`rancf.system.parts.support`); ``contact_force`` and ``touchdown`` of an obstacle
(:mod:`rancf.system.parts.obstacle`); ``fluid_force`` and ``wave_elevation`` of the fluid
(:mod:`rancf.system.parts.fluid`); ``winch`` (:mod:`rancf.system.parts.winch`).

Mass, centre of mass and momentum of a flexible body: a rigid translation ``e_i`` moves every
node's position by ``e_i`` and no gradient, and the shape functions' position parts sum to one,
so with the mass matrix ``M`` and ``w_i = M T_i`` (``T_i``: the coordinates of that
translation) ``m = T_iᵀ M T_i``, ``∫ ρA r_i ds = w_i · y`` and ``p_i = w_i · v`` (beams: their
consistent translational mass, the same identity).  Rigid bodies and point masses contribute
``m x`` and ``m ẋ``; angular momentum adds ``R J ω`` (3D, ``ω = 2 G(p) ṗ`` in the body frame).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from rancf.bodies.flexible import Model
from rancf.bodies.motion import angular_momentum
from rancf.bodies.rigid import PointMass, RigidBody, body_angular_velocity
from rancf.bodies.shell_model import shell_reader
from rancf.errors import InputError
from rancf.system.at_point import at_point_reader
from rancf.system.places import Place
from rancf.system.readers import Block, NamedReader, Reader, SensorBuilder, sensor_places

__all__ = ["SensorReader"]


class OutputsView(Protocol):
    """What the sensors read of a run's derived outputs
    (:class:`rancf.system.outputs.SystemOutputs`, which holds the sensors)."""

    system: Any
    flex: list[tuple[str, Model]]
    samplers: dict[str, Any]
    part_columns: list[tuple[Any, list[str]]]

    def joint_columns(self, name: str) -> slice: ...

    def contact_columns(self, name: str) -> slice: ...

    def body_along(self, along: NDArray, name: str) -> NDArray[np.float64]: ...


class SensorReader:
    """The sensors' columns of blocks of rows (module docstring)."""

    def __init__(self, outputs: OutputsView, sensors: Sequence[Any]) -> None:
        self.out = outputs
        self.system = outputs.system
        self.names: list[str] = []
        self._readers: list[Reader] = []
        self._mass: dict[str, tuple[float, NDArray]] = {}
        self._kinds = {**self._part_kinds(), **self._system_kinds()}
        self._used: list[str] = []
        for sen in sensors:
            reader = self._reader(sen)
            columns = reader.columns if isinstance(reader, NamedReader) else []
            self.names += columns or sen.columns(self.system.dim)
            self._readers.append(reader)
            self._used.append(sen.kind)

    def values(
        self,
        t: NDArray,
        q: NDArray,
        v: NDArray | None,
        derived: dict[str, NDArray],
        energy: NDArray | None,
    ) -> NDArray[np.float64]:
        """Columns ``(k, n_columns)`` of rows ``q``, ``v`` with their ``derived`` values."""
        vv = np.zeros_like(q) if v is None else np.asarray(v, dtype=float).reshape(q.shape)
        if energy is None and "energy" in self._used:
            sy = self.system
            energy = np.array(
                [
                    sy.energies(sy.y_from_q(a), sy.y_from_q(b), tt)
                    for a, b, tt in zip(q, vv, t, strict=True)
                ]
            )
        block = (t, q, vv, derived, energy if energy is not None else np.zeros((len(t), 3)))
        cols = [np.asarray(r(block), dtype=float).reshape(len(t), -1) for r in self._readers]
        return np.concatenate(cols, axis=1) if cols else np.empty((len(t), 0))

    # ------------------------------------------------------------------ places
    def place(self, sen: Any, spec: Any) -> Place:
        """The place ``spec`` of sensor ``sen``, on a body (one line naming the sensor if
        not)."""
        try:
            p = self.system.resolve(spec)
        except InputError as exc:
            raise InputError(f"sensors.{sen.name}", spec, exc.allowed) from None
        if p.body is None:
            raise InputError(f"sensors.{sen.name}", "ground", "a place on a body")
        return p

    def _position(self, sen: Any, spec: Any) -> Reader:
        s = self.system
        p = self.place(sen, spec)
        body = p.body_name()
        b = s.bodies[body]
        if isinstance(b, Model):
            base = s.offsets[body] + p.node() * b.dpn
            return lambda blk: blk[1][:, base : base + s.dim]
        if isinstance(b, PointMass) or p.at is None:
            o = s.offsets[body]
            return lambda blk: blk[1][:, o : o + s.dim]
        s.place_state(p, s.y0)  # raises unless the place is observed

        def read(blk: Block) -> NDArray:
            return np.array(
                [
                    s.place_state(p, s.y_from_q(row), tt)[0][: s.dim]
                    for tt, row in zip(blk[0], blk[1], strict=True)
                ]
            )

        return read

    # ------------------------------------------------------------------ kinds
    def _reader(self, sen: Any) -> Reader:
        """The reader of sensor ``sen``: of its kind among the system's own kinds and those the
        part classes offer (:func:`rancf.system.parts.catalog.sensor_kinds`)."""
        build = self._kinds.get(sen.kind)
        if build is None:  # a kind of a part the system lacks: its builder names what is missing
            from rancf.system.parts.catalog import sensor_kinds

            build = sensor_kinds().get(sen.kind)
        if build is None:
            raise InputError(f"sensors.{sen.name}.kind", sen.kind, "a sensor kind")
        return build(self, sen)

    def _part_kinds(self) -> dict[str, SensorBuilder]:
        """The sensor kinds the system's parts offer (their classes' ``sensor_kinds``; the
        modules of parts it lacks stay unloaded)."""
        kinds: dict[str, SensorBuilder] = {}
        for part in self.system.parts:
            kinds.update(getattr(type(part), "sensor_kinds", {}))
        return kinds

    def _system_kinds(self) -> dict[str, SensorBuilder]:
        """The kinds of the whole system (or of any body): ``position`` and ``distance`` of
        places, ``energy``, ``angular_momentum``, ``center_of_mass`` and ``momentum``."""
        return {
            "position": self._position_sensor,
            "distance": self._distance,
            "energy": lambda host, sen: lambda blk: blk[4].sum(axis=1),
            "angular_momentum": lambda host, sen: self._angular_momentum(sen),
            "center_of_mass": lambda host, sen: self._mass_moment(sen, False),
            "momentum": lambda host, sen: self._mass_moment(sen, True),
        }

    def _position_sensor(self, host: Any, sen: Any) -> Reader:
        if getattr(sen, "point", None) is not None:
            return at_point_reader(self.out, sen)
        place = sensor_places(sen)[0]  # a shell's point [u, v] by its shape-function row
        return shell_reader(self.system, place) or self._position(sen, place)

    def _distance(self, host: Any, sen: Any) -> Reader:
        a, b = (self._position(sen, x) for x in sensor_places(sen)[:2])
        return lambda blk: np.linalg.norm(b(blk) - a(blk), axis=1)

    def _translation(self, name: str) -> tuple[float, NDArray]:
        """Mass and ``w_i = M T_i`` ``(dim, n_body)`` of a flexible body (module docstring)."""
        if name not in self._mass:
            b = self.system.bodies[name]
            assert isinstance(b, Model)
            d = self.system.dim
            w = np.empty((d, b.n))
            for i in range(d):
                ti = np.zeros((b.n_nodes, b.dpn))
                ti[:, i] = 1.0
                w[i] = b.mass_times(ti.ravel())
                if i == 0:
                    mass = float(w[0] @ ti.ravel())
            self._mass[name] = (mass, w)
        return self._mass[name]

    def _mass_moment(self, sen: Any, momentum: bool) -> Reader:
        s = self.system
        names = s.names if sen.body is None else [sen.body]
        if sen.body is not None and sen.body not in s.bodies:
            raise InputError(f"sensors.{sen.name}.body", sen.body, f"a body: {', '.join(s.names)}")

        def read(blk: Block) -> NDArray:
            total, acc = 0.0, np.zeros((len(blk[0]), s.dim))
            for name in names:
                b, sl = s.bodies[name], s.body_slice(name)
                x = blk[2][:, sl] if momentum else blk[1][:, sl]
                if isinstance(b, Model):
                    m, w = self._translation(name)
                    acc += s.y_from_q(blk[2] if momentum else blk[1])[:, sl] @ w.T
                else:
                    m = b.mass
                    acc += m * x[:, : s.dim]
                total += m
            return acc if momentum else acc / total

        return read

    def _angular_momentum(self, sen: Any) -> Reader:
        s = self.system
        about = getattr(sen, "about", None)
        c = np.zeros(3) if about is None else np.r_[np.asarray(about, float), 0.0][:3]

        def read(blk: Block) -> NDArray:
            k = len(blk[0])
            total = np.zeros((k, 3 if s.dim == 3 else 1))
            for name in s.names:
                b, sl = s.bodies[name], s.body_slice(name)
                q, v = blk[1][:, sl], blk[2][:, sl]
                if isinstance(b, Model):
                    total += angular_momentum(b, q, v, c[: s.dim])
                    continue
                r, p = q[:, : s.dim] - c[: s.dim], b.mass * v[:, : s.dim]
                if s.dim == 2:
                    total[:, 0] += r[:, 0] * p[:, 1] - r[:, 1] * p[:, 0]
                    if isinstance(b, RigidBody):
                        total[:, 0] += b.inertia_vector()[0] * v[:, 2]
                    continue
                total += np.cross(r, p)
                if isinstance(b, RigidBody):
                    from scipy.spatial.transform import Rotation

                    rot = Rotation.from_quat(q[:, 3:7][:, [1, 2, 3, 0]]).as_matrix()
                    for i in range(k):
                        w = body_angular_velocity(q[i, 3:7], v[i, 3:7])
                        total[i] += rot[i] @ (b.inertia_vector() * w)
            return total

        return read
